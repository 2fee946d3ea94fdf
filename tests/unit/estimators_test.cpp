// SPDX-License-Identifier: BSD-3-Clause
// Renewal-reward estimators and their mergeable moments (estimators.hpp,
// theory.md, section 7). References are computed directly from the stored samples
// in long double (two-pass), never from the library's moment algebra.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "stickslip/stats/estimators.hpp"
#include "stickslip/params.hpp"

namespace ss = stickslip;

namespace {

// Portable draws from std::mt19937_64 (its output sequence is fixed by the
// standard, unlike std::normal_distribution's).
struct Draws {
    std::mt19937_64 g;
    explicit Draws(std::uint64_t seed) : g(seed) {}
    double uniform() { return (static_cast<double>(g() >> 11) + 0.5) * 0x1.0p-53; } // (0, 1)
    double normal() {
        const double u1 = uniform(), u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    }
    double exponential() { return -std::log(uniform()); }
};

struct Sample {
    std::vector<double> x, y;
    void add(double a, double b) {
        x.push_back(a);
        y.push_back(b);
    }
    std::size_t size() const { return x.size(); }
};

struct Central {
    long double n, mx, my;
    long double m[5][5];   // sum (x - mx)^p (y - my)^q
    long double abs[5][5]; // sum |x - mx|^p |y - my|^q: the rounding scale
};

Central two_pass(const Sample& s, std::size_t begin = 0, std::size_t end = std::size_t(-1)) {
    end = std::min(end, s.size());
    Central c{};
    c.n = static_cast<long double>(end - begin);
    for (std::size_t k = begin; k < end; ++k) {
        c.mx += s.x[k];
        c.my += s.y[k];
    }
    c.mx /= c.n;
    c.my /= c.n;
    for (std::size_t k = begin; k < end; ++k) {
        const long double dx = s.x[k] - c.mx, dy = s.y[k] - c.my;
        for (int p = 0; p <= 4; ++p)
            for (int q = 0; p + q <= 4; ++q) {
                const long double v = std::pow(dx, p) * std::pow(dy, q);
                c.m[p][q] += v;
                c.abs[p][q] += std::fabs(v);
            }
    }
    return c;
}

ss::BivariateMoments moments_of(const Sample& s, std::size_t begin = 0, std::size_t end = std::size_t(-1)) {
    end = std::min(end, s.size());
    ss::BivariateMoments m;
    for (std::size_t k = begin; k < end; ++k) m.add(s.x[k], s.y[k]);
    return m;
}

void expect_matches(const ss::BivariateMoments& m, const Central& c, double rel, const std::string& what) {
    ASSERT_EQ(static_cast<long double>(m.count()), c.n) << what;
    EXPECT_NEAR(m.mean_x(), static_cast<double>(c.mx), 1e-14 * std::fabs(static_cast<double>(c.mx)) + 1e-300)
        << what;
    EXPECT_NEAR(m.mean_y(), static_cast<double>(c.my), 1e-14 * std::fabs(static_cast<double>(c.my)) + 1e-300)
        << what;
    for (int p = 0; p <= 4; ++p)
        for (int q = 0; p + q <= 4; ++q) {
            if (p + q < 2) continue;
            const double want = static_cast<double>(c.m[p][q]);
            const double scale = static_cast<double>(c.abs[p][q]);
            EXPECT_NEAR(m.central_sum(p, q), want, rel * scale)
                << what << ": central_sum(" << p << "," << q << ")";
            EXPECT_NEAR(m.central_moment(p, q), static_cast<double>(c.m[p][q] / c.n),
                        rel * scale / static_cast<double>(c.n))
                << what << ": central_moment(" << p << "," << q << ")";
        }
}

// A correlated, skewed, heavy-ish tailed sample like (U, t) of excursions.
Sample excursion_like(std::uint64_t seed, std::size_t n) {
    Draws d(seed);
    Sample s;
    for (std::size_t k = 0; k < n; ++k) {
        const double t = 0.1 + d.exponential();
        const double u = 0.3 * t + std::sqrt(t) * d.normal() * (1.0 + 0.5 * d.exponential());
        s.add(u, t);
    }
    return s;
}

} // namespace

TEST(BivariateMoments, OnePassMatchesTwoPassReference) {
    const Sample s = excursion_like(11, 2000);
    expect_matches(moments_of(s), two_pass(s), 1e-12, "one pass");
}

TEST(BivariateMoments, MergeInAnySplitEqualsReference) {
    const Sample s = excursion_like(12, 1500);
    const Central ref = two_pass(s);
    Draws d(99);
    for (int trial = 0; trial < 20; ++trial) {
        // Random cut points; merge left to right.
        std::vector<std::size_t> cuts = {0};
        while (cuts.back() < s.size()) {
            const std::size_t len = 1 + static_cast<std::size_t>(d.uniform() * (trial < 10 ? 10 : 400));
            cuts.push_back(std::min(s.size(), cuts.back() + len));
        }
        ss::BivariateMoments acc;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) acc.merge(moments_of(s, cuts[k], cuts[k + 1]));
        expect_matches(acc, ref, 1e-12, "left-to-right merge, trial " + std::to_string(trial));
        // Same blocks merged right to left, and as a balanced tree.
        ss::BivariateMoments rev;
        for (std::size_t k = cuts.size() - 1; k > 0; --k) {
            ss::BivariateMoments b = moments_of(s, cuts[k - 1], cuts[k]);
            b.merge(rev);
            rev = b;
        }
        expect_matches(rev, ref, 1e-12, "right-to-left merge, trial " + std::to_string(trial));
        std::vector<ss::BivariateMoments> level;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) level.push_back(moments_of(s, cuts[k], cuts[k + 1]));
        while (level.size() > 1) {
            std::vector<ss::BivariateMoments> up;
            for (std::size_t k = 0; k < level.size(); k += 2) {
                ss::BivariateMoments m = level[k];
                if (k + 1 < level.size()) m.merge(level[k + 1]);
                up.push_back(m);
            }
            level = up;
        }
        expect_matches(level[0], ref, 1e-12, "tree merge, trial " + std::to_string(trial));
    }
    // Two blocks: each block's own moments are right too.
    expect_matches(moments_of(s, 0, 700), two_pass(s, 0, 700), 1e-12, "block [0,700)");
}

TEST(BivariateMoments, RobustToLargeMeans) {
    // Mean 1e8, sd 1 (and y with mean -3e7, sd 2, correlated): raw power sums
    // would lose every digit of the variance (1e16 * eps = 2).
    Draws d(5);
    Sample s;
    for (int k = 0; k < 20000; ++k) {
        const double z1 = d.normal(), z2 = d.normal();
        s.add(1e8 + z1, -3e7 + 2.0 * (0.6 * z1 + 0.8 * z2));
    }
    const Central ref = two_pass(s);
    const ss::BivariateMoments m = moments_of(s);
    const double var = static_cast<double>(ref.m[2][0] / ref.n);
    const double m4 = static_cast<double>(ref.m[4][0] / ref.n);
    ASSERT_NEAR(var, 1.0, 0.05) << "test setup";
    // A running (streamed) mean is rounded at every add, to ~ulp(1e8) = 1.5e-8, and
    // that error enters the centred sums at first order: ~sqrt(n) ulp(1e8)/sd in
    // relative terms, 5e-9 for var and 2e-8 for the 4th moment here (measured).
    // Raw power sums would be off by O(1). Tolerance 1e-7.
    const double tol = 1e-7;
    EXPECT_NEAR(m.central_moment(2, 0), var, tol * var);
    EXPECT_NEAR(m.central_moment(4, 0), m4, tol * m4);
    EXPECT_NEAR(m.central_moment(0, 2), static_cast<double>(ref.m[0][2] / ref.n), tol * 4.0);
    EXPECT_NEAR(m.central_moment(1, 1), static_cast<double>(ref.m[1][1] / ref.n), tol * 2.0);
    EXPECT_NEAR(m.central_moment(2, 2), static_cast<double>(ref.m[2][2] / ref.n),
                tol * static_cast<double>(ref.abs[2][2] / ref.n));
    EXPECT_NEAR(m.mean_x(), static_cast<double>(ref.mx), 2e-14 * 1e8);
    // Also when the sample is split and merged.
    ss::BivariateMoments a = moments_of(s, 0, 7777), b = moments_of(s, 7777);
    a.merge(b);
    EXPECT_NEAR(a.central_moment(2, 0), var, tol * var);
    EXPECT_NEAR(a.central_moment(4, 0), m4, tol * m4);
    // Merging two blocks whose means differ by 1e8 (a pure shift of the second
    // block) is exact in the centred form: between-block term n_a n_b/n d^2.
    ss::BivariateMoments lo, hi;
    for (int k = 0; k < 100; ++k) {
        lo.add(0.01 * k, 1.0);
        hi.add(1e8 + 0.01 * k, 1.0);
    }
    lo.merge(hi);
    // Exact: 200 points, x = 1e8 * [k >= 100] + 0.01 (k mod 100).
    long double mean = 0, m2 = 0;
    for (int k = 0; k < 200; ++k) mean += (k >= 100 ? 1e8L : 0.0L) + 0.01L * (k % 100);
    mean /= 200;
    for (int k = 0; k < 200; ++k) {
        const long double dx = (k >= 100 ? 1e8L : 0.0L) + 0.01L * (k % 100) - mean;
        m2 += dx * dx;
    }
    EXPECT_NEAR(lo.central_sum(2, 0), static_cast<double>(m2), 1e-13 * static_cast<double>(m2));
}

TEST(BivariateMoments, MergeWithEmpty) {
    const Sample s = excursion_like(13, 50);
    const ss::BivariateMoments m = moments_of(s);
    ss::BivariateMoments a = m;
    a.merge(ss::BivariateMoments{});
    ss::BivariateMoments b;
    b.merge(m);
    for (const ss::BivariateMoments* x : {&a, &b}) {
        EXPECT_EQ(x->count(), m.count());
        EXPECT_EQ(x->mean_x(), m.mean_x());
        EXPECT_EQ(x->mean_y(), m.mean_y());
        for (int p = 0; p <= 4; ++p)
            for (int q = 0; p + q <= 4; ++q) EXPECT_EQ(x->central_sum(p, q), m.central_sum(p, q)) << p << q;
    }
    ss::BivariateMoments e;
    e.merge(ss::BivariateMoments{});
    EXPECT_EQ(e.count(), 0u);
    EXPECT_EQ(e.central_moment(2, 0), 0.0);
    // Single point: zero central sums.
    ss::BivariateMoments one;
    one.add(3.0, 4.0);
    EXPECT_EQ(one.mean_x(), 3.0);
    EXPECT_EQ(one.central_sum(2, 0), 0.0);
    EXPECT_EQ(one.central_sum(1, 1), 0.0);
}

namespace {

struct Direct {
    long double m0, d_renewal, d_paper, tbar;
    long double se_d, se_m0, se_t, se_paper;
};

// Estimators computed directly from the sample (theory.md, section 7).
Direct direct_estimates(const Sample& s) {
    const std::size_t n = s.size();
    const long double N = static_cast<long double>(n);
    long double su = 0, st = 0, su2 = 0;
    for (std::size_t k = 0; k < n; ++k) {
        su += s.x[k];
        st += s.y[k];
        su2 += static_cast<long double>(s.x[k]) * s.x[k];
    }
    Direct r{};
    r.m0 = su / st;
    r.tbar = st / N;
    long double sw2 = 0, swt = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const long double w = s.x[k] - r.m0 * s.y[k];
        sw2 += w * w;
        swt += w * s.y[k];
    }
    r.d_renewal = sw2 / st;
    r.d_paper = (su2 - su * su / N) / st;
    const long double c = (swt / N) / r.tbar;
    auto sd_over_sqrt_n = [&](auto phi) {
        long double mean = 0;
        for (std::size_t k = 0; k < n; ++k) mean += phi(k);
        mean /= N;
        long double ss2 = 0;
        for (std::size_t k = 0; k < n; ++k) ss2 += (phi(k) - mean) * (phi(k) - mean);
        return std::sqrt(ss2 / (N - 1)) / std::sqrt(N);
    };
    r.se_d = sd_over_sqrt_n([&](std::size_t k) {
        const long double w = s.x[k] - r.m0 * s.y[k];
        return (w * w - r.d_renewal * s.y[k] - 2 * c * w) / r.tbar;
    });
    r.se_m0 = sd_over_sqrt_n([&](std::size_t k) { return (s.x[k] - r.m0 * s.y[k]) / r.tbar; });
    r.se_t = sd_over_sqrt_n([&](std::size_t k) { return static_cast<long double>(s.y[k]); });
    const long double ubar = su / N;
    r.se_paper = sd_over_sqrt_n([&](std::size_t k) {
        const long double du = s.x[k] - ubar;
        return (du * du - r.d_paper * s.y[k]) / r.tbar;
    });
    return r;
}

/// M0, E[t1], M0_t: the symmetric interval value -+ q se.
void expect_estimate(const ss::Estimate& e, long double value, long double se, double q, const std::string& what) {
    EXPECT_NEAR(e.value, static_cast<double>(value), 1e-13 * std::fabs(static_cast<double>(value))) << what;
    EXPECT_NEAR(e.error, static_cast<double>(se), 1e-11 * static_cast<double>(se)) << what << " std_error";
    EXPECT_NEAR(e.lo, static_cast<double>(value - q * se), 1e-12 * static_cast<double>(std::fabs(value) + q * se))
        << what << " lo";
    EXPECT_NEAR(e.hi, static_cast<double>(value + q * se), 1e-12 * static_cast<double>(std::fabs(value) + q * se))
        << what << " hi";
}

/// D, D_t: the relative-error interval value / (1 +- q se / value).
void expect_scale_estimate(const ss::Estimate& e, long double value, long double se, double q,
                           const std::string& what) {
    EXPECT_NEAR(e.value, static_cast<double>(value), 1e-13 * std::fabs(static_cast<double>(value))) << what;
    EXPECT_NEAR(e.error, static_cast<double>(se), 1e-11 * static_cast<double>(se)) << what << " std_error";
    const long double h = q * se / value;
    EXPECT_NEAR(e.lo, static_cast<double>(value / (1 + h)), 1e-11 * static_cast<double>(value)) << what << " lo";
    EXPECT_GT(e.lo, 0.0) << what;
    if (h >= 1) { // q se >= D: no upper bound (8 excursions)
        EXPECT_TRUE(std::isinf(e.hi) && e.hi > 0) << what << " hi " << e.hi;
        return;
    }
    EXPECT_NEAR(e.hi, static_cast<double>(value / (1 - h)), 1e-11 * static_cast<double>(value / (1 - h)))
        << what << " hi";
    EXPECT_GT(e.hi - e.value, e.value - e.lo) << what << ": longer above";
}

} // namespace

TEST(LongExcursionEstimates, HandMadeSample) {
    // Eight excursions (U [m], t [s]) with a clear drift.
    Sample s;
    const double data[8][2] = {{0.31, 1.2}, {-0.05, 0.4}, {1.7, 3.1}, {0.02, 0.25},
                               {0.9, 2.0},  {-0.4, 0.9},  {0.55, 1.1}, {2.4, 4.6}};
    for (const auto& p : data) s.add(p[0], p[1]);
    const ss::BivariateMoments m = moments_of(s);
    const Direct ref = direct_estimates(s);
    const double q95 = 1.959963984540054;
    const ss::LongExcursionEstimates r = ss::estimate_long_excursion(m, 0.95);
    EXPECT_EQ(r.excursions, 8u);
    EXPECT_EQ(r.estimator, ss::Estimator::RenewalReward);
    expect_scale_estimate(r.diffusivity, ref.d_renewal, ref.se_d, q95, "D renewal");
    expect_estimate(r.mobility, ref.m0, ref.se_m0, q95, "M0");
    expect_estimate(r.mean_duration, ref.tbar, ref.se_t, q95, "E[t1]");
    EXPECT_EQ(r.diffusivity.level, 0.95);
    // The paper's eq. (12), and it differs from the renewal form since M0 != 0.
    const ss::LongExcursionEstimates p = ss::estimate_long_excursion(m, 0.95, ss::Estimator::Paper);
    EXPECT_EQ(p.estimator, ss::Estimator::Paper);
    expect_scale_estimate(p.diffusivity, ref.d_paper, ref.se_paper, q95, "D paper");
    EXPECT_GT(std::fabs(p.diffusivity.value - r.diffusivity.value), 0.05 * r.diffusivity.value);
    // Another level changes only the interval.
    const ss::LongExcursionEstimates r99 = ss::estimate_long_excursion(m, 0.99);
    expect_scale_estimate(r99.diffusivity, ref.d_renewal, ref.se_d, 2.5758293035489004, "D renewal 99%");
    EXPECT_EQ(r99.diffusivity.level, 0.99);
}

TEST(LongExcursionEstimates, LargerSampleAndMergedMoments) {
    const Sample s = excursion_like(21, 5000);
    const Direct ref = direct_estimates(s);
    ss::BivariateMoments a = moments_of(s, 0, 1234), b = moments_of(s, 1234);
    a.merge(b);
    const double q95 = 1.959963984540054;
    const ss::LongExcursionEstimates r = ss::estimate_long_excursion(a, 0.95);
    expect_scale_estimate(r.diffusivity, ref.d_renewal, ref.se_d, q95, "D renewal");
    expect_estimate(r.mobility, ref.m0, ref.se_m0, q95, "M0");
    expect_estimate(r.mean_duration, ref.tbar, ref.se_t, q95, "E[t1]");
    const ss::LongExcursionEstimates p = ss::estimate_long_excursion(a, 0.95, ss::Estimator::Paper);
    expect_scale_estimate(p.diffusivity, ref.d_paper, ref.se_paper, q95, "D paper");
}

TEST(LongExcursionEstimates, ZeroMobilityMakesBothEstimatorsAgree) {
    // Symmetric sample: every (U, t) has its mirror (-U, t), so M0 = 0 exactly.
    Sample s;
    const Sample half = excursion_like(31, 300);
    for (std::size_t k = 0; k < half.size(); ++k) {
        s.add(half.x[k], half.y[k]);
        s.add(-half.x[k], half.y[k]);
    }
    const ss::BivariateMoments m = moments_of(s);
    const double dr = ss::estimate_long_excursion(m, 0.95).diffusivity.value;
    const double dp = ss::estimate_long_excursion(m, 0.95, ss::Estimator::Paper).diffusivity.value;
    EXPECT_NEAR(dr, dp, 1e-12 * dr);
}

TEST(LongExcursionEstimates, DeltaMethodIntervalCoverage) {
    // 2000 data sets of N i.i.d. (t, U): t ~ Exp(1) + 0.1, U = 0.5 t + sqrt(t) Z.
    // M0 = E[U]/E[t] = 0.5 and E[(U - M0 t)^2] = E[t Z^2] = E[t], so D = 1 exactly.
    // N = 1000, not 400: measured on 2e4-4e4 data sets, the symmetric 95% interval
    // for D covered 93.2% at N = 400 (the delta method is slow to converge for the
    // skewed (U - M0 t)^2), 94.2% at N = 1000 and 94.3% at N = 2000; M0 covers 94.8%
    // at all three. D now has the relative-error interval (94.3% here, 1886/2000;
    // heavy-tailed cases: tests/statistical/coverage_test.cpp).
    const double true_d = 1.0, true_m0 = 0.5;
    Draws d(20240601);
    const int datasets = 2000, n = 1000;
    int cover_d = 0, cover_m0 = 0;
    for (int k = 0; k < datasets; ++k) {
        ss::BivariateMoments m;
        for (int j = 0; j < n; ++j) {
            const double t = d.exponential() + 0.1;
            m.add(0.5 * t + std::sqrt(t) * d.normal(), t);
        }
        const ss::LongExcursionEstimates r = ss::estimate_long_excursion(m, 0.95);
        cover_d += (r.diffusivity.lo <= true_d && true_d <= r.diffusivity.hi);
        cover_m0 += (r.mobility.lo <= true_m0 && true_m0 <= r.mobility.hi);
    }
    // Binomial sd of the count at 95%: sqrt(2000 * 0.95 * 0.05) = 9.7, i.e. 0.5%.
    EXPECT_GE(cover_d, 1860) << "D interval covered the true D in " << cover_d << " of " << datasets;
    EXPECT_LE(cover_d, 1940) << "D interval covered the true D in " << cover_d << " of " << datasets;
    EXPECT_GE(cover_m0, 1860) << "M0 interval covered the true M0 in " << cover_m0 << " of " << datasets;
    EXPECT_LE(cover_m0, 1940) << "M0 interval covered the true M0 in " << cover_m0 << " of " << datasets;
    std::cout << "[ coverage ] D: " << cover_d << "/" << datasets << ", M0: " << cover_m0 << "/" << datasets
              << "\n";
}

TEST(Estimators, RelativeErrorInterval) {
    const double q = 1.959963984540054;
    // |value/D - 1| <= q r: value / (1 + q r) <= D <= value / (1 - q r).
    const ss::Estimate e = ss::make_relative_interval(2.0, 0.25, 0.95);
    EXPECT_EQ(e.value, 2.0);
    EXPECT_EQ(e.error, 0.25);
    EXPECT_EQ(e.level, 0.95);
    const double h = q * 0.25 / 2.0;
    EXPECT_DOUBLE_EQ(e.lo, 2.0 / (1 + h));
    EXPECT_DOUBLE_EQ(e.hi, 2.0 / (1 - h));
    // The normal interval of 1/D, mapped back; both ends satisfy |value - D| = q (se/value) D.
    EXPECT_NEAR(1 / e.hi, 1 / 2.0 - q * 0.25 / 4.0, 1e-15);
    EXPECT_NEAR(1 / e.lo, 1 / 2.0 + q * 0.25 / 4.0, 1e-15);
    for (double d : {e.lo, e.hi}) EXPECT_NEAR(std::fabs(2.0 - d), q * 0.25 / 2.0 * d, 1e-14);
    // Scale equivariance: D -> s D, se -> s se scales both ends.
    const ss::Estimate f = ss::make_relative_interval(2.0e-6, 0.25e-6, 0.95);
    EXPECT_NEAR(f.lo, 1e-6 * e.lo, 1e-21);
    EXPECT_NEAR(f.hi, 1e-6 * e.hi, 1e-21);
    // To first order in se the symmetric interval.
    const ss::Estimate g = ss::make_relative_interval(1.0, 1e-6, 0.95);
    EXPECT_NEAR(g.lo, 1 - q * 1e-6, 1e-11);
    EXPECT_NEAR(g.hi, 1 + q * 1e-6, 1e-11);
    // Never negative; unbounded above once q se >= value.
    const ss::Estimate wide = ss::make_relative_interval(1.0, 0.6, 0.95);
    EXPECT_GT(wide.lo, 0.0);
    EXPECT_DOUBLE_EQ(wide.lo, 1.0 / (1 + q * 0.6));
    EXPECT_TRUE(std::isinf(wide.hi) && wide.hi > 0);
    const ss::Estimate exact = ss::make_relative_interval(3.0, 0.0, 0.95);
    EXPECT_EQ(exact.lo, 3.0);
    EXPECT_EQ(exact.hi, 3.0);
    // A zero estimate: the symmetric interval, clamped at 0.
    const ss::Estimate zero = ss::make_relative_interval(0.0, 0.1, 0.95);
    EXPECT_EQ(zero.lo, 0.0);
    EXPECT_DOUBLE_EQ(zero.hi, q * 0.1);
    const ss::Estimate none = ss::make_relative_interval(std::numeric_limits<double>::quiet_NaN(), 0.1, 0.95);
    EXPECT_TRUE(std::isnan(none.lo) && std::isnan(none.hi));
    const ss::Estimate nose = ss::make_relative_interval(1.0, std::numeric_limits<double>::quiet_NaN(), 0.95);
    EXPECT_TRUE(std::isnan(nose.lo) && std::isnan(nose.hi));
    // The level is validated, and a higher one widens both sides.
    EXPECT_THROW(ss::make_relative_interval(1.0, 0.1, 1.0), ss::InvalidParameter);
    const ss::Estimate e99 = ss::make_relative_interval(2.0, 0.25, 0.99);
    EXPECT_LT(e99.lo, e.lo);
    EXPECT_GT(e99.hi, e.hi);
}

TEST(Estimators, NormalQuantileAndLevelValidation) {
    EXPECT_NEAR(ss::normal_quantile_two_sided(0.95), 1.959963984540054, 1e-15);
    EXPECT_NEAR(ss::normal_quantile_two_sided(0.99), 2.5758293035489004, 1e-14);
    EXPECT_NEAR(ss::normal_quantile_two_sided(0.6826894921370859), 1.0, 1e-13);
    for (double bad : {0.0, 1.0, -0.5, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
        try {
            ss::normal_quantile_two_sided(bad);
            ADD_FAILURE() << "no error for level " << bad;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), "level") << e.what();
        }
    }
    ss::BivariateMoments m;
    m.add(1.0, 1.0);
    m.add(2.0, 1.5);
    try {
        ss::estimate_long_excursion(m, 1.0);
        ADD_FAILURE() << "no error for level 1";
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), "level");
    }
    ss::BivariateMoments one;
    one.add(1.0, 1.0);
    EXPECT_THROW(ss::estimate_long_excursion(one, 0.95), ss::InvalidParameter);
    EXPECT_THROW(ss::estimate_bruteforce(one, 1.0, 0.95), ss::InvalidParameter);
    EXPECT_EQ(ss::to_string(ss::Estimator::Paper), "paper");
    EXPECT_EQ(ss::to_string(ss::Estimator::RenewalReward), "renewal");
    EXPECT_EQ(ss::parse_estimator("paper"), ss::Estimator::Paper);
    EXPECT_EQ(ss::parse_estimator("renewal"), ss::Estimator::RenewalReward);
    try {
        ss::parse_estimator("eq12");
        ADD_FAILURE();
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), "estimator");
    }
}

TEST(BruteForceEstimates, HandMadeSample) {
    // U(t) at t = 10 s of six trajectories.
    const std::vector<double> u = {0.8, -1.3, 2.2, 0.1, -0.6, 1.9};
    const double horizon = 10.0;
    ss::BivariateMoments m;
    for (double x : u) m.add(x, 0.0);
    long double mean = 0;
    for (double x : u) mean += x;
    mean /= u.size();
    long double ss2 = 0;
    for (double x : u) ss2 += (x - mean) * (x - mean);
    const long double n = u.size();
    const long double var = ss2 / (n - 1); // unbiased sample variance
    // SE of the variance: sd of phi_k = (U_k - mean)^2 (n - 1 in the sd) over sqrt(n); of the mean: sd/sqrt(n).
    long double sphi = 0;
    for (double x : u) {
        const long double phi = (x - mean) * (x - mean) - ss2 / n;
        sphi += phi * phi;
    }
    const long double se_var = std::sqrt(sphi / (n - 1) / n);
    const long double se_mean = std::sqrt(var / n);
    const double q95 = 1.959963984540054;
    const ss::BruteForceEstimates r = ss::estimate_bruteforce(m, horizon, 0.95);
    EXPECT_EQ(r.trajectories, 6u);
    EXPECT_EQ(r.horizon, horizon);
    expect_scale_estimate(r.diffusivity, var / horizon, se_var / horizon, q95, "D_t");
    expect_estimate(r.mobility, mean / horizon, se_mean / horizon, q95, "M0_t");
}
