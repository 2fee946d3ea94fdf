// SPDX-License-Identifier: BSD-3-Clause
// Regression tests for bugs found in review.
#include <gtest/gtest.h>

#include <cmath>

#include "stickslip/bruteforce.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/kernels/pdmp.hpp"

namespace ss = stickslip;

namespace {

void expect_consistent_band(const ss::ModelParams& p, double grid) {
    ss::EngineSettings s = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    s.engine = ss::Engine::Pdmp;
    s.grid = grid;
    const auto c = ss::make_pdmp_constants(p, s);
    // The object at s+ accelerates strictly up, at s- strictly down, and the
    // band edges cannot move: the same expression the kernels use.
    EXPECT_GT(ss::pdmp_acceleration(c, c.k_plus + 1, +1), 0.0);
    EXPECT_LE(ss::pdmp_acceleration(c, c.k_plus, +1), 0.0);
    EXPECT_LT(ss::pdmp_acceleration(c, c.k_minus - 1, -1), 0.0);
    EXPECT_GE(ss::pdmp_acceleration(c, c.k_minus, -1), 0.0);
}

ss::DiffusivityResult pdmp_run(const ss::ModelParams& p, double grid, std::uint64_t n) {
    ss::DiffusivityRequest r;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    r.params = p;
    r.engine.engine = ss::Engine::Pdmp;
    r.engine.grid = grid;
    r.excursions = n;
    r.control.seed = 3;
    return ss::compute_diffusivity(r);
}

} // namespace

TEST(Regression, PdmpThresholdOnALatticePoint) {
    // a = 0.5, x* = 0.6 is a lattice point of grid 0.1, and 0.3/0.05 rounds to
    // 5.999...: the thresholds used to disagree with the acceleration's sign,
    // the object got stuck outside the band, and D came out exactly 0.
    ss::ModelParams p;
    p.friction = 0.5;
    p.noise = 0.5;
    p.bias = 0.2;
    expect_consistent_band(p, 0.1);
    const auto on = pdmp_run(p, 0.1, 1000);
    p.bias = 0.2 + 1e-9;
    const auto off = pdmp_run(p, 0.1, 1000);
    EXPECT_GT(on.estimates.diffusivity.value, 0.0);
    // Same seed, almost the same model: the estimates must be close.
    EXPECT_NEAR(on.estimates.diffusivity.value, off.estimates.diffusivity.value,
                4 * off.estimates.diffusivity.error);
}

TEST(Regression, PdmpRoundingGivesWrongSignAtTheStartState) {
    ss::ModelParams p;
    p.friction = 2;
    p.noise = 2;
    p.bias = 0.05;
    p.tau = 0.5;
    expect_consistent_band(p, 0.01);
}

TEST(Regression, BruteForceUsesTheSimulatedHorizon) {
    // t = 0.105 s with dt = 0.01 s simulates 10 steps = 0.1 s.
    ss::BruteForceRequest r;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    r.engine.dt = 0.01;
    r.params.relaxation = 0.067;
    r.horizon = 0.105;
    r.engine.dt = 0.01;
    r.trajectories = 200;
    const auto a = ss::compute_bruteforce(r);
    r.horizon = 0.1;
    const auto b = ss::compute_bruteforce(r);
    EXPECT_DOUBLE_EQ(a.estimates.diffusivity.value, b.estimates.diffusivity.value);
    EXPECT_FALSE(a.warnings.empty());
}
