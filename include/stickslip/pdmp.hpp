// SPDX-License-Identifier: BSD-3-Clause
// stickslip/pdmp.hpp -- kept so that code written against stickslip 0.3 still
// compiles: the header moved to stickslip/kernels/pdmp.hpp (the tree by layer,
// ARCHITECTURE.md). New code includes the new path.
#pragma once

/// \file
/// Forwarding header: see stickslip/kernels/pdmp.hpp.

#include "stickslip/kernels/pdmp.hpp"
