// SPDX-License-Identifier: BSD-3-Clause
// Engine settings: names of the engines and stop rules, and their checks.
#include "stickslip/engine.hpp"

#include <cmath>

#include "core/format.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/params.hpp"
#include "stickslip/random/rng.hpp"

namespace stickslip {

std::string to_string(Engine e) {
    switch (e) {
    case Engine::Pdmp: return "pdmp";
    case Engine::Kolmogorov: return "kolmogorov";
    case Engine::Inclusion: break;
    }
    return "inclusion";
}

std::string to_string(StopRule r) {
    switch (r) {
    case StopRule::Bridge: return "bridge";
    case StopRule::Stuck: return "stuck";
    default: return "auto";
    }
}

std::string to_string(Scheme s) {
    switch (s) {
    case Scheme::Resolvent: return "resolvent";
    case Scheme::Event: return "event";
    default: return "auto";
    }
}

Scheme parse_scheme(const std::string& s) {
    if (s == "resolvent") return Scheme::Resolvent;
    if (s == "event") return Scheme::Event;
    if (s == "auto") return Scheme::Auto;
    throw InvalidParameter("scheme", "scheme must be 'event', 'resolvent' or 'auto', got '" + s + "'");
}

Engine parse_engine(const std::string& s) {
    if (s == "inclusion") return Engine::Inclusion;
    if (s == "pdmp") return Engine::Pdmp;
    if (s == "kolmogorov") return Engine::Kolmogorov;
    throw InvalidParameter("engine", "engine must be 'inclusion', 'pdmp' or 'kolmogorov', got '" + s + "'");
}

StopRule parse_stop_rule(const std::string& s) {
    if (s == "auto") return StopRule::Auto;
    if (s == "bridge" || s == "Q") return StopRule::Bridge;
    if (s == "stuck" || s == "P") return StopRule::Stuck;
    throw InvalidParameter("stop-rule", "stop-rule must be 'auto', 'bridge' (rule Q) or 'stuck' (rule P), got '" +
                                            s + "'");
}

EngineSettings fixed_step_settings(Scheme scheme, double dt) {
    EngineSettings s;
    s.scheme = scheme;
    s.dt = dt;
    s.dt_auto = false;
    return s;
}

void validate(const EngineSettings& s) {
    // Both step settings are checked whatever the engine, so a typo in the
    // unused one is reported rather than silently ignored.
    if (!std::isfinite(s.dt) || s.dt <= 0)
        throw InvalidParameter("dt", "dt must be a finite number > 0 (s), got " + detail::format_number(s.dt));
    if (!std::isfinite(s.grid) || s.grid <= 0)
        throw InvalidParameter("grid", "grid must be a finite number > 0 (s^-1/2), got " + detail::format_number(s.grid));
    if (!std::isfinite(s.lattice_bound) || s.lattice_bound < 0)
        throw InvalidParameter("lattice-bound", "lattice-bound must be >= 0 (s^-1/2; 0 chooses it)");
    if (!std::isfinite(s.white_level) || s.white_level < 0)
        throw InvalidParameter("white-level", "white-level must be a finite number >= 0 (m/s; 0 chooses it)");
    if (s.max_work_per_excursion == 0) throw InvalidParameter("max-steps", "max-steps must be >= 1");
    // One random block per step or event; a stream holds max_draws blocks.
    if (s.max_work_per_excursion > max_draws / 8)
        throw InvalidParameter("max-steps", "max-steps must be at most 2^44 (about 1.8e13)");
}

std::string format_setting(Engine e) { return to_string(e); }
std::string format_setting(StopRule r) { return to_string(r); }
void parse_setting(const SettingInfo&, const std::string& text, Engine& out) { out = parse_engine(text); }
void parse_setting(const SettingInfo&, const std::string& text, StopRule& out) { out = parse_stop_rule(text); }
std::string format_setting(Scheme s) { return to_string(s); }
void parse_setting(const SettingInfo&, const std::string& text, Scheme& out) { out = parse_scheme(text); }
const char* setting_form(const Engine&) { return "inclusion|pdmp|kolmogorov"; }
const char* setting_form(const Scheme&) { return "auto|event|resolvent"; }
const char* setting_form(const StopRule&) { return "auto|bridge|stuck"; }

const char* work_unit(const EngineSettings& s) { return s.engine == Engine::Pdmp ? "events" : "steps"; }

bool has_time_step(const EngineSettings& s) { return s.engine == Engine::Inclusion; }

bool samples(const EngineSettings& s) { return s.engine != Engine::Kolmogorov; }

const char* const kolmogorov_engine_scope =
    "the kolmogorov engine solves D, M0 and P(V = 0) (`stickslip diffusivity`), the stationary density "
    "(`stickslip density`) and the velocity spectrum (`stickslip spectrum`) on a grid, without sampling";

bool samples_at_steps(const EngineSettings& s) {
    return s.engine == Engine::Inclusion && s.scheme == Scheme::Resolvent;
}

std::string more_accurate_scheme_advice(const EngineSettings& s, double tau) {
    return tau == 0 || s.scheme == Scheme::Event ? "" : " or --scheme event";
}

bool samples_on_grid(const EngineSettings& s, double tau) {
    return !(s.engine == Engine::Inclusion && s.scheme == Scheme::Event && tau == 0);
}

std::uint64_t bruteforce_steps(double horizon, double dt) {
    if (!(horizon / dt >= 1)) throw InvalidParameter("time", "time must be at least one step dt");
    const double nsteps = std::nearbyint(horizon / dt);
    if (nsteps > 1e13) // a stream holds 2^47 random blocks
        throw InvalidParameter("time", "time/dt must be between 1 and 1e13 steps");
    return static_cast<std::uint64_t>(nsteps);
}

} // namespace stickslip
