// SPDX-License-Identifier: BSD-3-Clause
// stickslip/rng_batch.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/random/rng_batch.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/random/rng_batch.hpp.

#include "stickslip/random/rng_batch.hpp"
