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
//
// With a static friction above the friction the lattice is shifted and its
// step shortened (x_i = delta i + x_offset) so that both static edges are
// lattice points, where a slip starts. On the unshifted lattice a slip
// started at the first point past the edge, up to one step late, and with a
// static band the slip starts with a finite acceleration, so that lateness
// was an error of first order in the step (M0 -1.8% at grid 0.025 on Fig. 2
// at 1.5 Delta). The shift keeps the chain's drift exactly -x/tau, so its
// mean stays 0. Without a static band the offset is 0 and the step the grid:
// the one-coefficient model's zero acceleration at the edge hides the lateness.
#pragma once

/// \file
/// The exact, event-driven PDMP engine: per-run constants and per-event
/// kernels. The comment at the top of this header explains the design.

#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "stickslip/config.hpp"
#include "stickslip/drift_law.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/kernels/corrector.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

struct Model; // model.hpp: the parameters and their drift law, made once per run

/// Per-run constants of the PDMP engine (SI units).
struct PdmpConstants {
    double delta;     ///< lattice step [s^-1/2]
    /// x_0 [s^-1/2]: the lattice is x_i = delta i + x_offset (0 without a static band).
    double x_offset;
    double force_offset; ///< amp * x_offset [m s^-2]
    int n_max;        ///< lattice indices run over [-n_max, n_max]; L = n_max*delta
    double rate;      ///< jump rate Lambda = 2/(tau delta)^2 [s^-1]
    /// tau delta / 2 [s^1/2], the slope of the up-jump probability in X.
    double half_tau_delta; ///< tau*delta/2: alpha_i = (1 - half_tau_delta*x_i)/2
    /// Amplitude a of the random force a X [m s^-3/2].
    double amp;       ///< a = sqrt(noise/2)
    double friction;  ///< Delta [m s^-2]
    double bias;      ///< gbar [m s^-2]
    double relaxation;///< tauL [s], possibly +inf
    bool viscous;     ///< relaxation finite
    /// Last index of the static band (Delta_s the static friction): without a
    /// static band the last with a x <= Delta - gbar; with one the point below
    /// the upper static edge, which is k_plus + 1.
    int k_plus;
    int k_minus;      ///< first index of the band (the mirror image of k_plus)
    std::uint64_t max_events; ///< runaway guard per long excursion
    /// A law other than the affine one: the flow is linear within each of its
    /// pieces (bias then holds b(0), relaxation is unused), and reaching a
    /// piece's end is one more event beside the next jump and V = 0.
    bool knots_law;
    DriftLaw drift;   ///< knots law: b(v) [m s^-2]
};

/// Validates and precomputes; chooses L when s.lattice_bound == 0:
/// L = 8 tau^-1/2, widened to hold both thresholds plus 4 lattice steps,
/// and kept below 2/(tau delta). Throws InvalidParameter when impossible.
PdmpConstants make_pdmp_constants(const Model& m, const EngineSettings& s);
/// make_pdmp_constants(make_model(p), s), for callers that hold no Model.
PdmpConstants make_pdmp_constants(const ModelParams& p, const EngineSettings& s);

/// Noise x_i at lattice index i [s^-1/2].
STICKSLIP_HD inline double pdmp_noise(const PdmpConstants& c, int i) { return c.delta * i + c.x_offset; }

/// Net acceleration in mode y at V = 0 [m s^-2]: gbar + a x_i - y Delta.
STICKSLIP_HD inline double pdmp_acceleration(const PdmpConstants& c, int i, int y) {
    return c.bias + c.amp * c.delta * i + c.force_offset - y * c.friction;
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
    // Not half_tau_delta * pdmp_noise: grouped so that without an offset the
    // probability is bit for bit the unshifted lattice's.
    return 0.5 * (1.0 - (c.half_tau_delta * c.delta * i + c.half_tau_delta * c.x_offset));
}

/// Mode after V reaches 0 in mode y at lattice index i (Appendix B's kernel).
STICKSLIP_HD inline int pdmp_mode_at_rest(const PdmpConstants& c, int i, int y) {
    if (y > 0) return i <= c.k_minus - 1 ? -1 : 0;
    return i >= c.k_plus + 1 ? 1 : 0;
}

/// PDMP state: lattice index, mode, velocity [m/s].
struct PdmpState {
    /// Lattice index of the noise: X = pdmp_noise(i), |i| <= n_max.
    int i;
    /// Mode: -1 negative-dynamic, 0 static (stuck), +1 positive-dynamic.
    int y;
    /// Velocity V [m/s]; 0 in the static mode.
    double v;
};

/// Knots law: the piece of the drift law the flow from (x_i, y, v) runs in:
/// the one that holds v, or, with v exactly on a knot (where a knot event
/// puts it), the one on the side the flow moves to (b is continuous, so its
/// value at the knot gives the direction). Derived, not stored, so that the
/// state stays 16 bytes (measured: the PDMP's affine loop 7-10% slower with a
/// fourth field).
STICKSLIP_HD inline int pdmp_piece(const PdmpConstants& c, int i, int y, double v) {
    const DriftLaw& b = c.drift;
    int j = b.piece(v);
    int k = -1; // the knot v is on, if any
    if (j + 1 < b.knots && v == b.knot(j + 1)) k = j + 1;
    else if (v == b.knot(j)) k = j;
    if (k < 0) return j;
    const double rate = b.values[k] + c.amp * c.delta * i + c.force_offset - y * c.friction;
    j = rate >= 0.0 ? k : k - 1;
    const int last = b.pieces() - 1;
    return j < 0 ? 0 : j > last ? last : j;
}

/// expm1(x)/x, 1 at x = 0.
STICKSLIP_HD inline double pdmp_phi1(double x) { return x == 0.0 ? 1.0 : std::expm1(x) / x; }
/// (expm1(x) - x)/x^2, 1/2 at x = 0 (a series near 0, where the quotient cancels).
STICKSLIP_HD inline double pdmp_phi2(double x) {
    if (std::fabs(x) < 1e-2) return 0.5 + x * (1.0 / 6.0 + x * (1.0 / 24.0 + x * (1.0 / 120.0 + x / 720.0)));
    return (std::expm1(x) - x) / (x * x);
}

/// Knots law: net acceleration on piece j for the state s, dV/dt = slope V + k: writes slope [s^-1] and k [m s^-2].
STICKSLIP_HD inline void pdmp_piece_line(const PdmpConstants& c, const PdmpState& s, int j, double& slope, double& k) {
    slope = c.drift.piece_slope(j);
    k = c.drift.piece_intercept(j) + c.amp * c.delta * s.i + c.force_offset - s.y * c.friction;
}

/// Knots law: time [s] for the flow dV/dt = slope V + k from v to reach `level`; +inf if never.
STICKSLIP_HD inline double pdmp_time_to_level(double slope, double k, double v, double level) {
    const double inf = std::numeric_limits<double>::infinity();
    if (!(std::fabs(level) < inf)) return inf;
    if (slope == 0.0) {
        const double t = (level - v) / k;
        return t >= 0.0 ? t : inf; // also NaN (k = 0)
    }
    // V(t) - v* = (v - v*) e^{slope t} with v* = -k/slope.
    const double w = v + k / slope;
    const double t = std::log1p((level - v) / w) / slope;
    return t >= 0.0 ? t : inf;
}

/// Knots law: the end of piece j the flow from s moves towards [m/s] (+-inf: none; NaN: it stays).
STICKSLIP_HD inline double pdmp_piece_target(const PdmpConstants& c, const PdmpState& s, int j) {
    double slope, k;
    pdmp_piece_line(c, s, j, slope, k);
    const double rate = slope * s.v + k;
    if (rate > 0.0) return c.drift.piece_upper(j);
    if (rate < 0.0) return c.drift.piece_lower(j);
    return std::numeric_limits<double>::quiet_NaN();
}

/// Flow of duration t from state s, for either law: writes the new velocity
/// and adds the displacement [m] to du.
STICKSLIP_HD inline void pdmp_flow_state(const PdmpConstants& c, const PdmpState& s, double t, double& v_out,
                                         double& du) {
    if (!c.knots_law || s.y == 0) {
        pdmp_flow(c, s.i, s.y, s.v, t, v_out, du);
        return;
    }
    double slope, k;
    pdmp_piece_line(c, s, pdmp_piece(c, s.i, s.y, s.v), slope, k);
    const double st = slope * t;
    v_out = s.v + (slope * s.v + k) * t * pdmp_phi1(st);
    du += s.v * t * pdmp_phi1(st) + k * t * t * pdmp_phi2(st);
}



/// Advances the state by one event: either the next jump of X or V reaching 0,
/// whichever is first. Adds elapsed time [s] and displacement [m]. If `horizon`
/// is finite and the event would end after it, stops exactly at the horizon
/// and returns false.
template <class Rng>
STICKSLIP_HD inline bool pdmp_event_knots(const PdmpConstants& c, PdmpState& s, Rng& rng, double& time,
                                          double& disp, double horizon);

template <class Rng>
STICKSLIP_HD inline bool pdmp_event_affine(const PdmpConstants& c, PdmpState& s, Rng& rng, double& time,
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

/// pdmp_event for a knots law: the next event is the first of the jump of X,
/// V reaching 0 (a landing, as above) and V reaching another knot (the piece
/// changes; X does not jump: its wait, exponential, is drawn afresh after any
/// event, which memorylessness allows).
template <class Rng>
STICKSLIP_HD inline bool pdmp_event_knots(const PdmpConstants& c, PdmpState& s, Rng& rng, double& time,
                                          double& disp, double horizon) {
    double e, u1;
    rng.exponential_uniform(e, u1);
    const double wait = e / c.rate;
    double level = std::numeric_limits<double>::infinity(), t_end = level;
    if (s.y != 0) {
        const int j = pdmp_piece(c, s.i, s.y, s.v);
        double slope, k;
        pdmp_piece_line(c, s, j, slope, k);
        level = pdmp_piece_target(c, s, j);
        t_end = pdmp_time_to_level(slope, k, s.v, level);
    }
    const bool ends = t_end <= wait;
    const double dt = ends ? t_end : wait;
    double v_out;
    if (time + dt > horizon) {
        pdmp_flow_state(c, s, horizon - time, v_out, disp);
        s.v = v_out;
        time = horizon;
        return false;
    }
    pdmp_flow_state(c, s, dt, v_out, disp);
    time += dt;
    if ((ends && level == 0.0) || (s.y != 0 && s.v != 0.0 && s.y * v_out <= 0.0)) { // landing
        s.v = 0.0;
        s.y = pdmp_mode_at_rest(c, s.i, s.y);
        return true;
    }
    if (ends) { // a knot, exactly: the flow goes on in the next piece (pdmp_piece)
        s.v = level;
        return true;
    }
    s.v = v_out;
    const bool up = u1 <= pdmp_up_probability(c, s.i);
    if (s.y == 0) {
        if (up && s.i >= c.k_plus) s.y = 1;
        if (!up && s.i <= c.k_minus) s.y = -1;
    }
    s.i += up ? 1 : -1;
    return true;
}

/// One event for the law fixed at compile time (Knots: c is a knots law), so
/// that the loops below test the law once per half, not once per event.
template <bool Knots, class Rng>
STICKSLIP_HD inline bool pdmp_event_as(const PdmpConstants& c, PdmpState& s, Rng& rng, double& time, double& disp,
                                       double horizon) {
    if constexpr (Knots) return pdmp_event_knots(c, s, rng, time, disp, horizon);
    else return pdmp_event_affine(c, s, rng, time, disp, horizon);
}

/// Advances the state by one event (see pdmp_event_affine), for either law.
template <class Rng>
STICKSLIP_HD inline bool pdmp_event(const PdmpConstants& c, PdmpState& s, Rng& rng, double& time, double& disp,
                                    double horizon) {
    return c.knots_law ? pdmp_event_knots(c, s, rng, time, disp, horizon)
                       : pdmp_event_affine(c, s, rng, time, disp, horizon);
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
    auto run = [&](auto knots) {
        for (;;) {
            if (events >= c.max_events) return false;
            const PdmpState start = s;
            const double t_start = time, u_start = disp;
            pdmp_event_as<decltype(knots)::value>(c, s, rng, time, disp, inf);
            observe(start, t_start, u_start, time - t_start);
            ++events;
            if (s.v == 0.0 && s.y == -dir && s.i == target_i) return true;
        }
    };
    return c.knots_law ? run(std::true_type{}) : run(std::false_type{});
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

/// The PDMP's martingale for the control variate (kernels/corrector.hpp): X
/// is a birth-death chain, so with g frozen over each segment between events
/// at the segment's start state (predictable), M = sum over jumps of g dX
/// minus sum over segments of g mu(x) dt, mu = delta (lambda_up -
/// lambda_down) the chain's drift, is an exact martingale, with predictable
/// quadratic variation Q = sum over segments of g^2 delta^2 Lambda dt (X is
/// constant on a segment, so both sums are exact). A SegmentObserver: a jump
/// shows as the next segment starting at another lattice index; finish()
/// adds the excursion's last one.
struct PdmpMartingale {
    const PdmpConstants* c; ///< the engine's constants
    MartingaleSums sums;    ///< M and Q so far, and the corrector
    int last_i = 0;         ///< lattice index of the current segment
    double last_g = 0.0;    ///< g at its start [m s^1/2]
    bool started = false;   ///< a segment has been seen
    /// Observes the segment from `start` at time t0 [s] lasting dt [s].
    STICKSLIP_HD void operator()(const PdmpState& start, double /*t0*/, double /*u0*/, double dt) {
        if (started && start.i != last_i) sums.m += last_g * (c->delta * (start.i - last_i));
        const double x = pdmp_noise(*c, start.i);
        const double g = sums.g(x, start.v);
        const double up = pdmp_up_probability(*c, start.i);
        const double mu = c->delta * c->rate * (2.0 * up - 1.0); // [s^-1/2 / s]
        sums.m -= g * mu * dt;
        sums.q += (g * g) * (c->delta * c->delta * c->rate) * dt;
        last_i = start.i;
        last_g = g;
        started = true;
    }
    /// Adds the jump into the excursion's end state, lattice index i_end.
    STICKSLIP_HD void finish(int i_end) {
        if (started && i_end != last_i) sums.m += last_g * (c->delta * (i_end - last_i));
    }
};

/// One long excursion of the PDMP with the martingale of the corrector g in
/// the outcome (martingale, martingale_qv); U and t are pdmp_long_excursion's
/// bit for bit (the same draws).
template <class Rng>
STICKSLIP_HD inline ExcursionOutcome pdmp_long_excursion_with(const PdmpConstants& c, Rng& rng,
                                                              const CorrectorTable& g) {
    PdmpMartingale mart{&c, MartingaleSums{g}};
    ExcursionOutcome o = pdmp_long_excursion(c, rng, mart);
    mart.finish(c.k_plus + 1); // the excursion ends where it started
    o.martingale = mart.sums.m;
    o.martingale_qv = mart.sums.q;
    return o;
}

/// Initial state for a trajectory from noise x0 [s^-1/2] (rounded to the
/// nearest lattice point) and velocity v0 [m/s]: moving if v0 != 0 or if the
/// force at rest exceeds friction, else static.
STICKSLIP_HD inline PdmpState pdmp_initial_state(const PdmpConstants& c, double x0, double v0) {
    double r = std::nearbyint((x0 - c.x_offset) / c.delta);
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
    auto run = [&](auto knots) {
        for (;;) {
            const PdmpState start = s;
            const double t_start = time, u_start = disp;
            const bool more = pdmp_event_as<decltype(knots)::value>(c, s, rng, time, disp, horizon);
            observe(start, t_start, u_start, time - t_start);
            if (!more) break;
            ++events;
        }
    };
    if (c.knots_law) run(std::true_type{});
    else run(std::false_type{});
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
