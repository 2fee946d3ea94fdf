// Internal: the parallel, order-deterministic block driver behind every run.
//
// Samples [first_index, first_index + n) are cut into blocks of block_size
// consecutive indices (independent of the thread count). A block is filled by
// one thread into its own accumulator; finished blocks are merged strictly in
// block order. Any accumulator whose merge is deterministic (the moment classes
// of estimators.hpp) therefore gives bitwise-identical results for any thread
// count. `Extra` carries what an observable accumulates besides (U, t).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

#include "stickslip/params.hpp"
#include "stickslip/rng.hpp"
#include "stickslip/runner.hpp"

namespace stickslip::detail {

template <class Extra>
struct BlockResult {
    BivariateMoments moments;
    std::uint64_t capped = 0;
    std::uint64_t work = 0;
    Extra extra;
};

/// make_extra() -> Extra (an empty accumulator); sample(index, Extra&) ->
/// ExcursionOutcome, adding to Extra only when the outcome is not capped, or
/// the block form sample(first, count, ExcursionOutcome* out, Extra&) -> bool
/// (false: cancelled, out incomplete), which fills a block of outcomes at once;
/// merge(Extra& into, const Extra& from). Returns the totals; `extra_total`
/// receives the merged Extra.
template <class Extra, class MakeExtra, class Sample, class Merge>
RunTotals run_blocks(std::uint64_t n, const RunControl& ctl, MakeExtra make_extra, Sample sample, Merge merge,
                     Extra& extra_total) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    if (ctl.first_index > max_sample_index || n > max_sample_index - ctl.first_index)
        throw InvalidParameter("excursions", "sample indices exceed 2^56");
    if (ctl.threads > 4096) throw InvalidParameter("threads", "threads must be between 0 and 4096");
    unsigned threads = ctl.threads ? ctl.threads : std::thread::hardware_concurrency();
    if (threads == 0) threads = 1;
    const std::uint64_t nblocks = (n + block_size - 1) / block_size;
    if (nblocks < threads) threads = static_cast<unsigned>(std::max<std::uint64_t>(nblocks, 1));

    // Distributed: only this process's share of the blocks, merged after the
    // all-gather (see RunControl::combine).
    const bool distributed = ctl.ranks > 1;
    if (distributed) {
        if constexpr (!std::is_empty_v<Extra>)
            throw InvalidParameter("ranks", "this computation cannot be split across processes (MPI): run it "
                                            "with one process");
        if (!ctl.combine || ctl.rank >= ctl.ranks) throw std::logic_error("RunControl: bad distributed settings");
    }
    const std::uint64_t local_blocks =
        distributed ? (nblocks > ctl.rank ? (nblocks - ctl.rank + ctl.ranks - 1) / ctl.ranks : 0) : nblocks;
    if (local_blocks < threads) threads = static_cast<unsigned>(std::max<std::uint64_t>(local_blocks, 1));
    std::vector<BlockRecord> records; // distributed only

    RunTotals totals;
    totals.requested = n;
    totals.threads = threads;
    extra_total = make_extra();

    std::atomic<std::uint64_t> next_block{0};
    std::atomic<bool> stop{false};
    std::mutex merge_mutex;
    std::map<std::uint64_t, BlockResult<Extra>> pending; // finished blocks waiting for their turn
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
                const std::uint64_t local = next_block.fetch_add(1);
                if (local >= local_blocks) return;
                const std::uint64_t b = distributed ? ctl.rank + local * ctl.ranks : local;
                BlockResult<Extra> r{BivariateMoments{}, 0, 0, make_extra()};
                const std::uint64_t lo = b * block_size, hi = std::min(n, lo + block_size);
                auto cancel_requested = [&] {
                    if (ctl.cancel && ctl.cancel->load(std::memory_order_relaxed)) {
                        std::lock_guard<std::mutex> lock(merge_mutex);
                        cancelled = true;
                        stop = true;
                    }
                    return stop.load(std::memory_order_relaxed);
                };
                auto add = [&r](const ExcursionOutcome& o) {
                    r.work += o.work;
                    if (o.capped) ++r.capped;
                    else r.moments.add(o.displacement, o.duration);
                };
                if constexpr (std::is_invocable_v<Sample&, std::uint64_t, std::uint64_t, ExcursionOutcome*, Extra&>) {
                    // A whole block at once (the SIMD lanes); it returns false when it saw ctl.cancel.
                    ExcursionOutcome outs[block_size];
                    if (cancel_requested()) return;
                    if (!sample(ctl.first_index + lo, hi - lo, outs, r.extra)) {
                        cancel_requested();
                        return;
                    }
                    for (std::uint64_t k = lo; k < hi; ++k) add(outs[k - lo]); // in index order
                } else {
                    for (std::uint64_t k = lo; k < hi; ++k) {
                        if (cancel_requested()) return;
                        add(sample(ctl.first_index + k, r.extra));
                    }
                }
                std::lock_guard<std::mutex> lock(merge_mutex);
                if (distributed) {
                    records.push_back(BlockRecord{b, r.moments, r.capped, r.work});
                    merged_samples += hi - lo;
                    continue;
                }
                pending.emplace(b, std::move(r));
                // Merge strictly in block order: the result cannot depend on timing.
                for (auto it = pending.find(next_to_merge); it != pending.end(); it = pending.find(next_to_merge)) {
                    totals.moments.merge(it->second.moments);
                    totals.capped += it->second.capped;
                    totals.work += it->second.work;
                    merge(extra_total, it->second.extra);
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
    if (distributed) {
        std::vector<BlockRecord> all = ctl.combine(std::move(records));
        std::sort(all.begin(), all.end(), [](const BlockRecord& a, const BlockRecord& c) { return a.block < c.block; });
        if (all.size() != nblocks) throw std::runtime_error("distributed run: blocks missing after the gather");
        for (const auto& rec : all) {
            totals.moments.merge(rec.moments);
            totals.capped += rec.capped;
            totals.work += rec.work;
        }
        merged_samples = n;
    }
    totals.seconds = seconds_since_start();
    if (ctl.progress) {
        Progress pr{merged_samples, n, totals.seconds, &totals.moments};
        ctl.progress(pr);
    }
    return totals;
}

} // namespace stickslip::detail
