// SPDX-License-Identifier: BSD-3-Clause
// stickslip/exact_sum.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/stats/exact_sum.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/stats/exact_sum.hpp.

#include "stickslip/stats/exact_sum.hpp"
