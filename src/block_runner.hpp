// Internal: the parallel, order-deterministic block driver behind every run.
//
// Samples [first_index, first_index + n) are cut into blocks of block_size
// consecutive indices (independent of the thread count). BlockSchedule hands
// the blocks of this process to the worker threads; a block is filled by one
// thread into its own accumulator; OrderedMerge merges finished blocks
// strictly in block order. Any accumulator whose merge is deterministic (the
// moment classes of estimators.hpp) therefore gives bitwise-identical results
// for any thread count. `Extra` carries what an observable accumulates
// besides (U, t).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
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

/// Which blocks this process computes (all of them, or b % ranks == rank in a
/// distributed run), how many threads share them, and the next one to take.
class BlockSchedule {
public:
    BlockSchedule(std::uint64_t n, const RunControl& ctl) : n_(n), rank_(ctl.rank), ranks_(ctl.ranks) {
        if (ctl.first_index > max_sample_index || n > max_sample_index - ctl.first_index)
            throw InvalidParameter("excursions", "sample indices exceed 2^56");
        blocks_ = (n + block_size - 1) / block_size;
        local_ = ranks_ > 1 ? (blocks_ > rank_ ? (blocks_ - rank_ + ranks_ - 1) / ranks_ : 0) : blocks_;
        threads_ = ctl.threads ? ctl.threads : std::thread::hardware_concurrency();
        threads_ = static_cast<unsigned>(std::clamp<std::uint64_t>(local_, 1, std::max(threads_, 1u)));
    }

    std::uint64_t blocks() const { return blocks_; }
    unsigned threads() const { return threads_; }
    /// The next block to compute, from any thread; nullopt when none is left.
    std::optional<std::uint64_t> next() {
        const std::uint64_t local = next_.fetch_add(1);
        if (local >= local_) return std::nullopt;
        return ranks_ > 1 ? rank_ + local * ranks_ : local;
    }
    /// Sample range [lo, hi) of block b, relative to the first index.
    std::uint64_t lo(std::uint64_t b) const { return b * block_size; }
    std::uint64_t hi(std::uint64_t b) const { return std::min(n_, lo(b) + block_size); }

private:
    std::uint64_t n_, blocks_ = 0, local_ = 0;
    unsigned rank_, ranks_, threads_ = 1;
    std::atomic<std::uint64_t> next_{0};
};

/// Merges finished blocks strictly in block order (so the result cannot
/// depend on timing), reports progress, and in a distributed run collects
/// this process's block records for the gather instead. Callers hold `mutex`.
template <class Extra, class Merge>
class OrderedMerge {
public:
    OrderedMerge(std::uint64_t n, const RunControl& ctl, Merge merge, RunTotals& totals, Extra& extra_total)
        : n_(n), ctl_(ctl), merge_(merge), totals_(totals), extra_(extra_total), start_(clock::now()),
          last_report_(start_) {}

    std::mutex mutex;

    /// Takes block b; returns false when the progress callback asked to stop.
    bool add(std::uint64_t b, BlockResult<Extra>&& r, std::uint64_t samples) {
        if (ctl_.ranks > 1) {
            records_.push_back(BlockRecord{b, r.moments, r.capped, r.work});
            merged_ += samples;
            return true;
        }
        pending_.emplace(b, std::move(r));
        for (auto it = pending_.find(next_); it != pending_.end(); it = pending_.find(next_)) {
            take(it->second.moments, it->second.capped, it->second.work);
            merge_(extra_, it->second.extra);
            merged_ = std::min(n_, (next_ + 1) * block_size);
            pending_.erase(it);
            ++next_;
        }
        if (!ctl_.progress) return true;
        const auto now = clock::now();
        if (std::chrono::duration<double>(now - last_report_).count() < ctl_.progress_interval) return true;
        last_report_ = now;
        return ctl_.progress(Progress{merged_, n_, seconds(), &totals_.moments});
    }

    /// After the workers: a distributed run gathers every process's records
    /// and merges them in block order; then the final progress report.
    void finish(std::uint64_t blocks) {
        if (ctl_.ranks > 1) {
            std::vector<BlockRecord> all = ctl_.combine(std::move(records_));
            std::sort(all.begin(), all.end(), [](const BlockRecord& a, const BlockRecord& c) { return a.block < c.block; });
            if (all.size() != blocks) throw std::runtime_error("distributed run: blocks missing after the gather");
            for (const auto& rec : all) take(rec.moments, rec.capped, rec.work);
            merged_ = n_;
        }
        totals_.seconds = seconds();
        if (ctl_.progress) ctl_.progress(Progress{merged_, n_, totals_.seconds, &totals_.moments});
    }

private:
    using clock = std::chrono::steady_clock;

    void take(const BivariateMoments& m, std::uint64_t capped, std::uint64_t work) {
        totals_.moments.merge(m);
        totals_.capped += capped;
        totals_.work += work;
    }
    double seconds() const { return std::chrono::duration<double>(clock::now() - start_).count(); }

    std::uint64_t n_;
    const RunControl& ctl_;
    Merge merge_;
    RunTotals& totals_;
    Extra& extra_;
    clock::time_point start_, last_report_;
    std::map<std::uint64_t, BlockResult<Extra>> pending_; // finished blocks waiting for their turn
    std::uint64_t next_ = 0, merged_ = 0;
    std::vector<BlockRecord> records_; // distributed only
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
    if (ctl.ranks > 1) {
        if constexpr (!std::is_empty_v<Extra>)
            throw InvalidParameter("ranks", "this computation cannot be split across processes (MPI): run it "
                                            "with one process");
        if (!ctl.combine || ctl.rank >= ctl.ranks) throw std::logic_error("RunControl: bad distributed settings");
    }
    BlockSchedule schedule(n, ctl);
    RunTotals totals;
    totals.requested = n;
    totals.threads = schedule.threads();
    extra_total = make_extra();
    OrderedMerge<Extra, Merge> merged(n, ctl, merge, totals, extra_total);
    std::atomic<bool> stop{false};
    std::exception_ptr error;
    bool cancelled = false;
    // The cancel flag is read before every sample; a cancel (or an error
    // elsewhere) stops every worker at its next sample.
    auto stopping = [&] {
        if (ctl.cancel && ctl.cancel->load(std::memory_order_relaxed)) {
            std::lock_guard<std::mutex> lock(merged.mutex);
            cancelled = true;
            stop = true;
        }
        return stop.load(std::memory_order_relaxed);
    };

    auto worker = [&] {
        try {
            while (!stop.load(std::memory_order_relaxed)) {
                const auto b = schedule.next();
                if (!b) return;
                BlockResult<Extra> r{BivariateMoments{}, 0, 0, make_extra()};
                const std::uint64_t lo = schedule.lo(*b), hi = schedule.hi(*b);
                auto add = [&r](const ExcursionOutcome& o) {
                    r.work += o.work;
                    if (o.capped) ++r.capped;
                    else r.moments.add(o.displacement, o.duration);
                };
                if constexpr (std::is_invocable_v<Sample&, std::uint64_t, std::uint64_t, ExcursionOutcome*, Extra&>) {
                    // A whole block at once (the SIMD lanes); it returns false when it saw ctl.cancel.
                    ExcursionOutcome outs[block_size];
                    if (stopping()) return;
                    if (!sample(ctl.first_index + lo, hi - lo, outs, r.extra)) return (void)stopping();
                    for (std::uint64_t k = lo; k < hi; ++k) add(outs[k - lo]); // in index order
                } else {
                    for (std::uint64_t k = lo; k < hi; ++k) {
                        if (stopping()) return;
                        add(sample(ctl.first_index + k, r.extra));
                    }
                }
                std::lock_guard<std::mutex> lock(merged.mutex);
                if (!cancelled && !merged.add(*b, std::move(r), hi - lo)) cancelled = stop = true;
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(merged.mutex);
            if (!error) error = std::current_exception();
            stop = true;
        }
    };

    if (schedule.threads() == 1) {
        worker();
    } else {
        std::vector<std::thread> pool;
        pool.reserve(schedule.threads());
        try {
            for (unsigned t = 0; t < schedule.threads(); ++t) pool.emplace_back(worker);
        } catch (...) { // could not start a thread: stop the others cleanly
            stop = true;
            for (auto& th : pool) th.join();
            throw;
        }
        for (auto& th : pool) th.join();
    }
    if (error) std::rethrow_exception(error);
    if (cancelled) throw RunCancelled();
    merged.finish(schedule.blocks());
    return totals;
}

} // namespace stickslip::detail
