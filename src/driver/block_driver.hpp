// SPDX-License-Identifier: BSD-3-Clause
// Internal: the parallel block driver behind every run.
//
// Samples [first_index, first_index + n) are cut into blocks of block_size
// consecutive indices (independent of the thread count). RoundSchedule hands
// the blocks of this process to the worker threads; a block is filled by one
// thread into its own accumulators, in index order; as soon as it is done it
// is added into the run's exact, order-free sums (moment_sums.hpp), whoever
// finishes first. So a result is bitwise the same for any thread count,
// process split and timing, and no thread holds more than the block it is
// working on. What an observable accumulates besides (U, t) comes in two
// forms: `Block`, filled per block in sample order, and `Total`, its exact
// sum (total.add_block(block), total.merge(other), and words for MPI and
// checkpoints).
//
// Rounds: a run with a journal (checkpoints), a stop flag or split across
// processes completes its blocks in rounds of consecutive blocks, sized to last about a
// second. A round ends when all its blocks are done; a distributed run then
// reduces the round's sums over every process (one all-reduce of the sums'
// words, never of per-block records). So after each round every process holds
// the sums of the same prefix of blocks, which is what a checkpoint saves and
// what an interrupted run reports. A plain run is one round.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <concepts>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <vector>

#include "stickslip/checkpoint.hpp"
#include "stickslip/stats/moment_sums.hpp"
#include "stickslip/params.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/run_control.hpp"
#include "stickslip/stats/run_totals.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/threads.hpp"

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

/// The blocks of one round, [b0, b1), that this process computes (all of
/// them, or those with b % ranks == rank), handed out to the worker threads in
/// index order.
class RoundSchedule {
public:
    RoundSchedule(std::uint64_t b0, std::uint64_t b1, unsigned rank, unsigned ranks) : ranks_(ranks) {
        first_ = b0 + (rank + ranks - b0 % ranks) % ranks;
        local_ = first_ < b1 ? (b1 - first_ + ranks - 1) / ranks : 0;
    }
    std::uint64_t local() const { return local_; }
    /// The next block to compute, from any thread; nullopt when none is left.
    std::optional<std::uint64_t> next() {
        const std::uint64_t k = next_.fetch_add(1);
        if (k >= local_) return std::nullopt;
        return first_ + k * ranks_;
    }
    /// Blocks handed out so far: with every one finished, this process's
    /// blocks of the round are the first this many.
    std::uint64_t handed_out() const { return std::min(next_.load(), local_); }

private:
    std::uint64_t first_ = 0, local_ = 0;
    unsigned ranks_;
    std::atomic<std::uint64_t> next_{0};
};

/// What a run's total of an observable must offer: merging another total
/// exactly (any order, any process, the same bits) and its state as words of
/// ExactSum, for the all-reduce and the checkpoint. (Adding a block,
/// add_block(const Block&), depends on the block type.)
template <class T>
concept BlockTotal = requires(T& t, const T& other, std::uint64_t* w) {
    t.merge(other);
    { other.words() } -> std::convertible_to<std::size_t>;
    other.to_words(w);
    t.assign_words(w);
};

/// Sums of (U, t), of the observable, and the integer counts, as one unit.
template <class Total>
struct RoundSums {
    ExactBivariateSums sums;
    Total total;
    std::uint64_t capped = 0, work = 0, done = 0;

    void merge(const RoundSums& o) {
        sums.merge(o.sums);
        total.merge(o.total);
        capped += o.capped;
        work += o.work;
        done += o.done;
    }
    std::size_t words() const { return ExactBivariateSums::words + total.words(); }
    void to_words(std::uint64_t* w) const {
        sums.to_words(w);
        total.to_words(w + ExactBivariateSums::words);
    }
    void assign_words(const std::uint64_t* w) {
        sums = ExactBivariateSums::from_words(w);
        total.assign_words(w + ExactBivariateSums::words);
    }
};

inline std::uint64_t block_count(std::uint64_t n) { return (n + block_size - 1) / block_size; }

/// make_block() -> Block (an empty accumulator); sample(index, Block&) ->
/// ExcursionOutcome, adding to the block only when the outcome is not
/// capped, or the block form sample(first, count, ExcursionOutcome* out,
/// Block&) -> bool (false: cancelled, out incomplete), which fills a block of
/// outcomes at once. `total` (empty on entry) receives the exact sum of every
/// block.
template <class Block, BlockTotal Total, class MakeBlock, class Sample>
RunTotals run_blocks(std::uint64_t n, const RunControl& ctl, MakeBlock make_block, Sample sample, Total& total) {
    using clock = std::chrono::steady_clock;
    if (ctl.ranks > 1 && (!ctl.reduce || ctl.rank >= ctl.ranks))
        throw std::logic_error("RunControl: bad distributed settings");
    if (ctl.first_index > max_sample_index || n > max_sample_index - ctl.first_index)
        throw InvalidParameter("excursions", "sample indices exceed 2^56");
    const std::uint64_t blocks = block_count(n);
    const unsigned ranks = ctl.ranks > 1 ? ctl.ranks : 1, rank = ranks > 1 ? ctl.rank : 0;
    const ThreadChoice chosen = ctl.threads ? ThreadChoice{ctl.threads, "option"} : default_threads();
    const std::uint64_t local_blocks = blocks > rank ? (blocks - rank + ranks - 1) / ranks : 0;
    const unsigned threads =
        static_cast<unsigned>(std::clamp<std::uint64_t>(local_blocks, 1, std::max(chosen.threads, 1u)));

    RunTotals totals;
    totals.requested = n;
    totals.threads = threads;
    totals.threads_from = chosen.from + (threads < chosen.threads ? "+blocks" : "");
    const Total empty = total;
    RoundSums<Total> done{{}, empty}; // the prefix [0, b0) of blocks, over every process
    std::uint64_t b0 = 0;
    RunJournal::Call* call = ctl.journal ? &ctl.journal->begin_call(n, ctl.first_index, done.words()) : nullptr;
    auto save = [&] {
        if (!call) return;
        call->blocks_done = b0;
        call->complete = b0 == blocks;
        call->counts = {done.capped, done.work, done.done};
        done.to_words(call->words.data());
    };
    if (call && (call->blocks_done > 0 || call->complete)) {
        if (call->counts.size() != 3 || call->blocks_done > blocks)
            throw InvalidParameter("resume", "cannot resume: the checkpoint's state does not fit this run");
        done.assign_words(call->words.data());
        done.capped = call->counts[0];
        done.work = call->counts[1];
        done.done = call->counts[2];
        b0 = call->blocks_done;
        totals.resumed = done.done;
    }

    const auto start = clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
    auto last_report = start;
    // A first report at once: a run whose first block is slow shows it has started.
    if (ctl.progress && b0 < blocks && !ctl.progress(Progress{done.done, n, 0.0, nullptr})) throw RunCancelled();
    // With a stop flag too: a stopped run that must drop its blocks in
    // flight (RunControl::cancel after stop) then loses a round, not the run.
    const bool rounds = ctl.journal || ranks > 1 || ctl.stop;
    // Rounds of about a second: the time a stopped distributed run may lose,
    // and the granularity of checkpoints (shorter when they are asked for more often).
    const double round_seconds = ctl.journal ? std::min(1.0, ctl.journal->every()) : 1.0;
    std::uint64_t round_blocks = rounds ? std::uint64_t{4} * threads * ranks : blocks;

    std::exception_ptr error;
    bool cancelled = false;
    while (b0 < blocks && !totals.interrupted) {
        const std::uint64_t b1 = std::min(blocks, b0 + std::max<std::uint64_t>(round_blocks, 1));
        RoundSchedule schedule(b0, b1, rank, ranks);
        RoundSums<Total> round{{}, empty};
        std::mutex mutex;
        std::atomic<bool> halt{false}; // a cancel or an error: stop at the next sample
        bool stopped = false;          // the stop flag was seen: no new block
        const auto round_start = clock::now();
        // The cancel flag is read before every sample; a cancel (or an error
        // elsewhere) stops every worker at its next sample.
        auto halting = [&] {
            if (ctl.cancel && ctl.cancel->load(std::memory_order_relaxed)) {
                std::lock_guard<std::mutex> lock(mutex);
                cancelled = true;
                halt = true;
            }
            return halt.load(std::memory_order_relaxed);
        };
        auto report = [&]() -> bool { // under `mutex`
            if (!ctl.progress) return true;
            const auto now = clock::now();
            if (std::chrono::duration<double>(now - last_report).count() < ctl.progress_interval) return true;
            last_report = now;
            ExactBivariateSums merged = done.sums;
            merged.merge(round.sums);
            const BivariateMoments so_far = merged.moments();
            const std::uint64_t so_far_done = std::min(n, done.done + round.done * ranks);
            return ctl.progress(Progress{so_far_done, n, seconds(), &so_far});
        };

        auto worker = [&] {
            try {
                for (;;) {
                    if (halt.load(std::memory_order_relaxed)) return;
                    if (ctl.stop && ctl.stop->load(std::memory_order_relaxed)) {
                        std::lock_guard<std::mutex> lock(mutex);
                        stopped = true;
                        return;
                    }
                    const auto b = schedule.next();
                    if (!b) return;
                    BivariateMoments moments;
                    Block block = make_block();
                    std::uint64_t capped = 0, work = 0;
                    const std::uint64_t lo = *b * block_size, hi = std::min(n, lo + block_size);
                    auto add = [&](const ExcursionOutcome& o) {
                        work += o.work;
                        if (o.capped) ++capped;
                        else moments.add(o.displacement, o.duration);
                    };
                    if constexpr (std::is_invocable_v<Sample&, std::uint64_t, std::uint64_t, ExcursionOutcome*,
                                                      Block&>) {
                        // A whole block at once (the SIMD lanes); it returns false when it saw ctl.cancel.
                        ExcursionOutcome outs[block_size];
                        if (halting()) return;
                        if (!sample(ctl.first_index + lo, hi - lo, outs, block)) return (void)halting();
                        for (std::uint64_t k = lo; k < hi; ++k) add(outs[k - lo]); // in index order
                    } else {
                        for (std::uint64_t k = lo; k < hi; ++k) {
                            if (halting()) return;
                            add(sample(ctl.first_index + k, block));
                        }
                    }
                    std::lock_guard<std::mutex> lock(mutex);
                    if (halt) return;
                    round.sums.add_block(moments);
                    round.total.add_block(block);
                    round.capped += capped;
                    round.work += work;
                    round.done += hi - lo;
                    if (!report()) cancelled = halt = true;
                }
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex);
                if (!error) error = std::current_exception();
                halt = true;
            }
        };

        const unsigned round_threads =
            static_cast<unsigned>(std::clamp<std::uint64_t>(schedule.local(), 1, threads));
        if (round_threads == 1) {
            worker();
        } else {
            std::vector<std::thread> pool;
            pool.reserve(round_threads);
            try {
                for (unsigned t = 0; t < round_threads; ++t) pool.emplace_back(worker);
            } catch (...) { // could not start a thread: stop the others cleanly
                halt = true;
                for (auto& th : pool) th.join();
                throw;
            }
            for (auto& th : pool) th.join();
        }
        if (error) std::rethrow_exception(error);
        if (cancelled) {
            // A cancel after a stop request (the command line's deadline for
            // the blocks in flight, when they take minutes): the round's
            // blocks are dropped and the run returns the prefix before it.
            // A distributed run cannot: its processes would disagree.
            if (!(ctl.stop && ctl.stop->load(std::memory_order_relaxed)) || ranks > 1) throw RunCancelled();
            totals.interrupted = b0 < blocks;
            save();
            if (call) ctl.journal->updated();
            break;
        }

        const double elapsed = std::chrono::duration<double>(clock::now() - round_start).count();
        double mean_elapsed = elapsed;
        if (ranks > 1) {
            // One all-reduce per round: the round's exact sums and counts, whether
            // every process finished its share and whether any was stopped.
            std::vector<std::uint64_t> words(round.words());
            round.to_words(words.data());
            const bool finished = schedule.handed_out() == schedule.local();
            std::vector<std::uint64_t> counts{round.capped, round.work, round.done, finished ? 0u : 1u,
                                              stopped ? 1u : 0u,
                                              static_cast<std::uint64_t>(std::llround(elapsed * 1e6))};
            ctl.reduce(words, counts);
            stopped = counts[4] > 0;
            mean_elapsed = static_cast<double>(counts[5]) * 1e-6 / ranks;
            if (counts[3] == 0) { // every process finished the round: keep it
                round.assign_words(words.data());
                round.capped = counts[0];
                round.work = counts[1];
                round.done = counts[2];
                done.merge(round);
                b0 = b1;
            } // else the round is dropped: the processes' prefixes differ
        } else {
            // Every block handed out is finished: the round's blocks form a prefix.
            done.merge(round);
            b0 += schedule.handed_out();
        }
        if (stopped && b0 < blocks) totals.interrupted = true;
        save();
        if (call) ctl.journal->updated();
        if (rounds) {
            // The next round lasts about round_seconds (at most 16 times longer than this one).
            const double scale = mean_elapsed > 0 ? round_seconds / mean_elapsed : 16.0;
            const double next = static_cast<double>(round_blocks) * std::clamp(scale, 0.25, 16.0);
            round_blocks = std::max<std::uint64_t>(static_cast<std::uint64_t>(next), std::uint64_t{threads} * ranks);
        }
    }

    totals.sums = done.sums;
    total = done.total;
    totals.capped = done.capped;
    totals.work = done.work;
    totals.moments = totals.sums.moments();
    totals.seconds = seconds();
    if (ctl.progress) ctl.progress(Progress{done.done, n, totals.seconds, &totals.moments});
    return totals;
}

} // namespace stickslip::detail
