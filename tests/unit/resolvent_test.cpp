// SPDX-License-Identifier: BSD-3-Clause
// Differential-inclusion engine (resolvent.hpp, theory.md, section 5): the
// resolvent, the constants and their validation, one hand-computed step, and
// the Brownian-bridge crossing probability of stop rule Q.
#include <gtest/gtest.h>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "stickslip/kernels/resolvent.hpp"
#include "stickslip/params.hpp"

namespace ss = stickslip;
using big = boost::multiprecision::cpp_bin_float_50;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

ss::EngineSettings with_dt(double dt) {
    ss::EngineSettings s = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    s.dt = dt;
    return s;
}

void expect_bad_dt(const ss::ModelParams& p, double dt) {
    try {
        ss::make_resolvent_constants(p, with_dt(dt));
        ADD_FAILURE() << "no error for dt = " << dt << " (relaxation " << p.relaxation << ")";
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), "dt") << "dt = " << dt << ": " << e.what();
    }
}

} // namespace

TEST(SoftThreshold, ZeroInsideTheBandShiftedOutside) {
    const double band = 0.384;
    for (double f : {0.0, 0.1, -0.1, 0.383999, -0.383999, 1e-300, -1e-300})
        EXPECT_EQ(ss::soft_threshold(f, band), 0.0) << "f=" << f;
    // Exactly at the edges: stuck, exactly 0.
    EXPECT_EQ(ss::soft_threshold(band, band), 0.0);
    EXPECT_EQ(ss::soft_threshold(-band, band), 0.0);
    // Outside: pulled towards 0 by exactly the band.
    for (double f : {0.5, 1.0, 123.0, std::nextafter(band, 1.0)}) {
        EXPECT_EQ(ss::soft_threshold(f, band), f - band) << "f=" << f;
        EXPECT_EQ(ss::soft_threshold(-f, band), -f + band) << "f=" << -f;
        EXPECT_GT(ss::soft_threshold(f, band), 0.0);
        EXPECT_LT(ss::soft_threshold(-f, band), 0.0);
    }
    // Zero band is the identity.
    EXPECT_EQ(ss::soft_threshold(0.7, 0.0), 0.7);
    EXPECT_EQ(ss::soft_threshold(-0.7, 0.0), -0.7);
}

TEST(ResolventConstants, AutoStopRuleResolution) {
    ss::ModelParams p; // Fig. 2: tau = 0.5, relaxation 0.067
    auto rule = [&](double dt, ss::StopRule r) {
        ss::EngineSettings s = with_dt(dt);
        s.stop_rule = r;
        return ss::make_resolvent_constants(p, s).rule;
    };
    EXPECT_EQ(rule(1e-4, ss::StopRule::Auto), ss::StopRule::Bridge);
    EXPECT_EQ(rule(0.05, ss::StopRule::Auto), ss::StopRule::Bridge);  // dt == 0.1 tau
    EXPECT_EQ(rule(0.0500001, ss::StopRule::Auto), ss::StopRule::Stuck);
    EXPECT_EQ(rule(0.06, ss::StopRule::Auto), ss::StopRule::Stuck);
    // Explicit choices are kept.
    EXPECT_EQ(rule(1e-4, ss::StopRule::Stuck), ss::StopRule::Stuck);
    EXPECT_EQ(rule(0.06, ss::StopRule::Bridge), ss::StopRule::Bridge);
    // Tiny tau (the paper's 1e-5 s) with dt = 1e-4: dt > 0.1 tau.
    p.tau = 1e-5;
    EXPECT_EQ(rule(1e-4, ss::StopRule::Auto), ss::StopRule::Stuck);
    EXPECT_EQ(rule(1e-6, ss::StopRule::Auto), ss::StopRule::Bridge);
}

TEST(ResolventConstants, ColoredConstants) {
    ss::ModelParams p;
    const double dt = 1e-3;
    const ss::ResolventConstants c = ss::make_resolvent_constants(p, with_dt(dt));
    EXPECT_FALSE(c.white);
    EXPECT_EQ(c.h, dt);
    EXPECT_NEAR(c.keep, 1.0 - dt / p.relaxation, 1e-16);
    EXPECT_NEAR(c.h_bias, dt * p.bias, 1e-18);
    EXPECT_NEAR(c.h_friction, dt * p.friction, 1e-18);
    EXPECT_NEAR(c.h_amp, dt * std::sqrt(p.noise / 2), 1e-18);
    EXPECT_NEAR(c.x_up, (p.friction - p.bias) / std::sqrt(p.noise / 2), 1e-14);
    EXPECT_NEAR(c.x_down, (-p.friction - p.bias) / std::sqrt(p.noise / 2), 1e-14);
    EXPECT_NEAR(c.bridge_rate, p.tau * p.tau / dt, 1e-12);
    const ss::OUStep ou = ss::ou_step(p.tau, dt);
    EXPECT_EQ(c.ou.s11, ou.s11);
    EXPECT_EQ(c.ou.l22, ou.l22);
    EXPECT_EQ(c.max_steps, ss::EngineSettings{}.max_work_per_excursion);
    // No viscous drag: V is kept as is by the free flight.
    p.relaxation = kInf;
    EXPECT_EQ(ss::make_resolvent_constants(p, with_dt(dt)).keep, 1.0);
}

TEST(ResolventConstants, WhiteNoiseFlagAndLevel) {
    ss::ModelParams p;
    p.tau = 0.0;
    const double dt = 1e-4;
    ss::ResolventConstants c = ss::make_resolvent_constants(p, with_dt(dt));
    EXPECT_TRUE(c.white);
    EXPECT_NEAR(c.h_amp, std::sqrt(p.noise * dt), 1e-16);
    // Default level: half the smaller of 0.7 noise/friction and sqrt(noise relaxation/2).
    const double expect_level = 0.5 * std::fmin(0.7 * 5.0 / 3.84, std::sqrt(5.0 * 0.067 / 2.0));
    EXPECT_NEAR(c.level, expect_level, 1e-15);
    EXPECT_NEAR(ss::white_level_default(p), expect_level, 1e-15);
    EXPECT_GT(c.level, 0.0);
    // Without viscous drag only the dry-friction scale counts.
    p.relaxation = kInf;
    EXPECT_NEAR(ss::make_resolvent_constants(p, with_dt(dt)).level, 0.5 * 0.7 * 5.0 / 3.84, 1e-15);
    // An explicit level wins.
    ss::EngineSettings s = with_dt(dt);
    s.white_level = 0.3;
    EXPECT_EQ(ss::make_resolvent_constants(p, s).level, 0.3);
}

TEST(ResolventConstants, ValidationNamesDt) {
    ss::ModelParams p; // relaxation 0.067
    expect_bad_dt(p, 0.0);
    expect_bad_dt(p, -1e-4);
    expect_bad_dt(p, kNaN);
    expect_bad_dt(p, kInf);
    expect_bad_dt(p, 0.1);   // dt > relaxation
    expect_bad_dt(p, 0.0671);
    EXPECT_NO_THROW(ss::make_resolvent_constants(p, with_dt(0.067))); // keep = 0 is allowed
    ss::ModelParams w = p;
    w.tau = 0.0;
    expect_bad_dt(w, 0.0);
    expect_bad_dt(w, kNaN);
    expect_bad_dt(w, 0.5);
    // Parameters are validated too.
    ss::ModelParams bad = p;
    bad.friction = -1;
    try {
        ss::make_resolvent_constants(bad, with_dt(1e-4));
        ADD_FAILURE() << "no error for friction -1";
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), "friction");
    }
    ss::ModelParams runaway = p;
    runaway.relaxation = kInf;
    runaway.bias = -4.0;
    try {
        ss::make_resolvent_constants(runaway, with_dt(1e-4));
        ADD_FAILURE() << "no error for |bias| > friction without drag";
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), "bias");
    }
}

namespace {

struct HandStep {
    double x_next, f, v_next;
    double x_scale, f_scale; // sums of the magnitudes of the terms: the rounding scale
};

// theory.md, section 5, evaluated with 50 digits:
//   m = (tau/h (1 - e^{-r}), e^{-r}),
//   Sigma11 = tau/h^2 (2r - 3 + 4e^{-r} - e^{-2r}), Sigma12 = (1 - e^{-r})^2/h, Sigma22 = (1 - e^{-2r})/tau,
//   (xbar, x_next) = m x + L (z1, z2), L the Cholesky factor of Sigma,
//   f = V + h(-V/tauL + bias + sqrt(noise/2) xbar),  V_next = f - clamp(f, -h friction, h friction).
HandStep hand_step(const ss::ModelParams& p, double h_d, double x_d, double v_d, double z1, double z2) {
    const big tau = p.tau, h = h_d, x = x_d, v = v_d;
    const big r = h / tau, e1 = exp(-r), e2 = exp(-2 * r);
    const big m1 = tau / h * (1 - e1), m2 = e1;
    const big s11 = tau / (h * h) * (2 * r - 3 + 4 * e1 - e2);
    const big s12 = (1 - e1) * (1 - e1) / h;
    const big s22 = (1 - e2) / tau;
    const big l11 = sqrt(s11), l21 = s12 / l11, l22 = sqrt(s22 - l21 * l21);
    const big xbar = m1 * x + l11 * z1;
    const big x_next = m2 * x + l21 * z1 + l22 * z2;
    const big inv_tl = std::isinf(p.relaxation) ? big(0) : big(1) / big(p.relaxation);
    const big f = v + h * (-v * inv_tl + big(p.bias) + sqrt(big(p.noise) / 2) * xbar);
    const big band = h * big(p.friction);
    big v_next = 0;
    if (f > band) v_next = f - band;
    if (f < -band) v_next = f + band;
    const big x_scale = abs(m2 * x) + abs(l21 * z1) + abs(l22 * z2);
    const big f_scale = abs(v) + h * (abs(v * inv_tl) + abs(big(p.bias)) + sqrt(big(p.noise) / 2) * abs(xbar));
    return {static_cast<double>(x_next), static_cast<double>(f), static_cast<double>(v_next),
            static_cast<double>(x_scale), static_cast<double>(f_scale)};
}

} // namespace

TEST(ResolventStep, HandComputedColoredStep) {
    struct Case {
        double tau, relaxation, dt, x, v, z1, z2;
    };
    const std::vector<Case> cases = {
        {0.02, 0.067, 0.04, 0.7, 0.2, 0.3, -1.1},   // r = 2
        {0.05, 0.067, 0.04, -1.3, -0.4, 1.7, 0.25}, // r = 0.8 (closed-form branch)
        {0.5, 0.067, 1e-3, 2.5, 0.0, 0.9, -0.6},    // r = 2e-3 (series branch)
        {1e-5, 0.067, 1e-4, 100.0, 0.05, -0.4, 2.0},// r = 10, the paper's tau
        {0.5, kInf, 1e-4, 0.3, 1.5, -2.2, 0.1},     // no viscous drag
    };
    for (const Case& k : cases) {
        ss::ModelParams p;
        p.tau = k.tau;
        p.relaxation = k.relaxation;
        const ss::ResolventConstants c = ss::make_resolvent_constants(p, with_dt(k.dt));
        double x_next = 0, f = 0;
        ss::resolvent_colored_step(c, k.x, k.v, k.z1, k.z2, x_next, f);
        const HandStep ref = hand_step(p, k.dt, k.x, k.v, k.z1, k.z2);
        // Relative 2e-15 of the terms' magnitudes: a few roundings of a short sum.
        EXPECT_NEAR(x_next, ref.x_next, 2e-15 * ref.x_scale) << "tau " << k.tau << " dt " << k.dt;
        EXPECT_NEAR(f, ref.f, 2e-15 * ref.f_scale) << "tau " << k.tau << " dt " << k.dt;
        const double v_next = ss::soft_threshold(f, c.h_friction);
        EXPECT_NEAR(v_next, ref.v_next, 4e-15 * ref.f_scale) << "tau " << k.tau << " dt " << k.dt;
    }
}

TEST(ResolventStep, StickingStepGivesExactlyZero) {
    ss::ModelParams p;
    const double dt = 1e-3;
    const ss::ResolventConstants c = ss::make_resolvent_constants(p, with_dt(dt));
    // At rest with X inside the band and no kick: |f| = h |bias + a xbar| < h friction.
    double x_next, f;
    ss::resolvent_colored_step(c, 0.0, 0.0, 0.0, 0.0, x_next, f);
    EXPECT_EQ(x_next, 0.0);
    EXPECT_NEAR(f, dt * p.bias, 1e-18);
    EXPECT_EQ(ss::soft_threshold(f, c.h_friction), 0.0);
    // Just above x*: the mean of X over the step still exceeds x* when X starts well above it,
    // and the object leaves with velocity f - h friction > 0.
    ss::resolvent_colored_step(c, c.x_up + 1.0, 0.0, 0.0, 0.0, x_next, f);
    EXPECT_GT(ss::soft_threshold(f, c.h_friction), 0.0);
    EXPECT_EQ(ss::soft_threshold(f, c.h_friction), f - c.h_friction);
}

namespace {
/// A side uniform chosen by the test (the static start's bridge test).
struct FixedSideUniform {
    double u;
    double side_uniform() const { return u; }
};
} // namespace

TEST(ResolventStep, StaticFrictionRules) {
    ss::ModelParams p;
    p.static_friction = 1.5 * p.friction;
    const double dt = 1e-3;
    const ss::ResolventConstants c = ss::make_resolvent_constants(p, with_dt(dt));
    ASSERT_TRUE(c.static_band);
    EXPECT_EQ(c.h_static, dt * p.static_friction);
    const double hk = c.h_friction, hs = c.h_static;
    // At rest: held while |f| <= h Delta_s, else started with f -+ h Delta.
    EXPECT_EQ(ss::static_friction_step(c, 0.0, 0.9 * hs, 0.9 * hs), 0.0);
    EXPECT_EQ(ss::static_friction_step(c, 0.0, -0.9 * hs, -0.9 * hs), 0.0);
    EXPECT_EQ(ss::static_friction_step(c, 0.0, 1.1 * hs, 1.1 * hs), 1.1 * hs - hk);
    EXPECT_EQ(ss::static_friction_step(c, 0.0, -1.1 * hs, -1.1 * hs), -1.1 * hs + hk);
    // Sliding: the soft threshold with h Delta (stays positive, or lands).
    EXPECT_EQ(ss::static_friction_step(c, 0.2, 1.3 * hk, 0.0), 1.3 * hk - hk);
    EXPECT_EQ(ss::static_friction_step(c, 0.2, 0.5 * hk, 0.0), 0.0);
    // Passing through 0: stops there when the force alone is in the static
    // band, goes on to the other side when it is beyond it.
    EXPECT_EQ(ss::static_friction_step(c, 0.2, -1.2 * hk, -1.2 * hk), 0.0);
    EXPECT_EQ(ss::static_friction_step(c, 0.2, -2.0 * hs, -1.6 * hs), -2.0 * hs + hk);
    EXPECT_EQ(ss::static_friction_step(c, -0.2, 1.2 * hk, 1.2 * hk), 0.0);
    EXPECT_EQ(ss::static_friction_step(c, -0.2, 2.0 * hs, 1.6 * hs), 2.0 * hs - hk);
    // Starting from rest with X at the band's edges: the mean force inside
    // the static band but beyond the kinetic one starts the slip when X
    // crossed the edge (its end beyond it, or the bridge: u below exp(-e)).
    const double f_mid = 1.2 * hk; // between h Delta and h Delta_s
    FixedSideUniform never{1.0}, always{0.0};
    EXPECT_EQ(ss::resolvent_static_start(c, c.x_up - 1.0, c.x_up + 0.01, f_mid, never), f_mid - hk);
    EXPECT_EQ(ss::resolvent_static_start(c, c.x_up - 0.01, c.x_up - 0.01, f_mid, always), f_mid - hk);
    EXPECT_EQ(ss::resolvent_static_start(c, c.x_up - 0.01, c.x_up - 0.01, f_mid, never), 0.0);
    EXPECT_EQ(ss::resolvent_static_start(c, c.x_down + 0.01, c.x_down - 0.01, -f_mid, never), -f_mid + hk);
    // Below the kinetic band no start, whatever X did.
    EXPECT_EQ(ss::resolvent_static_start(c, c.x_up - 1.0, c.x_up + 0.01, 0.5 * hk, always), 0.0);
    EXPECT_EQ(ss::resolvent_static_start(c, 0.0, 0.0, 1.1 * hs, never), 1.1 * hs - hk);
}

TEST(ResolventStep, StaticFrictionEqualToFrictionIsTheSoftThreshold) {
    // Delta_s = Delta: the static rules reduce to the soft threshold bit for
    // bit (the runs take the soft threshold's branch anyway; this is the
    // algebra behind "the same numbers").
    ss::ModelParams p;
    p.static_friction = p.friction;
    ss::ResolventConstants c = ss::make_resolvent_constants(p, with_dt(1e-3));
    EXPECT_FALSE(c.static_band);
    c.static_band = true; // force the static branch
    const double hk = c.h_friction;
    for (double v : {0.0, 0.3, -0.3})
        for (double f : {-3.0 * hk, -hk, -0.5 * hk, 0.0, 0.5 * hk, hk, 3.0 * hk}) {
            const double f0 = f - (1.0 - 0.0) * v; // no drag here: the free flight from rest
            EXPECT_EQ(ss::static_friction_step(c, v, f, f0), ss::soft_threshold(f, hk)) << "v " << v << " f " << f;
        }
}

TEST(ResolventStep, BridgeCrossingProbability) {
    ss::ModelParams p;
    for (double dt : {1e-4, 1e-3}) {
        const ss::ResolventConstants c = ss::make_resolvent_constants(p, with_dt(dt));
        const double level = c.x_down;
        for (double d0 : {1e-4, 1e-3, 0.01, 0.05}) {
            for (double d1 : {0.0, 1e-3, 0.02}) {
                const double x0 = level + d0, x1 = level + d1;
                const double want = std::exp(-(x0 - level) * (x1 - level) * p.tau * p.tau / dt);
                EXPECT_NEAR(ss::bridge_crossing_probability(c, x0, x1, level), want, 1e-15)
                    << "dt " << dt << " d0 " << d0 << " d1 " << d1;
                // Mirror image (from below the upper threshold).
                const double y0 = c.x_up - d0, y1 = c.x_up - d1;
                EXPECT_NEAR(ss::bridge_crossing_probability(c, y0, y1, c.x_up),
                            std::exp(-(y0 - c.x_up) * (y1 - c.x_up) * p.tau * p.tau / dt), 1e-15);
            }
        }
        // Endpoint on the level: certain. Far from it: exactly 0 (exponent beyond the cutoff).
        EXPECT_EQ(ss::bridge_crossing_probability(c, level + 0.3, level, level), 1.0);
        EXPECT_EQ(ss::bridge_crossing_probability(c, level + 1.0, level + 1.0, level), 0.0);
        const double e_just_below = 49.0;
        const double d = std::sqrt(e_just_below * dt) / p.tau;
        EXPECT_NEAR(ss::bridge_crossing_probability(c, level + d, level + d, level), std::exp(-49.0),
                    1e-12 * std::exp(-49.0));
    }
}

namespace {
// Replays fixed normal pairs.
struct ScriptedNormals {
    std::vector<std::pair<double, double>> z;
    std::size_t next = 0;
    struct Pair {
        double x, y;
    };
    Pair normal2() {
        const auto& q = z.at(next++);
        return {q.first, q.second};
    }
    double uniform() { return 0.5; }
    double side_uniform() const { return 0.5; } // the static band's start test (unused at Delta_s = Delta)
};
} // namespace

TEST(ResolventStep, TrajectoryIsTheLeftPointSumOfSteps) {
    ss::ModelParams p;
    const double dt = 1e-3;
    const ss::ResolventConstants c = ss::make_resolvent_constants(p, with_dt(dt));
    ScriptedNormals rng{{{3.0, 0.5}, {2.5, -1.0}, {-0.3, 0.2}, {-4.0, 1.0}, {0.1, 0.1}}};
    const double x0 = 2.8, v0 = 0.1;
    const ss::ExcursionOutcome o = ss::resolvent_trajectory(c, x0, v0, 5, rng);
    // Manual recursion with the hand formulas (50 digits): U = h * (V_0 + ... + V_4).
    double x = x0, v = v0, u = 0.0;
    for (const auto& z : rng.z) {
        const HandStep s = hand_step(p, dt, x, v, z.first, z.second);
        u += dt * v;
        x = s.x_next;
        v = s.v_next;
    }
    EXPECT_NEAR(o.displacement, u, 1e-14 * (std::fabs(u) + dt));
    EXPECT_EQ(o.duration, 5 * dt);
    EXPECT_EQ(o.work, 5u);
    EXPECT_FALSE(o.capped);
}
