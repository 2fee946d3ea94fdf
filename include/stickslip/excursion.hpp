// SPDX-License-Identifier: BSD-3-Clause
// stickslip/excursion.hpp -- the outcome of one long excursion.
//
// A long excursion (theory.md, section 6) is a +HLE followed by a -HLE, each
// started exactly at its threshold state. Excursions are i.i.d. and are the
// units of the renewal-reward estimators in estimators.hpp. This header holds
// what both engines' samplers (resolvent.hpp, pdmp.hpp) return.
#pragma once

/// \file
/// ExcursionOutcome: what one long excursion (or trajectory) yields. The
/// comment at the top of this header explains the design.

#include <cstdint>

#include "stickslip/engine.hpp"

namespace stickslip {

/// Outcome of one long excursion (or one brute-force trajectory).
struct ExcursionOutcome {
    double displacement = 0.0; ///< U [m]
    double duration = 0.0;     ///< t [s]
    std::uint64_t work = 0;    ///< steps or events used
    bool capped = false;       ///< hit max_work_per_excursion; U, t meaningless
    double first_half = 0.0;   ///< long excursions: duration of the +HLE [s]
    /// Long excursions with a corrector (kernels/corrector.hpp): the
    /// martingale M = sum (g xi + c (xi^2 - var)) [m] (0 without one).
    double martingale = 0.0;
    /// Its compensator Q [m^2], sum g^2 var(xi) plus the second-order term's
    /// part (kernels/corrector.hpp), so that E[M^2 - Q] = 0; it can be
    /// negative on an excursion (0 without a corrector).
    double martingale_qv = 0.0;
};

} // namespace stickslip
