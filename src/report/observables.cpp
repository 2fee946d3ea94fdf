// SPDX-License-Identifier: BSD-3-Clause
// Reports of the velocity statistics (report.hpp): the stationary density, the
// transient moments, the autocorrelation and sample paths, as JSON (the
// contract the Python module's to_dict() shares), aligned tables and CSV.
#include <cmath>

#include "core/format.hpp"
#include "quantities/solved.hpp"
#include "report/common.hpp"
#include "report/fields_csv.hpp"
#include "report/fields_json.hpp"
#include "report/solved.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/report.hpp"

namespace stickslip {

using namespace detail;

namespace {

/// A stationary density's histogram: P(V = 0) is reported beside it, as the
/// solver reports it.
ordered_json histogram_json(const VelocityHistogram& h) {
    return fields_json(h, FieldJsonStyle{nullptr, {"stuck_probability"}});
}

} // namespace

// ---- stationary density ----------------------------------------------------------

namespace {

// The reports of a density solved by the Kolmogorov engine: the cells and
// values of the grid with the finest velocity cells, no standard errors.

/// The same histogram as a sampled one, on the grid with the finest velocity
/// cells: a grid value has no error estimate (NaN: null, an empty cell), and
/// the grid spans the velocities that hold mass, so the mass below and above
/// it is 0 to within the grid's tail mass.
VelocityHistogram solved_histogram(const KolmogorovResult& s) {
    const KolmogorovGridSolution& fine = s.levels.back();
    VelocityHistogram h;
    h.edges = fine.velocity_faces;
    for (double value : fine.velocity_density) h.density.push_back(solved_estimate(value, std::nan("")));
    h.stuck = s.stuck_probability;
    h.below = h.above = solved_estimate(0.0, grid_span(s).tail_mass);
    return h;
}

std::string solved_json(const DensityResult& r, int indent) {
    const auto& q = r.request;
    const KolmogorovResult& s = *r.solution;
    const KolmogorovSettings settings = kolmogorov_settings(q, 0.0);
    ordered_json j = solved_head("stationary_density", q);
    j["nondimensional"] = nondimensional_json(q);
    j["histogram"] = histogram_json(solved_histogram(s));
    append_members(j, fields_json(r)); // the solver's, where a sampled result has them
    add_solved_estimates(j, s, settings);
    const ordered_json work = solved_work_json(s, settings);
    add_report_tail(j, r.request, &work, r.warnings, s.interrupted);
    return dump(j, indent);
}

std::string solved_table(const DensityResult& r) {
    const auto& q = r.request;
    const KolmogorovResult& s = *r.solution;
    const KolmogorovGridSolution& fine = s.levels.back();
    std::ostringstream os = report_stream();
    os << engine_line("density", q.engine, ", no sampling: the Kolmogorov equations of (X, V) on the grid with the finest velocity cells");
    os << param_line(q.params, q.engine) << "\n";
    using number_text::pad;
    os << pad("v_lo [m/s]", 13) << " " << pad("v_hi [m/s]", 13) << "  " << pad("density [s/m] (grid)", 20) << "\n";
    for (std::size_t k = 0; k < fine.velocity_density.size(); ++k)
        os << pad(format_number(fine.velocity_faces[k]), 13) << " " << pad(format_number(fine.velocity_faces[k + 1]), 13)
           << "  " << pad(format_number(fine.velocity_density[k]), 20) << "\n";
    os << "\n" << solved_table_head();
    solved_table_rows(os, s, scales_of(q.params));
    os << "\n" << solved_work_line(s, kolmogorov_settings(q, 0.0)) << notes(r.warnings);
    return os.str();
}


} // namespace

std::string to_json(const DensityResult& r, int indent) {
    if (r.solution) return solved_json(r, indent);
    const auto& q = r.request;
    ordered_json j = report_head("stationary_density", q.engine, nullptr, &r.monte_carlo().engine.stop_rule);
    auto params = params_json(q);
    params["excursions"] = q.excursions;
    params["bins"] = q.bins.count;
    params["range"] = {q.bins.lo, q.bins.hi};
    if (!has_time_step(q.engine)) params["sample_dt"] = q.sample_dt > 0 ? q.sample_dt : q.engine.dt;
    params["level"] = q.level;
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q);
    j["histogram"] = histogram_json(r.histogram);
    j["stuck_probability"] = estimate_json(r.histogram.stuck);
    append_members(j, fields_json(r));
    append_members(j, long_excursion_json(r.estimates));
    append_members(j, fields_json(r.monte_carlo().totals)); // capped
    j["engine_details"] = engine_details_json(r.monte_carlo().engine, q);
    const ordered_json work = work_json(q.engine, r.monte_carlo().totals);
    add_report_tail(j, r.request, &work, r.warnings, r.monte_carlo().totals.interrupted);
    return dump(j, indent);
}

std::string to_table(const DensityResult& r) {
    if (r.solution) return solved_table(r);
    const auto& q = r.request;
    std::ostringstream os = report_stream();
    os << engine_line("density", q.engine, ", stationary velocity density by long excursions (renewal-reward)");
    os << param_line(q.params, q.engine) << "\n";
    using number_text::pad;
    os << pad("v_lo [m/s]", 13) << " " << pad("v_hi [m/s]", 13) << "  " << pad("density [s/m] +- stderr", -25) << "\n";
    for (std::size_t k = 0; k < r.histogram.density.size(); ++k)
        os << pad(format_number(r.histogram.edges[k]), 13) << " " << pad(format_number(r.histogram.edges[k + 1]), 13)
           << "  " << estimate_cell(r.histogram.density[k]) << "\n";
    os << "\nP(V = 0) (stuck)   " << estimate_cell(r.histogram.stuck) << "\n";
    os << "P(outside range)   " << format_number(r.histogram.below.value + r.histogram.above.value) << "\n";
    os << "mean E[V]          " << estimate_cell(r.mean) << " m/s\n";
    os << "variance Var(V)    " << estimate_cell(r.variance) << " m^2/s^2\n";
    os << "diffusivity D      " << estimate_cell(r.estimates.diffusivity) << " m^2/s (same excursions)\n\n";
    os << work_line(r.estimates.excursions, "excursions", q.control.seed, q.engine, r.monte_carlo().totals) << notes(r.warnings);
    return os.str();
}

std::string to_csv(const DensityResult& r) {
    // The histogram's rows, and P(V = 0) among them (the JSON's beside it).
    const FieldCsvStyle style{.solved = r.solution.has_value()};
    std::ostringstream os = report_stream();
    os << histogram_csv_header(style) << "\n"
       << histogram_csv_rows(r.solution ? solved_histogram(*r.solution) : r.histogram, style);
    return csv_provenance(r.request) + os.str();
}

// ---- transient ------------------------------------------------------------------------

std::string to_json(const MomentsResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j = report_head("transient", q.engine, nullptr, nullptr);
    auto params = params_json(q);
    params["v0"] = q.v0;
    if (std::isnan(q.x0)) params["x0"] = q.params.white() ? ordered_json(nullptr) : ordered_json("stationary");
    else params["x0"] = q.x0;
    params["trajectories"] = q.trajectories;
    params["level"] = q.level;
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q);
    append_members(j, fields_json(r));
    if (!r.density.empty()) {
        ordered_json d = ordered_json::array();
        for (const VelocityHistogram& h : r.density) d.push_back(fields_json(h)); // with its P(V(t) = 0) and time
        j["density"] = d;
    }
    j["engine_details"] = engine_details_json(r.monte_carlo().engine, q);
    const ordered_json work = work_json(q.engine, r.monte_carlo().totals);
    add_report_tail(j, r.request, &work, r.warnings, r.monte_carlo().totals.interrupted);
    return dump(j, indent);
}

std::string to_table(const MomentsResult& r) {
    const auto& q = r.request;
    std::ostringstream os = report_stream();
    os << engine_line("moments", q.engine,
                      ", from v0 = " + format_number(q.v0) + " m/s, X(0) " +
                          (q.params.white() ? std::string("n/a (white noise)")
                                            : std::isnan(q.x0) ? std::string("~ N(0, 1/tau)") : "= " + format_number(q.x0)));
    os << param_line(q.params, q.engine) << "\n";
    using number_text::pad;
    os << pad("t [s]", 12) << " " << pad("E[V(t)] [m/s]", -25) << " " << pad("E[V(t)^2] [m^2/s^2]", -25) << " "
       << pad("P(V(t) = 0)", -25) << "\n";
    for (std::size_t k = 0; k < r.time.size(); ++k)
        os << pad(format_number(r.time[k]), 12) << " " << estimate_cell(r.first_moment[k]) << " "
           << estimate_cell(r.second_moment[k]) << " " << estimate_cell(r.stuck[k]) << "\n";
    if (!r.density.empty())
        os << "(the transient density, " << r.density.size() << " times x " << q.bins.count
           << " bins, is in --format json; --format csv gives it alone)\n";
    os << "\n" << work_line(r.monte_carlo().totals.moments.count(), "trajectories", q.control.seed, q.engine, r.monte_carlo().totals)
       << notes(r.warnings);
    return os.str();
}

std::string to_csv(const MomentsResult& r) {
    std::ostringstream os = report_stream();
    if (r.density.empty()) {
        os << series_csv_header<MomentsResult>() << "\n" << series_csv_rows(r);
        return csv_provenance(r.request) + os.str();
    }
    // Each time's histogram, its time first on every row.
    os << "time," << histogram_csv_header() << "\n";
    for (const VelocityHistogram& h : r.density) os << histogram_csv_rows(h, {}, csv_number(h.time) + ",");
    return csv_provenance(r.request) + os.str(); // what made it, as every CSV says (it was missing here)
}

// ---- correlation ----------------------------------------------------------------------

std::string to_json(const CorrelationResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j = report_head("autocorrelation", q.engine, nullptr, &r.monte_carlo().engine.stop_rule);
    auto params = params_json(q);
    params["excursions"] = q.excursions;
    params["max_lag"] = q.max_lag;
    params["lags"] = q.lags;
    if (!has_time_step(q.engine)) params["sample_dt"] = q.sample_dt > 0 ? q.sample_dt : q.engine.dt;
    params["level"] = q.level;
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q);
    append_members(j, fields_json(r));
    append_members(j, long_excursion_json(r.estimates));
    append_members(j, fields_json(r.monte_carlo().totals)); // capped
    j["engine_details"] = engine_details_json(r.monte_carlo().engine, q);
    const ordered_json work = work_json(q.engine, r.monte_carlo().totals);
    add_report_tail(j, r.request, &work, r.warnings, r.monte_carlo().totals.interrupted);
    return dump(j, indent);
}

std::string to_table(const CorrelationResult& r) {
    const auto& q = r.request;
    std::ostringstream os = report_stream();
    os << engine_line("correlation", q.engine, ", stationary autocorrelation by long excursions (renewal-reward)");
    os << param_line(q.params, q.engine) << "\n";
    using number_text::pad;
    os << pad("lag r [s]", 12) << " " << pad("<V(0)V(r)> [m^2/s^2]", -25) << " " << pad("h(r) [m^2/s^2]", -25) << " "
       << pad("h(r)/h(0)", -25) << "\n";
    for (std::size_t k = 0; k < r.lag.size(); ++k)
        os << pad(format_number(r.lag[k]), 12) << " " << estimate_cell(r.autocorrelation[k]) << " "
           << estimate_cell(r.covariance[k]) << " " << estimate_cell(r.normalised[k]) << "\n";
    os << "\nmean E[V]          " << estimate_cell(r.mean) << " m/s\n";
    os << "diffusivity D      " << estimate_cell(r.estimates.diffusivity) << " m^2/s (same excursions)\n\n";
    os << work_line(r.estimates.excursions, "excursions", q.control.seed, q.engine, r.monte_carlo().totals) << notes(r.warnings);
    return os.str();
}

std::string to_csv(const CorrelationResult& r) {
    std::ostringstream os = report_stream();
    os << series_csv_header<CorrelationResult>() << "\n" << series_csv_rows(r);
    return csv_provenance(r.request) + os.str();
}

// ---- trajectories -------------------------------------------------------------------------

std::string to_json(const TrajectoryResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j = report_head(q.paths == 0 ? "excursion" : "paths", q.engine, nullptr, nullptr);
    auto params = params_json(q);
    if (q.paths == 0) params["index"] = q.index;
    else {
        params["paths"] = q.paths;
        params["time"] = q.horizon;
        params["v0"] = q.v0;
        params["every"] = q.every;
    }
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q);
    if (q.paths == 0) append_members(j, fields_json(r.excursion));
    ordered_json ps = ordered_json::array();
    for (const auto& p : r.paths) {
        ordered_json o;
        o["t"] = p.t;
        o["x"] = p.x;
        o["mode"] = p.mode;
        o["v"] = p.v;
        o["u"] = p.u;
        ps.push_back(o);
    }
    j["paths"] = ps;
    j["engine_details"] = engine_details_json(r.resolved, q);
    add_report_tail(j, r.request, nullptr, r.warnings);
    return dump(j, indent);
}

std::string to_csv(const TrajectoryResult& r) {
    std::ostringstream os = report_stream();
    os << "path,t,x,mode,v,u\n";
    for (std::size_t k = 0; k < r.paths.size(); ++k) {
        const auto& p = r.paths[k];
        for (std::size_t i = 0; i < p.t.size(); ++i)
            os << k << "," << csv_number(p.t[i]) << "," << csv_number(p.x[i]) << "," << p.mode[i] << ","
               << csv_number(p.v[i]) << "," << csv_number(p.u[i]) << "\n";
    }
    return csv_provenance(r.request) + os.str();
}

std::string to_table(const TrajectoryResult& r) {
    const auto& q = r.request;
    std::ostringstream os = report_stream();
    if (q.paths == 0)
        os << engine_line("trajectory", q.engine,
                          ", long excursion " + std::to_string(q.index) + ": U = " +
                              format_number(r.excursion.displacement) + " m, t1 = " +
                              format_number(r.excursion.duration) + " s");
    else
        os << engine_line("trajectory", q.engine,
                          ", " + std::to_string(q.paths) + " paths on [0, " + format_number(q.horizon) + "] s");
    os << param_line(q.params, q.engine) << "\n";
    using number_text::pad;
    os << pad("path", 5) << " " << pad("t [s]", 13) << " " << pad("X [s^-1/2]", 13) << " " << pad("mode", 5) << " "
       << pad("V [m/s]", 13) << " " << pad("U [m]", 13) << "\n";
    for (std::size_t k = 0; k < r.paths.size(); ++k) {
        const auto& p = r.paths[k];
        for (std::size_t i = 0; i < p.t.size(); ++i)
            os << pad(std::to_string(k), 5) << " " << pad(format_number(p.t[i]), 13) << " "
               << pad(format_number(p.x[i]), 13) << " " << pad(std::to_string(p.mode[i]), 5) << " "
               << pad(format_number(p.v[i]), 13) << " " << pad(format_number(p.u[i]), 13) << "\n";
    }
    os << notes(r.warnings);
    return os.str();
}

} // namespace stickslip
