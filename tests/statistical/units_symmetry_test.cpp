// SPDX-License-Identifier: BSD-3-Clause
// A physical run and its nondimensional twin describe the same trajectories
// (same random streams, exactly scaled dynamics), so D, M0, E[t1] must agree
// after scaling to far better than their standard errors. And the model's
// mirror symmetry: bias -> -bias flips M0 and keeps D.
#include <gtest/gtest.h>

#include <cmath>

#include "support.hpp"

namespace {

using namespace sstest;

void expect_twins(const ss::EngineSettings& phys, std::uint64_t n) {
    const ss::ModelParams p; // Fig. 2 case
    const ss::Scales sc = ss::scales_of(p);
    const ss::ModelParams nd = ss::to_nondimensional(p);
    ss::EngineSettings e_nd = phys;
    e_nd.dt = phys.dt / sc.time;
    e_nd.grid = phys.grid * std::sqrt(sc.time);
    const auto a = run_le(p, phys, n, 99);
    const auto b = run_le(nd, e_nd, n, 99);
    struct Q {
        const char* name;
        const ss::Estimate& x;
        const ss::Estimate& y;
        double unit;
    } qs[] = {{"diffusivity", a.estimates.diffusivity, b.estimates.diffusivity, sc.diffusivity},
              {"mobility", a.estimates.mobility, b.estimates.mobility, sc.velocity},
              {"mean_duration", a.estimates.mean_duration, b.estimates.mean_duration, sc.time}};
    for (const auto& q : qs) {
        // Rounding can flip a rare threshold decision; allow 2% of a standard error.
        const auto c = compare(q.x.value / q.unit, 0.0, q.y.value, q.y.error, 0.0, 0.02);
        EXPECT_TRUE(check(c, std::string(q.name) + " physical/unit vs nondimensional"));
        EXPECT_NEAR(q.x.error / q.unit, q.y.error, 0.02 * q.y.error) << q.name;
    }
}

TEST(Units, PdmpPhysicalRunEqualsNondimensionalTwin) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.engine = ss::Engine::Pdmp;
    expect_twins(e, 4000);
}

TEST(Units, InclusionPhysicalRunEqualsNondimensionalTwin) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.dt = 1e-3;
    expect_twins(e, 2000);
}

TEST(Symmetry, ZeroBiasGivesZeroMobility) {
    const ss::ModelParams p{.bias = 0.0};
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.engine = ss::Engine::Pdmp;
    const auto r = run_le(p, e, 20000, 4);
    const auto c = compare(r.estimates.mobility.value, r.estimates.mobility.error, 0.0, 0.0);
    EXPECT_TRUE(check(c, "mobility with bias 0 against 0"));
}

void expect_mirror(const ss::EngineSettings& e, std::uint64_t n) {
    ss::ModelParams plus, minus;
    plus.bias = 0.342;
    minus.bias = -0.342;
    const auto a = run_le(plus, e, n, 11);
    const auto b = run_le(minus, e, n, 12);
    const auto cm = compare(a.estimates.mobility.value, a.estimates.mobility.error, -b.estimates.mobility.value,
                            b.estimates.mobility.error);
    EXPECT_TRUE(check(cm, "M0(bias) vs -M0(-bias)"));
    const auto cd = compare(a.estimates.diffusivity.value, a.estimates.diffusivity.error,
                            b.estimates.diffusivity.value, b.estimates.diffusivity.error);
    EXPECT_TRUE(check(cd, "D(bias) vs D(-bias)"));
    // The mobility is clearly non-zero here, so the sign flip is a real test.
    EXPECT_GT(std::fabs(a.estimates.mobility.value), 5 * a.estimates.mobility.error);
    EXPECT_LT(b.estimates.mobility.value, 0.0);
}

TEST(Symmetry, BiasSignFlipsMobilityKeepsDiffusivityPdmp) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.engine = ss::Engine::Pdmp;
    expect_mirror(e, 20000);
}

TEST(Symmetry, BiasSignFlipsMobilityKeepsDiffusivityInclusion) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.dt = 1e-3;
    expect_mirror(e, 3000);
}

} // namespace
