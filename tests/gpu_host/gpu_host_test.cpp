// SPDX-License-Identifier: BSD-3-Clause
// The CUDA backend's per-thread loop (stickslip/kernels/device_excursions.hpp),
// compiled as host code, against the CPU engine: every outcome bitwise the
// same, and the run's exact sums too, for both schemes, coloured noise with
// stop rules Q and P, white noise, capped excursions, partial blocks, odd
// first indices and any order in which the device's threads would take the
// excursions. This is what keeps the kernels one code: the device runs this
// loop, and differs from it only in the transcendental functions, which
// portable_math_test.cpp checks. Label gpu-host; needs no CUDA.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

#include "engines/cuda/host_merge.hpp"
#include "stickslip/kernels/device_excursions.hpp"
#include "stickslip/kernels/resolvent_lanes.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "stickslip/run.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/sample_runs.hpp"

namespace ss = stickslip;

namespace {

constexpr std::uint64_t kSeed = 20260614;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

ss::PreparedEngine engine(ss::ModelParams p, ss::Scheme scheme = ss::Scheme::Resolvent,
                          ss::StopRule rule = ss::StopRule::Auto, std::uint64_t max_work = 200'000'000) {
    ss::EngineSettings s = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    s.engine = ss::Engine::Inclusion;
    s.scheme = scheme;
    s.dt = 1e-4; // the Fig. 2 case's step
    s.stop_rule = rule;
    s.max_work_per_excursion = max_work;
    return ss::prepare_engine(p, s);
}

ss::ModelParams fig2() { return ss::ModelParams{}; } // the defaults are the paper's Fig. 2 case

ss::ModelParams fig2_white() {
    ss::ModelParams p;
    p.tau = 0.0;
    return p;
}

/// The device loop, run by `threads` host threads that take the excursions
/// from one shared counter, as the device's threads do (or, with reverse,
/// from the last excursion down: any order must give the same outcomes).
std::vector<ss::ExcursionOutcome> device_loop(const ss::PreparedEngine& e, std::uint64_t first, std::uint64_t n,
                                              unsigned threads, bool reverse = false) {
    std::vector<ss::ExcursionOutcome> out(n);
    std::atomic<std::uint64_t> counter{0};
    auto work = [&] {
        auto next = [&]() -> std::uint64_t {
            const std::uint64_t k = counter.fetch_add(1);
            return reverse && k < n ? n - 1 - k : k;
        };
        if (e.settings.scheme == ss::Scheme::Event)
            ss::device_event_worker(std::get<ss::EventConstants>(e.constants), kSeed, first, n, next, out.data());
        else
            ss::device_resolvent_worker(std::get<ss::ResolventConstants>(e.constants), kSeed, first, n, next, out.data());
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    return out;
}

/// The CPU engine's outcomes, by its production kernels (the SIMD lanes or
/// one excursion at a time with the batched streams; the event scheme as the
/// runner calls it).
std::vector<ss::ExcursionOutcome> cpu_engine(const ss::PreparedEngine& e, std::uint64_t first, std::uint64_t n) {
    std::vector<ss::ExcursionOutcome> out(n);
    if (e.settings.scheme == ss::Scheme::Event) {
        for (std::uint64_t k = 0; k < n; ++k) {
            ss::BatchedCounterRng rng(kSeed, ss::StreamPurpose::LongExcursion, first + k);
            ss::CounterRng ref(kSeed, ss::StreamPurpose::Refinement, first + k);
            out[k] = ss::event_long_excursion(std::get<ss::EventConstants>(e.constants), rng, ref);
        }
    } else {
        EXPECT_TRUE(ss::resolvent_long_excursions(std::get<ss::ResolventConstants>(e.constants), kSeed, first, n, out.data()));
    }
    return out;
}

std::vector<std::uint64_t> words(const ss::ExactBivariateSums& s) {
    std::vector<std::uint64_t> w(ss::ExactBivariateSums::words);
    s.to_words(w.data());
    return w;
}

struct Tally {
    std::uint64_t capped = 0, work = 0;
};

/// Compares the device loop with the CPU engine excursion by excursion, and
/// the merged totals with the CPU run's (run_long_excursions), bitwise.
Tally expect_same(const ss::PreparedEngine& e, std::uint64_t first, std::uint64_t n, unsigned threads = 2,
                  bool reverse = false) {
    const std::vector<ss::ExcursionOutcome> dev = device_loop(e, first, n, threads, reverse);
    const std::vector<ss::ExcursionOutcome> cpu = cpu_engine(e, first, n);
    Tally tally;
    int bad = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
        const ss::ExcursionOutcome &d = dev[i], &c = cpu[i];
        const bool same = same_bits(d.displacement, c.displacement) && same_bits(d.duration, c.duration) &&
                          same_bits(d.first_half, c.first_half) && d.work == c.work && d.capped == c.capped;
        if (!same && ++bad <= 3)
            ADD_FAILURE() << "excursion " << first + i << ": device loop U = " << d.displacement << ", t = "
                          << d.duration << ", work " << d.work << ", capped " << d.capped << "; CPU engine U = "
                          << c.displacement << ", t = " << c.duration << ", work " << c.work << ", capped "
                          << c.capped;
        tally.capped += c.capped ? 1 : 0;
        tally.work += c.work;
    }
    EXPECT_EQ(bad, 0) << "of " << n << " excursions";

    ss::RunControl ctl;
    ctl.seed = kSeed;
    ctl.threads = 2;
    ctl.first_index = first;
    const ss::RunTotals run = ss::run_long_excursions(e, n, ctl);
    const ss::RunTotals merged = ss::cuda::merge_outcomes(dev.data(), n);
    EXPECT_EQ(words(merged.sums), words(run.sums)) << "exact sums of (U, t) differ from the CPU run's";
    EXPECT_EQ(merged.capped, run.capped);
    EXPECT_EQ(merged.work, run.work);
    EXPECT_TRUE(same_bits(merged.moments.mean_x(), run.moments.mean_x()));
    EXPECT_TRUE(same_bits(merged.moments.central_sum(2, 0), run.moments.central_sum(2, 0)));
    return tally;
}

} // namespace

TEST(GpuHost, Fig2BridgeRuleMatchesCpuEngine) {
    const ss::PreparedEngine e = engine(fig2());
    ASSERT_EQ(std::get<ss::ResolventConstants>(e.constants).rule, ss::StopRule::Bridge); // dt = 1e-4 <= tau / 10
    const Tally t = expect_same(e, 0, 300);
    EXPECT_EQ(t.capped, 0u);
    EXPECT_GT(t.work, 300u * 1000u);
}

TEST(GpuHost, Fig2BridgeRuleOddFirstIndexPartialBlocksAnyOrder) {
    // Blocks of 64, 64 and 2 from an odd first index; the excursions taken from the last down.
    expect_same(engine(fig2()), 1000003, 130, 2, true);
}

TEST(GpuHost, Fig2StuckRuleMatchesCpuEngine) {
    const ss::PreparedEngine e = engine(fig2(), ss::Scheme::Resolvent, ss::StopRule::Stuck);
    ASSERT_EQ(std::get<ss::ResolventConstants>(e.constants).rule, ss::StopRule::Stuck);
    expect_same(e, 64, 200);
}

TEST(GpuHost, WhiteNoiseMatchesCpuEngine) {
    const ss::PreparedEngine e = engine(fig2_white());
    ASSERT_TRUE(std::get<ss::ResolventConstants>(e.constants).white);
    expect_same(e, 0, 300);
}

TEST(GpuHost, CappedExcursionsMatchCpuEngine) {
    // A cap of 20000 steps stops a good part of the Fig. 2 excursions.
    const Tally t = expect_same(engine(fig2(), ss::Scheme::Resolvent, ss::StopRule::Auto, 20000), 777, 173, 3);
    EXPECT_GT(t.capped, 0u);
    EXPECT_LT(t.capped, 173u);
    const Tally w = expect_same(engine(fig2_white(), ss::Scheme::Resolvent, ss::StopRule::Auto, 2000), 5, 100);
    EXPECT_GT(w.capped, 0u);
}

TEST(GpuHost, EventSchemeMatchesCpuEngine) {
    const ss::PreparedEngine e = engine(fig2(), ss::Scheme::Event);
    expect_same(e, 0, 64, 2);
    expect_same(e, 4099, 37, 2, true); // a partial block from an odd index, in reverse
}

TEST(GpuHost, EventSchemeCappedMatchesCpuEngine) {
    const Tally t = expect_same(engine(fig2(), ss::Scheme::Event, ss::StopRule::Auto, 300), 11, 70);
    EXPECT_GT(t.capped, 0u);
}

TEST(GpuHost, OneThreadOrManyGiveTheSameOutcomes) {
    const ss::PreparedEngine e = engine(fig2());
    const auto one = device_loop(e, 40, 96, 1);
    const auto three = device_loop(e, 40, 96, 3, true);
    for (std::size_t i = 0; i < one.size(); ++i) {
        EXPECT_TRUE(same_bits(one[i].displacement, three[i].displacement)) << i;
        EXPECT_EQ(one[i].work, three[i].work) << i;
    }
}

namespace {
/// A stream whose side uniform is set by the test.
struct FixedSide {
    double u;
    double side_uniform() const { return u; }
};
} // namespace

TEST(GpuHost, BridgeTestDecidesAsBefore) {
    // bridge_crossed must be, on the host, exactly the former test
    // p = bridge_crossing_probability(...); p > 0 && u < p.
    const ss::ResolventConstants c = std::get<ss::ResolventConstants>(engine(fig2()).constants);
    ss::CounterRng rng(kSeed, ss::StreamPurpose::Test, 1);
    int crossings = 0;
    for (int k = 0; k < 200000; ++k) {
        double a, b, u, v;
        rng.uniform2(a, b);
        rng.uniform2(u, v);
        // X near the lower threshold, on its upper side, as in a stuck step.
        const double x0 = c.x_down + 0.03 * a, x1 = c.x_down + 0.03 * b;
        FixedSide side{k % 2 ? u : v * 1e-3};
        const double p = ss::bridge_crossing_probability(c, x0, x1, c.x_down);
        const bool before = p > 0.0 && side.u < p;
        EXPECT_EQ(ss::bridge_crossed(c, x0, x1, c.x_down, side), before) << x0 << " " << x1 << " " << side.u;
        crossings += before ? 1 : 0;
    }
    EXPECT_GT(crossings, 1000); // the test saw both outcomes
    EXPECT_LT(crossings, 199000);
}
