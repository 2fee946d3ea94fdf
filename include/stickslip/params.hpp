// SPDX-License-Identifier: BSD-3-Clause
// stickslip/params.hpp -- the physical model's parameters, their validation and
// the nondimensional system of theory.md, section 3.
//
// Model (theory.md, section 1): dV/dt + dphi(V) contains b(V) + force(t), with
// phi(v) = friction*|v| and b(v) = -v/relaxation + bias. A static friction
// above the kinetic one (theory.md, section 1) widens the band of forces that
// hold an object at rest: it starts only when |b(0) + force| exceeds
// static_friction, then slides against friction. Unset, it is the friction
// itself, and every number is that of the one-coefficient model. The random force is
// sqrt(noise/2)*X(t), X the paper's Ornstein-Uhlenbeck process with
// E[X(0)X(t)] = exp(-|t|/tau)/tau, so that as tau -> 0 the force tends to a white
// noise of intensity `noise` (theory.md, section 2). tau = 0 is white noise.
//
// Everything is in SI units (m, s). The nondimensional system takes
// friction = noise = 1: time unit noise/friction^2, length unit noise^2/friction^3.
#pragma once

/// \file
/// The physical model's parameters (SI units), their validation and the
/// nondimensional system. The comment at the top of this header explains the
/// design.

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "stickslip/result_fields.hpp"
#include "stickslip/setting.hpp"

namespace stickslip {

/// Physical parameters of the model, SI units. Defaults: the paper's Fig. 2 case.
struct ModelParams {
    double friction = 3.84;    ///< Delta, dry-friction coefficient [m s^-2], > 0
    double noise = 5.0;        ///< Gamma, white-noise intensity [m^2 s^-3], > 0
    double tau = 0.5;          ///< noise correlation time [s], >= 0 (0: white noise)
    double relaxation = 0.067; ///< tauL, viscous relaxation time [s], > 0 or +inf
    double bias = 0.342;       ///< gbar, constant force [m s^-2], any finite sign
    /// Delta_s, static friction [m s^-2], >= friction; NaN (unset): equal to
    /// friction. Read it through static_friction_level().
    double static_friction = std::numeric_limits<double>::quiet_NaN();

    /// @name A drift law other than the affine one (drift_input.hpp)
    /// When one is given, relaxation and bias are not used: the law is b(v).
    /// @{
    std::string drift{};       ///< b(v) as an expression in v (SI: v in m/s, b in m s^-2); "" = affine
    std::string drift_params{}; ///< values of the expression's named constants: "a=0.8,c=0.5"
    std::string drift_table{}; ///< path of a file of "v,b" rows; "" = none
    std::vector<double> drift_table_v{}; ///< table rows given directly (Python arrays) [m/s]
    std::vector<double> drift_table_b{}; ///< their b [m s^-2]
    /// The --drift-table file's contents as read (read_drift_inputs, once per
    /// command): its digest, for the reports' provenance and the checkpoint's
    /// identity; "" while the file is unread or there is none.
    std::string drift_table_digest{};
    std::function<double(double)> drift_function{}; ///< b(v) as a callable (Python); empty = none
    int knots = 1025;          ///< knots of the interpolant of a non-affine law (odd, 3..2049)
    /// @}

    /// The static friction Delta_s [m s^-2] that holds a stuck object:
    /// static_friction, or friction when it is unset.
    double static_friction_level() const { return static_friction == static_friction ? static_friction : friction; }
    /// True when the static friction exceeds the kinetic one (a static band
    /// wider than the sliding threshold; theory.md, section 1).
    bool has_static_band() const { return static_friction_level() > friction; }

    /// True when a law other than the affine one is given (drift, drift_table,
    /// drift_table_v or drift_function).
    bool has_drift_law() const {
        return !drift.empty() || !drift_table.empty() || !drift_table_v.empty() || static_cast<bool>(drift_function);
    }

    /// Amplitude a of the random force a*X [m s^-2 per s^-1/2]: sqrt(noise/2).
    double force_amplitude() const;
    /// 1/relaxation [s^-1]; 0 when relaxation is infinite (no viscous drag).
    double inverse_relaxation() const;
    /// True for white noise (tau == 0), where the force has no memory and the
    /// velocity alone is Markov: the PDMP engine and the event scheme refuse it.
    bool white() const { return tau == 0.0; }
    /// b(v) [m s^-2], v in m/s: -v/relaxation + bias, or the given law's
    /// interpolant (made anew at each call: for checks, not for loops).
    double drift_at(double v) const;
    /// b(0) [m s^-2]: bias for the affine law; sets the noise thresholds.
    double drift_at_zero() const;
    /// Upper noise threshold x* = (Delta_s - b(0))/a, in the paper's X units
    /// [s^-1/2] (Delta_s the static friction, the friction unless set): while
    /// stuck, the object starts moving up when X exceeds it.
    double upper_threshold() const;
    /// Lower noise threshold x-* = (-Delta_s - b(0))/a [s^-1/2].
    double lower_threshold() const;
};

/// The noise thresholds [s^-1/2] of p when its drift at rest is b0 [m s^-2]:
/// (Delta_s - b0)/a (upper, side +1) or (-Delta_s - b0)/a (lower, side -1),
/// a = sqrt(noise/2), Delta_s = p.static_friction_level(): the edges of the
/// static band, where a stuck object starts and a landing one sticks. The one formula behind ModelParams' and Model's
/// thresholds, which differ only in where b0 comes from.
double noise_threshold(const ModelParams& p, double b0, int side);

/// The model parameters, as the command line, config files and Python name them.
template <class Visitor>
void visit_settings(ModelParams& p, Visitor&& v) {
    v(p.friction, SettingInfo{"friction", "m s^-2", "dry (Coulomb) friction force per unit mass, > 0 (the paper's Delta)"});
    v(p.noise, SettingInfo{"noise", "m^2 s^-3", "noise intensity Gamma, > 0"});
    v(p.tau, SettingInfo{"tau", "s", "noise correlation time, >= 0 (0 = white noise)"});
    v(p.relaxation, SettingInfo{"relaxation", "s", "viscous relaxation time: drag -v/relaxation, > 0, or inf for none (the paper's tauL)", "NUM|inf"});
    v(p.bias, SettingInfo{"bias", "m s^-2", "constant force per unit mass, e.g. gravity on an incline (the paper's gbar)"});
    v(OptionalNumber{p.static_friction},
      SettingInfo{"static-friction", "m s^-2",
                  "static friction Delta_s >= friction: a stuck object starts only when the force exceeds it, then "
                  "slides against friction; default: equal to friction"});
    v(TextValue{p.drift}, SettingInfo{"drift", "m s^-2", "drift law b(v) as an expression in v [m/s], replacing relaxation and bias: e.g. \"0.8*v - 0.5*v^3\", \"0.4*tanh(v/0.1) - v/2\"", "EXPR"});
    v(TextValue{p.drift_params}, SettingInfo{"drift-params", "", "values of named constants of --drift: \"a=0.8,c=0.5\"", "NAME=NUM,..."});
    v(TextValue{p.drift_table}, SettingInfo{"drift-table", "", "drift law b(v) from a file of v,b rows (m/s, m s^-2), linear between them, replacing relaxation and bias", "FILE"});
    v(p.knots, SettingInfo{"knots", "", "knots of the drift law's interpolant on its velocity range, odd, 3..2049 (--drift, --drift-table)"});
}

/// Units of the nondimensional system (theory.md, section 3), in SI.
struct Scales {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    double time;
    double length;
    double velocity;
    double acceleration;
    double diffusivity;
    double noise_level;
    /// @}

    /// The fields (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = Scales;
        visit(&S::time, FieldInfo{"time", "s", "tau0 = noise/friction^2"});
        visit(&S::length, FieldInfo{"length", "m", "u0 = noise^2/friction^3"});
        visit(&S::velocity, FieldInfo{"velocity", "m/s", "u0/tau0 = noise/friction"});
        visit(&S::acceleration, FieldInfo{"acceleration", "m s^-2", "friction"});
        visit(&S::diffusivity, FieldInfo{"diffusivity", "m^2/s", "u0^2/tau0 = noise^3/friction^4"});
        visit(&S::noise_level,
              FieldInfo{"noise_level", "s^-1/2", "unit of X: tau0^-1/2 (X' = X sqrt(tau0))"});
    }
};

/// The units of p's nondimensional system (friction = noise = 1), in SI.
Scales scales_of(const ModelParams& p);

/// The same system in nondimensional form: friction = noise = 1, tau/tau0,
/// relaxation/tau0, bias/friction.
ModelParams to_nondimensional(const ModelParams& p);

/// Inverse of to_nondimensional for a chosen friction and noise (SI).
ModelParams from_nondimensional(const ModelParams& nd, double friction, double noise);

/// The note of a white-noise run with a static friction above the friction:
/// a white force holds the object at rest for no positive time, so the static
/// band changes nothing there (theory.md, section 1). Said once, for the
/// references and the sampled runs.
std::string white_noise_static_friction_note();

/// Throws InvalidParameter with one clear message for the first problem found:
/// non-positive friction or noise, negative or non-finite tau, non-positive
/// relaxation, non-finite bias.
void validate(const ModelParams& p);

/// True when the stationary state exists: with no viscous drag the constant
/// force must be weaker than friction (|bias| < friction).
bool has_stationary_state(const ModelParams& p);

/// Throws InvalidParameter ("bias") when there is no stationary state.
void require_stationary_state(const ModelParams& p);

} // namespace stickslip
