// SPDX-License-Identifier: BSD-3-Clause
// Internal: the quantities that a grid solver can compute (diffusivity,
// density) choose their method once, at their top (method.hpp): with
// --engine kolmogorov they return the Kolmogorov solver's result and never
// reach the Monte Carlo paths. What they share is here, so that the mapping of
// the run's settings to the solver's, and its notes, are defined once.
#pragma once

#include <string>
#include <vector>

#include "stickslip/kolmogorov.hpp"
#include "stickslip/run.hpp"

namespace stickslip::detail {

/// The Kolmogorov solver's settings for a run: rel_precision is the relative
/// precision of D asked for (--rel-precision; 0, Monte Carlo's "off", takes the
/// solver's default KolmogorovSettings::rel_precision), threads 1 when the run
/// asks for one, else 2 (the solver uses at most 2).
KolmogorovSettings kolmogorov_settings(const RunSettings& r, double rel_precision);

/// Every check of a run with the Kolmogorov engine: the engine settings (a
/// typo in an unused one is still reported) and validate_kolmogorov
/// (InvalidParameter: white noise and tau' < kolmogorov_min_tau_prime name
/// "tau" and say what to use instead).
void validate_solved(const RunSettings& r, double rel_precision);

/// Solves the run's model (validated first). `notes` gets the solver's
/// remarks: the budget reached before the precision, the drift law used.
KolmogorovResult solve(const RunSettings& r, double rel_precision, std::vector<std::string>& notes);

} // namespace stickslip::detail
