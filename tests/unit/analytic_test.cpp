// Exact white-noise references (analytic.hpp, MODEL.md sections 7 and 9): the
// closed forms for pure dry friction, the viscous limit, the normalisation of
// Hayakawa's density, unit scaling, and an independent grid quadrature of the
// M0/D formulas for a case with every force present.
#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
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

// Independent reference for M0, Var and D by grid quadrature (MODEL.md section 7):
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
            // MODEL.md section 9, written out here independently of analytic.cpp.
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
        // Ratios against MODEL.md section 7: p ~ exp(-v^2/(noise tauL) - 2 friction |v|/noise + 2 bias v/noise).
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
