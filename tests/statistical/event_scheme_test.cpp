// SPDX-License-Identifier: BSD-3-Clause
// The event scheme against references it did not produce: the PDMP engine on
// the paper's Fig. 4 case (D, M0 and the stuck fraction at a step 200 times
// the resolvent's default), and the mean exit time of the stuck noise against
// its quadrature. Tolerances: a few combined standard errors plus the
// allowances measured for this scheme (docs/validation.md, "The event scheme").
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "support.hpp"

namespace {

using namespace sstest;

ss::EngineSettings event(double dt) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.scheme = ss::Scheme::Event;
    e.dt = dt;
    return e;
}

TEST(EventSchemeStatistics, Fig4CaseAgreesWithPdmpAtACoarseStep) {
    ss::ModelParams p; // Fig. 2/4: tau 0.5, relaxation 0.067, bias 0.342
    ss::EngineSettings pdmp = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    pdmp.engine = ss::Engine::Pdmp;
    const auto a = run_le(p, event(2e-2), 60000, 2024);
    const auto b = run_le(p, pdmp, 60000, 2025);
    EXPECT_TRUE(check(compare(a.estimates.diffusivity.value, a.estimates.diffusivity.error,
                              b.estimates.diffusivity.value, b.estimates.diffusivity.error),
                      "D, event dt 2e-2 s vs pdmp grid 0.125"));
    EXPECT_TRUE(check(compare(a.estimates.mobility.value, a.estimates.mobility.error, b.estimates.mobility.value,
                              b.estimates.mobility.error),
                      "M0, event dt 2e-2 s vs pdmp grid 0.125"));
}

TEST(EventSchemeStatistics, StuckFractionAgreesWithPdmp) {
    auto stuck = [](const ss::EngineSettings& e, std::uint64_t seed) {
        ss::DensityRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.engine = e;
        r.excursions = 6000;
        r.bins.count = 4;
        r.sample_dt = 1e-3;
        r.control.seed = seed;
        return ss::compute_density(r).histogram.stuck;
    };
    ss::EngineSettings pdmp = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    pdmp.engine = ss::Engine::Pdmp;
    const auto a = stuck(event(1e-2), 1), b = stuck(pdmp, 2);
    // Allowance 0.002: the launch cascade resolved to h/64 (measured here:
    // 0.8800 against the PDMP's 0.8812, z = -1.0).
    EXPECT_TRUE(check(compare(a.value, a.error, b.value, b.error, 0.002, 3.0),
                      "P(V = 0), event dt 1e-2 s vs pdmp grid 0.125"));
}

TEST(EventSchemeStatistics, StuckFractionHasNoStepPartAtTauOverTen) {
    // Pure dry friction, tau = 1e-2 s, friction 3.84, noise 1, dt = 1e-3 s =
    // tau/10: P(V = 0) against its dt -> 0 limit 0.0800 (the PDMP: 0.07947 and
    // 0.07980 +- 0.00024 at grids 0.5 and 0.25; the resolvent step: 0.0842,
    // 0.0823, 0.0813 at dt = 1e-4, 5e-5, 2.5e-5 s, and 0.105 at 1e-3 s).
    // Allowance 0.001 (the target). Measured: 0.0802 +- 0.0001 over
    // 1e6 excursions; 0.0907 before every refined piece was observed on its
    // own (a step from a launch to a landing read as stuck throughout).
    ss::DensityRequest r;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    r.params.friction = 3.84;
    r.params.noise = 1;
    r.params.tau = 0.01;
    r.params.relaxation = INFINITY;
    r.params.bias = 0;
    r.engine = event(1e-3);
    r.excursions = 100000;
    r.bins.count = 4;
    r.control.seed = 17;
    const auto stuck = ss::compute_density(r).histogram.stuck;
    EXPECT_TRUE(check(compare(stuck.value, stuck.error, 0.0800, 0.0002, 0.001, 3.0),
                      "P(V = 0), event dt = tau/10 vs its dt -> 0 limit"));
}

/// The stuck phase alone: X from 0 until it first leaves the band, n times.
struct StuckExits {
    double mean, se; ///< of the exit time [s]
    double up, up_se; ///< fraction leaving through the upper threshold
};

StuckExits simulate_stuck_exits(const ss::ModelParams& p, double dt, int n, std::uint64_t seed) {
    const ss::EventConstants c = ss::make_event_constants(p, event(dt));
    double sum = 0, sum2 = 0, ups = 0;
    ss::NoPieceObserver none;
    for (int k = 0; k < n; ++k) {
        ss::BatchedCounterRng rng(seed, ss::StreamPurpose::Test, static_cast<std::uint64_t>(k));
        ss::CounterRng ref(seed, ss::StreamPurpose::Refinement, static_cast<std::uint64_t>(k));
        ss::EventWalk w = ss::event_walk_from(c, 0.0, 0.0);
        while (w.phase == 0) ss::event_step(c, w, 0, rng, ref, none);
        const double t = c.leaf * static_cast<double>(w.t);
        sum += t;
        sum2 += t * t;
        ups += w.phase > 0;
    }
    const double mean = sum / n, up = ups / n;
    return {mean, std::sqrt((sum2 / n - mean * mean) / n), up, std::sqrt(up * (1 - up) / n)};
}

/// The exact mean exit time from 0 of tau dX = -X dt + sqrt(2) dW from
/// [x-*, x*], T(0) = int G(0, y) m(y) dy with scale density s(y) =
/// e^{tau y^2/2}, and the probability S(0) / S(x*) of leaving upwards (S the
/// scale function from x-*).
struct ExactStuckExit {
    double mean, up;
};

ExactStuckExit exact_stuck_exit(const ss::ModelParams& p) {
    const double tau = p.tau, xu = p.upper_threshold(), xd = p.lower_threshold();
    const int m = 400000;
    std::vector<double> y(m + 1), S(m + 1, 0.0);
    for (int i = 0; i <= m; ++i) y[i] = xd + (xu - xd) * i / m;
    auto scale = [&](double v) { return std::exp(tau * v * v / 2); };
    for (int i = 1; i <= m; ++i) S[i] = S[i - 1] + 0.5 * (scale(y[i]) + scale(y[i - 1])) * (y[i] - y[i - 1]);
    const double Sb = S[m];
    int i0 = 0;
    while (y[i0] < 0) ++i0;
    // S at 0 exactly: interpolate between the grid points around it.
    const double S0 = S[i0 - 1] + (S[i0] - S[i0 - 1]) * (0 - y[i0 - 1]) / (y[i0] - y[i0 - 1]);
    double exact = 0;
    for (int i = 0; i < m; ++i) {
        const double ym = 0.5 * (y[i] + y[i + 1]), Sm = 0.5 * (S[i] + S[i + 1]);
        const double speed = tau * tau / scale(ym); // 2 / (sigma^2 s(y)), sigma^2 = 2 / tau^2
        const double G = ym < 0 ? Sm * (Sb - S0) / Sb : S0 * (Sb - Sm) / Sb;
        exact += G * speed * (y[i + 1] - y[i]);
    }
    return {exact, S0 / Sb};
}

TEST(EventSchemeStatistics, StuckNoiseExitsAtTheRightMeanTime) {
    const ss::ModelParams p; // Fig. 2/4 case: the band is 5.1 noise standard deviations wide
    const StuckExits a = simulate_stuck_exits(p, 2e-2, 100000, 7);
    const ExactStuckExit exact = exact_stuck_exit(p);
    // Allowance 0.4%: the straight-line boundary of the clock change at
    // step/tau = 0.04 (measured: -0.3% at dt = 1e-2 s, -0.9% at 0.1 s before
    // stuck pieces longer than tau/8 were halved).
    EXPECT_TRUE(check(compare(a.mean, a.se, exact.mean, 0.0, 0.004 * exact.mean, 3.0), "mean exit time of the stuck noise"));
    EXPECT_TRUE(check(compare(a.up, a.up_se, exact.up, 0.0), "P(the stuck noise leaves upwards)"));
}

TEST(EventSchemeStatistics, ANarrowBandIsLeftThroughEitherThresholdFairly) {
    // friction = noise = 1, tau 0.1 s: the band is 0.9 noise standard
    // deviations wide, so one step of dt = 0.05 s = tau/2 often reaches both
    // thresholds. Testing the upper one first made every such step leave
    // upwards: P(up) = 0.5 by symmetry came out far above it, and M0 = 0.06
    // m/s for a symmetric model (docs/validation.md, "The event scheme at
    // steps near tau"). Now such a step is halved until one threshold is
    // out of reach.
    ss::ModelParams p;
    p.friction = 1;
    p.noise = 1;
    p.tau = 0.1;
    p.relaxation = INFINITY;
    p.bias = 0;
    const ExactStuckExit exact = exact_stuck_exit(p);
    for (double dt : {0.05, 0.5}) {
        const StuckExits a = simulate_stuck_exits(p, dt, 100000, 11);
        const std::string at = " at dt " + std::to_string(dt) + " s";
        EXPECT_TRUE(check(compare(a.up, a.up_se, exact.up, 0.0), "P(the stuck noise leaves upwards)" + at));
        // No allowance: measured 0.6 and 0.3 standard errors (the old order
        // of the tests gave z = 120 and 2500 for P(up), 125 and 165 here).
        EXPECT_TRUE(check(compare(a.mean, a.se, exact.mean, 0.0, 0.0, 3.0),
                          "mean exit time of the stuck noise" + at));
    }
}

TEST(EventSchemeStatistics, WhiteNoiseAtTheAutomaticStepMatchesTheQuadrature) {
    // The white-noise event scheme at its automatic step against the exact
    // quadrature (friction = noise = 1): pure dry friction (dt' = 1/16; the
    // resolvent step is -10% there), a bias of 0.3 (dt' = 1/16), and a drag
    // of relaxation 0.2 with that bias (dt = relaxation/16 = 0.0125). Allowance
    // 0.5% of the value: over 1e6 excursions per case no bias was seen at
    // 0.3 to 1.8% standard errors (docs/validation.md, "The event scheme for
    // white noise").
    struct Case {
        double relaxation, bias;
        std::uint64_t excursions, seed;
    };
    for (const Case& k : {Case{INFINITY, 0.0, 100000, 31}, Case{INFINITY, 0.3, 100000, 32}, Case{0.2, 0.3, 100000, 33}}) {
        ss::ModelParams p;
        p.friction = 1;
        p.noise = 1;
        p.tau = 0;
        p.relaxation = k.relaxation;
        p.bias = k.bias;
        ss::EngineSettings e = event(0.0);
        e.dt_auto = true;
        const auto r = run_le(p, e, k.excursions, k.seed);
        const ss::WhiteNoiseReference exact = ss::white_noise_reference(p);
        const std::string at = " (relaxation " + std::to_string(k.relaxation) + ", bias " + std::to_string(k.bias) +
                               ", dt " + std::to_string(r.request.engine.dt) + ")";
        EXPECT_TRUE(check(compare(r.estimates.diffusivity.value, r.estimates.diffusivity.error, exact.diffusivity,
                                  0.0, 0.005 * exact.diffusivity, 3.0),
                          "D, white-noise event scheme vs quadrature" + at));
        EXPECT_TRUE(check(compare(r.estimates.mobility.value, r.estimates.mobility.error, exact.mobility, 0.0,
                                  0.005 * std::fabs(exact.mobility), 3.0),
                          "M0, white-noise event scheme vs quadrature" + at));
    }
}

} // namespace
