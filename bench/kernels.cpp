// SPDX-License-Identifier: BSD-3-Clause
// bench/kernels.cpp -- single-thread throughput of stickslip's kernels
// (Google Benchmark). Every number is per core: one thread, no runner.
//
//   BM_NormalPairs                BatchedCounterRng::normal2 alone (Philox4x32-10
//                                 over 32 counters at once + ziggurat); items =
//                                 pairs. One colored inclusion step draws one
//                                 pair: this is the random-number limit of
//                                 steps/s on this core.
//   BM_NormalPairsScalar          the same numbers from CounterRng, one call at a time.
//   BM_PdmpDraws                  BatchedUniformRng::exponential_uniform; one PDMP
//                                 event takes one draw (an exponential wait and a
//                                 uniform direction): the PDMP engine's limit of
//                                 events/s.
//   BM_PdmpDrawsScalar            the same from CounterRng.
//   BM_InclusionSteps/<case>      resolvent_long_excursion, one excursion per
//                                 iteration (BatchedCounterRng); items = steps.
//   BM_InclusionLanes/<case>      resolvent_long_excursions, the kernel the runner
//                                 uses (8 SIMD lanes with AVX-512), 64
//                                 excursions per iteration; items = steps.
//   BM_PdmpEvents/<case>          pdmp_long_excursion, grid 0.125
//   BM_PdmpEventsLogWaits/fig2_grid0.125  the same with the waits drawn as
//                                 -log(u) of a uniform pair's first half, the
//                                 PDMP's draw before its exponential ziggurat:
//                                 the two side by side in one run.
//                                 (BatchedUniformRng); items = events.
//   BM_EventSteps/<case>          event_long_excursion (the event scheme, one
//                                 excursion at a time, no lanes); items =
//                                 steps and refinement midpoints.
//   BM_EventLanes/<case>          event_long_excursions, the kernel the runner
//                                 uses (8 SIMD lanes with AVX-512 for coloured
//                                 noise), 64 excursions per iteration; items =
//                                 steps and refinement midpoints.
//   BM_InclusionLanesCv, BM_EventLanesCv, BM_EventStepsCv, BM_PdmpEventsCv/<case>
//                                 the same kernels with the control variate's
//                                 martingale, as the runner calls them: the cost
//                                 of its table lookup per step, side by side
//                                 with the plain twins in one run.
//   BM_InclusionLanes/white_dry_dt1e-2, BM_EventSteps/white_dry_dt1e-2 and
//   .../white_dry_dt0.0625: white noise (friction 1, noise 1, tau 0,
//                                 relaxation inf, bias 0); 0.0625 is the
//                                 event scheme's automatic step.
//
// Cases: fig2 = ModelParams defaults (the paper's Fig. 2), inclusion dt 1e-4
//               (and 6.7e-4, the resolvent's automatic step);
//        dry  = pure dry friction: friction 1, noise 1, tau 0.5, relaxation inf,
//               bias 0, inclusion dt 1e-3;
//        fig2_knots = the Fig. 2 law given as the expression "0.342 - v/0.067"
//               (1025 knots: every knot an event), beside fig2 at the same step.
// Successive iterations use successive sample indices: independent excursions.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "stickslip/corrector.hpp"
#include "stickslip/kernels/event_lanes.hpp"
#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/kernels/resolvent.hpp"
#include "stickslip/kernels/resolvent_lanes.hpp"
#include "stickslip/kernels/pdmp.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"

namespace {

using namespace stickslip;

constexpr std::uint64_t kSeed = 20240901;

ModelParams fig2_params() { return ModelParams{}; }

ModelParams dry_params() {
    ModelParams p;
    p.friction = 1.0;
    p.noise = 1.0;
    p.tau = 0.5;
    p.relaxation = std::numeric_limits<double>::infinity();
    p.bias = 0.0;
    return p;
}

// Pairs drawn one at a time from a stream and summed (the sum keeps the
// compiler from discarding them without adding a store per pair); `draw(rng)`
// returns the sum of one pair.
template <class Rng, class Draw>
void pairs(benchmark::State& state, Draw draw) {
    constexpr std::int64_t batch = 1 << 16;
    std::uint64_t index = 0;
    double sink = 0.0;
    for (auto _ : state) {
        Rng rng(kSeed, StreamPurpose::Test, index++);
        for (std::int64_t k = 0; k < batch; ++k) sink += draw(rng);
    }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(state.iterations() * batch);
}
constexpr auto normal_pair = [](auto& rng) {
    const auto z = rng.normal2();
    return z.x + z.y;
};
constexpr auto pdmp_draw = [](auto& rng) { // one PDMP event takes one draw
    double e, u;
    rng.exponential_uniform(e, u);
    return e + u;
};
void BM_NormalPairs(benchmark::State& state) { pairs<BatchedCounterRng>(state, normal_pair); }
void BM_NormalPairsScalar(benchmark::State& state) { pairs<CounterRng>(state, normal_pair); }
void BM_PdmpDraws(benchmark::State& state) { pairs<BatchedUniformRng>(state, pdmp_draw); }
void BM_PdmpDrawsScalar(benchmark::State& state) { pairs<CounterRng>(state, pdmp_draw); }

// Items = steps (inclusion) or events (pdmp); `sink` keeps the kernel from
// being optimised away.
void report_work(benchmark::State& state, double sink, std::uint64_t work, std::uint64_t excursions,
                 const char* per_excursion_name) {
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(static_cast<std::int64_t>(work));
    state.counters[per_excursion_name] =
        benchmark::Counter(static_cast<double>(work) / static_cast<double>(excursions ? excursions : 1));
}

ResolventConstants resolvent_constants(const ModelParams& p, double dt) {
    EngineSettings s;
    s.engine = Engine::Inclusion;
    s.dt = dt;
    return make_resolvent_constants(p, s);
}

// One long excursion per iteration: excursion(index) runs excursion `index`
// on its own streams; successive iterations take successive indices.
template <class Excursion>
void time_excursions(benchmark::State& state, const char* per_excursion_name, Excursion excursion) {
    std::uint64_t index = 0, work = 0;
    double sink = 0.0;
    for (auto _ : state) {
        const ExcursionOutcome o = excursion(index++);
        sink += o.displacement;
        work += o.work;
    }
    report_work(state, sink, work, index, per_excursion_name);
}

void run_resolvent(benchmark::State& state, const ModelParams& p, double dt) {
    const ResolventConstants c = resolvent_constants(p, dt);
    time_excursions(state, "steps_per_excursion", [&c](std::uint64_t k) {
        BatchedCounterRng rng(kSeed, StreamPurpose::LongExcursion, k);
        return resolvent_long_excursion(c, rng);
    });
}

// A block kernel as the runner calls it (block(first, count, out)): one
// iteration = one block of 64 excursions; items = steps (and midpoints).
template <class Block>
void time_blocks(benchmark::State& state, Block&& block) {
    std::uint64_t first = 0, work = 0, excursions = 0;
    double sink = 0.0;
    ExcursionOutcome out[64];
    for (auto _ : state) {
        block(first, 64, out);
        first += 64;
        for (const auto& o : out) {
            sink += o.displacement;
            work += o.work;
        }
        excursions += 64;
    }
    report_work(state, sink, work, excursions, "steps_per_excursion");
}

// The kernel the runner uses (resolvent_long_excursions: 8 SIMD lanes where vectorised).
void run_resolvent_lanes(benchmark::State& state, const ModelParams& p, double dt) {
    const ResolventConstants c = resolvent_constants(p, dt);
    time_blocks(state, [&c](std::uint64_t first, std::uint64_t count, ExcursionOutcome* out) {
        resolvent_long_excursions(c, kSeed, first, count, out);
    });
}

/// The PDMP's draw as it was before the exponential ziggurat: the wait is
/// -log(u0) of the pair (u0, u1) of one block, u1 the jump direction's uniform.
struct LogWaitRng {
    BatchedUniformRng inner;
    LogWaitRng(std::uint64_t seed, StreamPurpose purpose, std::uint64_t index) : inner(seed, purpose, index) {}
    void exponential_uniform(double& e, double& u) {
        double u0;
        inner.uniform2(u0, u);
        e = -std::log(u0);
    }
};

template <class Rng = BatchedUniformRng>
void run_pdmp(benchmark::State& state, const ModelParams& p, double grid) {
    EngineSettings s;
    s.engine = Engine::Pdmp;
    s.grid = grid;
    const PdmpConstants c = make_pdmp_constants(p, s);
    time_excursions(state, "events_per_excursion", [&c](std::uint64_t k) {
        Rng rng(kSeed, StreamPurpose::LongExcursion, k);
        return pdmp_long_excursion(c, rng);
    });
}

// The event scheme: one excursion at a time (it has no lanes). A drift law's
// laws per piece are built outside the timing.
void run_event(benchmark::State& state, const ModelParams& p, double dt) {
    EngineSettings s;
    s.scheme = Scheme::Event;
    s.dt = dt;
    std::shared_ptr<const std::vector<EventDriftPiece>> pieces;
    const EventConstants c = make_event_constants(p, s, &pieces);
    time_excursions(state, "steps_per_excursion", [&c](std::uint64_t k) {
        BatchedCounterRng rng(kSeed, StreamPurpose::LongExcursion, k);
        BatchedCounterRng ref(kSeed, StreamPurpose::Refinement, k);
        return event_long_excursion(c, rng, ref);
    });
}

// The event scheme's kernel as the runner uses it: one block of 64 excursions.
void run_event_lanes(benchmark::State& state, const ModelParams& p, double dt) {
    EngineSettings s;
    s.scheme = Scheme::Event;
    s.dt = dt;
    const EventConstants c = make_event_constants(p, s);
    time_blocks(state, [&c](std::uint64_t first, std::uint64_t count, ExcursionOutcome* out) {
        event_long_excursions(c, kSeed, first, count, out);
    });
}

ModelParams white_dry_params() {
    ModelParams p = dry_params();
    p.tau = 0.0;
    return p;
}

// The same kernels with the control variate's martingale (kernels/corrector.hpp),
// as the runner calls them (both schemes in their SIMD lanes where the plain
// kernel has them, the PDMP one excursion at a time): their time per step
// against the plain kernels' above, side by side in one run (the corrector is
// made once, outside the timing). The *_fig2_auto cases run at 0.01675 s,
// relaxation/4, the event scheme's automatic step until 2026-12-05 (now
// relaxation/8), kept so that their numbers compare with earlier runs.
void run_resolvent_cv(benchmark::State& state, const ModelParams& p, double dt) {
    const ResolventConstants c = resolvent_constants(p, dt);
    const auto g = make_corrector(p);
    time_blocks(state, [&c, &g](std::uint64_t first, std::uint64_t count, ExcursionOutcome* out) {
        resolvent_long_excursions_with(c, kSeed, first, count, out, nullptr, g->table);
    });
}

void run_event_cv(benchmark::State& state, const ModelParams& p, double dt) {
    EngineSettings s;
    s.scheme = Scheme::Event;
    s.dt = dt;
    const EventConstants c = make_event_constants(p, s);
    const auto g = make_corrector(p);
    time_blocks(state, [&c, &g](std::uint64_t first, std::uint64_t count, ExcursionOutcome* out) {
        event_long_excursions_with(c, kSeed, first, count, out, nullptr, g->table);
    });
}

void run_pdmp_cv(benchmark::State& state, const ModelParams& p, double grid) {
    EngineSettings s;
    s.engine = Engine::Pdmp;
    s.grid = grid;
    const PdmpConstants c = make_pdmp_constants(p, s);
    const auto g = make_corrector(p);
    time_excursions(state, "events_per_excursion", [&c, &g](std::uint64_t k) {
        BatchedUniformRng rng(kSeed, StreamPurpose::LongExcursion, k);
        return pdmp_long_excursion_with(c, rng, g->table);
    });
}

void BM_InclusionLanesCv_dry(benchmark::State& st) { run_resolvent_cv(st, dry_params(), 1e-3); }
void BM_InclusionLanesCv_fig2(benchmark::State& st) { run_resolvent_cv(st, fig2_params(), 1e-4); }
void BM_EventStepsCv_fig2_auto(benchmark::State& st) { run_event_cv(st, fig2_params(), 0.01675); }
void BM_EventLanesCv_fig2(benchmark::State& st) { run_event_cv(st, fig2_params(), 1e-4); }
// Pure dry friction with tau = 0.5 s at the event scheme's automatic step
// (tau/16): no drag, so the lanes run, with and without the martingale.
void BM_EventLanes_dry_auto(benchmark::State& st) { run_event_lanes(st, dry_params(), 0.03125); }
void BM_EventLanesCv_dry_auto(benchmark::State& st) { run_event_cv(st, dry_params(), 0.03125); }
void BM_PdmpEventsCv_dry(benchmark::State& st) { run_pdmp_cv(st, dry_params(), 0.125); }

void BM_EventSteps_fig2(benchmark::State& st) { run_event(st, fig2_params(), 1e-4); }
void BM_EventSteps_fig2_auto(benchmark::State& st) { run_event(st, fig2_params(), 0.01675); }
// The Fig. 2 law given as an expression: the same model cut into 1024 pieces,
// every knot an event (against BM_EventSteps/fig2_dt0.01675: what the pieces cost).
ModelParams fig2_knots_params() {
    ModelParams p;
    p.drift = "0.342 - v/0.067";
    return p;
}
void BM_EventSteps_fig2_knots(benchmark::State& st) { run_event(st, fig2_knots_params(), 0.01675); }
void BM_EventSteps_white(benchmark::State& st) { run_event(st, white_dry_params(), 1e-2); }
void BM_EventSteps_white_auto(benchmark::State& st) { run_event(st, white_dry_params(), 0.0625); }
void BM_EventLanes_fig2(benchmark::State& st) { run_event_lanes(st, fig2_params(), 1e-4); }
void BM_EventLanes_fig2_auto(benchmark::State& st) { run_event_lanes(st, fig2_params(), 0.01675); }
void BM_InclusionLanes_white(benchmark::State& st) { run_resolvent_lanes(st, white_dry_params(), 1e-2); }
void BM_InclusionSteps_fig2(benchmark::State& st) { run_resolvent(st, fig2_params(), 1e-4); }
void BM_InclusionSteps_dry(benchmark::State& st) { run_resolvent(st, dry_params(), 1e-3); }
void BM_InclusionLanes_fig2(benchmark::State& st) { run_resolvent_lanes(st, fig2_params(), 1e-4); }
// The resolvent's own automatic step on the Fig. 2 case (relaxation/100).
void BM_InclusionLanes_fig2_auto(benchmark::State& st) { run_resolvent_lanes(st, fig2_params(), 6.7e-4); }
void BM_InclusionLanes_dry(benchmark::State& st) { run_resolvent_lanes(st, dry_params(), 1e-3); }
void BM_PdmpEvents_fig2(benchmark::State& st) { run_pdmp(st, fig2_params(), 0.125); }
void BM_PdmpEvents_dry(benchmark::State& st) { run_pdmp(st, dry_params(), 0.125); }
void BM_PdmpEventsLogWaits_fig2(benchmark::State& st) { run_pdmp<LogWaitRng>(st, fig2_params(), 0.125); }

} // namespace

BENCHMARK(BM_NormalPairs)->Name("BM_NormalPairs")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NormalPairsScalar)->Name("BM_NormalPairsScalar")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdmpDraws)->Name("BM_PdmpDraws")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdmpDrawsScalar)->Name("BM_PdmpDrawsScalar")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionSteps_fig2)->Name("BM_InclusionSteps/fig2_dt1e-4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionSteps_dry)->Name("BM_InclusionSteps/dry_dt1e-3")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionLanes_fig2)->Name("BM_InclusionLanes/fig2_dt1e-4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionLanes_fig2_auto)->Name("BM_InclusionLanes/fig2_dt6.7e-4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionLanes_dry)->Name("BM_InclusionLanes/dry_dt1e-3")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdmpEvents_fig2)->Name("BM_PdmpEvents/fig2_grid0.125")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdmpEvents_dry)->Name("BM_PdmpEvents/dry_grid0.125")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdmpEventsLogWaits_fig2)
    ->Name("BM_PdmpEventsLogWaits/fig2_grid0.125")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventSteps_fig2)->Name("BM_EventSteps/fig2_dt1e-4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventSteps_fig2_auto)->Name("BM_EventSteps/fig2_dt0.01675")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventSteps_fig2_knots)->Name("BM_EventSteps/fig2_knots_dt0.01675")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventLanes_fig2)->Name("BM_EventLanes/fig2_dt1e-4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventLanes_fig2_auto)->Name("BM_EventLanes/fig2_dt0.01675")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionLanes_white)->Name("BM_InclusionLanes/white_dry_dt1e-2")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventSteps_white)->Name("BM_EventSteps/white_dry_dt1e-2")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventSteps_white_auto)->Name("BM_EventSteps/white_dry_dt0.0625")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionLanesCv_dry)->Name("BM_InclusionLanesCv/dry_dt1e-3")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionLanesCv_fig2)->Name("BM_InclusionLanesCv/fig2_dt1e-4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventLanesCv_fig2)->Name("BM_EventLanesCv/fig2_dt1e-4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventLanes_dry_auto)->Name("BM_EventLanes/dry_dt0.03125")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventLanesCv_dry_auto)->Name("BM_EventLanesCv/dry_dt0.03125")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EventStepsCv_fig2_auto)->Name("BM_EventStepsCv/fig2_dt0.01675")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdmpEventsCv_dry)->Name("BM_PdmpEventsCv/dry_grid0.125")->Unit(benchmark::kMillisecond);

// BENCHMARK_MAIN, plus which code paths ran, in the report's context.
int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::AddCustomContext("stickslip_rng_isa", stickslip::detail::rng_batch_isa());
    benchmark::AddCustomContext("stickslip_inclusion_kernel", stickslip::resolvent_kernel_name());
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
