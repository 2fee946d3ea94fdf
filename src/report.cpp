#include "stickslip/report.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "stickslip/config.hpp"

namespace stickslip {

namespace {

using nlohmann::ordered_json;

ordered_json number_or_inf(double x) {
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    return x;
}

ordered_json estimate_json(const Estimate& e, bool with_ci = true) {
    ordered_json j;
    j["value"] = e.value;
    j["stderr"] = e.std_error;
    if (with_ci) {
        j["ci"] = {e.lo, e.hi};
        j["level"] = e.level;
    }
    return j;
}

ordered_json params_json(const ModelParams& p, const EngineSettings& s, std::uint64_t seed) {
    ordered_json j;
    j["friction"] = p.friction;
    j["noise"] = p.noise;
    j["tau"] = p.tau;
    j["relaxation"] = number_or_inf(p.relaxation);
    j["bias"] = p.bias;
    if (s.engine == Engine::Pdmp) j["grid"] = s.grid;
    else j["dt"] = s.dt;
    j["seed"] = seed;
    return j;
}

ordered_json nondimensional_json(const ModelParams& p, const EngineSettings& s) {
    const ModelParams nd = to_nondimensional(p);
    const Scales sc = scales_of(p);
    ordered_json j;
    j["tau"] = nd.tau;
    j["relaxation"] = number_or_inf(nd.relaxation);
    j["bias"] = nd.bias;
    if (s.engine == Engine::Pdmp) j["grid"] = s.grid / sc.noise_level;
    else j["dt"] = s.dt / sc.time;
    j["time_unit"] = sc.time;
    j["length_unit"] = sc.length;
    j["velocity_unit"] = sc.velocity;
    j["diffusivity_unit"] = sc.diffusivity;
    return j;
}

ordered_json resolved_json(const ResolvedEngine& r, const ModelParams& p, const EngineSettings& s) {
    ordered_json j;
    if (!p.white()) {
        j["upper_threshold"] = r.upper_threshold;
        j["lower_threshold"] = r.lower_threshold;
    }
    if (s.engine == Engine::Pdmp) {
        j["lattice_bound"] = r.lattice_bound;
        j["lattice_points"] = r.lattice_points;
        j["truncated_mass"] = r.truncated_mass;
        j["jump_rate"] = r.jump_rate;
    } else if (p.white()) {
        j["white_level"] = r.white_level;
    }
    j["max_work_per_excursion"] = s.max_work_per_excursion;
    return j;
}

/// The common tail of every report: work done (the only part that changes
/// between runs with the same seed), warnings and the library version.
void add_work_and_notes(ordered_json& j, const EngineSettings& s, const RunTotals& totals,
                        const std::vector<std::string>& warnings) {
    ordered_json work;
    work[s.engine == Engine::Pdmp ? "events" : "steps"] = totals.work;
    work["seconds"] = totals.seconds;
    work["threads"] = totals.threads;
    j["work"] = work;
    j["warnings"] = warnings;
    j["version"] = STICKSLIP_VERSION_STRING;
}

std::string dump(const ordered_json& j, int indent) { return j.dump(indent) + "\n"; }

std::string g(double x, int prec = 6) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", prec, x);
    return buf;
}

void table_row(std::ostringstream& os, const std::string& name, const Estimate& e, double unit,
               const std::string& units, bool ci = true) {
    char buf[256];
    if (ci)
        std::snprintf(buf, sizeof buf, "%-14s %13.6g  +- %-10.3g [%11.6g, %11.6g]  %-7s %11.6g\n", name.c_str(),
                      e.value, e.std_error, e.lo, e.hi, units.c_str(), e.value / unit);
    else
        std::snprintf(buf, sizeof buf, "%-14s %13.6g  +- %-10.3g %27s  %-7s %11.6g\n", name.c_str(), e.value,
                      e.std_error, "", units.c_str(), e.value / unit);
    os << buf;
}

std::string param_line(const ModelParams& p, const EngineSettings& s) {
    std::ostringstream os;
    os << "friction " << g(p.friction) << " m/s^2, noise " << g(p.noise) << " m^2/s^3, tau " << g(p.tau)
       << " s, relaxation " << (std::isinf(p.relaxation) ? std::string("inf") : g(p.relaxation) + " s") << ", bias "
       << g(p.bias) << " m/s^2\n";
    const ModelParams nd = to_nondimensional(p);
    os << "nondimensional: tau' " << g(nd.tau) << ", relaxation' "
       << (std::isinf(nd.relaxation) ? std::string("inf") : g(nd.relaxation)) << ", bias' " << g(nd.bias);
    if (s.engine == Engine::Pdmp) os << ", grid' " << g(s.grid / scales_of(p).noise_level);
    else os << ", dt' " << g(s.dt / scales_of(p).time);
    os << "  (time unit " << g(scales_of(p).time) << " s, length unit " << g(scales_of(p).length) << " m)\n";
    return os.str();
}

} // namespace

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
    char head[200];
    std::snprintf(head, sizeof head, "%-14s %13s  %-13s %-25s  %-7s %11s\n", "quantity", "value", "+- stderr",
                  (" " + g(100 * q.level, 3) + "% interval").c_str(), "unit", "nondim");
    os << "\n" << head;
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
    char head[200];
    std::snprintf(head, sizeof head, "%-14s %13s  %-13s %-25s  %-7s %11s\n", "quantity", "value", "+- stderr",
                  (" " + g(100 * q.level, 3) + "% interval").c_str(), "unit", "nondim");
    os << "\n" << head;
    table_row(os, "D_t", r.estimates.diffusivity, sc.diffusivity, "m^2/s");
    table_row(os, "U(t)/t", r.estimates.mobility, sc.velocity, "m/s");
    os << "\n" << r.estimates.trajectories << " trajectories (seed " << q.control.seed << "), " << r.totals.work
       << (q.engine.engine == Engine::Pdmp ? " events" : " steps") << ", " << g(r.totals.seconds, 3) << " s on "
       << r.totals.threads << " thread" << (r.totals.threads > 1 ? "s" : "") << "\n";
    for (const auto& w : r.warnings) os << "note: " << w << "\n";
    return os.str();
}

} // namespace stickslip
