// SPDX-License-Identifier: BSD-3-Clause
// Construction and validation of the inclusion engine's per-run constants.
#include "stickslip/kernels/resolvent.hpp"

#include <cmath>

#include "core/format.hpp"
#include "stickslip/model.hpp"

namespace stickslip {

double white_level_default(const ModelParams& p) { return white_level_default(make_model(p)); }

double white_level_default(const Model& m) {
    const ModelParams& p = m.params;
    double scale = 0.7 * p.noise / p.friction;
    const double relaxation = m.drift_time_scale(); // 1/L for a general law
    if (!std::isinf(relaxation)) scale = std::fmin(scale, std::sqrt(p.noise * relaxation / 2.0));
    return 0.5 * scale;
}

ResolventConstants make_resolvent_constants(const ModelParams& p, const EngineSettings& s) {
    return make_resolvent_constants(make_model(p), s);
}

ResolventConstants make_resolvent_constants(const Model& m, const EngineSettings& s) {
    const ModelParams& p = m.params;
    validate(s);
    require_stationary_state(m);
    ResolventConstants c{};
    c.h = s.dt;
    c.keep = 1.0 - s.dt * p.inverse_relaxation();
    if (c.keep < 0)
        throw InvalidParameter("dt", "dt must be smaller than relaxation (dt = " + detail::format_number(s.dt) +
                                         " s, relaxation = " + detail::format_number(p.relaxation) +
                                         " s): the explicit drift step would overshoot");
    c.h_bias = s.dt * p.bias;
    c.knots_law = p.has_drift_law();
    if (c.knots_law) {
        c.drift = *m.law;
        c.keep = 1.0;
        c.h_bias = 0.0;
        const double lip = lipschitz_constant(c.drift);
        // The explicit drift step of a law with slope -L overshoots when h L > 1.
        if (!(s.dt * lip < 1.0))
            throw InvalidParameter("dt", "dt = " + detail::format_number(s.dt) + " s times the drift law's largest slope " +
                                             detail::format_number(lip) + " s^-1 is " +
                                             detail::format_number(s.dt * lip) +
                                             ": the explicit drift step needs dt * L < 1; use dt <= " +
                                             detail::format_number(0.5 / lip) + " s");
    }
    c.h_friction = s.dt * p.friction;
    c.h_static = s.dt * p.static_friction_level(); // == h_friction, bit for bit, when unset or equal
    c.static_band = p.has_static_band();
    c.h_rest = s.dt * m.drift_at_zero();
    c.white = p.white();
    c.max_steps = s.max_work_per_excursion;
    if (c.white) {
        c.h_amp = std::sqrt(p.noise * s.dt);
        c.level = s.white_level > 0 ? s.white_level : white_level_default(m);
        c.rule = StopRule::Stuck; // unused for white noise
    } else {
        c.h_amp = s.dt * p.force_amplitude();
        c.ou = ou_step(p.tau, s.dt);
        c.f_x = c.h_amp * c.ou.mean_coef;
        c.f_z = c.h_amp * c.ou.l11;
        if (!(std::isfinite(c.ou.l11) && std::isfinite(c.ou.l21) && std::isfinite(c.ou.l22) &&
              std::isfinite(c.ou.mean_coef)))
        {
            // With the automatic step the step follows tau: tau itself is the
            // setting to change (--tau 5e-324 was blamed on --dt).
            if (s.dt_auto)
                throw InvalidParameter("tau", "tau = " + detail::format_number(p.tau) + " s gives dt/tau = " +
                                                  detail::format_number(s.dt / p.tau) +
                                                  ", outside the range where the OU step is computable: the noise "
                                                  "is white to double precision there; use --tau 0");
            throw InvalidParameter("dt", "dt/tau = " + detail::format_number(s.dt / p.tau) +
                                             " is outside the range where the OU step is computable");
        }
        c.x_up = m.upper_threshold();
        c.x_down = m.lower_threshold();
        c.bridge_rate = p.tau * p.tau / s.dt;
        c.rule = s.stop_rule;
        if (c.rule == StopRule::Auto) c.rule = s.dt <= auto_bridge_ratio * p.tau ? StopRule::Bridge : StopRule::Stuck;
    }
    return c;
}

} // namespace stickslip
