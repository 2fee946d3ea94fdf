// The subcommands of `stickslip`. Each one registers its flags and returns the
// action to run when it is chosen: parse the strings (errors name the flag),
// build the library request, validate it before any work, compute, emit.
#include "commands.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "stickslip/observables.hpp"
#include "stickslip/report.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/white_noise.hpp"

namespace stickslip::cli {

namespace {

/// Flags shared by the long-excursion commands.
struct ExcursionFlags {
    std::string excursions = "10000";
    bool allow_capped = false;
};

void add_excursion_flags(CLI::App* app, ExcursionFlags& f, const std::string& default_n) {
    f.excursions = default_n;
    add_value(app, "--excursions", f.excursions, "INT", "number N of long excursions (>= 2)");
    app->add_flag("--allow-capped", f.allow_capped,
                  "report a result even if some excursions hit --max-steps (they are dropped; biased)");
}

/// "lo,hi" or empty (automatic).
void parse_range(const std::string& s, VelocityBins& b) {
    if (s.empty()) return;
    const auto v = to_list("range", s);
    if (v.size() != 2) throw InvalidParameter("range", "range must be 'lo,hi' in m/s, got '" + s + "'");
    b.lo = v[0];
    b.hi = v[1];
    if (!(b.lo < b.hi)) throw InvalidParameter("range", "range needs lo < hi, got '" + s + "'");
}

int to_int(const std::string& name, const std::string& s, int max) {
    const std::uint64_t n = to_count(name, s);
    if (n > static_cast<std::uint64_t>(max))
        throw InvalidParameter(name, name + " must be at most " + std::to_string(max) + ", got '" + s + "'");
    return static_cast<int>(n);
}

/// The common tail of every simulating action: validate before any work, attach
/// the progress line, compute, emit.
template <class Request, class Compute>
void finish(Output& out, Request& req, bool quiet, const char* what, Compute compute, double level = 0.0) {
    validate(req);
    req.control.progress = progress_line(quiet, what, level);
    emit(out, compute(req));
}

// ---- diffusivity -----------------------------------------------------------------

Action register_diffusivity(CLI::App& app) {
    struct Flags {
        ModelFlags model;
        OutputFlags out;
        ExcursionFlags exc;
        std::string estimator = "renewal", rel_precision = "0", max_excursions = "1e8";
    };
    auto f = std::make_shared<Flags>();
    auto* sub = app.add_subcommand(
        "diffusivity",
        "D, mobility M0 and mean long-excursion duration E[t1] from N i.i.d. long excursions, with delta-method "
        "confidence intervals. D = sum (U - M0 t)^2 / sum t (renewal-reward form; correct for any M0).");
    add_model_flags(sub, f->model);
    add_excursion_flags(sub, f->exc, "10000");
    add_value(sub, "--estimator", f->estimator, "renewal|paper",
              "renewal (default, correct) or paper (eq. 12, Var U/E t: biased when M0 != 0; for reproducing the "
              "paper's numbers only)");
    add_value(sub, "--rel-precision", f->rel_precision, "NUM",
              "precision on demand: run in batches (the first of --excursions) until the interval half-width of D "
              "is at most this fraction of D, e.g. 0.01; 0 = off. The stopping time depends on the data, so the "
              "interval's coverage is slightly below --level");
    add_value(sub, "--max-excursions", f->max_excursions, "INT", "cap of --rel-precision: most excursions in all");
    add_output_flags(sub, f->out);
    sub->footer(kConventions);
    return {sub, [f] {
                DiffusivityRequest req;
                Output out(f->out);
                fill(f->model, req.params, req.engine, req.control, req.level);
                req.excursions = to_count("excursions", f->exc.excursions);
                req.estimator = parse_estimator(f->estimator);
                req.allow_capped = f->exc.allow_capped;
                req.rel_precision = to_double("rel-precision", f->rel_precision);
                req.max_excursions = to_count("max-excursions", f->max_excursions);
                finish(out, req, f->out.quiet, "excursions", compute_diffusivity, req.level);
            }};
}

// ---- bruteforce ---------------------------------------------------------------------

Action register_bruteforce(CLI::App& app) {
    struct Flags {
        ModelFlags model;
        OutputFlags out;
        std::string horizon = "10", trajectories = "1000", x0, v0 = "0";
    };
    auto f = std::make_shared<Flags>();
    auto* sub = app.add_subcommand(
        "bruteforce",
        "Brute-force estimate D_t = var U(t) / t (paper eq. 13) from N' trajectories on [0, t]: biased by O(1/t), "
        "for comparison with the long-excursion estimator.");
    add_model_flags(sub, f->model);
    add_value(sub, "--time", f->horizon, "NUM", "horizon t [s]");
    add_value(sub, "--trajectories", f->trajectories, "INT", "number N' of trajectories (>= 2)");
    sub->add_option("--x0", f->x0,
                    "initial noise X(0) [s^-1/2]; default: the upper threshold x* (pdmp: the first lattice point "
                    "above it, where the object starts moving)")
        ->type_name("NUM");
    add_value(sub, "--v0", f->v0, "NUM", "initial velocity [m/s]");
    add_output_flags(sub, f->out);
    sub->footer(kConventions);
    return {sub, [f] {
                BruteForceRequest req;
                Output out(f->out);
                fill(f->model, req.params, req.engine, req.control, req.level);
                req.horizon = to_double("time", f->horizon);
                req.trajectories = to_count("trajectories", f->trajectories);
                if (!f->x0.empty()) req.x0 = to_double("x0", f->x0);
                req.v0 = to_double("v0", f->v0);
                finish(out, req, f->out.quiet, "trajectories", compute_bruteforce);
            }};
}

// ---- density ----------------------------------------------------------------------------

Action register_density(CLI::App& app) {
    struct Flags {
        ModelFlags model;
        OutputFlags out;
        ExcursionFlags exc;
        std::string bins = "80", range, sample_dt = "0";
    };
    auto f = std::make_shared<Flags>();
    auto* sub = app.add_subcommand(
        "density",
        "Stationary velocity density as a histogram with error bars, without burn-in bias: time spent in each bin "
        "over a long excursion divided by its duration (renewal-reward ratio, delta-method intervals). The atom at "
        "V = 0 (probability of being stuck, positive for colored noise) is reported separately.");
    add_model_flags(sub, f->model);
    add_excursion_flags(sub, f->exc, "10000");
    add_value(sub, "--bins", f->bins, "INT", "number of equal velocity bins");
    sub->add_option("--range", f->range,
                    "velocity range 'lo,hi' [m/s]; default: white-noise mean -+ 6 standard deviations")
        ->type_name("LO,HI");
    add_value(sub, "--sample-dt", f->sample_dt, "NUM",
              "pdmp only: sampling interval of the path [s]; 0 = --dt (the inclusion engine samples every step)");
    add_output_flags(sub, f->out);
    sub->footer(kConventions);
    return {sub, [f] {
                StationaryDensityRequest req;
                Output out(f->out);
                fill(f->model, req.params, req.engine, req.control, req.level);
                req.excursions = to_count("excursions", f->exc.excursions);
                req.allow_capped = f->exc.allow_capped;
                req.bins.count = to_int("bins", f->bins, 100000);
                parse_range(f->range, req.bins);
                req.sample_dt = to_double("sample-dt", f->sample_dt);
                finish(out, req, f->out.quiet, "excursions", compute_stationary_density);
            }};
}

// ---- moments (transient) -------------------------------------------------------------------

Action register_moments(CLI::App& app) {
    struct Flags {
        ModelFlags model;
        OutputFlags out;
        std::string v0, x0, times, trajectories = "10000", bins = "80", range;
        bool density = false;
    };
    auto f = std::make_shared<Flags>();
    auto* sub = app.add_subcommand(
        "moments",
        "Transient statistics from V(0) = v0 with X(0) drawn from its stationary law N(0, 1/tau) (the paper's "
        "Table I and Fig. 7 set-up): first and second moments E[V(t)|v0], E[V(t)^2|v0] and P(V(t) = 0) at the "
        "given times, and with --density the histogram of V(t). Plain means over independent trajectories.");
    add_model_flags(sub, f->model);
    sub->add_option("--v0", f->v0, "initial velocity v0 [m/s]; default: 1 velocity unit, noise/friction")
        ->type_name("NUM");
    sub->add_option("--x0", f->x0, "initial noise X(0) [s^-1/2]; default: drawn from N(0, 1/tau) per trajectory")
        ->type_name("NUM");
    sub->add_option("--times", f->times,
                    "times t >= 0 [s], comma-separated or lo:hi:n (log-spaced); default: Table I's t' = 0.05, "
                    "0.125, 0.25, 0.5, 1, 2.5 time units (noise/friction^2)")
        ->type_name("LIST");
    add_value(sub, "--trajectories", f->trajectories, "INT", "number of independent trajectories (>= 2)");
    sub->add_flag("--density", f->density, "also estimate the density of V(t) at every time (histogram)");
    add_value(sub, "--bins", f->bins, "INT", "number of velocity bins of --density");
    sub->add_option("--range", f->range, "velocity range 'lo,hi' [m/s] of --density; default: automatic")
        ->type_name("LO,HI");
    add_output_flags(sub, f->out);
    sub->footer(kConventions);
    return {sub, [f] {
                TransientRequest req;
                Output out(f->out);
                fill(f->model, req.params, req.engine, req.control, req.level);
                const Scales sc = scales_of(req.params);
                req.v0 = f->v0.empty() ? sc.velocity : to_double("v0", f->v0);
                if (!f->x0.empty()) req.x0 = to_double("x0", f->x0);
                if (f->times.empty()) {
                    for (double t : {0.05, 0.125, 0.25, 0.5, 1.0, 2.5}) req.times.push_back(t * sc.time);
                } else {
                    req.times = to_list("times", f->times);
                }
                req.trajectories = to_count("trajectories", f->trajectories);
                req.with_density = f->density;
                req.bins.count = to_int("bins", f->bins, 100000);
                parse_range(f->range, req.bins);
                finish(out, req, f->out.quiet, "trajectories", compute_transient);
            }};
}

// ---- correlation ---------------------------------------------------------------------------------

Action register_correlation(CLI::App& app) {
    struct Flags {
        ModelFlags model;
        OutputFlags out;
        ExcursionFlags exc;
        std::string max_lag = "0", lags = "50", sample_dt = "0";
    };
    auto f = std::make_shared<Flags>();
    auto* sub = app.add_subcommand(
        "correlation",
        "Stationary autocorrelation <V(0)V(r)>, covariance h(r) = <V(0)V(r)> - M0^2 and normalised covariance "
        "h(r)/h(0) (the paper's Figs. 5 and 8), as renewal-reward ratios over long excursions: int_0^t1 V(s)V(s+r) ds "
        "/ t1, each excursion continued past its end by the largest lag (exact: the process regenerates). "
        "Delta-method intervals.");
    add_model_flags(sub, f->model);
    add_excursion_flags(sub, f->exc, "10000");
    add_value(sub, "--max-lag", f->max_lag, "NUM", "largest lag r [s]; 0 = 5 time units (noise/friction^2)");
    add_value(sub, "--lags", f->lags, "INT", "number of lag intervals: lags 0, max/lags, ..., max");
    add_value(sub, "--sample-dt", f->sample_dt, "NUM",
              "pdmp only: sampling interval of the path [s]; 0 = --dt (the inclusion engine samples every step)");
    add_output_flags(sub, f->out);
    sub->footer(kConventions);
    return {sub, [f] {
                CorrelationRequest req;
                Output out(f->out);
                fill(f->model, req.params, req.engine, req.control, req.level);
                req.excursions = to_count("excursions", f->exc.excursions);
                req.allow_capped = f->exc.allow_capped;
                req.max_lag = to_double("max-lag", f->max_lag);
                req.lags = to_int("lags", f->lags, 100000);
                req.sample_dt = to_double("sample-dt", f->sample_dt);
                finish(out, req, f->out.quiet, "excursions", compute_correlation);
            }};
}

// ---- trajectory --------------------------------------------------------------------------------------

Action register_trajectory(CLI::App& app) {
    struct Flags {
        ModelFlags model;
        OutputFlags out;
        std::string index = "0", paths = "0", horizon = "2", x0, v0 = "0", every = "0", max_points = "5000000";
    };
    auto f = std::make_shared<Flags>();
    auto* sub = app.add_subcommand(
        "trajectory",
        "Sample paths (X, mode, V, U against t). Default: one long excursion, number --index of --seed, the very "
        "one `diffusivity` runs (the paper's Figs. 2 and 3). With --paths N: N independent paths on [0, --time] "
        "from (x0, v0) (Fig. 6, right). Best with --format csv.");
    add_model_flags(sub, f->model, FlagSet{true, true, true, false});
    add_value(sub, "--seed", f->model.seed, "INT", "random seed (64-bit)");
    add_value(sub, "--index", f->index, "INT", "excursion number (excursion mode)");
    add_value(sub, "--paths", f->paths, "INT", "number of independent paths (0 = one long excursion instead)");
    add_value(sub, "--time", f->horizon, "NUM", "path length [s] (path mode)");
    sub->add_option("--x0", f->x0, "initial noise X(0) [s^-1/2] (path mode); default: the upper threshold x*")
        ->type_name("NUM");
    add_value(sub, "--v0", f->v0, "NUM", "initial velocity [m/s] (path mode)");
    add_value(sub, "--every", f->every, "NUM",
              "recording interval [s]; 0 = every step (inclusion) or event (pdmp) of an excursion, time/1000 for "
              "paths");
    add_value(sub, "--max-points", f->max_points, "INT", "refuse to record more points than this per path");
    add_output_flags(sub, f->out);
    sub->footer(kConventions);
    return {sub, [f] {
                TrajectoryRequest req;
                Output out(f->out);
                double level = 0.95;
                ModelFlags m = f->model;
                fill(m, req.params, req.engine, req.control, level);
                req.index = to_count("index", f->index);
                req.paths = to_count("paths", f->paths);
                req.horizon = to_double("time", f->horizon);
                if (!f->x0.empty()) req.x0 = to_double("x0", f->x0);
                req.v0 = to_double("v0", f->v0);
                req.every = to_double("every", f->every);
                req.max_points = to_count("max-points", f->max_points);
                validate(req);
                emit(out, compute_trajectory(req));
            }};
}

// ---- analytic --------------------------------------------------------------------------------------------

Action register_analytic(CLI::App& app) {
    struct Flags {
        ModelFlags model;
        OutputFlags out;
        std::string v0 = "0", times, velocities;
    };
    auto f = std::make_shared<Flags>();
    auto* sub = app.add_subcommand(
        "analytic",
        "Exact white-noise references (no simulation): mobility M0, diffusivity D and stationary variance by "
        "quadrature of Hayakawa's density for any b(v); with --times, the first moment E[V(t)|v0] and the "
        "stationary autocorrelation <V(t)V(0)> (closed forms of Touchette et al. 2010 for pure dry friction, "
        "a Fokker-Planck solution otherwise). Physical units; tau is not used.");
    add_model_flags(sub, f->model, FlagSet{true, false, false, false});
    add_value(sub, "--v0", f->v0, "NUM", "initial velocity of the first moment [m/s]");
    sub->add_option("--times", f->times, "times t >= 0 [s], comma-separated or lo:hi:n (log-spaced)")
        ->type_name("LIST");
    sub->add_option("--velocities", f->velocities,
                    "velocities v [m/s], comma-separated or lo:hi:n (n evenly spaced): adds the stationary density "
                    "p(v) and, with --times, the transition density p(v, t | v0) (json)")
        ->type_name("LIST");
    add_output_flags(sub, f->out);
    sub->footer(kConventions);
    return {sub, [f] {
                WhiteNoiseRequest req;
                if (!f->velocities.empty()) req.velocities = to_list("velocities", f->velocities, true);
                Output out(f->out);
                ModelFlags m = f->model;
                m.tau = "0";
                fill_physics(m, req.params);
                req.v0 = to_double("v0", f->v0);
                if (!f->times.empty()) req.times = to_list("times", f->times);
                validate(req);
                emit(out, compute_white_noise(req));
            }};
}

// ---- sweep --------------------------------------------------------------------------------------------------

Action register_sweep(CLI::App& app) {
    struct Flags {
        ModelFlags model;
        OutputFlags out;
        ExcursionFlags exc;
        std::string estimator = "renewal";
    };
    auto f = std::make_shared<Flags>();
    f->model.noise = "1:10:5";
    f->model.tau = "0.125,0.25,0.5,1";
    auto* sub = app.add_subcommand(
        "sweep",
        "D, M0 and E[t1] over a grid of noise and tau values (the paper's Figs. 4 and 9), with the local log-log "
        "slope d log D / d log noise and its error, and per tau the fitted exponent of D ~ noise^alpha. --noise "
        "and --tau take lists. Each point has its own random streams (independent errors).");
    add_model_flags(sub, f->model);
    sub->get_option("--noise")->description("noise intensities Gamma [m^2 s^-3]: comma-separated or lo:hi:n (n log-spaced)")->type_name("LIST");
    sub->get_option("--tau")->description("correlation times [s]: comma-separated or lo:hi:n (n log-spaced)")->type_name("LIST");
    add_excursion_flags(sub, f->exc, "10000");
    sub->get_option("--excursions")->description("long excursions per point (>= 2)");
    add_value(sub, "--estimator", f->estimator, "renewal|paper", "renewal (default) or paper (eq. 12)");
    add_output_flags(sub, f->out);
    sub->footer(kConventions);
    return {sub, [f] {
                SweepRequest req;
                Output out(f->out);
                ModelFlags m = f->model;
                m.noise = "1";
                m.tau = "1";
                fill(m, req.params, req.engine, req.control, req.level);
                req.noises = to_list("noise", f->model.noise);
                req.taus = to_list("tau", f->model.tau);
                req.excursions = to_count("excursions", f->exc.excursions);
                req.estimator = parse_estimator(f->estimator);
                req.allow_capped = f->exc.allow_capped;
                validate(req);
                const bool quiet = f->out.quiet;
                req.point_progress = [quiet](std::size_t k, std::size_t n, double noise, double tau) {
                    char what[160];
                    std::snprintf(what, sizeof what, "excursions (point %zu/%zu: noise %g, tau %g)", k + 1, n, noise,
                                  tau);
                    return progress_line(quiet, what);
                };
                emit(out, compute_sweep(req));
            }};
}

} // namespace

std::vector<Action> register_all(CLI::App& app) {
    return {register_diffusivity(app), register_bruteforce(app),  register_density(app),
            register_moments(app),     register_correlation(app), register_trajectory(app),
            register_analytic(app),    register_sweep(app)};
}

} // namespace stickslip::cli
