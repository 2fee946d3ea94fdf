// Internal: the pieces every report shares (parameter blocks, units, the
// work/warnings/version tail, number formatting), so all outputs agree.
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "stickslip/config.hpp"
#include "stickslip/diffusivity.hpp"

namespace stickslip::detail {

using nlohmann::ordered_json;

inline ordered_json number_or_inf(double x) {
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    return x;
}

inline ordered_json estimate_json(const Estimate& e, bool with_ci = true) {
    ordered_json j;
    j["value"] = e.value;
    j["stderr"] = e.std_error;
    if (with_ci) {
        j["ci"] = {e.lo, e.hi};
        j["level"] = e.level;
    }
    return j;
}

inline ordered_json params_json(const ModelParams& p, const EngineSettings& s, std::uint64_t seed) {
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

inline ordered_json nondimensional_json(const ModelParams& p, const EngineSettings& s) {
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

inline ordered_json resolved_json(const ResolvedEngine& r, const ModelParams& p, const EngineSettings& s) {
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
inline void add_work_and_notes(ordered_json& j, const EngineSettings& s, const RunTotals& totals,
                        const std::vector<std::string>& warnings) {
    ordered_json work;
    work[s.engine == Engine::Pdmp ? "events" : "steps"] = totals.work;
    work["seconds"] = totals.seconds;
    work["threads"] = totals.threads;
    j["work"] = work;
    j["warnings"] = warnings;
    j["version"] = STICKSLIP_VERSION_STRING;
}

inline std::string dump(const ordered_json& j, int indent) { return j.dump(indent) + "\n"; }

inline std::string g(double x, int prec = 6) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", prec, x);
    return buf;
}

inline void table_row(std::ostringstream& os, const std::string& name, const Estimate& e, double unit,
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

/// Column titles of the estimate tables, with the interval's level.
inline std::string table_head(double level) {
    // Built with append: GCC 12 warns (-Wrestrict, a false positive) on " " + std::string.
    std::string interval = "  ";
    interval.append(g(100 * level, 3)).append("% interval");
    char head[200];
    std::snprintf(head, sizeof head, "%-14s %13s  %-13s %-25s  %-7s %11s\n", "quantity", "value", "+- stderr",
                  interval.c_str() + 1, "unit", "nondim");
    return head;
}

inline std::string param_line(const ModelParams& p, const EngineSettings& s) {
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


} // namespace stickslip::detail
