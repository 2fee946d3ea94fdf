// SPDX-License-Identifier: BSD-3-Clause
// stickslip/engine.hpp -- the numerical settings of the two engines.
//
// Two engines sample long excursions (theory.md, sections 4 to 6): `pdmp`, an
// exact event-driven simulation in which the noise is a jump process on a
// lattice of step `grid`, and `inclusion`, a time-stepping scheme of step `dt`
// for the differential inclusion, with the noise's exact step law. The
// per-run constants each engine derives from these settings are in pdmp.hpp
// and resolvent.hpp.
#pragma once

/// \file
/// The engines (exact PDMP, time-stepping inclusion) and their numerical
/// settings. The comment at the top of this header explains the design.

#include <cstdint>
#include <string>

#include "stickslip/setting.hpp"

namespace stickslip {

/// Which engine samples the long excursions (theory.md, sections 4 and 5).
///  * Inclusion: time stepping of the differential inclusion with step
///    EngineSettings::dt and the noise's exact step law; white or coloured
///    noise. Its error is the time step's (see Scheme).
///  * Pdmp: exact event-driven simulation of a piecewise-deterministic Markov
///    process whose noise is a jump process on a lattice of step
///    EngineSettings::grid; coloured noise only (tau > 0). Its only
///    approximation is the lattice, which converges to the OU noise as grid -> 0.
///  * Kolmogorov: no sampling: the Kolmogorov equations of (X, V) solved on a
///    grid (kolmogorov.hpp) for D, M0, P(V = 0) and the stationary density,
///    each with an estimated discretisation error; coloured noise of every
///    tau' > 0 (two discretisations, kolmogorov.hpp). Not an engine that runs excursions: the
///    quantities that can be solved choose it at their top (diffusivity,
///    density), every other one refuses it (prepare_engine).
enum class Engine { Inclusion, Pdmp, Kolmogorov };

/// How a time-stepping HLE detects its end (theory.md, section 6).
///  * Bridge ("rule Q"): stuck at the start of the step and the noise path
///    reaches the opposite threshold during it (endpoint beyond it, or a
///    Brownian-bridge crossing). Flat in dt; the right rule when dt << tau.
///  * Stuck ("rule P"): the object was genuinely stuck during the previous step
///    and the step's force leaves the band the other way. Converges like
///    sqrt(dt/tau); used when dt is not small against tau.
///  * Auto: Bridge when dt <= auto_bridge_ratio * tau, else Stuck.
/// The paper's literal test ("rule A") is biased and deliberately absent.
enum class StopRule { Auto, Bridge, Stuck };

/// How the inclusion engine steps (theory.md, section 10).
///  * Resolvent: the paper's Algorithm 3, corrected: the exact OU pair, an
///    explicit drift and the resolvent of the friction, events on the grid of
///    steps; first order.
///  * Event: exact Gaussian steps within a phase, events (landings, exits,
///    the end of a half) located by refinement and placed at their times
///    (event_scheme.hpp).
///  * Auto (the default): the event scheme, except where it cannot serve the
///    quantity (white-noise paths sampled on a grid) or its step would be the
///    shorter (near-white noise): the resolvent scheme there (auto_scheme,
///    run.hpp). Every run resolves it first, so a prepared
///    engine and a result's request hold Resolvent or Event.
enum class Scheme { Resolvent, Event, Auto };

/// dt/tau at or below which StopRule::Auto selects the bridge rule.
inline constexpr double auto_bridge_ratio = 0.1;

/// The setting's name of an engine: "inclusion" | "pdmp" | "kolmogorov".
std::string to_string(Engine e);
/// The setting's name of a stop rule: "auto" | "bridge" | "stuck".
std::string to_string(StopRule r);
/// The setting's name of a scheme: "resolvent" | "event" | "auto".
std::string to_string(Scheme s);
Engine parse_engine(const std::string& s);     ///< "inclusion" | "pdmp" | "kolmogorov"
Scheme parse_scheme(const std::string& s);     ///< "resolvent" | "event" | "auto"
StopRule parse_stop_rule(const std::string& s); ///< "auto" | "bridge" | "stuck"

/// Numerical settings of the engines, SI units.
struct EngineSettings {
    /// Which engine runs (--engine); the inclusion engine by default.
    Engine engine = Engine::Inclusion;
    Scheme scheme = Scheme::Auto; ///< how the inclusion engine steps
    /// Time step h of the inclusion engine [s]; used only when dt_auto is
    /// false (a run with dt_auto true overwrites it with the step it chose).
    double dt = 1e-4;
    /// --dt auto, the default: the step is chosen from the model's time scales
    /// for the scheme (auto_time_step, run.hpp), and `dt` holds it once a run
    /// has resolved it (resolve_engine_settings). Set it false to use `dt`.
    bool dt_auto = true;
    double grid = 0.125;     ///< lattice step delta of the PDMP noise [s^-1/2]
    /// Half-width L of the PDMP lattice [s^-1/2]; 0 chooses it (see pdmp.hpp).
    double lattice_bound = 0.0;
    /// How the inclusion engine's resolvent scheme detects the end of a half
    /// long excursion (coloured noise only; the event scheme and the PDMP
    /// engine detect it exactly).
    StopRule stop_rule = StopRule::Auto;
    /// White noise only: the regeneration velocity levels +-c [m/s]; 0 chooses
    /// c = white_level_default(params).
    double white_level = 0.0;
    /// Runaway guard: most steps (inclusion) or events (PDMP) in one long
    /// excursion. An excursion that reaches it is dropped and counted as capped.
    std::uint64_t max_work_per_excursion = 200'000'000;
};

/// The engine settings, as the command line, config files and Python name them.
template <class Visitor>
void visit_settings(EngineSettings& s, Visitor&& v) {
    v(s.engine, SettingInfo{"engine", "",
                            "inclusion (time stepping with the exact Ornstein-Uhlenbeck noise step), pdmp (exact "
                            "event-driven, the noise a jump process on a lattice) or kolmogorov (no sampling: the "
                            "Kolmogorov equations solved on a grid: diffusivity, density, sweep and spectrum, coloured noise)"});
    v(s.scheme, SettingInfo{"scheme", "",
                            "inclusion time stepping: event (exact within phases, events at their times), resolvent "
                            "(the paper's, first order) or auto: event, except resolvent for white-noise density and "
                            "correlation, which event cannot sample, and for near-white noise (tau below 1e-4 "
                            "noise/friction^2), where its step is the longer"});
    v(NumberOrAuto{s.dt, s.dt_auto},
      SettingInfo{"dt", "s",
                  "time step of the inclusion engine, > 0; auto: from the model's time scales, the largest step at "
                  "which the scheme's measured bias of D is below 0.1% (docs/guide.md, \"Choosing the step\")"});
    v(s.grid, SettingInfo{"grid", "s^-1/2", "lattice step delta of the pdmp noise, > 0"});
    v(s.lattice_bound, SettingInfo{"lattice-bound", "s^-1/2",
                                   "pdmp lattice half-width L; 0 = 8 tau^-1/2 (or what tau*grid*L < 2 allows)"});
    v(s.stop_rule, SettingInfo{"stop-rule", "",
                               "resolvent scheme, how it detects the end of a half long excursion (stuck, the "
                               "noise crosses the static band): auto (bridge if dt <= tau/10, else stuck), bridge (the noise's Brownian "
                               "bridge within a step; the paper's rule Q), stuck (a stuck step, then a step leaving "
                               "the band; rule P)"});
    v(s.white_level, SettingInfo{"white-level", "m/s", "white noise only: regeneration velocity levels +-c; 0 chooses c"});
    v(s.max_work_per_excursion, SettingInfo{"max-steps", "",
                                            "runaway guard: most steps (inclusion) or events (pdmp) per long excursion"});
}

/// The inclusion engine with `scheme` at the fixed step dt [s] (dt_auto
/// false), every other setting at its default: what a C++ caller who wants a
/// given step sets (the defaults choose both the scheme and the step).
EngineSettings fixed_step_settings(Scheme scheme, double dt);

/// @name What the engine settings imply, for reports and checks
/// The one place outside the engines' own code that knows which engine has
/// which kind of numerics (ARCHITECTURE.md, "Add an engine").
/// @{

/// What the work of a run counts: "steps" (inclusion engine) or "events" (PDMP).
const char* work_unit(const EngineSettings& s);
/// Whether the engine samples (inclusion, PDMP); false for the Kolmogorov
/// grid solver, which no Monte Carlo path may reach.
bool samples(const EngineSettings& s);
/// What the Kolmogorov engine computes, for the refusals of the commands it
/// cannot serve: "the kolmogorov engine solves D, M0 and P(V = 0) (...)".
extern const char* const kolmogorov_engine_scope;
/// Whether the engine advances by a time step dt (the inclusion engine, both
/// schemes); otherwise its resolution is the lattice step `grid` (PDMP).
bool has_time_step(const EngineSettings& s);
/// Whether the engine knows its paths at its own steps only, so that they are
/// sampled there and --sample-dt does not apply (the resolvent scheme).
bool samples_at_steps(const EngineSettings& s);
/// Whether the engine can sample paths of the model with noise correlation
/// time tau [s] on a time grid: all but the event scheme with white noise
/// (tau = 0), whose V between events is a Brownian bridge that interpolation
/// would flatten.
bool samples_on_grid(const EngineSettings& s, double tau);
/// Advice for a run whose step bias shows: " or --scheme event" where a
/// coloured-noise run uses the first-order resolvent scheme, else "".
std::string more_accurate_scheme_advice(const EngineSettings& s, double tau);
/// @}

/// Throws InvalidParameter for a non-positive or non-finite dt or grid, a
/// negative lattice bound or white level, or a zero work cap. Both step
/// settings are checked whatever the engine.
void validate(const EngineSettings& s);

// Text forms of the enums (setting.hpp).

/// @name Text forms of the engine enums as settings
/// @{

/// As for the other setting types (setting.hpp): format_setting is
/// to_string; parse_setting accepts the same names (and "Q", "P" for the stop
/// rules) and throws InvalidParameter("engine" / "stop-rule" / "scheme") for
/// anything else; setting_form lists the choices ("inclusion|pdmp", ...).
std::string format_setting(Engine e);
std::string format_setting(StopRule r);
void parse_setting(const SettingInfo& info, const std::string& text, Engine& out);
void parse_setting(const SettingInfo& info, const std::string& text, StopRule& out);
std::string format_setting(Scheme s);
void parse_setting(const SettingInfo& info, const std::string& text, Scheme& out);
const char* setting_form(const Engine&);
const char* setting_form(const StopRule&);
const char* setting_form(const Scheme&);
/// @}

/// Engine details resolved for a run, reported alongside the estimates.
struct ResolvedEngine {
    /// How the run ends a half long excursion; "none" for runs that have no
    /// excursions (brute force, transient moments).
    std::string stop_rule;   ///< "bridge" | "stuck" | "velocity-levels" (white) | "exact" (PDMP, event scheme)
    double lattice_bound = 0; ///< PDMP: L [s^-1/2]
    /// PDMP: the lattice step delta [s^-1/2]: --grid, or with a static band the
    /// largest step <= --grid that fits a whole number of steps across the band.
    double lattice_step = 0;
    /// PDMP: x_0 [s^-1/2], the lattice being x_i = delta i + x_0 (0 without a
    /// static band; with one the shift that puts the static edges on lattice points).
    double lattice_offset = 0;
    int lattice_points = 0;   ///< PDMP: 2N+1
    double truncated_mass = 0;///< PDMP: stationary Gaussian mass of X beyond +-L
    double jump_rate = 0;     ///< PDMP: Lambda [s^-1]
    double white_level = 0;   ///< white noise: regeneration level c [m/s]
    /// @{
    /// Coloured noise: the noise thresholds x* (upper) and x-* (lower)
    /// [s^-1/2] between which a stuck object stays stuck
    /// (ModelParams::upper_threshold, lower_threshold); 0 for white noise.
    double upper_threshold = 0, lower_threshold = 0; ///< x*, x-* [s^-1/2] (colored)
    /// @}
};

/// Steps of the inclusion engine in a brute-force trajectory of length
/// horizon [s] (time rounded to whole steps of dt); InvalidParameter ("time")
/// outside 1 .. 1e13 steps.
std::uint64_t bruteforce_steps(double horizon, double dt);

} // namespace stickslip
