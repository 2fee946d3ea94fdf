// SPDX-License-Identifier: BSD-3-Clause
// Coverage of the 95% interval of D over many independent small runs
// (docs/validation.md, "Interval coverage"). Each run has its own seed; the
// reference is D of all runs pooled (their moments merged), so the check is
// about the estimator and its interval, not the discretisation. The counts
// are binomial: over R runs at true coverage p their sd is sqrt(R p (1 - p)).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <vector>

#include "support.hpp"

namespace {

using namespace sstest;
const double inf = std::numeric_limits<double>::infinity();

struct Coverage {
    int runs = 0, below = 0, above = 0; ///< misses: the interval lies below / above the reference
    int below_sym = 0, above_sym = 0;   ///< the same for the symmetric interval D -+ q se
    int nonpositive_lo = 0, infinite_hi = 0;
    double reference = 0.0;
    int covered() const { return runs - below - above; }
    int covered_sym() const { return runs - below_sym - above_sym; }
};

/// `runs` runs of n excursions, seeds first_seed, first_seed + 1, ..., of
/// `base` (its model, engine and control-variate pilot).
Coverage measure(const ss::DiffusivityRequest& base, std::uint64_t n, int runs, std::uint64_t first_seed) {
    std::vector<ss::Estimate> d;
    ss::BivariateMoments pooled;
    ss::ControlVariateSums pooled_cv;
    bool cv = false;
    for (int i = 0; i < runs; ++i) {
        ss::DiffusivityRequest q = base;
        q.excursions = n;
        q.control.seed = first_seed + static_cast<std::uint64_t>(i);
        q.control.threads = 2;
        const auto r = ss::compute_diffusivity(q);
        EXPECT_EQ(r.monte_carlo().totals.capped, 0u);
        pooled.merge(r.monte_carlo().totals.moments);
        pooled_cv.merge(r.monte_carlo().totals.control_variate);
        cv = r.control_variate.has_value();
        d.push_back(r.estimates.diffusivity);
    }
    Coverage c;
    c.runs = runs;
    // The reference is the pooled estimate of the estimator under test: with
    // the control variate, the plain pool's own noise (its standard error over
    // 1000 runs is about a third of one control-variate run's) would count as
    // misses.
    c.reference = cv ? ss::estimate_control_variate(pooled_cv, 0.95).diffusivity.value
                     : ss::estimate_long_excursion(pooled, 0.95).diffusivity.value;
    const double q = ss::normal_quantile_two_sided(0.95);
    for (const ss::Estimate& x : d) {
        EXPECT_EQ(x.level, 0.95);
        c.below += x.hi < c.reference;
        c.above += x.lo > c.reference;
        c.below_sym += x.value + q * x.error < c.reference;
        c.above_sym += x.value - q * x.error > c.reference;
        c.nonpositive_lo += !(x.lo > 0);
        c.infinite_hi += std::isinf(x.hi);
    }
    std::cout << "[measured] " << runs << " runs of " << n << " excursions, pooled D " << c.reference
              << ": relative-error interval covers " << c.covered() << " (misses " << c.below << " below, "
              << c.above << " above), symmetric interval " << c.covered_sym() << " (" << c.below_sym << " below, "
              << c.above_sym << " above); lower bounds <= 0: " << c.nonpositive_lo
              << ", infinite upper bounds: " << c.infinite_hi << std::endl;
    return c;
}

/// The resolvent scheme at the fixed step dt, the default pilot.
Coverage measure(const ss::ModelParams& p, double dt, std::uint64_t n, int runs, std::uint64_t first_seed) {
    ss::DiffusivityRequest q;
    q.params = p;
    q.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, dt);
    return measure(q, n, runs, first_seed);
}

// White noise with viscous drag (relaxation' = 1): U grows like t over an
// excursion, so 2000 excursions are enough for the delta method. Measured with
// the CLI on 1000 other seeds (docs/validation.md, "Interval coverage"): the
// relative-error interval covers 93.6 +- 0.8% (misses 36 below, 28 above), the
// old symmetric one 92.6% (55 below, 19 above); here, plain, 946 (28/26) against 938
// (45/17); with the control variate, coefficients fitted on the run, 950
// (28/22) against 951 (29/20); with their pilot (the default) 955 (27/18);
// Binomial sd of the count at 94%: 7.5, so 920-980 leaves about 3 sd
// below. Each side must hold at least a quarter of the misses: about 45% are
// above here, so this is 3 sd from failing (the symmetric interval, at 27%,
// would scrape through: the gain is checked in the test below). About 2e6
// excursions, 3-5 s of CPU.
TEST(IntervalCoverage, DiffusivityIsNominalAt2000ExcursionsWithDrag) {
    const ss::ModelParams p{.friction = 1, .noise = 1, .tau = 0, .relaxation = 1, .bias = 0};
    const Coverage c = measure(p, 1e-2, 2000, 1000, 1000001);
    EXPECT_GE(c.covered(), 920);
    EXPECT_LE(c.covered(), 980);
    const int misses = c.below + c.above;
    EXPECT_GE(4 * c.below, misses) << "misses below: " << c.below << " of " << misses;
    EXPECT_GE(4 * c.above, misses) << "misses above: " << c.above << " of " << misses;
    EXPECT_EQ(c.nonpositive_lo, 0);
    EXPECT_EQ(c.infinite_hi, 0);
}

// Pure dry friction, white noise (the case): U grows like t^(3/2), the
// influence function of D has skewness about 55 and kurtosis about 8000, and
// 2000 excursions rarely hold the long excursions that carry the variance, so
// no interval computable from the run reaches 95% there (docs/validation.md:
// on 1000 runs symmetric 87.4%, log 88.9%, relative-error 89.1 +- 1.0%; even
// an order-6 skewness correction or a bootstrap-t over the 64-excursion
// blocks stays below 93%). Plain, here: 451 of 500 (38 below, 11 above)
// against 438 (61/1) for the symmetric interval. With the control variate (the
// default; the resolvent scheme has one for white noise, second-order sums):
// 468 (8/24) against 468 (11/21) with the coefficients fitted on the run; with
// their pilot (the default since issue 45) 480 (13/7) against 481 (14/5), and
// on 1000 other seeds with the CLI 94.3% (15/42):
// its estimate is no longer skewed, so both intervals miss on both sides. This
// guards the measured level and what holds anyway: misses on both sides, a
// positive lower bound, no more misses below than the symmetric interval.
TEST(IntervalCoverage, DiffusivityWithoutDragIsAsMeasured) {
    const ss::ModelParams p{.friction = 1, .noise = 1, .tau = 0, .relaxation = inf, .bias = 0};
    const Coverage c = measure(p, 1e-2, 2000, 500, 2000001);
    EXPECT_GE(c.covered(), 467); // 3 sd (4.4) below the measured 480
    EXPECT_LE(c.covered(), 490);
    EXPECT_GT(c.above, 0);
    EXPECT_LE(c.below, c.below_sym);
    EXPECT_EQ(c.nonpositive_lo, 0);
}

// The control variate's case (theory.md, section 12): coloured noise without
// drag, tau' = 0.1, the resolvent scheme at dt = 1e-2 s; the control variate
// removes 60-80 times the variance, but the interval at 2000 excursions still
// covered below nominal with its coefficients fitted on the run (measured on
// seeds 1..1000 with the CLI: 90.6% (59 below, 35 above) against the pooled
// control-variate D; here 439 of 500 (46 below, 15 above)); with their pilot
// (the default since issue 45) 469 (26/5) here and 95.1% (28/21) with the CLI.
// At least 453, 3 sd (5.4) below the measured 469: the old 439 fails it.
TEST(IntervalCoverage, ColouredWithoutDragWithTheControlVariateIsAsMeasured) {
    const ss::ModelParams p{.friction = 1, .noise = 1, .tau = 0.1, .relaxation = inf, .bias = 0};
    const Coverage c = measure(p, 1e-2, 2000, 500, 3000001);
    EXPECT_GE(c.covered(), 453);
    EXPECT_GT(c.above, 0);
    EXPECT_GT(c.below, 0);
    EXPECT_EQ(c.nonpositive_lo, 0);
}

// The issue "Honest intervals at every sample size": the control variate's
// coefficients fitted on the run's own excursions made the interval
// under-cover without drag (docs/validation.md, "Why D's interval
// under-covers without drag"); from an independent pilot (the default) it
// covers what it says. The hardest case, coloured noise with a bias, with the
// resolvent scheme at dt = 1e-2 s and with the event scheme at its automatic
// step; the same seeds with the old coefficients (pilot 0) must fail the
// bound, so that the test can tell the two apart. Measured: see the bounds.
Coverage coloured_bias(ss::Scheme scheme, std::uint64_t pilot, std::uint64_t first_seed) {
    ss::DiffusivityRequest q;
    q.params = ss::ModelParams{.friction = 1, .noise = 1, .tau = 0.1, .relaxation = inf, .bias = 0.3};
    if (scheme == ss::Scheme::Resolvent) q.engine = ss::fixed_step_settings(scheme, 1e-2);
    else q.engine.scheme = scheme; // its automatic step
    q.control_variate_pilot = pilot;
    return measure(q, 2000, 500, first_seed);
}

/// The pilot's interval holds `bound` of 500 runs; the fitted coefficients'
/// on the same seeds must not.
void expect_the_pilot_alone_holds(ss::Scheme scheme, std::uint64_t first_seed, int bound) {
    const Coverage c = coloured_bias(scheme, 8192, first_seed);
    const Coverage old = coloured_bias(scheme, 0, first_seed);
    EXPECT_GE(c.covered(), bound) << "the pilot's interval";
    EXPECT_LT(old.covered(), bound) << "the fitted coefficients' interval passes too: the test cannot fail";
    EXPECT_GT(c.below, 0);
    EXPECT_GT(c.above, 0);
}

TEST(IntervalCoverage, ColouredWithBiasIsHonestWithThePilotsCoefficients) {
    // Measured: 457 of 500 (36 below, 7 above) with the pilot (of 8000, 4 x
    // 2000), 407 (66/27) with the coefficients fitted on the run. Binomial sd
    // at 91.4%: 6.3, so 438 is 3 sd below.
    expect_the_pilot_alone_holds(ss::Scheme::Resolvent, 4000001, 438);
}

TEST(IntervalCoverage, TheEventSchemeAtItsAutomaticStepIsHonestWithThePilotsCoefficients) {
    // Measured: 464 of 500 (19 below, 17 above) with the pilot, 414 (54/32)
    // with the fitted coefficients. Binomial sd at 92.8%: 5.8; 447 is 3 sd below.
    expect_the_pilot_alone_holds(ss::Scheme::Event, 5000001, 447);
}

} // namespace
