// SPDX-License-Identifier: BSD-3-Clause
// A corrector table with no meaning, for the kernel tests of the control
// variate's martingale: any g makes one, so the lanes and the one-excursion
// kernels must agree bit for bit whatever its values. They vary in x and v on
// a few nodes (clamped lookups beyond them), with a stuck line of its own.
#pragma once

#include "stickslip/kernels/corrector.hpp"

namespace stickslip::test {

/// A corrector with no meaning (any g makes a martingale): values varying in x
/// and v on a few nodes, and a stuck line of its own.
struct ArbitraryCorrector {
    double slide[5 * 4];
    double stuck[3] = {0.7, -0.2, 1.1};
    ArbitraryCorrector() {
        for (int i = 0; i < 20; ++i) slide[i] = 0.3 * i - 0.05 * i * i;
    }
    CorrectorTable table() const {
        CorrectorTable g;
        g.slide = slide;
        g.nx = 5;
        g.nv = 4;
        g.x_first = -2.0;
        g.inv_dx = 1.0;
        g.v_first = -0.6;
        g.inv_dv = 2.5;
        g.stuck = stuck;
        g.ns = 3;
        g.s_first = -1.0;
        g.inv_ds = 1.0;
        return g;
    }
};

} // namespace stickslip::test
