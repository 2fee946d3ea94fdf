// SPDX-License-Identifier: BSD-3-Clause
// stickslip/event_lanes.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/kernels/event_lanes.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/event_lanes.hpp.

#include "stickslip/kernels/event_lanes.hpp"
