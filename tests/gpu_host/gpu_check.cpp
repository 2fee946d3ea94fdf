// SPDX-License-Identifier: BSD-3-Clause
// gpu_check: the CUDA backend against the CPU engine, bit for bit, and the
// speed of both (issue 14; docs/gpu.md). Built with STICKSLIP_CUDA only.
//
// For each case (the Fig. 2 case at dt = 1e-4 s with stop rules Q and P,
// white noise, capped excursions from an odd first index with a partial last
// block, the event scheme) it runs the same excursions on the CPU engine (the
// production path, run_long_excursions, timed, and the per-excursion kernel
// for the reference outcomes) and on the device, and compares every
// excursion's outcome (U, t, first half, work, capped) and the run's exact
// sums (what the JSON reports are computed from) bitwise. Then, with
// --bench N, the device alone on N excursions per case (the event scheme:
// N/64): steps and excursions per second, kernel only and whole call.
//
// --emulate runs the device's loop on host threads instead, to check this
// program where there is no device (the numbers are then the host's).
//
// Exit status: 0 every comparison bitwise equal; 1 some outcome differs; 2 no
// CUDA device ("gpu_check: no CUDA device found"); 3 any other error.
//
// The device computes exp, log and log1p with the project's own functions
// (portable_math.hpp); a CPU built without STICKSLIP_PORTABLE_MATH uses
// glibc's, which are not always correctly rounded, so a difference can then
// come from glibc (the report says which build this is).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "engines/cuda/cuda_engine.hpp"
#include "stickslip/kernels/device_excursions.hpp"
#include "engines/cuda/host_merge.hpp"
#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/kernels/resolvent.hpp"
#include "stickslip/kernels/resolvent_lanes.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "stickslip/run.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/sample_runs.hpp"

namespace ss = stickslip;

namespace {

struct Case {
    std::string name;
    ss::ModelParams params;
    ss::EngineSettings settings;
    std::uint64_t first = 0;
    std::uint64_t excursions = 0;
};

struct Options {
    std::uint64_t excursions = 4096; // per resolvent case (the event scheme's: a quarter)
    std::uint64_t seed = 1;
    unsigned cpu_threads = 2;        // the reference: a 2-core CPU
    std::uint64_t bench = 0;         // device-only excursions for the speed rows (0: none)
    unsigned device_threads = 0;     // 0: as many as fit
    std::string only;                // run only this case
    bool emulate = false;            // the device loop on host threads instead of the device
};

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same(const ss::ExcursionOutcome& a, const ss::ExcursionOutcome& b) {
    return same_bits(a.displacement, b.displacement) && same_bits(a.duration, b.duration) &&
           same_bits(a.first_half, b.first_half) && a.work == b.work && a.capped == b.capped;
}

bool same_sums(const ss::RunTotals& a, const ss::RunTotals& b) {
    std::vector<std::uint64_t> wa(ss::ExactBivariateSums::words), wb(ss::ExactBivariateSums::words);
    a.sums.to_words(wa.data());
    b.sums.to_words(wb.data());
    return wa == wb && a.capped == b.capped && a.work == b.work;
}

std::vector<Case> cases(const Options& o) {
    std::vector<Case> v;
    ss::EngineSettings s;
    s.engine = ss::Engine::Inclusion;
    s.dt = 1e-4;
    ss::ModelParams fig2; // the defaults are the paper's Fig. 2 case
    v.push_back({"fig2_bridge", fig2, s, 0, o.excursions});
    ss::EngineSettings stuck = s;
    stuck.stop_rule = ss::StopRule::Stuck;
    v.push_back({"fig2_stuck", fig2, stuck, 0, o.excursions});
    ss::ModelParams white = fig2;
    white.tau = 0.0;
    v.push_back({"white", white, s, 0, o.excursions});
    ss::EngineSettings capped = s;
    capped.max_work_per_excursion = 60000; // about half of the excursions
    v.push_back({"capped_partial", fig2, capped, 777, o.excursions - 27});
    ss::EngineSettings event = s;
    event.scheme = ss::Scheme::Event;
    v.push_back({"event", fig2, event, 0, std::max<std::uint64_t>(o.excursions / 4, 64)});
    return v;
}

/// The CPU reference outcomes of excursions first .. first+n-1, in `threads` threads.
std::vector<ss::ExcursionOutcome> cpu_outcomes(const ss::PreparedEngine& e, std::uint64_t seed, std::uint64_t first,
                                               std::uint64_t n, unsigned threads) {
    std::vector<ss::ExcursionOutcome> out(n);
    std::atomic<std::uint64_t> next{0};
    auto work = [&] {
        for (;;) {
            const std::uint64_t lo = next.fetch_add(ss::block_size);
            if (lo >= n) return;
            const std::uint64_t cnt = std::min<std::uint64_t>(ss::block_size, n - lo);
            if (e.settings.scheme == ss::Scheme::Event) {
                for (std::uint64_t k = lo; k < lo + cnt; ++k) {
                    ss::BatchedCounterRng rng(seed, ss::StreamPurpose::LongExcursion, first + k);
                    ss::CounterRng ref(seed, ss::StreamPurpose::Refinement, first + k);
                    out[k] = ss::event_long_excursion(std::get<ss::EventConstants>(e.constants), rng, ref);
                }
            } else {
                ss::resolvent_long_excursions(std::get<ss::ResolventConstants>(e.constants), seed, first + lo, cnt, out.data() + lo);
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    return out;
}

/// --emulate: the device's per-thread loop (device_excursions.hpp) on host
/// threads, to check this program itself where there is no device.
ss::cuda::DeviceTiming emulated(const ss::PreparedEngine& e, std::uint64_t seed, std::uint64_t first, std::uint64_t n,
                                unsigned threads, ss::ExcursionOutcome* out) {
    const auto start = std::chrono::steady_clock::now();
    std::atomic<std::uint64_t> counter{0};
    auto work = [&] {
        auto next = [&]() -> std::uint64_t { return counter.fetch_add(1); };
        if (e.settings.scheme == ss::Scheme::Event) ss::device_event_worker(std::get<ss::EventConstants>(e.constants), seed, first, n, next, out);
        else ss::device_resolvent_worker(std::get<ss::ResolventConstants>(e.constants), seed, first, n, next, out);
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    ss::cuda::DeviceTiming t;
    t.total_seconds = t.kernel_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    t.threads = threads;
    return t;
}

bool g_emulate = false;

ss::cuda::DeviceTiming gpu_outcomes(const ss::PreparedEngine& e, std::uint64_t seed, std::uint64_t first,
                                    std::uint64_t n, unsigned threads, ss::ExcursionOutcome* out) {
    if (g_emulate) return emulated(e, seed, first, n, threads ? threads : 2, out);
    if (e.settings.scheme == ss::Scheme::Event)
        return ss::cuda::event_long_excursions(std::get<ss::EventConstants>(e.constants), seed, first, n, out, threads);
    return ss::cuda::resolvent_long_excursions(std::get<ss::ResolventConstants>(e.constants), seed, first, n, out, threads);
}

std::uint64_t total_work(const std::vector<ss::ExcursionOutcome>& v) {
    std::uint64_t w = 0;
    for (const auto& o : v) w += o.work;
    return w;
}

int usage() {
    std::fprintf(stderr,
                 "usage: gpu_check [--excursions N=4096] [--seed S=1] [--cpu-threads T=2] [--bench N=0]\n"
                 "                 [--device-threads T=0] [--case NAME] [--emulate]\n"
                 "--emulate: the device loop on --device-threads host threads (default 2), no device\n"
                 "cases: fig2_bridge fig2_stuck white capped_partial event\n");
    return 3;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
        if (a == "--emulate") {
            o.emulate = true;
            continue;
        }
        const char* v = (a == "-h" || a == "--help") ? nullptr : value();
        if (!v) return usage();
        if (a == "--excursions") o.excursions = std::strtoull(v, nullptr, 10);
        else if (a == "--seed") o.seed = std::strtoull(v, nullptr, 10);
        else if (a == "--cpu-threads") o.cpu_threads = static_cast<unsigned>(std::strtoul(v, nullptr, 10));
        else if (a == "--bench") o.bench = std::strtoull(v, nullptr, 10);
        else if (a == "--device-threads") o.device_threads = static_cast<unsigned>(std::strtoul(v, nullptr, 10));
        else if (a == "--case") o.only = v;
        else return usage();
    }
    if (o.excursions < 128 || o.cpu_threads == 0) return usage();

    g_emulate = o.emulate;
    if (o.emulate) {
        std::printf("device: EMULATED (the device loop on %u host threads; host math); kernels: %s\n",
                    o.device_threads ? o.device_threads : 2, ss::cuda::build_info().c_str());
    } else {
        const ss::cuda::DeviceInfo dev = ss::cuda::device_info();
        if (!dev.present) {
            std::fprintf(stderr, "gpu_check: no CUDA device found (%s)\n", dev.error.c_str());
            return 2;
        }
        std::printf("device: %s (sm_%d%d, %d SMs, %.0f GiB); kernels: %s\n", dev.name.c_str(), dev.major,
                    dev.minor, dev.multiprocessors, dev.memory_gib, ss::cuda::build_info().c_str());
    }
    std::printf("CPU: %u threads, colored-noise kernel: %s; CPU exp/log/log1p: %s\n", o.cpu_threads,
                ss::resolvent_kernel_name(),
                STICKSLIP_KERNEL_MATH_PORTABLE ? "portable (STICKSLIP_PORTABLE_MATH)" : "glibc");
    std::printf("seed %llu\n\n", static_cast<unsigned long long>(o.seed));
    std::printf("%-15s %7s %9s %6s %11s %11s %11s %11s %8s %s\n", "case", "N", "steps/exc", "capped", "CPU exc/s",
                "CPU steps/s", "GPU exc/s", "GPU steps/s", "GPU/CPU", "bitwise");

    bool all_equal = true;
    try {
        for (const Case& k : cases(o)) {
            if (!o.only.empty() && o.only != k.name) continue;
            const ss::PreparedEngine e = ss::prepare_engine(k.params, k.settings);
            ss::RunControl ctl;
            ctl.seed = o.seed;
            ctl.threads = o.cpu_threads;
            ctl.first_index = k.first;
            const ss::RunTotals cpu = ss::run_long_excursions(e, k.excursions, ctl); // timed, production path
            const std::vector<ss::ExcursionOutcome> ref = cpu_outcomes(e, o.seed, k.first, k.excursions, o.cpu_threads);
            std::vector<ss::ExcursionOutcome> gpu(k.excursions);
            const ss::cuda::DeviceTiming t = gpu_outcomes(e, o.seed, k.first, k.excursions, o.device_threads, gpu.data());

            std::uint64_t differ = 0;
            for (std::uint64_t i = 0; i < k.excursions; ++i) {
                if (same(ref[i], gpu[i])) continue;
                if (differ < 3)
                    std::fprintf(stderr,
                                 "  %s: excursion %llu differs: CPU U=%a t=%a steps=%llu capped=%d, GPU U=%a t=%a "
                                 "steps=%llu capped=%d\n",
                                 k.name.c_str(), static_cast<unsigned long long>(k.first + i), ref[i].displacement,
                                 ref[i].duration, static_cast<unsigned long long>(ref[i].work), ref[i].capped ? 1 : 0,
                                 gpu[i].displacement, gpu[i].duration, static_cast<unsigned long long>(gpu[i].work),
                                 gpu[i].capped ? 1 : 0);
                ++differ;
            }
            const ss::RunTotals ref_totals = ss::cuda::merge_outcomes(ref.data(), k.excursions);
            const ss::RunTotals gpu_totals = ss::cuda::merge_outcomes(gpu.data(), k.excursions);
            const bool runner_ok = same_sums(cpu, ref_totals);  // the reference is the runner's
            const bool sums_ok = same_sums(cpu, gpu_totals);    // the GPU's totals are the CPU run's
            const bool ok = differ == 0 && runner_ok && sums_ok;
            all_equal = all_equal && ok;

            const double steps = static_cast<double>(cpu.work), n = static_cast<double>(k.excursions);
            const double gpu_s = t.total_seconds;
            char verdict[96];
            if (ok) std::snprintf(verdict, sizeof verdict, "equal");
            else
                std::snprintf(verdict, sizeof verdict, "DIFFER (%llu excursions%s%s)",
                              static_cast<unsigned long long>(differ), runner_ok ? "" : ", CPU reference vs runner",
                              sums_ok ? "" : ", sums");
            std::printf("%-15s %7llu %9.0f %6llu %11.4g %11.4g %11.4g %11.4g %8.2f %s\n", k.name.c_str(),
                        static_cast<unsigned long long>(k.excursions), steps / n,
                        static_cast<unsigned long long>(cpu.capped), n / cpu.seconds, steps / cpu.seconds, n / gpu_s,
                        static_cast<double>(total_work(gpu)) / gpu_s, cpu.seconds / gpu_s, verdict);
            std::fflush(stdout);
        }

        if (o.bench > 0) {
            std::printf("\ndevice only, %llu excursions per case (GPU steps/s: kernel alone; whole call with "
                        "allocation and transfers)\n",
                        static_cast<unsigned long long>(o.bench));
            std::printf("%-15s %9s %12s %12s %12s %10s\n", "case", "threads", "kernel s", "steps/s", "call steps/s",
                        "exc/s");
            for (const Case& k : cases(o)) {
                if (!o.only.empty() && o.only != k.name) continue;
                if (k.name == "capped_partial") continue;
                const ss::PreparedEngine e = ss::prepare_engine(k.params, k.settings);
                const std::uint64_t n = k.settings.scheme == ss::Scheme::Event ? std::max<std::uint64_t>(o.bench / 64, 1)
                                                                               : o.bench;
                std::vector<ss::ExcursionOutcome> gpu(n);
                const ss::cuda::DeviceTiming t = gpu_outcomes(e, o.seed, 0, n, o.device_threads, gpu.data());
                const double steps = static_cast<double>(total_work(gpu));
                std::printf("%-15s %9u %12.3f %12.4g %12.4g %10.4g\n", k.name.c_str(), t.threads, t.kernel_seconds,
                            steps / t.kernel_seconds, steps / t.total_seconds,
                            static_cast<double>(n) / t.total_seconds);
                std::fflush(stdout);
            }
        }
    } catch (const std::exception& ex) {
        std::fprintf(stderr, "gpu_check: %s\n", ex.what());
        return 3;
    }
    std::printf("\n%s\n", all_equal ? "all cases bitwise equal" : "SOME OUTCOMES DIFFER");
    return all_equal ? 0 : 1;
}
