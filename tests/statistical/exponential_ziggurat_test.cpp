// SPDX-License-Identifier: BSD-3-Clause
// The exponentials of BatchedUniformRng::exponential_uniform (the PDMP
// engine's waiting times; bitwise those of CounterRng, tests/unit/
// rng_batch_test.cpp) are exponential of mean 1 and independent of the
// draw's uniform: 2e7 draws from eight streams with fixed seeds, compared
// with exact values using standard errors from the same sample (z-score in
// every message):
//   - raw moments E[e^k] = k!, k = 1..4;
//   - 31 bins whose edges are ziggurat layer edges (the top layer [0, x_1],
//     groups of wedges, the bottom edge zige_r, the tail split at r + 1.5):
//     per-bin z and a chi-square p-value; the two tail bins are filled by the
//     tail algorithm alone;
//   - Cov(e, u) = 0 and Cov(e^2, u) = 0 within a draw, and E[(e_j - 1)(e_(j+1) - 1)] = 0
//     between consecutive draws.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>

#include "stickslip/random/rng_batch.hpp"
#include "support.hpp"

namespace {

using namespace sstest;
namespace zd = stickslip::detail;

constexpr int kStreams = 8;
constexpr std::uint64_t kDrawsPerStream = 2500000; // 2e7 exponentials
constexpr double kZ = 5.0;

/// 0, x_1, x_2, x_5, x_10, x_20, ..., x_250, x_255 = r, r + 1.5, +inf.
std::vector<double> edges() {
    const double two53 = 9007199254740992.0;
    std::vector<double> e = {0.0};
    for (int i : {1, 2, 5}) e.push_back(zd::zige_w[i] * two53);
    for (int i = 10; i <= 250; i += 10) e.push_back(zd::zige_w[i] * two53);
    e.push_back(zd::zige_r);
    e.push_back(zd::zige_r + 1.5);
    e.push_back(HUGE_VAL);
    return e;
}

struct Sample {
    double n = 0;
    std::array<double, 9> pow_sum{}; // sums of e^k, k = 0..8
    double s_eu = 0, s_eu2 = 0, s_e2u = 0, s_e2u2 = 0, s_u = 0, s_u2 = 0; // within a draw
    double s_lag = 0, s_lag2 = 0, lags = 0;                             // consecutive draws
    std::vector<double> e, count;
};

const Sample& sample() {
    static const Sample s = [] {
        Sample out;
        out.e = edges();
        out.count.assign(out.e.size() - 1, 0.0);
        for (int st = 0; st < kStreams; ++st) {
            ss::BatchedUniformRng rng(20261202 + static_cast<std::uint64_t>(st) * 104729,
                                      st % 2 ? ss::StreamPurpose::LongExcursion : ss::StreamPurpose::BruteForce,
                                      static_cast<std::uint64_t>(st) * 999983);
            double prev = 0;
            for (std::uint64_t k = 0; k < kDrawsPerStream; ++k) {
                double e, u;
                rng.exponential_uniform(e, u);
                double p = 1;
                for (int j = 1; j <= 8; ++j) out.pow_sum[static_cast<std::size_t>(j)] += (p *= e);
                const double du = u - 0.5, de = e - 1, de2 = e * e - 2;
                out.s_u += du;
                out.s_u2 += du * du;
                out.s_eu += de * du;
                out.s_eu2 += de * de * du * du;
                out.s_e2u += de2 * du;
                out.s_e2u2 += de2 * de2 * du * du;
                if (k > 0) {
                    out.s_lag += (prev - 1) * de;
                    out.s_lag2 += (prev - 1) * (prev - 1) * de * de;
                    out.lags += 1;
                }
                prev = e;
                const auto it = std::upper_bound(out.e.begin() + 1, out.e.end(), e);
                out.count[static_cast<std::size_t>(it - out.e.begin()) - 1] += 1;
            }
        }
        out.n = static_cast<double>(kStreams) * static_cast<double>(kDrawsPerStream);
        out.pow_sum[0] = out.n;
        return out;
    }();
    return s;
}

} // namespace

TEST(ExponentialZiggurat, RawMomentsAreFactorials) {
    const Sample& s = sample();
    double factorial = 1;
    for (int k = 1; k <= 4; ++k) {
        factorial *= k;
        const double m = s.pow_sum[static_cast<std::size_t>(k)] / s.n;
        const double m2 = s.pow_sum[static_cast<std::size_t>(2 * k)] / s.n;
        const auto c = compare(m, std::sqrt((m2 - m * m) / s.n), factorial, 0.0, 0.0, kZ);
        const std::string what = "E[e^" + std::to_string(k) + "]";
        EXPECT_TRUE(check(c, what + " of 2e7 ziggurat exponentials vs " + std::to_string(k) + "!")) << c.message(what);
    }
}

TEST(ExponentialZiggurat, BinnedDistributionMatchesTheExponential) {
    const Sample& s = sample();
    double chi2 = 0, min_expected = s.n;
    const std::size_t nb = s.count.size();
    for (std::size_t b = 0; b < nb; ++b) {
        const double p = std::exp(-s.e[b]) - std::exp(-s.e[b + 1]);
        const double expected = s.n * p, observed = s.count[b];
        const double z = (observed - expected) / std::sqrt(expected * (1 - p));
        chi2 += (observed - expected) * (observed - expected) / expected;
        min_expected = std::min(min_expected, expected);
        EXPECT_LT(std::fabs(z), kZ) << "bin (" << s.e[b] << ", " << s.e[b + 1] << "]: observed " << observed
                                    << ", expected " << expected << ", z = " << z;
    }
    const double dof = static_cast<double>(nb) - 1;
    const double pvalue = boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), chi2));
    std::cout << "[measured] " << nb << " bins (layer edges; tail beyond r = " << zd::zige_r
              << " split at r + 1.5; smallest expected count " << min_expected << "): chi2 = " << chi2 << " on " << dof
              << " dof, p = " << pvalue << (pvalue > 1e-4 ? "" : "  <-- FAILS") << std::endl;
    EXPECT_GE(min_expected, 50.0);
    EXPECT_GT(pvalue, 1e-4) << "chi2 = " << chi2 << " on " << dof << " dof";
}

TEST(ExponentialZiggurat, IndependentOfTheUniformAndOfTheNextDraw) {
    const Sample& s = sample();
    const auto cov = [&](double sum, double sum_sq, double n, const std::string& what) {
        const double m = sum / n;
        const auto c = compare(m, std::sqrt((sum_sq / n - m * m) / n), 0.0, 0.0, 0.0, kZ);
        EXPECT_TRUE(check(c, what + " vs 0")) << c.message(what);
    };
    // E[u] = 1/2 exactly, E[e] = 1, E[e^2] = 2: the centred products have mean 0 under independence.
    cov(s.s_u, s.s_u2, s.n, "E[u - 1/2] of the draws' uniforms");
    cov(s.s_eu, s.s_eu2, s.n, "Cov(e, u) within a draw");
    cov(s.s_e2u, s.s_e2u2, s.n, "Cov(e^2, u) within a draw");
    cov(s.s_lag, s.s_lag2, s.lags, "Cov(e_j, e_(j+1)) between consecutive draws");
}
