// SPDX-License-Identifier: BSD-3-Clause
// The control-variate estimators of D and M0 (control_variate.hpp): known
// answers against a two-pass long-double computation from the samples (a tiny
// hand data set and a strongly driven one), the coefficients vanish when the
// control variates carry no information, a martingale that explains U - M0 t
// removes most of the variance without bias, the plain parts are those of
// estimate_long_excursion, and no merge order or serialisation leaves a trace.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "driver/block_driver.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/stats/control_variate.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/stats/moment_sums.hpp"

namespace {

// What the block driver needs of a run's total (merge, words, to_words, assign_words).
static_assert(stickslip::detail::BlockTotal<stickslip::ControlVariateSums>);

using stickslip::ControlVariateBlock;
using stickslip::ControlVariateEstimates;
using stickslip::ControlVariateSums;
using stickslip::ExactSum;
using stickslip::estimate_control_variate;
using stickslip::fit_control_variate;
using stickslip::influence_centres;
using stickslip::InfluenceCentres;
using stickslip::InfluenceTailSums;

struct Samples {
    std::vector<double> u, t, m, c;
    void push(double u_, double t_, double m_, double c_) {
        u.push_back(u_);
        t.push_back(t_);
        m.push_back(m_);
        c.push_back(c_);
    }
    std::size_t size() const { return u.size(); }
};

/// Blocks of 64 in index order, as the block driver makes them (with
/// `centres`, summing the influence functions' shape too).
std::vector<ControlVariateBlock> blocks_of(const Samples& s, const InfluenceCentres* centres = nullptr) {
    std::vector<ControlVariateBlock> out;
    for (std::size_t k = 0; k < s.size(); ++k) {
        if (k % 64 == 0) out.emplace_back(centres);
        out.back().add(s.u[k], s.t[k], s.m[k], s.c[k]);
    }
    return out;
}

ControlVariateSums sums_of(const Samples& s) {
    ControlVariateSums sums;
    for (const auto& b : blocks_of(s)) sums.add_block(b);
    return sums;
}

/// The plain estimates of the same samples, by the run's path for (U, t).
stickslip::LongExcursionEstimates plain_of(const Samples& s, double level = 0.95) {
    stickslip::ExactBivariateSums sums;
    for (std::size_t k = 0; k < s.size(); k += 64) {
        stickslip::BivariateMoments b;
        for (std::size_t j = k; j < std::min(k + 64, s.size()); ++j) b.add(s.u[j], s.t[j]);
        sums.add_block(b);
    }
    return stickslip::estimate_long_excursion(sums.moments(), level);
}

/// Every output of estimate_control_variate, two-pass in long double from the samples.
struct Reference {
    long double d_cv, se_d, beta, vr, m0_cv, se_m, beta_m, vr_m;

    /// With `fixed` {beta, beta'}: the estimates at those coefficients (a
    /// pilot's) instead of the fitted ones.
    explicit Reference(const Samples& s, const long double* fixed = nullptr) {
        const long double n = static_cast<long double>(s.size());
        long double su = 0, st = 0, sm = 0, sc = 0;
        for (std::size_t k = 0; k < s.size(); ++k) {
            su += s.u[k];
            st += s.t[k];
            sm += s.m[k];
            sc += s.c[k];
        }
        const long double tbar = st / n, m0 = su / st;
        std::vector<long double> w(s.size());
        long double sw2 = 0, swt = 0, swm = 0, sm2 = 0, sc2 = 0;
        for (std::size_t k = 0; k < s.size(); ++k) {
            w[k] = s.u[k] - m0 * s.t[k];
            sw2 += w[k] * w[k];
            swt += w[k] * s.t[k];
            swm += w[k] * s.m[k];
            sm2 += static_cast<long double>(s.m[k]) * s.m[k];
            sc2 += static_cast<long double>(s.c[k]) * s.c[k];
        }
        const long double d = sw2 / st, c = swt / n / tbar;
        long double sphi2 = 0, sphic = 0;
        for (std::size_t k = 0; k < s.size(); ++k) {
            const long double phi = w[k] * w[k] - d * s.t[k] - 2 * c * w[k];
            sphi2 += phi * phi;
            sphic += phi * s.c[k];
        }
        beta = fixed ? fixed[0] : sc2 > 0 ? sphic / sc2 : 0;
        d_cv = (sw2 - beta * sc) / st;
        beta_m = fixed ? fixed[1] : sm2 > 0 ? swm / sm2 : 0;
        m0_cv = (su - beta_m * sm) / st;
        long double spsi2 = 0, schi2 = 0;
        for (std::size_t k = 0; k < s.size(); ++k) {
            const long double psi = w[k] * w[k] - beta * s.c[k] - d_cv * s.t[k] - 2 * c * w[k];
            const long double chi = s.u[k] - beta_m * s.m[k] - m0_cv * s.t[k];
            spsi2 += psi * psi;
            schi2 += chi * chi;
        }
        se_d = std::sqrt(spsi2 / n / (n - 1)) / tbar;
        se_m = std::sqrt(schi2 / n / (n - 1)) / tbar;
        vr = sphi2 / spsi2;
        vr_m = sw2 / schi2;
    }
};

void expect_close(double got, long double want, double rel, const char* what) {
    const double w = static_cast<double>(want);
    EXPECT_NEAR(got, w, rel * std::fabs(w)) << what;
}

void expect_matches(const ControlVariateEstimates& e, const Reference& r, double rel) {
    expect_close(e.diffusivity.value, r.d_cv, rel, "D_cv");
    expect_close(e.diffusivity.error, r.se_d, rel, "se(D_cv)");
    expect_close(e.beta, r.beta, rel, "beta");
    expect_close(e.variance_reduction, r.vr, rel, "variance_reduction");
    expect_close(e.mobility.value, r.m0_cv, rel, "M0_cv");
    expect_close(e.mobility.error, r.se_m, rel, "se(M0_cv)");
    expect_close(e.beta_mobility, r.beta_m, rel, "beta'");
    expect_close(e.variance_reduction_mobility, r.vr_m, rel, "variance_reduction_mobility");
}

/// Excursions of K ~ 1 + Geometric(0.1) steps of length h: M = sum g xi with
/// g ~ U[0.5, 1.5] and xi ~ N(0, h), Q = sum g^2 h, t = K h, and
/// U = m0 t + M + noise sqrt(t) z. Then D = E[g^2] + noise^2 = 13/12 + noise^2
/// and M0 = m0 exactly, and C = M^2 - Q has mean 0.
Samples martingale_case(std::size_t n, double m0, double noise, unsigned seed) {
    std::mt19937_64 gen(seed);
    std::geometric_distribution<int> steps(0.1);
    std::uniform_real_distribution<double> gain(0.5, 1.5);
    std::normal_distribution<double> normal(0.0, 1.0);
    const double h = 0.1;
    Samples s;
    for (std::size_t k = 0; k < n; ++k) {
        const int K = 1 + steps(gen);
        double m = 0, q = 0;
        for (int j = 0; j < K; ++j) {
            const double g = gain(gen);
            m += g * std::sqrt(h) * normal(gen);
            q += g * g * h;
        }
        const double t = K * h;
        s.push(m0 * t + m + noise * std::sqrt(t) * normal(gen), t, m, m * m - q);
    }
    return s;
}

/// Six excursions by hand, with every sign of U, M and C.
Samples hand_data_set() {
    Samples s;
    s.push(1.5, 1.0, 0.8, 0.3);
    s.push(-0.5, 0.5, -0.6, -0.2);
    s.push(2.0, 2.0, 1.1, 0.9);
    s.push(0.25, 0.75, 0.1, -0.5);
    s.push(3.0, 2.5, 1.2, 0.4);
    s.push(-1.0, 1.25, -1.3, -0.6);
    return s;
}

TEST(ControlVariateEstimator, HandDataSetKnownAnswer) {
    const Samples s = hand_data_set();
    const ControlVariateEstimates e = estimate_control_variate(sums_of(s), 0.95);
    EXPECT_EQ(e.samples, 6u);
    expect_matches(e, Reference(s), 1e-13);
    EXPECT_EQ(e.diffusivity.level, 0.95);
    EXPECT_LT(e.mobility.lo, e.mobility.value);
    EXPECT_GT(e.mobility.hi, e.mobility.value);
}

TEST(ControlVariateEstimator, GivenCoefficientsAreUsedAsGivenAndFittedOnesAreThePilots) {
    const Samples s = hand_data_set();
    const long double fixed[2] = {0.7L, 1.3L};
    const ControlVariateEstimates e =
        estimate_control_variate(sums_of(s), 0.95, stickslip::ControlVariateCoefficients{0.7, 1.3});
    EXPECT_EQ(e.beta, 0.7);
    EXPECT_EQ(e.beta_mobility, 1.3);
    expect_matches(e, Reference(s, fixed), 1e-13);
    // The fit of a pilot's sums is what the estimate fitted on them uses, and
    // given back, it gives that estimate bit for bit.
    const stickslip::ControlVariateCoefficients fit = stickslip::fit_control_variate(sums_of(s));
    const ControlVariateEstimates fitted = estimate_control_variate(sums_of(s), 0.95);
    EXPECT_EQ(fit.beta, fitted.beta);
    EXPECT_EQ(fit.beta_mobility, fitted.beta_mobility);
    const ControlVariateEstimates again = estimate_control_variate(sums_of(s), 0.95, fit);
    EXPECT_EQ(again.diffusivity.value, fitted.diffusivity.value);
    EXPECT_EQ(again.mobility.value, fitted.mobility.value);
}

TEST(ControlVariateEstimator, StronglyDrivenCaseKeepsItsDigits) {
    // |mean U| / sd(U - M0 t) about 1e3: the order-4 raw sums cancel about 12 digits.
    std::mt19937_64 gen(11);
    std::exponential_distribution<double> duration(1.0);
    std::normal_distribution<double> normal(0.0, 1.0);
    Samples s;
    for (int k = 0; k < 20000; ++k) {
        const double t = 1.0 + 0.1 * duration(gen);
        const double m = std::sqrt(t) * normal(gen);
        s.push(1e3 * t + m + 0.3 * std::sqrt(t) * normal(gen), t, m, m * m - t);
    }
    const ControlVariateEstimates e = estimate_control_variate(sums_of(s), 0.95);
    expect_matches(e, Reference(s), 1e-12);
}

TEST(ControlVariateEstimator, UninformativeControlsChangeNothing) {
    // M and C independent of (U, t), mean zero: beta and beta' are sampling noise,
    // N (1 - 1/reduction) = N rho^2 is about chi-square(1).
    std::mt19937_64 gen(21);
    std::exponential_distribution<double> duration(1.0);
    std::normal_distribution<double> normal(0.0, 1.0);
    Samples s;
    const std::size_t n = 20000;
    for (std::size_t k = 0; k < n; ++k) {
        const double t = 0.2 + duration(gen);
        const double u = 0.5 * t + t * normal(gen); // heavy-ish: sd grows with t
        const double m = normal(gen);
        s.push(u, t, m, m * m - 1.0);
    }
    const ControlVariateEstimates e = estimate_control_variate(sums_of(s), 0.95);
    const auto plain = plain_of(s);
    const double nd = static_cast<double>(n);
    EXPECT_LT(nd * (1.0 - 1.0 / e.variance_reduction), 16.0) << "reduction " << e.variance_reduction;
    EXPECT_LT(nd * (1.0 - 1.0 / e.variance_reduction_mobility), 16.0)
        << "reduction " << e.variance_reduction_mobility;
    // Nor does it add variance, but for O(1/N): psi is phi less beta (C - E[C] t / E[t]),
    // not the least-squares residual of phi on C.
    EXPECT_GT(e.variance_reduction, 1.0 - 10.0 / nd);
    EXPECT_GT(e.variance_reduction_mobility, 1.0 - 10.0 / nd);
    EXPECT_LT(std::fabs(e.diffusivity.value - plain.diffusivity.value), 0.5 * e.diffusivity.error)
        << "z = " << (e.diffusivity.value - plain.diffusivity.value) / e.diffusivity.error;
    EXPECT_LT(std::fabs(e.mobility.value - plain.mobility.value), 0.5 * e.mobility.error)
        << "z = " << (e.mobility.value - plain.mobility.value) / e.mobility.error;
    EXPECT_LT(std::fabs(e.diffusivity.error / plain.diffusivity.error - 1.0), 1e-3);
}

TEST(ControlVariateEstimator, MartingaleRemovesMostOfTheVarianceWithoutBias) {
    const double m0 = 2.0, noise = 0.05;
    const double d_true = 13.0 / 12.0 + noise * noise;
    const Samples s = martingale_case(20000, m0, noise, 31);
    const ControlVariateEstimates e = estimate_control_variate(sums_of(s), 0.95);
    EXPECT_GT(e.variance_reduction, 20.0);
    EXPECT_GT(e.variance_reduction_mobility, 20.0);
    const double z_d = (e.diffusivity.value - d_true) / e.diffusivity.error;
    const double z_m = (e.mobility.value - m0) / e.mobility.error;
    EXPECT_LT(std::fabs(z_d), 3.0) << "D_cv " << e.diffusivity.value << " +- " << e.diffusivity.error
                                   << " against " << d_true << ": z = " << z_d;
    EXPECT_LT(std::fabs(z_m), 3.0) << "M0_cv " << e.mobility.value << " +- " << e.mobility.error
                                   << " against " << m0 << ": z = " << z_m;
    // The optimal coefficients are 1 here (U - M0 t - M is independent noise).
    EXPECT_NEAR(e.beta, 1.0, 0.05);
    EXPECT_NEAR(e.beta_mobility, 1.0, 0.05);
    EXPECT_GT(e.diffusivity.lo, 0.0);
    EXPECT_LT(e.diffusivity.lo, e.diffusivity.value);
    EXPECT_GT(e.diffusivity.hi, e.diffusivity.value);
}

TEST(ControlVariateEstimator, PlainPartsAreThoseOfTheLongExcursionEstimator) {
    const Samples s = martingale_case(5000, 1.5, 0.2, 41);
    const ControlVariateEstimates e = estimate_control_variate(sums_of(s), 0.9);
    const auto plain = plain_of(s, 0.9);
    // The plain variance E[phi^2] is reduction * E[psi^2]: the plain se is se_cv sqrt(reduction).
    EXPECT_NEAR(e.diffusivity.error * std::sqrt(e.variance_reduction), plain.diffusivity.error,
                1e-12 * plain.diffusivity.error);
    EXPECT_NEAR(e.mobility.error * std::sqrt(e.variance_reduction_mobility), plain.mobility.error,
                1e-12 * plain.mobility.error);

    // With no corrector signal (M = C = 0) the estimates are the plain ones.
    Samples bare = s;
    std::fill(bare.m.begin(), bare.m.end(), 0.0);
    std::fill(bare.c.begin(), bare.c.end(), 0.0);
    const ControlVariateEstimates b = estimate_control_variate(sums_of(bare), 0.9);
    EXPECT_EQ(b.beta, 0.0);
    EXPECT_EQ(b.beta_mobility, 0.0);
    EXPECT_EQ(b.variance_reduction, 1.0);
    EXPECT_EQ(b.variance_reduction_mobility, 1.0);
    EXPECT_NEAR(b.diffusivity.value, plain.diffusivity.value, 1e-14 * plain.diffusivity.value);
    EXPECT_NEAR(b.diffusivity.error, plain.diffusivity.error, 1e-12 * plain.diffusivity.error);
    EXPECT_NEAR(b.diffusivity.lo, plain.diffusivity.lo, 1e-12 * plain.diffusivity.lo);
    EXPECT_NEAR(b.diffusivity.hi, plain.diffusivity.hi, 1e-12 * plain.diffusivity.hi);
    EXPECT_NEAR(b.mobility.value, plain.mobility.value, 1e-14 * std::fabs(plain.mobility.value));
    EXPECT_NEAR(b.mobility.error, plain.mobility.error, 1e-12 * plain.mobility.error);
}

/// The estimate's doubles, bit for bit.
std::vector<unsigned char> bits(const ControlVariateEstimates& e) {
    const double v[] = {e.diffusivity.value, e.diffusivity.error, e.diffusivity.lo,     e.diffusivity.hi,
                        e.mobility.value,    e.mobility.error,    e.mobility.lo,        e.mobility.hi,
                        e.beta,              e.beta_mobility,         e.variance_reduction, e.variance_reduction_mobility};
    std::vector<unsigned char> out(sizeof v);
    std::memcpy(out.data(), v, sizeof v);
    return out;
}

std::vector<std::uint64_t> words_of(const ControlVariateSums& s) {
    std::vector<std::uint64_t> w(s.words());
    s.to_words(w.data());
    return w;
}

TEST(ControlVariateSums, MergeOrderAndSerialisationLeaveNoTrace) {
    const Samples s = martingale_case(6400 + 37, 3.0, 0.1, 51); // a last, partial block
    const auto centres = influence_centres(sums_of(s), fit_control_variate(sums_of(s)));
    ASSERT_TRUE(centres.has_value());
    auto blocks = blocks_of(s, &*centres);
    ControlVariateSums forward;
    for (const auto& b : blocks) forward.add_block(b);
    EXPECT_EQ(forward.count(), s.size());
    EXPECT_EQ(forward.words(), std::size_t{ControlVariateBlock::monomials} * ExactSum::words +
                                   2 * InfluenceTailSums::words); // the monomials, then the two shapes' sums

    std::mt19937 gen(52);
    std::shuffle(blocks.begin(), blocks.end(), gen);
    ControlVariateSums shuffled;
    for (const auto& b : blocks) shuffled.add_block(b);

    // A tree: three threads' totals, merged pairwise in another order.
    ControlVariateSums part[3];
    for (std::size_t k = 0; k < blocks.size(); ++k) part[k % 3].add_block(blocks[k]);
    ControlVariateSums tree = part[2];
    ControlVariateSums left = part[1];
    left.merge(part[0]);
    tree.merge(left);

    // An MPI reduction on words (ExactSum::merge_words, sum by sum) and a checkpoint's round trip.
    std::vector<std::uint64_t> reduced = words_of(part[0]);
    for (int p = 1; p < 3; ++p) {
        const std::vector<std::uint64_t> w = words_of(part[p]);
        for (std::size_t k = 0; k < w.size() / ExactSum::words; ++k) // every ExactSum, the shapes' too
            ExactSum::merge_words(w.data() + k * ExactSum::words, reduced.data() + k * ExactSum::words);
    }
    ControlVariateSums restored;
    restored.assign_words(reduced.data());

    const auto w0 = words_of(forward);
    EXPECT_EQ(w0, words_of(shuffled));
    EXPECT_EQ(w0, words_of(tree));
    EXPECT_EQ(w0, reduced);
    EXPECT_EQ(w0, words_of(restored));
    const auto e0 = bits(estimate_control_variate(forward, 0.95));
    EXPECT_EQ(e0, bits(estimate_control_variate(shuffled, 0.95)));
    EXPECT_EQ(e0, bits(estimate_control_variate(tree, 0.95)));
    EXPECT_EQ(e0, bits(estimate_control_variate(restored, 0.95)));
    EXPECT_EQ(forward.tail().count(), s.size());
    EXPECT_EQ(restored.tail().shape().tail_index, forward.tail().shape().tail_index);
    EXPECT_EQ(restored.plain_tail().shape().excess_kurtosis, forward.plain_tail().shape().excess_kurtosis);
}

TEST(ControlVariateEstimator, RefusesTooFewSamplesAndBadLevels) {
    Samples s;
    s.push(1.0, 1.0, 0.5, 0.1);
    EXPECT_THROW(estimate_control_variate(sums_of(s), 0.95), stickslip::InvalidParameter);
    EXPECT_THROW(estimate_control_variate(ControlVariateSums{}, 0.95), stickslip::InvalidParameter);
    s.push(2.0, 1.5, -0.5, 0.2);
    EXPECT_NO_THROW(estimate_control_variate(sums_of(s), 0.95));
    EXPECT_THROW(estimate_control_variate(sums_of(s), 1.0), stickslip::InvalidParameter);
    EXPECT_THROW(estimate_control_variate(sums_of(s), 0.0), stickslip::InvalidParameter);
}

} // namespace
