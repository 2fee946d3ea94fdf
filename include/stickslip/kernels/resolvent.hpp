// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/resolvent.hpp -- the differential-inclusion (time-stepping) engine.
//
// One step of length h (theory.md, section 5): draw the exact OU pair
// (mean of X over the step, X at its end), form the free-flight velocity
// f = V + h (b(V) + a*xbar), and apply the resolvent of h*dphi, the soft
// threshold V' = f - clamp(f, -h Delta, h Delta): the object sticks exactly
// when |f| <= h Delta. Displacement uses the left-point rule U += h V.
// (The paper's printed update pushes the wrong way; this is the correct one.)
//
// With a static friction Delta_s > Delta (theory.md, section 5) the implicit
// step has two solutions for f in (h Delta, h Delta_s], and the state
// decides: at rest the object stays at rest while |f| <= h Delta_s and else
// starts with V' = f -+ h Delta (the jump in acceleration at the start of a
// slip); sliding, the soft threshold with h Delta applies, except that a
// velocity that passes through 0 within the step stops there when the free
// flight from rest, the force alone, lies in the static band. At Delta_s =
// Delta both rules are the soft threshold's, bit for bit, so the runs of the
// one-coefficient model take the unchanged branch.
//
// For white noise (tau = 0) the force over a step is sqrt(Gamma h) z / h.
//
// Everything here is a small inline function without allocation, exceptions or
// virtual calls, marked STICKSLIP_HD, so the same code can be compiled for a GPU.
// The constants are computed once per run by make_resolvent_constants, which
// validates its input; the kernels trust them.
#pragma once

/// \file
/// The time-stepping (differential-inclusion) engine: per-run constants and
/// per-step kernels. The comment at the top of this header explains the design.

#include <cmath>
#include <concepts>
#include <cstdint>
#include <type_traits>

#include "stickslip/config.hpp"
#include "stickslip/drift_law.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/kernels/corrector.hpp"
#include "stickslip/kernels/noise.hpp"
#include "stickslip/params.hpp"
#include "stickslip/random/portable_math.hpp"

namespace stickslip {

struct Model; // model.hpp: the parameters and their drift law, made once per run

/// Per-run constants of the inclusion engine (SI units). Built once by
/// make_resolvent_constants; every per-step quantity is precomputed here so the
/// step has no division or exponential.
struct ResolventConstants {
    double h;          ///< time step [s]
    double keep;       ///< 1 - h/relaxation: free-flight factor on V
    double h_bias;     ///< h * bias [m/s]
    double h_amp;      ///< colored: h * a [m/s per s^-1/2]; white: sqrt(noise h) [m/s]
    double h_friction; ///< h * friction [m/s]: the sticking band of f
    double h_static;   ///< h * static friction [m/s]: the band of f that holds an object at rest
    double h_rest;     ///< h * b(0) [m/s]: the drift's part of the free flight from rest
    bool static_band;  ///< static friction above friction (then h_static > h_friction)
    bool white;        ///< tau == 0
    OUStep ou;         ///< exact OU step (colored only)
    double f_x;        ///< colored: h_amp * ou.mean_coef, the free flight's weight on X [m s^1/2 / s]
    double f_z;        ///< colored: h_amp * ou.l11, its weight on the first normal [m/s]
    double x_up;       ///< x*  [s^-1/2] (colored only)
    double x_down;     ///< x-* [s^-1/2] (colored only)
    double bridge_rate;///< tau^2 / h [s]: Brownian-bridge crossing exponent factor
    StopRule rule;     ///< resolved rule: Bridge or Stuck (colored only)
    double level;      ///< white only: regeneration velocity level c > 0 [m/s]
    std::uint64_t max_steps; ///< runaway guard per long excursion
    /// A law other than the affine one (then keep and h_bias are unused and
    /// the free flight is V + h b(V), the paper's Algorithm 3 for any b).
    bool knots_law;
    DriftLaw drift;    ///< b(v) [m s^-2] when knots_law
};

/// Validates p and s (throws InvalidParameter) and precomputes the constants.
ResolventConstants make_resolvent_constants(const Model& m, const EngineSettings& s);
/// make_resolvent_constants(make_model(p), s), for callers that hold no Model.
ResolventConstants make_resolvent_constants(const ModelParams& p, const EngineSettings& s);

/// Default white-noise regeneration level c [m/s]: half the smaller of the
/// dry-friction velocity scale 0.7*noise/friction and the viscous one
/// sqrt(noise*relaxation/2), so that both levels are visited often.
double white_level_default(const Model& m);
/// white_level_default(make_model(p)).
double white_level_default(const ModelParams& p);

/// Resolvent of h*dphi: f - clamp(f, -band, band), i.e. f - band above the band,
/// f + band below it and exactly 0 inside (band >= 0). Written as
/// max(f - band, min(f + band, 0)): two independent adds, then a min and a max,
/// which compile to single instructions (std::fmax/fmin would be library calls,
/// to honour their NaN rules), so the step's dependency chain stays short.
STICKSLIP_HD inline double soft_threshold(double f, double band) {
    const double up = f - band, down = f + band;
    const double lower = down < 0.0 ? down : 0.0;
    return up > lower ? up : lower;
}

/// The friction's step with a static band (c.static_band), given the free
/// flight f from v and the free flight from rest f0 (the force alone over the
/// step) [m/s]: at rest (v == 0), stay while |f| <= h Delta_s, else start
/// with f -+ h Delta; sliding, the soft threshold with h Delta, and a
/// velocity that would pass through 0 stops there when |f0| <= h Delta_s.
STICKSLIP_HD inline double static_friction_step(const ResolventConstants& c, double v, double f, double f0) {
    if (v == 0.0) return f > c.h_static ? f - c.h_friction : (f < -c.h_static ? f + c.h_friction : 0.0);
    const double out = soft_threshold(f, c.h_friction);
    const bool through = v > 0.0 ? out < 0.0 : out > 0.0;
    return through && f0 <= c.h_static && f0 >= -c.h_static ? 0.0 : out;
}

/// The friction's step of either model: the soft threshold with h Delta, or
/// static_friction_step when the static friction is higher. `rest_flight()`
/// gives the free flight from rest, asked for only then.
template <class RestFlight>
STICKSLIP_HD inline double friction_step(const ResolventConstants& c, double v, double f, RestFlight&& rest_flight) {
    if (!c.static_band) return soft_threshold(f, c.h_friction);
    return static_friction_step(c, v, f, rest_flight());
}

/// Exponent above which the bridge crossing probability exp(-e) < 2e-22 is
/// treated as 0 (saves an exponential and a draw on most stuck steps).
inline constexpr double bridge_exponent_cutoff = 50.0;

/// Probability that a Brownian bridge with variance rate 2/tau^2 between x0 and
/// x1 (both on the same side of `level`) touches `level` within the step.
STICKSLIP_HD inline double bridge_crossing_probability(const ResolventConstants& c, double x0,
                                                       double x1, double level) {
    const double e = (x0 - level) * (x1 - level) * c.bridge_rate;
    return e > bridge_exponent_cutoff ? 0.0 : std::exp(-e);
}

/// The bridge test of rule Q: whether the side uniform of the last draw is
/// below bridge_crossing_probability(c, x0, x1, level), i.e. the bridge
/// touched the level. The exponential is taken through kernel_below_exp
/// (portable_math.hpp): std::exp on the host, as bridge_crossing_probability;
/// on a CUDA device so that the decision is the correctly rounded exp's.
template <class Rng>
STICKSLIP_HD inline bool bridge_crossed(const ResolventConstants& c, double x0, double x1, double level, Rng& rng) {
    const double e = (x0 - level) * (x1 - level) * c.bridge_rate;
    return !(e > bridge_exponent_cutoff) && kernel_below_exp(rng.side_uniform(), -e);
}

/// Colored noise with a static band: the velocity at the end of a step that
/// starts at rest [m/s], given the noise x at its start and x_next at its
/// end [s^-1/2] and the free flight f [m/s]. The object starts when the force
/// leaves the static band within the step: |f| > h Delta_s (its mean over
/// the step), or X reaches an edge (x_next beyond it, or the Brownian bridge
/// between x and x_next touching it: the side uniform of the step's draw)
/// with f beyond h Delta on that side; it then slides with f -+ h Delta.
/// Testing the mean force alone would start late by the bridge's excursions
/// past the edge, an error of order sqrt(h) that the one-coefficient model
/// does not see (its acceleration at the edge is 0) and the static band does
/// (the slip starts with acceleration Delta_s - Delta): measured, the Fig. 2
/// case at Delta_s = 1.5 Delta, M0 -3.7% at dt 1e-3 s and -2.0% at 3e-4 s.
/// Both edges' tests read the step's one side uniform, as rule Q's stop test
/// does (its edge's test here then agrees with it); the two crossing
/// probabilities are both far from 0 only when the band is a few noise steps
/// wide, a step far too coarse for the scheme anyway.
template <class Rng>
STICKSLIP_HD inline double resolvent_static_start(const ResolventConstants& c, double x, double x_next, double f,
                                                  Rng& rng) {
    if (f > c.h_static) return f - c.h_friction;
    if (f < -c.h_static) return f + c.h_friction;
    if (f > c.h_friction && (x_next >= c.x_up || bridge_crossed(c, x, x_next, c.x_up, rng))) return f - c.h_friction;
    if (f < -c.h_friction && (x_next <= c.x_down || bridge_crossed(c, x, x_next, c.x_down, rng)))
        return f + c.h_friction;
    return 0.0;
}

/// One colored-noise step from (x, v): writes the end-of-step noise and the
/// free-flight velocity f; returns nothing else so the caller can test f first.
/// f = keep v + h (bias + a xbar) with xbar = mean_coef x + l11 z1, the forcing
/// folded into two precomputed weights and added last as one sum. The sums are
/// grouped so that the chains carried from step to step (X and V) are one
/// multiply and one add each; the random terms are computed off the chain.
STICKSLIP_HD inline void resolvent_colored_step_affine(const ResolventConstants& c, double x, double v,
                                                       double z1, double z2, double& x_next, double& f) {
    x_next = c.ou.end_coef * x + (c.ou.l21 * z1 + c.ou.l22 * z2);
    f = c.keep * v + ((c.h_bias + c.f_x * x) + c.f_z * z1);
}

/// resolvent_colored_step for either law: the affine one as above, a knots
/// law with f = V + h b(V) + forcing (the branch is fixed for the run, so it
/// is predicted; the SIMD lanes, which run the affine law only, call the
/// affine step directly so that their loop has no branch).
STICKSLIP_HD inline void resolvent_colored_step(const ResolventConstants& c, double x, double v,
                                                double z1, double z2, double& x_next, double& f) {
    if (!c.knots_law) return resolvent_colored_step_affine(c, x, v, z1, z2, x_next, f);
    x_next = c.ou.end_coef * x + (c.ou.l21 * z1 + c.ou.l22 * z2);
    f = (v + c.h * c.drift(v)) + (c.f_x * x + c.f_z * z1);
}

/// Colored noise: the free flight from rest over the step that drew z1 from
/// noise x [m/s]: h (b(0) + a xbar), the force alone (static_friction_step).
STICKSLIP_HD inline double resolvent_rest_flight(const ResolventConstants& c, double x, double z1) {
    return (c.h_rest + c.f_x * x) + c.f_z * z1;
}

/// One white-noise step from v with the standard normal z: the velocity at the
/// end of the step [m/s] (the free flight, then the friction's resolvent).
STICKSLIP_HD inline double resolvent_white_step(const ResolventConstants& c, double v, double z) {
    const auto rest = [&] { return c.h_rest + c.h_amp * z; };
    if (c.knots_law) return friction_step(c, v, (v + c.h * c.drift(v)) + c.h_amp * z, rest);
    return friction_step(c, v, c.keep * v + (c.h_bias + c.h_amp * z), rest);
}

/// Observer that ignores the path: the default of the long-excursion kernels,
/// compiled away entirely.
struct NoPathObserver {
    /// Does nothing with the state (x [s^-1/2], v [m/s]).
    STICKSLIP_HD void operator()(double /*x*/, double /*v*/) const {}
};

/// What observes a resolvent path: observe(x [s^-1/2], v [m/s]) at the start
/// of every applied step.
template <class O>
concept StepObserver = std::invocable<O&, double, double>;

/// A long excursion of the inclusion engine between two steps. The kernels
/// advance it one step at a time (resolvent_walk_step_as), so the same step serves
/// the one-excursion kernel below and the interleaved one (resolvent_lanes.hpp).
struct ResolventWalk {
    double x = 0.0;          ///< noise X at the start of the next step [s^-1/2] (0 for white noise)
    double v = 0.0;          ///< velocity at the start of the next step [m/s]
    double vsum = 0.0;       ///< sum of V over the applied steps [m/s]
    std::uint64_t steps = 0; ///< applied steps, both halves
    std::uint64_t first = 0; ///< applied steps of the first half, once it is over
    int dir = +1;            ///< +1: first half (+HLE), -1: second half (-HLE)
    bool prev_stuck = false; ///< rule P: the previous step started and ended at V = 0
    bool spare_ok = false;   ///< white noise: the second normal of the last pair is unused
    double spare = 0.0;      ///< that normal
};

/// What a step of a walk ended with: Running (go on), HalfDone (the half's
/// stop test fired; the detecting step was not applied) or Capped (the walk
/// has made max_steps steps).
enum class WalkStatus { Running, HalfDone, Capped };

/// The three step laws: white noise, colored noise with stop rule Q (Bridge)
/// or P (Stuck).
enum class StepKind { White, ColoredBridge, ColoredStuck };

/// Calls f(std::integral_constant<StepKind, K>{}) with K the step kind of c.
template <class F>
STICKSLIP_HD inline decltype(auto) with_step_kind(const ResolventConstants& c, F&& f) {
    if (c.white) return f(std::integral_constant<StepKind, StepKind::White>{});
    if (c.rule == StopRule::Bridge) return f(std::integral_constant<StepKind, StepKind::ColoredBridge>{});
    return f(std::integral_constant<StepKind, StepKind::ColoredStuck>{});
}

/// Puts w at the start of half `dir`. Colored noise: +1 starts from (x*, 0), -1
/// from (x-*, 0); white noise: from V = dir * c.level.
STICKSLIP_HD inline void resolvent_walk_start_half(const ResolventConstants& c, ResolventWalk& w, int dir) {
    w.dir = dir;
    w.prev_stuck = false;
    w.spare_ok = false;
    if (c.white) {
        w.x = 0.0;
        w.v = dir * c.level;
    } else {
        w.x = dir > 0 ? c.x_up : c.x_down;
        w.v = 0.0;
    }
}

/// One step of the current half. Colored noise: the half of direction +1 ends
/// when the object, stuck, sees X reach x-* (rule Q: at the end of the step or,
/// by the Brownian-bridge test, within it; rule P: a stuck step followed by a
/// step whose free flight leaves the band downwards); -1 is the mirror image.
/// White noise: the half ends when V reaches -c (+1) or +c (-1). The detecting
/// step is not applied (returns HalfDone). `observe(x, v)` sees the state at
/// the start of every applied step (each stands for a time h). Returns Capped,
/// without stepping, once the excursion has made c.max_steps steps.
/// (K is c's step kind, as with_step_kind chooses it, fixed at compile time
/// so that the kernels test the noise and the stop rule once per excursion,
/// not once per step.)
///
/// `mart` (kernels/corrector.hpp) sees every step whose draws were made, the
/// detecting one too: its innovation is the noise's own, so the sums are an
/// exact martingale of the simulated chain (NoMartingale: nothing).
template <StepKind K, class Rng, class Observer, class Martingale = NoMartingale>
STICKSLIP_HD inline WalkStatus resolvent_walk_step_as(const ResolventConstants& c, ResolventWalk& w, Rng& rng,
                                                      Observer& observe, Martingale&& mart = Martingale{}) {
    if (w.steps >= c.max_steps) return WalkStatus::Capped;
    if constexpr (K == StepKind::White) {
        double z;
        if (w.spare_ok) {
            z = w.spare;
            w.spare_ok = false;
        } else { // one Philox block serves two steps
            const auto p = rng.normal2();
            z = p.x;
            w.spare = p.y;
            w.spare_ok = true;
        }
        const double v_next = resolvent_white_step(c, w.v, z);
        if constexpr (std::remove_reference_t<Martingale>::active) mart.add(0.0, w.v, c.h_amp * z, c.h_amp * c.h_amp);
        if (w.dir > 0 ? v_next <= -c.level : v_next >= c.level) return WalkStatus::HalfDone;
        observe(0.0, w.v);
        w.vsum += w.v;
        ++w.steps;
        w.v = v_next;
        return WalkStatus::Running;
    }
    const auto z = rng.normal2();
    double x_next, f;
    resolvent_colored_step(c, w.x, w.v, z.x, z.y, x_next, f);
    if constexpr (std::remove_reference_t<Martingale>::active)
        mart.add(w.x, w.v, c.ou.l21 * z.x + c.ou.l22 * z.y, c.ou.s22); // X's exact innovation
    if (w.v == 0.0) {
        if constexpr (K == StepKind::ColoredBridge) {
            if (w.x >= c.x_down && w.x <= c.x_up) { // stuck at the start of the step
                const double target = w.dir > 0 ? c.x_down : c.x_up;
                bool crossed = w.dir > 0 ? x_next <= target : x_next >= target;
                if (!crossed) crossed = bridge_crossed(c, w.x, x_next, target, rng);
                if (crossed) return WalkStatus::HalfDone;
            }
        } else if (w.prev_stuck && (w.dir > 0 ? f < -c.h_static : f > c.h_static)) {
            return WalkStatus::HalfDone;
        }
    }
    const double v_next = c.static_band && w.v == 0.0
                              ? resolvent_static_start(c, w.x, x_next, f, rng)
                              : friction_step(c, w.v, f, [&] { return resolvent_rest_flight(c, w.x, z.x); });
    if constexpr (K == StepKind::ColoredStuck) w.prev_stuck = (w.v == 0.0 && v_next == 0.0);
    observe(w.x, w.v);
    w.vsum += w.v;
    ++w.steps;
    w.x = x_next;
    w.v = v_next;
    return WalkStatus::Running;
}

/// The outcome of a finished (or capped) walk.
STICKSLIP_HD inline ExcursionOutcome resolvent_walk_outcome(const ResolventConstants& c, const ResolventWalk& w,
                                                            bool capped) {
    ExcursionOutcome o;
    o.first_half = c.h * static_cast<double>(w.first);
    o.displacement = c.h * w.vsum;
    o.duration = c.h * static_cast<double>(w.steps);
    o.work = w.steps;
    o.capped = capped;
    return o;
}

/// resolvent_long_excursion for step kind K, c's (as with_step_kind chooses it).
/// (`mart` accumulates the excursion's martingale; its sums are returned in
/// the outcome.)
template <StepKind K, class Rng, class Observer, class Martingale = NoMartingale>
STICKSLIP_HD inline ExcursionOutcome resolvent_long_excursion_as(const ResolventConstants& c, Rng& rng,
                                                                 Observer& observe, Martingale&& mart = Martingale{}) {
    ResolventWalk w;
    resolvent_walk_start_half(c, w, +1);
    WalkStatus st;
    while ((st = resolvent_walk_step_as<K>(c, w, rng, observe, mart)) == WalkStatus::Running) {
    }
    if (st == WalkStatus::HalfDone) {
        w.first = w.steps;
        resolvent_walk_start_half(c, w, -1);
        while ((st = resolvent_walk_step_as<K>(c, w, rng, observe, mart)) == WalkStatus::Running) {
        }
    }
    ExcursionOutcome o = resolvent_walk_outcome(c, w, st == WalkStatus::Capped);
    if constexpr (std::remove_reference_t<Martingale>::active) {
        o.martingale = mart.m;
        o.martingale_qv = mart.q;
    }
    return o;
}

/// One long excursion (+HLE then -HLE) of the inclusion engine; `observe(x, v)`
/// sees every applied step (x = 0 for white noise).
template <class Rng, StepObserver Observer = NoPathObserver>
STICKSLIP_HD inline ExcursionOutcome resolvent_long_excursion(const ResolventConstants& c, Rng& rng,
                                                              Observer&& observe = Observer{}) {
    return with_step_kind(c, [&](auto kind) { return resolvent_long_excursion_as<kind.value>(c, rng, observe); });
}

/// One long excursion with the martingale of the corrector g (outcome's
/// martingale and martingale_qv; kernels/corrector.hpp). The draws, and so
/// U and t, are those of resolvent_long_excursion, bit for bit.
template <class Rng>
STICKSLIP_HD inline ExcursionOutcome resolvent_long_excursion_with(const ResolventConstants& c, Rng& rng,
                                                                   const CorrectorTable& g) {
    NoPathObserver none;
    return with_step_kind(c, [&](auto kind) {
        return resolvent_long_excursion_as<kind.value>(c, rng, none, MartingaleSums{g});
    });
}

/// Brute-force trajectory (Algorithm 2 with time stepping): from noise x0
/// [s^-1/2] (ignored for white noise) and velocity v0 [m/s], `nsteps` steps.
/// Returns U(nsteps*h).
/// `observe(x, v)` sees the state at the start of each of the nsteps steps;
/// on return x0 and v0 hold the final state, so a path can be continued.
template <class Rng, StepObserver Observer = NoPathObserver>
STICKSLIP_HD inline ExcursionOutcome resolvent_path(const ResolventConstants& c, double& x0, double& v0,
                                                    std::uint64_t nsteps, Rng& rng,
                                                    Observer&& observe = Observer{}) {
    double vsum = 0.0, v = v0, x = x0;
    std::uint64_t n = 0;
    if (c.white) {
        while (n < nsteps) {
            const auto z = rng.normal2();
            const double zz[2] = {z.x, z.y};
            for (int k = 0; k < 2 && n < nsteps; ++k, ++n) {
                observe(0.0, v);
                vsum += v;
                v = resolvent_white_step(c, v, zz[k]);
            }
        }
    } else {
        for (; n < nsteps; ++n) {
            const auto z = rng.normal2();
            double x_next, f;
            resolvent_colored_step(c, x, v, z.x, z.y, x_next, f);
            observe(x, v);
            vsum += v;
            v = c.static_band && v == 0.0 ? resolvent_static_start(c, x, x_next, f, rng)
                                          : friction_step(c, v, f, [&] { return resolvent_rest_flight(c, x, z.x); });
            x = x_next;
        }
    }
    x0 = x;
    v0 = v;
    ExcursionOutcome o;
    o.displacement = c.h * vsum;
    o.duration = c.h * static_cast<double>(nsteps);
    o.work = nsteps;
    return o;
}

/// Brute-force trajectory: resolvent_path from (x0, v0) without an observer.
template <class Rng>
STICKSLIP_HD inline ExcursionOutcome resolvent_trajectory(const ResolventConstants& c, double x0,
                                                          double v0, std::uint64_t nsteps, Rng& rng) {
    return resolvent_path(c, x0, v0, nsteps, rng);
}

} // namespace stickslip
