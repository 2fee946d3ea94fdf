// SPDX-License-Identifier: BSD-3-Clause
// stickslip/runner.hpp -- parallel, reproducible Monte Carlo runs.
//
// Sample k (a long excursion or a brute-force trajectory) draws only from the
// stream (seed, purpose, k). Samples are grouped in fixed blocks of
// `block_size` consecutive indices (independent of the thread count); each
// block's moments are computed by one thread in index order, then added into
// exact, order-free sums (moment_sums.hpp) as soon as the block is done. Hence
// every result is bitwise identical for any thread count, any split of the
// blocks across processes (reduced in any order) and any interruption and
// resumption of a run.
#pragma once

/// \file
/// Parallel, reproducible Monte Carlo runs: the run control and the block
/// driver's entry points. The comment at the top of this header explains the
/// design.

#include <atomic>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "stickslip/errors.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/kernels/corrector.hpp"
#include "stickslip/stats/control_variate.hpp"
#include "stickslip/stats/moment_sums.hpp"
#include "stickslip/params.hpp"

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
/// bits (runner.hpp, top).
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

/// Samples per block: the unit of work and of deterministic merging.
inline constexpr std::uint64_t block_size = 64;

/// Raw outcome of a run: the exact sums of (U, t) over completed samples and
/// the centred moments computed from them.
struct RunTotals {
    /// Exact sums of (U, t) (x = displacement U [m], y = duration t [s]) over
    /// the completed samples, capped ones excluded.
    ExactBivariateSums sums;
    BivariateMoments moments; ///< sums.moments()
    /// Samples asked for (completed, capped and, if interrupted, not run).
    std::uint64_t requested = 0;
    std::uint64_t capped = 0; ///< samples dropped by the runaway guard
    std::uint64_t work = 0;   ///< steps or events, all samples
    /// Wall time of the run [s]; a resumed run counts only this invocation.
    double seconds = 0.0;
    /// Worker threads used: RunControl::threads (0: default_threads()), at
    /// most one per block of this process.
    unsigned threads = 1;
    /// How `threads` was chosen: ThreadChoice::from ("option" for
    /// RunControl::threads > 0, else "hardware", "affinity", "cpu-quota",
    /// "slurm", each possibly with "+local-ranks"), with "+blocks" when this
    /// process had fewer blocks than that.
    std::string threads_from;
    bool interrupted = false; ///< stopped early (RunControl::stop): the sums are of a prefix of whole blocks
    std::uint64_t resumed = 0; ///< samples restored from a checkpoint rather than computed
    /// Long excursions run with a corrector (run_long_excursions' g): the
    /// exact sums of (U, t, M, M^2 - Q) over the completed excursions (empty
    /// otherwise).
    ControlVariateSums control_variate;
};

struct PreparedEngine; // prepared_engine.hpp

/// Throws InvalidParameter for a thread count above 4096.
void check_run_control(const RunControl& ctl);

/// N long excursions of a prepared engine (run.hpp), which is trusted.
RunTotals run_long_excursions(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl);
/// The same with the martingale of the corrector g accumulated in every
/// excursion (kernels/corrector.hpp) into RunTotals::control_variate; U and t,
/// and so `sums`, are bitwise those of the plain run. The engine must have a
/// martingale kernel (engine_has_martingale), else std::logic_error.
RunTotals run_long_excursions(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl,
                              const CorrectorTable& g);
/// Whether the prepared engine's kernels accumulate a martingale: the PDMP,
/// the inclusion engine's resolvent scheme, and its event scheme with
/// coloured noise; otherwise *why (if given) says why not, for a note.
bool engine_has_martingale(const PreparedEngine& e, std::string* why = nullptr);
/// The same, preparing (and so validating) the engine first.
RunTotals run_long_excursions(const ModelParams& p, const EngineSettings& s, std::uint64_t excursions,
                              const RunControl& ctl);

/// N brute-force trajectories on [0, horizon] from noise x0 [s^-1/2] and
/// velocity v0 [m/s], of a prepared engine. Moments are of (U(horizon), horizon).
RunTotals run_bruteforce(const PreparedEngine& e, double horizon, double x0, double v0, std::uint64_t trajectories,
                         const RunControl& ctl);
/// The same, preparing (and so validating) the engine and the start first.
RunTotals run_bruteforce(const ModelParams& p, const EngineSettings& s, double horizon, double x0,
                         double v0, std::uint64_t trajectories, const RunControl& ctl);

/// Generic driver used by both: calls sample(index) for every index in
/// [first_index, first_index + n) in parallel; blocks are merged exactly.
RunTotals run_samples(std::uint64_t n, const RunControl& ctl,
                      const std::function<ExcursionOutcome(std::uint64_t)>& sample);

} // namespace stickslip
