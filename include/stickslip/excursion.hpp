// SPDX-License-Identifier: BSD-3-Clause
// stickslip/excursion.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/kernels/excursion.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/excursion.hpp.

#include "stickslip/kernels/excursion.hpp"
