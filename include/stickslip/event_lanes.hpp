// SPDX-License-Identifier: BSD-3-Clause
// stickslip/event_lanes.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/kernels/event_lanes.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/event_lanes.hpp.

#include "stickslip/kernels/event_lanes.hpp"
