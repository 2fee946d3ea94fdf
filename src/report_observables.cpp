// Reports of the observables and sweeps (report.hpp): JSON (the contract the
// Python module's to_dict() shares), aligned tables, CSV.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "report_common.hpp"
#include "stickslip/report.hpp"

namespace stickslip {

using namespace detail;

namespace {

std::string c(double x) {
    if (std::isnan(x)) return ""; // undefined (e.g. a slope from one point): an empty cell, never "nan"
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.12g", x);
    return buf;
}

/// JSON number, or null for NaN (JSON has no NaN).
ordered_json num(double x) {
    if (std::isnan(x)) return nullptr;
    return number_or_inf(x);
}

ordered_json point(const char* key, double where, const Estimate& e) {
    ordered_json j;
    j[key] = where;
    j["value"] = num(e.value);
    j["stderr"] = num(e.std_error);
    j["ci"] = {num(e.lo), num(e.hi)};
    return j;
}

ordered_json histogram_json(const VelocityHistogram& h) {
    ordered_json bins = ordered_json::array();
    for (std::size_t k = 0; k < h.density.size(); ++k) {
        ordered_json b;
        b["lo"] = h.edges[k];
        b["hi"] = h.edges[k + 1];
        b["density"] = h.density[k].value;
        b["stderr"] = h.density[k].std_error;
        bins.push_back(b);
    }
    ordered_json j;
    j["bins"] = bins;
    j["stuck"] = estimate_json(h.stuck);
    j["below"] = estimate_json(h.below, false);
    j["above"] = estimate_json(h.above, false);
    return j;
}

ordered_json long_excursion_json(const LongExcursionEstimates& e) {
    ordered_json j;
    j["diffusivity"] = estimate_json(e.diffusivity);
    j["mobility"] = estimate_json(e.mobility);
    j["mean_duration"] = estimate_json(e.mean_duration, false);
    j["completed"] = e.excursions;
    return j;
}

/// Copies every member of `from` into `into` (keeps the order).
void put_all(ordered_json& into, const ordered_json& from) {
    for (auto it = from.begin(); it != from.end(); ++it) into[it.key()] = it.value();
}

std::string engine_line(const char* what, const EngineSettings& s, const std::string& extra) {
    std::ostringstream os;
    os << "stickslip " << what << ": " << to_string(s.engine) << " engine, "
       << (s.engine == Engine::Pdmp ? "grid " + g(s.grid) + " s^-1/2" : "dt " + g(s.dt) + " s") << extra << "\n";
    return os.str();
}

std::string work_line(std::uint64_t samples, const char* what, std::uint64_t seed, const EngineSettings& s,
                      const RunTotals& t) {
    std::ostringstream os;
    os << samples << " " << what << " (seed " << seed << "), " << t.work
       << (s.engine == Engine::Pdmp ? " events" : " steps") << ", " << g(t.seconds, 3) << " s on " << t.threads
       << " thread" << (t.threads > 1 ? "s" : "") << "\n";
    return os.str();
}

std::string notes(const std::vector<std::string>& warnings) {
    std::string s;
    for (const auto& w : warnings) s += "note: " + w + "\n";
    return s;
}

std::string estimate_cell(const Estimate& e) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "%12.6g +- %-10.3g", e.value, e.std_error);
    return buf;
}

const char* csv_estimate_header(const char* name) {
    static thread_local std::string h;
    h = std::string(name) + "," + name + "_stderr," + name + "_lo," + name + "_hi";
    return h.c_str();
}

std::string csv_estimate(const Estimate& e) { return c(e.value) + "," + c(e.std_error) + "," + c(e.lo) + "," + c(e.hi); }

} // namespace

// ---- diffusivity and bruteforce as CSV ------------------------------------------

std::string to_csv(const DiffusivityResult& r) {
    const auto& q = r.request;
    std::ostringstream os;
    os << "engine,friction,noise,tau,relaxation,bias,excursions,seed," << csv_estimate_header("diffusivity") << ","
       << csv_estimate_header("mobility") << ",mean_duration,mean_duration_stderr\n";
    os << to_string(q.engine.engine) << "," << c(q.params.friction) << "," << c(q.params.noise) << ","
       << c(q.params.tau) << "," << c(q.params.relaxation) << "," << c(q.params.bias) << ","
       << r.estimates.excursions << "," << q.control.seed << "," << csv_estimate(r.estimates.diffusivity) << ","
       << csv_estimate(r.estimates.mobility) << "," << c(r.estimates.mean_duration.value) << ","
       << c(r.estimates.mean_duration.std_error) << "\n";
    return os.str();
}

std::string to_csv(const BruteForceResult& r) {
    const auto& q = r.request;
    std::ostringstream os;
    os << "engine,friction,noise,tau,relaxation,bias,time,trajectories,seed," << csv_estimate_header("diffusivity")
       << "," << csv_estimate_header("mobility") << "\n";
    os << to_string(q.engine.engine) << "," << c(q.params.friction) << "," << c(q.params.noise) << ","
       << c(q.params.tau) << "," << c(q.params.relaxation) << "," << c(q.params.bias) << "," << c(q.horizon) << ","
       << r.estimates.trajectories << "," << q.control.seed << "," << csv_estimate(r.estimates.diffusivity) << ","
       << csv_estimate(r.estimates.mobility) << "\n";
    return os.str();
}

// ---- stationary density ----------------------------------------------------------

std::string to_json(const StationaryDensityResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j;
    j["quantity"] = "stationary_density";
    j["engine"] = to_string(q.engine.engine);
    j["stop_rule"] = r.resolved.stop_rule;
    auto params = params_json(q.params, q.engine, q.control.seed);
    params["excursions"] = q.excursions;
    params["bins"] = q.bins.count;
    params["range"] = {q.bins.lo, q.bins.hi};
    if (q.engine.engine == Engine::Pdmp) params["sample_dt"] = q.sample_dt > 0 ? q.sample_dt : q.engine.dt;
    params["level"] = q.level;
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q.params, q.engine);
    j["histogram"] = histogram_json(r.histogram);
    j["mean"] = estimate_json(r.mean);
    j["variance"] = estimate_json(r.variance);
    put_all(j, long_excursion_json(r.estimates));
    j["capped"] = r.totals.capped;
    j["engine_details"] = resolved_json(r.resolved, q.params, q.engine);
    add_work_and_notes(j, q.engine, r.totals, r.warnings);
    return dump(j, indent);
}

std::string to_table(const StationaryDensityResult& r) {
    const auto& q = r.request;
    std::ostringstream os;
    os << engine_line("density", q.engine, ", stationary velocity density by long excursions (renewal-reward)");
    os << param_line(q.params, q.engine) << "\n";
    char buf[200];
    std::snprintf(buf, sizeof buf, "%13s %13s  %-25s\n", "v_lo [m/s]", "v_hi [m/s]", "density [s/m] +- stderr");
    os << buf;
    for (std::size_t k = 0; k < r.histogram.density.size(); ++k) {
        std::snprintf(buf, sizeof buf, "%13.6g %13.6g  %s\n", r.histogram.edges[k], r.histogram.edges[k + 1],
                      estimate_cell(r.histogram.density[k]).c_str());
        os << buf;
    }
    os << "\nP(V = 0) (stuck)   " << estimate_cell(r.histogram.stuck) << "\n";
    os << "P(outside range)   " << g(r.histogram.below.value + r.histogram.above.value) << "\n";
    os << "mean E[V]          " << estimate_cell(r.mean) << " m/s\n";
    os << "variance Var(V)    " << estimate_cell(r.variance) << " m^2/s^2\n";
    os << "diffusivity D      " << estimate_cell(r.estimates.diffusivity) << " m^2/s (same excursions)\n\n";
    os << work_line(r.estimates.excursions, "excursions", q.control.seed, q.engine, r.totals) << notes(r.warnings);
    return os.str();
}

std::string to_csv(const StationaryDensityResult& r) {
    std::ostringstream os;
    os << "kind,v_lo,v_hi,value,stderr,lo,hi\n";
    for (std::size_t k = 0; k < r.histogram.density.size(); ++k)
        os << "density," << c(r.histogram.edges[k]) << "," << c(r.histogram.edges[k + 1]) << ","
           << csv_estimate(r.histogram.density[k]) << "\n";
    os << "stuck,0,0," << csv_estimate(r.histogram.stuck) << "\n";
    os << "below,-inf," << c(r.histogram.edges.front()) << "," << csv_estimate(r.histogram.below) << "\n";
    os << "above," << c(r.histogram.edges.back()) << ",inf," << csv_estimate(r.histogram.above) << "\n";
    return os.str();
}

// ---- transient ------------------------------------------------------------------------

std::string to_json(const TransientResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j;
    j["quantity"] = "transient";
    j["engine"] = to_string(q.engine.engine);
    auto params = params_json(q.params, q.engine, q.control.seed);
    params["v0"] = q.v0;
    if (std::isnan(q.x0)) params["x0"] = q.params.white() ? ordered_json(nullptr) : ordered_json("stationary");
    else params["x0"] = q.x0;
    params["trajectories"] = q.trajectories;
    params["level"] = q.level;
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q.params, q.engine);
    ordered_json m1 = ordered_json::array(), m2 = ordered_json::array(), st = ordered_json::array();
    for (std::size_t k = 0; k < r.time.size(); ++k) {
        m1.push_back(point("time", r.time[k], r.first_moment[k]));
        m2.push_back(point("time", r.time[k], r.second_moment[k]));
        st.push_back(point("time", r.time[k], r.stuck[k]));
    }
    j["first_moment"] = m1;
    j["second_moment"] = m2;
    j["stuck"] = st;
    if (!r.density.empty()) {
        ordered_json d = ordered_json::array();
        for (std::size_t k = 0; k < r.time.size(); ++k) {
            ordered_json h = histogram_json(r.density[k]);
            h["time"] = r.time[k];
            d.push_back(h);
        }
        j["density"] = d;
    }
    j["engine_details"] = resolved_json(r.resolved, q.params, q.engine);
    add_work_and_notes(j, q.engine, r.totals, r.warnings);
    return dump(j, indent);
}

std::string to_table(const TransientResult& r) {
    const auto& q = r.request;
    std::ostringstream os;
    os << engine_line("moments", q.engine,
                      ", from v0 = " + g(q.v0) + " m/s, X(0) " +
                          (q.params.white() ? std::string("n/a (white noise)")
                                            : std::isnan(q.x0) ? std::string("~ N(0, 1/tau)") : "= " + g(q.x0)));
    os << param_line(q.params, q.engine) << "\n";
    char buf[200];
    std::snprintf(buf, sizeof buf, "%12s %-25s %-25s %-25s\n", "t [s]", "E[V(t)] [m/s]", "E[V(t)^2] [m^2/s^2]",
                  "P(V(t) = 0)");
    os << buf;
    for (std::size_t k = 0; k < r.time.size(); ++k) {
        std::snprintf(buf, sizeof buf, "%12.6g %s %s %s\n", r.time[k], estimate_cell(r.first_moment[k]).c_str(),
                      estimate_cell(r.second_moment[k]).c_str(), estimate_cell(r.stuck[k]).c_str());
        os << buf;
    }
    os << "\n" << work_line(r.totals.moments.count(), "trajectories", q.control.seed, q.engine, r.totals)
       << notes(r.warnings);
    return os.str();
}

std::string to_csv(const TransientResult& r) {
    std::ostringstream os;
    if (r.density.empty()) {
        os << "time," << csv_estimate_header("first_moment") << "," << csv_estimate_header("second_moment") << ","
           << csv_estimate_header("stuck") << "\n";
        for (std::size_t k = 0; k < r.time.size(); ++k)
            os << c(r.time[k]) << "," << csv_estimate(r.first_moment[k]) << "," << csv_estimate(r.second_moment[k])
               << "," << csv_estimate(r.stuck[k]) << "\n";
        return os.str();
    }
    os << "time,v_lo,v_hi,density,stderr\n";
    for (std::size_t k = 0; k < r.time.size(); ++k) {
        const auto& h = r.density[k];
        for (std::size_t b = 0; b < h.density.size(); ++b)
            os << c(r.time[k]) << "," << c(h.edges[b]) << "," << c(h.edges[b + 1]) << "," << c(h.density[b].value)
               << "," << c(h.density[b].std_error) << "\n";
    }
    return os.str();
}

// ---- correlation ----------------------------------------------------------------------

std::string to_json(const CorrelationResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j;
    j["quantity"] = "autocorrelation";
    j["engine"] = to_string(q.engine.engine);
    j["stop_rule"] = r.resolved.stop_rule;
    auto params = params_json(q.params, q.engine, q.control.seed);
    params["excursions"] = q.excursions;
    params["max_lag"] = q.max_lag;
    params["lags"] = q.lags;
    if (q.engine.engine == Engine::Pdmp) params["sample_dt"] = q.sample_dt > 0 ? q.sample_dt : q.engine.dt;
    params["level"] = q.level;
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q.params, q.engine);
    ordered_json a = ordered_json::array(), h = ordered_json::array(), n = ordered_json::array();
    for (std::size_t k = 0; k < r.lag.size(); ++k) {
        a.push_back(point("lag", r.lag[k], r.autocorrelation[k]));
        h.push_back(point("lag", r.lag[k], r.covariance[k]));
        n.push_back(point("lag", r.lag[k], r.normalised[k]));
    }
    j["autocorrelation"] = a;
    j["covariance"] = h;
    j["normalised_covariance"] = n;
    j["mean"] = estimate_json(r.mean);
    put_all(j, long_excursion_json(r.estimates));
    j["capped"] = r.totals.capped;
    j["engine_details"] = resolved_json(r.resolved, q.params, q.engine);
    add_work_and_notes(j, q.engine, r.totals, r.warnings);
    return dump(j, indent);
}

std::string to_table(const CorrelationResult& r) {
    const auto& q = r.request;
    std::ostringstream os;
    os << engine_line("correlation", q.engine, ", stationary autocorrelation by long excursions (renewal-reward)");
    os << param_line(q.params, q.engine) << "\n";
    char buf[200];
    std::snprintf(buf, sizeof buf, "%12s %-25s %-25s %-25s\n", "lag r [s]", "<V(0)V(r)> [m^2/s^2]",
                  "h(r) [m^2/s^2]", "h(r)/h(0)");
    os << buf;
    for (std::size_t k = 0; k < r.lag.size(); ++k) {
        std::snprintf(buf, sizeof buf, "%12.6g %s %s %s\n", r.lag[k], estimate_cell(r.autocorrelation[k]).c_str(),
                      estimate_cell(r.covariance[k]).c_str(), estimate_cell(r.normalised[k]).c_str());
        os << buf;
    }
    os << "\nmean E[V]          " << estimate_cell(r.mean) << " m/s\n";
    os << "diffusivity D      " << estimate_cell(r.estimates.diffusivity) << " m^2/s (same excursions)\n\n";
    os << work_line(r.estimates.excursions, "excursions", q.control.seed, q.engine, r.totals) << notes(r.warnings);
    return os.str();
}

std::string to_csv(const CorrelationResult& r) {
    std::ostringstream os;
    os << "lag," << csv_estimate_header("autocorrelation") << "," << csv_estimate_header("covariance") << ","
       << csv_estimate_header("normalised") << "\n";
    for (std::size_t k = 0; k < r.lag.size(); ++k)
        os << c(r.lag[k]) << "," << csv_estimate(r.autocorrelation[k]) << "," << csv_estimate(r.covariance[k]) << ","
           << csv_estimate(r.normalised[k]) << "\n";
    return os.str();
}

// ---- trajectories -------------------------------------------------------------------------

std::string to_json(const TrajectoryResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j;
    j["quantity"] = q.paths == 0 ? "excursion" : "paths";
    j["engine"] = to_string(q.engine.engine);
    auto params = params_json(q.params, q.engine, q.control.seed);
    if (q.paths == 0) params["index"] = q.index;
    else {
        params["paths"] = q.paths;
        params["time"] = q.horizon;
        params["v0"] = q.v0;
        params["every"] = q.every;
    }
    j["params"] = params;
    j["nondimensional"] = nondimensional_json(q.params, q.engine);
    if (q.paths == 0) {
        j["displacement"] = r.excursion.displacement;
        j["duration"] = r.excursion.duration;
        j["first_half_duration"] = r.excursion.first_half;
        j["complete"] = !r.excursion.capped;
    }
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
    j["engine_details"] = resolved_json(r.resolved, q.params, q.engine);
    j["warnings"] = r.warnings;
    j["version"] = STICKSLIP_VERSION_STRING;
    return dump(j, indent);
}

std::string to_csv(const TrajectoryResult& r) {
    std::ostringstream os;
    os << "path,t,x,mode,v,u\n";
    for (std::size_t k = 0; k < r.paths.size(); ++k) {
        const auto& p = r.paths[k];
        for (std::size_t i = 0; i < p.t.size(); ++i)
            os << k << "," << c(p.t[i]) << "," << c(p.x[i]) << "," << p.mode[i] << "," << c(p.v[i]) << ","
               << c(p.u[i]) << "\n";
    }
    return os.str();
}

std::string to_table(const TrajectoryResult& r) {
    const auto& q = r.request;
    std::ostringstream os;
    if (q.paths == 0)
        os << engine_line("trajectory", q.engine,
                          ", long excursion " + std::to_string(q.index) + ": U = " + g(r.excursion.displacement) +
                              " m, t1 = " + g(r.excursion.duration) + " s");
    else
        os << engine_line("trajectory", q.engine,
                          ", " + std::to_string(q.paths) + " paths on [0, " + g(q.horizon) + "] s");
    os << param_line(q.params, q.engine) << "\n";
    char buf[200];
    std::snprintf(buf, sizeof buf, "%5s %13s %13s %5s %13s %13s\n", "path", "t [s]", "X [s^-1/2]", "mode", "V [m/s]",
                  "U [m]");
    os << buf;
    for (std::size_t k = 0; k < r.paths.size(); ++k) {
        const auto& p = r.paths[k];
        for (std::size_t i = 0; i < p.t.size(); ++i) {
            std::snprintf(buf, sizeof buf, "%5zu %13.6g %13.6g %5d %13.6g %13.6g\n", k, p.t[i], p.x[i], p.mode[i],
                          p.v[i], p.u[i]);
            os << buf;
        }
    }
    os << notes(r.warnings);
    return os.str();
}

// ---- white-noise references ---------------------------------------------------------------

std::string to_json(const WhiteNoiseResult& r, int indent) {
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    ordered_json j;
    j["quantity"] = "white_noise_reference";
    j["mobility"] = r.reference.mobility;
    j["diffusivity"] = r.reference.diffusivity;
    j["variance"] = r.reference.variance;
    if (!q.times.empty()) {
        j["times"] = q.times;
        j["v0"] = q.v0;
        j["first_moment"] = r.first_moment;
        j["autocorrelation"] = r.autocorrelation;
        j["method"] = r.method;
    }
    if (!q.velocities.empty()) {
        j["velocities"] = q.velocities;
        j["stationary_density"] = r.stationary_density;
        if (!q.times.empty()) j["transient_density"] = r.transient_density;
    }
    ordered_json params;
    params["friction"] = q.params.friction;
    params["noise"] = q.params.noise;
    params["relaxation"] = number_or_inf(q.params.relaxation);
    params["bias"] = q.params.bias;
    j["params"] = params;
    const ModelParams nd = to_nondimensional(q.params);
    j["nondimensional"] = {{"relaxation", number_or_inf(nd.relaxation)},
                           {"bias", nd.bias},
                           {"mobility", r.reference.mobility / sc.velocity},
                           {"diffusivity", r.reference.diffusivity / sc.diffusivity},
                           {"variance", r.reference.variance / (sc.velocity * sc.velocity)},
                           {"time_unit", sc.time},
                           {"velocity_unit", sc.velocity},
                           {"diffusivity_unit", sc.diffusivity}};
    j["warnings"] = r.warnings;
    j["version"] = STICKSLIP_VERSION_STRING;
    return dump(j, indent);
}

std::string to_table(const WhiteNoiseResult& r) {
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    std::ostringstream os;
    os << "stickslip analytic: exact white-noise references\n";
    os << "friction " << g(q.params.friction) << " m/s^2, noise " << g(q.params.noise) << " m^2/s^3, relaxation "
       << (std::isinf(q.params.relaxation) ? std::string("inf") : g(q.params.relaxation) + " s") << ", bias "
       << g(q.params.bias) << " m/s^2\n\n";
    char buf[200];
    std::snprintf(buf, sizeof buf, "%-16s %15.10g %-8s %15.10g\n", "mobility M0", r.reference.mobility, "m/s",
                  r.reference.mobility / sc.velocity);
    os << buf;
    std::snprintf(buf, sizeof buf, "%-16s %15.10g %-8s %15.10g\n", "diffusivity D", r.reference.diffusivity, "m^2/s",
                  r.reference.diffusivity / sc.diffusivity);
    os << buf;
    std::snprintf(buf, sizeof buf, "%-16s %15.10g %-8s %15.10g\n", "variance Var(V)", r.reference.variance,
                  "m^2/s^2", r.reference.variance / (sc.velocity * sc.velocity));
    os << buf << "(last column: nondimensional)\n";
    if (!q.times.empty()) {
        os << "\n" << r.method << "; v0 = " << g(q.v0) << " m/s\n";
        std::snprintf(buf, sizeof buf, "%14s %18s %22s\n", "t [s]", "E[V(t)|v0] [m/s]", "<V(t)V(0)> [m^2/s^2]");
        os << buf;
        for (std::size_t k = 0; k < q.times.size(); ++k) {
            std::snprintf(buf, sizeof buf, "%14.6g %18.10g %22.10g\n", q.times[k], r.first_moment[k],
                          r.autocorrelation[k]);
            os << buf;
        }
    }
    os << notes(r.warnings);
    return os.str();
}

std::string to_csv(const WhiteNoiseResult& r) {
    std::ostringstream os;
    const auto& q = r.request;
    os << "mobility,diffusivity,variance";
    if (!q.times.empty()) os << ",time,first_moment,autocorrelation";
    os << "\n";
    const std::string head = c(r.reference.mobility) + "," + c(r.reference.diffusivity) + "," + c(r.reference.variance);
    if (q.times.empty()) os << head << "\n";
    for (std::size_t k = 0; k < q.times.size(); ++k)
        os << head << "," << c(q.times[k]) << "," << c(r.first_moment[k]) << "," << c(r.autocorrelation[k]) << "\n";
    return os.str();
}

// ---- sweep ------------------------------------------------------------------------------------

std::string to_json(const SweepResult& r, int indent) {
    const auto& q = r.request;
    ordered_json j;
    j["quantity"] = "sweep";
    j["engine"] = to_string(q.engine.engine);
    j["estimator"] = to_string(q.estimator);
    auto params = params_json(q.params, q.engine, q.control.seed);
    params.erase("noise");
    params.erase("tau");
    params["noises"] = q.noises;
    params["taus"] = q.taus;
    params["excursions"] = q.excursions;
    params["level"] = q.level;
    j["params"] = params;
    ordered_json pts = ordered_json::array();
    for (const auto& p : r.points) {
        ModelParams mp = q.params;
        mp.noise = p.noise;
        mp.tau = p.tau;
        const Scales sc = scales_of(mp);
        ordered_json o;
        o["noise"] = p.noise;
        o["tau"] = p.tau;
        o["stop_rule"] = p.stop_rule;
        put_all(o, long_excursion_json(p.estimates));
        o["slope"] = {{"value", num(p.slope.value)}, {"stderr", num(p.slope.std_error)}};
        o["nondimensional"] = {{"tau", p.tau / sc.time},
                               {"diffusivity", p.estimates.diffusivity.value / sc.diffusivity},
                               {"mobility", p.estimates.mobility.value / sc.velocity},
                               {"mean_duration", p.estimates.mean_duration.value / sc.time}};
        o["work"] = {{q.engine.engine == Engine::Pdmp ? "events" : "steps", p.work}, {"seconds", p.seconds}};
        pts.push_back(o);
    }
    j["points"] = pts;
    ordered_json ex = ordered_json::array();
    for (const auto& e : r.exponents) {
        ordered_json o;
        o["tau"] = e.tau;
        o["exponent"] = estimate_json(e.exponent);
        o["chi2_per_dof"] = num(e.chi2_per_dof);
        o["points"] = e.points;
        ex.push_back(o);
    }
    j["exponents"] = ex;
    j["work"] = {{"seconds", r.seconds}};
    j["warnings"] = r.warnings;
    j["version"] = STICKSLIP_VERSION_STRING;
    return dump(j, indent);
}

std::string to_table(const SweepResult& r) {
    const auto& q = r.request;
    std::ostringstream os;
    os << engine_line("sweep", q.engine,
                      ", " + std::to_string(q.excursions) + " excursions per point, estimator " +
                          to_string(q.estimator));
    os << "friction " << g(q.params.friction) << " m/s^2, relaxation "
       << (std::isinf(q.params.relaxation) ? std::string("inf") : g(q.params.relaxation) + " s") << ", bias "
       << g(q.params.bias) << " m/s^2\n\n";
    char buf[300];
    std::snprintf(buf, sizeof buf, "%10s %10s  %-25s %-25s %-20s %-20s\n", "tau [s]", "noise", "D [m^2/s]",
                  "M0 [m/s]", "E[t1] [s]", "dlogD/dlogGamma");
    os << buf;
    for (const auto& p : r.points) {
        char slope[64];
        if (std::isnan(p.slope.value)) std::snprintf(slope, sizeof slope, "%s", "-");
        else std::snprintf(slope, sizeof slope, "%7.3f +- %-7.3f", p.slope.value, p.slope.std_error);
        std::snprintf(buf, sizeof buf, "%10.4g %10.4g  %s %s %10.4g +- %-7.2g %s\n", p.tau, p.noise,
                      estimate_cell(p.estimates.diffusivity).c_str(), estimate_cell(p.estimates.mobility).c_str(),
                      p.estimates.mean_duration.value, p.estimates.mean_duration.std_error, slope);
        os << buf;
    }
    if (!r.exponents.empty()) {
        os << "\nfitted D ~ noise^alpha per tau (weighted least squares in log-log):\n";
        for (const auto& e : r.exponents) {
            const std::string chi2 = std::isnan(e.chi2_per_dof) ? "-" : g(e.chi2_per_dof, 2);
            std::snprintf(buf, sizeof buf, "  tau %10.4g s: alpha = %.3f +- %.3f (chi2/dof %s over %d points)\n",
                          e.tau, e.exponent.value, e.exponent.std_error, chi2.c_str(), e.points);
            os << buf;
        }
    }
    os << "\n" << r.points.size() << " points in " << g(r.seconds, 3) << " s (seed " << q.control.seed << ")\n"
       << notes(r.warnings);
    return os.str();
}

std::string to_csv(const SweepResult& r) {
    std::ostringstream os;
    os << "tau,noise," << csv_estimate_header("diffusivity") << "," << csv_estimate_header("mobility")
       << ",mean_duration,mean_duration_stderr,slope,slope_stderr,tau_nondim,diffusivity_nondim,excursions\n";
    for (const auto& p : r.points) {
        ModelParams mp = r.request.params;
        mp.noise = p.noise;
        mp.tau = p.tau;
        const Scales sc = scales_of(mp);
        os << c(p.tau) << "," << c(p.noise) << "," << csv_estimate(p.estimates.diffusivity) << ","
           << csv_estimate(p.estimates.mobility) << "," << c(p.estimates.mean_duration.value) << ","
           << c(p.estimates.mean_duration.std_error) << "," << c(p.slope.value) << "," << c(p.slope.std_error) << ","
           << c(p.tau / sc.time) << "," << c(p.estimates.diffusivity.value / sc.diffusivity) << ","
           << p.estimates.excursions << "\n";
    }
    return os.str();
}

} // namespace stickslip
