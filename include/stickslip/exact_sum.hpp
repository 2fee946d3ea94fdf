// SPDX-License-Identifier: BSD-3-Clause
// stickslip/exact_sum.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/stats/exact_sum.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/stats/exact_sum.hpp.

#include "stickslip/stats/exact_sum.hpp"
