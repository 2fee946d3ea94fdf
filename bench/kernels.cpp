// bench/kernels.cpp -- single-thread throughput of stickslip's kernels
// (Google Benchmark). Every number is per core: one thread, no runner.
//
//   BM_PhiloxNormalPairs          CounterRng::normal2 alone; items = pairs.
//                                 One pair is what one colored inclusion step
//                                 draws, so this is the practical ceiling of
//                                 steps/s on this core.
//   BM_InclusionSteps/<case>      whole long excursions of the inclusion engine
//                                 (inclusion_long_excursion); items = steps.
//   BM_PdmpEvents/<case>          whole long excursions of the PDMP engine
//                                 (pdmp_long_excursion, grid 0.125); items = events.
//
// Cases: fig2 = ModelParams defaults (the paper's Fig. 2), inclusion dt 1e-4;
//        dry  = pure dry friction: friction 1, noise 1, tau 0.5, relaxation inf,
//               bias 0, inclusion dt 1e-3.
// One benchmark iteration is one long excursion (sample index = iteration
// number, so successive iterations are independent excursions).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <limits>

#include "stickslip/inclusion.hpp"
#include "stickslip/pdmp.hpp"
#include "stickslip/rng.hpp"

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

void BM_PhiloxNormalPairs(benchmark::State& state) {
    constexpr std::int64_t batch = 1 << 16;
    CounterRng rng(kSeed, StreamPurpose::Test, 0);
    for (auto _ : state) {
        for (std::int64_t k = 0; k < batch; ++k) {
            auto z = rng.normal2();
            benchmark::DoNotOptimize(z); // keeps both normals, adds no dependency chain
        }
    }
    state.SetItemsProcessed(state.iterations() * batch);
}

void run_inclusion(benchmark::State& state, const ModelParams& p, double dt) {
    EngineSettings s;
    s.engine = Engine::Inclusion;
    s.dt = dt;
    const InclusionConstants c = make_inclusion_constants(p, s);
    std::uint64_t index = 0, work = 0, excursions = 0;
    double sink = 0.0;
    for (auto _ : state) {
        CounterRng rng(kSeed, StreamPurpose::LongExcursion, index++);
        const ExcursionOutcome o = inclusion_long_excursion(c, rng);
        sink += o.displacement;
        work += o.work;
        ++excursions;
    }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(static_cast<std::int64_t>(work));
    state.counters["steps_per_excursion"] =
        benchmark::Counter(static_cast<double>(work) / static_cast<double>(excursions ? excursions : 1));
}

void run_pdmp(benchmark::State& state, const ModelParams& p, double grid) {
    EngineSettings s;
    s.engine = Engine::Pdmp;
    s.grid = grid;
    const PdmpConstants c = make_pdmp_constants(p, s);
    std::uint64_t index = 0, work = 0, excursions = 0;
    double sink = 0.0;
    for (auto _ : state) {
        CounterRng rng(kSeed, StreamPurpose::LongExcursion, index++);
        const ExcursionOutcome o = pdmp_long_excursion(c, rng);
        sink += o.displacement;
        work += o.work;
        ++excursions;
    }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(static_cast<std::int64_t>(work));
    state.counters["events_per_excursion"] =
        benchmark::Counter(static_cast<double>(work) / static_cast<double>(excursions ? excursions : 1));
}

void BM_InclusionSteps_fig2(benchmark::State& st) { run_inclusion(st, fig2_params(), 1e-4); }
void BM_InclusionSteps_dry(benchmark::State& st) { run_inclusion(st, dry_params(), 1e-3); }
void BM_PdmpEvents_fig2(benchmark::State& st) { run_pdmp(st, fig2_params(), 0.125); }
void BM_PdmpEvents_dry(benchmark::State& st) { run_pdmp(st, dry_params(), 0.125); }

} // namespace

BENCHMARK(BM_PhiloxNormalPairs)->Name("BM_PhiloxNormalPairs")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionSteps_fig2)->Name("BM_InclusionSteps/fig2_dt1e-4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InclusionSteps_dry)->Name("BM_InclusionSteps/dry_dt1e-3")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdmpEvents_fig2)->Name("BM_PdmpEvents/fig2_grid0.125")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PdmpEvents_dry)->Name("BM_PdmpEvents/dry_grid0.125")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
