// SPDX-License-Identifier: BSD-3-Clause
// Exact one-step law of the OU noise (noise.hpp, theory.md, sections 2 and 5).
//
// References, all independent of the library's formulas:
//  * direct numerical integration (Boost.Math Gauss-Kronrod, long double, single
//    and nested double integrals) of the OU law started at x:
//      E[X_s] = x e^{-s/tau},
//      Cov(X_s, X_u) = (1/tau)(e^{-|s-u|/tau} - e^{-(s+u)/tau})
//                    = -(1/tau) e^{-|s-u|/tau} expm1(-2 min(s,u)/tau)   (no cancellation);
//  * the closed forms of theory.md, section 5 evaluated with 50 significant digits
//    (Boost.Multiprecision), which is exact to ~1e-25 even where double loses every digit;
//  * the small-r Taylor series and the large-r asymptote, in long double.
#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <map>
#include <vector>

#include "stickslip/kernels/noise.hpp"

namespace ss = stickslip;
using boost::math::quadrature::gauss_kronrod;
using big = boost::multiprecision::cpp_bin_float_50;

namespace {

// Ratios r = h/tau of the brief: 1e-8 ... 1e8.
const std::vector<double> kAllRatios = {1e-8, 1e-6, 1e-4, 1e-2, 0.3, 0.5, 0.7, 1.0, 10.0, 1e3, 1e8};
// Where the quadrature in [0,1]^2 resolves the boundary layer (width 1/r) easily.
const std::vector<double> kQuadRatios = {1e-8, 1e-6, 1e-4, 1e-2, 0.3, 0.5, 0.7, 1.0, 10.0};

struct Reference {
    long double m1, m2, s11, s12, s22; // for tau = 1 (Sigma entries times tau)
};

// Direct integration of the OU law in the scaled variables s = h a, u = h b
// (a, b in [0, 1]), tau = 1, h = r.
Reference integrate_ou_law(double r_in) {
    const long double r = r_in;
    // GK61 is exact to long double rounding on these smooth pieces after a few
    // bisections; a tolerance near epsilon would only make it refine forever.
    constexpr unsigned depth = 8;
    constexpr long double tol = 1e-16L;
    // Cov(X_{ha}, X_{hb}) * tau.
    auto cov = [r](long double a, long double b) {
        const long double lo = std::fmin(a, b), d = std::fabs(a - b);
        return -std::exp(-r * d) * std::expm1(-2.0L * r * lo);
    };
    Reference ref{};
    // m1 = (1/h) int_0^h e^{-s/tau} ds = int_0^1 e^{-r a} da
    ref.m1 = gauss_kronrod<long double, 61>::integrate([r](long double a) { return std::exp(-r * a); }, 0.0L,
                                                       1.0L, depth, tol);
    ref.m2 = std::exp(-r);
    // Sigma11 = (1/h^2) int int Cov = int_0^1 int_0^1 cov(a, b) db da; the inner integral
    // is split at the kink b = a.
    auto inner = [&](long double a) {
        long double s = 0.0L;
        if (a > 0) s += gauss_kronrod<long double, 61>::integrate([&](long double b) { return cov(a, b); }, 0.0L, a,
                                                                   depth, tol);
        if (a < 1) s += gauss_kronrod<long double, 61>::integrate([&](long double b) { return cov(a, b); }, a, 1.0L,
                                                                   depth, tol);
        return s;
    };
    ref.s11 = gauss_kronrod<long double, 61>::integrate(inner, 0.0L, 1.0L, depth, tol);
    // Sigma12 = (1/h) int_0^h Cov(X_s, X_h) ds
    ref.s12 = gauss_kronrod<long double, 61>::integrate([&](long double a) { return cov(a, 1.0L); }, 0.0L, 1.0L,
                                                        depth, tol);
    // Sigma22 = Cov(X_h, X_h)
    ref.s22 = cov(1.0L, 1.0L);
    return ref;
}

// Cached: the nested integrals are the slow part of this file.
Reference quadrature_reference(double r) {
    static std::map<double, Reference> cache;
    auto it = cache.find(r);
    if (it == cache.end()) it = cache.emplace(r, integrate_ou_law(r)).first;
    return it->second;
}

// theory.md, section 5 closed forms with 50 digits (tau = 1).
Reference closed_form_reference(double r_in) {
    const big r = r_in;
    const big e1 = exp(-r), e2 = exp(-2 * r);
    Reference ref{};
    ref.m1 = static_cast<long double>((1 - e1) / r);
    ref.m2 = static_cast<long double>(e1);
    ref.s11 = static_cast<long double>((2 * r - 3 + 4 * e1 - e2) / (r * r));
    ref.s12 = static_cast<long double>((1 - e1) * (1 - e1) / r);
    ref.s22 = static_cast<long double>(1 - e2);
    return ref;
}

::testing::AssertionResult rel_close(const char* what, double r, long double got, long double want,
                                     long double tol) {
    const long double err = std::fabs(got - want) / std::fabs(want);
    if (std::isfinite(static_cast<double>(got)) && err <= tol) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << " at r = h/tau = " << r << ": got "
                                         << static_cast<double>(got) << ", want " << static_cast<double>(want)
                                         << ", relative error " << static_cast<double>(err) << " > "
                                         << static_cast<double>(tol);
}

} // namespace

TEST(OUStep, QuadratureReferenceAgreesWithClosedForm) {
    // Guards the references themselves: the integration of the OU law and the
    // closed forms of theory.md, section 5 (50 digits) must agree to ~1e-15.
    for (double r : kQuadRatios) {
        const Reference q = quadrature_reference(r), c = closed_form_reference(r);
        EXPECT_TRUE(rel_close("quad m1", r, q.m1, c.m1, 1e-15L));
        EXPECT_TRUE(rel_close("quad s11", r, q.s11, c.s11, 1e-14L));
        EXPECT_TRUE(rel_close("quad s12", r, q.s12, c.s12, 1e-14L));
        EXPECT_TRUE(rel_close("quad s22", r, q.s22, c.s22, 1e-15L));
    }
}

TEST(OUStep, MatchesDirectIntegrationOfTheOULaw) {
    // tau = 1 and tau = 1e-5 s (the paper's smallest) with h = r tau.
    for (double tau : {1.0, 1e-5}) {
        for (double r : kQuadRatios) {
            const double h = r * tau;
            const ss::OUStep s = ss::ou_step(tau, h);
            const Reference q = quadrature_reference(h / tau);
            const double rr = h / tau;
            EXPECT_TRUE(rel_close("mean_coef", rr, s.mean_coef, q.m1, 1e-13L));
            EXPECT_TRUE(rel_close("end_coef", rr, s.end_coef, q.m2, 1e-14L));
            EXPECT_TRUE(rel_close("s11*tau", rr, s.s11 * tau, q.s11, 1e-12L));
            EXPECT_TRUE(rel_close("s12*tau", rr, s.s12 * tau, q.s12, 1e-12L));
            EXPECT_TRUE(rel_close("s22*tau", rr, s.s22 * tau, q.s22, 1e-13L));
        }
    }
}

TEST(OUStep, MatchesHighPrecisionClosedFormOverTheWholeRange) {
    for (double r : kAllRatios) {
        const ss::OUStep s = ss::ou_step(1.0, r);
        const Reference c = closed_form_reference(r);
        EXPECT_TRUE(rel_close("mean_coef", r, s.mean_coef, c.m1, 1e-14L));
        EXPECT_TRUE(rel_close("s11", r, s.s11, c.s11, 1e-13L));
        EXPECT_TRUE(rel_close("s12", r, s.s12, c.s12, 1e-13L));
        EXPECT_TRUE(rel_close("s22", r, s.s22, c.s22, 1e-14L));
        if (r < 700) EXPECT_TRUE(rel_close("end_coef", r, s.end_coef, c.m2, 1e-14L));
        else EXPECT_GE(s.end_coef, 0.0);
    }
}

TEST(OUStep, AsymptoticFormsAtExtremeRatios) {
    // Small r, Taylor series to O(r^7) (Horner, long double):
    //   Sigma11*tau = 2r/3 - r^2/2 + 7r^3/30 - r^4/12 + 31r^5/1260 - r^6/160
    //   Sigma12*tau = r - r^2 + 7r^3/12 - r^4/4 + 31r^5/360 - r^6/40
    //   Sigma22*tau = 2r - 2r^2 + 4r^3/3 - 2r^4/3 + 4r^5/15 - 4r^6/45
    //   m1          = 1 - r/2 + r^2/6 - r^3/24 + r^4/120 - r^5/720 + r^6/5040
    auto poly = [](long double r, std::initializer_list<long double> c) { // c0 + c1 r + ...
        long double s = 0.0L;
        for (auto it = std::rbegin(c); it != std::rend(c); ++it) s = s * r + *it;
        return s;
    };
    for (double rd : {1e-8, 1e-6, 1e-4, 1e-2}) {
        const long double r = rd;
        const ss::OUStep s = ss::ou_step(2.0, 2.0 * rd); // tau = 2
        const long double s11 = poly(r, {0, 2.0L / 3, -0.5L, 7.0L / 30, -1.0L / 12, 31.0L / 1260, -1.0L / 160});
        const long double s12 = poly(r, {0, 1, -1, 7.0L / 12, -0.25L, 31.0L / 360, -1.0L / 40});
        const long double s22 = poly(r, {0, 2, -2, 4.0L / 3, -2.0L / 3, 4.0L / 15, -4.0L / 45});
        const long double m1 = poly(r, {1, -0.5L, 1.0L / 6, -1.0L / 24, 1.0L / 120, -1.0L / 720, 1.0L / 5040});
        // Truncation error is O(r^6) relative: < 1e-13 even at r = 1e-2.
        EXPECT_TRUE(rel_close("series s11", rd, s.s11 * 2.0, s11, 1e-13L));
        EXPECT_TRUE(rel_close("series s12", rd, s.s12 * 2.0, s12, 1e-13L));
        EXPECT_TRUE(rel_close("series s22", rd, s.s22 * 2.0, s22, 1e-13L));
        EXPECT_TRUE(rel_close("series m1", rd, s.mean_coef, m1, 1e-14L));
    }
    // Huge r: Sigma11*tau = (2r - 3)/r^2, Sigma12*tau = 1/r, Sigma22*tau = 1, m1 = 1/r.
    for (double rd : {1e3, 1e8}) {
        const long double r = rd;
        const ss::OUStep s = ss::ou_step(0.5, 0.5 * rd); // tau = 0.5
        EXPECT_TRUE(rel_close("asymptote s11", rd, s.s11 * 0.5, (2 * r - 3) / (r * r), 1e-13L));
        EXPECT_TRUE(rel_close("asymptote s12", rd, s.s12 * 0.5, 1 / r, 1e-13L));
        EXPECT_TRUE(rel_close("asymptote s22", rd, s.s22 * 0.5, 1.0L, 1e-15L));
        EXPECT_TRUE(rel_close("asymptote m1", rd, s.mean_coef, 1 / r, 1e-14L));
    }
}

TEST(OUStep, CholeskyFactorReproducesSigma) {
    for (double r : kAllRatios) {
        for (double tau : {1.0, 1e-5, 3.0}) {
            const ss::OUStep s = ss::ou_step(tau, r * tau);
            ASSERT_TRUE(std::isfinite(s.l11) && std::isfinite(s.l21) && std::isfinite(s.l22)) << "r=" << r;
            EXPECT_GT(s.l11, 0.0) << "r=" << r;
            EXPECT_GT(s.l21, 0.0) << "r=" << r;
            EXPECT_GT(s.l22, 0.0) << "r=" << r;
            const long double l11 = s.l11, l21 = s.l21, l22 = s.l22;
            EXPECT_TRUE(rel_close("L11^2", r, l11 * l11, s.s11, 1e-15L));
            EXPECT_TRUE(rel_close("L11 L21", r, l11 * l21, s.s12, 1e-15L));
            EXPECT_TRUE(rel_close("L21^2+L22^2", r, l21 * l21 + l22 * l22, s.s22, 1e-15L));
            // The Schur complement (conditional variance of the endpoint given the
            // mean) against its 50-digit value: the numerically delicate entry.
            const Reference c = closed_form_reference(r);
            const big b11 = c.s11, b12 = c.s12, b22 = c.s22;
            const long double schur = static_cast<long double>(b22 - b12 * b12 / b11) / tau;
            EXPECT_TRUE(rel_close("L22^2 (Schur)", r, l22 * l22, schur, 1e-12L));
        }
    }
}

TEST(OUStep, SeriesBranchIsContinuousAtHalf) {
    // ou_s11_scaled switches from the Taylor series to the closed form at r = 0.5.
    const double below = std::nextafter(0.5, 0.0);
    const double a = ss::ou_s11_scaled(below), b = ss::ou_s11_scaled(0.5);
    EXPECT_NEAR(a, b, 1e-15 * b) << "jump at the series/closed-form switch: " << a << " vs " << b;
    for (double r : {0.45, 0.49, 0.4999999, below, 0.5, 0.5000001, 0.51, 0.55}) {
        const Reference c = closed_form_reference(r);
        EXPECT_TRUE(rel_close("ou_s11_scaled", r, ss::ou_s11_scaled(r), c.s11, 2e-15L));
    }
    // No kink either: the centred finite-difference slope across the switch matches the
    // 50-digit one.
    const double hstep = 1e-4;
    const double slope = (ss::ou_s11_scaled(0.5 + hstep) - ss::ou_s11_scaled(0.5 - hstep)) / (2 * hstep);
    const double slope_ref = static_cast<double>(
        (closed_form_reference(0.5 + hstep).s11 - closed_form_reference(0.5 - hstep).s11) / (2 * hstep));
    EXPECT_NEAR(slope, slope_ref, 1e-9 * std::fabs(slope_ref));
}

TEST(OUStep, ScalesWithTau) {
    // Sigma(h) * tau and m(h) depend on h/tau only.
    for (double r : {1e-6, 0.3, 2.0, 1e4}) {
        const ss::OUStep a = ss::ou_step(1.0, r), b = ss::ou_step(1e-5, r * 1e-5);
        const double rr = (r * 1e-5) / 1e-5;
        ASSERT_NEAR(rr, r, 1e-15 * r);
        EXPECT_NEAR(b.mean_coef, a.mean_coef, 1e-14 * a.mean_coef) << r;
        EXPECT_NEAR(b.s11 * 1e-5, a.s11, 1e-13 * a.s11) << r;
        EXPECT_NEAR(b.s12 * 1e-5, a.s12, 1e-13 * a.s12) << r;
        EXPECT_NEAR(b.s22 * 1e-5, a.s22, 1e-13 * a.s22) << r;
    }
}
