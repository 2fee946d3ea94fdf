// Internal: the parallel block driver behind every run.
//
// Samples [first_index, first_index + n) are cut into blocks of block_size
// consecutive indices (independent of the thread count). BlockSchedule hands
// the blocks of this process to the worker threads; a block is filled by one
// thread into its own accumulators, in index order; as soon as it is done it
// is added into the run's exact, order-free sums (moment_sums.hpp), whoever
// finishes first. So a result is bitwise the same for any thread count,
// process split and timing, and no thread holds more than the block it is
// working on. What an observable accumulates besides (U, t) comes in two
// forms: `Block`, filled per block in sample order, and `Total`, its exact
// sum (total.add_block(block), total.merge(other), and words for MPI).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <vector>

#include "stickslip/moment_sums.hpp"
#include "stickslip/params.hpp"
#include "stickslip/rng.hpp"
#include "stickslip/runner.hpp"

namespace stickslip::detail {

/// What a run that accumulates nothing besides (U, t) carries.
struct NoBlock {};
struct NoTotal {
    void add_block(const NoBlock&) {}
    void merge(const NoTotal&) {}
    std::size_t words() const { return 0; }
    void to_words(std::uint64_t*) const {}
    void assign_words(const std::uint64_t*) {}
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

/// The run's exact sums, added to as blocks finish (callers hold `mutex`), the
/// progress reports, and the reduction across processes at the end.
template <class Block, class Total>
class BlockSums {
public:
    BlockSums(std::uint64_t n, const RunControl& ctl, RunTotals& totals, Total& total)
        : n_(n), ctl_(ctl), totals_(totals), total_(total), start_(clock::now()), last_report_(start_) {}

    std::mutex mutex;

    /// Takes a finished block; returns false when the progress callback asked to stop.
    bool add(const BivariateMoments& moments, const Block& block, std::uint64_t capped, std::uint64_t work,
             std::uint64_t samples) {
        totals_.sums.add_block(moments);
        total_.add_block(block);
        totals_.capped += capped;
        totals_.work += work;
        done_ += samples;
        if (!ctl_.progress) return true;
        const auto now = clock::now();
        if (std::chrono::duration<double>(now - last_report_).count() < ctl_.progress_interval) return true;
        last_report_ = now;
        const BivariateMoments so_far = totals_.sums.moments();
        return ctl_.progress(Progress{done_, n_, seconds(), &so_far});
    }

    /// After the workers: a distributed run adds up every process's sums;
    /// then the moments and the final progress report.
    void finish() {
        if (ctl_.ranks > 1) {
            std::vector<std::uint64_t> words(ExactBivariateSums::words + total_.words());
            totals_.sums.to_words(words.data());
            total_.to_words(words.data() + ExactBivariateSums::words);
            std::vector<std::uint64_t> counts{totals_.capped, totals_.work, done_};
            ctl_.reduce(words, counts);
            totals_.sums = ExactBivariateSums::from_words(words.data());
            total_.assign_words(words.data() + ExactBivariateSums::words);
            totals_.capped = counts[0];
            totals_.work = counts[1];
            done_ = counts[2];
        }
        totals_.moments = totals_.sums.moments();
        totals_.seconds = seconds();
        if (ctl_.progress) ctl_.progress(Progress{done_, n_, totals_.seconds, &totals_.moments});
    }

private:
    using clock = std::chrono::steady_clock;
    double seconds() const { return std::chrono::duration<double>(clock::now() - start_).count(); }

    std::uint64_t n_;
    const RunControl& ctl_;
    RunTotals& totals_;
    Total& total_;
    clock::time_point start_, last_report_;
    std::uint64_t done_ = 0;
};

/// make_block() -> Block (an empty accumulator); sample(index, Block&) ->
/// ExcursionOutcome, adding to the block only when the outcome is not
/// capped, or the block form sample(first, count, ExcursionOutcome* out,
/// Block&) -> bool (false: cancelled, out incomplete), which fills a block of
/// outcomes at once. `total` receives the exact sum of every block.
template <class Block, class Total, class MakeBlock, class Sample>
RunTotals run_blocks(std::uint64_t n, const RunControl& ctl, MakeBlock make_block, Sample sample, Total& total) {
    if (ctl.ranks > 1 && (!ctl.reduce || ctl.rank >= ctl.ranks))
        throw std::logic_error("RunControl: bad distributed settings");
    BlockSchedule schedule(n, ctl);
    RunTotals totals;
    totals.requested = n;
    totals.threads = schedule.threads();
    BlockSums<Block, Total> sums(n, ctl, totals, total);
    std::atomic<bool> stop{false};
    std::exception_ptr error;
    bool cancelled = false;
    // The cancel flag is read before every sample; a cancel (or an error
    // elsewhere) stops every worker at its next sample.
    auto stopping = [&] {
        if (ctl.cancel && ctl.cancel->load(std::memory_order_relaxed)) {
            std::lock_guard<std::mutex> lock(sums.mutex);
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
                BivariateMoments moments;
                Block block = make_block();
                std::uint64_t capped = 0, work = 0;
                const std::uint64_t lo = schedule.lo(*b), hi = schedule.hi(*b);
                auto add = [&](const ExcursionOutcome& o) {
                    work += o.work;
                    if (o.capped) ++capped;
                    else moments.add(o.displacement, o.duration);
                };
                if constexpr (std::is_invocable_v<Sample&, std::uint64_t, std::uint64_t, ExcursionOutcome*, Block&>) {
                    // A whole block at once (the SIMD lanes); it returns false when it saw ctl.cancel.
                    ExcursionOutcome outs[block_size];
                    if (stopping()) return;
                    if (!sample(ctl.first_index + lo, hi - lo, outs, block)) return (void)stopping();
                    for (std::uint64_t k = lo; k < hi; ++k) add(outs[k - lo]); // in index order
                } else {
                    for (std::uint64_t k = lo; k < hi; ++k) {
                        if (stopping()) return;
                        add(sample(ctl.first_index + k, block));
                    }
                }
                std::lock_guard<std::mutex> lock(sums.mutex);
                if (!cancelled && !sums.add(moments, block, capped, work, hi - lo)) cancelled = stop = true;
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(sums.mutex);
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
    sums.finish();
    return totals;
}

} // namespace stickslip::detail
