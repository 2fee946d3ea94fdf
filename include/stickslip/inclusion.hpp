// SPDX-License-Identifier: BSD-3-Clause
// stickslip/inclusion.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/kernels/resolvent.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/resolvent.hpp.

#include "stickslip/kernels/resolvent.hpp"

namespace stickslip {
/// The resolvent scheme's constants under their name before the scheme was named resolvent.
using InclusionConstants = ResolventConstants;
} // namespace stickslip
