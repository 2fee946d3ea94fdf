// SPDX-License-Identifier: BSD-3-Clause
// The event scheme's SIMD lanes (event_lanes.hpp) against its one-excursion
// kernel: every outcome must be bitwise the same -- with refinements, stuck
// and sliding lanes, relaxation finite and infinite, steps near tau and far
// below it, capped excursions, partial lane groups, large indices -- and the
// cancel flag must stop it. On machines without AVX-512 the public function
// runs one excursion at a time, so the lanes are also run forced
// (detail::event_long_excursions_in_lanes) on every machine.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "stickslip/kernels/event_lanes.hpp"
#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "arbitrary_corrector.hpp"

namespace ss = stickslip;

namespace {

constexpr std::uint64_t kSeed = 8675309;

ss::ModelParams dry_params(double tau) {
    ss::ModelParams p;
    p.friction = 1.0;
    p.noise = 1.0;
    p.tau = tau;
    p.relaxation = std::numeric_limits<double>::infinity();
    p.bias = 0.0;
    return p;
}

ss::EventConstants constants(const ss::ModelParams& p, double dt, std::uint64_t max_work = 200'000'000) {
    ss::EngineSettings s = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    s.scheme = ss::Scheme::Event;
    s.dt = dt;
    s.max_work_per_excursion = max_work;
    return ss::make_event_constants(p, s);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same(const ss::ExcursionOutcome& a, const ss::ExcursionOutcome& b) {
    return same_bits(a.displacement, b.displacement) && same_bits(a.duration, b.duration) &&
           same_bits(a.first_half, b.first_half) && a.work == b.work && a.capped == b.capped;
}

// Runs `count` excursions from `first` by the public entry point, by the lanes
// forced on, and one at a time with CounterRng; counts the differences.
int mismatches(const ss::EventConstants& c, std::uint64_t first, std::uint64_t count, int* capped = nullptr) {
    std::vector<ss::ExcursionOutcome> lanes(count), forced(count);
    EXPECT_TRUE(ss::event_long_excursions(c, kSeed, first, count, lanes.data()));
    EXPECT_TRUE(ss::detail::event_long_excursions_in_lanes(c, kSeed, first, count, forced.data()));
    int bad = 0;
    for (std::uint64_t i = 0; i < count; ++i) {
        ss::CounterRng rng(kSeed, ss::StreamPurpose::LongExcursion, first + i);
        ss::CounterRng ref(kSeed, ss::StreamPurpose::Refinement, first + i);
        const ss::ExcursionOutcome o = ss::event_long_excursion(c, rng, ref);
        for (const auto* l : {&lanes[i], &forced[i]}) {
            const bool ok = same(o, *l);
            if (!ok && bad < 3)
                ADD_FAILURE() << "excursion " << first + i << ": one-at-a-time U = " << o.displacement << ", work "
                              << o.work << ", first half " << o.first_half << ", capped " << o.capped
                              << "; lanes U = " << l->displacement << ", work " << l->work << ", first half "
                              << l->first_half << ", capped " << l->capped;
            bad += ok ? 0 : 1;
        }
        if (capped) *capped += o.capped ? 1 : 0;
    }
    return bad;
}

// The control variate's kernel: the default entry point and the forced lanes
// against event_long_excursion_with one at a time, M and Q included.
int mismatches_with(const ss::EventConstants& c, std::uint64_t first, std::uint64_t count) {
    const ss::test::ArbitraryCorrector corrector;
    const ss::CorrectorTable g = corrector.table();
    std::vector<ss::ExcursionOutcome> lanes(count), forced(count);
    EXPECT_TRUE(ss::event_long_excursions_with(c, kSeed, first, count, lanes.data(), nullptr, g));
    EXPECT_TRUE(ss::detail::event_long_excursions_in_lanes_with(c, kSeed, first, count, forced.data(), nullptr, g));
    int bad = 0, nonzero = 0;
    for (std::uint64_t i = 0; i < count; ++i) {
        ss::CounterRng rng(kSeed, ss::StreamPurpose::LongExcursion, first + i);
        ss::CounterRng ref(kSeed, ss::StreamPurpose::Refinement, first + i);
        const ss::ExcursionOutcome o = ss::event_long_excursion_with(c, rng, ref, g);
        for (const auto* l : {&lanes[i], &forced[i]}) {
            const bool ok = same(o, *l) && same_bits(o.martingale, l->martingale) &&
                            same_bits(o.martingale_qv, l->martingale_qv);
            if (!ok && bad < 3)
                ADD_FAILURE() << "excursion " << first + i << ": one at a time U = " << o.displacement << ", M = "
                              << o.martingale << ", Q = " << o.martingale_qv << "; lanes U = " << l->displacement
                              << ", M = " << l->martingale << ", Q = " << l->martingale_qv;
            bad += ok ? 0 : 1;
        }
        nonzero += o.martingale_qv != 0.0 ? 1 : 0;
    }
    EXPECT_EQ(nonzero, static_cast<int>(count)) << "every excursion accumulates a Q";
    return bad;
}

} // namespace

TEST(EventLanes, BitwiseEqualToOneAtATimeOnTheFig2Case) {
    EXPECT_EQ(mismatches(constants(ss::ModelParams{}, 1e-3), 0, 100), 0);
    EXPECT_EQ(mismatches(constants(ss::ModelParams{}, 1e-2), 0, 100), 0);
}

TEST(EventLanes, BitwiseEqualWithoutDragAtStepsNearTauAndLargeIndices) {
    const std::uint64_t first = (std::uint64_t{1} << 40) + 3;
    EXPECT_EQ(mismatches(constants(dry_params(0.1), 1e-2), first, 77), 0);
    EXPECT_EQ(mismatches(constants(dry_params(0.1), 5e-2), first, 77), 0);
    EXPECT_EQ(mismatches(constants(dry_params(1.0), 1e-2), 11, 40), 0);
}

TEST(EventLanes, BitwiseEqualWithBiasAndDrag) {
    ss::ModelParams p = dry_params(0.5);
    p.relaxation = 0.5; // relaxation = tau
    p.bias = 0.3;
    EXPECT_EQ(mismatches(constants(p, 2e-2), 0, 64), 0);
}

TEST(EventLanes, WhiteNoiseRunsTheOneExcursionKernel) {
    EXPECT_EQ(mismatches(constants(dry_params(0.0), 1e-2), 5, 40), 0);
}

TEST(EventLanes, PartialGroupsAndEmptyRuns) {
    const auto c = constants(ss::ModelParams{}, 1e-2);
    for (std::uint64_t n : {0u, 1u, 7u, 8u, 9u, 17u}) EXPECT_EQ(mismatches(c, 1000, n), 0) << n << " excursions";
}

TEST(EventLanes, CappedExcursionsMatchToo) {
    // A cap below the median work: many excursions end capped, some in their first half.
    int capped = 0;
    EXPECT_EQ(mismatches(constants(ss::ModelParams{}, 1e-3, 4000), 0, 64, &capped), 0);
    EXPECT_GT(capped, 10);
    EXPECT_LT(capped, 64);
}

TEST(EventLanes, MartingaleSumsBitwiseEqualToOneAtATime) {
    EXPECT_EQ(mismatches_with(constants(ss::ModelParams{}, 1e-3), 0, 33), 0);
    EXPECT_EQ(mismatches_with(constants(dry_params(0.1), 5e-2), (std::uint64_t{1} << 40) + 3, 30), 0);
    EXPECT_EQ(mismatches_with(constants(dry_params(1.0), 1e-2), 11, 20), 0);
    EXPECT_EQ(mismatches_with(constants(ss::ModelParams{}, 1e-3, 4000), 0, 17), 0); // capped
}

TEST(EventLanes, CancelStopsStartingExcursions) {
    const auto c = constants(ss::ModelParams{}, 1e-2);
    std::atomic<bool> cancel{true};
    std::vector<ss::ExcursionOutcome> out(64);
    EXPECT_FALSE(ss::event_long_excursions(c, kSeed, 0, out.size(), out.data(), &cancel));
    EXPECT_FALSE(ss::detail::event_long_excursions_in_lanes(c, kSeed, 0, out.size(), out.data(), &cancel));
    cancel = false;
    EXPECT_TRUE(ss::event_long_excursions(c, kSeed, 0, 3, out.data(), &cancel));
    EXPECT_TRUE(ss::detail::event_long_excursions_in_lanes(c, kSeed, 0, 3, out.data(), &cancel));
    cancel = true; // nothing left to start: complete
    EXPECT_TRUE(ss::detail::event_long_excursions_in_lanes(c, kSeed, 0, 0, nullptr, &cancel));
}

TEST(EventLanes, SideDrawsInBatchesAreTheScalarOnes) {
    // Across the carry of the draw counter's low word, where the side block's
    // counter word 1 takes the high bits.
    const auto key = ss::CounterRng::make_key(kSeed);
    const auto ctr = ss::CounterRng::make_counter(ss::StreamPurpose::LongExcursion, 12345, 0);
    int bad = 0;
    for (std::uint64_t j0 : {std::uint64_t{0}, std::uint64_t{96}, (std::uint64_t{1} << 32) - 7}) {
        double side[2][ss::detail::rng_batch_size];
        ss::detail::fill_side_draws(key, ctr.v[2], ctr.v[3], j0, side);
        for (int i = 0; i < ss::detail::rng_batch_size; ++i) {
            const ss::NormalPair want = ss::CounterRng::side_draw_of(key, ctr.v[2], ctr.v[3], j0 + i);
            bad += same_bits(side[0][i], want.x) && same_bits(side[1][i], want.y) ? 0 : 1;
        }
    }
    EXPECT_EQ(bad, 0);
}
