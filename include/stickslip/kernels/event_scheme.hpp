// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/event_scheme.hpp -- the event scheme of the inclusion engine: exact
// Gaussian steps within a phase, events at their times (theory.md, section 10).
//
// Why: the resolvent step (resolvent.hpp) is exact for the noise but first
// order for everything else -- the displacement by the left-point rule, the
// drift taken explicitly, and above all the events (V landing on 0, X leaving
// the static band) placed on the grid of steps. Within a phase the dynamics is
// linear, so a step can be drawn exactly (phase_law.hpp); only the events need
// care, and they are placed at their times by conditional refinement: given
// the state at both ends of a step, the state at its midpoint is Gaussian with
// a known law (the bridge), so a step where an event is possible is halved,
// and halved again in the half where the first event can be, down to a bounded
// depth. The step then stops at the event, with the event's state set exactly
// (V = 0 at a landing, X beyond the threshold at an exit), and the next step
// starts there: the process after the event depends on nothing but that
// state (strong Markov), so what was drawn beyond it is simply dropped.
//
// Phases and events (coloured noise):
//  * stuck (V = 0, X in the band [x-*, x*]): X is OU, U does not move; the
//    phase ends when X reaches a threshold (the Brownian-bridge crossing test
//    decides at the finest depth of a stuck step, event_exit_depth). Reaching the opposite threshold ends a half
//    long excursion exactly at its regeneration state; the other one launches
//    the object in its direction.
//  * sliding in direction s: (X, V, U) is the linear Gaussian process of
//    phase_law.hpp with c = bias - s friction; the phase ends when V reaches
//    0. The force at that time decides: inside the band the object sticks,
//    beyond it V passes through 0 and slides on the other way.
// A step is refined where an event is possible: V changes sign, or comes
// within event_sigma_margin standard deviations of 0 at the step's midpoint,
// or heads for 0 fast enough at either end to reach it within the step; X
// leaves the band, or its bridge crossing probability exceeds
// event_crossing_floor. Right after a launch, V = 0 and the noise sits at the
// threshold, where the true path sticks and re-launches on a set of ever
// smaller intervals; there the refinement stops at event_launch_depth, so
// that cascade is resolved to h / 2^event_launch_depth instead of
// h / 2^event_depth (its total duration is of that order).
//
// Time is counted in leaves, h / 2^event_depth, as an integer: event times are
// leaf boundaries, sums of durations are exact, and the grid of a path stays
// aligned. Random numbers: step j of an excursion uses draw j of its stream
// (two normals) and the side draw of draw j (a third normal); midpoint r of
// the excursion uses draw r of its refinement stream (StreamPurpose::
// Refinement, same index) and its side draw, and a leaf's crossing test the
// next refinement draw's uniform. Every number is thus a pure function of
// (seed, excursion, counter): results are bitwise the same for any thread
// count and process split.
//
// White noise (tau = 0): no stuck phase and no X; V itself is linear within a
// sign, and the events are V reaching 0 and V reaching the level that ends
// the half; see event_white_step.
//
// Units are SI; the constants are built once per run by make_event_constants
// (src/engines/event/event_scheme.cpp), and the kernels below are STICKSLIP_HD, without
// allocation or exceptions.
#pragma once

/// \file
/// The inclusion engine's event scheme: exact Gaussian steps within a phase,
/// events placed at their times. The comment at the top of this header explains
/// the design.

#include <atomic>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <memory>
#include <vector>

#include "stickslip/config.hpp"
#include "stickslip/engine.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/params.hpp"
#include "stickslip/kernels/phase_law.hpp"
#include "stickslip/kernels/corrector.hpp"
#include "stickslip/random/portable_math.hpp"
#include "stickslip/random/rng.hpp"




namespace stickslip {

struct Model; // model.hpp: the parameters and their drift law, made once per run

/// Depth of the finest refinement: events are placed to h / 2^16.
inline constexpr int event_depth = 16;
/// Depth of the refinement within h / 2^6 after a launch (see above).
inline constexpr int event_launch_depth = 6;

/// A step is refined where V may come within this many conditional standard
/// deviations of 0 at its midpoint (a miss is a 6-sigma event).
inline constexpr double event_sigma_margin = 6.0;
/// A stuck piece longer than this many tau that may reach a threshold is
/// halved: first_passage takes the threshold, in its Brownian clock, as a
/// straight line, which is exact to second order in len/tau only.
inline constexpr double event_stuck_piece_max = 0.125;
/// White noise: a piece where V may touch a level is halved, whether or not
/// it does, down to h / 2^this; only below it are touches decided from the
/// piece's ends and U at a touch taken by the trapezoid. Measured (drag 0.2,
/// bias 0.3 in friction units, dt' = 0.01 and 0.03): D -1.5% and -5.5% with
/// no halving, within 0.2% (z < 1) with 3 levels, no better with 6 at 2.6
/// times the cost (docs/validation.md, "The event scheme for white noise").
inline constexpr int event_white_refine_depth = 3;
/// Bridge crossing probabilities below this count as no crossing.
inline constexpr double event_crossing_floor = 1e-12;
/// A bridge crossing exponent above this is no crossing without a uniform
/// being compared (e^-50 ~ 2e-22, far below any uniform's resolution).
inline constexpr double event_exponent_max = 50.0;

/// The laws of one refinement depth d: a step of length h / 2^d.
struct EventLevel {
    std::uint64_t leaves; ///< 2^(event_depth - d)
    double len;           ///< h / 2^d [s]
    // coloured noise
    ColoredSlideLaw slide;     ///< sliding step
    ColoredSlideBridge mid;    ///< its midpoint bridge
    double v_mid_sd;           ///< conditional sd of V at the midpoint [m/s]
    /// @{
    /// Stuck step of length len: X' = x_keep X + x_sd n with n ~ N(0, 1),
    /// x_keep = e^{-len/tau} [1] and x_sd the exact OU standard deviation
    /// [s^-1/2].
    double x_keep, x_sd;       ///< stuck step: X' = x_keep X + x_sd n
    /// @}
    OUBridge x_mid;            ///< stuck step: X at its midpoint given both ends
    double x_grow;             ///< e^{len/tau}: X e^{t/tau} is a Brownian motion (see first_passage)
    double x_u_len;            ///< tau (e^{2 len/tau} - 1) / 2 [s]: the step in that motion's clock
    double x_var_rate;         ///< its variance rate 2 / tau^2 [s^-2]
    double x_tau;              ///< tau [s]
    // white noise
    WhiteSlideLaw wslide;      ///< sliding step of (V, U)
    WhiteSlideBridge wmid;     ///< its midpoint bridge
    /// @{
    /// V - c tauL is an OU process: V e^{t/tauL} is a Brownian motion of
    /// variance rate noise in the clock tauL (e^{2t/tauL} - 1)/2 (as X for
    /// the stuck phase): v_grow = e^{len/tauL}, v_u_len = the step in that
    /// clock [s] (len and 1 without drag).
    double v_grow, v_u_len;
    /// @}
    /// 2 v_grow / (noise v_u_len) [s m^-2]: a touch between ends at distances
    /// d_a, d_b has probability exp(-d_a d_b v_touch_rate).
    double v_touch_rate;
};

/// The sliding laws of one refinement depth within one piece of a knots drift
/// law (drift_law.hpp): EventLevel's slide, mid and v_mid_sd with the piece's
/// own slope.
struct EventSlideLevel {
    ColoredSlideLaw slide;  ///< sliding step
    ColoredSlideBridge mid; ///< its midpoint bridge
    double v_mid_sd;        ///< conditional sd of V at the midpoint [m/s]
};

/// One piece of a knots drift law as the event scheme slides on it (coloured
/// noise): b(v) = -v inv_relaxation + intercept for v in [lower, upper].
struct EventDriftPiece {
    double inv_relaxation; ///< -db/dv on the piece [s^-1] (negative where the law pushes V away from 0)
    double intercept;      ///< the piece's line at v = 0 [m s^-2]
    /// @{
    /// The piece's ends [m/s]; -inf and +inf for the outer pieces (the law continues).
    double lower, upper;
    /// @}
    EventSlideLevel lv[event_depth + 1]; ///< the laws of every refinement depth
};

/// Per-run constants of the event scheme (SI units).
struct EventConstants {
    double h;             ///< step [s]
    double leaf;          ///< h / 2^event_depth [s]: the unit of time
    /// Amplitude a of the random force a X [m s^-3/2].
    double amp;           ///< a = sqrt(noise/2) (coloured)
    /// @{
    /// bias gbar and friction Delta [m s^-2], as in ModelParams.
    double bias, friction;
    /// @}
    double inv_relaxation; ///< 1/tauL [s^-1], 0 without drag
    double relaxation;     ///< tauL [s], +inf without drag
    double noise;          ///< Gamma [m^2 s^-3]
    /// @{
    /// The noise thresholds x* (upper) and x-* (lower) [s^-1/2] of the static
    /// band (coloured).
    double x_up, x_down;   ///< x*, x-* [s^-1/2] (coloured)
    /// @}
    std::uint64_t max_work; ///< runaway guard: steps and midpoints per long excursion
    bool white;             ///< tau = 0: the white-noise step (event_white_step)
    double level;           ///< white noise: the regeneration velocity levels +-c [m/s]
    /// White noise: the longest piece drawn from V = 0 [leaves]: short enough
    /// that it practically never reaches a level (6 standard deviations) and
    /// that the drag it leaves out is small (tauL/16).
    std::uint64_t leave_zero_leaves;
    /// @{
    /// A knots drift law (coloured noise): its pieces, pieces[0 .. piece_count),
    /// owned by whoever built the constants (make_event_constants); null for
    /// the affine law, whose laws are lv[d] and bias, inv_relaxation above.
    /// zero_piece is the piece just above v = 0 (a knot is at 0), knot_first
    /// [m/s] and knot_inv_spacing [s/m] locate a piece in O(1). Host memory:
    /// a device kernel takes the affine law only.
    const EventDriftPiece* pieces;
    int piece_count, zero_piece;
    double knot_first, knot_inv_spacing;
    /// @}
    /// The laws of every refinement depth d = 0 .. event_depth (steps h / 2^d).
    EventLevel lv[event_depth + 1];
};

/// Validates p and s (InvalidParameter) and builds the laws of every depth.
/// A knots drift law (coloured noise) also needs the laws of every piece:
/// they are built into *pieces, which must outlive the constants (they point
/// into it); without `pieces` such a law is refused (InvalidParameter
/// "scheme"), as is a knots law with white noise. A set `stop` (a signal)
/// ends the pieces' construction with RunInterrupted.
EventConstants make_event_constants(const Model& m, const EngineSettings& s,
                                    std::shared_ptr<const std::vector<EventDriftPiece>>* pieces = nullptr,
                                    const std::atomic<bool>* stop = nullptr);
/// make_event_constants(make_model(p), ...), for callers that hold no Model.
EventConstants make_event_constants(const ModelParams& p, const EngineSettings& s,
                                    std::shared_ptr<const std::vector<EventDriftPiece>>* pieces = nullptr,
                                    const std::atomic<bool>* stop = nullptr);

/// The piece of the knots law of c that holds velocity v [m/s] for an object
/// sliding in direction s (+1 or -1): at v = 0 the piece on s's side.
STICKSLIP_HD inline const EventDriftPiece& event_drift_piece(const EventConstants& c, double v, int s) {
    int j;
    if (v == 0.0) {
        j = s > 0 ? c.zero_piece : c.zero_piece - 1;
    } else {
        const double r = (v - c.knot_first) * c.knot_inv_spacing;
        const int last = c.piece_count - 1;
        j = !(r > 0.0) ? 0 : (r >= static_cast<double>(last) ? last : static_cast<int>(r));
        // (The quotient's rounding can put v one piece off next to a knot.)
        if (j > 0 && v < c.pieces[j].lower) --j;
        else if (j < last && v >= c.pieces[j].upper) ++j;
    }
    return c.pieces[j];
}

/// A long excursion (or a path) of the event scheme between two steps.
struct EventWalk {
    double x = 0.0;              ///< noise X [s^-1/2] (0 for white noise)
    double v = 0.0;              ///< velocity [m/s]
    double u = 0.0;              ///< displacement since the start [m]
    std::uint64_t t = 0;         ///< time since the start [leaves]
    int phase = 0;               ///< 0 stuck, +1 / -1 sliding up / down
    int dir = +1;                ///< +1: first half (+HLE), -1: second half
    bool launched = false;       ///< a launch at time `launch` limits the refinement after it
    std::uint64_t launch = 0;    ///< [leaves]
    std::uint64_t first = 0;     ///< duration of the first half, once it is over [leaves]
    std::uint64_t steps = 0;     ///< steps drawn (whole or cut short by an event)
    std::uint64_t midpoints = 0; ///< refinement midpoints drawn
};

/// One piece of a path between two events or step ends: the phase is the same
/// throughout, the state at both ends is exact. Times in leaves.
struct EventPiece {
    /// @{
    /// Start and end time of the piece since the start of the walk [leaves].
    std::uint64_t t0, t1;
    /// @}
    /// The phase throughout the piece: 0 stuck, +1 / -1 sliding up / down.
    int phase;
    /// @{
    /// The state at the start (x0, v0, u0) and at the end (x1, v1, u1): noise
    /// X [s^-1/2], velocity V [m/s], displacement U since the start [m].
    double x0, v0, u0, x1, v1, u1;
    /// @}
};

/// What observes an event-scheme path: observe(piece) for every piece
/// between two events or step ends.
template <class O>
concept PieceObserver = std::invocable<O&, const EventPiece&>;

/// Observer that ignores the path (the default of the long-excursion kernel).
struct NoPieceObserver {
    /// Does nothing with the piece.
    STICKSLIP_HD void operator()(const EventPiece&) const {}
};

/// What a step of the event scheme ended with: Running (go on), HalfDone (a
/// regeneration state was reached: the half long excursion is over) or Capped
/// (the runaway guard max_work was reached).
enum class EventStatus { Running, HalfDone, Capped };

namespace detail {

/// Probability that a Brownian bridge between a and b (same side of `level`)
/// with the given exponent factor touches the level: exp(-(a-l)(b-l) rate).
STICKSLIP_HD inline double bridge_touch(double a, double b, double level, double rate) {
    const double e = (a - level) * (b - level) * rate;
    return e > event_exponent_max ? 0.0 : std::exp(-e);
}

/// A piece of a step under refinement: the state (N components) at its
/// start a and end b, its depth d (length h / 2^d) and start time t [leaves].
template <int N>
struct RefinedPiece {
    double a[N], b[N];
    int d;
    std::uint64_t t;
};

/// Rounds a time within a step [s] to whole leaves, at least 1 and at most the step.
STICKSLIP_HD inline std::uint64_t leaves_of(const EventConstants& c, double t, std::uint64_t step_leaves) {
    const double n = t / c.leaf;
    if (!(n >= 1.0)) return 1;
    if (n >= static_cast<double>(step_leaves)) return step_leaves;
    return static_cast<std::uint64_t>(n + 0.5);
}

/// Real time [s] of the time t_u [s] in the Brownian clock tau (e^{2t/tau} -
/// 1)/2 of an OU process of relaxation time tau (the identity when tau is
/// infinite): the inverse of the clock change that first_passage and
/// white_touch_time use.
STICKSLIP_HD inline double from_brownian_clock(double t_u, double tau) {
    if (tau == HUGE_VAL) return t_u;
    return 0.5 * tau * kernel_log1p(2.0 * t_u / tau);
}

/// Can the noise, stuck through a step of level L from distance da to
/// distance db (signed: <= 0 beyond) of a threshold, reach it with a
/// probability above event_crossing_floor?
STICKSLIP_HD inline bool threshold_reachable(const EventLevel& L, double da, double db) {
    if (!(da > 0.0) || !(db > 0.0)) return true;
    constexpr double exponent_of_floor = 27.631021115928547; // -log(event_crossing_floor)
    return 2.0 * da * (db * L.x_grow) / (L.x_var_rate * L.x_u_len) <= exponent_of_floor;
}

/// The first time a Brownian bridge over [0, len] (variance rate var_rate)
/// from distance a > 0 of a level to the signed distance y <= 0 (beyond it;
/// for a bridge that touched the level and came back, the reflected end)
/// reaches the level, in [0, len]. After the time change s = t/(1 - t/len)
/// the bridge is a Brownian motion with drift y/len, whose hitting time of -a
/// is inverse Gaussian: s ~ IG(mean a len / |y|, shape a^2 / var_rate),
/// drawn from one normal and one uniform of the refinement stream (Michael,
/// Schucany, Haas 1976).
template <class RefRng>
STICKSLIP_HD inline double bridge_hitting_time(double a, double y, double len, double var_rate, RefRng& ref) {
    const NormalPair n = ref.normal2();
    const double v = ref.side_draw().y;
    double s_hit;
    if (y == 0.0) {
        s_hit = 1e300;
    } else {
        const double mu = a * len / -y, lambda = a * a / var_rate;
        // The smaller root mu (1 + r - sqrt(r (r + 2))), r = mu nu^2 / (2 lambda),
        // written without the cancellation that loses it when r is large.
        const double r = mu * n.x * n.x / (2.0 * lambda);
        const double root = mu / (1.0 + r + std::sqrt(r * (r + 2.0)));
        s_hit = v * (mu + root) <= mu ? root : mu * mu / root;
    }
    return len * s_hit / (len + s_hit); // back to the bridge's clock
}

/// Does the noise, stuck through a step of level L from distance da > 0 to
/// distance db (signed: <= 0 beyond) of a threshold, reach it? Returns the
/// time of the first passage within the step [s], or -1 if there is none.
///
/// Why this is (nearly) exact: X e^{t/tau} is a Brownian motion in the clock
/// u = tau (e^{2t/tau} - 1)/2, with variance rate 2/tau^2, and the threshold
/// becomes a boundary growing like e^{t/tau}, which over a step is a straight
/// line to second order in step/tau. A Brownian bridge crosses a straight
/// line with probability exp(-2 da db' / (sigma^2 u_len)) (db' the distance at
/// the end in the new clock); the uniform `u` decides (u < probability). The first passage time
/// of a bridge that crosses is that of the bridge reflected after it (the
/// reflection principle: the end moves to -db'), and for a bridge that ends
/// beyond the line it is, after the time change s = u/(1 - u/u_len), the
/// first passage of a Brownian motion with drift: an inverse Gaussian, drawn
/// from one normal and one uniform of the refinement stream.
template <class RefRng>
STICKSLIP_HD inline double first_passage(const EventLevel& L, double da, double db, double u, RefRng& ref) {
    if (!(da > 0.0)) return 0.0; // at (or, after rounding, beyond) the threshold already
    const double a = da, b = db * L.x_grow; // the distance at the end, in the new clock
    double y = b;
    if (b > 0.0) { // both ends short of it: cross with the bridge probability
        const double e = 2.0 * a * b / (L.x_var_rate * L.x_u_len);
        if (e > event_exponent_max || !kernel_below_exp(u, -e)) return -1.0;
        y = -b; // the reflected end
    }
    const double t_u = bridge_hitting_time(a, y, L.x_u_len, L.x_var_rate, ref);
    return from_brownian_clock(t_u, L.x_tau); // back to real time
}

/// The ends of the cubic of cubic_low: s V at both ends (va, vb [m/s]) and
/// its slopes there times the length (ma, mb [m/s]).
struct CubicEnds {
    /// @{
    /// s V at the start and end, and len s dV/dt at the start and end [m/s].
    double va, vb, ma, mb;
    /// @}
};

/// The CubicEnds of a sliding piece (see cubic_low for the arguments).
STICKSLIP_HD inline CubicEnds cubic_ends(double amp, double inv_relaxation, double len, double xa, double v_a,
                                         double xb, double v_b, double s, double cs) {
    return {s * v_a, s * v_b, s * (amp * xa + cs - v_a * inv_relaxation) * len,
            s * (amp * xb + cs - v_b * inv_relaxation) * len};
}

/// The cubic H(q) = va + ma q + c2 q^2 + c3 q^3 on q in [0, 1] that takes the
/// values and slopes of a CubicEnds at q = 0 and q = 1 (the Hermite cubic).
struct Cubic {
    /// @{
    /// The coefficients [m/s].
    double va, ma, c2, c3;
    /// @}
    /// H(q) [m/s].
    STICKSLIP_HD double at(double q) const { return va + q * (ma + q * (c2 + q * c3)); }
};

/// The Cubic through the ends e.
STICKSLIP_HD inline Cubic cubic_through(const CubicEnds& e) {
    return {e.va, e.ma, 3.0 * (e.vb - e.va) - 2.0 * e.ma - e.mb, 2.0 * (e.va - e.vb) + e.ma + e.mb};
}

/// The lowest value of s V [m/s] over a sliding piece of length len [s]
/// between the states (xa, v_a) and (xb, v_b) of (X, V), with force amplitude amp, 1/tauL and
/// the constant cs [m s^-2] of direction s (+1 or -1): given both ends, V's conditional
/// mean path is close to the cubic that matches V and its slope
/// dV/dt = a X + c - V/tauL at both ends (exactly that cubic for an
/// integrated Brownian motion); this returns the cubic's minimum on the piece,
/// ends included.
STICKSLIP_HD inline double cubic_low(double amp, double inv_relaxation, double len, double xa, double v_a,
                                     double xb, double v_b, double s, double cs) {
    const CubicEnds e = cubic_ends(amp, inv_relaxation, len, xa, v_a, xb, v_b, s, cs);
    const Cubic h = cubic_through(e);
    const double va = e.va, vb = e.vb, ma = e.ma, c2 = h.c2, c3 = h.c3;
    double lowest = va < vb ? va : vb;
    // Roots of H'(q) = ma + 2 c2 q + 3 c3 q^2 inside (0, 1), written without
    // branches (selects only) so that the SIMD lanes of event_lanes.cpp run
    // this same code: the linear root where qa = 0 (if qb != 0), else the two
    // quadratic roots where disc >= 0.
    const double qa = 3.0 * c3, qb = 2.0 * c2, qc = ma;
    const double disc = qb * qb - 4.0 * qa * qc;
    const double sq = std::sqrt(disc >= 0.0 ? disc : 0.0);
    const bool linear = qa == 0.0;
    // (Every quotient and comparison computed, then selected: one under a
    // condition could trap, a branch that the vectoriser will not remove.)
    const double q_linear = -qc / qb, q_quadratic = (-qb - sq) / (2.0 * qa);
    const double q1 = linear ? q_linear : q_quadratic;
    const double q2 = (-qb + sq) / (2.0 * qa);
    const bool real_roots = disc >= 0.0, sloped = qb != 0.0;
    const bool has1 = (linear & sloped) | (!linear & real_roots);
    const bool has2 = !linear & real_roots;
    const double h1 = h.at(q1), h2 = h.at(q2);
    lowest = (has1 & (q1 > 0.0) & (q1 < 1.0) & (h1 < lowest)) ? h1 : lowest;
    lowest = (has2 & (q2 > 0.0) & (q2 < 1.0) & (h2 < lowest)) ? h2 : lowest;
    return lowest;
}

/// Is a stuck step from xa to xb certain not to reach either threshold
/// (x_up, x_down [s^-1/2])? True where both ends are inside the band and both
/// bridge exponents 2 d_a d_b x_grow / spread (spread = x_var_rate x_u_len of
/// the step's level) exceed event_exponent_max, with a margin of 1e-6 for the
/// rounding of the quotient, which is not taken: first_passage then says "no
/// crossing" without a uniform, and the step is X' = xb and nothing more.
/// Branch-free and without a division, for the SIMD lanes (event_lanes.cpp),
/// which apply such steps and leave every other one to event_colored_step.
STICKSLIP_HD inline bool stuck_step_is_quiet(double x_up, double x_down, double x_grow, double spread, double xa,
                                             double xb) {
    const double ua = x_up - xa, ub = x_up - xb, da = xa - x_down, db = xb - x_down;
    const double limit = event_exponent_max * (1.0 + 1e-6) * spread;
    return (ua > 0.0) & (ub > 0.0) & (da > 0.0) & (db > 0.0) & (2.0 * ua * (ub * x_grow) > limit) &
           (2.0 * da * (db * x_grow) > limit);
}

/// Is a whole sliding step from (xa, v_a) to (xb, v_b) (direction s,
/// constant cs; level of length len [s] and midpoint sd v_mid_sd [m/s])
/// certain to be left whole by event_colored_step? True where s V stays above
/// 0 at the end and a lower bound of the cubic that cubic_low minimises stays
/// above event_sigma_margin midpoint standard deviations: in Hermite form the
/// cubic is va h00 + vb h01 + ma h10 + mb h11, where h00 + h01 = 1 (both >= 0)
/// and 0 <= h10, -h11 <= 4/27 on [0, 1], so it is at least min(va, vb) -
/// 4/27 (max(0, -ma) + max(0, mb)); a margin of 1e-9 of the coefficients
/// covers the rounding of cubic_low. Branch-free and without division or
/// square root, for the SIMD lanes; a step it does not pass goes to
/// event_colored_step, which decides exactly.
STICKSLIP_HD inline bool slide_step_is_quiet(double amp, double inv_relaxation, double len, double v_mid_sd,
                                             double xa, double v_a, double xb, double v_b, double s, double cs) {
    const CubicEnds e = cubic_ends(amp, inv_relaxation, len, xa, v_a, xb, v_b, s, cs);
    const double va = e.va, vb = e.vb, ma = e.ma, mb = e.mb;
    const double down = (ma < 0.0 ? -ma : 0.0) + (mb > 0.0 ? mb : 0.0);
    const double bound = (va < vb ? va : vb) - (4.0 / 27.0) * down;
    const double size = (va < 0.0 ? -va : va) + (vb < 0.0 ? -vb : vb) + (ma < 0.0 ? -ma : ma) + (mb < 0.0 ? -mb : mb);
    return (vb > 0.0) & (bound - 1e-9 * size >= 0.0 + event_sigma_margin * v_mid_sd);
}

} // namespace detail

/// One coloured-noise step of length h / 2^d0 from w, cut short at the first
/// event. `observe(piece)` sees the piece it covered.
template <class Rng, class RefRng, class Observer>
STICKSLIP_HD inline EventStatus event_colored_step(const EventConstants& c, EventWalk& w, int d0, Rng& rng,
                                                   RefRng& ref, Observer& observe) {
    if (w.steps + w.midpoints >= c.max_work) return EventStatus::Capped;
    ++w.steps;
    const NormalPair z = rng.normal2();
    const std::uint64_t t0 = w.t;
    if (w.phase == 0) {
        // Stuck: X alone, until it first reaches a threshold. The crossing and
        // its time are drawn from the ends of a piece (detail::first_passage),
        // one threshold at a time. Where both thresholds are within reach of
        // one piece (a narrow band, or a step long against tau), which is
        // reached first matters: testing one before the other would favour it
        // (measured, tau' = 0.1 at dt = 0.5 tau: M0 = 0.06 for a symmetric
        // model). Such a piece is halved at its OU bridge midpoint, and the
        // halves are tested in time order, down to the finest depth.
        const EventLevel& L0 = c.lv[d0];
        const double xa = w.x, xb = L0.x_keep * xa + L0.x_sd * z.x;
        if (detail::stuck_step_is_quiet(c.x_up, c.x_down, L0.x_grow, L0.x_var_rate * L0.x_u_len, xa, xb)) {
            // (What the refinement below does with this step, without its side draw.)
            observe(EventPiece{t0, t0 + L0.leaves, 0, xa, 0.0, w.u, xb, 0.0, w.u});
            w.x = xb;
            w.t = t0 + L0.leaves;
            return EventStatus::Running;
        }
        const NormalPair side = rng.side_draw();
        struct Piece {
            double a, b;
            int d;
            std::uint64_t t;
        };
        Piece stack[event_depth + 1];
        int top = 0;
        Piece cur{xa, xb, d0, t0};
        double u = side.y;
        double up = -1.0, down = -1.0;
        for (;;) {
            const EventLevel& L = c.lv[cur.d];
            const bool reach_up = detail::threshold_reachable(L, c.x_up - cur.a, c.x_up - cur.b);
            const bool reach_down = detail::threshold_reachable(L, cur.a - c.x_down, cur.b - c.x_down);
            if (cur.d < event_depth &&
                ((reach_up && reach_down) || ((reach_up || reach_down) && L.len > event_stuck_piece_max * c.lv[0].x_tau))) {
                if (w.steps + w.midpoints >= c.max_work) return EventStatus::Capped;
                ++w.midpoints;
                const double m = apply(L.x_mid, cur.a, cur.b, ref.normal2().x);
                stack[top++] = Piece{m, cur.b, cur.d + 1, cur.t + L.leaves / 2};
                cur = Piece{cur.a, m, cur.d + 1, cur.t};
                u = ref.side_draw().y; // the left half's uniform; a right half draws its own
                continue;
            }
            up = detail::first_passage(L, c.x_up - cur.a, c.x_up - cur.b, u, ref);
            // (1 - u for the other threshold: the two crossings are disjoint events.)
            if (up < 0.0) down = detail::first_passage(L, cur.a - c.x_down, cur.b - c.x_down, 1.0 - u, ref);
            if (up >= 0.0 || down >= 0.0 || top == 0) break;
            cur = stack[--top];
            u = ref.uniform();
        }
        if (up < 0.0 && down < 0.0) {
            observe(EventPiece{t0, t0 + L0.leaves, 0, xa, 0.0, w.u, xb, 0.0, w.u});
            w.x = xb;
            w.t = t0 + L0.leaves;
            return EventStatus::Running;
        }
        const int exit_dir = up >= 0.0 ? +1 : -1;
        const double x_exit = exit_dir > 0 ? c.x_up : c.x_down;
        const std::uint64_t t_exit = cur.t + detail::leaves_of(c, up >= 0.0 ? up : down, c.lv[cur.d].leaves);
        observe(EventPiece{t0, t_exit, 0, xa, 0.0, w.u, x_exit, 0.0, w.u});
        w.x = x_exit;
        w.t = t_exit;
        if (w.dir != 0 && exit_dir == -w.dir) return EventStatus::HalfDone; // the half's regeneration state
        w.phase = exit_dir;
        w.launched = true;
        w.launch = t_exit;
        return EventStatus::Running;
    }
    // Sliding in direction s. Where V, pushed by the noise, comes back to 0
    // and the force is inside the band, the object sticks until the noise
    // pushes it off again: V is the free sliding path V_free reflected at 0,
    // V = V_free - min(0, its running minimum) (in the direction s; exact
    // without drag, and to first order in V/tauL with it). So within a step
    // the object may stick and slip again without the step ending -- which
    // is what happens, on ever smaller scales, right after every launch from
    // a threshold. The step ends at a landing when V is at its running
    // minimum at the end of a finest piece (the object is stuck there) and
    // the noise is then away from the launching threshold: the stuck phase
    // (or, beyond the opposite threshold, a pass-through) takes over.
    //
    // With a knots drift law the step slides on the piece that holds V
    // (EventDriftPiece: its own laws, slope and intercept), and V reaching
    // either end of the piece is one more event, refined like a landing (the
    // cubic's highest and lowest values against the ends): the step ends at
    // the end of the finest piece beyond a knot, and the next one slides on
    // the new piece. A piece next to v = 0 has 0 as its lower end in s V,
    // which is the landing; beyond it the law is continued by the piece's line
    // for at most one leaf (the law is continuous, so that changes b by its
    // slope's jump times V's move within a leaf; within h / 2^event_launch_depth
    // right after a launch, where the refinement stops there).
    const int s = w.phase;
    const EventDriftPiece* law_piece = c.pieces ? &event_drift_piece(c, w.v, s) : nullptr;
    const double cs = (law_piece ? law_piece->intercept : c.bias) - s * c.friction;
    const double inv_relaxation = law_piece ? law_piece->inv_relaxation : c.inv_relaxation;
    // The piece's ends in s V: [piece_bottom, piece_top], piece_bottom >= 0 (0: it can land).
    const double piece_bottom = law_piece ? (s > 0 ? law_piece->lower : -law_piece->upper) : 0.0;
    const double piece_top = law_piece ? (s > 0 ? law_piece->upper : -law_piece->lower) : HUGE_VAL;
    const NormalPair side = rng.side_draw();
    using Node = detail::RefinedPiece<3>;
    Node stack[event_depth + 1];
    int top = 0;
    const EventLevel& L0 = c.lv[d0];
    const std::uint64_t t_end = t0 + L0.leaves;
    // U within the refinement is counted from the step's start, and w.u is
    // added only where a state leaves the step: the midpoint bridge weighs
    // U_b - U_a by about 1 / (a len^2) (the displacement tells about the
    // noise), so at a fine depth the rounding of an absolute displacement
    // (|U| eps, 2e-15 m at U = 18 m) swamps the information it carries
    // (a sd(X) len^2, 1e-21 m at len = 5e-9 s) and the bridge draws X
    // arbitrarily far from its ends: measured, pure dry friction tau' = 1
    // at dt = 3e-4 s, X jumped from 1.4 to -7.9 within one leaf and D came
    // out 2e4 times too large (docs/validation.md, "The event scheme at
    // fine steps").
    const double u_start = w.u;
    Node cur{{w.x, w.v, 0.0}, {0.0, 0.0, 0.0}, d0, t0};
    {
        const double n[3] = {z.x, z.y, side.x};
        apply(law_piece ? law_piece->lv[d0].slide : L0.slide, cur.a, cs, n, cur.b);
    }
    const Node whole = cur;
    const std::uint64_t window = std::uint64_t{1} << (event_depth - event_launch_depth);
    double floor = 0.0; // min(0, running minimum of s V_free): V = V_free - s floor
    double du = 0.0;    // the displacement that reflection adds, up to t_end [m]
    bool landed = false, crossed = false;
    // The observer sees every piece of the refinement that is not halved, in
    // time order, with its exact ends: a step that launches from V = 0 and
    // lands again has V > 0 in between, which one piece from end to end would
    // interpolate as 0 (measured: P(V = 0) +0.011 at tau = 1e-2 s, dt = 1e-3
    // s). Within a piece the reflection is the one at its start (V = V_free -
    // s floor, U = U_free - s int floor dt; floor_leaves: that integral so far
    // [m/s leaves]).
    double floor_leaves = 0.0;
    auto emit = [&](const Node& piece, double floor_before, double floor_after) {
        const std::uint64_t tb = piece.t + c.lv[piece.d].leaves;
        const double i_b = floor_leaves + floor_before * static_cast<double>(tb - piece.t);
        observe(EventPiece{piece.t, tb, s, piece.a[0], piece.a[1] - s * floor_before,
                           u_start + (piece.a[2] - s * c.leaf * floor_leaves), piece.b[0],
                           piece.b[1] - s * floor_after, u_start + (piece.b[2] - s * c.leaf * i_b)});
        floor_leaves = i_b;
    };
    for (;;) {
        const EventLevel& L = c.lv[cur.d];
        const double v_mid_sd = law_piece ? law_piece->lv[cur.d].v_mid_sd : L.v_mid_sd;
        const double low = s * cur.b[1] <= floor ? s * cur.b[1] : detail::cubic_low(c.amp, inv_relaxation, L.len, cur.a[0], cur.a[1], cur.b[0],
                                                                          cur.b[1], s, cs);
        const double floor_before = floor;
        // Near the lower end: the landing at 0 (the reflection's floor), or a knot.
        bool near = low < (piece_bottom > 0.0 ? piece_bottom : floor) + event_sigma_margin * v_mid_sd;
        if (piece_top < HUGE_VAL) { // near the upper knot, V lifted by the reflection
            const double high = s * cur.b[1] >= piece_top + floor
                                    ? s * cur.b[1]
                                    : -detail::cubic_low(c.amp, inv_relaxation, L.len, cur.a[0], cur.a[1], cur.b[0],
                                                         cur.b[1], -s, cs);
            near = near || high - floor > piece_top - event_sigma_margin * v_mid_sd;
        }
        if (near) {
            const int max_depth = w.launched && cur.t < w.launch + window ? event_launch_depth : event_depth;
            if (cur.d >= max_depth && piece_bottom > 0.0) {
                // A knots law away from 0: no landing, no reflection (floor = 0).
                const double sv = s * cur.b[1];
                if (sv <= 0.0) { // past the next piece and 0 within one finest piece: a landing there
                    landed = true;
                    emit(cur, floor_before, floor);
                    break;
                }
                if (sv < piece_bottom || sv > piece_top) {
                    crossed = true; // on the next piece at the end of this one
                    emit(cur, floor_before, floor);
                    break;
                }
            } else if (cur.d >= max_depth) {
                const double m = low < s * cur.b[1] ? low : s * cur.b[1];
                const std::uint64_t t_b = cur.t + L.leaves;
                if (m < floor) { // a new minimum: the reflection lifts the rest of the step
                    du += s * (floor - m) * c.leaf * static_cast<double>(t_end - t_b);
                    floor = m;
                }
                if (s * cur.b[1] <= floor && !(s > 0 ? cur.b[0] > c.x_up : cur.b[0] < c.x_down)) {
                    landed = true; // stuck at the end of this piece
                    emit(cur, floor_before, floor);
                    break;
                }
                if (s * cur.b[1] - floor > piece_top) {
                    crossed = true; // on the next piece at the end of this one
                    emit(cur, floor_before, floor);
                    break;
                }
            } else {
                const NormalPair n01 = ref.normal2();
                const NormalPair n2 = ref.side_draw();
                ++w.midpoints;
                const double n[3] = {n01.x, n01.y, n2.x};
                // U relative to the start of the interval (translation invariance).
                const double a_rel[3] = {cur.a[0], cur.a[1], 0.0};
                const double b_rel[3] = {cur.b[0], cur.b[1], cur.b[2] - cur.a[2]};
                double m[3];
                apply(law_piece ? law_piece->lv[cur.d].mid : L.mid, a_rel, b_rel, cs, n, m);
                m[2] += cur.a[2];
                Node right{{m[0], m[1], m[2]}, {cur.b[0], cur.b[1], cur.b[2]}, cur.d + 1, cur.t + L.leaves / 2};
                stack[top++] = right;
                cur = Node{{cur.a[0], cur.a[1], cur.a[2]}, {m[0], m[1], m[2]}, cur.d + 1, cur.t};
                continue;
            }
        }
        emit(cur, floor_before, floor);
        if (top == 0) break;
        cur = stack[--top];
    }
    if (crossed) { // the step ends at the end of cur, sliding on
        const std::uint64_t te = cur.t + c.lv[cur.d].leaves;
        w.x = cur.b[0];
        w.v = cur.b[1] - s * floor;
        w.u = u_start + (cur.b[2] + du - s * (-floor) * c.leaf * static_cast<double>(t_end - te));
        w.t = te;
        return EventStatus::Running;
    }
    if (!landed) {
        const double v_end = whole.b[1] - s * floor, u_end = u_start + (whole.b[2] + du);
        w.x = whole.b[0];
        w.v = v_end;
        w.u = u_end;
        w.t = t_end;
        return EventStatus::Running;
    }
    // Stuck at the end of the piece: V = 0 there; the noise decides.
    const std::uint64_t te = cur.t + c.lv[cur.d].leaves;
    const double u_e = u_start + (cur.b[2] + du - s * (-floor) * c.leaf * static_cast<double>(t_end - te));
    w.x = cur.b[0];
    w.v = 0.0;
    w.u = u_e;
    w.t = te;
    if (w.x >= c.x_down && w.x <= c.x_up) {
        w.phase = 0; // sticks
        w.launched = false;
    } else {
        w.phase = -s; // beyond the opposite threshold: passes through 0
        w.launched = true;
        w.launch = te;
    }
    return EventStatus::Running;
}

namespace detail {

/// White noise: V over a time r [s] from V = 0, drawn from the normal n and
/// the uniforms u_sign and u_max (see event_white_step). Exact without drag
/// and bias: |V| is then a reflected Brownian motion with drift -friction,
/// whose value at r has the law of the running maximum of that motion
/// (Levy), drawn from its endpoint and the bridge-maximum formula; the sign
/// is a fair coin, independent of |V|. With a bias b each side pulls back
/// with its own drift (friction -+ b), and the coin is tilted to
/// 1/2 + b sqrt(pi r / (32 noise)) so that E[V(r)] = b r + O(r^{3/2}), as
/// for the true motion (the side drifts alone give E[V(r)] = b r / 2 at this
/// order, the tilt the other half); E[V(r)^2] is right to O(r^{3/2}) too. The
/// drag, of order |V| / tauL, is left out over such a short piece.
STICKSLIP_HD inline double white_leave_zero(const EventConstants& c, double r, double n, double u_sign, double u_max) {
    double p_plus = 0.5 + c.bias * std::sqrt(3.141592653589793 * r / (32.0 * c.noise));
    p_plus = p_plus < 0.0 ? 0.0 : (p_plus > 1.0 ? 1.0 : p_plus);
    const double s = u_sign <= p_plus ? 1.0 : -1.0;
    const double pull = c.friction - s * c.bias;
    const double end = -pull * r + std::sqrt(c.noise * r) * n;
    const double m = 0.5 * (end + std::sqrt(end * end - 2.0 * c.noise * r * kernel_log(u_max)));
    return s * m;
}

/// White noise: the time [s] within a piece of level L at which V first
/// touches a level, from distance a > 0 to the clock-changed end distance y
/// <= 0 (see EventLevel::v_grow): the Brownian bridge's hitting time, back
/// in real time.
template <class RefRng>
STICKSLIP_HD inline double white_touch_time(const EventConstants& c, const EventLevel& L, double a, double y,
                                            RefRng& ref) {
    return from_brownian_clock(bridge_hitting_time(a, y, L.v_u_len, c.noise, ref), c.relaxation);
}

} // namespace detail

/// A touch whose bridge exponent exceeds this has a probability below
/// event_crossing_floor (e^-27.63 = 1e-12): no touch.
inline constexpr double kWhiteNoTouch = 27.631021115928547;

/// One white-noise step of length h / 2^d0 from w, cut short at the first
/// event (theory.md, section 10).
///
/// While V keeps its sign s, dV = (bias - s friction - V/tauL) dt +
/// sqrt(noise) dW is linear and (V, U) is exactly Gaussian over the step
/// (phase_law.hpp): the step's end is drawn from it (the two normals of the
/// step's draw). Two events can cut it short: V reaching 0, and V reaching the
/// level -dir c that ends the half. Whether the path touched a level between
/// the two ends is decided exactly (for a constant drift; to first order in
/// h/tauL with drag) by the Brownian-bridge probability exp(-2 d_a d_b /
/// (noise h)) against the step's side uniform, and the time of the touch is
/// drawn from the bridge's first-passage law (bridge_hitting_time), so no
/// refinement is needed; only a piece that can reach both levels is halved
/// at its bridge midpoint, its halves tested in time order. U at the touch is
/// the trapezoid over the piece cut there. At a touch of the half's level the
/// half is over (V set to the level). From V = 0 the object leaves at once,
/// the rest of the step drawn by detail::white_leave_zero (U by the
/// trapezoid), so the many zeros of V near a touch need no steps of their
/// own. Weak order 1 (docs/validation.md, "The event scheme for white noise").
template <class Rng, class RefRng, class Observer>
STICKSLIP_HD inline EventStatus event_white_step(const EventConstants& c, EventWalk& w, int d0, Rng& rng, RefRng& ref,
                                                 Observer& observe) {
    if (w.steps + w.midpoints >= c.max_work) return EventStatus::Capped;
    ++w.steps;
    const NormalPair z = rng.normal2();
    const EventLevel& L0 = c.lv[d0];
    const std::uint64_t t0 = w.t, t_end = t0 + L0.leaves;
    const bool has_level = w.dir != 0;
    const double level = -w.dir * c.level; // the level that ends the half
    const double v_start = w.v, u_start = w.u;
    // The rest of the step from V = 0 at time t (leaves); HalfDone if it ends beyond the level.
    // (The step then ends after that piece, which may be before t_end.)
    auto leave_zero = [&](std::uint64_t t, double u, double n, double u_sign, double u_max) {
        const std::uint64_t t_stop = t_end - t > c.leave_zero_leaves ? t + c.leave_zero_leaves : t_end;
        const double r = c.leaf * static_cast<double>(t_stop - t);
        const double v = detail::white_leave_zero(c, r, n, u_sign, u_max);
        const double u_next = u + 0.5 * r * v;
        const bool beyond = has_level && (level < 0.0 ? v <= level : v >= level);
        const double v_next = beyond ? level : v;
        observe(EventPiece{t, t_stop, v_next > 0 ? 1 : -1, 0.0, 0.0, u, 0.0, v_next, u_next});
        w.v = v_next;
        w.u = u_next;
        w.t = t_stop;
        w.phase = v_next > 0 ? 1 : (v_next < 0 ? -1 : 0);
        return beyond ? EventStatus::HalfDone : EventStatus::Running;
    };
    if (v_start == 0.0) {
        const double u_sign = rng.side_uniform();
        const double u_max = ref.uniform();
        return leave_zero(t0, u_start, z.x, u_sign, u_max);
    }
    const int s = v_start > 0.0 ? 1 : -1;
    const double cs = c.bias - s * c.friction;
    const bool level_here = has_level && (level > 0.0) == (s > 0); // on this side of 0
    using Piece = detail::RefinedPiece<2>;
    Piece stack[event_depth + 1];
    int top = 0;
    // U counted from the step's start within it, as in event_colored_step
    // (the bridge weighs U_b - U_a by 1 / len: an absolute U's rounding would
    // swamp it at fine depths).
    Piece cur{{v_start, 0.0}, {0.0, 0.0}, d0, t0};
    {
        const double n[2] = {z.x, z.y};
        apply(L0.wslide, cur.a, cs, n, cur.b);
    }
    const double whole_b[2] = {cur.b[0], cur.b[1]};
    // Most steps are far from both levels: no touch is possible, and the
    // step's side uniform is not even computed.
    {
        const double rate = L0.v_touch_rate;
        const double ez = s * cur.b[0] <= 0.0 ? 0.0 : cur.a[0] * cur.b[0] * rate;
        const double el = !level_here ? 1e300 : (s * (cur.b[0] - level) >= 0.0 ? 0.0 : (cur.a[0] - level) * (cur.b[0] - level) * rate);
        if (ez > kWhiteNoTouch && el > kWhiteNoTouch) {
            observe(EventPiece{t0, t_end, s, 0.0, v_start, u_start, 0.0, whole_b[0], u_start + whole_b[1]});
            w.v = whole_b[0];
            w.u = u_start + whole_b[1];
            w.t = t_end;
            w.phase = s;
            return EventStatus::Running;
        }
    }
    // The step's side uniform decides a touch only for a step at the finest
    // depth; any other step where a touch is possible is halved first.
    double u = d0 < event_depth ? 0.0 : rng.side_uniform();
    double hit = -1.0; // time of the touch within the current piece [s]
    bool hit_level = false;
    for (;;) {
        const EventLevel& L = c.lv[cur.d];
        const double rate = L.v_touch_rate;
        const double pz = s * cur.b[0] <= 0.0 ? 1.0 : detail::bridge_touch(cur.a[0], cur.b[0], 0.0, rate);
        const double pl = !level_here ? 0.0
                          : (s * (cur.b[0] - level) >= 0.0 ? 1.0 : detail::bridge_touch(cur.a[0], cur.b[0], level, rate));
        const bool both = pz > event_crossing_floor && pl > event_crossing_floor;
        const bool near = cur.d < d0 + event_white_refine_depth && (pz > event_crossing_floor || pl > event_crossing_floor);
        if (cur.d < event_depth && (both || near)) {
            if (w.steps + w.midpoints >= c.max_work) return EventStatus::Capped;
            ++w.midpoints;
            const NormalPair nm = ref.normal2();
            const double n[2] = {nm.x, nm.y};
            const double a_rel[2] = {cur.a[0], 0.0};
            const double b_rel[2] = {cur.b[0], cur.b[1] - cur.a[1]};
            double m[2];
            apply(L.wmid, a_rel, b_rel, cs, n, m);
            m[1] += cur.a[1];
            stack[top++] = Piece{{m[0], m[1]}, {cur.b[0], cur.b[1]}, cur.d + 1, cur.t + L.leaves / 2};
            cur = Piece{{cur.a[0], cur.a[1]}, {m[0], m[1]}, cur.d + 1, cur.t};
            u = ref.side_draw().y;
            continue;
        }
        // (1 - u for the level: the two touches are disjoint events.)
        if (pz >= 1.0 || u < pz) {
            const double db = s * cur.b[0] * L.v_grow; // the end's distance, in the Brownian clock
            hit = detail::white_touch_time(c, L, s * cur.a[0], db <= 0.0 ? db : -db, ref);
        } else if (pl > 0.0 && (pl >= 1.0 || 1.0 - u < pl)) {
            const double da = s * (level - cur.a[0]), db = s * (level - cur.b[0]) * L.v_grow;
            hit = detail::white_touch_time(c, L, da, db <= 0.0 ? db : -db, ref);
            hit_level = true;
        }
        if (hit >= 0.0) break;
        // No touch in this piece: the observer sees it with its exact ends.
        observe(EventPiece{cur.t, cur.t + L.leaves, s, 0.0, cur.a[0], u_start + cur.a[1], 0.0, cur.b[0],
                           u_start + cur.b[1]});
        if (top == 0) break;
        cur = stack[--top];
        u = ref.uniform();
    }
    if (hit < 0.0) { // no event: the whole step
        w.v = whole_b[0];
        w.u = u_start + whole_b[1];
        w.t = t_end;
        w.phase = s;
        return EventStatus::Running;
    }
    const std::uint64_t t_hit = cur.t + detail::leaves_of(c, hit, c.lv[cur.d].leaves);
    const double v_hit = hit_level ? level : 0.0;
    const double u_hit = u_start + (cur.a[1] + 0.5 * c.leaf * static_cast<double>(t_hit - cur.t) * (cur.a[0] + v_hit));
    observe(EventPiece{cur.t, t_hit, s, 0.0, cur.a[0], u_start + cur.a[1], 0.0, v_hit, u_hit});
    w.v = v_hit;
    w.u = u_hit;
    w.t = t_hit;
    if (hit_level) {
        w.phase = s;
        return EventStatus::HalfDone;
    }
    w.phase = 0;
    if (t_hit == t_end) return EventStatus::Running; // at 0 at the step's end: the next step leaves it
    // (One draw at a time: the order of a call's arguments is unspecified.)
    const double n_leave = ref.normal2().x;
    const double u_sign = ref.side_draw().y;
    const double u_max = ref.uniform();
    return leave_zero(t_hit, u_hit, n_leave, u_sign, u_max);
}

/// Puts w at the start of half `dir` at its current time: it launches from
/// (x*, 0) upwards (+1) or from (x-*, 0) downwards (-1); white noise: it
/// starts at V = +c (+1) or -c (-1).
STICKSLIP_HD inline void event_start_half(const EventConstants& c, EventWalk& w, int dir) {
    w.dir = dir;
    if (c.white) { // from V = dir c (the levels +-c of white noise)
        w.v = dir * c.level;
        w.x = 0.0;
        w.phase = dir;
        w.launched = false;
        return;
    }
    w.v = 0.0;
    w.x = dir > 0 ? c.x_up : c.x_down;
    w.phase = dir;
    w.launched = true;
    w.launch = w.t;
}

/// The outcome of a finished (or capped) walk.
STICKSLIP_HD inline ExcursionOutcome event_walk_outcome(const EventConstants& c, const EventWalk& w, bool capped) {
    ExcursionOutcome o;
    o.first_half = c.leaf * static_cast<double>(w.first);
    o.displacement = w.u;
    o.duration = c.leaf * static_cast<double>(w.t);
    o.work = w.steps + w.midpoints;
    o.capped = capped;
    return o;
}

template <class Rng, class RefRng, class Observer>
STICKSLIP_HD inline EventStatus event_step(const EventConstants& c, EventWalk& w, int d0, Rng& rng, RefRng& ref,
                                           Observer& observe);

/// One long excursion (+HLE then -HLE) of the event scheme; `observe` sees
/// every piece of it.
template <class Rng, class RefRng, PieceObserver Observer = NoPieceObserver>
STICKSLIP_HD inline ExcursionOutcome event_long_excursion(const EventConstants& c, Rng& rng, RefRng& ref,
                                                          Observer&& observe = Observer{}) {
    EventWalk w;
    event_start_half(c, w, +1);
    EventStatus st;
    while ((st = event_step(c, w, 0, rng, ref, observe)) == EventStatus::Running) {
    }
    if (st == EventStatus::HalfDone) {
        w.first = w.t;
        event_start_half(c, w, -1);
        while ((st = event_step(c, w, 0, rng, ref, observe)) == EventStatus::Running) {
        }
    }
    return event_walk_outcome(c, w, st == EventStatus::Capped);
}

/// One step of event_step (coloured noise) with the martingale of `mart`
/// (kernels/corrector.hpp): g at the step's start state, times the noise's
/// exact martingale increment over the step, e^{T/tau} X_T - X_0, T the
/// step's length, cut short by an event or not (T is a stopping time and g
/// is fixed before the step, so the sum is a martingale of the exact
/// process; the scheme's own approximations, event times to a leaf, are far
/// below any standard error).
template <class Rng, class RefRng, class Martingale>
STICKSLIP_HD inline EventStatus event_step_with(const EventConstants& c, EventWalk& w, Rng& rng, RefRng& ref,
                                                Martingale& mart) {
    const double x0 = w.x, v0 = w.v;
    const std::uint64_t t0 = w.t;
    NoPieceObserver none;
    const EventStatus st = event_colored_step(c, w, 0, rng, ref, none);
    if (st == EventStatus::Capped) return st;
    const EventLevel& L0 = c.lv[0];
    const std::uint64_t leaves = w.t - t0;
    // A whole step's growth factor and variance are the level's; a step cut
    // short takes its own (one exponential, at an event).
    const double grow = leaves == L0.leaves ? L0.x_grow : std::exp(c.leaf * static_cast<double>(leaves) / L0.x_tau);
    const double var = leaves == L0.leaves ? L0.x_var_rate * L0.x_u_len : (grow * grow - 1.0) / L0.x_tau;
    mart.add(x0, v0, grow * w.x - x0, var);
    return st;
}

/// One long excursion of the event scheme (coloured noise) with the
/// martingale of the corrector g in the outcome (martingale, martingale_qv).
/// The draws, and so U and t, are event_long_excursion's, bit for bit.
template <class Rng, class RefRng>
STICKSLIP_HD inline ExcursionOutcome event_long_excursion_with(const EventConstants& c, Rng& rng, RefRng& ref,
                                                               const CorrectorTable& g) {
    MartingaleSums mart{g};
    EventWalk w;
    event_start_half(c, w, +1);
    EventStatus st;
    while ((st = event_step_with(c, w, rng, ref, mart)) == EventStatus::Running) {
    }
    if (st == EventStatus::HalfDone) {
        w.first = w.t;
        event_start_half(c, w, -1);
        while ((st = event_step_with(c, w, rng, ref, mart)) == EventStatus::Running) {
        }
    }
    ExcursionOutcome o = event_walk_outcome(c, w, st == EventStatus::Capped);
    o.martingale = mart.m;
    o.martingale_qv = mart.q;
    return o;
}

/// One step of length h / 2^d0 of the event scheme.
template <class Rng, class RefRng, class Observer>
STICKSLIP_HD inline EventStatus event_step(const EventConstants& c, EventWalk& w, int d0, Rng& rng, RefRng& ref,
                                           Observer& observe) {
    if (c.white) return event_white_step(c, w, d0, rng, ref, observe);
    return event_colored_step(c, w, d0, rng, ref, observe);
}

/// Advances w to time t_end [leaves], exactly: steps of h while a whole one
/// fits, then the binary digits of what is left (h/2, h/4, ...), each cut
/// short by its events as usual. For paths of a given length and fixed
/// observation times. Returns Running, or Capped, or HalfDone when the walk
/// reaches a regeneration state before t_end (only walks that track a half).
template <class Rng, class RefRng, class Observer>
STICKSLIP_HD inline EventStatus event_advance_to(const EventConstants& c, EventWalk& w, std::uint64_t t_end, Rng& rng,
                                                 RefRng& ref, Observer& observe) {
    while (w.t < t_end) {
        const std::uint64_t left = t_end - w.t;
        int d = 0;
        while (d < event_depth && c.lv[d].leaves > left) ++d;
        const EventStatus st = event_step(c, w, d, rng, ref, observe);
        if (st != EventStatus::Running) return st;
    }
    return EventStatus::Running;
}

/// A walk that starts at noise x0 [s^-1/2] and velocity v0 [m/s] (a path, not
/// a long excursion): sliding in v0's direction, or at V = 0 stuck inside the
/// band and launched beyond it. The walk's `dir` is 0: no half is tracked
/// (reaching a threshold never ends it).
STICKSLIP_HD inline EventWalk event_walk_from(const EventConstants& c, double x0, double v0) {
    EventWalk w;
    w.x = x0;
    w.v = v0;
    w.dir = 0;
    if (v0 != 0.0) w.phase = v0 > 0 ? +1 : -1;
    else if (x0 > c.x_up) w.phase = +1;
    else if (x0 < c.x_down) w.phase = -1;
    else w.phase = 0;
    w.launched = w.phase != 0 && v0 == 0.0;
    return w;
}

} // namespace stickslip
