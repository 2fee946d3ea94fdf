// SPDX-License-Identifier: BSD-3-Clause
// Construction of the event scheme's per-run constants: the exact laws of a
// step and of its midpoint at every refinement depth.
#include "stickslip/kernels/event_scheme.hpp"

#include <cmath>

#include "core/format.hpp"
#include "stickslip/kernels/resolvent.hpp"

namespace stickslip {

EventConstants make_event_constants(const ModelParams& p, const EngineSettings& s) {
    validate(p);
    validate(s);
    require_stationary_state(p);
    if (p.has_drift_law())
        throw InvalidParameter("scheme", "the event scheme takes the affine drift law only (--relaxation, --bias); "
                                         "with --drift or --drift-table use --scheme resolvent or --engine pdmp");
    EventConstants c{};
    c.h = s.dt;
    c.leaf = std::ldexp(s.dt, -event_depth);
    c.amp = p.force_amplitude();
    c.bias = p.bias;
    c.friction = p.friction;
    c.inv_relaxation = p.inverse_relaxation();
    c.relaxation = p.relaxation;
    c.noise = p.noise;
    c.max_work = s.max_work_per_excursion;
    c.white = p.white();
    if (c.white) {
        c.level = s.white_level > 0 ? s.white_level : white_level_default(p);
        double r = c.level * c.level / (36.0 * p.noise);
        if (std::isfinite(p.relaxation)) r = std::fmin(r, p.relaxation / 16.0);
        const double leaves = std::floor(r / c.leaf);
        c.leave_zero_leaves = leaves < 1.0 ? 1 : (leaves >= std::ldexp(1.0, event_depth) ? std::uint64_t{1} << event_depth
                                                                                        : static_cast<std::uint64_t>(leaves));
    } else {
        c.x_up = p.upper_threshold();
        c.x_down = p.lower_threshold();
    }
    // The laws reject what they cannot compute (tiny or huge ratios); say it with the flag's name.
    try {
        for (int d = 0; d <= event_depth; ++d) {
            EventLevel& L = c.lv[d];
            L.leaves = std::uint64_t{1} << (event_depth - d);
            L.len = std::ldexp(s.dt, -d);
            if (c.white) {
                L.wslide = white_slide_law(p.relaxation, p.noise, L.len);
                L.wmid = white_slide_bridge(p.relaxation, p.noise, L.len);
                const double k = p.inverse_relaxation();
                L.v_grow = k == 0.0 ? 1.0 : std::exp(L.len * k);
                L.v_u_len = k == 0.0 ? L.len : 0.5 * std::expm1(2.0 * L.len * k) / k;
                L.v_touch_rate = 2.0 * L.v_grow / (p.noise * L.v_u_len);
            } else {
                L.slide = colored_slide_law(p.tau, p.relaxation, c.amp, L.len);
                L.mid = colored_slide_bridge(p.tau, p.relaxation, c.amp, L.len);
                L.v_mid_sd = std::sqrt(L.mid.cov[1][1]);
                const OUStep ou = ou_step(p.tau, L.len);
                L.x_keep = ou.end_coef;
                L.x_sd = std::sqrt(ou.s22);
                L.x_mid = ou_bridge(p.tau, L.len);
                L.x_grow = std::exp(L.len / p.tau);
                L.x_u_len = 0.5 * p.tau * std::expm1(2.0 * L.len / p.tau);
                L.x_var_rate = 2.0 / (p.tau * p.tau);
                L.x_tau = p.tau;
            }
        }
    } catch (const std::invalid_argument& e) {
        throw InvalidParameter("dt", "dt = " + detail::format_number(s.dt) +
                                         " s is outside the range the event scheme's laws can be computed for (" +
                                         e.what() + ")");
    }
    return c;
}

} // namespace stickslip
