// SPDX-License-Identifier: BSD-3-Clause
// Exact white-noise references (analytic.hpp, theory.md, section 8): the
// closed forms for pure dry friction, the viscous limit, the normalisation of
// Hayakawa's density, unit scaling, and an independent grid quadrature of the
// M0/D formulas for a case with every force present. The transient closed forms
// of Touchette et al. are checked against the paper's Table I and against each
// other by quadrature (normalisation, first moment, Chapman-Kolmogorov,
// autocorrelation from the first moment, Green-Kubo), which no shared typo
// could pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/params.hpp"

namespace ss = stickslip;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

ss::ModelParams dry(double friction, double noise, double bias) {
    ss::ModelParams p;
    p.friction = friction;
    p.noise = noise;
    p.tau = 0.0;
    p.relaxation = kInf;
    p.bias = bias;
    return p;
}

::testing::AssertionResult rel_close(const std::string& what, double got, double want, double tol) {
    const double err = std::fabs(got - want) / std::fabs(want);
    if (err <= tol) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << ": got " << got << ", want " << want << ", relative error "
                                         << err << " > " << tol;
}

// Independent reference for M0, Var and D by grid quadrature (theory.md, section 8):
// p ~ exp(-phi), phi(v) = v^2/(noise tauL) + 2 friction |v|/noise - 2 bias v/noise;
// M0 = int v p, F(v) = int_{-inf}^v (u - M0) p du, D = (4/noise) int F^2/p dv.
// Grid with v = 0 as a node; F by 3-point Gauss-Legendre per cell (taken from the
// nearer end), outer integrals by composite Simpson on panels that do not cross 0.
struct GridReference {
    double m0, var, d;
};

GridReference grid_reference(const ss::ModelParams& p, double hcell) {
    const long double inv_tl = std::isinf(p.relaxation) ? 0.0L : 1.0L / p.relaxation;
    const long double G = p.noise, Dl = p.friction, g = p.bias;
    auto phi = [&](long double v) { return v * v * inv_tl / G + 2 * Dl * std::fabs(v) / G - 2 * g * v / G; };
    // Mode of the density (minimum of phi) to centre the exponent.
    long double vmin = 0;
    if (inv_tl > 0) {
        if (g > Dl) vmin = (g - Dl) / inv_tl;
        if (g < -Dl) vmin = (g + Dl) / inv_tl;
    }
    const long double phimin = phi(vmin);
    auto q = [&](long double v) { return std::exp(-(phi(v) - phimin)); };
    // Range where phi - phimin < 80 (the mass beyond is < e^-80).
    auto edge = [&](long double dir) {
        long double v = vmin;
        while (phi(v) - phimin < 80) v += dir * 0.01L;
        return v;
    };
    const long double lo = edge(-1), hi = edge(+1);
    const long double h = hcell;
    const long n_neg = static_cast<long>(std::ceil(-lo / h / 2)) * 2; // even: Simpson panels
    const long n_pos = static_cast<long>(std::ceil(hi / h / 2)) * 2;
    std::vector<long double> v;
    for (long k = -n_neg; k <= n_pos; ++k) v.push_back(k * h);
    const std::size_t n = v.size();
    auto simpson = [&](const std::vector<long double>& f) {
        long double s = 0;
        for (std::size_t k = 0; k + 2 < n; k += 2) s += h / 3 * (f[k] + 4 * f[k + 1] + f[k + 2]);
        return s;
    };
    std::vector<long double> fq(n), fvq(n), fvvq(n);
    for (std::size_t k = 0; k < n; ++k) {
        fq[k] = q(v[k]);
        fvq[k] = v[k] * fq[k];
    }
    const long double z = simpson(fq);
    const long double m0 = simpson(fvq) / z;
    for (std::size_t k = 0; k < n; ++k) fvvq[k] = (v[k] - m0) * (v[k] - m0) * fq[k];
    const long double var = simpson(fvvq) / z;
    // Cell integrals of (u - M0) q by 3-point Gauss-Legendre (cells never cross 0).
    const long double gl_x = std::sqrt(0.6L), w0 = 8.0L / 9, w1 = 5.0L / 9;
    std::vector<long double> cell(n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const long double c = 0.5L * (v[k] + v[k + 1]), r = 0.5L * h;
        auto f = [&](long double u) { return (u - m0) * q(u); };
        cell[k] = r * (w0 * f(c) + w1 * (f(c - r * gl_x) + f(c + r * gl_x)));
    }
    std::vector<long double> left(n, 0.0L), right(n, 0.0L);
    for (std::size_t k = 1; k < n; ++k) left[k] = left[k - 1] + cell[k - 1];
    for (std::size_t k = n - 1; k-- > 0;) right[k] = right[k + 1] - cell[k];
    std::vector<long double> integrand(n);
    for (std::size_t k = 0; k < n; ++k) {
        const long double F = v[k] <= m0 ? left[k] : right[k];
        integrand[k] = F * F / fq[k];
    }
    const long double d = 4.0L / G * simpson(integrand) / z;
    return {static_cast<double>(m0), static_cast<double>(var), static_cast<double>(d)};
}

} // namespace

TEST(WhiteNoiseReference, PureDryFrictionNondimensional) {
    const ss::WhiteNoiseReference r = ss::white_noise_reference(dry(1.0, 1.0, 0.0));
    EXPECT_TRUE(rel_close("D", r.diffusivity, 1.25, 1e-10));
    EXPECT_TRUE(rel_close("variance", r.variance, 0.5, 1e-10));
    EXPECT_NEAR(r.mobility, 0.0, 1e-13);
}

TEST(WhiteNoiseReference, PureDryFrictionPhysicalUnits) {
    const double friction = 3.84, noise = 5.0;
    const ss::WhiteNoiseReference r = ss::white_noise_reference(dry(friction, noise, 0.0));
    EXPECT_TRUE(rel_close("D", r.diffusivity, 1.25 * std::pow(noise, 3) / std::pow(friction, 4), 1e-10));
    EXPECT_TRUE(rel_close("variance", r.variance, 0.5 * std::pow(noise / friction, 2), 1e-10));
    EXPECT_NEAR(r.mobility, 0.0, 1e-13 * noise / friction);
}

TEST(WhiteNoiseReference, DryFrictionWithBiasMatchesClosedForms) {
    for (double g : {0.2, 0.5, -0.7}) {
        for (auto [friction, noise] : {std::pair{1.0, 1.0}, std::pair{3.84, 5.0}, std::pair{0.5, 0.16}}) {
            const ss::ModelParams p = dry(friction, noise, g * friction);
            const std::string where = "g=" + std::to_string(g) + " friction=" + std::to_string(friction) +
                                      " noise=" + std::to_string(noise);
            // theory.md, section 8, written out here independently of analytic.cpp.
            const double g2 = g * g, vel = noise / friction, diff = std::pow(noise, 3) / std::pow(friction, 4);
            const double m0 = vel * g / (1 - g2);
            const double var = vel * vel * (1 + g2) / (2 * std::pow(1 - g2, 2));
            const double d = diff * (5 * g2 * g2 + 22 * g2 + 5) / (4 * std::pow(1 - g2, 4));
            EXPECT_TRUE(rel_close("dry_friction_mobility " + where, ss::dry_friction_mobility(p), m0, 1e-14));
            EXPECT_TRUE(rel_close("dry_friction_diffusivity " + where, ss::dry_friction_diffusivity(p), d, 1e-14));
            const ss::WhiteNoiseReference r = ss::white_noise_reference(p);
            EXPECT_TRUE(rel_close("quadrature M0 " + where, r.mobility, m0, 1e-9));
            EXPECT_TRUE(rel_close("quadrature D " + where, r.diffusivity, d, 1e-9));
            EXPECT_TRUE(rel_close("quadrature variance " + where, r.variance, var, 1e-9));
        }
    }
}

TEST(WhiteNoiseReference, ViscousLimit) {
    // Negligible friction (1e-6 m s^-2 against a velocity scale sqrt(noise tauL/2) = 0.16
    // m/s over tauL = 0.05 s, i.e. a relative perturbation ~ friction tauL/0.16 ~ 3e-7):
    // D = tauL^2 noise (Ornstein-Uhlenbeck velocity), Var = noise tauL/2, M0 = tauL bias.
    for (double bias : {0.0, 0.3}) {
        ss::ModelParams p;
        p.friction = 1e-6;
        p.noise = 1.0;
        p.tau = 0.0;
        p.relaxation = 0.05;
        p.bias = bias;
        const ss::WhiteNoiseReference r = ss::white_noise_reference(p);
        EXPECT_TRUE(rel_close("D", r.diffusivity, 0.05 * 0.05 * 1.0, 1e-5)) << "bias " << bias;
        EXPECT_TRUE(rel_close("variance", r.variance, 1.0 * 0.05 / 2, 1e-5)) << "bias " << bias;
        EXPECT_NEAR(r.mobility, 0.05 * bias, 1e-5 * 0.16) << "bias " << bias;
    }
}

TEST(WhiteNoiseReference, MatchesIndependentGridQuadrature) {
    // All forces present: the paper's Fig. 2 drift and friction (tau ignored), a strong
    // bias beyond friction (the mode moves off 0), and a negative bias.
    std::vector<ss::ModelParams> cases(3);
    cases[1].bias = 6.0; // |bias| > friction: allowed with viscous drag
    cases[2].bias = -1.0;
    cases[2].relaxation = 0.5;
    cases[2].noise = 1.0;
    for (const ss::ModelParams& p : cases) {
        const std::string where = "bias " + std::to_string(p.bias) + " relaxation " + std::to_string(p.relaxation);
        const GridReference g = grid_reference(p, 2e-4 * std::sqrt(p.noise * p.relaxation));
        const ss::WhiteNoiseReference r = ss::white_noise_reference(p);
        EXPECT_TRUE(rel_close("M0 " + where, r.mobility, g.m0, 1e-9));
        EXPECT_TRUE(rel_close("variance " + where, r.variance, g.var, 1e-9));
        EXPECT_TRUE(rel_close("D " + where, r.diffusivity, g.d, 1e-9));
    }
}

TEST(WhiteNoiseReference, PhysicalRunAgreesWithItsNondimensionalTwin) {
    ss::ModelParams p; // Fig. 2
    p.tau = 0.0;
    const ss::ModelParams nd = ss::to_nondimensional(p);
    const ss::Scales s = ss::scales_of(p);
    const ss::WhiteNoiseReference a = ss::white_noise_reference(p), b = ss::white_noise_reference(nd);
    EXPECT_TRUE(rel_close("D", a.diffusivity, b.diffusivity * s.diffusivity, 1e-10));
    EXPECT_TRUE(rel_close("M0", a.mobility, b.mobility * s.velocity, 1e-10));
    EXPECT_TRUE(rel_close("variance", a.variance, b.variance * s.velocity * s.velocity, 1e-10));
}

TEST(Hayakawa, DensityIsNormalisedAndHasTheRightShape) {
    for (double bias : {0.342, 6.0, -0.5}) {
        ss::ModelParams p; // Fig. 2
        p.bias = bias;
        auto dens = [&](double v) { return ss::hayakawa_density(p, v); };
        using boost::math::quadrature::gauss_kronrod;
        // The density has a kink at 0; integrate each side to where it is < e^-700.
        const double mode = bias > p.friction ? p.relaxation * (bias - p.friction) : 0.0;
        double total = 0.0;
        const double reach = std::sqrt(p.noise * p.relaxation * 800.0) + std::fabs(mode);
        std::vector<double> cuts = {-reach, 0.0, reach};
        if (mode != 0.0) cuts = {-reach, 0.0, mode, reach};
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
            total += gauss_kronrod<double, 61>::integrate(dens, cuts[k], cuts[k + 1], 15, 1e-14);
        EXPECT_NEAR(total, 1.0, 1e-10) << "bias " << bias;
        // Ratios against theory.md, section 8: p ~ exp(-v^2/(noise tauL) - 2 friction |v|/noise + 2 bias v/noise).
        auto logp = [&](double v) {
            return -v * v / (p.noise * p.relaxation) - 2 * p.friction * std::fabs(v) / p.noise + 2 * bias * v / p.noise;
        };
        for (double v : {-1.0, -0.3, 0.2, 0.7, 1.5}) {
            EXPECT_NEAR(std::log(dens(v) / dens(0.1)), logp(v) - logp(0.1), 1e-12) << "bias " << bias << " v " << v;
            EXPECT_NEAR(ss::hayakawa_potential(p, v) - ss::hayakawa_potential(p, 0.1), -(logp(v) - logp(0.1)),
                        1e-12)
                << "bias " << bias << " v " << v;
        }
    }
    // Pure dry friction, nondimensional: p(v) = e^{-2|v|}.
    const ss::ModelParams d = dry(1.0, 1.0, 0.0);
    for (double v : {-2.0, -0.5, 0.0, 0.25, 3.0})
        EXPECT_NEAR(ss::hayakawa_density(d, v), std::exp(-2 * std::fabs(v)), 1e-13) << v;
}

TEST(WhiteNoiseReference, NoStationaryStateThrowsBias) {
    for (double bias : {1.0, -1.0, 1.5, -3.0}) {
        const ss::ModelParams p = dry(1.0, 1.0, bias);
        try {
            ss::white_noise_reference(p);
            ADD_FAILURE() << "no error for bias " << bias;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), "bias") << e.what();
        }
        try {
            ss::hayakawa_density(p, 0.0);
            ADD_FAILURE() << "no error for bias " << bias;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), "bias") << e.what();
        }
    }
    // With viscous drag any bias has a stationary state.
    ss::ModelParams v = dry(1.0, 1.0, 3.0);
    v.relaxation = 0.2;
    EXPECT_NO_THROW(ss::white_noise_reference(v));
    // Invalid parameters are named.
    ss::ModelParams bad = dry(1.0, 1.0, 0.0);
    bad.noise = -1;
    try {
        ss::white_noise_reference(bad);
        ADD_FAILURE();
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), "noise");
    }
}

// ---- HayakawaDensity ---------------------------------------------------------

namespace {

std::vector<ss::ModelParams> hayakawa_cases() {
    std::vector<ss::ModelParams> cases(4); // Fig. 2 drift and friction (tau ignored)
    cases[1].bias = 6.0;                   // beyond friction: the mode moves off 0
    cases[2].bias = -1.0;
    cases[2].relaxation = 0.5;
    cases[2].noise = 1.0;
    cases[3] = dry(3.84, 5.0, 0.5 * 3.84); // no drag, g = 0.5
    return cases;
}

// Adaptive Gauss-Kronrod; every caller splits at the kinks, so 1e-13 is reached
// after a few bisections.
double gk(const std::function<double(double)>& f, double a, double b) {
    return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, a, b, 12, 1e-13);
}

} // namespace

TEST(HayakawaDensity, AgreesWithTheFreeFunctionsAndTheReference) {
    for (const ss::ModelParams& p : hayakawa_cases()) {
        const std::string where = "bias " + std::to_string(p.bias) + " relaxation " + std::to_string(p.relaxation);
        const ss::HayakawaDensity d(p);
        const ss::WhiteNoiseReference r = ss::white_noise_reference(p);
        EXPECT_TRUE(rel_close("mean " + where, d.mean(), r.mobility, 1e-10));
        EXPECT_TRUE(rel_close("variance " + where, d.variance(), r.variance, 1e-10));
        const double sd = std::sqrt(d.variance());
        for (double z : {-4.0, -1.0, -0.01, 0.0, 0.3, 2.0, 7.0}) {
            const double v = d.mean() + z * sd;
            EXPECT_TRUE(rel_close("density " + where, d(v), ss::hayakawa_density(p, v), 1e-13)) << v;
            EXPECT_NEAR(d.potential(v) - d.potential(d.mean()),
                        ss::hayakawa_potential(p, v) - ss::hayakawa_potential(p, d.mean()), 1e-11)
                << where << " v " << v;
            EXPECT_GE(d.potential(v), 0.0);
        }
        EXPECT_NEAR(d.potential(d.mode()), 0.0, 1e-14) << where;
    }
}

TEST(HayakawaDensity, ProbabilityIsExactOnBinsAnywhere) {
    const double inf = std::numeric_limits<double>::infinity();
    for (const ss::ModelParams& p : hayakawa_cases()) {
        const std::string where = "bias " + std::to_string(p.bias) + " relaxation " + std::to_string(p.relaxation);
        const ss::HayakawaDensity d(p);
        EXPECT_NEAR(d.probability(-inf, inf), 1.0, 1e-13) << where;
        const double sd = std::sqrt(d.variance()), m = d.mean();
        // Bins in the bulk, across the kink at 0 and the mode, and deep in both tails.
        const std::vector<std::pair<double, double>> bins = {
            {m - 0.1 * sd, m + 0.05 * sd}, {-0.03 * sd, 0.02 * sd}, {d.mode() - 0.2 * sd, d.mode() + 0.3 * sd},
            {m + 3 * sd, m + 3.5 * sd},    {m - 9 * sd, m - 8 * sd}, {m + 12 * sd, m + 13 * sd}, {m - sd, m + sd}};
        for (auto [a, b] : bins) {
            // Independent: adaptive Gauss-Kronrod of the density, split at the kink.
            double want = 0.0;
            if (a < 0 && b > 0)
                want = gk(d, a, 0.0) + gk(d, 0.0, b);
            else
                want = gk(d, a, b);
            EXPECT_TRUE(rel_close("P[" + std::to_string(a) + ", " + std::to_string(b) + "] " + where,
                                  d.probability(a, b), want, 1e-11));
            EXPECT_DOUBLE_EQ(d.probability(b, a), -d.probability(a, b));
        }
        // Additive over a partition of the line.
        double total = d.probability(-inf, m - 2 * sd) + d.probability(m + 2 * sd, inf);
        for (int k = 0; k < 40; ++k) total += d.probability(m - 2 * sd + 0.1 * k * sd, m - 2 * sd + 0.1 * (k + 1) * sd);
        EXPECT_NEAR(total, 1.0, 1e-13) << where;
    }
    // Pure dry friction, nondimensional: P[a, b] = (e^{-2a} - e^{-2b})/2 for 0 <= a < b.
    const ss::HayakawaDensity dd(dry(1.0, 1.0, 0.0));
    EXPECT_TRUE(rel_close("P[0.5, 0.6]", dd.probability(0.5, 0.6), 0.5 * (std::exp(-1.0) - std::exp(-1.2)), 1e-13));
    EXPECT_TRUE(rel_close("P[10, 11]", dd.probability(10, 11), 0.5 * (std::exp(-20.0) - std::exp(-22.0)), 1e-13));
    EXPECT_NEAR(dd.mean(), 0.0, 1e-15);
    EXPECT_TRUE(rel_close("variance", dd.variance(), 0.5, 1e-13));
}

TEST(HayakawaDensity, RejectsParametersWithoutStationaryState) {
    try {
        ss::HayakawaDensity d(dry(1.0, 1.0, 1.0));
        ADD_FAILURE() << "no error";
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), "bias") << e.what();
    }
    ss::ModelParams bad = dry(1.0, 1.0, 0.0);
    bad.friction = 0.0;
    EXPECT_THROW(ss::HayakawaDensity{bad}, ss::InvalidParameter);
    EXPECT_THROW(ss::HayakawaDensity(dry(1.0, 1.0, 0.0)).probability(std::nan(""), 1.0), ss::InvalidParameter);
}

// ---- Touchette, Van der Straeten and Just: pure dry friction -------------------

TEST(Touchette, FirstMomentReproducesTableI) {
    // theory.md, section 8: E[V(t)|v0 = 1], Delta = Gamma = 1.
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    const std::vector<std::pair<double, double>> table = {{0.05, 0.950000}, {0.125, 0.875248}, {0.25, 0.757249},
                                                          {0.5, 0.567963},  {1.0, 0.336204},   {2.5, 0.090194}};
    for (auto [t, want] : table) EXPECT_NEAR(ss::dry_friction_first_moment(p, t, 1.0), want, 1e-6) << "t " << t;
    EXPECT_EQ(ss::dry_friction_first_moment(p, 0.0, 1.0), 1.0);
    EXPECT_EQ(ss::dry_friction_first_moment(p, 0.0, -2.5), -2.5);
    // Odd in v0; before the velocity can reach 0 it decreases at the friction rate.
    EXPECT_DOUBLE_EQ(ss::dry_friction_first_moment(p, 0.7, -1.3), -ss::dry_friction_first_moment(p, 0.7, 1.3));
    EXPECT_EQ(ss::dry_friction_first_moment(p, 0.7, 0.0), 0.0);
    EXPECT_NEAR(ss::dry_friction_first_moment(p, 0.01, 3.0), 2.99, 1e-13);
}

TEST(Touchette, AutocorrelationStartsAtTheVarianceAndIntegratesToD) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    EXPECT_NEAR(ss::dry_friction_autocorrelation(p, 0.0), 0.5, 1e-15);
    auto c = [&](double t) { return ss::dry_friction_autocorrelation(p, t); };
    // Green-Kubo: D = 2 int_0^inf C (the stationary mean is 0).
    const double integral = boost::math::quadrature::exp_sinh<double>().integrate(c, 0.0, std::numeric_limits<double>::infinity(), 1e-13);
    EXPECT_NEAR(2.0 * integral, 1.25, 1e-8);
    EXPECT_DOUBLE_EQ(ss::dry_friction_autocorrelation(p, -0.8), ss::dry_friction_autocorrelation(p, 0.8));
    // Decreasing and positive.
    double previous = 0.5;
    for (double t : {0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 40.0}) {
        const double now = c(t);
        EXPECT_GT(now, 0.0) << t;
        EXPECT_LT(now, previous) << t;
        previous = now;
    }
}

TEST(Touchette, PropagatorIsNormalisedAndItsMeanIsTheFirstMoment) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    for (double v0 : {1.0, -0.4, 0.0, 3.0}) {
        for (double t : {0.01, 0.3, 1.0, 4.0}) {
            auto dens = [&](double v) { return ss::dry_friction_propagator(p, v, t, v0); };
            const double reach = std::fabs(v0) + t + 10.0 * std::sqrt(t) + 25.0;
            // Split at the kink, at the start, and around the drifting Gaussian bump.
            std::vector<double> cuts = {-reach, 0.0, v0, reach};
            const double centre = v0 - std::copysign(t, v0);
            for (double k : {-6.0, -2.0, 2.0, 6.0}) cuts.push_back(centre + k * std::sqrt(t));
            std::sort(cuts.begin(), cuts.end());
            double mass = 0.0, mean = 0.0;
            for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
                if (cuts[k + 1] <= cuts[k]) continue;
                mass += gk(dens, cuts[k], cuts[k + 1]);
                mean += gk([&](double v) { return v * dens(v); }, cuts[k], cuts[k + 1]);
            }
            EXPECT_NEAR(mass, 1.0, 1e-8) << "v0 " << v0 << " t " << t;
            EXPECT_NEAR(mean, ss::dry_friction_first_moment(p, t, v0), 1e-8) << "v0 " << v0 << " t " << t;
        }
    }
}

TEST(Touchette, PropagatorObeysChapmanKolmogorovAndRelaxesToHayakawa) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    const double v0 = 0.8, t1 = 0.3, t2 = 0.5;
    for (double v : {-1.0, 0.0, 0.25, 1.5}) {
        auto integrand = [&](double u) {
            return ss::dry_friction_propagator(p, v, t2, u) * ss::dry_friction_propagator(p, u, t1, v0);
        };
        double composed = 0.0;
        std::vector<double> cuts = {-30.0, 0.0, v, v0 - t1, v0, 30.0};
        std::sort(cuts.begin(), cuts.end());
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
            if (cuts[k + 1] > cuts[k]) composed += gk(integrand, cuts[k], cuts[k + 1]);
        EXPECT_TRUE(rel_close("p(v, t1 + t2 | v0) at v = " + std::to_string(v), composed,
                              ss::dry_friction_propagator(p, v, t1 + t2, v0), 1e-9));
    }
    for (double v : {-2.0, 0.0, 0.7}) EXPECT_NEAR(ss::dry_friction_propagator(p, v, 80.0, 1.0), std::exp(-2 * std::fabs(v)), 1e-12);
}

TEST(Touchette, AutocorrelationIsTheStationaryAverageOfTheFirstMoment) {
    // <V(t)V(0)> = int v0 E[V(t)|v0] p_s(v0) dv0 with p_s = e^{-2|v0|} (odd times odd: even).
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    for (double t : {0.05, 0.5, 2.0, 7.0}) {
        auto integrand = [&](double v0) { return 2.0 * v0 * ss::dry_friction_first_moment(p, t, v0) * std::exp(-2 * v0); };
        const double want = gk(integrand, 0.0, 1.0) + gk(integrand, 1.0, 5.0) + gk(integrand, 5.0, 40.0);
        EXPECT_TRUE(rel_close("C(" + std::to_string(t) + ")", ss::dry_friction_autocorrelation(p, t), want, 1e-10));
    }
}

TEST(Touchette, StableAtExtremeTimesAndVelocities) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    // References from the same formulas in 120-digit arithmetic (mpmath).
    EXPECT_TRUE(rel_close("E(1e-8 | 50)", ss::dry_friction_first_moment(p, 1e-8, 50.0), 49.99999999, 1e-15));
    EXPECT_TRUE(rel_close("E(200 | 50)", ss::dry_friction_first_moment(p, 200.0, 50.0), 1.1536987859264938e-26, 1e-11));
    EXPECT_TRUE(rel_close("E(200 | 1)", ss::dry_friction_first_moment(p, 200.0, 1.0), 5.526616229073464e-47, 1e-11));
    EXPECT_TRUE(rel_close("E(1000 | 1)", ss::dry_friction_first_moment(p, 1000.0, 1.0), 9.7098643958588041e-222, 1e-9));
    EXPECT_TRUE(rel_close("C(1e-8)", ss::dry_friction_autocorrelation(p, 1e-8), 0.49999999500000005, 1e-15));
    EXPECT_TRUE(rel_close("C(99.999)", ss::dry_friction_autocorrelation(p, 99.999), 1.1001934917607344e-24, 1e-11));
    EXPECT_TRUE(rel_close("C(100.001)", ss::dry_friction_autocorrelation(p, 100.001), 1.0990632190676439e-24, 1e-11));
    EXPECT_TRUE(rel_close("C(200)", ss::dry_friction_autocorrelation(p, 200.0), 7.9210319879456919e-47, 1e-11));
    EXPECT_TRUE(rel_close("C(1000)", ss::dry_friction_autocorrelation(p, 1000.0), 1.4210555763165202e-221, 1e-9));
    EXPECT_TRUE(rel_close("p(50, 1e-8 | 50)", ss::dry_friction_propagator(p, 50.0, 1e-8, 50.0), 3989.4227840672128, 1e-12));
    EXPECT_TRUE(rel_close("p(0, 200 | 50)", ss::dry_friction_propagator(p, 0.0, 200.0, 50.0), 1.0, 1e-12));
    EXPECT_TRUE(rel_close("p(-3, 200 | 50)", ss::dry_friction_propagator(p, -3.0, 200.0, 50.0), 0.0024787521766663584, 1e-12));
    for (double t : {1e-8, 1e-3, 1.0, 200.0, 5000.0}) {
        for (double v0 : {-300.0, -50.0, 0.0, 1e-9, 50.0, 300.0}) {
            const double e = ss::dry_friction_first_moment(p, t, v0);
            EXPECT_TRUE(std::isfinite(e)) << t << " " << v0;
            EXPECT_LE(std::fabs(e), std::fabs(v0)) << t << " " << v0;
            for (double v : {-400.0, -1.0, 0.0, 49.0, 400.0}) {
                const double d = ss::dry_friction_propagator(p, v, t, v0);
                EXPECT_TRUE(std::isfinite(d) && d >= 0.0) << v << " " << t << " " << v0;
            }
        }
        EXPECT_TRUE(std::isfinite(ss::dry_friction_autocorrelation(p, t)));
    }
    EXPECT_EQ(ss::dry_friction_autocorrelation(p, 1e5), 0.0);
}

TEST(Touchette, PhysicalUnitsAgreeWithTheNondimensionalTwin) {
    const ss::ModelParams si = dry(3.84, 5.0, 0.0), nd = dry(1.0, 1.0, 0.0);
    const double vel = 5.0 / 3.84, time = 5.0 / (3.84 * 3.84);
    EXPECT_TRUE(rel_close("C(0) = Gamma^2/(2 Delta^2)", ss::dry_friction_autocorrelation(si, 0.0), 0.5 * vel * vel, 1e-14));
    for (double t : {0.02, 0.4, 3.0}) {
        EXPECT_TRUE(rel_close("C", ss::dry_friction_autocorrelation(si, t * time),
                              ss::dry_friction_autocorrelation(nd, t) * vel * vel, 1e-13));
        for (double v0 : {-0.6, 1.0, 4.0}) {
            EXPECT_TRUE(rel_close("E", ss::dry_friction_first_moment(si, t * time, v0 * vel),
                                  ss::dry_friction_first_moment(nd, t, v0) * vel, 1e-13));
            for (double v : {-1.0, 0.0, 0.5, 2.0})
                EXPECT_TRUE(rel_close("p", ss::dry_friction_propagator(si, v * vel, t * time, v0 * vel),
                                      ss::dry_friction_propagator(nd, v, t, v0) / vel, 1e-13));
        }
    }
    // D of the white-noise reference from the SI autocorrelation (Green-Kubo).
    auto c = [&](double t) { return ss::dry_friction_autocorrelation(si, t); };
    const double d = 2.0 * boost::math::quadrature::exp_sinh<double>().integrate(c, 0.0, std::numeric_limits<double>::infinity(), 1e-13);
    EXPECT_TRUE(rel_close("D", d, ss::white_noise_reference(si).diffusivity, 1e-8));
}

TEST(Touchette, RejectsInvalidInput) {
    const ss::ModelParams p = dry(1.0, 1.0, 0.0);
    auto expect_parameter = [](const std::string& name, auto&& call) {
        try {
            call();
            ADD_FAILURE() << "no error, expected one for " << name;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), name) << e.what();
        }
    };
    ss::ModelParams drag = p;
    drag.relaxation = 2.0;
    ss::ModelParams biased = p;
    biased.bias = 0.1;
    for (const auto& [model, name] : {std::pair{drag, std::string("relaxation")}, std::pair{biased, std::string("bias")}}) {
        const ss::ModelParams& q = model; // clang 14 cannot capture a structured binding
        expect_parameter(name, [&] { ss::dry_friction_first_moment(q, 1.0, 1.0); });
        expect_parameter(name, [&] { ss::dry_friction_autocorrelation(q, 1.0); });
        expect_parameter(name, [&] { ss::dry_friction_propagator(q, 0.0, 1.0, 1.0); });
    }
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    expect_parameter("time", [&] { ss::dry_friction_first_moment(p, -1e-3, 1.0); });
    expect_parameter("time", [&] { ss::dry_friction_first_moment(p, nan, 1.0); });
    expect_parameter("time", [&] { ss::dry_friction_propagator(p, 0.0, 0.0, 1.0); });
    expect_parameter("time", [&] { ss::dry_friction_propagator(p, 0.0, -1.0, 1.0); });
    expect_parameter("time", [&] { ss::dry_friction_autocorrelation(p, inf); });
    expect_parameter("v0", [&] { ss::dry_friction_first_moment(p, 1.0, inf); });
    expect_parameter("v0", [&] { ss::dry_friction_propagator(p, 0.0, 1.0, nan); });
    expect_parameter("v", [&] { ss::dry_friction_propagator(p, nan, 1.0, 0.0); });
    ss::ModelParams bad = p;
    bad.noise = 0.0;
    expect_parameter("noise", [&] { ss::dry_friction_first_moment(bad, 1.0, 1.0); });
    // tau is ignored: these are white-noise references.
    ss::ModelParams colored = p;
    colored.tau = 0.5;
    EXPECT_EQ(ss::dry_friction_first_moment(colored, 0.5, 1.0), ss::dry_friction_first_moment(p, 0.5, 1.0));
}

TEST(AnalyticViscous, DiffusivityIsTheZeroFrictionLimit) {
    ss::ModelParams p;
    p.relaxation = 0.05;
    p.noise = 1.0;
    EXPECT_DOUBLE_EQ(ss::viscous_diffusivity(p), 0.05 * 0.05 * 1.0);
    p.friction = 1e-6; // negligible, as in WhiteNoiseReference.ViscousLimit
    p.bias = 0.3;
    EXPECT_TRUE(rel_close("D", ss::white_noise_reference(p).diffusivity, ss::viscous_diffusivity(p), 1e-5));
    ss::ModelParams none = p;
    none.relaxation = std::numeric_limits<double>::infinity();
    EXPECT_THROW(ss::viscous_diffusivity(none), ss::InvalidParameter);
    none.relaxation = 1.0;
    none.noise = -1.0;
    EXPECT_THROW(ss::viscous_diffusivity(none), ss::InvalidParameter);
}
