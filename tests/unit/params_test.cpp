// SPDX-License-Identifier: BSD-3-Clause
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "stickslip/params.hpp"

namespace ss = stickslip;

TEST(Params, NondimensionalRoundTrip) {
    ss::ModelParams p; // Fig. 2 case
    const ss::ModelParams nd = ss::to_nondimensional(p);
    EXPECT_DOUBLE_EQ(nd.friction, 1.0);
    EXPECT_DOUBLE_EQ(nd.noise, 1.0);
    const double tau0 = p.noise / (p.friction * p.friction);
    EXPECT_DOUBLE_EQ(nd.tau, p.tau / tau0);
    EXPECT_DOUBLE_EQ(nd.relaxation, p.relaxation / tau0);
    EXPECT_DOUBLE_EQ(nd.bias, p.bias / p.friction);
    const ss::ModelParams back = ss::from_nondimensional(nd, p.friction, p.noise);
    EXPECT_NEAR(back.tau, p.tau, 1e-15);
    EXPECT_NEAR(back.relaxation, p.relaxation, 1e-15);
    EXPECT_NEAR(back.bias, p.bias, 1e-15);
}

TEST(Params, InfiniteRelaxationSurvivesScaling) {
    ss::ModelParams p;
    p.relaxation = std::numeric_limits<double>::infinity();
    EXPECT_TRUE(std::isinf(ss::to_nondimensional(p).relaxation));
    EXPECT_EQ(p.inverse_relaxation(), 0.0);
}

TEST(Params, ValidationNamesTheParameter) {
    auto expect_bad = [](ss::ModelParams p, const char* name) {
        try {
            ss::validate(p);
            ADD_FAILURE() << "no error for " << name;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), name) << e.what();
        }
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    ss::ModelParams p;
    p.friction = 0; expect_bad(p, "friction");
    p = {}; p.friction = -1; expect_bad(p, "friction");
    p = {}; p.friction = nan; expect_bad(p, "friction");
    p = {}; p.noise = 0; expect_bad(p, "noise");
    p = {}; p.noise = inf; expect_bad(p, "noise");
    p = {}; p.tau = -0.1; expect_bad(p, "tau");
    p = {}; p.tau = inf; expect_bad(p, "tau");
    p = {}; p.relaxation = 0; expect_bad(p, "relaxation");
    p = {}; p.relaxation = nan; expect_bad(p, "relaxation");
    p = {}; p.bias = nan; expect_bad(p, "bias");
    p = {}; p.relaxation = inf; p.tau = 0; EXPECT_NO_THROW(ss::validate(p));
    p = {}; p.static_friction = 0.5 * p.friction; expect_bad(p, "static-friction");
    p = {}; p.static_friction = -1; expect_bad(p, "static-friction");
    p = {}; p.static_friction = inf; expect_bad(p, "static-friction");
    p = {}; p.static_friction = p.friction; EXPECT_NO_THROW(ss::validate(p));
    p = {}; p.static_friction = 2 * p.friction; EXPECT_NO_THROW(ss::validate(p));
}

TEST(Params, StaticFrictionSetsTheBandUnsetItIsTheFriction) {
    ss::ModelParams p; // Fig. 2: unset
    EXPECT_EQ(p.static_friction_level(), p.friction);
    EXPECT_FALSE(p.has_static_band());
    const double x_up = p.upper_threshold(), x_down = p.lower_threshold();
    p.static_friction = p.friction; // equal: the same thresholds, bit for bit
    EXPECT_EQ(p.upper_threshold(), x_up);
    EXPECT_EQ(p.lower_threshold(), x_down);
    EXPECT_FALSE(p.has_static_band());
    p.static_friction = 1.5 * p.friction; // the band's edges: (+-Delta_s - b(0)) / a
    EXPECT_TRUE(p.has_static_band());
    const double a = std::sqrt(p.noise / 2.0);
    EXPECT_DOUBLE_EQ(p.upper_threshold(), (p.static_friction - p.bias) / a);
    EXPECT_DOUBLE_EQ(p.lower_threshold(), (-p.static_friction - p.bias) / a);
    // Nondimensional: in units of the friction, and back.
    const ss::ModelParams nd = ss::to_nondimensional(p);
    EXPECT_DOUBLE_EQ(nd.static_friction, 1.5);
    EXPECT_DOUBLE_EQ(ss::from_nondimensional(nd, p.friction, p.noise).static_friction, p.static_friction);
    EXPECT_TRUE(std::isnan(ss::to_nondimensional(ss::ModelParams{}).static_friction));
}

TEST(Params, ScalesOfNondimensionalSystem) {
    ss::ModelParams p; // friction 3.84, noise 5
    const ss::Scales s = ss::scales_of(p);
    const double F = 3.84, G = 5.0;
    EXPECT_NEAR(s.time, G / (F * F), 1e-15 * s.time);
    EXPECT_NEAR(s.length, G * G / (F * F * F), 1e-15 * s.length);
    EXPECT_NEAR(s.velocity, G / F, 1e-15 * s.velocity);
    EXPECT_NEAR(s.acceleration, F, 1e-15);
    EXPECT_NEAR(s.diffusivity, G * G * G / (F * F * F * F), 1e-14 * s.diffusivity);
    EXPECT_NEAR(s.noise_level, 1.0 / std::sqrt(G / (F * F)), 1e-15 * s.noise_level);
    // Consistency: velocity = length/time, diffusivity = length^2/time, acceleration = velocity/time.
    EXPECT_NEAR(s.velocity, s.length / s.time, 1e-14 * s.velocity);
    EXPECT_NEAR(s.diffusivity, s.length * s.length / s.time, 1e-14 * s.diffusivity);
    EXPECT_NEAR(s.acceleration, s.velocity / s.time, 1e-14 * s.acceleration);
    // The nondimensional system has unit scales.
    const ss::Scales one = ss::scales_of(ss::to_nondimensional(p));
    for (double x : {one.time, one.length, one.velocity, one.acceleration, one.diffusivity, one.noise_level})
        EXPECT_DOUBLE_EQ(x, 1.0);
}

TEST(Params, ForceAmplitudeThresholdsAndDrift) {
    ss::ModelParams p;
    const double a = std::sqrt(5.0 / 2.0);
    EXPECT_NEAR(p.force_amplitude(), a, 1e-15);
    EXPECT_NEAR(p.upper_threshold(), (3.84 - 0.342) / a, 1e-14);
    EXPECT_NEAR(p.lower_threshold(), (-3.84 - 0.342) / a, 1e-14);
    EXPECT_NEAR(p.inverse_relaxation(), 1.0 / 0.067, 1e-12);
    EXPECT_NEAR(p.drift_at(0.5), -0.5 / 0.067 + 0.342, 1e-13);
    EXPECT_EQ(p.drift_at(0.0), 0.342);
    EXPECT_FALSE(p.white());
    p.tau = 0.0;
    EXPECT_TRUE(p.white());
    // Thresholds are in units of the paper's X [s^-1/2]: X' = X sqrt(tau0).
    ss::ModelParams q;
    const ss::ModelParams nd = ss::to_nondimensional(q);
    const double tau0 = ss::scales_of(q).time;
    EXPECT_NEAR(nd.upper_threshold(), q.upper_threshold() * std::sqrt(tau0), 1e-13);
    EXPECT_NEAR(nd.lower_threshold(), q.lower_threshold() * std::sqrt(tau0), 1e-13);
    EXPECT_NEAR(nd.force_amplitude(), std::sqrt(0.5), 1e-15);
}

TEST(Params, StationaryStateCondition) {
    const double inf = std::numeric_limits<double>::infinity();
    ss::ModelParams p;
    p.relaxation = inf;
    p.friction = 1.0;
    p.bias = 0.99;
    EXPECT_TRUE(ss::has_stationary_state(p));
    p.bias = 1.0;
    EXPECT_FALSE(ss::has_stationary_state(p));
    p.bias = -1.2;
    EXPECT_FALSE(ss::has_stationary_state(p));
    p.relaxation = 0.1; // viscous drag: always stationary
    EXPECT_TRUE(ss::has_stationary_state(p));
}

TEST(Params, FromNondimensionalToOtherUnits) {
    ss::ModelParams nd;
    nd.friction = 1.0;
    nd.noise = 1.0;
    nd.tau = 0.2;
    nd.relaxation = 0.5;
    nd.bias = 0.1;
    const ss::ModelParams p = ss::from_nondimensional(nd, 2.0, 8.0); // tau0 = 2 s
    EXPECT_EQ(p.friction, 2.0);
    EXPECT_EQ(p.noise, 8.0);
    EXPECT_NEAR(p.tau, 0.4, 1e-15);
    EXPECT_NEAR(p.relaxation, 1.0, 1e-15);
    EXPECT_NEAR(p.bias, 0.2, 1e-15);
    const ss::ModelParams back = ss::to_nondimensional(p);
    EXPECT_NEAR(back.tau, nd.tau, 1e-15);
    EXPECT_NEAR(back.relaxation, nd.relaxation, 1e-15);
    EXPECT_NEAR(back.bias, nd.bias, 1e-15);
}
