// SPDX-License-Identifier: BSD-3-Clause
// Construction and validation of the PDMP engine's per-run constants.
#include "stickslip/kernels/pdmp.hpp"

#include <cmath>

#include "core/format.hpp"
#include "stickslip/model.hpp"

namespace stickslip {

PdmpConstants make_pdmp_constants(const ModelParams& p, const EngineSettings& s) {
    return make_pdmp_constants(make_model(p), s);
}

PdmpConstants make_pdmp_constants(const Model& m, const EngineSettings& s) {
    const ModelParams& p = m.params;
    require_stationary_state(m);
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
    c.knots_law = p.has_drift_law();
    if (c.knots_law) {
        c.drift = *m.law;
        c.bias = c.drift(0.0); // b(0): the static band and the acceleration at rest
        c.viscous = false;
        zero_knot(c.drift); // the landing at 0 is a knot (make_drift_law's invariant)
    }
    c.max_events = s.max_work_per_excursion;
    // k+ is the last lattice index with a x <= Delta_s - bias, k- the first
    // with a x >= -Delta_s - bias. The rounded quotients can disagree with the
    // sign of pdmp_acceleration (what the kernels use to decide whether the
    // object moves) when a threshold falls on a lattice point, so they are
    // settled with that very expression: the object at s+ accelerates strictly
    // up, at s- strictly down, and the static band is exactly where it cannot move.
    // The band is the static one (Delta_s, the friction unless set): where a
    // stuck object stays and a landing one sticks; the flows slide against the
    // friction (pdmp_acceleration).
    const double band = p.static_friction_level();
    const auto band_edge_push = [&](int i, int y) { return c.bias + c.amp * c.delta * i - y * band; };
    const double kp_est = std::floor((band - c.bias) / (c.amp * s.grid));
    const double km_est = std::ceil((-band - c.bias) / (c.amp * s.grid));
    const auto too_many_points = [&](double points) {
        return InvalidParameter("grid", "grid = " + detail::format_number(s.grid) + " gives " +
                                            detail::format_number(points) +
                                            " lattice points; choose grid so that tau*grid^2 is between 1e-16 and 1");
    };
    if (!(std::fabs(kp_est) < 1e8 && std::fabs(km_est) < 1e8))
        throw too_many_points(2 * std::fmax(std::fabs(kp_est), std::fabs(km_est)) + 1);
    int kp = static_cast<int>(kp_est), km = static_cast<int>(km_est);
    while (band_edge_push(kp + 1, +1) <= 0.0) ++kp;
    while (band_edge_push(kp, +1) > 0.0) --kp;
    while (band_edge_push(km - 1, -1) >= 0.0) --km;
    while (band_edge_push(km, -1) < 0.0) ++km;

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
    if (s.lattice_bound > 0 && !(n >= 1))
        throw InvalidParameter("lattice-bound", "lattice-bound L = " + detail::format_number(s.lattice_bound) +
                                                    " s^-1/2 is shorter than one grid step (" +
                                                    detail::format_number(s.grid) +
                                                    " s^-1/2): it must reach the noise thresholds x* = " +
                                                    detail::format_number(m.upper_threshold()) + ", x-* = " +
                                                    detail::format_number(m.lower_threshold()) +
                                                    " (s^-1/2) plus two grid steps, or be 0 (chosen)");
    if (!(n >= 1) || n > 1e8) throw too_many_points(2 * n + 1);
    const bool reaches = kp + 2 <= n && km - 2 >= -n;
    if (!reaches && s.lattice_bound > 0)
        throw InvalidParameter("lattice-bound", "lattice-bound L = " + detail::format_number(n * s.grid) +
                                                    " s^-1/2 does not reach the noise thresholds x* = " +
                                                    detail::format_number(m.upper_threshold()) + ", x-* = " +
                                                    detail::format_number(m.lower_threshold()) + " (s^-1/2) plus two grid steps");
    if (!reaches)
        throw InvalidParameter("grid", "tau*grid*L must be < 2, but the lattice must reach the noise thresholds x* = " +
                                           detail::format_number(m.upper_threshold()) + ", x-* = " + detail::format_number(m.lower_threshold()) +
                                           " (s^-1/2); with grid " + detail::format_number(s.grid) + " it only reaches L = " +
                                           detail::format_number(n * s.grid) + ": use a finer grid");
    c.n_max = static_cast<int>(n);
    c.k_plus = kp;
    c.k_minus = km;
    return c;
}

} // namespace stickslip
