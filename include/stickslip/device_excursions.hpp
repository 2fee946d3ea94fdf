// SPDX-License-Identifier: BSD-3-Clause
// stickslip/device_excursions.hpp -- kept so that code written before the tree by layer
// (ARCHITECTURE.md) still compiles: the header moved to stickslip/kernels/device_excursions.hpp.
// New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/device_excursions.hpp.

#include "stickslip/kernels/device_excursions.hpp"
