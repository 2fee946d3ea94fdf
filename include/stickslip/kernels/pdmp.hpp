// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/pdmp.hpp -- the exact, event-driven PDMP engine (theory.md, section 4).
//
// The OU noise X is replaced by a jump process on the lattice delta*Z cap [-L, L]
// (rate Lambda = 2/(tau delta)^2; up with probability (1 - tau delta x/2)/2,
// reflecting at +-L), which converges to the OU process as delta -> 0. Between
// jumps the velocity follows an ODE that is solved exactly, so the only
// approximation is the lattice: no time step. State Z = (X, Y, V) with
// Y = -1 / 0 / +1 for negative-dynamic / static / positive-dynamic.
//
// Kernels are inline, allocation-free and STICKSLIP_HD (GPU-ready), like
// resolvent.hpp. X is carried as its integer lattice index, so the regeneration
// state s- = (x_{k- - 1}, -1, 0) is recognised exactly.
#pragma once

/// \file
/// The exact, event-driven PDMP engine: per-run constants and per-event
/// kernels. The comment at the top of this header explains the design.

#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>

#include "stickslip/config.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

/// Per-run constants of the PDMP engine (SI units).
struct PdmpConstants {
    double delta;     ///< lattice step [s^-1/2]
    int n_max;        ///< lattice indices run over [-n_max, n_max]; L = n_max*delta
    double rate;      ///< jump rate Lambda = 2/(tau delta)^2 [s^-1]
    /// tau delta / 2 [s^1/2], the slope of the up-jump probability in X.
    double half_tau_delta; ///< tau*delta/2: alpha_i = (1 - half_tau_delta*delta*i)/2
    /// Amplitude a of the random force a X [m s^-3/2].
    double amp;       ///< a = sqrt(noise/2)
    double friction;  ///< Delta [m s^-2]
    double bias;      ///< gbar [m s^-2]
    double relaxation;///< tauL [s], possibly +inf
    bool viscous;     ///< relaxation finite
    int k_plus;       ///< last index with a x <= Delta - gbar (top of the static band)
    int k_minus;      ///< first index with a x >= -Delta - gbar (bottom of the band)
    std::uint64_t max_events; ///< runaway guard per long excursion
};

/// Validates and precomputes; chooses L when s.lattice_bound == 0:
/// L = 8 tau^-1/2, widened to hold both thresholds plus 4 lattice steps,
/// and kept below 2/(tau delta). Throws InvalidParameter when impossible.
PdmpConstants make_pdmp_constants(const ModelParams& p, const EngineSettings& s);

/// Net acceleration in mode y at V = 0 [m s^-2]: gbar + a x_i - y Delta.
STICKSLIP_HD inline double pdmp_acceleration(const PdmpConstants& c, int i, int y) {
    return c.bias + c.amp * c.delta * i - y * c.friction;
}

/// Time [s] until the flow from (x_i, y, v) brings V to 0; +inf if never.
STICKSLIP_HD inline double pdmp_hitting_time(const PdmpConstants& c, int i, int y, double v) {
    const double inf = std::numeric_limits<double>::infinity();
    if (y == 0) return inf;
    const double k = pdmp_acceleration(c, i, y);
    if (c.viscous) {
        const double target = c.relaxation * k; // velocity the flow relaxes to
        if (y * target >= 0.0) return inf;      // driven away from 0 (or towards it only asymptotically)
        // V(t) = target + (v - target) e^{-t/tauL} = 0
        return c.relaxation * std::log1p(-v / target);
    }
    if (y * k >= 0.0) return inf;
    return -v / k;
}

/// Flow of duration t from (x_i, y, v): writes the new velocity and adds the
/// displacement [m] to du.
STICKSLIP_HD inline void pdmp_flow(const PdmpConstants& c, int i, int y, double v, double t,
                                   double& v_out, double& du) {
    if (y == 0) {
        v_out = 0.0;
        return;
    }
    const double k = pdmp_acceleration(c, i, y);
    if (c.viscous) {
        const double target = c.relaxation * k;
        const double em1 = std::expm1(-t / c.relaxation); // e^{-t/tauL} - 1
        v_out = v + (v - target) * em1;
        du += target * t - c.relaxation * (v - target) * em1;
    } else {
        v_out = v + k * t;
        du += v * t + 0.5 * k * t * t;
    }
}

/// Probability alpha_i of a jump up from lattice index i (reflecting ends).
STICKSLIP_HD inline double pdmp_up_probability(const PdmpConstants& c, int i) {
    if (i >= c.n_max) return 0.0;
    if (i <= -c.n_max) return 1.0;
    return 0.5 * (1.0 - c.half_tau_delta * c.delta * i);
}

/// Mode after V reaches 0 in mode y at lattice index i (Appendix B's kernel).
STICKSLIP_HD inline int pdmp_mode_at_rest(const PdmpConstants& c, int i, int y) {
    if (y > 0) return i <= c.k_minus - 1 ? -1 : 0;
    return i >= c.k_plus + 1 ? 1 : 0;
}

/// PDMP state: lattice index, mode, velocity [m/s].
struct PdmpState {
    /// Lattice index of the noise: X = i delta, |i| <= n_max.
    int i;
    /// Mode: -1 negative-dynamic, 0 static (stuck), +1 positive-dynamic.
    int y;
    /// Velocity V [m/s]; 0 in the static mode.
    double v;
};

/// Advances the state by one event: either the next jump of X or V reaching 0,
/// whichever is first. Adds elapsed time [s] and displacement [m]. If `horizon`
/// is finite and the event would end after it, stops exactly at the horizon
/// and returns false.
template <class Rng>
STICKSLIP_HD inline bool pdmp_event(const PdmpConstants& c, PdmpState& s, Rng& rng, double& time,
                                    double& disp, double horizon) {
    double e, u1; // the wait in units of the mean wait, and the jump direction's uniform
    rng.exponential_uniform(e, u1);
    const double wait = e / c.rate;
    const double t_hit = pdmp_hitting_time(c, s.i, s.y, s.v);
    const bool hits = t_hit <= wait;
    const double dt = hits ? t_hit : wait;
    if (time + dt > horizon) {
        double v_out;
        pdmp_flow(c, s.i, s.y, s.v, horizon - time, v_out, disp);
        s.v = v_out;
        time = horizon;
        return false;
    }
    double v_out;
    pdmp_flow(c, s.i, s.y, s.v, dt, v_out, disp);
    time += dt;
    if (hits || (s.y != 0 && s.v != 0.0 && s.y * v_out <= 0.0)) {
        // V reached 0. The second test catches rounding just before t_hit; it
        // does not apply to a start from V = 0 (s+- or after a stop), where a
        // zero-length wait must leave the mode alone.
        s.v = 0.0;
        s.y = pdmp_mode_at_rest(c, s.i, s.y);
        return true;
    }
    s.v = v_out;
    const bool up = u1 <= pdmp_up_probability(c, s.i);
    if (s.y == 0) { // leaving the static band starts the motion
        if (up && s.i >= c.k_plus) s.y = 1;
        if (!up && s.i <= c.k_minus) s.y = -1;
    }
    s.i += up ? 1 : -1;
    return true;
}

/// What observes a PDMP path: observe(start state, start time [s], start
/// displacement [m], duration [s]) for every segment between two events.
template <class O>
concept SegmentObserver = std::invocable<O&, const PdmpState&, double, double, double>;

/// Observer that ignores the path (the default; compiled away).
struct NoSegmentObserver {
    /// Does nothing with the segment (start state, start time [s], start
    /// displacement [m], duration [s]).
    STICKSLIP_HD void operator()(const PdmpState& /*start*/, double /*t_start*/, double /*u_start*/,
                                 double /*duration*/) const {}
};

/// One half long excursion: dir = +1 from s+ = (x_{k+ +1}, +1, 0) to the first
/// exact arrival at s- = (x_{k- -1}, -1, 0), however it arrives; dir = -1 the
/// mirror image. Adds its time [s], displacement [m] and events to `time`,
/// `disp` and `events`. Returns false when the event cap is reached.
/// `observe(start, t_start, u_start, duration)` sees every flow segment: the
/// state at its start, its start time [s], the displacement there [m] and its
/// length [s]; inside it X and the mode are constant and V, U follow pdmp_flow
/// from `start`.
template <class Rng, SegmentObserver Observer = NoSegmentObserver>
STICKSLIP_HD inline bool pdmp_half(const PdmpConstants& c, int dir, Rng& rng, double& time,
                                   double& disp, std::uint64_t& events, Observer&& observe = Observer{}) {
    const double inf = std::numeric_limits<double>::infinity();
    PdmpState s{dir > 0 ? c.k_plus + 1 : c.k_minus - 1, dir, 0.0};
    const int target_i = dir > 0 ? c.k_minus - 1 : c.k_plus + 1;
    for (;;) {
        if (events >= c.max_events) return false;
        const PdmpState start = s;
        const double t_start = time, u_start = disp;
        pdmp_event(c, s, rng, time, disp, inf);
        observe(start, t_start, u_start, time - t_start);
        ++events;
        if (s.v == 0.0 && s.y == -dir && s.i == target_i) return true;
    }
}

/// One long excursion (+HLE then -HLE) of the PDMP engine.
template <class Rng, SegmentObserver Observer = NoSegmentObserver>
STICKSLIP_HD inline ExcursionOutcome pdmp_long_excursion(const PdmpConstants& c, Rng& rng,
                                                         Observer&& observe = Observer{}) {
    double time = 0.0, disp = 0.0, first = 0.0;
    std::uint64_t events = 0;
    const bool ok = pdmp_half(c, +1, rng, time, disp, events, observe) && ((first = time), true) &&
                    pdmp_half(c, -1, rng, time, disp, events, observe);
    ExcursionOutcome o;
    o.first_half = first;
    o.displacement = disp;
    o.duration = time;
    o.work = events;
    o.capped = !ok;
    return o;
}

/// Initial state for a trajectory from noise x0 [s^-1/2] (rounded to the
/// nearest lattice point) and velocity v0 [m/s]: moving if v0 != 0 or if the
/// force at rest exceeds friction, else static.
STICKSLIP_HD inline PdmpState pdmp_initial_state(const PdmpConstants& c, double x0, double v0) {
    double r = std::nearbyint(x0 / c.delta);
    if (r > c.n_max) r = c.n_max;
    if (r < -c.n_max) r = -c.n_max;
    PdmpState s{static_cast<int>(r), 0, v0};
    if (v0 > 0) s.y = 1;
    else if (v0 < 0) s.y = -1;
    else if (s.i > c.k_plus) s.y = 1;
    else if (s.i < c.k_minus) s.y = -1;
    return s;
}

/// Path on [0, horizon] from state s (Algorithm 2, with the displacement over
/// each inter-event interval); `observe` sees every flow segment, the last one
/// cut at the horizon. Returns U(horizon); s holds the final state.
template <class Rng, SegmentObserver Observer = NoSegmentObserver>
STICKSLIP_HD inline ExcursionOutcome pdmp_path(const PdmpConstants& c, PdmpState& s, double horizon, Rng& rng,
                                               Observer&& observe = Observer{}) {
    double time = 0.0, disp = 0.0;
    std::uint64_t events = 0;
    for (;;) {
        const PdmpState start = s;
        const double t_start = time, u_start = disp;
        const bool more = pdmp_event(c, s, rng, time, disp, horizon);
        observe(start, t_start, u_start, time - t_start);
        if (!more) break;
        ++events;
    }
    ExcursionOutcome o;
    o.displacement = disp;
    o.duration = horizon;
    o.work = events + 1;
    return o;
}

/// Brute-force trajectory from (x0, v0): pdmp_path without an observer.
template <class Rng>
STICKSLIP_HD inline ExcursionOutcome pdmp_trajectory(const PdmpConstants& c, double x0, double v0,
                                                     double horizon, Rng& rng) {
    PdmpState s = pdmp_initial_state(c, x0, v0);
    return pdmp_path(c, s, horizon, rng);
}

} // namespace stickslip
