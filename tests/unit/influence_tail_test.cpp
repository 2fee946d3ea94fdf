// SPDX-License-Identifier: BSD-3-Clause
// The shape of an influence function from mergeable sums (influence_tail.hpp):
// known answers for the tail index (the quantiles of a Pareto law) and the
// moments (a long-double reference), and the same words for any split of the
// terms into blocks and any merge order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "stickslip/stats/influence_tail.hpp"

namespace ss = stickslip;

namespace {

/// Sums of xs split into blocks of `block` terms (the last shorter), merged
/// from the last block to the first, or (stride > 1) first every stride-th
/// block from each offset, then those groups: another reduction tree.
ss::InfluenceTailSums sums_in_blocks(const std::vector<double>& xs, std::size_t block, std::size_t stride = 1) {
    std::vector<ss::InfluenceTailSums> parts;
    for (std::size_t i = 0; i < xs.size(); i += block) {
        ss::InfluenceTailBlock b;
        for (std::size_t j = i; j < xs.size() && j < i + block; ++j) b.add(xs[j]);
        ss::InfluenceTailSums s;
        s.add_block(b);
        parts.push_back(s);
    }
    ss::InfluenceTailSums total;
    if (stride == 1)
        for (auto it = parts.rbegin(); it != parts.rend(); ++it) total.merge(*it);
    else
        for (std::size_t offset = 0; offset < stride; ++offset) {
            ss::InfluenceTailSums group;
            for (std::size_t k = offset; k < parts.size(); k += stride) group.merge(parts[k]);
            total.merge(group);
        }
    return total;
}

std::vector<std::uint64_t> words(const ss::InfluenceTailSums& s) {
    std::vector<std::uint64_t> w(ss::InfluenceTailSums::words);
    s.to_words(w.data());
    return w;
}

/// The n quantiles (i + 1/2)/n of |x| for a Pareto law P(|x| > y) = y^-alpha,
/// y >= 1, with alternating signs.
std::vector<double> pareto_quantiles(std::size_t n, double alpha) {
    std::vector<double> xs(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double u = (static_cast<double>(i) + 0.5) / static_cast<double>(n);
        xs[i] = (i % 2 ? -1.0 : 1.0) * std::pow(u, -1.0 / alpha);
    }
    return xs;
}

} // namespace

TEST(InfluenceTail, HillsBinnedEstimateRecoversAParetoIndex) {
    for (const double alpha : {1.5, 2.5, 3.5}) {
        const ss::InfluenceShape shape = sums_in_blocks(pareto_quantiles(1 << 16, alpha), 64).shape();
        ASSERT_EQ(shape.samples, 1u << 16);
        EXPECT_GE(shape.tail_terms, 256u) << "k = sqrt(N) at least";
        // The quantiles are the law without sampling noise: what is left is the
        // binning of the top bin edge (measured: within 3%).
        EXPECT_NEAR(shape.tail_index, alpha, 0.03 * alpha) << "alpha " << alpha;
    }
}

TEST(InfluenceTail, SkewnessAndKurtosisAgreeWithALongDoubleReference) {
    std::vector<double> xs;
    for (int i = 0; i < 1000; ++i) xs.push_back(std::exp(0.003 * i) - 2.0 + 0.25 * std::sin(i)); // skewed
    long double m = 0;
    for (double x : xs) m += x;
    m /= xs.size();
    long double c2 = 0, c3 = 0, c4 = 0;
    for (double x : xs) {
        const long double d = x - m;
        c2 += d * d;
        c3 += d * d * d;
        c4 += d * d * d * d;
    }
    c2 /= xs.size();
    c3 /= xs.size();
    c4 /= xs.size();
    const ss::InfluenceShape shape = sums_in_blocks(xs, 64).shape();
    EXPECT_NEAR(shape.skewness, static_cast<double>(c3 / std::pow(c2, 1.5L)), 1e-12);
    EXPECT_NEAR(shape.excess_kurtosis, static_cast<double>(c4 / (c2 * c2) - 3), 1e-12);
}

TEST(InfluenceTail, AnyMergeOrderOfTheBlocksGivesTheSameWords) {
    // The blocks are fixed (a run's 64 samples in index order, summed in
    // double-double); their merge is exact in any order or tree.
    const std::vector<double> xs = pareto_quantiles(5000, 2.2);
    const std::vector<std::uint64_t> reference = words(sums_in_blocks(xs, 64));
    for (std::size_t stride : {2u, 3u, 16u}) EXPECT_EQ(words(sums_in_blocks(xs, 64, stride)), reference) << stride;
    ss::InfluenceTailSums back;
    back.assign_words(reference.data());
    EXPECT_EQ(words(back), reference);
    EXPECT_EQ(back.count(), 5000u);
}

TEST(InfluenceTail, TooFewTermsGiveNoShape) {
    EXPECT_EQ(sums_in_blocks({1.0, 2.0, 3.0}, 64).shape().samples, 0u);
    const ss::InfluenceShape flat = sums_in_blocks(std::vector<double>(100, 1e-3), 64).shape();
    EXPECT_EQ(flat.samples, 0u) << "no variance";
}
