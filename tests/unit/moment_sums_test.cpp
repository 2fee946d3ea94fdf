// SPDX-License-Identifier: BSD-3-Clause
// Exact moment sums (moment_sums.hpp) against a 50-digit recomputation from
// the samples themselves: nothing is lost to the final centring even when the
// sample is nearly ballistic (U ~ M0 t, |mean| >> sd), and the order in which
// blocks are merged leaves no trace.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "stickslip/stats/moment_sums.hpp"

namespace {

using stickslip::BivariateMoments;
using stickslip::ExactBivariateSums;
using stickslip::ExactRatioSums;
using stickslip::RatioMoments;
using big = boost::multiprecision::cpp_bin_float_50;

struct Sample {
    std::vector<double> x, y;
};

/// Displacement-like x = drift * y + noise and duration-like y > 0: |mean x|
/// / sd(x) grows with `drift` / `noise`.
Sample driven(std::size_t n, double drift, double noise, unsigned seed) {
    std::mt19937_64 gen(seed);
    std::exponential_distribution<double> duration(1.0);
    std::normal_distribution<double> normal(0.0, 1.0);
    Sample s;
    for (std::size_t k = 0; k < n; ++k) {
        const double t = 1.0 + duration(gen);
        s.y.push_back(t);
        s.x.push_back(drift * t + noise * std::sqrt(t) * normal(gen));
    }
    return s;
}

/// The centred sums sum (x - mean x)^p (y - mean y)^q in 50 digits, from the samples.
class Reference {
public:
    explicit Reference(const Sample& s) {
        big mx = 0, my = 0;
        for (std::size_t k = 0; k < s.x.size(); ++k) {
            mx += s.x[k];
            my += s.y[k];
        }
        mx /= s.x.size();
        my /= s.y.size();
        for (std::size_t k = 0; k < s.x.size(); ++k) {
            dx_.push_back(big(s.x[k]) - mx);
            dy_.push_back(big(s.y[k]) - my);
        }
    }
    big operator()(int p, int q) const {
        big sum = 0;
        for (std::size_t k = 0; k < dx_.size(); ++k) {
            big term = 1;
            for (int i = 0; i < p; ++i) term *= dx_[k];
            for (int i = 0; i < q; ++i) term *= dy_[k];
            sum += term;
        }
        return sum;
    }

private:
    std::vector<big> dx_, dy_;
};

big reference(const Sample& s, int p, int q) { return Reference(s)(p, q); }

/// Blocks of 64 in index order, as the block driver makes them.
std::vector<BivariateMoments> blocks_of(const Sample& s) {
    std::vector<BivariateMoments> out;
    for (std::size_t k = 0; k < s.x.size(); ++k) {
        if (k % 64 == 0) out.emplace_back();
        out.back().add(s.x[k], s.y[k]);
    }
    return out;
}

/// Relative error of every centred sum against the reference, the worst.
double worst_error(const Sample& s, const BivariateMoments& m, int max_order) {
    const Reference reference(s);
    double worst = 0;
    for (int p = 0; p <= max_order; ++p)
        for (int q = 0; p + q <= max_order; ++q) {
            if (p + q < 2) continue;
            const big ref = reference(p, q);
            // An odd mixed sum can be near zero: measure it against the product of the scales.
            const big scale = sqrt(reference(2 * p, 0) * reference(0, 2 * q));
            const double err = static_cast<double>(abs(big(m.central_sum(p, q)) - ref) / std::max(abs(ref), scale));
            worst = std::max(worst, err);
        }
    return worst;
}

TEST(ExactBivariateSums, NearlyBallisticSampleKeepsEveryDigit) {
    // |mean x| / sd(x) about 1e3 (drift 1e4 per unit time, noise 10), 20000 samples.
    const Sample s = driven(20000, 1e4, 10.0, 1);
    ExactBivariateSums sums;
    for (const auto& b : blocks_of(s)) sums.add_block(b);
    const BivariateMoments m = sums.moments();
    EXPECT_EQ(m.count(), 20000u);
    const double err = worst_error(s, m, 4);
    EXPECT_LT(err, 1e-13) << "worst relative error of a centred sum of order <= 4";
    // The same data merged with Chan's floating-point update, for comparison:
    // it is accurate too, but depends on the order of the merges.
    BivariateMoments chained;
    for (const auto& b : blocks_of(s)) chained.merge(b);
    EXPECT_LT(worst_error(s, chained, 4), 1e-9);
}

TEST(ExactBivariateSums, StronglyDrivenSecondMoments) {
    // |mean x| / sd(x) about 1e6: the second-order sums (D, M0) still to 1e-12.
    const Sample s = driven(5000, 1e6, 1.0, 2);
    ExactBivariateSums sums;
    for (const auto& b : blocks_of(s)) sums.add_block(b);
    EXPECT_LT(worst_error(s, sums.moments(), 2), 1e-12);
}

TEST(ExactBivariateSums, MergeOrderLeavesNoTrace) {
    const Sample s = driven(6400, 3.0, 1.0, 3);
    auto blocks = blocks_of(s);
    ExactBivariateSums forward, shuffled, tree_a, tree_b;
    for (const auto& b : blocks) forward.add_block(b);
    std::mt19937 gen(4);
    std::shuffle(blocks.begin(), blocks.end(), gen);
    for (std::size_t k = 0; k < blocks.size(); ++k) (k % 2 ? tree_a : tree_b).add_block(blocks[k]);
    for (const auto& b : blocks) shuffled.add_block(b);
    tree_b.merge(tree_a);
    std::vector<std::uint64_t> w1(ExactBivariateSums::words), w2(ExactBivariateSums::words),
        w3(ExactBivariateSums::words);
    forward.to_words(w1.data());
    shuffled.to_words(w2.data());
    tree_b.to_words(w3.data());
    EXPECT_EQ(w1, w2);
    EXPECT_EQ(w1, w3);
    // And the words are the whole state.
    const ExactBivariateSums back = ExactBivariateSums::from_words(w1.data());
    const BivariateMoments a = forward.moments(), b = back.moments();
    for (int p = 0; p <= 4; ++p)
        for (int q = 0; p + q <= 4; ++q) EXPECT_EQ(a.central_sum(p, q), b.central_sum(p, q));
}

TEST(ExactRatioSums, MergeOrderLeavesNoTraceAndMatchesTheReference) {
    // Two ratios y_0 = U, y_1 = U^2 over t; covariances with column 0 kept.
    const Sample s = driven(3200, 2.0, 1.0, 5);
    std::vector<RatioMoments> blocks;
    for (std::size_t k = 0; k < s.x.size(); ++k) {
        if (k % 64 == 0) blocks.emplace_back(2, std::vector<std::size_t>{0});
        const double y[2] = {s.x[k], s.x[k] * s.x[k]};
        blocks.back().add(y, s.y[k]);
    }
    ExactRatioSums forward(2, {0}), backward(2, {0});
    for (const auto& b : blocks) forward.add_block(b);
    for (auto it = blocks.rbegin(); it != blocks.rend(); ++it) backward.add_block(*it);
    std::vector<std::uint64_t> w1(forward.words()), w2(backward.words());
    forward.to_words(w1.data());
    backward.to_words(w2.data());
    EXPECT_EQ(w1, w2);
    const RatioMoments m = forward.moments();
    big sx = 0, st = 0;
    for (std::size_t k = 0; k < s.x.size(); ++k) {
        sx += s.x[k];
        st += s.y[k];
    }
    EXPECT_NEAR(m.ratio(0), static_cast<double>(sx / st), 1e-15 * std::fabs(m.ratio(0)));
    EXPECT_NEAR(m.central_tt(), static_cast<double>(reference(s, 0, 2)), 1e-13 * m.central_tt());
    ExactRatioSums restored(2, {0});
    restored.assign_words(w1.data());
    EXPECT_EQ(restored.moments().ratio(1), m.ratio(1));
}

} // namespace
