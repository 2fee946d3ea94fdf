// The `stickslip` command: a thin layer over the library (diffusivity.hpp,
// report.hpp). It parses flags, reports progress on a terminal, prints the
// result, and maps errors to exit codes: 2 bad input (one line on stderr,
// nothing on stdout), 3 a run that cannot be trusted (capped excursions).
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <unistd.h>

#include "stickslip/diffusivity.hpp"
#include "stickslip/report.hpp"

namespace ss = stickslip;

namespace {

constexpr const char* kConventions = R"(
Model (SI units): dV/dt + friction*sgn(V) = -V/relaxation + bias + sqrt(noise/2)*X(t),
with X the Ornstein-Uhlenbeck noise tau dX = -X dt + sqrt(2) dW (E[X(0)X(t)] =
exp(-|t|/tau)/tau). As tau -> 0 the random force tends to a white noise of
intensity `noise` (<f(t)f(s)> = noise*delta(t-s)); tau = 0 is that white noise.
The object sticks (V = 0) while |bias + force| <= friction.
Nondimensional units: time noise/friction^2, length noise^2/friction^3,
diffusivity noise^3/friction^4; both are reported.
Defaults are the paper's Fig. 2 case. Results are bitwise reproducible for a
given --seed, whatever --threads. Exit codes: 0 ok, 2 bad input, 3 untrustworthy
run (runaway excursions).

Examples:
  stickslip diffusivity                                  # Fig. 2 case, inclusion engine
  stickslip diffusivity --engine pdmp --excursions 100000 --format json
  stickslip diffusivity --friction 1 --noise 1 --tau 0 --relaxation inf --bias 0 \
      --dt 1e-3                                          # white noise, exact D = 5/4
  stickslip bruteforce --engine pdmp --time 10 --trajectories 20000)";

struct ModelFlags {
    std::string friction = "3.84", noise = "5", tau = "0.5", relaxation = "0.067", bias = "0.342";
    std::string engine = "inclusion", dt = "1e-4", grid = "0.125", lattice_bound = "0";
    std::string seed = "1", threads = "0", level = "0.95", format = "table", max_steps = "200000000";
    std::string stop_rule = "auto", white_level = "0";
    bool quiet = false;
};

/// A value option: shown with its type and its default in --help.
CLI::Option* add_value(CLI::App* app, const std::string& name, std::string& value, const std::string& type,
                       const std::string& help) {
    return app->add_option(name, value, help)->type_name(type)->capture_default_str();
}

void add_model_flags(CLI::App* app, ModelFlags& f) {
    add_value(app, "--friction", f.friction, "NUM", "dry-friction coefficient Delta [m s^-2], > 0");
    add_value(app, "--noise", f.noise, "NUM", "noise intensity Gamma [m^2 s^-3], > 0");
    add_value(app, "--tau", f.tau, "NUM", "noise correlation time [s], >= 0 (0 = white noise)");
    add_value(app, "--relaxation", f.relaxation, "NUM|inf", "viscous relaxation time tauL [s], > 0, or inf for none");
    add_value(app, "--bias", f.bias, "NUM", "constant force gbar [m s^-2], e.g. gravity on an incline");
    add_value(app, "--engine", f.engine, "inclusion|pdmp",
              "inclusion (time stepping, exact OU noise) or pdmp (exact event-driven, lattice noise)");
    add_value(app, "--dt", f.dt, "NUM", "time step of the inclusion engine [s]");
    add_value(app, "--grid", f.grid, "NUM", "lattice step delta of the pdmp noise [s^-1/2]");
    add_value(app, "--lattice-bound", f.lattice_bound, "NUM",
              "pdmp lattice half-width L [s^-1/2]; 0 = 8 tau^-1/2 (or what tau*grid*L < 2 allows)");
    add_value(app, "--stop-rule", f.stop_rule, "auto|bridge|stuck",
              "inclusion HLE end test: auto (bridge if dt <= tau/10, else stuck), bridge (rule Q), stuck (rule P)");
    add_value(app, "--white-level", f.white_level, "NUM",
              "white noise only: regeneration velocity levels +-c [m/s]; 0 chooses c");
    add_value(app, "--seed", f.seed, "INT", "random seed (64-bit); same seed, same result");
    add_value(app, "--threads", f.threads, "INT", "worker threads; 0 = all cores");
    add_value(app, "--level", f.level, "NUM", "confidence level of the intervals, in (0, 1)");
    add_value(app, "--max-steps", f.max_steps, "INT",
              "runaway guard: most steps (inclusion) or events (pdmp) per long excursion");
    add_value(app, "--format", f.format, "table|json", "table (human) or json (one object on stdout)");
    app->add_flag("--quiet", f.quiet, "no progress line on stderr");
}

double to_double(const std::string& name, const std::string& s) {
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE)
        throw ss::InvalidParameter(name, name + " must be a number, got '" + s + "'");
    if (std::isnan(x)) throw ss::InvalidParameter(name, name + " must be a number, got NaN");
    return x;
}

std::uint64_t to_seed(const std::string& s) {
    // Parsed as an integer: seeds above 2^53 must not be rounded.
    char* end = nullptr;
    errno = 0;
    if (s.empty() || s[0] == '-' || s[0] == '+')
        throw ss::InvalidParameter("seed", "seed must be an integer in [0, 2^64), got '" + s + "'");
    const unsigned long long x = std::strtoull(s.c_str(), &end, 0);
    if (end != s.c_str() + s.size() || errno == ERANGE)
        throw ss::InvalidParameter("seed", "seed must be an integer in [0, 2^64), got '" + s + "'");
    return x;
}

std::uint64_t to_count(const std::string& name, const std::string& s) {
    const double x = to_double(name, s); // accepts 1e6
    if (!(x >= 0) || x != std::floor(x) || x > 1.8e19)
        throw ss::InvalidParameter(name, name + " must be a non-negative integer, got '" + s + "'");
    return static_cast<std::uint64_t>(x);
}

void fill(const ModelFlags& f, ss::ModelParams& p, ss::EngineSettings& e, ss::RunControl& c, double& level) {
    p.friction = to_double("friction", f.friction);
    p.noise = to_double("noise", f.noise);
    p.tau = to_double("tau", f.tau);
    p.relaxation = to_double("relaxation", f.relaxation);
    p.bias = to_double("bias", f.bias);
    e.engine = ss::parse_engine(f.engine);
    e.dt = to_double("dt", f.dt);
    e.grid = to_double("grid", f.grid);
    e.lattice_bound = to_double("lattice-bound", f.lattice_bound);
    e.stop_rule = ss::parse_stop_rule(f.stop_rule);
    e.white_level = to_double("white-level", f.white_level);
    e.max_work_per_excursion = to_count("max-steps", f.max_steps);
    c.seed = to_seed(f.seed);
    const std::uint64_t threads = to_count("threads", f.threads);
    if (threads > 4096) throw ss::InvalidParameter("threads", "threads must be between 0 and 4096");
    c.threads = static_cast<unsigned>(threads);
    level = to_double("level", f.level);
    if (f.format != "table" && f.format != "json")
        throw ss::InvalidParameter("format", "format must be 'table' or 'json', got '" + f.format + "'");
}

/// Progress line on stderr, only when it is a terminal.
std::function<bool(const ss::Progress&)> progress_line(bool quiet, const char* what) {
    if (quiet || !isatty(STDERR_FILENO)) return {};
    return [what](const ss::Progress& pr) {
        const double rate = pr.seconds > 0 ? static_cast<double>(pr.done) / pr.seconds : 0.0;
        const double left = rate > 0 ? static_cast<double>(pr.total - pr.done) / rate : 0.0;
        std::fprintf(stderr, "\r%llu/%llu %s, %.1f s elapsed, ~%.0f s left   ",
                     static_cast<unsigned long long>(pr.done), static_cast<unsigned long long>(pr.total), what,
                     pr.seconds, left);
        if (pr.done == pr.total) std::fprintf(stderr, "\n");
        std::fflush(stderr);
        return true;
    };
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"stickslip: diffusivity and mobility of an object with dry friction under white or colored "
                 "noise,\nby the unbiased long-excursion estimators (exact PDMP or differential-inclusion engine)."};
    app.footer(kConventions);
    app.require_subcommand(1);
    app.set_version_flag("--version", STICKSLIP_VERSION_STRING);

    ModelFlags df;
    std::string excursions = "10000", estimator = "renewal";
    bool allow_capped = false;
    auto* diff = app.add_subcommand(
        "diffusivity",
        "D, mobility M0 and mean long-excursion duration E[t1] from N i.i.d. long excursions, with delta-method "
        "confidence intervals. D = sum (U - M0 t)^2 / sum t (renewal-reward form; correct for any M0).");
    add_model_flags(diff, df);
    add_value(diff, "--excursions", excursions, "INT", "number N of long excursions (>= 2)");
    add_value(diff, "--estimator", estimator, "renewal|paper",
              "renewal (default, correct) or paper (eq. 12, Var U/E t: biased when M0 != 0; for reproducing the "
              "paper's numbers only)");
    diff->add_flag("--allow-capped", allow_capped,
                   "report a result even if some excursions hit --max-steps (they are dropped; biased)");
    diff->footer(kConventions);

    ModelFlags bf;
    std::string horizon = "10", trajectories = "1000", x0 = "", v0 = "0";
    auto* brute = app.add_subcommand(
        "bruteforce",
        "Brute-force estimate D_t = var U(t) / t (paper eq. 13) from N' trajectories on [0, t]: biased by O(1/t), "
        "for comparison with the long-excursion estimator.");
    add_model_flags(brute, bf);
    add_value(brute, "--time", horizon, "NUM", "horizon t [s]");
    add_value(brute, "--trajectories", trajectories, "INT", "number N' of trajectories (>= 2)");
    brute->add_option("--x0", x0,
                      "initial noise X(0) [s^-1/2]; default: the upper threshold x* (pdmp: the first lattice point "
                      "above it, where the object starts moving)")
        ->type_name("NUM");
    add_value(brute, "--v0", v0, "NUM", "initial velocity [m/s]");
    brute->footer(kConventions);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::string msg = e.what();
        for (auto& ch : msg)
            if (ch == '\n') ch = ' ';
        std::fprintf(stderr, "stickslip: error: %s (see --help)\n", msg.c_str());
        return 2;
    }

    try {
        if (diff->parsed()) {
            ss::DiffusivityRequest req;
            fill(df, req.params, req.engine, req.control, req.level);
            req.excursions = to_count("excursions", excursions);
            req.estimator = ss::parse_estimator(estimator);
            req.allow_capped = allow_capped;
            ss::validate(req);
            req.control.progress = progress_line(df.quiet, "excursions");
            const auto result = ss::compute_diffusivity(req);
            std::cout << (df.format == "json" ? ss::to_json(result) : ss::to_table(result)) << std::flush;
        } else {
            ss::BruteForceRequest req;
            fill(bf, req.params, req.engine, req.control, req.level);
            req.horizon = to_double("time", horizon);
            req.trajectories = to_count("trajectories", trajectories);
            if (!x0.empty()) req.x0 = to_double("x0", x0);
            req.v0 = to_double("v0", v0);
            ss::validate(req);
            req.control.progress = progress_line(bf.quiet, "trajectories");
            const auto result = ss::compute_bruteforce(req);
            std::cout << (bf.format == "json" ? ss::to_json(result) : ss::to_table(result)) << std::flush;
        }
    } catch (const ss::InvalidParameter& e) {
        std::fprintf(stderr, "stickslip: error: --%s: %s\n", e.parameter().c_str(), e.what());
        return 2;
    } catch (const ss::CappedExcursions& e) {
        std::fprintf(stderr, "stickslip: ERROR: %s\n", e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "stickslip: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
