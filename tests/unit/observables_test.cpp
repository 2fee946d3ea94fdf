// SPDX-License-Identifier: BSD-3-Clause
// Exact properties of the observables and the sweep (observables.hpp,
// sweep.hpp): the ratio accumulator, normalisation, thread invariance, and
// that observables run exactly the excursions `diffusivity` runs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "stickslip/observables.hpp"
#include "stickslip/sample_runs.hpp"
#include "stickslip/sweep.hpp"

namespace ss = stickslip;

namespace {

const double inf = std::numeric_limits<double>::infinity();

TEST(RatioMoments, MergeEqualsSequentialAndMatchesDirectFormulas) {
    // Deterministic pseudo-data: y = (a, b), t.
    std::vector<std::array<double, 3>> data;
    for (int k = 0; k < 257; ++k) {
        const double t = 1.0 + 0.5 * std::sin(0.7 * k);
        data.push_back({t * (0.3 + std::cos(1.3 * k)), t * t * 0.1 * (k % 7), t});
    }
    ss::RatioMoments all(2, true), a(2, true), b(2, true);
    for (std::size_t k = 0; k < data.size(); ++k) {
        all.add(data[k].data(), data[k][2]);
        (k < 100 ? a : b).add(data[k].data(), data[k][2]);
    }
    a.merge(b);
    ASSERT_EQ(a.count(), all.count());
    for (std::size_t j = 0; j < 2; ++j) {
        EXPECT_NEAR(a.ratio(j), all.ratio(j), 1e-14);
        for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(a.ratio_covariance(i, j), all.ratio_covariance(i, j), 1e-15);
    }
    // Direct two-pass formulas.
    const double n = static_cast<double>(data.size());
    double sy[2] = {0, 0}, st = 0;
    for (const auto& d : data) {
        sy[0] += d[0];
        sy[1] += d[1];
        st += d[2];
    }
    const double r0 = sy[0] / st, r1 = sy[1] / st, tbar = st / n;
    double c01 = 0, c00 = 0;
    for (const auto& d : data) {
        c00 += (d[0] - r0 * d[2]) * (d[0] - r0 * d[2]);
        c01 += (d[0] - r0 * d[2]) * (d[1] - r1 * d[2]);
    }
    EXPECT_NEAR(all.ratio(0), r0, 1e-13);
    EXPECT_NEAR(all.ratio_covariance(0, 0), c00 / (n - 1) / n / (tbar * tbar), 1e-15);
    EXPECT_NEAR(all.ratio_covariance(0, 1), c01 / (n - 1) / n / (tbar * tbar), 1e-15);
    // A diagonal accumulator refuses off-diagonal covariances.
    ss::RatioMoments diag(2, false);
    diag.add(data[0].data(), 1.0);
    diag.add(data[1].data(), 2.0);
    EXPECT_THROW(diag.ratio_covariance(0, 1), std::logic_error);
}

ss::DensityRequest small_density(ss::Engine engine) {
    ss::DensityRequest r;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    r.engine.engine = engine;
    r.engine.dt = 1e-3;
    r.excursions = 200;
    r.bins = {-0.3, 0.3, 12};
    r.control.seed = 9;
    return r;
}

TEST(StationaryDensity, ProbabilitiesAddUpToOne) {
    for (auto engine : {ss::Engine::Inclusion, ss::Engine::Pdmp}) {
        const auto res = ss::compute_density(small_density(engine));
        const auto& h = res.histogram;
        double total = h.stuck.value + h.below.value + h.above.value;
        for (std::size_t k = 0; k < h.density.size(); ++k) total += h.density[k].value * (h.edges[k + 1] - h.edges[k]);
        EXPECT_NEAR(total, 1.0, 1e-12) << ss::to_string(engine);
        EXPECT_GT(h.stuck.value, 0.5) << "the Fig. 2 case is stuck most of the time";
    }
}

TEST(StationaryDensity, SameExcursionsAsDiffusivityAndThreadInvariant) {
    for (auto engine : {ss::Engine::Inclusion, ss::Engine::Pdmp}) {
        auto r = small_density(engine);
        r.control.threads = 1;
        const auto one = ss::compute_density(r);
        r.control.threads = 2;
        const auto two = ss::compute_density(r);
        for (std::size_t k = 0; k < one.histogram.density.size(); ++k)
            EXPECT_EQ(one.histogram.density[k].value, two.histogram.density[k].value);
        EXPECT_EQ(one.variance.value, two.variance.value);

        ss::DiffusivityRequest d;

        d.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        d.engine = r.engine;
        d.excursions = r.excursions;
        d.control.seed = r.control.seed;
        d.allow_capped = true;
        d.control_variate = ss::ControlVariateMode::Off; // density reports the plain estimates
        const auto diff = ss::compute_diffusivity(d);
        EXPECT_EQ(one.estimates.diffusivity.value, diff.estimates.diffusivity.value) << ss::to_string(engine);
        EXPECT_EQ(one.estimates.mean_duration.value, diff.estimates.mean_duration.value);
    }
}

TEST(Correlation, LagZeroIsTheSecondMomentOfTheSameExcursions) {
    for (auto engine : {ss::Engine::Inclusion, ss::Engine::Pdmp}) {
        const auto dens = ss::compute_density(small_density(engine));
        ss::CorrelationRequest c;
        c.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        c.engine = dens.request.engine;
        c.excursions = dens.request.excursions;
        c.control.seed = dens.request.control.seed;
        c.max_lag = 0.2;
        c.lags = 4;
        const auto corr = ss::compute_correlation(c);
        const double m2 = dens.variance.value + dens.mean.value * dens.mean.value;
        EXPECT_NEAR(corr.autocorrelation[0].value, m2, 1e-12 * m2) << ss::to_string(engine);
        EXPECT_NEAR(corr.covariance[0].value, dens.variance.value, 1e-9 * dens.variance.value);
        EXPECT_EQ(corr.normalised[0].value, 1.0);
        EXPECT_EQ(corr.mean.value, dens.mean.value);
        for (std::size_t k = 1; k < corr.lag.size(); ++k) {
            EXPECT_LT(corr.normalised[k].value, 1.0);
            EXPECT_GT(corr.normalised[k].error, 0.0);
        }
    }
}

TEST(Transient, TimeZeroIsTheStartAndThreadsDoNotMatter) {
    for (auto engine : {ss::Engine::Inclusion, ss::Engine::Pdmp}) {
        ss::MomentsRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.engine.engine = engine;
        r.engine.dt = 1e-3;
        r.v0 = 0.25;
        r.times = {0.5, 0.0, 0.1}; // unsorted on purpose
        r.trajectories = 300;
        r.with_density = true;
        r.bins = {-0.5, 0.5, 10};
        r.control.threads = 1;
        const auto one = ss::compute_moments(r);
        ASSERT_EQ(one.time, (std::vector<double>{0.0, 0.1, 0.5}));
        EXPECT_EQ(one.first_moment[0].value, 0.25);
        EXPECT_EQ(one.first_moment[0].error, 0.0);
        EXPECT_EQ(one.stuck[0].value, 0.0);
        ASSERT_EQ(one.density.size(), 3u);
        for (const auto& h : one.density) {
            double total = h.stuck.value + h.below.value + h.above.value;
            for (std::size_t k = 0; k < h.density.size(); ++k) total += h.density[k].value * 0.1;
            EXPECT_NEAR(total, 1.0, 1e-12);
        }
        r.control.threads = 2;
        const auto two = ss::compute_moments(r);
        for (std::size_t k = 0; k < one.time.size(); ++k)
            EXPECT_EQ(one.first_moment[k].value, two.first_moment[k].value);
    }
}

TEST(Trajectory, ExcursionModeIsTheDiffusivityExcursion) {
    for (auto engine : {ss::Engine::Inclusion, ss::Engine::Pdmp}) {
        ss::TrajectoryRequest t;
        t.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        t.engine.engine = engine;
        t.engine.dt = 1e-3;
        t.index = 5;
        t.control.seed = 4;
        const auto path = ss::compute_trajectory(t);
        ASSERT_EQ(path.paths.size(), 1u);
        const auto& p = path.paths[0];
        ASSERT_GE(p.t.size(), 2u);
        EXPECT_EQ(p.t.front(), 0.0);
        EXPECT_EQ(p.v.front(), 0.0);
        EXPECT_DOUBLE_EQ(p.t.back(), path.excursion.duration);
        EXPECT_DOUBLE_EQ(p.u.back(), path.excursion.displacement);
        for (std::size_t i = 1; i < p.t.size(); ++i) ASSERT_GE(p.t[i], p.t[i - 1]);

        // The same excursion as sample 5 of `diffusivity` with that seed: one
        // excursion run from index 5 has exactly its U and t.
        ss::RunControl ctl;
        ctl.seed = 4;
        ctl.first_index = 5;
        ctl.threads = 1;
        const auto run = ss::run_long_excursions(t.params, t.engine, 1, ctl);
        EXPECT_EQ(run.moments.mean_x(), path.excursion.displacement) << ss::to_string(engine);
        EXPECT_EQ(run.moments.mean_y(), path.excursion.duration);
    }
}

TEST(Trajectory, PathModeRecordsTheGrid) {
    for (auto engine : {ss::Engine::Inclusion, ss::Engine::Pdmp}) {
        ss::TrajectoryRequest t;
        t.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        t.engine.engine = engine;
        t.engine.dt = 1e-3;
        t.paths = 3;
        t.horizon = 1.0;
        t.every = 0.01;
        const auto res = ss::compute_trajectory(t);
        ASSERT_EQ(res.paths.size(), 3u);
        for (const auto& p : res.paths) {
            ASSERT_EQ(p.t.size(), 101u) << ss::to_string(engine);
            EXPECT_EQ(p.u.front(), 0.0);
            EXPECT_NEAR(p.t.back(), 1.0, 1e-12);
            for (std::size_t i = 0; i < p.t.size(); ++i) EXPECT_NEAR(p.t[i], 0.01 * static_cast<double>(i), 1e-12);
        }
        EXPECT_NE(res.paths[0].u.back(), res.paths[1].u.back()) << "independent paths";
    }
}

TEST(Observables, InvalidRequestsThrowNamingTheParameter) {
    auto expect = [](auto fn, const std::string& name) {
        try {
            fn();
            ADD_FAILURE() << "expected InvalidParameter(" << name << ")";
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), name) << e.what();
        }
    };
    expect([] {
        auto r = small_density(ss::Engine::Inclusion);
        r.bins.count = 0;
        ss::validate(r);
    }, "bins");
    expect([] {
        auto r = small_density(ss::Engine::Inclusion);
        r.bins = {1, -1, 10};
        ss::validate(r);
    }, "range");
    expect([] {
        ss::CorrelationRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.lags = 0;
        ss::validate(r);
    }, "lags");
    expect([] {
        ss::CorrelationRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.max_lag = -1;
        ss::validate(r);
    }, "max-lag");
    expect([] {
        ss::MomentsRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.times = {1, -0.5};
        ss::validate(r);
    }, "times");
    expect([] {
        ss::MomentsRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.times = {1};
        r.v0 = inf;
        ss::validate(r);
    }, "v0");
    expect([] {
        ss::TrajectoryRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.paths = 2;
        r.horizon = 0;
        ss::validate(r);
    }, "time");
    expect([] {
        ss::SweepRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.noises = {1, -2};
        r.taus = {0.5};
        ss::validate(r);
    }, "noise");
    expect([] {
        ss::SweepRequest r;
        r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
        r.noises = {1};
        r.taus.clear();
        ss::validate(r);
    }, "tau");
    // The defaults that depend on the model are valid: a transient request
    // without times uses Table I's, without v0 one velocity unit.
    EXPECT_NO_THROW(ss::validate(ss::MomentsRequest{}));
}

TEST(Sweep, PointsHaveIndependentStreamsAndSortedGrid) {
    ss::SweepRequest r;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    r.engine.dt = 1e-3;
    r.noises = {6, 4};
    r.taus = {0.5};
    r.excursions = 100;
    r.allow_capped = true;
    r.control.seed = 8;
    const auto res = ss::compute_sweep(r);
    ASSERT_EQ(res.points.size(), 2u);
    EXPECT_EQ(res.points[0].noise, 4.0);
    EXPECT_EQ(res.points[1].noise, 6.0);
    // Point 1 is `diffusivity` at noise 6 with sample indices from 2^40.
    ss::DiffusivityRequest d;
    d.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    d.engine = r.engine;
    d.params.noise = 6;
    d.excursions = 100;
    d.allow_capped = true;
    d.control.seed = 8;
    d.control.first_index = ss::sweep_index_stride;
    const auto one = ss::compute_diffusivity(d);
    EXPECT_EQ(res.points[1].estimates.diffusivity.value, one.estimates.diffusivity.value);
    // Two noises: both local slopes are the one secant, with the same error.
    EXPECT_EQ(res.points[0].slope.value, res.points[1].slope.value);
    const double secant = std::log(res.points[1].estimates.diffusivity.value / res.points[0].estimates.diffusivity.value) /
                          std::log(1.5);
    EXPECT_NEAR(res.points[0].slope.value, secant, 1e-12);
    ASSERT_EQ(res.exponents.size(), 1u);
    EXPECT_NEAR(res.exponents[0].exponent.value, secant, 1e-9);
}

} // namespace
