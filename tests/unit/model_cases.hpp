// SPDX-License-Identifier: BSD-3-Clause
// Models the unit tests share, made in one place.
#pragma once

#include <cmath>

#include "stickslip/params.hpp"

namespace stickslip::test {

/// Pure dry friction at friction = noise = 1 (so tau' = tau; tau = 0: white
/// noise): no drag, no bias.
inline ModelParams pure_dry_friction(double tau) {
    ModelParams p;
    p.friction = 1.0;
    p.noise = 1.0;
    p.tau = tau;
    p.relaxation = INFINITY;
    p.bias = 0.0;
    return p;
}

} // namespace stickslip::test
