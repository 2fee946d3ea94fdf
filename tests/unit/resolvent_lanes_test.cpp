// SPDX-License-Identifier: BSD-3-Clause
// The interleaved inclusion kernel (resolvent_lanes.hpp) against the
// one-excursion kernel: every outcome must be bitwise the same, for both stop
// rules, white noise, capped excursions, partial lane groups and any first
// index; and the cancel flag must stop it. On machines without AVX-512 the
// public function runs the one-excursion kernel itself, so the lanes are also
// run forced (detail::resolvent_long_excursions_in_lanes) on every machine.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "stickslip/kernels/resolvent.hpp"
#include "stickslip/kernels/resolvent_lanes.hpp"
#include "stickslip/random/rng.hpp"
#include "arbitrary_corrector.hpp"

namespace ss = stickslip;

namespace {

constexpr std::uint64_t kSeed = 424242;

ss::ModelParams dry_params() {
    ss::ModelParams p;
    p.friction = 1.0;
    p.noise = 1.0;
    p.tau = 0.5;
    p.relaxation = std::numeric_limits<double>::infinity();
    p.bias = 0.0;
    return p;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Runs `count` excursions from `first` by the public entry point, by the lanes
// forced on (so that the lane code is checked on machines without AVX-512,
// where it is not the default), and one at a time; counts the differences.
int mismatches(const ss::ResolventConstants& c, std::uint64_t first, std::uint64_t count, int* capped = nullptr) {
    std::vector<ss::ExcursionOutcome> lanes(count), forced(count);
    EXPECT_TRUE(ss::resolvent_long_excursions(c, kSeed, first, count, lanes.data()));
    EXPECT_TRUE(ss::detail::resolvent_long_excursions_in_lanes(c, kSeed, first, count, forced.data()));
    int bad = 0;
    for (std::uint64_t i = 0; i < count; ++i) {
        const bool same = same_bits(lanes[i].displacement, forced[i].displacement) &&
                          same_bits(lanes[i].duration, forced[i].duration) && lanes[i].work == forced[i].work;
        if (!same && bad < 3)
            ADD_FAILURE() << "excursion " << first + i << ": forced lanes U = " << forced[i].displacement
                          << ", default kernel U = " << lanes[i].displacement;
        bad += same ? 0 : 1;
    }
    for (std::uint64_t i = 0; i < count; ++i) {
        ss::CounterRng rng(kSeed, ss::StreamPurpose::LongExcursion, first + i);
        const ss::ExcursionOutcome o = ss::resolvent_long_excursion(c, rng);
        const ss::ExcursionOutcome& l = lanes[i];
        const bool same = same_bits(o.displacement, l.displacement) && same_bits(o.duration, l.duration) &&
                          same_bits(o.first_half, l.first_half) && o.work == l.work && o.capped == l.capped;
        if (!same && bad < 3)
            ADD_FAILURE() << "excursion " << first + i << ": one-at-a-time U = " << o.displacement
                          << ", steps " << o.work << ", first half " << o.first_half << ", capped " << o.capped
                          << "; lanes U = " << l.displacement << ", steps " << l.work << ", first half "
                          << l.first_half << ", capped " << l.capped;
        bad += same ? 0 : 1;
        if (capped) *capped += o.capped ? 1 : 0;
    }
    return bad;
}

ss::ResolventConstants constants(const ss::ModelParams& p, double dt, ss::StopRule rule,
                                 std::uint64_t max_steps = 200'000'000) {
    ss::EngineSettings s = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    s.engine = ss::Engine::Inclusion;
    s.dt = dt;
    s.stop_rule = rule;
    s.max_work_per_excursion = max_steps;
    return ss::make_resolvent_constants(p, s);
}

// The control variate's kernel: the default entry point and the forced lanes
// against resolvent_long_excursion_with one at a time, M and Q included.
int mismatches_with(const ss::ResolventConstants& c, std::uint64_t first, std::uint64_t count) {
    const ss::test::ArbitraryCorrector corrector;
    const ss::CorrectorTable g = corrector.table();
    std::vector<ss::ExcursionOutcome> lanes(count), forced(count);
    EXPECT_TRUE(ss::resolvent_long_excursions_with(c, kSeed, first, count, lanes.data(), nullptr, g));
    EXPECT_TRUE(ss::detail::resolvent_long_excursions_in_lanes_with(c, kSeed, first, count, forced.data(), nullptr, g));
    int bad = 0, nonzero = 0;
    for (std::uint64_t i = 0; i < count; ++i) {
        ss::CounterRng rng(kSeed, ss::StreamPurpose::LongExcursion, first + i);
        const ss::ExcursionOutcome o = ss::resolvent_long_excursion_with(c, rng, g);
        for (const ss::ExcursionOutcome* l : {&lanes[i], &forced[i]}) {
            const bool same = same_bits(o.displacement, l->displacement) && same_bits(o.duration, l->duration) &&
                              same_bits(o.martingale, l->martingale) && same_bits(o.martingale_qv, l->martingale_qv) &&
                              o.work == l->work && o.capped == l->capped;
            if (!same && bad < 3)
                ADD_FAILURE() << "excursion " << first + i << ": one at a time U = " << o.displacement << ", M = "
                              << o.martingale << ", Q = " << o.martingale_qv << "; lanes U = " << l->displacement
                              << ", M = " << l->martingale << ", Q = " << l->martingale_qv;
            bad += same ? 0 : 1;
        }
        nonzero += o.martingale_qv != 0.0 ? 1 : 0;
    }
    EXPECT_EQ(nonzero, static_cast<int>(count)) << "every excursion accumulates a Q";
    return bad;
}

} // namespace

TEST(ResolventLanes, BitwiseEqualToOneAtATimeBridgeRule) {
    EXPECT_EQ(mismatches(constants(ss::ModelParams{}, 1e-3, ss::StopRule::Bridge), 0, 100), 0);
}

TEST(ResolventLanes, BitwiseEqualToOneAtATimeStuckRule) {
    EXPECT_EQ(mismatches(constants(ss::ModelParams{}, 1e-3, ss::StopRule::Stuck), 0, 100), 0);
}

TEST(ResolventLanes, BitwiseEqualWithoutViscousDragAndAtLargeIndices) {
    const std::uint64_t first = (std::uint64_t{1} << 40) + 3;
    EXPECT_EQ(mismatches(constants(dry_params(), 1e-3, ss::StopRule::Bridge), first, 77), 0);
    EXPECT_EQ(mismatches(constants(dry_params(), 2e-2, ss::StopRule::Stuck), first, 77), 0);
}

TEST(ResolventLanes, WhiteNoiseRunsTheOneExcursionKernel) {
    ss::ModelParams p = dry_params();
    p.tau = 0.0;
    EXPECT_EQ(mismatches(constants(p, 1e-3, ss::StopRule::Auto), 5, 40), 0);
}

TEST(ResolventLanes, PartialGroupsAndEmptyRuns) {
    const auto c = constants(ss::ModelParams{}, 1e-3, ss::StopRule::Bridge);
    for (std::uint64_t n : {0u, 1u, 7u, 8u, 9u, 17u}) EXPECT_EQ(mismatches(c, 1000, n), 0) << n << " excursions";
}

TEST(ResolventLanes, CappedExcursionsMatchToo) {
    // A cap below the median length: many excursions end capped, some in their first half.
    int capped = 0;
    EXPECT_EQ(mismatches(constants(ss::ModelParams{}, 1e-3, ss::StopRule::Bridge, 4000), 0, 64, &capped), 0);
    EXPECT_GT(capped, 10);
    EXPECT_LT(capped, 64);
}

TEST(ResolventLanes, MartingaleSumsBitwiseEqualToOneAtATime) {
    EXPECT_EQ(mismatches_with(constants(ss::ModelParams{}, 1e-3, ss::StopRule::Bridge), 0, 41), 0);
    EXPECT_EQ(mismatches_with(constants(ss::ModelParams{}, 1e-3, ss::StopRule::Stuck), 9, 23), 0);
    EXPECT_EQ(mismatches_with(constants(dry_params(), 2e-2, ss::StopRule::Bridge), (std::uint64_t{1} << 40) + 3, 30),
              0);
    EXPECT_EQ(mismatches_with(constants(ss::ModelParams{}, 1e-3, ss::StopRule::Bridge, 4000), 0, 17), 0); // capped
    ss::ModelParams white = dry_params();
    white.tau = 0.0;
    EXPECT_EQ(mismatches_with(constants(white, 1e-3, ss::StopRule::Auto), 5, 12), 0);
}

TEST(ResolventLanes, CancelStopsStartingExcursions) {
    const auto c = constants(ss::ModelParams{}, 1e-3, ss::StopRule::Bridge);
    std::atomic<bool> cancel{true};
    std::vector<ss::ExcursionOutcome> out(64);
    EXPECT_FALSE(ss::resolvent_long_excursions(c, kSeed, 0, out.size(), out.data(), &cancel));
    EXPECT_FALSE(ss::detail::resolvent_long_excursions_in_lanes(c, kSeed, 0, out.size(), out.data(), &cancel));
    cancel = false;
    EXPECT_TRUE(ss::resolvent_long_excursions(c, kSeed, 0, 3, out.data(), &cancel));
    EXPECT_TRUE(ss::detail::resolvent_long_excursions_in_lanes(c, kSeed, 0, 3, out.data(), &cancel));
}

TEST(ResolventLanes, NothingToStartMeansNothingCancelled) {
    // Both kernels agree that a run with nothing left to start is complete.
    const auto c = constants(ss::ModelParams{}, 1e-3, ss::StopRule::Bridge);
    std::atomic<bool> cancel{true};
    EXPECT_TRUE(ss::resolvent_long_excursions(c, kSeed, 0, 0, nullptr, &cancel));
    EXPECT_TRUE(ss::detail::resolvent_long_excursions_in_lanes(c, kSeed, 0, 0, nullptr, &cancel));
}

TEST(ResolventLanes, ReportsItsKernel) {
    const std::string name = ss::resolvent_kernel_name();
    EXPECT_EQ(name, ss::resolvent_lanes_vectorised() ? "8 SIMD lanes (AVX-512)" : "one excursion at a time");
}
