// stickslip/runner.hpp -- parallel, reproducible Monte Carlo runs.
//
// Sample k (a long excursion or a brute-force trajectory) draws only from the
// stream (seed, purpose, k). Samples are grouped in fixed blocks of
// `block_size` consecutive indices (independent of the thread count); each
// block's moments are computed by one thread, and blocks are merged strictly in
// index order. Hence every result is bitwise identical for any thread count,
// and a split of the block range across processes reproduces it as long as the
// partial results are merged in the same order.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "estimators.hpp"
#include "excursion.hpp"
#include "params.hpp"

namespace stickslip {

/// Progress snapshot passed to RunControl::progress.
struct Progress {
    std::uint64_t done = 0;  ///< samples finished and merged
    std::uint64_t total = 0; ///< samples requested
    double seconds = 0.0;    ///< wall time so far
    const BivariateMoments* moments = nullptr; ///< merged so far (in index order)
};

/// One block's result, as exchanged between processes in a distributed run.
struct BlockRecord {
    std::uint64_t block = 0; ///< block number (samples block*64 ... relative to first_index)
    BivariateMoments moments;
    std::uint64_t capped = 0;
    std::uint64_t work = 0;
};

struct RunControl {
    unsigned threads = 0;          ///< 0: all hardware threads
    std::uint64_t seed = 1;        ///< user seed (the Philox key)
    std::uint64_t first_index = 0; ///< first sample index (for splitting runs)
    /// Called about every `progress_interval` seconds, after a block of
    /// samples is merged, on whichever worker thread merged it (so not
    /// necessarily the caller's thread; never concurrently), and once at the
    /// end; return false to cancel the run (throws RunCancelled).
    std::function<bool(const Progress&)> progress;
    double progress_interval = 1.0;
    /// Optional cancel flag, read by the workers before every sample: set it
    /// from any thread (a signal watcher, a GUI) to stop the run within one
    /// sample; the run then throws RunCancelled.
    const std::atomic<bool>* cancel = nullptr;
    /// Distributed runs (MPI, see cli/distributed.hpp): this process computes only the
    /// blocks b with b % ranks == rank, hands them to `combine`, which must
    /// return the blocks of every process (an all-gather); they are then
    /// merged in block order exactly as one process merges them, so the
    /// result is bitwise that of a single process with the same seed. Only
    /// runs whose samples reduce to (U, t) moments (diffusivity, bruteforce,
    /// sweep) can be distributed. ranks == 1: a plain run.
    unsigned rank = 0, ranks = 1;
    std::function<std::vector<BlockRecord>(std::vector<BlockRecord>)> combine;
};

/// Thrown when RunControl::progress asked to stop.
struct RunCancelled : std::runtime_error {
    RunCancelled() : std::runtime_error("run cancelled") {}
};

/// Samples per block: the unit of work and of deterministic merging.
inline constexpr std::uint64_t block_size = 64;

/// Raw outcome of a run: moments of (U, t) over completed samples, in index order.
struct RunTotals {
    BivariateMoments moments;
    std::uint64_t requested = 0;
    std::uint64_t capped = 0; ///< samples dropped by the runaway guard
    std::uint64_t work = 0;   ///< steps or events, all samples
    double seconds = 0.0;
    unsigned threads = 1;
};

struct PreparedEngine; // run.hpp

/// Throws InvalidParameter for a thread count above 4096.
void check_run_control(const RunControl& ctl);

/// N long excursions of a prepared engine (run.hpp), which is trusted.
RunTotals run_long_excursions(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl);
/// The same, preparing (and so validating) the engine first.
RunTotals run_long_excursions(const ModelParams& p, const EngineSettings& s, std::uint64_t excursions,
                              const RunControl& ctl);

/// Steps of the inclusion engine in a brute-force trajectory of length
/// horizon [s] (time rounded to whole steps of dt); InvalidParameter ("time")
/// outside 1 .. 1e13 steps.
std::uint64_t bruteforce_steps(double horizon, double dt);

/// N brute-force trajectories on [0, horizon] from noise x0 [s^-1/2] and
/// velocity v0 [m/s], of a prepared engine. Moments are of (U(horizon), horizon).
RunTotals run_bruteforce(const PreparedEngine& e, double horizon, double x0, double v0, std::uint64_t trajectories,
                         const RunControl& ctl);
/// The same, preparing (and so validating) the engine and the start first.
RunTotals run_bruteforce(const ModelParams& p, const EngineSettings& s, double horizon, double x0,
                         double v0, std::uint64_t trajectories, const RunControl& ctl);

/// Generic driver used by both: calls sample(index) for every index in
/// [first_index, first_index + n) in parallel and merges in index order.
RunTotals run_samples(std::uint64_t n, const RunControl& ctl,
                      const std::function<ExcursionOutcome(std::uint64_t)>& sample);

} // namespace stickslip
