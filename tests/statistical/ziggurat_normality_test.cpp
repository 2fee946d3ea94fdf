// SPDX-License-Identifier: BSD-3-Clause
// The ziggurat normals of BatchedCounterRng (bitwise those of CounterRng,
// tests/unit/rng_batch_test.cpp) are standard normal: 2e7 normals from eight
// streams with fixed seeds, compared with exact values using standard errors
// computed from the same sample (z-score in every message):
//   - raw moments E[z], E[z^2], E[z^3], E[z^4] = 0, 1, 0, 3;
//   - 62 bins whose edges are ziggurat layer edges (the top layer [0, x_1],
//     groups of wedges, the bottom edge zig_r, the tail split at 4.5): per-bin
//     z and a chi-square p-value;
//   - P(|Z| > zig_r), the part produced by the tail algorithm alone;
//   - the two normals of a pair are independent: E[xy] = 0 and
//     Cov(x^2, y^2) = 0, and consecutive pairs: E[x_j x_(j+1)] = 0;
//   - the tail algorithm alone (2e6 samples of Z | Z > zig_r): binned shape
//     and mean excess, which the 5e3 tail normals above cannot resolve.
// The sample is drawn once per process and shared by the tests (0.6 s, Release).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>

#include "stickslip/random/rng_batch.hpp"
#include "support.hpp"

namespace {

using namespace sstest;
namespace zd = stickslip::detail;

constexpr int kStreams = 8;
constexpr std::uint64_t kPairsPerStream = 1250000; // 8 x 1.25e6 pairs = 2e7 normals
constexpr double kZ = 5.0;                          // allowed |z| for single checks

std::string fmt(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

/// P(Z > a) for the standard normal (a may be +-infinity).
double upper_tail(double a) { return 0.5 * std::erfc(a / std::numbers::sqrt2); }

/// Bin edges on the positive half line: 0, x_1, x_2, x_5, x_10, x_20, ..., x_250,
/// x_255 = zig_r, 4.5, +inf, where x_i is the right edge of ziggurat layer i.
/// Mirrored for the negative half: 31 + 31 = 62 bins.
std::vector<double> positive_edges() {
    const double two52 = 4503599627370496.0;
    std::vector<double> e = {0.0};
    for (int i : {1, 2, 5}) e.push_back(zd::zig_w[i] * two52);
    for (int i = 10; i <= 250; i += 10) e.push_back(zd::zig_w[i] * two52);
    e.push_back(zd::zig_r);
    e.push_back(4.5);
    e.push_back(std::numeric_limits<double>::infinity());
    return e;
}

struct Sample {
    double n = 0;                           // number of normals
    double pairs = 0;                       // number of (x, y) pairs
    std::array<double, 9> pow_sum{};        // sums of z^k, k = 0..8
    double sxy = 0, sx2y2 = 0;              // sums over pairs of x y and x^2 y^2
    double s_lag = 0, s_lag2 = 0, lags = 0; // x_j x_(j+1) over consecutive pairs of one stream
    double beyond_r = 0;                    // count of |z| > zig_r
    std::vector<double> edges;              // positive edges
    std::vector<double> pos_count, neg_count;
    double seconds = 0;
};

const Sample& sample() {
    static const Sample s = [] {
        Sample out;
        out.edges = positive_edges();
        const std::size_t nb = out.edges.size() - 1;
        out.pos_count.assign(nb, 0.0);
        out.neg_count.assign(nb, 0.0);
        std::vector<std::uint64_t> pos(nb, 0), neg(nb, 0);
        const auto t0 = std::chrono::steady_clock::now();
        for (int st = 0; st < kStreams; ++st) {
            ss::BatchedCounterRng rng(20240611 + static_cast<std::uint64_t>(st) * 7919,
                                      st % 2 ? ss::StreamPurpose::LongExcursion : ss::StreamPurpose::BruteForce,
                                      static_cast<std::uint64_t>(st) * 1000003);
            std::array<double, 9> ps{};
            double sxy = 0, sx2y2 = 0, slag = 0, slag2 = 0, beyond = 0, prev_x = 0;
            for (std::uint64_t k = 0; k < kPairsPerStream; ++k) {
                const ss::NormalPair z = rng.normal2();
                for (double v : {z.x, z.y}) {
                    const double v2 = v * v, v4 = v2 * v2;
                    ps[1] += v;
                    ps[2] += v2;
                    ps[3] += v2 * v;
                    ps[4] += v4;
                    ps[5] += v4 * v;
                    ps[6] += v4 * v2;
                    ps[7] += v4 * v2 * v;
                    ps[8] += v4 * v4;
                    const double a = std::fabs(v);
                    beyond += a > zd::zig_r ? 1.0 : 0.0;
                    // Bin b holds (edges[b], edges[b + 1]]; a = 0 goes to bin 0.
                    const auto it = std::lower_bound(out.edges.begin() + 1, out.edges.end(), a);
                    const std::size_t b = static_cast<std::size_t>(it - out.edges.begin()) - 1;
                    ++(std::signbit(v) ? neg : pos)[b];
                }
                sxy += z.x * z.y;
                sx2y2 += z.x * z.x * z.y * z.y;
                if (k > 0) {
                    slag += prev_x * z.x;
                    slag2 += prev_x * prev_x * z.x * z.x;
                }
                prev_x = z.x;
            }
            for (int p = 1; p <= 8; ++p) out.pow_sum[static_cast<std::size_t>(p)] += ps[static_cast<std::size_t>(p)];
            out.sxy += sxy;
            out.sx2y2 += sx2y2;
            out.s_lag += slag;
            out.s_lag2 += slag2;
            out.lags += static_cast<double>(kPairsPerStream - 1);
            out.beyond_r += beyond;
        }
        out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        out.pairs = static_cast<double>(kStreams) * static_cast<double>(kPairsPerStream);
        out.n = 2 * out.pairs;
        out.pow_sum[0] = out.n;
        for (std::size_t b = 0; b < nb; ++b) {
            out.pos_count[b] = static_cast<double>(pos[b]);
            out.neg_count[b] = static_cast<double>(neg[b]);
        }
        std::cout << "[measured] " << out.n << " ziggurat normals (BatchedCounterRng, " << kStreams
                  << " streams, ISA " << zd::rng_batch_isa() << ") drawn and tallied in " << out.seconds << " s"
                  << std::endl;
        return out;
    }();
    return s;
}

/// Mean of z^k and its standard error from the same sample.
struct Moment {
    double mean, se;
};
Moment moment(const Sample& s, int k) {
    const double m = s.pow_sum[static_cast<std::size_t>(k)] / s.n;
    const double m2 = s.pow_sum[static_cast<std::size_t>(2 * k)] / s.n;
    return {m, std::sqrt((m2 - m * m) / s.n)};
}

TEST(ZigguratNormality, RawMomentsUpToFour) {
    const Sample& s = sample();
    const double exact[5] = {1, 0, 1, 0, 3};
    const char* names[5] = {"", "E[z]", "E[z^2]", "E[z^3]", "E[z^4]"};
    for (int k = 1; k <= 4; ++k) {
        const Moment m = moment(s, k);
        const auto c = compare(m.mean, m.se, exact[k], 0.0, 0.0, kZ);
        EXPECT_TRUE(check(c, std::string(names[k]) + " of 2e7 ziggurat normals vs " + fmt(exact[k])))
            << c.message(names[k]);
    }
    // The sample variance, for the record (its se: sqrt((m4 - 1) / n)).
    const Moment m1 = moment(s, 1), m2 = moment(s, 2);
    const double var = m2.mean - m1.mean * m1.mean;
    const auto c = compare(var, m2.se, 1.0, 0.0, 0.0, kZ);
    EXPECT_TRUE(check(c, "sample variance vs 1")) << c.message("variance");
}

TEST(ZigguratNormality, BinnedDistributionMatchesPhi) {
    const Sample& s = sample();
    const auto& e = s.edges;
    const std::size_t nb = e.size() - 1;
    double chi2 = 0, max_z = 0, min_expected = s.n, worst_lo = 0, worst_hi = 0;
    int bins = 0;
    for (int sign : {+1, -1})
        for (std::size_t b = 0; b < nb; ++b) {
            const double p = upper_tail(e[b]) - upper_tail(e[b + 1]);
            const double expected = s.n * p;
            const double observed = sign > 0 ? s.pos_count[b] : s.neg_count[b];
            const double z = (observed - expected) / std::sqrt(expected * (1 - p));
            chi2 += (observed - expected) * (observed - expected) / expected;
            min_expected = std::min(min_expected, expected);
            if (std::fabs(z) > std::fabs(max_z)) {
                max_z = z;
                worst_lo = sign > 0 ? e[b] : -e[b + 1];
                worst_hi = sign > 0 ? e[b + 1] : -e[b];
            }
            ++bins;
            EXPECT_LT(std::fabs(z), kZ) << "bin (" << (sign > 0 ? e[b] : -e[b + 1]) << ", "
                                        << (sign > 0 ? e[b + 1] : -e[b]) << "]: observed " << observed
                                        << ", expected " << expected << ", z = " << z;
        }
    const double dof = bins - 1;
    const double pvalue = boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), chi2));
    std::cout << "[measured] " << bins << " bins (layer edges, tail split at 4.5; smallest expected count "
              << min_expected << "): chi2 = " << chi2 << " on " << dof << " dof, p = " << pvalue
              << "; max |z| = " << std::fabs(max_z) << " (z = " << max_z << " in (" << worst_lo << ", " << worst_hi
              << "])" << (pvalue > 1e-4 ? "" : "  <-- FAILS") << std::endl;
    EXPECT_GE(min_expected, 50.0); // chi-square approximation valid in every bin
    EXPECT_GT(pvalue, 1e-4) << "chi2 = " << chi2 << " on " << dof << " dof; max |z| = " << max_z;
}

TEST(ZigguratNormality, TailBeyondTheBottomLayer) {
    // P(|Z| > r) = erfc(r / sqrt 2): only the tail algorithm puts mass there.
    const Sample& s = sample();
    const double p = 2 * upper_tail(zd::zig_r);
    const double phat = s.beyond_r / s.n;
    const auto c = compare(phat, std::sqrt(phat * (1 - phat) / s.n), p, 0.0, 0.0, kZ);
    EXPECT_TRUE(check(c, "P(|Z| > zig_r) of 2e7 ziggurat normals vs erfc(r / sqrt 2) (" +
                             fmt(s.beyond_r) + " beyond)"))
        << c.message("tail probability");
}

TEST(ZigguratNormality, HalvesOfAPairAreIndependent) {
    const Sample& s = sample();
    // E[xy] = 0; se from the sample: sqrt(E[x^2 y^2] / pairs).
    const double mxy = s.sxy / s.pairs;
    const double se_xy = std::sqrt((s.sx2y2 / s.pairs - mxy * mxy) / s.pairs);
    const auto c = compare(mxy, se_xy, 0.0, 0.0, 0.0, kZ);
    EXPECT_TRUE(check(c, "E[x y] of 1e7 pairs (correlation of the two halves) vs 0")) << c.message("E[xy]");
    // Cov(x^2, y^2) = E[x^2 y^2] - E[x^2] E[y^2] = 0 (the halves share a block;
    // a dependence of magnitudes would show here). Var(x^2 y^2) = E[x^4 y^4] - ...;
    // under independence that is 9 - 1 = 8, estimated from the fourth moments.
    const double m2 = s.pow_sum[2] / s.n, m4 = s.pow_sum[4] / s.n;
    const double cov = s.sx2y2 / s.pairs - m2 * m2;
    const double se_cov = std::sqrt((m4 * m4 - m2 * m2 * m2 * m2) / s.pairs);
    const auto c2 = compare(cov, se_cov, 0.0, 0.0, 0.0, kZ);
    EXPECT_TRUE(check(c2, "Cov(x^2, y^2) of 1e7 pairs vs 0")) << c2.message("Cov(x^2, y^2)");
    // Consecutive draws of a stream: E[x_j x_(j+1)] = 0.
    const double mlag = s.s_lag / s.lags;
    const double se_lag = std::sqrt((s.s_lag2 / s.lags - mlag * mlag) / s.lags);
    const auto c3 = compare(mlag, se_lag, 0.0, 0.0, 0.0, kZ);
    EXPECT_TRUE(check(c3, "E[x_j x_(j+1)] over consecutive draws vs 0")) << c3.message("lag-1");
}

TEST(ZigguratNormality, TailAlgorithmGivesTheConditionalNormalTail) {
    // The tail (layer 0 beyond r) is 1.3% of the slow path and 2.6e-4 of all
    // normals: too few above to see its shape. Here the tail algorithm alone:
    // a base-strip word beyond r resolved from the retry substreams of 2e6 draw
    // numbers gives 2e6 independent samples of Z | Z > r (negated for sign 1).
    // 31 bins of Z - r (width 0.05 up to 1.5, then open) against
    // P(a < Z < b | Z > r) = (erfc(a / sqrt 2) - erfc(b / sqrt 2)) / erfc(r / sqrt 2),
    // and the mean excess E[Z - r | Z > r] = phi(r) / Q(r) - r.
    const auto t0 = std::chrono::steady_clock::now();
    const auto key = ss::CounterRng::make_key(777);
    const auto ctr = ss::CounterRng::make_counter(ss::StreamPurpose::Test, 42, 0);
    const std::uint64_t word_pos = (std::uint64_t{1} << 61) - 1 - 0x1ff; // layer 0, sign 0, position all ones
    const std::uint64_t word_neg = word_pos | 0x100;                     // sign 1
    const int n = 2000000, nb = 31;
    const double width = 0.05, r = zd::zig_r;
    std::vector<double> count(nb, 0.0);
    double s1 = 0, s2 = 0;
    for (int j = 0; j < n / 2; ++j)
        for (unsigned half = 0; half < 2; ++half) {
            const double z = ss::CounterRng::resolve_rejected(key, ctr.v[2], ctr.v[3], static_cast<std::uint64_t>(j),
                                                              half, half ? word_neg : word_pos);
            ASSERT_TRUE(half ? z < -r : z > r) << "tail sample " << z << " at draw " << j << ", half " << half;
            const double t = std::fabs(z) - r;
            s1 += t;
            s2 += t * t;
            count[static_cast<std::size_t>(std::min(static_cast<int>(t / width), nb - 1))] += 1;
        }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double q_r = upper_tail(r);
    double chi2 = 0, max_z = 0;
    for (int b = 0; b < nb; ++b) {
        const double lo = r + b * width, hi = b == nb - 1 ? std::numeric_limits<double>::infinity() : lo + width;
        const double p = (upper_tail(lo) - upper_tail(hi)) / q_r;
        const double expected = n * p, observed = count[static_cast<std::size_t>(b)];
        const double z = (observed - expected) / std::sqrt(expected * (1 - p));
        chi2 += (observed - expected) * (observed - expected) / expected;
        if (std::fabs(z) > std::fabs(max_z)) max_z = z;
        EXPECT_LT(std::fabs(z), kZ) << "tail bin (" << lo << ", " << hi << "]: observed " << observed << ", expected "
                                    << expected << ", z = " << z;
    }
    const double dof = nb - 1;
    const double pvalue = boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), chi2));
    std::cout << "[measured] tail algorithm, " << n << " samples of |Z| - r in " << seconds << " s: chi2 = " << chi2
              << " on " << dof << " dof, p = " << pvalue << ", max |z| = " << std::fabs(max_z)
              << (pvalue > 1e-4 ? "" : "  <-- FAILS") << std::endl;
    EXPECT_GT(pvalue, 1e-4) << "chi2 = " << chi2 << " on " << dof << " dof; max |z| = " << max_z;
    const double phi_r = std::exp(-0.5 * r * r) / std::sqrt(2 * std::numbers::pi);
    const double mean = s1 / n, se = std::sqrt((s2 / n - mean * mean) / n);
    const auto c = compare(mean, se, phi_r / q_r - r, 0.0, 0.0, kZ);
    EXPECT_TRUE(check(c, "tail algorithm: E[Z - r | Z > r] vs phi(r) / Q(r) - r")) << c.message("mean excess");
}

} // namespace
