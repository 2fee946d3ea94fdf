// SPDX-License-Identifier: BSD-3-Clause
// stickslip/phase_law.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/kernels/phase_law.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/phase_law.hpp.

#include "stickslip/kernels/phase_law.hpp"
