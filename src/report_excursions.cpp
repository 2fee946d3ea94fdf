#include "stickslip/report.hpp"

#include "report_common.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "stickslip/config.hpp"

namespace stickslip {

using namespace detail;

std::string to_json(const DiffusivityResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j;
    j["engine"] = to_string(q.engine.engine);
    j["estimator"] = to_string(q.estimator);
    j["stop_rule"] = r.resolved.stop_rule;
    auto params = params_json(q.params, q.engine, q.control.seed);
    params["excursions"] = q.excursions;
    params["level"] = q.level;
    j["params"] = params;
    auto nd = nondimensional_json(q.params, q.engine);
    const Scales sc = scales_of(q.params);
    nd["diffusivity"] = r.estimates.diffusivity.value / sc.diffusivity;
    nd["mobility"] = r.estimates.mobility.value / sc.velocity;
    nd["mean_duration"] = r.estimates.mean_duration.value / sc.time;
    j["nondimensional"] = nd;
    j["diffusivity"] = estimate_json(r.estimates.diffusivity);
    j["mobility"] = estimate_json(r.estimates.mobility);
    j["mean_duration"] = estimate_json(r.estimates.mean_duration, false);
    j["completed"] = r.estimates.excursions;
    j["capped"] = r.totals.capped;
    if (q.rel_precision > 0) {
        ordered_json pr;
        pr["target"] = r.precision.target;
        pr["relative_half_width"] = r.precision.relative_half_width;
        pr["reached"] = r.precision.reached;
        pr["batches"] = r.precision.batches;
        pr["max_excursions"] = q.max_excursions;
        j["precision"] = pr;
    }
    j["engine_details"] = resolved_json(r.resolved, q.params, q.engine);
    add_work_and_notes(j, q.engine, r.totals, r.warnings);
    return dump(j, indent);
}

std::string to_json(const BruteForceResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j;
    j["engine"] = to_string(q.engine.engine);
    j["estimator"] = "bruteforce";
    j["stop_rule"] = r.resolved.stop_rule;
    auto params = params_json(q.params, q.engine, q.control.seed);
    params["time"] = q.horizon;
    params["trajectories"] = q.trajectories;
    params["x0"] = r.start_noise;
    params["v0"] = q.v0;
    params["level"] = q.level;
    j["params"] = params;
    auto nd = nondimensional_json(q.params, q.engine);
    const Scales sc = scales_of(q.params);
    nd["time"] = q.horizon / sc.time;
    nd["diffusivity"] = r.estimates.diffusivity.value / sc.diffusivity;
    nd["mobility"] = r.estimates.mobility.value / sc.velocity;
    j["nondimensional"] = nd;
    j["diffusivity"] = estimate_json(r.estimates.diffusivity);
    j["mobility"] = estimate_json(r.estimates.mobility);
    j["engine_details"] = resolved_json(r.resolved, q.params, q.engine);
    add_work_and_notes(j, q.engine, r.totals, r.warnings);
    return dump(j, indent);
}

std::string to_table(const DiffusivityResult& r) {
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    std::ostringstream os;
    os << "stickslip diffusivity: " << to_string(q.engine.engine) << " engine, "
       << (q.engine.engine == Engine::Pdmp ? "grid " + g(q.engine.grid) + " s^-1/2"
                                           : "dt " + g(q.engine.dt) + " s")
       << ", stop rule " << r.resolved.stop_rule << ", estimator " << to_string(q.estimator) << "\n";
    os << param_line(q.params, q.engine);
    os << "\n" << table_head(q.level);
    table_row(os, "diffusivity D", r.estimates.diffusivity, sc.diffusivity, "m^2/s");
    table_row(os, "mobility M0", r.estimates.mobility, sc.velocity, "m/s");
    table_row(os, "mean E[t1]", r.estimates.mean_duration, sc.time, "s", false);
    os << "\n" << r.estimates.excursions << " excursions (seed " << q.control.seed << "), " << r.totals.work
       << (q.engine.engine == Engine::Pdmp ? " events" : " steps") << ", " << g(r.totals.seconds, 3) << " s on "
       << r.totals.threads << " thread" << (r.totals.threads > 1 ? "s" : "") << "; relative half-width of D: "
       << g(100 * (r.estimates.diffusivity.hi - r.estimates.diffusivity.value) / r.estimates.diffusivity.value, 3)
       << "%\n";
    for (const auto& w : r.warnings) os << "note: " << w << "\n";
    return os.str();
}

std::string to_table(const BruteForceResult& r) {
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    std::ostringstream os;
    os << "stickslip bruteforce: " << to_string(q.engine.engine) << " engine, "
       << (q.engine.engine == Engine::Pdmp ? "grid " + g(q.engine.grid) + " s^-1/2"
                                           : "dt " + g(q.engine.dt) + " s")
       << ", horizon t = " << g(q.horizon) << " s, start x0 = " << g(r.start_noise) << " s^-1/2, v0 = " << g(q.v0)
       << " m/s\n";
    os << param_line(q.params, q.engine);
    os << "\n" << table_head(q.level);
    table_row(os, "D_t", r.estimates.diffusivity, sc.diffusivity, "m^2/s");
    table_row(os, "U(t)/t", r.estimates.mobility, sc.velocity, "m/s");
    os << "\n" << r.estimates.trajectories << " trajectories (seed " << q.control.seed << "), " << r.totals.work
       << (q.engine.engine == Engine::Pdmp ? " events" : " steps") << ", " << g(r.totals.seconds, 3) << " s on "
       << r.totals.threads << " thread" << (r.totals.threads > 1 ? "s" : "") << "\n";
    for (const auto& w : r.warnings) os << "note: " << w << "\n";
    return os.str();
}

} // namespace stickslip
