// SPDX-License-Identifier: BSD-3-Clause
// stickslip/noise.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/kernels/noise.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/noise.hpp.

#include "stickslip/kernels/noise.hpp"
