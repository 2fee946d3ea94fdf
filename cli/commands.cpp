// SPDX-License-Identifier: BSD-3-Clause
// The subcommands of `stickslip`. Each is one library request: its flags are
// the request's settings (setting_flags.hpp), and running it fills the
// request, arms the process split and the progress line, computes and emits
// the report. The library validates the request, once, before any work.
#include "commands.hpp"

#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <optional>
#include <type_traits>

#include "distributed.hpp"
#include "interrupt.hpp"
#include "output.hpp"
#include "progress.hpp"
#include "stickslip/drift_input.hpp"
#include "setting_flags.hpp"
#include "stickslip/bruteforce.hpp"
#include "stickslip/checkpoint.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/report.hpp"
#include "stickslip/spectrum.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/white_noise.hpp"

namespace stickslip::cli {

const char* const kConventions = R"(
Model (SI units): dV/dt + friction*sgn(V) = -V/relaxation + bias + sqrt(noise/2)*X(t),
with X the Ornstein-Uhlenbeck noise tau dX = -X dt + sqrt(2) dW (E[X(0)X(t)] =
exp(-|t|/tau)/tau). As tau -> 0 the random force tends to a white noise of
intensity `noise` (<f(t)f(s)> = noise*delta(t-s)); tau = 0 is that white noise.
The object sticks (V = 0) while |bias + force| <= friction. A long excursion
runs from rest with the noise X at the upper threshold x* (about to slide up)
to rest at the lower one (about to slide down: a half long excursion) and back;
long excursions are independent, E[t1] is their mean duration.
Nondimensional units: time noise/friction^2, velocity noise/friction, length
noise^2/friction^3, diffusivity noise^3/friction^4; both are reported.
Defaults are the paper's Fig. 2 case. Results are bitwise reproducible for a
given --seed, whatever --threads. A run's settings can be kept in a file:
--print-config writes them, --config FILE reads them back. Exit codes: 0 ok,
1 I/O error while running or internal error, 2 bad input (an --output that
cannot be created included), 3 untrustworthy run (runaway excursions, or every
excursion shorter than one step),
130/143/129 stopped by SIGINT/SIGTERM/SIGHUP: the first signal lets the blocks in flight
finish and writes the result so far (marked "interrupted") and the checkpoint;
a second one, a second or more later, aborts. --checkpoint FILE saves a run every --checkpoint-every
seconds; --resume FILE continues it, with a result identical to an
uninterrupted run's.

Examples:
  stickslip diffusivity                                  # Fig. 2 case, inclusion engine
  stickslip diffusivity --engine pdmp --excursions 100000 --format json
  stickslip diffusivity --friction 1 --noise 1 --tau 0 --relaxation inf --bias 0 \
      --dt 1e-3                                          # white noise, exact D = 5/4
  stickslip bruteforce --engine pdmp --time 10 --trajectories 20000
  stickslip analytic --friction 1 --noise 1 --relaxation inf --bias 0 --v0 1 --times 0.5,1
  stickslip moments --friction 1 --noise 1 --tau 5e-6 --relaxation inf --bias 0 --dt 1e-3
  stickslip density --format csv --output density.csv
  stickslip spectrum --frequencies 0,0.1,1,10 --format json  # S(w), Fig. 2 case
  stickslip sweep --noise 1:10:5 --tau 0.125,0.5 --excursions 4000 --format csv
  stickslip sweep --drift "a*v - c*v^3" --drift-params a=0.8 --vary c \
      --vary-values 0.2:1:5 --tau 0.25 --noise 5 --engine kolmogorov   # D against c
  stickslip diffusivity --excursions 1e5 --print-config > run.toml
  stickslip diffusivity --config run.toml --seed 2
  stickslip diffusivity --excursions 1e8 --checkpoint run.ckpt --resume run.ckpt)";

namespace {

/// What a subcommand shows on its progress line: the samples' name, and
/// whether D and its half-width go with it (long excursions).
struct ProgressLabel {
    const char* samples = nullptr; ///< nullptr: no progress line
    bool with_estimate = false;
};

/// --checkpoint, --checkpoint-every, --resume (help texts from the library).
struct CheckpointFlags {
    CheckpointOptions options;
    std::string every; ///< as given: read like every other number (CLI11 would take hexadecimal)
};

void add_checkpoint_flags(CLI::App* app, CheckpointFlags& o) {
    app->add_option("--checkpoint", o.options.path, CheckpointOptions::path_help)->type_name("FILE");
    app->add_option("--checkpoint-every", o.every, CheckpointOptions::every_help)
        ->type_name("SECONDS")
        ->default_str(format_setting(o.options.every));
    app->add_option("--resume", o.options.resume, CheckpointOptions::resume_help)->type_name("FILE");
}

/// The checkpoint options, --checkpoint-every read and every option checked
/// (whether or not a checkpoint is asked for).
const CheckpointOptions& read_checkpoint_flags(CheckpointFlags& o) {
    if (!o.every.empty())
        parse_setting(SettingInfo{"checkpoint-every", "s", CheckpointOptions::every_help}, o.every, o.options.every);
    validate(o.options);
    return o.options;
}

/// The run's journal (make_journal) with the command's warning lines. Only
/// the first process writes the checkpoint, so only it can find the path
/// unwritable: every process learns whether all could start, so that they all
/// stop, with exit 2, rather than wait for the one that stopped.
template <class Request>
std::unique_ptr<RunJournal> open_journal(Request& req, CheckpointOptions options) {
    options.warn = [](const std::string& line) { std::fprintf(stderr, "stickslip: warning: --checkpoint: %s\n", line.c_str()); };
    std::unique_ptr<RunJournal> journal;
    std::exception_ptr failure;
    try {
        journal = make_journal(req, options);
    } catch (...) {
        failure = std::current_exception();
    }
    if (!all_ok(!failure)) {
        if (failure) std::rethrow_exception(failure);
        throw InvalidParameter("checkpoint", "another process of the run could not open its checkpoint or resume file");
    }
    return journal;
}

/// Writes the report of a run stopped before it had an estimate (report.hpp),
/// in the chosen format; `checkpoint`: the run's checkpoint path ("" none).
void emit_interrupted(Output& out, const RunInterrupted& e, const std::string& command,
                      const std::string& checkpoint) {
    const std::vector<std::string> warnings{
        checkpoint.empty()
            ? std::string("interrupted before a block finished; run it again, with --checkpoint FILE to keep what "
                          "a run has done")
            : "interrupted before a block finished; --resume " + printable_text(checkpoint) +
                  " continues the run from its checkpoint"};
    if (out.format() == "json") out.commit(to_json(e, command.c_str(), warnings), {});
    else if (out.format() == "csv") out.commit(to_csv(e, command.c_str()), warnings);
    else out.commit(to_table(e, command.c_str(), warnings), {});
}

template <class Request>
constexpr bool resumable() {
    if constexpr (requires { Request::resumable; }) return Request::resumable;
    return false;
}

/// A subcommand for `Request`: the flags of its settings, --format/--output/
/// --quiet, for a run through the block driver --checkpoint/--resume, and the
/// run, which stops gracefully on the first SIGINT, SIGTERM or SIGHUP (interrupt.hpp).
/// `customise(request, quiet)`, when given, is called just before computing
/// (the sweep sets its per-point progress there).
template <class Request, class Result>
Action add_command(CLI::App& app, const char* description, Result (*compute)(const Request&),
                   ProgressLabel progress, void (*customise)(Request&, bool quiet) = nullptr) {
    struct State {
        Request request;
        SettingFlags flags;
        OutputFlags output;
        CheckpointFlags checkpoint;
    };
    auto state = std::make_shared<State>();
    const std::string command = Request::command;
    CLI::App* sub = app.add_subcommand(command, description);
    state->flags.add_to(sub, state->request);
    add_output_flags(sub, state->output);
    if constexpr (resumable<Request>()) add_checkpoint_flags(sub, state->checkpoint);
    sub->footer(kConventions);
    return {sub, [state, compute, progress, customise, command](const std::string& command_line) {
                state->flags.apply();
                read_output_flags(state->output);
                Request& req = state->request;
                {
                    std::vector<std::pair<std::string, std::string>> inputs{{"config", state->flags.config_path()}};
                    if constexpr (requires { req.params.drift_table; })
                        inputs.push_back({"drift-table", req.params.drift_table});
                    refuse_output_over_inputs(state->output, inputs);
                }
                // The input files, read once for the whole command (its
                // digest in the reports and the checkpoint).
                if constexpr (requires { req.params.drift_table; }) read_drift_inputs(req.params);
                req.command_line = command_line; // the reports' provenance
                if constexpr (resumable<Request>()) read_checkpoint_flags(state->checkpoint);
                if (state->flags.print_config()) {
                    // Checked as the run would check them: a config file
                    // that cannot run is refused now, not when it is used.
                    validate(static_cast<const Request&>(req));
                    Output out(state->output);
                    out.commit(state->flags.config_text(command), {});
                    return;
                }
                if constexpr (resumable<Request>()) refuse_shared_paths(state->output, state->checkpoint.options);
                Output out(state->output);
                if constexpr (std::is_base_of_v<RunSettings, Request>) {
                    distribute(req.control);
                    if (progress.samples)
                        req.control.progress = progress_line(state->output.quiet, progress.samples,
                                                             progress.with_estimate ? req.level : 0.0);
                    req.control.notice = notice_line(state->output.quiet);
                    req.control.long_run = long_run_line(state->output.quiet);
                } else {
                    (void)progress; // only runs report progress
                }
                if constexpr (resumable<Request>()) {
                    // From here the run polls the stop flag (a signal while
                    // the journal opens is seen by the first block); writing
                    // the result afterwards is not stopped gracefully.
                    std::optional<GracefulStop> graceful(std::in_place);
                    req.control.stop = StopOnSignals::flag();
                    req.control.cancel = StopOnSignals::drop_flag();
                    const std::unique_ptr<RunJournal> journal = open_journal(req, state->checkpoint.options);
                    req.control.journal = journal.get();
                    if (customise) customise(req, state->output.quiet);
                    try {
                        const Result r = compute(req);
                        graceful.reset();
                        if (journal) journal->write();
                        emit(out, r);
                    } catch (const RunInterrupted& e) {
                        // Stopped before anything could be estimated: the
                        // checkpoint and a result that says so, every time.
                        graceful.reset(); // writing to a FIFO nobody reads must not swallow the next signal
                        if (journal) journal->write();
                        emit_interrupted(out, e, command, state->checkpoint.options.path);
                        throw;
                    }
                } else {
                    if (customise) customise(req, state->output.quiet);
                    emit(out, compute(req));
                }
            }};
}

void sweep_progress(SweepRequest& req, bool quiet) {
    // A solved sweep counts points, not excursions (SweepRequest).
    if (!samples(req.engine)) req.control.progress = progress_line(quiet, "points solved (kolmogorov engine)");
    req.point_progress = [quiet](std::size_t k, std::size_t n, const std::string& point) {
        return progress_line(quiet, "excursions (point " + std::to_string(k + 1) + "/" + std::to_string(n) + ": " +
                                        point + ")");
    };
}

} // namespace

std::string command_line(int argc, char** argv) {
    std::string line = "stickslip";
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        const bool plain = !arg.empty() && arg.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                                                 "0123456789_./:=,+-%@") == std::string::npos;
        if (plain) {
            line += " " + arg;
            continue;
        }
        line += " '";
        for (char c : arg) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
        line += "'";
    }
    return printable_text(line); // one line, whatever bytes were given
}

std::vector<Action> register_all(CLI::App& app) {
    return {
        add_command(app,
                    "D, mobility M0 and mean long-excursion duration E[t1] from N i.i.d. long excursions, with "
                    "delta-method confidence intervals. D = sum (U - M0 t)^2 / sum t (renewal-reward form; correct for "
                    "any M0).",
                    &compute_diffusivity, {"excursions", true}),
        add_command(app,
                    "Brute-force estimate D_t = var U(t) / t (paper eq. 13) from N' trajectories on [0, t]: biased by "
                    "O(1/t), for comparison with the long-excursion estimator.",
                    &compute_bruteforce, {"trajectories", false}),
        add_command(app,
                    "Stationary velocity density as a histogram with error bars, without burn-in bias: time spent in "
                    "each bin over a long excursion divided by its duration (renewal-reward ratio, delta-method "
                    "intervals). The atom at V = 0 (probability of being stuck, positive for colored noise) is "
                    "reported separately.",
                    &compute_density, {"excursions", false}),
        add_command(app,
                    "Transient statistics from V(0) = v0 with X(0) drawn from its stationary law N(0, 1/tau) (the "
                    "paper's Table I and Fig. 7 set-up): first and second moments E[V(t)|v0], E[V(t)^2|v0] and "
                    "P(V(t) = 0) at the given times, and with --density the histogram of V(t). Plain means over "
                    "independent trajectories.",
                    &compute_moments, {"trajectories", false}),
        add_command(app,
                    "Stationary autocorrelation <V(0)V(r)>, covariance h(r) = <V(0)V(r)> - M0^2 and normalised "
                    "covariance h(r)/h(0) (the paper's Figs. 5 and 8), as renewal-reward ratios over long excursions: "
                    "int_0^t1 V(s)V(s+r) ds / t1, each excursion continued past its end by the largest lag (exact: the "
                    "process regenerates). Delta-method intervals.",
                    &compute_correlation, {"excursions", false}),
        add_command(app,
                    "Sample paths (X, mode, V, U against t). Default: one long excursion, number --index of --seed, "
                    "the very one `diffusivity` runs (the paper's Figs. 2 and 3). With --paths N: N independent paths "
                    "on [0, --time] from (x0, v0) (Fig. 6, right). Best with --format csv.",
                    &compute_trajectory, {}),
        add_command(app,
                    "Exact white-noise references (no simulation): mobility M0, diffusivity D and stationary variance "
                    "by quadrature of Hayakawa's density for any b(v); with --times, the first moment E[V(t)|v0] and "
                    "the stationary autocorrelation <V(t)V(0)> (closed forms of Touchette et al. 2010 for pure dry "
                    "friction, a Fokker-Planck solution otherwise). Physical units; tau is not used.",
                    &compute_white_noise, {}),
        add_command(app,
                    "Two-sided velocity power spectrum S(w) = int C(t) exp(-i w t) dt over all t (C the stationary "
                    "autocovariance of V; S(0) = D) at angular frequencies --frequencies. Default, without sampling: "
                    "the kolmogorov engine's complex resolvent solves on its grids, extrapolated like D, each value "
                    "with its estimated error; white noise in closed form without drag, on the velocity's Fokker-Planck "
                    "chain with drag. --engine inclusion or pdmp: "
                    "sampled over long excursions (each cycle's transform and the geometric sum of the cross-cycle "
                    "terms; delta-method intervals).",
                    &compute_spectrum, {"excursions", false}),
        add_command(app,
                    "D, M0 and E[t1] over a grid of noise and tau values (the paper's Figs. 4 and 9), with the local "
                    "log-log slope d log D / d log noise and its error, and per tau the fitted exponent of D ~ "
                    "noise^alpha. --noise and --tau take lists. Each point has its own random streams (independent "
                    "errors).",
                    &compute_sweep, {}, &sweep_progress),
    };
}

} // namespace stickslip::cli
