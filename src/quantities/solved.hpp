// SPDX-License-Identifier: BSD-3-Clause
// Internal: the quantities that a grid solver can compute (diffusivity,
// density) choose their method once, at their top (method.hpp): with
// --engine kolmogorov they return the Kolmogorov solver's result and never
// reach the Monte Carlo paths. What they share is here, so that the mapping of
// the run's settings to the solver's, and its notes, are defined once.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "stickslip/errors.hpp"
#include "stickslip/setting.hpp"

#include "stickslip/kolmogorov.hpp"
#include "stickslip/run.hpp"

namespace stickslip::detail {

/// The Kolmogorov solver's settings for a run: rel_precision is the relative
/// precision of D asked for (--rel-precision; 0, Monte Carlo's "off", takes the
/// solver's default KolmogorovSettings::rel_precision), threads 1 when the run
/// asks for one, else 2 (the solver uses at most 2).
/// `frequencies` [rad/s]: those of the spectrum (KolmogorovSettings::frequencies).
KolmogorovSettings kolmogorov_settings(const RunSettings& r, double rel_precision,
                                       const std::vector<double>& frequencies = {});

/// Every check of a run with the Kolmogorov engine: the engine settings (a
/// typo in an unused one is still reported) and validate_kolmogorov
/// (InvalidParameter: white noise names "tau" and says what to use instead;
/// a model beyond the grids' reach names the setting to change).
void validate_solved(const RunSettings& r, double rel_precision, const std::vector<double>& frequencies = {});

/// Solves the run's model (validated first). `notes` gets the solver's
/// remarks: the budget reached before the precision, the drift law used.
KolmogorovResult solve(const RunSettings& r, double rel_precision, std::vector<std::string>& notes,
                       const std::vector<double>& frequencies = {});

/// The solver's D, M0 and E[t1] as the long-excursion estimates a sampled run
/// fills (kind Solved; no excursions: `completed` 0), so that a result's
/// estimates are where they are whatever the method.
LongExcursionEstimates solved_long_excursion_estimates(const KolmogorovResult& s);

/// The settings that only sampling uses (the Kolmogorov engine samples
/// nothing): given a value other than their default, they are refused, so
/// that `--excursions 1e6 --engine kolmogorov` does not pass for a run of a
/// million excursions.
inline constexpr const char* sampling_settings[] = {
    "scheme", "dt", "grid", "lattice-bound", "stop-rule", "white-level", "max-steps", "seed", "level",
    "excursions", "allow-capped", "estimator", "max-excursions", "control-variate", "control-variate-pilot",
    "check-knots", "bins",
    "sample-dt", "range", "first-index"};

/// Throws InvalidParameter naming the first of sampling_settings that `r`
/// gives a value other than a default Request's.
template <class Request>
void refuse_sampling_settings(const Request& r) {
    Request given = r, defaults;
    std::vector<std::pair<std::string, std::string>> values;
    visit_settings(given, [&](auto&& field, const SettingInfo& info) { values.emplace_back(info.name, format_setting(field)); });
    std::size_t k = 0;
    visit_settings(defaults, [&](auto&& field, const SettingInfo& info) {
        const auto& [name, value] = values[k++];
        if (value == format_setting(field)) return;
        for (const char* s : sampling_settings)
            if (name == s)
                throw InvalidParameter(info.name, std::string(info.name) + " is a setting of the Monte Carlo engines: "
                                                  "the kolmogorov engine samples nothing (no excursions, seed, step, "
                                                  "lattice or intervals), so --" + name + " " + value +
                                                  " would change nothing; drop it, or use --engine inclusion or pdmp");
    });
}

} // namespace stickslip::detail
