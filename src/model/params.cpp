// SPDX-License-Identifier: BSD-3-Clause
#include "core/format.hpp"
#include "stickslip/params.hpp"

#include "stickslip/drift_input.hpp"
#include "model/params_checks.hpp"

#include <cmath>
#include <limits>

namespace stickslip {

double ModelParams::force_amplitude() const { return std::sqrt(noise / 2.0); }

double ModelParams::inverse_relaxation() const { return std::isinf(relaxation) ? 0.0 : 1.0 / relaxation; }

double ModelParams::drift_at(double v) const {
    if (!has_drift_law()) return -v * inverse_relaxation() + bias;
    return make_drift_law(*this)(v);
}

double ModelParams::drift_at_zero() const { return has_drift_law() ? make_drift_law(*this)(0.0) : bias; }

double noise_threshold(const ModelParams& p, double b0, int side) {
    return (side * p.static_friction_level() - b0) / p.force_amplitude();
}

double ModelParams::upper_threshold() const { return noise_threshold(*this, drift_at_zero(), +1); }

double ModelParams::lower_threshold() const { return noise_threshold(*this, drift_at_zero(), -1); }

std::string white_noise_static_friction_note() {
    return "white noise: a static friction above the friction holds the object at rest for no positive time (the "
           "force's integral over a time r grows like sqrt(r), the static band's like r), so every white-noise "
           "quantity is that of the static friction equal to the friction (docs/theory.md, section 1)";
}

Scales scales_of(const ModelParams& p) {
    Scales s{};
    s.time = p.noise / (p.friction * p.friction);
    s.length = p.noise * p.noise / (p.friction * p.friction * p.friction);
    s.velocity = p.noise / p.friction;
    s.acceleration = p.friction;
    s.diffusivity = s.length * s.length / s.time;
    s.noise_level = 1.0 / std::sqrt(s.time);
    return s;
}

ModelParams to_nondimensional(const ModelParams& p) {
    const Scales s = scales_of(p);
    ModelParams nd;
    nd.friction = 1.0;
    nd.noise = 1.0;
    nd.tau = p.tau / s.time;
    nd.relaxation = std::isinf(p.relaxation) ? p.relaxation : p.relaxation / s.time;
    nd.bias = p.bias / p.friction;
    nd.static_friction = p.static_friction / p.friction; // NaN (unset) stays unset
    return nd;
}

ModelParams from_nondimensional(const ModelParams& nd, double friction, double noise) {
    ModelParams unit;
    unit.friction = friction;
    unit.noise = noise;
    const Scales s = scales_of(unit);
    ModelParams p;
    p.friction = friction;
    p.noise = noise;
    p.tau = nd.tau * s.time;
    p.relaxation = std::isinf(nd.relaxation) ? nd.relaxation : nd.relaxation * s.time;
    p.bias = nd.bias * friction;
    p.static_friction = nd.static_friction * friction;
    return p;
}

namespace detail {

void validate_numbers(const ModelParams& p) {
    if (!std::isfinite(p.friction) || p.friction <= 0)
        throw InvalidParameter("friction", "friction must be a finite number > 0 (m s^-2), got " + detail::format_number(p.friction));
    if (!std::isfinite(p.noise) || p.noise <= 0)
        throw InvalidParameter("noise", "noise must be a finite number > 0 (m^2 s^-3), got " + detail::format_number(p.noise));
    if (!std::isfinite(p.tau) || p.tau < 0)
        throw InvalidParameter("tau", "tau must be a finite number >= 0 (s; 0 is white noise), got " + detail::format_number(p.tau));
    if (std::isnan(p.relaxation) || p.relaxation <= 0)
        throw InvalidParameter("relaxation",
                               "relaxation must be > 0 (s) or inf (no viscous drag), got " + detail::format_number(p.relaxation));
    // A subnormal relaxation time makes 1/relaxation infinite and the
    // automatic step zero: refused here, by name, rather than blamed on --dt.
    if (p.relaxation < std::numeric_limits<double>::min())
        throw InvalidParameter("relaxation", "relaxation must be at least " +
                                                 format_setting(std::numeric_limits<double>::min()) +
                                                 " s (the smallest normal double) or inf, got " +
                                                 detail::format_number(p.relaxation));
    if (!std::isfinite(p.bias))
        throw InvalidParameter("bias", "bias must be a finite number (m s^-2), got " + detail::format_number(p.bias));
    // NaN is "unset" (the parsers refuse a NaN typed as the value).
    if (!std::isnan(p.static_friction) && !(std::isfinite(p.static_friction) && p.static_friction >= p.friction))
        throw InvalidParameter("static-friction",
                               "static-friction must be a finite number >= friction = " + detail::format_number(p.friction) +
                                   " m s^-2 (an object at rest is held at least as firmly as a sliding one is "
                                   "braked), got " + detail::format_number(p.static_friction));
    // Products that overflow would make every later formula meaningless.
    const Scales s = scales_of(p);
    if (!std::isfinite(s.diffusivity) || s.diffusivity <= 0 || !std::isfinite(s.time) || s.time <= 0) {
        // Name the parameter that is further from 1 (the one to rescale), and
        // say which unit of the nondimensional system leaves double's range.
        const bool friction_off = std::fabs(std::log10(p.friction)) >= std::fabs(std::log10(p.noise));
        const char* unit = !(std::isfinite(s.time) && s.time > 0) ? "the time unit noise/friction^2"
                                                                  : "the diffusivity unit noise^3/friction^4";
        throw InvalidParameter(friction_off ? "friction" : "noise",
                               "friction = " + detail::format_number(p.friction) + " m s^-2 and noise = " +
                                   detail::format_number(p.noise) + " m^2 s^-3 put " + unit +
                                   " outside double precision's range; rescale the units (SI multiples) so that "
                                   "both are nearer 1");
    }
    // Settings of a drift law with no law to take them: they would change
    // nothing, silently (issue 50).
    if (!p.drift_params.empty() && p.drift.empty())
        throw InvalidParameter("drift-params", "drift-params gives the constants of a --drift expression, and there is "
                                               "none" + std::string(p.has_drift_law() ? " (a table's law has no "
                                                                                         "constants)" : ""));
    if (p.knots != ModelParams{}.knots && !p.has_drift_law())
        throw InvalidParameter("knots", "knots sets the interpolant of a --drift or --drift-table law, and there is "
                                        "none: the affine law of --relaxation and --bias has no knots");
}

} // namespace detail

void validate(const ModelParams& p) {
    detail::validate_numbers(p);
    // A drift law is checked when it is given (parses, finite, confines).
    if (p.has_drift_law()) make_drift_law(p);
}

bool has_stationary_state(const ModelParams& p) {
    if (p.has_drift_law()) {
        try {
            make_drift_law(p);
        } catch (const InvalidParameter&) {
            return false;
        }
        return true;
    }
    return !std::isinf(p.relaxation) || std::fabs(p.bias) < p.friction;
}

void require_stationary_state(const ModelParams& p) {
    if (p.has_drift_law()) {
        make_drift_law(p); // throws, naming the law's setting and what is wrong
        return;
    }
    if (!has_stationary_state(p))
        throw InvalidParameter("bias", "with relaxation inf the bias must satisfy |bias| < friction (otherwise the "
                                       "object accelerates forever and D is undefined); got bias " +
                                           detail::format_number(p.bias) + ", friction " + detail::format_number(p.friction));
}

} // namespace stickslip
