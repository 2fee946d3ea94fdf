// SPDX-License-Identifier: BSD-3-Clause
// stickslip/portable_math.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/random/portable_math.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/random/portable_math.hpp.

#include "stickslip/random/portable_math.hpp"
