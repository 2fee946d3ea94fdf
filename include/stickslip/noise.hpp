// SPDX-License-Identifier: BSD-3-Clause
// stickslip/noise.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/kernels/noise.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/noise.hpp.

#include "stickslip/kernels/noise.hpp"
