// SPDX-License-Identifier: BSD-3-Clause
// stickslip/ziggurat.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/random/ziggurat.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/random/ziggurat.hpp.

#include "stickslip/random/ziggurat.hpp"
