// SPDX-License-Identifier: BSD-3-Clause
// The white-noise Fokker-Planck solver (fokker_planck.hpp) against every exact
// reference that does not share its code path: Touchette et al.'s closed forms
// for pure dry friction (first moment, autocorrelation, propagator), and for
// drifts with bias and drag the stationary quantities of HayakawaDensity and
// white_noise_reference, including D through the Green-Kubo integral of the
// solver's autocorrelation, D = 2 int_0^inf (<V(t)V(0)> - M0^2) dt.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/fokker_planck.hpp"
#include "stickslip/params.hpp"

namespace ss = stickslip;

namespace {

ss::ModelParams dry(double friction, double noise, double bias) {
    ss::ModelParams p;
    p.friction = friction;
    p.noise = noise;
    p.tau = 0.0;
    p.relaxation = std::numeric_limits<double>::infinity();
    p.bias = bias;
    return p;
}

// The paper's Fig. 2 drift and friction, white noise.
ss::ModelParams fig2() {
    ss::ModelParams p;
    p.friction = 3.84;
    p.noise = 5.0;
    p.tau = 0.0;
    p.relaxation = 0.067;
    p.bias = 0.342;
    return p;
}

// 2 int_0^{s_max^2} (C(t) - m0^2) dt with t = s^2 (C has a t^{3/2} term at 0,
// smooth in s), Gauss-Legendre panels in s; all lags in one unsorted call.
double green_kubo(const ss::WhiteNoiseFokkerPlanck& fp, double m0, double s_max, int panels) {
    using Rule = boost::math::quadrature::gauss<double, 10>;
    std::vector<double> times, weights;
    const double width = s_max / panels;
    for (int j = 0; j < panels; ++j) {
        const double c = (j + 0.5) * width, r = 0.5 * width;
        for (std::size_t i = 0; i < Rule::abscissa().size(); ++i) {
            for (double sign : {-1.0, 1.0}) {
                const double s = c + sign * r * Rule::abscissa()[i];
                times.push_back(s * s);
                weights.push_back(r * Rule::weights()[i] * 2.0 * s);
            }
        }
    }
    const std::vector<double> c = fp.autocorrelation(times);
    double integral = 0.0;
    for (std::size_t k = 0; k < times.size(); ++k) integral += weights[k] * (c[k] - m0 * m0);
    return 2.0 * integral;
}

} // namespace

// ---- Pure dry friction: the closed forms ----------------------------------------

TEST(FokkerPlanck, PureDryFrictionFirstMomentMatchesTouchette) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    const ss::WhiteNoiseFokkerPlanck fp(p);
    const std::vector<double> times = {0.0, 0.05, 0.125, 0.25, 0.5, 1.0, 2.5, 5.0};
    for (double v0 : {1.0, -0.37, 2.5}) {
        const std::vector<double> e = fp.first_moment(v0, times);
        for (std::size_t k = 0; k < times.size(); ++k)
            EXPECT_NEAR(e[k], ss::dry_friction_first_moment(p, times[k], v0), 2e-6)
                << "v0 " << v0 << " t " << times[k];
        EXPECT_EQ(e[0], v0);
    }
}

TEST(FokkerPlanck, PureDryFrictionAutocorrelationMatchesTouchette) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    const ss::WhiteNoiseFokkerPlanck fp(p);
    const std::vector<double> times = {0.0, 0.01, 0.1, 0.5, 1.0, 2.0, 5.0};
    const std::vector<double> c = fp.autocorrelation(times);
    for (std::size_t k = 0; k < times.size(); ++k)
        EXPECT_NEAR(c[k], ss::dry_friction_autocorrelation(p, times[k]), 1e-6) << "t " << times[k];
    // Green-Kubo on the solver's own autocorrelation: D = 5/4.
    EXPECT_NEAR(green_kubo(fp, 0.0, 9.0, 30), 1.25, 2e-6);
}

TEST(FokkerPlanck, PureDryFrictionDensityMatchesThePropagator) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    const ss::WhiteNoiseFokkerPlanck fp(p);
    const std::vector<double> times = {0.5, 2.0};
    std::vector<double> v;
    for (double x = -3.0; x <= 4.0; x += 0.0371) v.push_back(x);
    v.push_back(0.0);
    for (double v0 : {1.0, -0.2}) {
        const auto d = fp.density(v0, times, v);
        for (std::size_t k = 0; k < times.size(); ++k)
            for (std::size_t j = 0; j < v.size(); ++j)
                EXPECT_NEAR(d[k][j], ss::dry_friction_propagator(p, v[j], times[k], v0), 5e-6)
                    << "v0 " << v0 << " t " << times[k] << " v " << v[j];
    }
}

// ---- Bias and drag: stationary references ------------------------------------------

TEST(FokkerPlanck, BiasedViscousCaseRelaxesToHayakawa) {
    const ss::ModelParams p = fig2();
    const ss::WhiteNoiseFokkerPlanck fp(p);
    const ss::HayakawaDensity hd(p);
    const ss::WhiteNoiseReference ref = ss::white_noise_reference(p);
    const double vel = ss::scales_of(p).velocity, m0 = ref.mobility;
    // The discrete stationary state is Hayakawa's, by construction.
    std::vector<double> v;
    for (double x = -0.8; x <= 0.8; x += 0.0173) v.push_back(x);
    const std::vector<double> stationary = fp.stationary_density(v);
    for (std::size_t j = 0; j < v.size(); ++j) EXPECT_NEAR(stationary[j] / hd(v[j]), 1.0, 1e-12) << v[j];
    // ... and the transient law reaches it (3 s = 45 relaxation times).
    const auto late = fp.density(1.0, {3.0}, v);
    for (std::size_t j = 0; j < v.size(); ++j) EXPECT_NEAR(late[0][j] / hd(v[j]), 1.0, 1e-8) << v[j];
    const std::vector<double> e = fp.first_moment(1.0, {0.0, 3.0});
    EXPECT_EQ(e[0], 1.0);
    EXPECT_NEAR(e[1], m0, 1e-10 * vel);
    // <V(t)V(0)> from <V^2> = Var + M0^2 down to M0^2 (not the covariance).
    const std::vector<double> c = fp.autocorrelation({0.0, 3.0});
    EXPECT_NEAR(c[0], ref.variance + m0 * m0, 1e-9 * vel * vel);
    EXPECT_NEAR(c[1], m0 * m0, 1e-9 * vel * vel);
    EXPECT_NEAR(hd.mean(), m0, 1e-12 * vel);
    // Green-Kubo on the solver's autocorrelation against the quadrature D.
    const double d = green_kubo(fp, m0, std::sqrt(60 * p.relaxation), 20);
    EXPECT_NEAR(d / ref.diffusivity, 1.0, 1e-6) << d << " vs " << ref.diffusivity;
}

TEST(FokkerPlanck, DryFrictionWithBiasMatchesItsClosedForms) {
    // No drag, g = 0.5: M0' = g/(1-g^2), Var' = (1+g^2)/(2(1-g^2)^2), D' of theory.md, section 8.
    const double g = 0.5;
    const ss::ModelParams p = dry(1.0, 1.0, g);
    const ss::WhiteNoiseFokkerPlanck fp(p);
    const double m0 = g / (1 - g * g), var = (1 + g * g) / (2 * (1 - g * g) * (1 - g * g));
    const std::vector<double> c = fp.autocorrelation({0.0, 400.0});
    EXPECT_NEAR(c[0], var + m0 * m0, 1e-9);
    EXPECT_NEAR(c[1], m0 * m0, 1e-9);
    EXPECT_NEAR(fp.first_moment(-1.0, {400.0})[0], m0, 1e-9);
    const double d = green_kubo(fp, m0, 20.0, 40);
    EXPECT_NEAR(d / ss::dry_friction_diffusivity(p), 1.0, 2e-6) << d;
}

TEST(FokkerPlanck, BiasedViscousCaseIsConvergedAtDefaultResolution) {
    // No closed form for the transient: compare with twice the resolution in
    // both space and time (the errors, O(dt^2) and smaller in h, shrink about
    // 4-fold), at the times where the law still moves.
    const ss::ModelParams p = fig2();
    ss::FokkerPlanckSettings fine;
    fine.cells = 2 * fine.cells;
    fine.steps_per_unit_time = 2 * fine.steps_per_unit_time;
    const ss::WhiteNoiseFokkerPlanck coarse_fp(p), fine_fp(p, fine);
    const std::vector<double> times = {0.002, 0.01, 0.05, 0.2};
    const double vel = ss::scales_of(p).velocity;
    const auto a = coarse_fp.first_moment(0.8, times), b = fine_fp.first_moment(0.8, times);
    const auto ca = coarse_fp.autocorrelation(times), cb = fine_fp.autocorrelation(times);
    for (std::size_t k = 0; k < times.size(); ++k) {
        EXPECT_NEAR(a[k], b[k], 2e-7 * vel) << "t " << times[k];
        EXPECT_NEAR(ca[k], cb[k], 2e-7 * vel * vel) << "t " << times[k];
    }
}

// ---- Units, ordering, settings ---------------------------------------------------

TEST(FokkerPlanck, PhysicalRunAgreesWithItsNondimensionalTwin) {
    const ss::ModelParams p = fig2();
    const ss::ModelParams nd = ss::to_nondimensional(p);
    const ss::Scales s = ss::scales_of(p);
    const ss::WhiteNoiseFokkerPlanck a(p), b(nd);
    EXPECT_NEAR(a.cell_width() / (b.cell_width() * s.velocity), 1.0, 1e-12);
    const std::vector<double> times = {0.0, 0.01, 0.1};
    std::vector<double> nd_times;
    for (double t : times) nd_times.push_back(t / s.time);
    const double v0 = 0.9;
    const auto ea = a.first_moment(v0, times), eb = b.first_moment(v0 / s.velocity, nd_times);
    const auto ca = a.autocorrelation(times), cb = b.autocorrelation(nd_times);
    for (std::size_t k = 0; k < times.size(); ++k) {
        EXPECT_NEAR(ea[k] / (eb[k] * s.velocity), 1.0, 1e-10) << times[k];
        EXPECT_NEAR(ca[k] / (cb[k] * s.velocity * s.velocity), 1.0, 1e-10) << times[k];
    }
    const std::vector<double> v = {-0.3, 0.0, 0.2};
    std::vector<double> nd_v;
    for (double x : v) nd_v.push_back(x / s.velocity);
    const auto da = a.density(v0, {0.05}, v), db = b.density(v0 / s.velocity, {0.05 / s.time}, nd_v);
    for (std::size_t j = 0; j < v.size(); ++j) EXPECT_NEAR(da[0][j] / (db[0][j] / s.velocity), 1.0, 1e-10) << v[j];
}

TEST(FokkerPlanck, TimesInAnyOrderGiveTheSameResults) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    const ss::WhiteNoiseFokkerPlanck fp(p);
    std::vector<double> times = {0.0, 0.05, 0.3, 0.3, 1.0, 2.0};
    const auto sorted_e = fp.first_moment(0.5, times), sorted_c = fp.autocorrelation(times);
    std::vector<std::size_t> order = {4, 0, 2, 5, 1, 3};
    std::vector<double> shuffled;
    for (std::size_t k : order) shuffled.push_back(times[k]);
    const auto e = fp.first_moment(0.5, shuffled), c = fp.autocorrelation(shuffled);
    for (std::size_t k = 0; k < order.size(); ++k) {
        EXPECT_EQ(e[k], sorted_e[order[k]]) << shuffled[k];
        EXPECT_EQ(c[k], sorted_c[order[k]]) << shuffled[k];
    }
    EXPECT_TRUE(fp.first_moment(0.5, {}).empty());
}

TEST(FokkerPlanck, SettingsChangeResolutionNotResults) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    ss::FokkerPlanckSettings chosen;
    chosen.half_width = 12.0;
    chosen.cells = 3000;
    chosen.richardson = false;
    const ss::WhiteNoiseFokkerPlanck a(p), b(p, chosen);
    EXPECT_NEAR(b.lower_velocity(), -12.0, 1e-12); // centred on M0 = 0
    EXPECT_NEAR(b.upper_velocity(), 12.0, 1e-12);
    EXPECT_NEAR(b.cell_width(), 24.0 / 3000, 1e-15);
    const std::vector<double> times = {0.25, 1.0};
    const auto eb = b.first_moment(1.0, times);
    for (std::size_t k = 0; k < times.size(); ++k)
        EXPECT_NEAR(eb[k], ss::dry_friction_first_moment(p, times[k], 1.0), 3e-5) << times[k]; // O(h^2) without Richardson
    // A v0 far outside the chosen interval widens the grid instead of failing.
    EXPECT_NEAR(b.first_moment(20.0, {1.0})[0], 19.0, 1e-4);
}

TEST(FokkerPlanck, RejectsInvalidInput) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    auto expect_parameter = [](const std::string& name, auto&& call) {
        try {
            call();
            ADD_FAILURE() << "no error, expected one for " << name;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), name) << e.what();
        }
    };
    expect_parameter("bias", [&] { ss::WhiteNoiseFokkerPlanck fp(dry(1.0, 1.0, 1.2)); });
    ss::FokkerPlanckSettings s;
    s.cells = 3;
    expect_parameter("cells", [&] { ss::WhiteNoiseFokkerPlanck fp(p, s); });
    s = {};
    s.steps_per_unit_time = 0;
    expect_parameter("steps_per_unit_time", [&] { ss::WhiteNoiseFokkerPlanck fp(p, s); });
    s = {};
    s.half_width = -1.0;
    expect_parameter("half_width", [&] { ss::WhiteNoiseFokkerPlanck fp(p, s); });

    s = {};
    s.cells = 200; // cheap: only validation is exercised below
    const ss::WhiteNoiseFokkerPlanck fp(p, s);
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    expect_parameter("time", [&] { fp.first_moment(1.0, {0.5, -0.1}); });
    expect_parameter("time", [&] { fp.autocorrelation({nan}); });
    expect_parameter("time", [&] { fp.autocorrelation({inf}); });
    expect_parameter("time", [&] { fp.density(1.0, {0.0}, {0.0}); });
    expect_parameter("v0", [&] { fp.first_moment(inf, {1.0}); });
    expect_parameter("v0", [&] { fp.density(nan, {1.0}, {0.0}); });
    expect_parameter("v0", [&] { fp.first_moment(1e9, {1.0}); });
}
