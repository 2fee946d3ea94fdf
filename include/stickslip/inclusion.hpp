// SPDX-License-Identifier: BSD-3-Clause
// stickslip/inclusion.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/kernels/resolvent.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/resolvent.hpp.

#include "stickslip/kernels/resolvent.hpp"

namespace stickslip {
/// The resolvent scheme's constants under their name of stickslip 0.3.
using InclusionConstants = ResolventConstants;
} // namespace stickslip
