#include "stickslip/runner.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

#include "stickslip/inclusion.hpp"
#include "stickslip/pdmp.hpp"
#include "stickslip/rng.hpp"

namespace stickslip {

namespace {
struct BlockResult {
    BivariateMoments moments;
    std::uint64_t capped = 0;
    std::uint64_t work = 0;
};
} // namespace

RunTotals run_samples(std::uint64_t n, const RunControl& ctl,
                      const std::function<ExcursionOutcome(std::uint64_t)>& sample) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    if (ctl.first_index > max_sample_index || n > max_sample_index - ctl.first_index)
        throw InvalidParameter("excursions", "sample indices exceed 2^56");
    unsigned threads = ctl.threads ? ctl.threads : std::thread::hardware_concurrency();
    if (threads == 0) threads = 1;
    const std::uint64_t nblocks = (n + block_size - 1) / block_size;
    if (nblocks < threads) threads = static_cast<unsigned>(std::max<std::uint64_t>(nblocks, 1));

    RunTotals totals;
    totals.requested = n;
    totals.threads = threads;

    std::atomic<std::uint64_t> next_block{0};
    std::atomic<bool> stop{false};
    std::mutex merge_mutex;
    std::map<std::uint64_t, BlockResult> pending; // finished blocks waiting for their turn
    std::uint64_t next_to_merge = 0;
    std::uint64_t merged_samples = 0;
    auto last_report = start;
    std::exception_ptr error;
    bool cancelled = false;

    auto seconds_since_start = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };

    auto worker = [&] {
        try {
            for (;;) {
                if (stop.load(std::memory_order_relaxed)) return;
                const std::uint64_t b = next_block.fetch_add(1);
                if (b >= nblocks) return;
                BlockResult r;
                const std::uint64_t lo = b * block_size, hi = std::min(n, lo + block_size);
                for (std::uint64_t k = lo; k < hi; ++k) {
                    const ExcursionOutcome o = sample(ctl.first_index + k);
                    r.work += o.work;
                    if (o.capped) ++r.capped;
                    else r.moments.add(o.displacement, o.duration);
                }
                std::lock_guard<std::mutex> lock(merge_mutex);
                pending.emplace(b, std::move(r));
                // Merge strictly in block order: the result cannot depend on timing.
                for (auto it = pending.find(next_to_merge); it != pending.end(); it = pending.find(next_to_merge)) {
                    totals.moments.merge(it->second.moments);
                    totals.capped += it->second.capped;
                    totals.work += it->second.work;
                    merged_samples = std::min(n, (next_to_merge + 1) * block_size);
                    pending.erase(it);
                    ++next_to_merge;
                }
                if (ctl.progress && !cancelled) {
                    const auto now = clock::now();
                    if (std::chrono::duration<double>(now - last_report).count() >= ctl.progress_interval) {
                        last_report = now;
                        Progress pr{merged_samples, n, seconds_since_start(), &totals.moments};
                        if (!ctl.progress(pr)) {
                            cancelled = true;
                            stop = true;
                        }
                    }
                }
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(merge_mutex);
            if (!error) error = std::current_exception();
            stop = true;
        }
    };

    if (threads == 1) {
        worker();
    } else {
        std::vector<std::thread> pool;
        pool.reserve(threads);
        try {
            for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
        } catch (...) { // could not start a thread: stop the others cleanly
            stop = true;
            for (auto& th : pool) th.join();
            throw;
        }
        for (auto& th : pool) th.join();
    }
    if (error) std::rethrow_exception(error);
    if (cancelled) throw RunCancelled();
    totals.seconds = seconds_since_start();
    if (ctl.progress) {
        Progress pr{merged_samples, n, totals.seconds, &totals.moments};
        ctl.progress(pr);
    }
    return totals;
}

RunTotals run_long_excursions(const ModelParams& p, const EngineSettings& s, std::uint64_t excursions,
                              const RunControl& ctl) {
    const std::uint64_t seed = ctl.seed;
    if (s.engine == Engine::Pdmp) {
        const PdmpConstants c = make_pdmp_constants(p, s);
        return run_samples(excursions, ctl, [&c, seed](std::uint64_t k) {
            CounterRng rng(seed, StreamPurpose::LongExcursion, k);
            return pdmp_long_excursion(c, rng);
        });
    }
    const InclusionConstants c = make_inclusion_constants(p, s);
    return run_samples(excursions, ctl, [&c, seed](std::uint64_t k) {
        CounterRng rng(seed, StreamPurpose::LongExcursion, k);
        return inclusion_long_excursion(c, rng);
    });
}

RunTotals run_bruteforce(const ModelParams& p, const EngineSettings& s, double horizon, double x0, double v0,
                         std::uint64_t trajectories, const RunControl& ctl) {
    if (!std::isfinite(horizon) || horizon <= 0)
        throw InvalidParameter("time", "time must be a finite number > 0 (s)");
    if (!std::isfinite(v0)) throw InvalidParameter("v0", "v0 must be a finite number (m/s)");
    const std::uint64_t seed = ctl.seed;
    if (s.engine == Engine::Pdmp) {
        const PdmpConstants c = make_pdmp_constants(p, s);
        return run_samples(trajectories, ctl, [&c, seed, horizon, x0, v0](std::uint64_t k) {
            CounterRng rng(seed, StreamPurpose::BruteForce, k);
            return pdmp_trajectory(c, x0, v0, horizon, rng);
        });
    }
    const InclusionConstants c = make_inclusion_constants(p, s);
    const double nsteps_real = std::nearbyint(horizon / s.dt);
    if (nsteps_real < 1 || nsteps_real > 1e15)
        throw InvalidParameter("time", "time/dt must be between 1 and 1e15 steps");
    const auto nsteps = static_cast<std::uint64_t>(nsteps_real);
    return run_samples(trajectories, ctl, [&c, seed, x0, v0, nsteps](std::uint64_t k) {
        CounterRng rng(seed, StreamPurpose::BruteForce, k);
        return inclusion_trajectory(c, x0, v0, nsteps, rng);
    });
}

} // namespace stickslip
