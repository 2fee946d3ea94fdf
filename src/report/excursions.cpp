// SPDX-License-Identifier: BSD-3-Clause
// Reports of the long-excursion diffusivity run and the brute-force run
// (report.hpp): JSON, aligned table, CSV.
#include "report/common.hpp"
#include "report/fields_csv.hpp"
#include "report/fields_json.hpp"
#include "stickslip/report.hpp"

#include "core/format.hpp"
#include "quantities/solved.hpp"
#include "report/solved.hpp"

namespace stickslip {

using namespace detail;

// ---- diffusivity ----------------------------------------------------------------

namespace {

// The reports of a diffusivity solved by the Kolmogorov engine.

std::string solved_json(const DiffusivityResult& r, int indent) {
    const auto& q = r.request;
    const KolmogorovResult& s = *r.solution;
    const KolmogorovSettings settings = kolmogorov_settings(q, q.rel_precision);
    ordered_json j = solved_head("diffusivity", q);
    j["nondimensional"] = nondimensional_json(
        q, NondimensionalValues::of(scales_of(q.params), s.diffusivity.value, s.mobility.value, s.mean_duration.value));
    add_solved_estimates(j, s, settings);
    const ordered_json work = solved_work_json(s, settings);
    add_report_tail(j, r.request, &work, r.warnings, s.interrupted);
    return dump(j, indent);
}

std::string solved_table(const DiffusivityResult& r) {
    const auto& q = r.request;
    const KolmogorovResult& s = *r.solution;
    std::ostringstream os = report_stream();
    os << engine_line("diffusivity", q.engine, ", no sampling: the Kolmogorov equations of (X, V) on grids, extrapolated");
    os << param_line(q.params, q.engine);
    os << "\n" << solved_table_head();
    solved_table_rows(os, s, scales_of(q.params));
    os << "\n" << solved_work_line(s, kolmogorov_settings(q, q.rel_precision)) << notes(r.warnings);
    return os.str();
}

std::string solved_csv(const DiffusivityResult& r) {
    const auto& p = r.request.params;
    const KolmogorovResult& s = *r.solution;
    std::ostringstream os = report_stream();
    os << "engine,friction,noise,tau,relaxation,bias," << fields_csv_header<KolmogorovResult>() << "\n";
    os << to_string(r.request.engine.engine) << "," << csv_number(p.friction) << "," << csv_number(p.noise) << ","
       << csv_number(p.tau) << "," << csv_number(p.relaxation) << "," << csv_number(p.bias) << ","
       << fields_csv_row(s) << "\n";
    return os.str();
}

} // namespace

std::string to_json(const DiffusivityResult& r, int indent) {
    if (r.solution) return solved_json(r, indent);
    const auto& q = r.request;
    const std::string estimator = to_string(q.estimator);
    ordered_json j = report_head("diffusivity", q.engine, estimator.c_str(), &r.monte_carlo().engine.stop_rule);
    auto params = params_json(q);
    params["excursions"] = q.excursions;
    params["level"] = q.level;
    j["params"] = params;
    j["nondimensional"] =
        nondimensional_json(q, NondimensionalValues::of(scales_of(q.params), r.estimates.diffusivity.value,
                                                        r.estimates.mobility.value, r.estimates.mean_duration.value));
    append_members(j, long_excursion_json(r.estimates));
    append_members(j, fields_json(r.monte_carlo().totals)); // capped
    if (q.rel_precision > 0) j["precision"] = fields_json(r.precision);
    if (r.control_variate) j["control_variate"] = fields_json(*r.control_variate);
    if (r.discretisation) j["discretisation"] = fields_json(*r.discretisation);
    if (r.knots_check) j["knots_check"] = fields_json(*r.knots_check);
    j["engine_details"] = engine_details_json(r.monte_carlo().engine, q);
    RunWork run = run_work(q.engine, r.monte_carlo().totals);
    if (r.control_variate) run.corrector_seconds = r.control_variate->corrector_seconds; // prepared once per run
    const ordered_json work = work_json(run, work_unit(q.engine));
    add_report_tail(j, r.request, &work, r.warnings, r.monte_carlo().totals.interrupted);
    return dump(j, indent);
}

namespace {
/// "a +- b unit (z = ...)" for a --check-dt difference.
std::string difference_text(const Estimate& difference, const char* unit) {
    return format_number(difference.value, 3) + " +- " + format_number(difference.error, 2) + " " + unit +
           " (z = " + format_number(difference.value / difference.error, 2) + ")";
}
} // namespace

std::string to_table(const DiffusivityResult& r) {
    if (r.solution) return solved_table(r);
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    const Estimate& d = r.estimates.diffusivity;
    std::ostringstream os = report_stream();
    os << engine_line("diffusivity", q.engine,
                      ", stop rule " + r.monte_carlo().engine.stop_rule + ", estimator " + to_string(q.estimator));
    os << param_line(q.params, q.engine);
    os << "\n" << table_head(q.level);
    table_row(os, "diffusivity D", d, sc.diffusivity, "m^2/s");
    table_row(os, "mobility M0", r.estimates.mobility, sc.velocity, "m/s");
    table_row(os, "mean E[t1]", r.estimates.mean_duration, sc.time, "s", false);
    if (r.control_variate) {
        const ControlVariateReport& c = *r.control_variate;
        os << "\ncontrol variate (corrector: " << c.source << ", " << c.grid << "; coefficients "
           << (c.pilot_excursions > 0 ? "from a pilot of " + std::to_string(c.pilot_excursions) + " excursions"
                                      : std::string("fitted on the run"))
           << "): variance of D reduced " << format_number(c.variance_reduction, 3) << "x, of M0 "
           << format_number(c.variance_reduction_mobility, 3) << "x; without it:\n";
        table_row(os, "plain D", c.plain_diffusivity, sc.diffusivity, "m^2/s");
        table_row(os, "plain M0", c.plain_mobility, sc.velocity, "m/s");
    }
    if (r.discretisation) {
        const DiscretisationCheck& c = *r.discretisation;
        os << "\ncheck at 2 dt = " << format_number(c.check_dt) << " s (" << c.excursions
           << " excursions): D(2 dt) - D(dt) = "
           << difference_text(c.diffusivity_difference, "m^2/s")
           << "\n                                   M0(2 dt) - M0(dt) = "
           << difference_text(c.mobility_difference, "m/s") << "\n";
    }
    if (r.knots_check) {
        const DiscretisationCheck& c = *r.knots_check;
        os << "\ncheck with " << c.check_knots << " knots (" << c.excursions << " excursions): D - D("
           << c.knots << " knots) = " << difference_text(c.diffusivity_difference, "m^2/s")
           << "\n                                  M0 - M0(" << c.knots << " knots) = "
           << difference_text(c.mobility_difference, "m/s") << "\n";
    }
    // The work (steps, seconds) is the run's and its pilot's: the line says so.
    std::string what = "excursions";
    if (r.control_variate && r.control_variate->pilot_excursions > 0)
        what += " + " + std::to_string(r.control_variate->pilot_excursions) + " of the control variate's pilot";
    os << "\n"
       << work_line(r.estimates.excursions, what.c_str(), q.control.seed, q.engine, r.monte_carlo().totals,
                    "; relative half-width of D: " + format_number(100 * (d.hi - d.value) / d.value, 3) + "%")
       << notes(r.warnings);
    return os.str();
}

std::string to_csv(const DiffusivityResult& r) {
    if (r.solution) return csv_provenance(r.request) + solved_csv(r);
    const auto& q = r.request;
    const auto& p = q.params;
    // The checks' blocks after the estimates, each column named by its JSON
    // path (discretisation.diffusivity -> discretisation_diffusivity).
    const FieldCsvStyle dt_check{{"knots", "check_knots"}, false, "discretisation_"};
    const FieldCsvStyle knots_check{{"dt", "check_dt", "steps"}, false, "knots_check_"};
    std::ostringstream os = report_stream();
    os << "engine,friction,noise,tau,relaxation,bias,seed," << fields_csv_header<LongExcursionEstimates>();
    if (r.discretisation) os << "," << fields_csv_header<DiscretisationCheck>(dt_check);
    if (r.knots_check) os << "," << fields_csv_header<DiscretisationCheck>(knots_check);
    os << "\n";
    os << to_string(q.engine.engine) << "," << csv_number(p.friction) << "," << csv_number(p.noise) << ","
       << csv_number(p.tau) << "," << csv_number(p.relaxation) << "," << csv_number(p.bias) << ","
       << q.control.seed << "," << fields_csv_row(r.estimates);
    if (r.discretisation) os << "," << fields_csv_row(*r.discretisation, dt_check);
    if (r.knots_check) os << "," << fields_csv_row(*r.knots_check, knots_check);
    os << "\n";
    return csv_provenance(r.request) + os.str();
}

// ---- brute force --------------------------------------------------------------

std::string to_json(const BruteForceResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j = report_head("finite_time_diffusivity", q.engine, "bruteforce", &r.monte_carlo().engine.stop_rule);
    auto params = params_json(q);
    params["time"] = q.horizon;
    params["trajectories"] = q.trajectories;
    params["x0"] = r.start_noise;
    params["v0"] = q.v0;
    params["level"] = q.level;
    j["params"] = params;
    const Scales sc = scales_of(q.params);
    NondimensionalValues values = NondimensionalValues::of(sc, r.estimates.diffusivity.value,
                                                           r.estimates.mobility.value, std::nan(""));
    values.time = q.horizon / sc.time;
    j["nondimensional"] = nondimensional_json(q, values);
    append_members(j, fields_json(r.estimates));
    j["engine_details"] = engine_details_json(r.monte_carlo().engine, q);
    const ordered_json work = work_json(q.engine, r.monte_carlo().totals);
    add_report_tail(j, r.request, &work, r.warnings, r.monte_carlo().totals.interrupted);
    return dump(j, indent);
}

std::string to_table(const BruteForceResult& r) {
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    std::ostringstream os = report_stream();
    os << engine_line("bruteforce", q.engine,
                      ", horizon t = " + format_number(q.horizon) + " s, start x0 = " + format_number(r.start_noise) +
                          " s^-1/2, v0 = " + format_number(q.v0) + " m/s");
    os << param_line(q.params, q.engine);
    os << "\n" << table_head(q.level);
    table_row(os, "D_t", r.estimates.diffusivity, sc.diffusivity, "m^2/s");
    table_row(os, "U(t)/t", r.estimates.mobility, sc.velocity, "m/s");
    os << "\n"
       << work_line(r.estimates.trajectories, "trajectories", q.control.seed, q.engine, r.monte_carlo().totals)
       << notes(r.warnings);
    return os.str();
}

std::string to_csv(const BruteForceResult& r) {
    const auto& q = r.request;
    const auto& p = q.params;
    std::ostringstream os = report_stream();
    os << "engine,friction,noise,tau,relaxation,bias,time,trajectories,seed,"
       << fields_csv_header<BruteForceEstimates>() << "\n";
    os << to_string(q.engine.engine) << "," << csv_number(p.friction) << "," << csv_number(p.noise) << ","
       << csv_number(p.tau) << "," << csv_number(p.relaxation) << "," << csv_number(p.bias) << ","
       << csv_number(q.horizon) << "," << r.estimates.trajectories << "," << q.control.seed << ","
       << fields_csv_row(r.estimates) << "\n";
    return csv_provenance(r.request) + os.str();
}

} // namespace stickslip
