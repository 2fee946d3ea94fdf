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

struct RunControl {
    unsigned threads = 0;          ///< 0: all hardware threads
    std::uint64_t seed = 1;        ///< user seed (the Philox key)
    std::uint64_t first_index = 0; ///< first sample index (for splitting runs)
    /// Called from the merging thread about every `progress_interval` seconds
    /// and at the end; return false to cancel the run (throws RunCancelled).
    std::function<bool(const Progress&)> progress;
    double progress_interval = 1.0;
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

/// N long excursions of the chosen engine.
RunTotals run_long_excursions(const ModelParams& p, const EngineSettings& s, std::uint64_t excursions,
                              const RunControl& ctl);

/// N brute-force trajectories on [0, horizon] from noise x0 [s^-1/2] and
/// velocity v0 [m/s]. Moments are of (U(horizon), horizon).
RunTotals run_bruteforce(const ModelParams& p, const EngineSettings& s, double horizon, double x0,
                         double v0, std::uint64_t trajectories, const RunControl& ctl);

/// Generic driver used by both: calls sample(index) for every index in
/// [first_index, first_index + n) in parallel and merges in index order.
RunTotals run_samples(std::uint64_t n, const RunControl& ctl,
                      const std::function<ExcursionOutcome(std::uint64_t)>& sample);

} // namespace stickslip
