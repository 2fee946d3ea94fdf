// SPDX-License-Identifier: BSD-3-Clause
// stickslip/rng_batch.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/random/rng_batch.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/random/rng_batch.hpp.

#include "stickslip/random/rng_batch.hpp"
