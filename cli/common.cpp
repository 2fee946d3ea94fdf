#include "common.hpp"

#include "distributed.hpp"

#include <cerrno>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace stickslip::cli {

const char* const kConventions = R"(
Model (SI units): dV/dt + friction*sgn(V) = -V/relaxation + bias + sqrt(noise/2)*X(t),
with X the Ornstein-Uhlenbeck noise tau dX = -X dt + sqrt(2) dW (E[X(0)X(t)] =
exp(-|t|/tau)/tau). As tau -> 0 the random force tends to a white noise of
intensity `noise` (<f(t)f(s)> = noise*delta(t-s)); tau = 0 is that white noise.
The object sticks (V = 0) while |bias + force| <= friction.
Nondimensional units: time noise/friction^2, velocity noise/friction, length
noise^2/friction^3, diffusivity noise^3/friction^4; both are reported.
Defaults are the paper's Fig. 2 case. Results are bitwise reproducible for a
given --seed, whatever --threads. Exit codes: 0 ok, 1 I/O or internal error,
2 bad input, 3 untrustworthy run (runaway excursions).

Examples:
  stickslip diffusivity                                  # Fig. 2 case, inclusion engine
  stickslip diffusivity --engine pdmp --excursions 100000 --format json
  stickslip diffusivity --friction 1 --noise 1 --tau 0 --relaxation inf --bias 0 \
      --dt 1e-3                                          # white noise, exact D = 5/4
  stickslip bruteforce --engine pdmp --time 10 --trajectories 20000
  stickslip analytic --friction 1 --noise 1 --relaxation inf --bias 0 --v0 1 --times 0.5,1
  stickslip moments --friction 1 --noise 1 --tau 5e-6 --relaxation inf --bias 0 --dt 1e-3
  stickslip density --format csv --output density.csv
  stickslip sweep --noise 1:10:5 --tau 0.125,0.5 --excursions 4000 --format csv)";

CLI::Option* add_value(CLI::App* app, const std::string& name, std::string& value, const std::string& type,
                       const std::string& help) {
    return app->add_option(name, value, help)->type_name(type)->capture_default_str();
}

void add_model_flags(CLI::App* app, ModelFlags& f, FlagSet which) {
    if (which.physics) {
        add_value(app, "--friction", f.friction, "NUM", "dry-friction coefficient Delta [m s^-2], > 0");
        add_value(app, "--noise", f.noise, "NUM", "noise intensity Gamma [m^2 s^-3], > 0");
        if (which.tau) add_value(app, "--tau", f.tau, "NUM", "noise correlation time [s], >= 0 (0 = white noise)");
        add_value(app, "--relaxation", f.relaxation, "NUM|inf",
                  "viscous relaxation time tauL [s], > 0, or inf for none");
        add_value(app, "--bias", f.bias, "NUM", "constant force gbar [m s^-2], e.g. gravity on an incline");
    }
    if (which.engine) {
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
        add_value(app, "--max-steps", f.max_steps, "INT",
                  "runaway guard: most steps (inclusion) or events (pdmp) per long excursion");
    }
    if (which.run) {
        add_value(app, "--seed", f.seed, "INT", "random seed (64-bit); same seed, same result");
        add_value(app, "--threads", f.threads, "INT", "worker threads; 0 = all cores");
        add_value(app, "--level", f.level, "NUM", "confidence level of the intervals, in (0, 1)");
    }
}

void add_output_flags(CLI::App* app, OutputFlags& o) {
    add_value(app, "--format", o.format, "table|json|csv",
              "table (human), json (one object) or csv (header + rows; notes go to stderr)");
    app->add_option("--output", o.output,
                    "write the result to FILE instead of stdout (atomically: a temporary file renamed into place, "
                    "nothing left behind on failure)")
        ->type_name("FILE");
    app->add_flag("--quiet", o.quiet, "no progress line on stderr");
}

double to_double(const std::string& name, const std::string& s) {
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE)
        throw InvalidParameter(name, name + " must be a number, got '" + s + "'");
    if (std::isnan(x)) throw InvalidParameter(name, name + " must be a number, got NaN");
    return x;
}

std::uint64_t to_seed(const std::string& s) {
    // Parsed as an integer: seeds above 2^53 must not be rounded.
    char* end = nullptr;
    errno = 0;
    // Decimal digits only: no sign, no spaces, no octal/hex surprises ("010" is ten).
    if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
        throw InvalidParameter("seed", "seed must be an integer in [0, 2^64), got '" + s + "'");
    const unsigned long long x = std::strtoull(s.c_str(), &end, 10);
    if (end != s.c_str() + s.size() || errno == ERANGE)
        throw InvalidParameter("seed", "seed must be an integer in [0, 2^64), got '" + s + "'");
    return x;
}

std::uint64_t to_count(const std::string& name, const std::string& s) {
    const double x = to_double(name, s); // accepts 1e6
    if (!(x >= 0) || x != std::floor(x) || x > 1.8e19)
        throw InvalidParameter(name, name + " must be a non-negative integer, got '" + s + "'");
    return static_cast<std::uint64_t>(x);
}

std::vector<double> to_list(const std::string& name, const std::string& s, bool linear) {
    std::vector<double> out;
    if (s.empty()) throw InvalidParameter(name, name + " must list at least one number");
    const auto colon = s.find(':');
    if (colon != std::string::npos) {
        const auto colon2 = s.find(':', colon + 1);
        const char* form = linear ? "lo:hi:n (n evenly spaced values)" : "lo:hi:n (n log-spaced values)";
        if (colon2 == std::string::npos || s.find(':', colon2 + 1) != std::string::npos)
            throw InvalidParameter(name, name + ": expected " + form + ", got '" + s + "'");
        const double lo = to_double(name, s.substr(0, colon));
        const double hi = to_double(name, s.substr(colon + 1, colon2 - colon - 1));
        const std::uint64_t n = to_count(name, s.substr(colon2 + 1));
        const bool ok = std::isfinite(lo) && std::isfinite(hi) && (linear || (lo > 0 && hi > 0));
        if (!ok || n < 1 || n > 1000000)
            throw InvalidParameter(name, name + ": " + form + " needs finite lo, hi" + (linear ? "" : " > 0") +
                                             " and 1 <= n <= 1000000, got '" + s + "'");
        for (std::uint64_t k = 0; k < n; ++k) {
            const double f = n == 1 ? 0.0 : static_cast<double>(k) / static_cast<double>(n - 1);
            out.push_back(linear ? lo + (hi - lo) * f : std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * f));
        }
        out.front() = lo;
        if (n > 1) out.back() = hi;
        return out;
    }
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(to_double(name, item));
    if (!s.empty() && s.back() == ',') throw InvalidParameter(name, name + ": trailing comma in '" + s + "'");
    return out;
}

void fill_physics(const ModelFlags& f, ModelParams& p) {
    p.friction = to_double("friction", f.friction);
    p.noise = to_double("noise", f.noise);
    p.tau = to_double("tau", f.tau);
    p.relaxation = to_double("relaxation", f.relaxation);
    p.bias = to_double("bias", f.bias);
}

void fill(const ModelFlags& f, ModelParams& p, EngineSettings& e, RunControl& c, double& level) {
    fill_physics(f, p);
    e.engine = parse_engine(f.engine);
    e.dt = to_double("dt", f.dt);
    e.grid = to_double("grid", f.grid);
    e.lattice_bound = to_double("lattice-bound", f.lattice_bound);
    e.stop_rule = parse_stop_rule(f.stop_rule);
    e.white_level = to_double("white-level", f.white_level);
    e.max_work_per_excursion = to_count("max-steps", f.max_steps);
    c.seed = to_seed(f.seed);
    const std::uint64_t threads = to_count("threads", f.threads);
    if (threads > 4096) throw InvalidParameter("threads", "threads must be between 0 and 4096");
    c.threads = static_cast<unsigned>(threads);
    level = to_double("level", f.level);
    distribute(c);
}

namespace {

/// The temporary output file of this process, removed by the signal handler
/// (a fixed buffer: only async-signal-safe calls in the handler).
char g_temp_path[4096] = {0};

extern "C" void remove_temp_and_reraise(int sig) {
    if (g_temp_path[0]) ::unlink(g_temp_path);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

} // namespace

Output::Output(const OutputFlags& o) : format_(o.format), path_(o.output), quiet_(o.quiet) {
    if (format_ != "table" && format_ != "json" && format_ != "csv")
        throw InvalidParameter("format", "format must be 'table', 'json' or 'csv', got '" + format_ + "'");
    if (path_.empty()) return;
    // Only the first process writes; every process learns whether it can, so
    // that a bad path stops them all before any work.
    std::string error;
    if (is_root()) {
        struct stat st {};
        if (::stat(path_.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
            error = "'" + path_ + "' is a directory";
        } else {
            // The temporary lives in the target's directory so that rename() is atomic.
            temp_ = path_ + ".tmp." + std::to_string(::getpid());
            fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
            if (fd_ < 0) error = "cannot write '" + path_ + "': " + std::strerror(errno);
        }
    }
    if (!all_ok(error.empty()))
        throw InvalidParameter("output", error.empty() ? "cannot write '" + path_ + "'" : error);
    if (fd_ >= 0 && temp_.size() < sizeof g_temp_path) {
        // Ctrl-C or a kill during a long run must not leave the temporary behind.
        std::memcpy(g_temp_path, temp_.c_str(), temp_.size() + 1);
        std::signal(SIGINT, remove_temp_and_reraise);
        std::signal(SIGTERM, remove_temp_and_reraise);
    }
}

Output::~Output() {
    if (fd_ >= 0) {
        ::close(fd_);
        ::unlink(temp_.c_str());
    }
    g_temp_path[0] = '\0';
}

void Output::commit(const std::string& text, const std::vector<std::string>& warnings) {
    if (!is_root()) return;
    for (const auto& w : warnings) std::fprintf(stderr, "stickslip: note: %s\n", w.c_str());
    if (path_.empty()) {
        std::cout << text << std::flush;
        if (!std::cout) throw std::runtime_error("cannot write to stdout");
        return;
    }
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t w = ::write(fd_, text.data() + done, text.size() - done);
        if (w < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error("cannot write '" + temp_ + "': " + std::strerror(errno));
        }
        done += static_cast<std::size_t>(w);
    }
    const bool synced = ::fsync(fd_) == 0;
    const int sync_errno = errno;
    const bool closed = ::close(fd_) == 0;
    const int close_errno = errno;
    fd_ = -1;
    if (!synced || !closed) {
        const std::string err = std::strerror(!synced ? sync_errno : close_errno);
        ::unlink(temp_.c_str());
        throw std::runtime_error("cannot write '" + temp_ + "': " + err);
    }
    if (::rename(temp_.c_str(), path_.c_str()) != 0) {
        const std::string err = std::strerror(errno);
        ::unlink(temp_.c_str());
        throw std::runtime_error("cannot rename '" + temp_ + "' to '" + path_ + "': " + err);
    }
    if (!quiet_ && isatty(STDERR_FILENO)) std::fprintf(stderr, "wrote %s\n", path_.c_str());
}

std::function<bool(const Progress&)> progress_line(bool quiet, const std::string& what, double level) {
    if (quiet || !isatty(STDERR_FILENO) || distributed()) return {}; // no interleaved lines from many processes
    return [what, level](const Progress& pr) {
        const double rate = pr.seconds > 0 ? static_cast<double>(pr.done) / pr.seconds : 0.0;
        const double left = rate > 0 ? static_cast<double>(pr.total - pr.done) / rate : 0.0;
        std::string estimate;
        if (level > 0 && pr.moments && pr.moments->count() >= 2) {
            const auto e = estimate_long_excursion(*pr.moments, level);
            const double d = e.diffusivity.value;
            char buf[96];
            std::snprintf(buf, sizeof buf, ", D = %.4g +- %.2g%%", d, d > 0 ? 100 * (e.diffusivity.hi - d) / d : 0.0);
            estimate = buf;
        }
        std::fprintf(stderr, "\r%llu/%llu %s%s, %.0f/s, %.1f s elapsed, ~%.0f s left   ",
                     static_cast<unsigned long long>(pr.done), static_cast<unsigned long long>(pr.total), what.c_str(),
                     estimate.c_str(), rate, pr.seconds, left);
        if (pr.done == pr.total) std::fprintf(stderr, "\n");
        std::fflush(stderr);
        return true;
    };
}

} // namespace stickslip::cli
