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
    c.amp = p.force_amplitude();
    c.bias = p.has_drift_law() ? (*m.law)(0.0) : p.bias; // b(0): where the static band lies
    const double band = p.static_friction_level();
    const auto too_many_points = [&](double points) {
        return InvalidParameter("grid", "grid = " + detail::format_number(s.grid) + " gives " +
                                            detail::format_number(points) +
                                            " lattice points; choose grid so that tau*grid^2 is between 1e-16 and 1");
    };
    // With a static band, the largest step <= grid that fits a whole number N
    // of steps across the band (its edges s-+ = (-+Delta_s - b(0))/a), and the
    // shift that puts the lower edge on a lattice point (kernels/pdmp.hpp).
    // The 1e-9 keeps N when grid already fits the band (as when the
    // Kolmogorov engine rebuilds these constants from the step chosen here).
    double step = s.grid;
    double lower_edge_index = 0.0, band_steps = 0.0;
    if (p.has_static_band()) {
        const double lower_edge = (-band - c.bias) / c.amp, width = 2.0 * band / c.amp;
        band_steps = std::ceil(width / s.grid - 1e-9);
        if (!(band_steps >= 2.0 && band_steps < 1e8)) throw too_many_points(band_steps + 1.0);
        step = width / band_steps;
        lower_edge_index = std::nearbyint(lower_edge / step);
        c.x_offset = lower_edge - lower_edge_index * step;
        c.force_offset = c.amp * c.x_offset;
    }
    c.delta = step;
    c.rate = 2.0 / (p.tau * p.tau * step * step);
    c.half_tau_delta = 0.5 * p.tau * step;
    c.friction = p.friction;
    c.relaxation = p.relaxation;
    c.viscous = !std::isinf(p.relaxation);
    c.knots_law = p.has_drift_law();
    if (c.knots_law) {
        c.drift = *m.law;
        c.viscous = false;
        zero_knot(c.drift); // the landing at 0 is a knot (make_drift_law's invariant)
    }
    c.max_events = s.max_work_per_excursion;
    // Without a static band, k+ is the last lattice index with a x <= Delta -
    // bias, k- the first with a x >= -Delta - bias. The rounded quotients can disagree with the
    // sign of pdmp_acceleration (what the kernels use to decide whether the
    // object moves) when a threshold falls on a lattice point, so they are
    // settled with that very expression: the object at s+ accelerates strictly
    // up, at s- strictly down, and the static band is exactly where it cannot move.
    // The band is where a stuck object stays and a landing one sticks; the
    // flows slide against the friction (pdmp_acceleration).
    // With a static band the edges are the lattice points lower_edge_index
    // and lower_edge_index + band_steps, and the band is the points strictly
    // between: at an edge the force equals the static friction and a slip
    // starts (the continuum process is there for no positive time).
    const auto band_edge_push = [&](int i, int y) { return c.bias + c.amp * c.delta * i - y * band; };
    const double kp_est = std::floor((band - c.bias) / (c.amp * step));
    const double km_est = std::ceil((-band - c.bias) / (c.amp * step));
    if (!(std::fabs(kp_est) < 1e8 && std::fabs(km_est) < 1e8))
        throw too_many_points(2 * std::fmax(std::fabs(kp_est), std::fabs(km_est)) + 1);
    int kp = static_cast<int>(kp_est), km = static_cast<int>(km_est);
    if (p.has_static_band()) {
        km = static_cast<int>(lower_edge_index) + 1;
        kp = static_cast<int>(lower_edge_index + band_steps) - 1;
    } else {
        while (band_edge_push(kp + 1, +1) <= 0.0) ++kp;
        while (band_edge_push(kp, +1) > 0.0) --kp;
        while (band_edge_push(km - 1, -1) >= 0.0) --km;
        while (band_edge_push(km, -1) < 0.0) ++km;
    }

    // Largest lattice half-width with tau*delta*L < 2 (alpha >= 0 inside;
    // shifted, L reaches |x_offset| further on one side).
    const double shift = std::fabs(c.x_offset);
    const double n_allowed = shift == 0.0 ? std::ceil(2.0 / (p.tau * step * step)) - 1.0
                                          : std::ceil((2.0 / (p.tau * step) - shift) / step) - 1.0;
    double n;
    if (s.lattice_bound > 0) {
        n = std::floor(s.lattice_bound / step);
        if ((n * step + shift) * p.tau * step >= 2.0)
            throw InvalidParameter("lattice-bound", "tau*grid*L = " +
                                                        detail::format_number(p.tau * step * (n * step + shift)) +
                                                        " must be < 2; use a smaller lattice-bound or grid");
    } else {
        n = std::ceil(8.0 / std::sqrt(p.tau) / step);
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
        throw InvalidParameter("lattice-bound", "lattice-bound L = " + detail::format_number(n * step) +
                                                    " s^-1/2 does not reach the noise thresholds x* = " +
                                                    detail::format_number(m.upper_threshold()) + ", x-* = " +
                                                    detail::format_number(m.lower_threshold()) + " (s^-1/2) plus two grid steps");
    if (!reaches)
        throw InvalidParameter("grid", "tau*grid*L must be < 2, but the lattice must reach the noise thresholds x* = " +
                                           detail::format_number(m.upper_threshold()) + ", x-* = " + detail::format_number(m.lower_threshold()) +
                                           " (s^-1/2); with grid " + detail::format_number(s.grid) + " it only reaches L = " +
                                           detail::format_number(n * step) + ": use a finer grid");
    c.n_max = static_cast<int>(n);
    c.k_plus = kp;
    c.k_minus = km;
    return c;
}

} // namespace stickslip
