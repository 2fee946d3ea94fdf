// SPDX-License-Identifier: BSD-3-Clause
// stickslip/run.hpp -- what every run shares: the model, the engine, the run
// control and the confidence level (RunSettings), the number of excursions
// (ExcursionSettings), and how a run's engine is resolved and prepared (the
// prepared constants themselves are in prepared_engine.hpp, so that the
// requests include no kernel).
//
// Every request of the library (diffusivity.hpp, bruteforce.hpp,
// observables.hpp, sweep.hpp) is a RunSettings, and the long-excursion ones an
// ExcursionSettings too, plus the fields of its own; each setting is declared
// once, with its default, in one of these structs, and described once, in the
// visit_settings() beside it (setting.hpp).
#pragma once

#include <atomic>

/// \file
/// The settings every run shares and the engine prepared for a run. The comment
/// at the top of this header explains the design.

#include <concepts>
#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/engine.hpp"
#include "stickslip/model.hpp"
#include "stickslip/params.hpp"
#include "stickslip/run_control.hpp"
#include "stickslip/setting.hpp"

namespace stickslip {

struct PreparedEngine; // prepared_engine.hpp: the engine constants a run is prepared with

/// The settings of every run: model, engine, run control and interval level.
/// Of the run control, seed and threads are settings; the progress callback,
/// the cancel flag and the process split are set by the caller.
struct RunSettings {
    /// The physical model (SI units); a sweep replaces its noise and tau.
    ModelParams params;
    /// The engine and its numerical settings.
    EngineSettings engine;
    /// Seed and threads (settings), and the caller's callbacks, flags and
    /// process split (run_control.hpp).
    RunControl control;
    double level = 0.95; ///< confidence level of the intervals, in (0, 1)
    /// What asked for the run, as the reports' provenance gives it: the
    /// command line after the program's name (`stickslip diffusivity
    /// --excursions 2000`), or the Python call; empty for a library call (the
    /// reports then write null). Not a setting: it changes no result.
    std::string command_line;
};

/// The shared settings, as the command line, config files and Python name
/// them: the model's, the engine's, then seed, threads and level.
template <class Visitor>
void visit_settings(RunSettings& r, Visitor&& v) {
    visit_settings(r.params, v);
    visit_settings(r.engine, v);
    v(SeedValue{r.control.seed}, SettingInfo{"seed", "", "random seed (64-bit); same seed, same result"});
    v(r.control.threads, SettingInfo{"threads", "",
                                     "worker threads; 0 = the CPUs this process may use (affinity, CPU quota, "
                                     "MPI ranks per node)"});
    v(r.level, SettingInfo{"level", "", "confidence level of the intervals, in (0, 1)"});
}

/// The settings of runs over long excursions.
struct ExcursionSettings {
    std::uint64_t excursions = 10000; ///< number of long excursions, >= 2 (a sweep: per point)
    bool allow_capped = false;        ///< if false, capped excursions make the result an error
};

/// The long-excursion settings as settings: --excursions and --allow-capped.
template <class Visitor>
void visit_settings(ExcursionSettings& e, Visitor&& v) {
    v(e.excursions, SettingInfo{"excursions", "", "number N of long excursions (>= 2; a sweep: per point)"});
    v(e.allow_capped, SettingInfo{"allow-capped", "",
                                  "report a result even if some excursions hit --max-steps (they are dropped; biased)"});
}

/// The step [s] that --dt auto chooses for the inclusion engine's `scheme` on
/// model p: the largest step at which the project's measurements show the
/// scheme's bias of D below 0.1% (docs/validation.md, "Choosing the step").
///  * Resolvent: from the measured bias law in friction times T_f =
///    noise/friction^2: (0.001/0.39)^2 T_f = 6.6e-6 T_f for white and
///    near-white noise (tau < 0.3 T_f), 0.001/0.35 T_f = 2.9e-3 T_f for
///    coloured noise; and at most relaxation/100.
///  * Event: min(tau/16, relaxation/8, T_f/16) for coloured noise,
///    min(relaxation/16, T_f/16) for white noise, each a few times below the
///    largest steps at which no bias was seen at 0.3% resolution
///    (relaxation/8, measured more closely: D within 0.1% on the Fig. 2 case).
/// Throws InvalidParameter for an invalid model.
double auto_time_step(const ModelParams& p, Scheme scheme);
/// auto_time_step on a model made once (model.hpp).
double auto_time_step(const Model& m, Scheme scheme);

/// What a quantity needs of the inclusion engine's paths, for Scheme::Auto.
///  * Events: the long excursions' sums, moments at fixed times, a path with
///    its event times (diffusivity, bruteforce, moments, trajectory, sweep).
///  * GridSamples: stationary averages over paths sampled on a time grid
///    (density, correlation).
enum class PathUse { Events, GridSamples };

/// The scheme Scheme::Auto stands for on model p: the event scheme, except
///  * white noise with PathUse::GridSamples, which it cannot sample (between
///    its events V is a Brownian bridge, which interpolation would flatten);
///  * near-white coloured noise, where the resolvent's automatic step is the
///    longer (the event step resolves tau: tau/16 against 6.6e-6 friction
///    times, so below tau' = 1e-4),
/// where it is the resolvent scheme. Throws InvalidParameter for an invalid
/// model (coloured noise).
Scheme auto_scheme(const ModelParams& p, PathUse use);
/// auto_scheme on a model made once (model.hpp).
Scheme auto_scheme(const Model& m, PathUse use);

/// s with Scheme::Auto replaced by auto_scheme(p, use) for the inclusion
/// engine (a PDMP run keeps it: it has no scheme), then dt =
/// auto_time_step(p, s.scheme) when s.dt_auto and the engine is the inclusion
/// engine (dt_auto stays true, so that reports say so); the rest unchanged.
/// Every run resolves its settings so, first; resolving again changes nothing.
EngineSettings resolve_engine_settings(const ModelParams& p, EngineSettings s, PathUse use = PathUse::Events);
/// resolve_engine_settings on a model made once (model.hpp).
EngineSettings resolve_engine_settings(const Model& m, EngineSettings s, PathUse use = PathUse::Events);

/// A request of the library: its settings are a RunSettings plus its own.
template <class R>
concept Request = std::derived_from<R, RunSettings>;

/// A request (any RunSettings) with its engine settings resolved so.
template <Request R>
R with_resolved_engine(R r, PathUse use = PathUse::Events) {
    r.engine = resolve_engine_settings(r.params, r.engine, use);
    return r;
}

/// Validates the model and the engine settings together (InvalidParameter on
/// the first problem) and builds the engine's constants (resolving the scheme
/// and --dt auto first, for PathUse::Events: `settings` holds what was used).
/// A set `stop` (RunControl::stop) ends a long construction (a knots law's
/// pieces) with RunInterrupted.
PreparedEngine prepare_engine(const ModelParams& p, const EngineSettings& s,
                              const std::atomic<bool>* stop = nullptr);

/// The resolved details alone: prepare_engine(p, s).resolved.
ResolvedEngine resolve_engine(const ModelParams& p, const EngineSettings& s);

/// Checks the settings every run shares (the model with the engine, the level,
/// the thread count, and that the step resolves the dynamics: a step whose
/// predicted bias of D exceeds 20% is refused, one beyond 2% noted;
/// InvalidParameter on the first problem) and prepares the engine: the one
/// validation of a run's shared settings.
PreparedEngine prepare(const RunSettings& r);
/// prepare(r), for its checks alone.
void validate(const RunSettings& r);
/// Checks the number of excursions (>= 2).
void validate(const ExcursionSettings& e);

} // namespace stickslip
