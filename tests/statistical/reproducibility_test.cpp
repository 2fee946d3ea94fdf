// SPDX-License-Identifier: BSD-3-Clause
// Results are bitwise identical for any thread count (one Philox stream per
// excursion, blocks merged in index order), and change with the seed.
#include <gtest/gtest.h>

#include <cstring>

#include "stickslip/sample_runs.hpp"
#include "support.hpp"

namespace {

using namespace sstest;

bool same_bits(const ss::BivariateMoments& a, const ss::BivariateMoments& b) {
    if (a.count() != b.count()) return false;
    auto eq = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
    if (!eq(a.mean_x(), b.mean_x()) || !eq(a.mean_y(), b.mean_y())) return false;
    for (int p = 0; p <= 4; ++p)
        for (int q = 0; p + q <= 4; ++q)
            if (!eq(a.central_sum(p, q), b.central_sum(p, q))) return false;
    return true;
}

ss::RunTotals le(const ss::EngineSettings& e, unsigned threads, std::uint64_t seed, std::uint64_t n) {
    ss::RunControl c;
    c.threads = threads;
    c.seed = seed;
    return ss::run_long_excursions(ss::ModelParams{}, e, n, c);
}

TEST(Reproducibility, PdmpIdenticalForAnyThreadCount) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.engine = ss::Engine::Pdmp;
    const auto t1 = le(e, 1, 5, 1000), t2 = le(e, 2, 5, 1000), t3 = le(e, 3, 5, 1000), t7 = le(e, 7, 5, 1000);
    EXPECT_TRUE(same_bits(t1.moments, t2.moments));
    EXPECT_TRUE(same_bits(t1.moments, t3.moments));
    EXPECT_TRUE(same_bits(t1.moments, t7.moments));
    EXPECT_EQ(t1.work, t7.work);
}

TEST(Reproducibility, InclusionIdenticalForAnyThreadCount) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.dt = 2e-3;
    const auto t1 = le(e, 1, 9, 300), t2 = le(e, 2, 9, 300), t5 = le(e, 5, 9, 300);
    EXPECT_TRUE(same_bits(t1.moments, t2.moments));
    EXPECT_TRUE(same_bits(t1.moments, t5.moments));
}

TEST(Reproducibility, WhiteNoiseAndBruteForceIdenticalForAnyThreadCount) {
    const ss::ModelParams p{.tau = 0};
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.dt = 1e-3;
    ss::RunControl c1, c2;
    c1.threads = 1;
    c2.threads = 2;
    EXPECT_TRUE(same_bits(ss::run_long_excursions(p, e, 2000, c1).moments,
                          ss::run_long_excursions(p, e, 2000, c2).moments));
    EXPECT_TRUE(same_bits(ss::run_bruteforce(ss::ModelParams{}, e, 0.5, 0.0, 0.0, 500, c1).moments,
                          ss::run_bruteforce(ss::ModelParams{}, e, 0.5, 0.0, 0.0, 500, c2).moments));
}

TEST(Reproducibility, SeedChangesResult) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.engine = ss::Engine::Pdmp;
    EXPECT_FALSE(same_bits(le(e, 2, 1, 500).moments, le(e, 2, 2, 500).moments));
}

TEST(Reproducibility, SampleIndexIsTheStream) {
    // Excursion k depends only on (seed, k), and runs merge exactly: runs
    // over [0, 64) and [64, 128), their sums added in either order, reproduce
    // the run over [0, 128) bit for bit (the basis of splitting a run across
    // processes, and of resuming it).
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.engine = ss::Engine::Pdmp;
    ss::RunControl c;
    c.seed = 3;
    c.threads = 1;
    const auto whole = le(e, 1, 3, 128);
    c.first_index = 64;
    const auto second = ss::run_long_excursions(ss::ModelParams{}, e, 64, c);
    c.first_index = 0;
    const auto first = ss::run_long_excursions(ss::ModelParams{}, e, 64, c);
    ss::ExactBivariateSums a = first.sums, b = second.sums;
    a.merge(second.sums);
    b.merge(first.sums);
    EXPECT_TRUE(same_bits(a.moments(), whole.moments));
    EXPECT_TRUE(same_bits(b.moments(), whole.moments));
}

} // namespace
