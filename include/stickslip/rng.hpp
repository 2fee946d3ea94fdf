// SPDX-License-Identifier: BSD-3-Clause
// stickslip/rng.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/random/rng.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/random/rng.hpp.

#include "stickslip/random/rng.hpp"
