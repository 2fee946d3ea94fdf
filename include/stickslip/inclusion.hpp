// stickslip/inclusion.hpp -- the differential-inclusion (time-stepping) engine.
//
// One step of length h (MODEL.md section 5): draw the exact OU pair
// (mean of X over the step, X at its end), form the free-flight velocity
// f = V + h (b(V) + a*xbar), and apply the resolvent of h*dphi, the soft
// threshold V' = f - clamp(f, -h Delta, h Delta): the object sticks exactly
// when |f| <= h Delta. Displacement uses the left-point rule U += h V.
// (The paper's printed update pushes the wrong way; this is the correct one.)
//
// For white noise (tau = 0) the force over a step is sqrt(Gamma h) z / h.
//
// Everything here is a small inline function without allocation, exceptions or
// virtual calls, marked STICKSLIP_HD, so the same code can be compiled for a GPU.
// The constants are computed once per run by make_inclusion_constants, which
// validates its input; the kernels trust them.
#pragma once

#include <cmath>
#include <cstdint>

#include "config.hpp"
#include "excursion.hpp"
#include "noise.hpp"
#include "params.hpp"

namespace stickslip {

/// Per-run constants of the inclusion engine (SI units). Built once by
/// make_inclusion_constants; every per-step quantity is precomputed here so the
/// step has no division or exponential.
struct InclusionConstants {
    double h;          ///< time step [s]
    double keep;       ///< 1 - h/relaxation: free-flight factor on V
    double h_bias;     ///< h * bias [m/s]
    double h_amp;      ///< colored: h * a [m/s per s^-1/2]; white: sqrt(noise h) [m/s]
    double h_friction; ///< h * friction [m/s]: the sticking band of f
    bool white;        ///< tau == 0
    OUStep ou;         ///< exact OU step (colored only)
    double x_up;       ///< x*  [s^-1/2] (colored only)
    double x_down;     ///< x-* [s^-1/2] (colored only)
    double bridge_rate;///< tau^2 / h [s]: Brownian-bridge crossing exponent factor
    StopRule rule;     ///< resolved rule: Bridge or Stuck (colored only)
    double level;      ///< white only: regeneration velocity level c > 0 [m/s]
    std::uint64_t max_steps; ///< runaway guard per long excursion
};

/// Validates p and s (throws InvalidParameter) and precomputes the constants.
InclusionConstants make_inclusion_constants(const ModelParams& p, const EngineSettings& s);

/// Default white-noise regeneration level c [m/s]: half the smaller of the
/// dry-friction velocity scale 0.7*noise/friction and the viscous one
/// sqrt(noise*relaxation/2), so that both levels are visited often.
double white_level_default(const ModelParams& p);

/// Resolvent of h*dphi: f - clamp(f, -band, band). Exactly 0 when |f| <= band.
STICKSLIP_HD inline double soft_threshold(double f, double band) {
    return f - std::fmin(std::fmax(f, -band), band);
}

/// Exponent above which the bridge crossing probability exp(-e) < 2e-22 is
/// treated as 0 (saves an exponential and a draw on most stuck steps).
inline constexpr double bridge_exponent_cutoff = 50.0;

/// Probability that a Brownian bridge with variance rate 2/tau^2 between x0 and
/// x1 (both on the same side of `level`) touches `level` within the step.
STICKSLIP_HD inline double bridge_crossing_probability(const InclusionConstants& c, double x0,
                                                       double x1, double level) {
    const double e = (x0 - level) * (x1 - level) * c.bridge_rate;
    return e > bridge_exponent_cutoff ? 0.0 : std::exp(-e);
}

/// One colored-noise step from (x, v): writes the end-of-step noise and the
/// free-flight velocity f; returns nothing else so the caller can test f first.
STICKSLIP_HD inline void inclusion_colored_step(const InclusionConstants& c, double x, double v,
                                                double z1, double z2, double& x_next, double& f) {
    const double xbar = c.ou.mean_coef * x + c.ou.l11 * z1;
    x_next = c.ou.end_coef * x + c.ou.l21 * z1 + c.ou.l22 * z2;
    f = c.keep * v + c.h_bias + c.h_amp * xbar;
}

/// Runs one colored-noise half long excursion. dir = +1: from (x*, 0) until the
/// object, stuck, sees X reach x-*; dir = -1: the mirror image. Adds the
/// displacement sum of V (in units of h: multiply by h) to vsum and the steps to
/// `steps`. Returns false when the step cap is reached. `observe(x, v)` sees the
/// state at the start of every applied step (each stands for a time h), so an
/// observable of the path is sampled exactly as the displacement is.
/// Observer that ignores the path: the default of the long-excursion kernels,
/// compiled away entirely.
struct NoPathObserver {
    STICKSLIP_HD void operator()(double /*x*/, double /*v*/) const {}
};

template <class Rng, class Observer = NoPathObserver>
STICKSLIP_HD inline bool inclusion_colored_half(const InclusionConstants& c, int dir, Rng& rng,
                                                double& vsum, std::uint64_t& steps,
                                                Observer&& observe = Observer{}) {
    double x = dir > 0 ? c.x_up : c.x_down;
    double v = 0.0;
    const double target = dir > 0 ? c.x_down : c.x_up;
    bool prev_stuck = false;
    for (;;) {
        if (steps >= c.max_steps) return false;
        const auto z = rng.normal2();
        double x_next, f;
        inclusion_colored_step(c, x, v, z.x, z.y, x_next, f);
        if (v == 0.0) {
            if (c.rule == StopRule::Bridge) {
                if (x >= c.x_down && x <= c.x_up) { // stuck at the start of the step
                    bool crossed = dir > 0 ? x_next <= target : x_next >= target;
                    if (!crossed) {
                        const double p = bridge_crossing_probability(c, x, x_next, target);
                        crossed = p > 0.0 && rng.uniform() < p;
                    }
                    if (crossed) return true; // the detecting step is not applied
                }
            } else if (prev_stuck && (dir > 0 ? f < -c.h_friction : f > c.h_friction)) {
                return true;
            }
        }
        const double v_next = soft_threshold(f, c.h_friction);
        prev_stuck = (v == 0.0 && v_next == 0.0);
        observe(x, v);
        vsum += v;
        ++steps;
        x = x_next;
        v = v_next;
    }
}

/// White-noise half excursion between the velocity levels: dir = +1 runs from
/// V = +c until V reaches -c (the crossing step is not applied), dir = -1 the
/// mirror image. One Philox call serves two steps.
template <class Rng, class Observer = NoPathObserver>
STICKSLIP_HD inline bool inclusion_white_half(const InclusionConstants& c, int dir, Rng& rng,
                                              double& vsum, std::uint64_t& steps,
                                              Observer&& observe = Observer{}) {
    double v = dir * c.level;
    for (;;) {
        if (steps >= c.max_steps) return false;
        const auto z = rng.normal2();
        const double zz[2] = {z.x, z.y};
        for (int k = 0; k < 2; ++k) {
            const double f = c.keep * v + c.h_bias + c.h_amp * zz[k];
            const double v_next = soft_threshold(f, c.h_friction);
            if (dir > 0 ? v_next <= -c.level : v_next >= c.level) return true;
            observe(0.0, v);
            vsum += v;
            ++steps;
            v = v_next;
        }
    }
}

/// One long excursion (+HLE then -HLE) of the inclusion engine; `observe(x, v)`
/// sees every applied step (x = 0 for white noise).
template <class Rng, class Observer = NoPathObserver>
STICKSLIP_HD inline ExcursionOutcome inclusion_long_excursion(const InclusionConstants& c, Rng& rng,
                                                              Observer&& observe = Observer{}) {
    double vsum = 0.0;
    std::uint64_t steps = 0, first = 0;
    bool ok;
    if (c.white)
        ok = inclusion_white_half(c, +1, rng, vsum, steps, observe) && ((first = steps), true) &&
             inclusion_white_half(c, -1, rng, vsum, steps, observe);
    else
        ok = inclusion_colored_half(c, +1, rng, vsum, steps, observe) && ((first = steps), true) &&
             inclusion_colored_half(c, -1, rng, vsum, steps, observe);
    ExcursionOutcome o;
    o.first_half = c.h * static_cast<double>(first);
    o.displacement = c.h * vsum;
    o.duration = c.h * static_cast<double>(steps);
    o.work = steps;
    o.capped = !ok;
    return o;
}

/// Brute-force trajectory (Algorithm 2 with time stepping): from noise x0
/// [s^-1/2] (ignored for white noise) and velocity v0 [m/s], `nsteps` steps.
/// Returns U(nsteps*h).
/// `observe(x, v)` sees the state at the start of each of the nsteps steps;
/// on return x0 and v0 hold the final state, so a path can be continued.
template <class Rng, class Observer = NoPathObserver>
STICKSLIP_HD inline ExcursionOutcome inclusion_path(const InclusionConstants& c, double& x0, double& v0,
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
                v = soft_threshold(c.keep * v + c.h_bias + c.h_amp * zz[k], c.h_friction);
            }
        }
    } else {
        for (; n < nsteps; ++n) {
            const auto z = rng.normal2();
            double x_next, f;
            inclusion_colored_step(c, x, v, z.x, z.y, x_next, f);
            observe(x, v);
            vsum += v;
            v = soft_threshold(f, c.h_friction);
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

/// Brute-force trajectory: inclusion_path from (x0, v0) without an observer.
template <class Rng>
STICKSLIP_HD inline ExcursionOutcome inclusion_trajectory(const InclusionConstants& c, double x0,
                                                          double v0, std::uint64_t nsteps, Rng& rng) {
    return inclusion_path(c, x0, v0, nsteps, rng);
}

} // namespace stickslip
