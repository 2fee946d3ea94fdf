// SPDX-License-Identifier: BSD-3-Clause
// The Kolmogorov engine's shared path for diffusivity and density (solved.hpp).
#include "quantities/solved.hpp"

#include "core/format.hpp"
#include "stickslip/model.hpp"

namespace stickslip::detail {

KolmogorovSettings kolmogorov_settings(const RunSettings& r, double rel_precision,
                                       const std::vector<double>& frequencies) {
    KolmogorovSettings s;
    s.frequencies = frequencies;
    if (rel_precision > 0) s.rel_precision = rel_precision;
    s.threads = r.control.threads == 1 ? 1 : 2;
    s.stop = r.control.stop;
    return s;
}

void validate_solved(const RunSettings& r, double rel_precision, const std::vector<double>& frequencies) {
    validate(r.engine);
    validate_kolmogorov(r.params, kolmogorov_settings(r, rel_precision, frequencies));
}

KolmogorovResult solve(const RunSettings& r, double rel_precision, std::vector<std::string>& notes,
                       const std::vector<double>& frequencies) {
    validate(r.engine);
    const Model model = make_model(r.params); // the run's law, made once
    KolmogorovResult result = solve_kolmogorov(model, kolmogorov_settings(r, rel_precision, frequencies));
    if (r.params.has_drift_law()) {
        const DriftLawReport& law = model.law_report;
        notes.push_back(drift_law_note(law));
        notes.insert(notes.end(), law.notes.begin(), law.notes.end());
    }
    if (!result.note.empty()) notes.push_back(result.note);
    return result;
}

LongExcursionEstimates solved_long_excursion_estimates(const KolmogorovResult& s) {
    LongExcursionEstimates e;
    e.diffusivity = s.diffusivity;
    e.mobility = s.mobility;
    e.mean_duration = s.mean_duration;
    return e;
}

} // namespace stickslip::detail
