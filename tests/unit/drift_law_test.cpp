// SPDX-License-Identifier: BSD-3-Clause
// The drift law b(v) (drift_law.hpp, drift_input.hpp) and its white-noise
// quadrature (drift_law_quadrature.hpp):
//  * the type: pieces, values, potential against its definition, confinement,
//    coarsening, scaling;
//  * making a law from an expression, a table, a callable: one knot at v = 0
//    with b(0) exact, the interpolation error, and every bad input refused by
//    name (able to fail: each is a separate expectation);
//  * the quadrature against an independent one (trapezoid rule on a grid
//    through the knots, Richardson-extrapolated) to 1e-8, against the affine law's closed-form quadrature
//    to 1e-9, and pure dry friction's D = 5/4 Gamma^3/Delta^4.
#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>
#include <algorithm>

#include "stickslip/analytic.hpp"
#include "stickslip/drift_input.hpp"
#include "stickslip/drift_law_quadrature.hpp"
#include "stickslip/errors.hpp"

namespace ss = stickslip;

namespace {

ss::ModelParams with_law(const std::string& expr, double tau = 0.5) {
    ss::ModelParams p; // friction 3.84, noise 5 (the Fig. 2 case's)
    p.tau = tau;
    p.drift = expr;
    return p;
}

/// The parameter an InvalidParameter names, or "" when none is thrown.
template <class F>
std::string refused(F&& f) {
    try {
        f();
    } catch (const ss::InvalidParameter& e) {
        return e.parameter();
    }
    return "";
}

std::string temp_file(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path) << text;
    return path;
}

} // namespace

TEST(DriftLaw, AffineLawIsTheOldFormula) {
    const ss::DriftLaw b = ss::affine_drift_law(0.067, 0.342);
    for (double v : {-3.0, -0.1, 0.0, 0.2, 5.0}) EXPECT_EQ(b(v), -v * (1.0 / 0.067) + 0.342);
    const ss::DriftLaw dry = ss::affine_drift_law(HUGE_VAL, 0.1);
    EXPECT_EQ(dry(7.0), 0.1);
    EXPECT_TRUE(ss::confines(b, 3.84));
    EXPECT_TRUE(ss::confines(dry, 3.84));
    EXPECT_FALSE(ss::confines(ss::affine_drift_law(HUGE_VAL, 5.0), 3.84)); // |bias| > friction, no drag
}

TEST(DriftLaw, KnotsHaveOneAtZeroAndTheLawsValueThere) {
    const ss::DriftLaw b = ss::make_drift_law(with_law("0.3 + 0.8*v - 0.5*v^3"));
    ASSERT_FALSE(b.affine());
    EXPECT_EQ(b.knots, 1025);
    const int zero = static_cast<int>(std::lround(-b.first * b.inv_spacing));
    EXPECT_EQ(b.knot(zero), 0.0);
    EXPECT_EQ(b(0.0), 0.3);
    EXPECT_EQ(b.values[zero], 0.3);
    // Values at knots are the law's; between them the chord.
    for (int k = 0; k < b.knots; k += 97) {
        const double v = b.knot(k);
        EXPECT_NEAR(b(v), 0.3 + 0.8 * v - 0.5 * v * v * v, 1e-9 * (1 + std::fabs(v * v * v))) << "knot " << k;
    }
    const double mid = b.knot(600) + 0.5 * b.spacing;
    EXPECT_NEAR(b(mid), 0.5 * (b.values[600] + b.values[601]), 1e-12);
    // Outer pieces continue the law's chords.
    EXPECT_EQ(b.piece(-1e9), 0);
    EXPECT_EQ(b.piece(1e9), b.knots - 2);
}

TEST(DriftLaw, PotentialIsTheIntegralOfTheLaw) {
    const ss::DriftLaw b = ss::make_drift_law(with_law("0.4*tanh(v/0.1) - v/2"));
    for (double v : {-3.3, -0.05, 0.0, 0.07, 1.9, 40.0}) {
        const double direct = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
            [&](double u) { return b(u); }, 0.0, v, 20, 1e-13);
        EXPECT_NEAR(ss::drift_potential(b, v), direct, 1e-10 * (1 + std::fabs(direct))) << "v = " << v;
    }
    const ss::DriftLaw a = ss::affine_drift_law(0.5, 0.2);
    EXPECT_DOUBLE_EQ(ss::drift_potential(a, 2.0), -0.5 * 4.0 / 0.5 + 0.4);
}

// The O(1) potential of the white-noise quadratures is drift_potential's
// sums in drift_potential's order: the same bits at every velocity, knots, 0
// and the outer pieces included.
TEST(DriftLaw, FastPotentialIsTheSameBits) {
    const ss::DriftLaw b = ss::make_drift_law(with_law("3.5 - 0.01*v + 0.4*tanh(v/0.1)"));
    const ss::DriftPotential fast(b);
    std::vector<double> vs{0.0, -0.0, 1e-300, -1e-300, 1e9, -1e9};
    for (int k = 0; k < b.knots; k += 3) {
        vs.push_back(b.knot(k));
        vs.push_back(b.knot(k) + 0.37 * b.spacing);
        vs.push_back(std::nextafter(b.knot(k), -HUGE_VAL));
        vs.push_back(std::nextafter(b.knot(k), HUGE_VAL));
    }
    for (double v : vs) {
        const double slow = ss::drift_potential(b, v), quick = fast(v);
        EXPECT_EQ(std::memcmp(&slow, &quick, sizeof slow), 0) << "v = " << v << ": " << slow << " vs " << quick;
    }
    const ss::DriftLaw a = ss::affine_drift_law(0.5, 0.2);
    EXPECT_EQ(ss::DriftPotential(a)(2.0), ss::drift_potential(a, 2.0));
}

TEST(DriftLaw, CoarseningKeepsTheKnotAtZero) {
    const ss::DriftLaw b = ss::make_drift_law(with_law("0.8*v - 0.5*v^3"));
    const ss::DriftLaw c = ss::coarsened_drift_law(b);
    EXPECT_EQ(c.spacing, 2 * b.spacing);
    EXPECT_EQ(c(0.0), b(0.0));
    const int zero = static_cast<int>(std::lround(-c.first * c.inv_spacing));
    EXPECT_EQ(c.knot(zero), 0.0);
    for (int k = 0; k < c.knots; k += 50) EXPECT_EQ(c(c.knot(k)), b(c.knot(k))) << k;
}

TEST(DriftLaw, InterpolationErrorIsSecondOrderForASmoothLaw) {
    ss::DriftLawReport fine, coarse;
    ss::ModelParams p = with_law("0.8*v - 0.5*v^3");
    ss::make_drift_law(p, &fine);
    p.knots = 513;
    ss::make_drift_law(p, &coarse);
    EXPECT_EQ(fine.lower, coarse.lower);
    EXPECT_NEAR(coarse.interpolation_error / fine.interpolation_error, 4.0, 0.1);
}

TEST(DriftLaw, TablesAndCallablesGiveTheSameLawAsTheExpression) {
    const ss::ModelParams expr = with_law("0.5 - v/2");
    ss::ModelParams table = expr;
    table.drift.clear();
    table.drift_table = temp_file("affine_table.csv", "v,b\n# two rows are an affine law\n-1,1\n1,0\n");
    ss::ModelParams fn = expr;
    fn.drift.clear();
    fn.drift_function = [](double v) { return 0.5 - v / 2; };
    const ss::DriftLaw a = ss::make_drift_law(expr), b = ss::make_drift_law(table), c = ss::make_drift_law(fn);
    for (double v : {-2.0, 0.0, 0.3, 4.0}) {
        EXPECT_NEAR(a(v), b(v), 1e-12 * (1 + std::fabs(a(v))));
        EXPECT_NEAR(a(v), c(v), 1e-12 * (1 + std::fabs(a(v))));
    }
}

TEST(DriftLaw, BadInputIsRefusedByName) {
    EXPECT_EQ(refused([] { ss::make_drift_law(with_law("sin(")); }), "drift");          // does not parse
    EXPECT_EQ(refused([] { ss::make_drift_law(with_law("x*v")); }), "drift");           // another variable
    EXPECT_EQ(refused([] { ss::make_drift_law(with_law("1/v")); }), "drift");           // not finite at 0
    EXPECT_EQ(refused([] { ss::make_drift_law(with_law("-v + sqrt(1-v)")); }), "drift"); // NaN on the range
    EXPECT_EQ(refused([] { ss::make_drift_law(with_law("v")); }), "drift");             // does not confine
    EXPECT_EQ(refused([] { ss::make_drift_law(with_law("5")); }), "drift");             // constant > friction
    EXPECT_EQ(refused([] { ss::make_drift_law(with_law("0.8*v - c*v^3")); }), "drift"); // c has no value
    ss::ModelParams p = with_law("0.8*v - c*v^3");
    p.drift_params = "c=0.5";
    EXPECT_EQ(refused([&] { ss::make_drift_law(p); }), "");
    p.drift_params = "c";
    EXPECT_EQ(refused([&] { ss::make_drift_law(p); }), "drift-params");
    p = with_law("-v");
    p.knots = 4;
    EXPECT_EQ(refused([&] { ss::make_drift_law(p); }), "knots");
    p.knots = 4097;
    EXPECT_EQ(refused([&] { ss::make_drift_law(p); }), "knots");
    auto table = [](const std::string& text) {
        ss::ModelParams q;
        q.drift_table = temp_file("bad_table.csv", text);
        return refused([&] { ss::make_drift_law(q); });
    };
    EXPECT_EQ(table("0,1\n-1,2\n"), "drift-table");        // not sorted
    EXPECT_EQ(table("-1,1\n-1,2\n1,0\n"), "drift-table");  // duplicate v
    EXPECT_EQ(table("-1,nan\n1,0\n"), "drift-table");      // NaN
    EXPECT_EQ(table("-1,1\n"), "drift-table");             // one row
    EXPECT_EQ(table("-1,1\n0,x\n"), "drift-table");        // not numbers
    EXPECT_EQ(table("-1,1\n1,2\n"), "drift-table");        // b = 1.5 + v/2 does not confine
    ss::ModelParams missing;
    missing.drift_table = "/nonexistent/table.csv";
    EXPECT_EQ(refused([&] { ss::make_drift_law(missing); }), "drift-table");
}

namespace {

/// An independent white-noise reference: the composite trapezoid rule on a
/// uniform grid with the knots on its nodes (so every kink of the integrands is
/// a node), m nodes per piece, F accumulated from the left and the right, then
/// Richardson over m and 2m (the error is a series in h^2 on each smooth
/// stretch). Shares only the law's values with drift_law_quadrature.cpp.
ss::WhiteNoiseReference trapezoid_reference(const ss::ModelParams& p, double lo, double hi, int m) {
    const ss::DriftLaw b = ss::make_drift_law(p);
    const double h = b.spacing / m;
    const long i0 = static_cast<long>(std::floor((lo - b.first) / h)), i1 = static_cast<long>(std::ceil((hi - b.first) / h));
    const std::size_t n = static_cast<std::size_t>(i1 - i0 + 1);
    std::vector<double> v(n), phi(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) v[i] = b.first + h * static_cast<double>(i0 + static_cast<long>(i));
    // Phi by the trapezoid rule of the net force (exact: the force is linear
    // between nodes, 0 is a node), from the node at v = 0.
    std::size_t zero = 0;
    while (std::fabs(v[zero]) > 0.5 * h) ++zero;
    v[zero] = 0.0;
    auto net = [&](double u, double side) { return 2.0 / p.noise * (b(u) - side * p.friction); };
    for (std::size_t i = zero + 1; i < n; ++i) phi[i] = phi[i - 1] + 0.5 * (net(v[i - 1], 1) + net(v[i], 1)) * h;
    for (std::size_t i = zero; i-- > 0;) phi[i] = phi[i + 1] - 0.5 * (net(v[i], -1) + net(v[i + 1], -1)) * h;
    const double peak = *std::max_element(phi.begin(), phi.end());
    std::vector<double> w(n);
    for (std::size_t i = 0; i < n; ++i) w[i] = std::exp(phi[i] - peak);
    auto trap = [&](auto f) {
        double s = 0;
        for (std::size_t i = 0; i + 1 < n; ++i) s += 0.5 * (f(i) + f(i + 1)) * h;
        return s;
    };
    const double z = trap([&](std::size_t i) { return w[i]; });
    const double m0 = trap([&](std::size_t i) { return v[i] * w[i]; }) / z;
    const double var = trap([&](std::size_t i) { return (v[i] - m0) * (v[i] - m0) * w[i]; }) / z;
    std::vector<double> left(n, 0.0), right(n, 0.0);
    auto flux = [&](std::size_t i) { return (v[i] - m0) * w[i] / z; };
    for (std::size_t i = 1; i < n; ++i) left[i] = left[i - 1] + 0.5 * (flux(i - 1) + flux(i)) * h;
    for (std::size_t i = n - 1; i-- > 0;) right[i] = right[i + 1] + 0.5 * (flux(i) + flux(i + 1)) * h;
    const double d = trap([&](std::size_t i) {
        const double f = v[i] < m0 ? left[i] : -right[i];
        return f * f / (w[i] / z);
    });
    return {m0, 4.0 / p.noise * d, var};
}

ss::WhiteNoiseReference adaptive_reference(const ss::ModelParams& p, double lo, double hi) {
    const ss::WhiteNoiseReference a = trapezoid_reference(p, lo, hi, 16), c = trapezoid_reference(p, lo, hi, 32);
    auto rich = [](double x, double y) { return y + (y - x) / 3.0; };
    return {rich(a.mobility, c.mobility), rich(a.diffusivity, c.diffusivity), rich(a.variance, c.variance)};
}

} // namespace

TEST(DriftLawQuadrature, AgreesWithAnIndependentQuadrature) {
    struct Case {
        const char* law;
        double lo, hi; // where the density has fallen below e^-40 or so [m/s]
    } cases[] = {{"0.342 - 0.5*v*abs(v)", -8, 8}, {"0.8*v - 0.5*v^3", -6, 6}, {"0.4*tanh(v/0.1) - v/2", -12, 12}};
    for (const Case& c : cases) {
        ss::ModelParams p = with_law(c.law, 0.0);
        const ss::WhiteNoiseReference got = ss::DriftLawWhiteNoise(p).reference();
        const ss::WhiteNoiseReference want = adaptive_reference(p, c.lo, c.hi);
        EXPECT_NEAR(got.diffusivity, want.diffusivity, 1e-8 * want.diffusivity) << c.law;
        EXPECT_NEAR(got.variance, want.variance, 1e-8 * want.variance) << c.law;
        EXPECT_NEAR(got.mobility, want.mobility, 1e-8 * std::sqrt(want.variance)) << c.law;
    }
}

TEST(DriftLawQuadrature, AffineLawReproducesTheClosedFormQuadrature) {
    for (const char* law : {"0.342 - v/0.067", "1.5 - v/2", "-0.2 - v*3"}) {
        ss::ModelParams p = with_law(law, 0.0);
        const ss::WhiteNoiseReference got = ss::DriftLawWhiteNoise(p).reference();
        ss::ModelParams affine;
        affine.tau = 0.0;
        if (std::string(law) == "0.342 - v/0.067") affine.relaxation = 0.067, affine.bias = 0.342;
        else if (std::string(law) == "1.5 - v/2") affine.relaxation = 2, affine.bias = 1.5;
        else affine.relaxation = 1.0 / 3.0, affine.bias = -0.2;
        const ss::WhiteNoiseReference want = ss::white_noise_reference(affine);
        EXPECT_NEAR(got.diffusivity, want.diffusivity, 1e-9 * want.diffusivity) << law;
        EXPECT_NEAR(got.variance, want.variance, 1e-9 * want.variance) << law;
        EXPECT_NEAR(got.mobility, want.mobility, 1e-9 * std::sqrt(want.variance)) << law;
    }
}

TEST(DriftLawQuadrature, PureDryFrictionGivesFiveQuarters) {
    ss::ModelParams p;
    p.friction = p.noise = 1.0;
    p.tau = 0.0;
    p.drift = "0*v";
    const ss::WhiteNoiseReference r = ss::DriftLawWhiteNoise(p).reference();
    EXPECT_NEAR(r.diffusivity, 1.25, 1e-10);
    EXPECT_NEAR(r.variance, 0.5, 1e-12);
    EXPECT_NEAR(r.mobility, 0.0, 1e-12);
    const ss::DriftLawWhiteNoise law(p);
    EXPECT_NEAR(law.density(0.3), std::exp(-0.6), 1e-12);
    EXPECT_NEAR(law.probability(-HUGE_VAL, 0.0), 0.5, 1e-12);
    // The commute time between -c and c: 2 int_-c^c e^{2|v|} dv = 2 (e^{2c} - 1)
    // (E[t1] of the white-noise runs at level c; 2.030 +- 0.005 measured at c = 0.35).
    for (double c : {0.1, 0.35, 2.0}) EXPECT_NEAR(law.commute_time(-c, c), 2 * std::expm1(2 * c), 1e-10 * std::exp(2 * c));
    EXPECT_EQ(law.commute_time(-100, 100), HUGE_VAL); // beyond the quadrature's reach: never, as far as it can tell
}

// Knot refinement: the interpolant's error is O(h^2) where the law is smooth
// and O(h) on the one piece that holds a kink, whose width is h, so D and M0
// converge at second order for both (with an irregular constant for the kink,
// which moves within its piece as the knots change). Measured with the exact
// white-noise quadrature (no sampling), knots 33 ... 513 against 2049: the
// least-squares slope of log error against log spacing is 2.21 (smooth law,
// D), 2.11 (kinked, D) and 2.07 (kinked, M0); the test allows 1.6 to 2.6.
TEST(DriftLawQuadrature, KnotRefinementConvergesAtSecondOrder) {
    struct Case {
        const char* law;
        bool mobility; // M0 is 0 by symmetry for the odd law: check D only
    } cases[] = {{"0.4*tanh(v/0.1) - v/2", false}, {"0.2 - v - 0.5*abs(v - 0.3)", true}};
    for (const Case& c : cases) {
        ss::ModelParams p = with_law(c.law, 0.0);
        p.knots = 2049;
        const ss::WhiteNoiseReference best = ss::DriftLawWhiteNoise(p).reference();
        for (bool mobility : {false, true}) {
            if (mobility && !c.mobility) continue;
            double sx = 0, sy = 0, sxx = 0, sxy = 0;
            int n = 0;
            for (int knots : {33, 65, 129, 257, 513}) {
                p.knots = knots;
                const ss::WhiteNoiseReference r = ss::DriftLawWhiteNoise(p).reference();
                const double err = mobility ? std::fabs(r.mobility - best.mobility)
                                            : std::fabs(r.diffusivity - best.diffusivity);
                const double x = std::log(1.0 / (knots - 1)), y = std::log(err);
                sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
            }
            const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
            EXPECT_GT(slope, 1.6) << c.law << (mobility ? " M0" : " D");
            EXPECT_LT(slope, 2.6) << c.law << (mobility ? " M0" : " D");
            std::printf("[measured] %s, %s: convergence order %.3f in the knot spacing\n", c.law,
                        mobility ? "M0" : "D", slope);
        }
    }
}

// ---- the law made once per run ---------------------------------------------------

#include "stickslip/diffusivity.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/model.hpp"
#include "stickslip/prepared_engine.hpp"

namespace {

/// A law no other test makes (its constant unique to this file), so that the
/// count of laws made is this run's alone.
ss::ModelParams law_of_its_own(const char* constant) {
    ss::ModelParams p;
    p.drift = "-v/0.067 + c";
    p.drift_params = std::string("c=") + constant;
    return p;
}

} // namespace

// Issue 44, item 3: one event-scheme run made its law 32 times (constants,
// thresholds, step choice, corrector, chain); now the run makes it once and
// every part gets those bits.
TEST(DriftLaw, ARunMakesItsLawOnce) {
    ss::DiffusivityRequest req;
    req.params = law_of_its_own("0.3420001");
    req.engine.scheme = ss::Scheme::Event;
    req.excursions = 64;
    req.control.threads = 2;
    const std::uint64_t before = ss::drift_laws_made();
    const ss::DiffusivityResult r = ss::compute_diffusivity(req);
    EXPECT_EQ(ss::drift_laws_made() - before, 1u) << "laws made by one event-scheme run with its corrector";
    EXPECT_TRUE(r.control_variate.has_value()) << "the corrector (which needs the law too) ran";
    // Served again, the law is the same bits as one made anew.
    ss::ModelParams same = req.params;
    const ss::DriftLaw served = ss::make_drift_law(same);
    EXPECT_EQ(ss::drift_laws_made() - before, 1u);
    same.knots = 1023; // other inputs: another law, made
    (void)ss::make_drift_law(same);
    EXPECT_EQ(ss::drift_laws_made() - before, 2u);
    same.knots = req.params.knots;
    ss::ModelParams anew = same;
    anew.drift_params = "c=0.34200010"; // the same law under other inputs: made anew
    const ss::DriftLaw made = ss::make_drift_law(anew);
    EXPECT_EQ(ss::drift_laws_made() - before, 3u);
    ASSERT_EQ(served.knots, made.knots);
    EXPECT_EQ(std::memcmp(&served.first, &made.first, sizeof made.first), 0);
    EXPECT_EQ(std::memcmp(&served.spacing, &made.spacing, sizeof made.spacing), 0);
    EXPECT_EQ(std::memcmp(served.values, made.values, sizeof made.values), 0);
}

// The run holds its law as data (model.hpp) rather than asking for it again:
// a callable, which make_drift_law never keeps, is called to make a law once
// by preparing a run and once by the run's own resolution of --dt auto, and
// every part of the run (constants, thresholds, step checks, corrector) takes
// the law from the prepared engine.
TEST(DriftLaw, ARunTakesItsLawAsData) {
    ss::DiffusivityRequest req;
    req.params.drift_function = [](double v) { return -v / 0.067 + 0.342; };
    req.engine.scheme = ss::Scheme::Event;
    req.excursions = 64;
    req.control.threads = 2;
    const ss::PreparedEngine engine = ss::prepare(req);
    const std::uint64_t before = ss::drift_laws_made();
    const ss::DiffusivityResult r = ss::compute_diffusivity(req, engine);
    EXPECT_EQ(ss::drift_laws_made() - before, 0u) << "laws made by a run on a prepared engine, with its corrector";
    EXPECT_TRUE(r.control_variate.has_value()) << "the corrector (which needs the law too) ran";
}

// A prepared point keeps its Model: the affine law, which the noise and tau
// do not enter, is one allocation for every point of a sweep over them.
TEST(DriftLaw, ModelsOfOneAffineLawShareIt) {
    ss::ModelParams p;
    ss::ModelParams q = p;
    q.noise = 2 * p.noise;
    q.tau = 3 * p.tau;
    const ss::Model a = ss::make_model(p), b = ss::make_model(q);
    EXPECT_EQ(a.law.get(), b.law.get());
    q.bias = 0.5; // another law
    const ss::Model c = ss::make_model(q);
    EXPECT_NE(c.law.get(), a.law.get());
    EXPECT_EQ(c.law->intercept, 0.5);
    EXPECT_EQ(a.law->intercept, p.bias);
}

// A table rewritten after a run was prepared changes nothing in that run: the
// prepared engine holds the law, not the path.
TEST(DriftLaw, ATableRewrittenAfterPreparationChangesNothing) {
    const std::string path = temp_file("rewritten_table.csv", "v,b\n-1,15.27\n0,0.342\n1,-14.58\n");
    ss::DiffusivityRequest req;
    req.params.drift_table = path;
    req.engine.scheme = ss::Scheme::Resolvent;
    req.engine.dt = 4e-3;
    req.engine.dt_auto = false;
    req.excursions = 64;
    req.control.threads = 2;
    const ss::PreparedEngine engine = ss::prepare(req);
    const ss::DiffusivityResult first = ss::compute_diffusivity(req, engine);
    std::ofstream(path, std::ios::trunc) << "v,b\n-1,30\n0,1\n1,-28\n"; // another law
    const ss::DiffusivityResult second = ss::compute_diffusivity(req, engine);
    EXPECT_EQ(std::memcmp(&first.estimates.diffusivity.value, &second.estimates.diffusivity.value, sizeof(double)), 0)
        << first.estimates.diffusivity.value << " then " << second.estimates.diffusivity.value;
    EXPECT_EQ(std::memcmp(&first.estimates.mobility.value, &second.estimates.mobility.value, sizeof(double)), 0);
    // A run prepared anew reads the new law: the check above can fail.
    const ss::DiffusivityResult fresh = ss::compute_diffusivity(req);
    EXPECT_NE(fresh.estimates.mobility.value, first.estimates.mobility.value);
}

TEST(DriftLaw, ASweepMakesOneLawPerPoint) {
    ss::SweepRequest req;
    req.params = law_of_its_own("0.3420002");
    req.noises = {4.0, 5.0, 6.0};
    req.taus = {0.5};
    req.engine.scheme = ss::Scheme::Resolvent;
    req.engine.dt = 4e-3;
    req.engine.dt_auto = false;
    req.excursions = 32;
    req.control.threads = 2;
    const std::uint64_t before = ss::drift_laws_made();
    (void)ss::compute_sweep(req);
    // The law's knots span the velocities each noise (and tau) reaches: one
    // law per point, and one per noise for its white-noise reference D_white
    // (tau = 0: white_ratio), 3 + 3.
    EXPECT_EQ(ss::drift_laws_made() - before, 6u);
}

TEST(DriftLaw, ACallableIsMadeAnewEachTime) {
    ss::ModelParams p;
    p.drift_function = [](double v) { return -v / 0.067 + 0.342; };
    const std::uint64_t before = ss::drift_laws_made();
    (void)ss::make_drift_law(p);
    (void)ss::make_drift_law(p);
    EXPECT_EQ(ss::drift_laws_made() - before, 2u) << "a callable's value does not show its behaviour: not kept";
}
