// SPDX-License-Identifier: BSD-3-Clause
// stickslip/estimators.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/stats/estimators.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/stats/estimators.hpp.

#include "stickslip/stats/estimators.hpp"
