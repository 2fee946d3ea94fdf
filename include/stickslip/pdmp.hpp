// SPDX-License-Identifier: BSD-3-Clause
// stickslip/pdmp.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/kernels/pdmp.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/pdmp.hpp.

#include "stickslip/kernels/pdmp.hpp"
