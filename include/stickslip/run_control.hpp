// SPDX-License-Identifier: BSD-3-Clause
// stickslip/run_control.hpp -- how a Monte Carlo run is carried out, as
// opposed to what it computes: seed, threads, sample indices, the caller's
// callbacks and flags (progress, notes, cancel, graceful stop), checkpoints
// and the process split. Only the seed and the first index change a result's
// bits: sample k draws only from the stream (seed, purpose, k), and blocks of
// samples are merged into exact, order-free sums (stats/run_totals.hpp), so
// every result is bitwise identical for any thread count, any split of the
// blocks across processes and any interruption and resumption of a run.
#pragma once

/// \file
/// The run control of a Monte Carlo run. The comment at the top of this
/// header explains the design.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "stickslip/stats/estimators.hpp"

namespace stickslip {

class RunJournal; // checkpoint.hpp

/// Progress snapshot passed to RunControl::progress.
struct Progress {
    std::uint64_t done = 0;  ///< samples finished and merged
    std::uint64_t total = 0; ///< samples requested
    double seconds = 0.0;    ///< wall time so far
    const BivariateMoments* moments = nullptr; ///< merged so far (in index order)
};

/// How a run is carried out, as opposed to what it computes: seed, threads,
/// the sample indices, the caller's callbacks and flags, checkpoints and the
/// process split. None of it but the seed and first_index changes a result's
/// bits (this header, top).
struct RunControl {
    unsigned threads = 0;          ///< 0: the CPUs this process may use (default_threads(), threads.hpp)
    std::uint64_t seed = 1;        ///< user seed (the Philox key)
    std::uint64_t first_index = 0; ///< first sample index (for splitting runs)
    /// Called about every `progress_interval` seconds, after a block of
    /// samples is merged, on whichever worker thread merged it (so not
    /// necessarily the caller's thread; never concurrently), and once at the
    /// end; return false to cancel the run (throws RunCancelled).
    std::function<bool(const Progress&)> progress;
    /// Least time between two calls of `progress` [s]; 0 calls it after every
    /// merged block (which the Python module uses to check for Ctrl-C).
    double progress_interval = 1.0;
    /// Called, from the calling thread, before any work with each note about
    /// the run (a coarse step, a long run): for showing them at the start. The
    /// notes are in the result's warnings too.
    std::function<void(const std::string&)> notice;
    /// Called, from the calling thread, before any work, with the note on
    /// the run's predicted duration when that is long_run_seconds or more: for
    /// saying so at once where the notes are not shown at the start (the
    /// command without a terminal, a batch job's log).
    std::function<void(const std::string&)> long_run;
    /// Optional cancel flag, read by the workers before every sample: set it
    /// from any thread (a signal watcher, a GUI) to stop the run within one
    /// sample; the run then throws RunCancelled. Set after `stop` (a single
    /// process), it drops the blocks in flight instead, and the run returns
    /// the prefix of whole blocks finished before their round, as for `stop`.
    const std::atomic<bool>* cancel = nullptr;
    /// Optional stop flag, for a graceful stop (Ctrl-C): set it from any
    /// thread and the workers start no new block, finish those in flight and
    /// the run returns the result of a prefix of whole blocks, in index order
    /// (so no bias toward short samples), with RunTotals::interrupted set.
    /// Runs that consist of several calls of the driver (batches, sweep
    /// points) make no further call. A distributed run keeps the rounds that
    /// every process completed (see `journal`).
    const std::atomic<bool>* stop = nullptr;
    /// Optional journal (checkpoint.hpp): the run then completes its blocks in
    /// rounds of about a second (a distributed run always does, reducing its
    /// sums after each), records its state after every round, and, when the
    /// journal holds a saved state for this call, continues from it.
    RunJournal* journal = nullptr;
    /// @name Distributed runs
    /// MPI, see cli/distributed.hpp.
    /// @{

    /// This process's rank and the number of processes: this process
    /// computes only the blocks b with b % ranks == rank, in rounds of about a
    /// second. ranks == 1: a plain run (rank and reduce unused); ranks > 1
    /// needs rank < ranks and `reduce`.
    unsigned rank = 0, ranks = 1;
    /// The all-reduce, called once after every round, by every process alike
    /// (so the same number of times on each): it must replace `words` (this
    /// process's exact sums of the round, a sequence of ExactSum words: merge
    /// them chunk by chunk with ExactSum::merge_words) and `counts` (plain
    /// integers: add them) by their totals over every process, on every
    /// process. The sums are exact, so any reduction tree gives the result of
    /// a single process, bit for bit, in memory that does not grow with the run.
    std::function<void(std::vector<std::uint64_t>& words, std::vector<std::uint64_t>& counts)> reduce;
    /// @}
};

/// Throws InvalidParameter for a thread count above 4096.
void check_run_control(const RunControl& ctl);

} // namespace stickslip
