// SPDX-License-Identifier: BSD-3-Clause
// The white-noise references of analytic.hpp (theory.md section 8) are exact
// for every input the model validates, or refused: checked against references
// computed here independently of analytic.cpp.
//
//  * 50-digit references (Boost.Multiprecision cpp_bin_float_50). In the
//    standard variable x = v/s, s = sqrt(Gamma tauL/2), the density is
//    exp(-x^2/2 - alpha+ x) for x > 0 and exp(-x^2/2 + alpha- x) for x < 0,
//    alpha+- = (Delta -+ bias) sqrt(2 tauL/Gamma). With the Mills ratio
//    M(t) = e^{t^2/2} int_t^inf e^{-y^2/2} dy and G = 1 - t M, the side masses
//    are M(alpha+-), so M0 and Var are closed forms, and F/p on each side is
//    closed too: -(1 - c M(alpha + y)) at distance y from the kink, c = 2a W_other
//    (a = Delta sqrt(2 tauL/Gamma), W the side probabilities). Hence
//      D = tauL^2 Gamma [W- K(alpha-, 2a W+) + W+ K(alpha+, 2a W-)],
//      K(alpha, c) = (1/M(alpha)) int_0^inf e^{-y^2/2 - alpha y} (1 - c M(alpha + y))^2 dy,
//    one 50-digit Gauss-Kronrod quadrature per side (analytic.cpp instead folds
//    the two sides for M0 and accumulates F by nested quadrature).
//  * The no-drag closed forms of theory.md section 8 (M0', var', D'), up to
//    |bias| = (1 - 1e-12) friction, and P(V < 0) = (1 - g)/2.
//  * The viscous (Ornstein-Uhlenbeck) limit when the drift overwhelms friction:
//    D = tauL^2 Gamma, Var = Gamma tauL/2, M0 = tauL (bias -+ friction) --
//    including `stickslip analytic --friction 1 --noise 1 --relaxation 1
//    --bias 1e8`, which printed D = 4.81 and Var = 0.568 before, and bias 1e15,
//    which printed nan.
//  * A bias sweep from 0 to 1e15 and a grid of extreme scales: every value is
//    finite, obeys D <= tauL^2 Gamma and Var <= Gamma tauL/2 (Brascamp-Lieb: the
//    potential is at least as convex as the viscous one), is monotone in the
//    bias and agrees with its nondimensional twin -- or InvalidParameter is
//    thrown, naming the parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/params.hpp"

namespace ss = stickslip;

namespace {

using R50 = boost::multiprecision::cpp_bin_float_50;
const double kInf = std::numeric_limits<double>::infinity();

ss::ModelParams params(double friction, double noise, double relaxation, double bias) {
    ss::ModelParams p;
    p.friction = friction;
    p.noise = noise;
    p.tau = 0.0;
    p.relaxation = relaxation;
    p.bias = bias;
    return p;
}

std::string describe(const ss::ModelParams& p) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "friction %.17g noise %.17g relaxation %.17g bias %.17g", p.friction, p.noise,
                  p.relaxation, p.bias);
    return buf;
}

double rel_err(double got, const R50& want) {
    if (want == 0) return std::fabs(got);
    return static_cast<double>(abs((R50(got) - want) / want));
}

// ---- 50-digit reference ------------------------------------------------------------

const R50 kPi = boost::math::constants::pi<R50>();
const R50 kRoot2 = boost::math::constants::root_two<R50>();

R50 mills(const R50& t) { return sqrt(kPi / 2) * boost::math::erfc(t / kRoot2) * exp(t * t / 2); }

R50 integrate50(const std::function<R50(R50)>& f, const R50& a, const R50& b) {
    return boost::math::quadrature::gauss_kronrod<R50, 31>::integrate(f, a, b, 15, R50("1e-24"));
}

/// K(alpha, c), pieces on the scale of the integrand (peak at y = -alpha when
/// alpha < 0, decay rate ~ alpha otherwise), up to where it is < e^-140.
R50 k_integral(const R50& alpha, const R50& c) {
    const R50 m_alpha = mills(alpha);
    auto f = [&](R50 y) {
        const R50 b = 1 - c * mills(alpha + y);
        return exp(-(y * y / 2 + alpha * y)) * b * b / m_alpha;
    };
    std::vector<R50> cuts{R50(0)};
    if (alpha < 0) {
        const R50 peak = -alpha;
        for (double d : {-17.0, -6.0, -2.0, 0.0, 2.0, 6.0, 17.0})
            if (peak + d > cuts.back()) cuts.push_back(peak + d);
    } else {
        const R50 scale = 1 / (alpha + 1);
        for (R50 y = scale / 4; y * y / 2 + alpha * y < 145; y *= 3) cuts.push_back(y);
        R50 last = cuts.back() * 3;
        cuts.push_back(last);
    }
    R50 sum = 0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) sum += integrate50(f, cuts[k], cuts[k + 1]);
    return sum;
}

struct Ref50 {
    R50 m0, d, var;
};

/// M0, D and Var in SI, with drag (finite relaxation), in 50 digits.
Ref50 reference50(const ss::ModelParams& p) {
    const R50 delta = p.friction, gamma = p.noise, tl = p.relaxation, g = p.bias;
    const R50 r = sqrt(2 * tl / gamma), s = sqrt(gamma * tl / 2);
    const R50 a = delta * r, h = g * r, ap = a - h, am = a + h;
    const R50 mp = mills(ap), mm = mills(am);
    const R50 gp = 1 - ap * mp, gm = 1 - am * mm;
    const R50 m0 = (gp - gm) / (mp + mm);                         // E[x]
    const R50 ex2 = (mp - ap * gp + mm - am * gm) / (mp + mm);    // E[x^2]
    const R50 wp = mp / (mp + mm), wm = mm / (mp + mm);
    const R50 j = wm * k_integral(am, 2 * a * wp) + wp * k_integral(ap, 2 * a * wm);
    return {s * m0, tl * tl * gamma * j, s * s * (ex2 - m0 * m0)};
}

/// P(lo <= V <= hi) in 50 digits from erfc (both sides Gaussian, drag present).
R50 probability50(const ss::ModelParams& p, double lo_d, double hi_d) {
    const R50 delta = p.friction, gamma = p.noise, tl = p.relaxation, g = p.bias;
    const R50 a2 = 1 / (gamma * tl), ra = sqrt(a2);
    // phi on side sgn as a function of y = |v|: a2 y^2 + k y (unshifted), k = 2 (Delta - sgn g)/Gamma.
    // Shift by phi_min so that nothing overflows: phi - phi_min = a2 (y + k/(2 a2))^2 + offset.
    const R50 kp = 2 * (delta - g) / gamma, km = 2 * (delta + g) / gamma;
    auto vertex = [&](const R50& k) { return -k * k / (4 * a2); }; // min over all y of a2 y^2 + k y
    R50 phi_min = 0;
    if (kp < 0) phi_min = vertex(kp);
    if (km < 0) phi_min = vertex(km);
    // int_{y1}^{y2} exp(-(a2 (y + c)^2 + off)) dy, 0 <= y1 <= y2 <= inf.
    auto side = [&](const R50& k, R50 y1, R50 y2) -> R50 {
        if (!(y2 > y1)) return 0;
        const R50 c = k / (2 * a2), off = vertex(k) - phi_min;
        const R50 nearest = -c < y1 ? y1 : (-c > y2 ? y2 : -c); // least phi on [y1, y2]
        if (a2 * (nearest + c) * (nearest + c) + off > 1e5) return 0; // below e^-100000 of the total
        const R50 x1 = ra * (y1 + c), x2 = ra * (y2 + c);
        const R50 diff = x1 >= 0 ? boost::math::erfc(x1) - boost::math::erfc(x2)
                                 : boost::math::erfc(-x2) - boost::math::erfc(-x1);
        return sqrt(kPi) / (2 * ra) * exp(-off) * diff;
    };
    const R50 big = R50("1e300") * R50("1e300"); // "infinity"
    auto clamp = [&](double x) { return std::isinf(x) ? (x > 0 ? big : -big) : R50(x); };
    const R50 lo = clamp(lo_d), hi = clamp(hi_d);
    auto total = [&](const R50& l, const R50& u) {
        R50 s = 0;
        if (u > 0) s += side(kp, l > 0 ? l : R50(0), u);        // v > 0
        if (l < 0) s += side(km, u < 0 ? -u : R50(0), -l);      // v < 0, y = -v
        return s;
    };
    return total(lo, hi) / total(-big, big);
}

} // namespace

// ---- General cases against the 50-digit reference -------------------------------------

TEST(WhiteNoiseQuadrature, MatchesFiftyDigitReference) {
    const std::vector<ss::ModelParams> cases = {
        params(1, 1, 0.2, 0.3),       // the statistical test's case
        params(1, 1, 1, 3),           // mode off the kink, both sides matter
        params(1, 1, 1e-3, 1e3),      // drift overwhelms friction: viscous Gaussian far from 0
        params(3.84, 5, 0.067, 0.342), // the paper's Fig. 2 (tau ignored)
        params(2, 3, 0.5, 0.4),       // golden analytic_fp_json
        params(1, 1, 1, -0.3),
        params(1, 1, 1, 9.94),        // phi(0) = 79.2: just inside the quadrature regime
        params(1, 1, 1, 9.95),        // phi(0) = 80.1: just inside the viscous regime
        params(1, 1, 10, 0.5),
        params(1, 1, 1e3, 0.9),       // towards the no-drag limit
        params(1, 1, 1e3, -1.01),     // mode just past the kink, long tails
        params(1, 1, 1e-6, 0.2),      // friction nearly negligible
        params(1e-5, 1e10, 1, 0),     // friction/noise 1e-15: Ornstein-Uhlenbeck to 1e-10
        params(1e-5, 1e10, 1, 3e-6),
        params(0.5, 0.16, 2, -1.2),
        params(1, 1, 1, 1e-12),       // M0 tiny: the two sides' cancellation
    };
    double worst[3] = {0, 0, 0};
    for (const ss::ModelParams& p : cases) {
        const std::string where = describe(p);
        const Ref50 want = reference50(p);
        const ss::WhiteNoiseReference got = ss::white_noise_reference(p);
        const double e[3] = {rel_err(got.mobility, want.m0), rel_err(got.diffusivity, want.d),
                             rel_err(got.variance, want.var)};
        EXPECT_LE(e[0], 4e-16) << "M0 " << where << ": got " << got.mobility;
        EXPECT_LE(e[1], 4e-16) << "D " << where << ": got " << got.diffusivity;
        EXPECT_LE(e[2], 4e-16) << "Var " << where << ": got " << got.variance;
        for (int k = 0; k < 3; ++k) worst[k] = std::max(worst[k], e[k]);
        const ss::HayakawaDensity dens(p);
        EXPECT_LE(rel_err(dens.mean(), want.m0), 4e-16) << "HayakawaDensity::mean " << where;
        EXPECT_LE(rel_err(dens.variance(), want.var), 4e-16) << "HayakawaDensity::variance " << where;
    }
    std::printf("worst relative errors vs 50 digits: M0 %.2g, D %.2g, Var %.2g\n", worst[0], worst[1], worst[2]);
}

TEST(WhiteNoiseQuadrature, ProbabilityMatchesFiftyDigitErfc) {
    const std::vector<ss::ModelParams> cases = {
        params(3.84, 5, 0.067, 0.342), params(1, 1, 1, 3), params(1, 1, 1, -9.94),
        params(1, 1, 1, 1e8),  // mode/sd = 1.4e8
        params(1, 1, 1, 1e13), // mode/sd = 1.4e13: v itself has only ~3 digits below sd
    };
    for (const ss::ModelParams& p : cases) {
        const ss::HayakawaDensity d(p);
        const double m = d.mean(), sd = std::sqrt(d.variance());
        for (double z : {-30.0, -3.0, -1.0, -0.01, 0.0, 2.0, 20.0}) {
            const double a = m + z * sd, b = m + (z + 0.05) * sd; // narrow bins, deep tails included
            const R50 want = probability50(p, a, b);
            EXPECT_LE(rel_err(d.probability(a, b), want), 1e-15) << describe(p) << " bin at z = " << z;
        }
        EXPECT_LE(rel_err(d.probability(-kInf, 0.0), probability50(p, -kInf, 0.0)), 1e-15) << describe(p);
        EXPECT_NEAR(d.probability(-kInf, kInf), 1.0, 2e-16) << describe(p);
        EXPECT_EQ(d.potential(d.mode()), 0.0) << describe(p);
    }
}

// ---- No drag: the closed forms of theory.md section 8 -------------------------------------

TEST(WhiteNoiseQuadrature, NoDragClosedFormsUpToTheThreshold) {
    const double eps = 1e-12;
    for (double g : {0.0, 1e-12, 0.3, -0.5, 0.9, -0.999999, 1 - eps, -(1 - eps)}) {
        for (auto [friction, noise] : {std::pair{1.0, 1.0}, std::pair{3.84, 5.0}, std::pair{1e-5, 1e10}}) {
            const ss::ModelParams p = params(friction, noise, kInf, g * friction);
            const std::string where = describe(p);
            // theory.md: M0' = g/(1-g^2), var' = (1+g^2)/(2(1-g^2)^2), D' = (5g^4+22g^2+5)/(4(1-g^2)^4),
            // with g = bias/friction of the doubles given, in 50 digits.
            const R50 gl = R50(p.bias) / R50(p.friction), one_m = 1 - gl * gl, g2 = gl * gl;
            const R50 vel = R50(noise) / R50(friction), diff = vel * vel * vel / R50(friction);
            const R50 m0 = vel * gl / one_m;
            const R50 var = vel * vel * (1 + g2) / (2 * one_m * one_m);
            const R50 dd = diff * (5 * g2 * g2 + 22 * g2 + 5) / (4 * pow(one_m, 4));
            const ss::WhiteNoiseReference r = ss::white_noise_reference(p);
            EXPECT_LE(rel_err(r.mobility, m0), 4e-16) << "M0 " << where;
            EXPECT_LE(rel_err(r.variance, var), 4e-16) << "Var " << where;
            EXPECT_LE(rel_err(r.diffusivity, dd), 4e-16) << "D " << where;
            const ss::HayakawaDensity d(p);
            EXPECT_DOUBLE_EQ(d.mean(), r.mobility) << where;
            EXPECT_DOUBLE_EQ(d.variance(), r.variance) << where;
            // P(V < 0) = K+/(2 Delta) = (1 - g)/2: exact to rounding even when it is 5e-13.
            const double below = (p.friction - p.bias) / (2 * p.friction);
            EXPECT_LE(std::fabs(d.probability(-kInf, 0.0) - below), 1e-15 * below) << where;
            EXPECT_NEAR(d.probability(-kInf, kInf), 1.0, 1e-15) << where;
        }
    }
}

TEST(WhiteNoiseQuadrature, LargeRelaxationTendsToTheNoDragLimit) {
    // The corrections are O(1/relaxation'): about 6/relaxation' at g = 0 and 0.3.
    for (double g : {0.0, 0.3, -0.3}) {
        const ss::WhiteNoiseReference lim = ss::white_noise_reference(params(1, 1, kInf, g));
        for (double t : {1e6, 1e10, 1e14, 1e18, 1e30, 1e300}) {
            const ss::WhiteNoiseReference r = ss::white_noise_reference(params(1, 1, t, g));
            const double tol = 20 / t + 4e-16;
            EXPECT_LE(std::fabs(r.diffusivity / lim.diffusivity - 1), tol) << "g " << g << " relaxation " << t;
            EXPECT_LE(std::fabs(r.variance / lim.variance - 1), tol) << "g " << g << " relaxation " << t;
            if (g == 0) {
                EXPECT_EQ(r.mobility, 0.0);
            } else {
                EXPECT_LE(std::fabs(r.mobility / lim.mobility - 1), tol) << "g " << g << " relaxation " << t;
            }
        }
    }
}

// ---- Drift beyond friction: the viscous limit -----------------------------------------------

TEST(WhiteNoiseQuadrature, HugeBiasGivesTheViscousResultsTheCliPrints) {
    // stickslip analytic --friction 1 --noise 1 --relaxation 1 --bias 1e8 (was D = 4.81, Var = 0.568),
    // and --bias 1e15 (was nan).
    for (double bias : {1e8, -1e8, 1e15, -1e15, 1e300 / 1e10}) {
        const ss::ModelParams p = params(1, 1, 1, bias);
        const ss::WhiteNoiseReference r = ss::white_noise_reference(p);
        EXPECT_DOUBLE_EQ(r.diffusivity, 1.0) << bias;
        EXPECT_DOUBLE_EQ(r.variance, 0.5) << bias;
        EXPECT_DOUBLE_EQ(r.mobility, bias > 0 ? bias - 1 : bias + 1) << bias; // tauL (bias -+ friction)
        const ss::HayakawaDensity d(p);
        EXPECT_DOUBLE_EQ(d.mode(), r.mobility);
        // p = N(mode, 1/2) at the double nearest the mode, which is the mode itself up to
        // 1e15 - 1 and 1.4 sd away from 1e290 - 1.
        const double off = static_cast<double>((R50(d.mode()) - R50(bias)) + (bias > 0 ? 1 : -1));
        EXPECT_NEAR(d.potential(d.mode()), off * off, 1e-15) << bias;
        EXPECT_NEAR(d(d.mode()), std::exp(-off * off) / std::sqrt(std::numbers::pi), 1e-16) << bias;
        if (std::fabs(bias) <= 1e15) { // mode +- 0.5 exact in double
            EXPECT_EQ(off, 0.0);
            EXPECT_NEAR(d.probability(d.mode() - 0.5, d.mode() + 0.5), std::erf(0.5), 1e-15) << bias;
        }
    }
    // In SI with other scales: D = tauL^2 Gamma, Var = Gamma tauL/2, M0 = tauL (bias - friction).
    const ss::ModelParams p = params(3.84, 5, 0.067, 1e6);
    const ss::WhiteNoiseReference r = ss::white_noise_reference(p);
    EXPECT_LE(rel_err(r.diffusivity, R50(0.067) * R50(0.067) * 5), 2.3e-16);
    EXPECT_LE(rel_err(r.variance, R50(5) * R50(0.067) / 2), 2.3e-16);
    EXPECT_LE(rel_err(r.mobility, R50(0.067) * (R50(1e6) - R50(3.84))), 2.3e-16);
}

TEST(WhiteNoiseQuadrature, BiasSweepToOneEFifteenIsContinuousAndReachesTheLimits) {
    std::vector<double> biases{0.0};
    for (int k = -60; k <= 75; ++k) biases.push_back(std::pow(10.0, k / 5.0));
    for (double b = 9.90; b <= 10.0; b += 0.002) biases.push_back(b); // across phi(0) = 80
    std::sort(biases.begin(), biases.end());
    ss::WhiteNoiseReference prev{-1, 0, 0};
    for (double b : biases) {
        for (double sign : {1.0, -1.0}) {
            const ss::ModelParams p = params(1, 1, 1, sign * b);
            ss::WhiteNoiseReference r{};
            try {
                r = ss::white_noise_reference(p);
            } catch (const ss::InvalidParameter& e) {
                ADD_FAILURE() << "refused " << describe(p) << ": " << e.what();
                continue;
            }
            ASSERT_TRUE(std::isfinite(r.mobility) && std::isfinite(r.diffusivity) && std::isfinite(r.variance))
                << describe(p);
            EXPECT_GT(r.diffusivity, 0.0);
            EXPECT_LE(r.diffusivity, 1.0 + 4e-16) << describe(p); // D <= tauL^2 Gamma
            EXPECT_GT(r.variance, 0.0);
            EXPECT_LE(r.variance, 0.5 + 2e-16) << describe(p); // Var <= Gamma tauL/2
            if (sign < 0) {
                // Mirror symmetry.
                const ss::WhiteNoiseReference q = ss::white_noise_reference(params(1, 1, 1, b));
                EXPECT_NEAR(r.mobility, -q.mobility, 2.3e-16 * std::fabs(q.mobility)) << describe(p);
                EXPECT_NEAR(r.diffusivity, q.diffusivity, 2e-16 * q.diffusivity) << describe(p);
                EXPECT_NEAR(r.variance, q.variance, 2e-16 * q.variance) << describe(p);
                continue;
            }
            // Monotone in the bias (up to rounding).
            EXPECT_GE(r.mobility, prev.mobility) << describe(p);
            EXPECT_GE(r.diffusivity, prev.diffusivity * (1 - 4e-16)) << describe(p);
            EXPECT_GE(r.variance, prev.variance * (1 - 4e-16)) << describe(p);
            prev = r;
            if (b >= 10) { // phi(0) = (b - 1)^2 >= 81: Ornstein-Uhlenbeck around b - 1 to e^-80
                EXPECT_EQ(r.mobility, b - 1) << describe(p);
                EXPECT_EQ(r.diffusivity, 1.0) << describe(p);
                EXPECT_EQ(r.variance, 0.5) << describe(p);
            }
            if (b >= 8 && b < 10) { // quadrature regime, corrections already below 1e-16
                EXPECT_NEAR(r.mobility, b - 1, 4e-16 * b) << describe(p);
                EXPECT_NEAR(r.diffusivity, 1.0, 4e-16) << describe(p);
                EXPECT_NEAR(r.variance, 0.5, 4e-16) << describe(p);
            }
        }
    }
    const ss::WhiteNoiseReference zero = ss::white_noise_reference(params(1, 1, 1, 0));
    EXPECT_EQ(zero.mobility, 0.0);
}

// ---- Extreme scales: exact or refused ---------------------------------------------------------

TEST(WhiteNoiseQuadrature, ExtremeScalesAreExactOrRefused) {
    int computed = 0, refused = 0;
    for (double friction : {1e-100, 1e-5, 1.0, 1e5, 1e150}) {
        for (double noise : {1e-100, 1.0, 1e10}) {
            for (double t_nd : {1e-300, 1e-20, 1e-3, 1.0, 1e3, 1e20, 1e300, kInf}) {
                for (double g : {0.0, 0.5, -(1 - 1e-12), 2.0, -1e10, 1e300}) {
                    const ss::ModelParams p = params(friction, noise, t_nd * noise / (friction * friction), g * friction);
                    const std::string where = describe(p);
                    ss::WhiteNoiseReference r{};
                    try {
                        r = ss::white_noise_reference(p);
                    } catch (const ss::InvalidParameter& e) {
                        ++refused;
                        const std::string name = e.parameter();
                        EXPECT_TRUE(name == "friction" || name == "noise" || name == "relaxation" || name == "bias")
                            << where << ": " << name;
                        EXPECT_GT(std::string(e.what()).size(), 20u) << where;
                        continue;
                    }
                    ++computed;
                    ASSERT_TRUE(std::isfinite(r.mobility) && std::isfinite(r.diffusivity) && std::isfinite(r.variance))
                        << where;
                    EXPECT_GT(r.diffusivity, 0.0) << where;
                    EXPECT_GT(r.variance, 0.0) << where;
                    EXPECT_EQ(r.mobility == 0.0, g == 0.0) << where;
                    if (!std::isinf(p.relaxation)) {
                        const long double tl = p.relaxation;
                        EXPECT_LE(r.diffusivity, tl * tl * p.noise * (1 + 1e-15L)) << where;
                        EXPECT_LE(r.variance, tl * p.noise / 2 * (1 + 1e-15L)) << where;
                    }
                    // The nondimensional twin (friction = noise = 1) gives the same numbers. (Not
                    // next to the threshold: bias' = bias/friction is rounded there, and the
                    // results depend on it through 1/(1 - |g|).)
                    if (std::fabs(g) == 1 - 1e-12) continue;
                    const ss::ModelParams nd = ss::to_nondimensional(p);
                    const ss::Scales s = ss::scales_of(p);
                    ss::WhiteNoiseReference q{};
                    try {
                        q = ss::white_noise_reference(nd);
                    } catch (const ss::InvalidParameter&) {
                        continue; // e.g. the twin's own numbers out of range
                    }
                    // relaxation' and bias' are rounded once more in the twin: allow for that.
                    EXPECT_LE(rel_err(r.diffusivity, R50(q.diffusivity) * R50(s.diffusivity)), 2e-14) << where;
                    EXPECT_LE(rel_err(r.variance, R50(q.variance) * R50(s.velocity) * R50(s.velocity)), 2e-14) << where;
                    if (g != 0.0) {
                        EXPECT_LE(rel_err(r.mobility, R50(q.mobility) * R50(s.velocity)), 2e-14) << where;
                    }
                }
            }
        }
    }
    EXPECT_GT(computed, 100);
    EXPECT_GT(refused, 10);
}

TEST(WhiteNoiseQuadrature, OutOfRangeResultsAreRefusedWithTheRightName) {
    auto refused_as = [](const ss::ModelParams& p, const std::string& name) {
        try {
            const ss::WhiteNoiseReference r = ss::white_noise_reference(p);
            return ::testing::AssertionFailure() << describe(p) << ": no error, got M0 " << r.mobility << " D "
                                                 << r.diffusivity << " Var " << r.variance;
        } catch (const ss::InvalidParameter& e) {
            if (e.parameter() != name)
                return ::testing::AssertionFailure() << describe(p) << ": parameter " << e.parameter() << ", want "
                                                     << name << " (" << e.what() << ")";
            return ::testing::AssertionSuccess() << e.what();
        }
    };
    // D = tauL^2 Gamma = 1e400 with the mode far from the kink.
    EXPECT_TRUE(refused_as(params(1, 1, 1e200, 2), "relaxation"));
    // D = tauL^2 Gamma = 1e-400.
    EXPECT_TRUE(refused_as(params(1, 1, 1e-200, 0.5), "relaxation"));
    // The mode tauL (bias - friction) = 1e310.
    EXPECT_TRUE(refused_as(params(1, 1, 1e10, 1e300), "bias"));
    EXPECT_THROW(ss::HayakawaDensity(params(1, 1, 1e10, 1e300)), ss::InvalidParameter);
    // No drag, |bias| = friction (1 - 2^-52): D' = 5e62 times Gamma^3/Delta^4 = 3e256 (about the
    // largest that validate() lets through).
    EXPECT_TRUE(refused_as(params(1e51, 3e153, kInf, 1e51 * (1 - 0x1p-52)), "bias"));
    EXPECT_NO_THROW(ss::white_noise_reference(params(1e51, 3e153, kInf, 1e51 * (1 - 1e-12))));
    // friction 1e150: validate() already refuses the scales.
    EXPECT_THROW(ss::white_noise_reference(params(1e150, 1, 1, 0)), ss::InvalidParameter);
    // Still computed: deep but representable values.
    EXPECT_NO_THROW(ss::white_noise_reference(params(1, 1, 1e-150, 0.5)));
    EXPECT_NO_THROW(ss::white_noise_reference(params(1e-20, 1e40, kInf, 1e-20 * (1 - 1e-12))));
}
