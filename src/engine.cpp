// Construction and validation of the per-run engine constants.
#include <cmath>

#include "format.hpp"
#include "stickslip/inclusion.hpp"
#include "stickslip/rng.hpp"
#include "stickslip/pdmp.hpp"

namespace stickslip {

namespace {
void check_stationary(const ModelParams& p) {
    if (!has_stationary_state(p))
        throw InvalidParameter("bias", "with relaxation inf the bias must satisfy |bias| < friction (otherwise the "
                                       "object accelerates forever and D is undefined); got bias " +
                                           detail::format_number(p.bias) + ", friction " + detail::format_number(p.friction));
}
} // namespace

std::string to_string(Engine e) { return e == Engine::Pdmp ? "pdmp" : "inclusion"; }

std::string to_string(StopRule r) {
    switch (r) {
    case StopRule::Bridge: return "bridge";
    case StopRule::Stuck: return "stuck";
    default: return "auto";
    }
}

Engine parse_engine(const std::string& s) {
    if (s == "inclusion") return Engine::Inclusion;
    if (s == "pdmp") return Engine::Pdmp;
    throw InvalidParameter("engine", "engine must be 'inclusion' or 'pdmp', got '" + s + "'");
}

StopRule parse_stop_rule(const std::string& s) {
    if (s == "auto") return StopRule::Auto;
    if (s == "bridge" || s == "Q") return StopRule::Bridge;
    if (s == "stuck" || s == "P") return StopRule::Stuck;
    throw InvalidParameter("stop-rule", "stop-rule must be 'auto', 'bridge' (rule Q) or 'stuck' (rule P), got '" +
                                            s + "'");
}

double white_level_default(const ModelParams& p) {
    double scale = 0.7 * p.noise / p.friction;
    if (!std::isinf(p.relaxation)) scale = std::fmin(scale, std::sqrt(p.noise * p.relaxation / 2.0));
    return 0.5 * scale;
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

InclusionConstants make_inclusion_constants(const ModelParams& p, const EngineSettings& s) {
    validate(p);
    validate(s);
    check_stationary(p);
    InclusionConstants c{};
    c.h = s.dt;
    c.keep = 1.0 - s.dt * p.inverse_relaxation();
    if (c.keep < 0)
        throw InvalidParameter("dt", "dt must be smaller than relaxation (dt = " + detail::format_number(s.dt) +
                                         " s, relaxation = " + detail::format_number(p.relaxation) +
                                         " s): the explicit drift step would overshoot");
    c.h_bias = s.dt * p.bias;
    c.h_friction = s.dt * p.friction;
    c.white = p.white();
    c.max_steps = s.max_work_per_excursion;
    if (c.white) {
        c.h_amp = std::sqrt(p.noise * s.dt);
        c.level = s.white_level > 0 ? s.white_level : white_level_default(p);
        c.rule = StopRule::Stuck; // unused for white noise
    } else {
        c.h_amp = s.dt * p.force_amplitude();
        c.ou = ou_step(p.tau, s.dt);
        c.f_x = c.h_amp * c.ou.mean_coef;
        c.f_z = c.h_amp * c.ou.l11;
        if (!(std::isfinite(c.ou.l11) && std::isfinite(c.ou.l21) && std::isfinite(c.ou.l22) &&
              std::isfinite(c.ou.mean_coef)))
            throw InvalidParameter("dt", "dt/tau = " + detail::format_number(s.dt / p.tau) +
                                             " is outside the range where the OU step is computable");
        c.x_up = p.upper_threshold();
        c.x_down = p.lower_threshold();
        c.bridge_rate = p.tau * p.tau / s.dt;
        c.rule = s.stop_rule;
        if (c.rule == StopRule::Auto) c.rule = s.dt <= auto_bridge_ratio * p.tau ? StopRule::Bridge : StopRule::Stuck;
    }
    return c;
}

PdmpConstants make_pdmp_constants(const ModelParams& p, const EngineSettings& s) {
    validate(p);
    check_stationary(p);
    if (p.white())
        throw InvalidParameter("tau", "the pdmp engine needs colored noise (tau > 0); use --engine inclusion for "
                                      "white noise");
    validate(s);
    PdmpConstants c{};
    c.delta = s.grid;
    c.rate = 2.0 / (p.tau * p.tau * s.grid * s.grid);
    c.half_tau_delta = 0.5 * p.tau * s.grid;
    c.amp = p.force_amplitude();
    c.friction = p.friction;
    c.bias = p.bias;
    c.relaxation = p.relaxation;
    c.viscous = !std::isinf(p.relaxation);
    c.max_events = s.max_work_per_excursion;
    // k+ is the last lattice index with a x <= friction - bias, k- the first
    // with a x >= -friction - bias. The rounded quotients can disagree with the
    // sign of pdmp_acceleration (what the kernels use to decide whether the
    // object moves) when a threshold falls on a lattice point, so they are
    // settled with that very expression: the object at s+ accelerates strictly
    // up, at s- strictly down, and the static band is exactly where it cannot move.
    const double kp_est = std::floor((p.friction - p.bias) / (c.amp * s.grid));
    const double km_est = std::ceil((-p.friction - p.bias) / (c.amp * s.grid));
    const auto too_many_points = [&](double points) {
        return InvalidParameter("grid", "grid = " + detail::format_number(s.grid) + " gives " +
                                            detail::format_number(points) +
                                            " lattice points; choose grid so that tau*grid^2 is between 1e-16 and 1");
    };
    if (!(std::fabs(kp_est) < 1e8 && std::fabs(km_est) < 1e8))
        throw too_many_points(2 * std::fmax(std::fabs(kp_est), std::fabs(km_est)) + 1);
    int kp = static_cast<int>(kp_est), km = static_cast<int>(km_est);
    while (pdmp_acceleration(c, kp + 1, +1) <= 0.0) ++kp;
    while (pdmp_acceleration(c, kp, +1) > 0.0) --kp;
    while (pdmp_acceleration(c, km - 1, -1) >= 0.0) --km;
    while (pdmp_acceleration(c, km, -1) < 0.0) ++km;

    // Largest lattice half-width with tau*delta*L < 2 (alpha >= 0 inside).
    const double n_allowed = std::ceil(2.0 / (p.tau * s.grid * s.grid)) - 1.0;
    double n;
    if (s.lattice_bound > 0) {
        n = std::floor(s.lattice_bound / s.grid);
        if (n * s.grid * p.tau * s.grid >= 2.0)
            throw InvalidParameter("lattice-bound", "tau*grid*L = " + detail::format_number(p.tau * s.grid * n * s.grid) +
                                                        " must be < 2; use a smaller lattice-bound or grid");
    } else {
        n = std::ceil(8.0 / std::sqrt(p.tau) / s.grid);
        n = std::fmax(n, std::fmax(kp + 5.0, -km + 5.0));
        n = std::fmin(n, n_allowed);
    }
    if (!(n >= 1) || n > 1e8) throw too_many_points(2 * n + 1);
    const bool reaches = kp + 2 <= n && km - 2 >= -n;
    if (!reaches && s.lattice_bound > 0)
        throw InvalidParameter("lattice-bound", "lattice-bound L = " + detail::format_number(n * s.grid) +
                                                    " s^-1/2 does not reach the noise thresholds x* = " +
                                                    detail::format_number(p.upper_threshold()) + ", x-* = " +
                                                    detail::format_number(p.lower_threshold()) + " (s^-1/2) plus two grid steps");
    if (!reaches)
        throw InvalidParameter("grid", "tau*grid*L must be < 2, but the lattice must reach the noise thresholds x* = " +
                                           detail::format_number(p.upper_threshold()) + ", x-* = " + detail::format_number(p.lower_threshold()) +
                                           " (s^-1/2); with grid " + detail::format_number(s.grid) + " it only reaches L = " +
                                           detail::format_number(n * s.grid) + ": use a finer grid");
    c.n_max = static_cast<int>(n);
    c.k_plus = kp;
    c.k_minus = km;
    return c;
}

} // namespace stickslip
