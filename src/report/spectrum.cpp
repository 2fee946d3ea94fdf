// SPDX-License-Identifier: BSD-3-Clause
// Reports of the velocity spectrum (report.hpp): JSON, table, CSV. The
// Kolmogorov engine's solve is reported as a solved diffusivity is
// (solved.hpp), the closed form as `analytic`'s references are, and the
// series at its one path whatever computed it.
#include <cmath>

#include "core/format.hpp"
#include "report/common.hpp"
#include "report/fields_csv.hpp"
#include "report/fields_json.hpp"
#include "quantities/solved.hpp"
#include "report/solved.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/report.hpp"

namespace stickslip {

using namespace detail;

namespace {

/// The settings the Kolmogorov engine ran with (its precision target and threads).
KolmogorovSettings solver_settings(const SpectrumResult& r) {
    return kolmogorov_settings(r.request, r.request.rel_precision, r.frequencies);
}

/// A Monte Carlo spectrum: reported as `correlation`'s sampled paths are.
std::string sampled_json(const SpectrumResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j = report_head("velocity_spectrum", q.engine, nullptr, &r.monte_carlo().engine.stop_rule);
    auto params = params_json(q);
    params["excursions"] = q.excursions;
    if (!has_time_step(q.engine)) params["sample_dt"] = q.sample_dt > 0 ? q.sample_dt : q.engine.dt;
    params["level"] = q.level;
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q);
    append_members(j, long_excursion_json(*r.estimates));
    append_members(j, fields_json(r.monte_carlo().totals)); // capped
    j["engine_details"] = engine_details_json(r.monte_carlo().engine, q);
    append_members(j, fields_json(r)); // frequency, spectrum
    const ordered_json work = work_json(q.engine, r.monte_carlo().totals);
    add_report_tail(j, r.request, &work, r.warnings, r.monte_carlo().totals.interrupted);
    return dump(j, indent);
}

/// The series' rows: w, S(w), its error, w in time units, S/D.
void spectrum_rows(std::ostringstream& os, const SpectrumResult& r, const Scales& sc, double d) {
    using number_text::pad;
    os << "\n" << pad("w [rad/s]", 14) << " " << pad("S(w) [m^2/s]", 16) << " " << pad("+- error", 12) << " "
       << pad("w' (nondim)", 14) << " " << pad("S/D", 12) << "\n";
    for (std::size_t k = 0; k < r.frequencies.size(); ++k) {
        const Estimate& e = r.spectrum[k];
        os << pad(format_number(r.frequencies[k]), 14) << " " << pad(format_number(e.value, 8), 16) << " "
           << pad(format_number(e.error, 3), 12) << " " << pad(format_number(r.frequencies[k] * sc.time), 14) << " "
           << pad(format_number(e.value / d, 6), 12) << "\n";
    }
}

std::string sampled_table(const SpectrumResult& r) {
    const auto& q = r.request;
    std::ostringstream os = report_stream();
    os << engine_line("spectrum", q.engine, ", regenerative estimator over long excursions (renewal-reward cycles)");
    os << param_line(q.params, q.engine) << "\n";
    os << "mobility M0        " << estimate_cell(r.estimates->mobility) << " m/s\n";
    os << "diffusivity D      " << estimate_cell(r.estimates->diffusivity) << " m^2/s (= S(0))\n";
    spectrum_rows(os, r, scales_of(q.params), r.estimates->diffusivity.value);
    os << "(error: the standard error)\n\n";
    os << work_line(r.estimates->excursions, "excursions", q.control.seed, q.engine, r.monte_carlo().totals)
       << notes(r.warnings);
    return os.str();
}

} // namespace

std::string to_json(const SpectrumResult& r, int indent) {
    if (r.estimates) return sampled_json(r, indent);
    const auto& q = r.request;
    ordered_json j = solved_head("velocity_spectrum", q);
    std::optional<ordered_json> work;
    if (r.solution) {
        const KolmogorovResult& s = *r.solution;
        j["nondimensional"] = nondimensional_json(q, NondimensionalValues::of(scales_of(q.params), s.diffusivity.value,
                                                                              s.mobility.value, s.mean_duration.value));
        add_solved_estimates(j, s, solver_settings(r));
        work = solved_work_json(s, solver_settings(r));
    } else {
        j["nondimensional"] = nondimensional_json(q, NondimensionalValues::of(scales_of(q.params), r.reference->diffusivity,
                                                                              r.reference->mobility, std::nan("")));
        append_members(j, fields_json(*r.reference, FieldJsonStyle{&q.params}));
        j["engine_details"] = {{"method", r.grid().solver}};
    }
    append_members(j, fields_json(r)); // frequency, spectrum
    add_report_tail(j, r.request, work ? &*work : nullptr, r.warnings, r.solution && r.solution->interrupted);
    return dump(j, indent);
}

std::string to_table(const SpectrumResult& r) {
    if (r.estimates) return sampled_table(r);
    using number_text::pad;
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    std::ostringstream os = report_stream();
    if (r.solution) {
        os << engine_line("spectrum", q.engine, ", no sampling: complex resolvent solves on grids, extrapolated");
        os << param_line(q.params, q.engine);
        os << "\n" << solved_table_head();
        solved_table_rows(os, *r.solution, sc);
    } else {
        os << "stickslip spectrum: " << r.grid().solver << "\n" << param_line(q.params, q.engine) << "\n";
        os << pad("mobility M0", -16) << " " << pad(format_number(r.reference->mobility, 10), 15) << " m/s\n";
        os << pad("diffusivity D", -16) << " " << pad(format_number(r.reference->diffusivity, 10), 15) << " m^2/s\n";
    }
    spectrum_rows(os, r, sc, r.solution ? r.solution->diffusivity.value : r.reference->diffusivity);
    if (r.solution) os << "\n" << solved_work_line(*r.solution, solver_settings(r));
    os << notes(r.warnings);
    return os.str();
}

std::string to_csv(const SpectrumResult& r) {
    std::ostringstream os = report_stream();
    // Solved: a value and its discretisation error (0 when exact); sampled: with its interval.
    const FieldCsvStyle style{.solved = !r.estimates};
    os << series_csv_header<SpectrumResult>(style) << "\n" << series_csv_rows(r, style);
    return csv_provenance(r.request) + os.str();
}

} // namespace stickslip
