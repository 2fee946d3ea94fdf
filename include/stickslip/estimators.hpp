// SPDX-License-Identifier: BSD-3-Clause
// stickslip/estimators.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/stats/estimators.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/stats/estimators.hpp.

#include "stickslip/stats/estimators.hpp"
