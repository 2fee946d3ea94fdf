// SPDX-License-Identifier: BSD-3-Clause
// stickslip/moment_sums.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/stats/moment_sums.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/stats/moment_sums.hpp.

#include "stickslip/stats/moment_sums.hpp"
