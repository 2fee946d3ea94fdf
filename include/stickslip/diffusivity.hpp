// stickslip/diffusivity.hpp -- the library's top-level computations:
// the long-excursion diffusivity run and the brute-force run, with everything a
// report needs (resolved settings, estimates, work, warnings). The CLI and the
// Python module are thin layers over these two functions and report.hpp.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "estimators.hpp"
#include "excursion.hpp"
#include "params.hpp"
#include "runner.hpp"

namespace stickslip {

struct DiffusivityRequest {
    ModelParams params;
    EngineSettings engine;
    std::uint64_t excursions = 10000;
    double level = 0.95; ///< confidence level of the intervals, in (0, 1)
    Estimator estimator = Estimator::RenewalReward;
    RunControl control;
    bool allow_capped = false; ///< if false, capped excursions make the result an error
    /// Precision on demand: when > 0, run in batches until the interval's
    /// half-width is at most rel_precision * D, or max_excursions have run.
    /// The first batch has `excursions` (rounded up to whole blocks of 64);
    /// each later one is sized from the current half-width (half-width ~
    /// 1/sqrt(N)), at most 4x what has run.
    /// Batches start at block-aligned sample indices, so the result is
    /// deterministic and thread-invariant. Caveat (sequential stopping): N
    /// depends on the data, so the interval's coverage is slightly below its
    /// nominal level; with few, large batches the effect is small.
    double rel_precision = 0.0;
    std::uint64_t max_excursions = 100'000'000; ///< cap of the precision-on-demand mode
};

/// How a precision-on-demand run ended.
struct PrecisionOutcome {
    double target = 0.0;              ///< requested relative half-width (0: mode off)
    double relative_half_width = 0.0; ///< achieved (hi - D) / D
    bool reached = true;
    int batches = 1;
};

/// Engine details resolved for a run, reported alongside the estimates.
struct ResolvedEngine {
    std::string stop_rule;   ///< "bridge" | "stuck" | "velocity-levels" (white) | "exact" (PDMP)
    double lattice_bound = 0; ///< PDMP: L [s^-1/2]
    int lattice_points = 0;   ///< PDMP: 2N+1
    double truncated_mass = 0;///< PDMP: stationary Gaussian mass of X beyond +-L
    double jump_rate = 0;     ///< PDMP: Lambda [s^-1]
    double white_level = 0;   ///< white noise: regeneration level c [m/s]
    double upper_threshold = 0, lower_threshold = 0; ///< x*, x-* [s^-1/2] (colored)
};

/// Validates p and s (InvalidParameter) and resolves the engine's details.
ResolvedEngine resolve_engine(const ModelParams& p, const EngineSettings& s);

struct DiffusivityResult {
    DiffusivityRequest request;
    ResolvedEngine resolved;
    LongExcursionEstimates estimates;
    RunTotals totals;
    PrecisionOutcome precision;
    std::vector<std::string> warnings;
};

/// Validates everything (InvalidParameter), runs, estimates. Throws
/// CappedExcursions when excursions hit the guard and !allow_capped.
DiffusivityResult compute_diffusivity(const DiffusivityRequest& req);

struct CappedExcursions : std::runtime_error {
    explicit CappedExcursions(const std::string& m) : std::runtime_error(m) {}
};

/// Checks a request without running it (InvalidParameter on the first problem).
void validate(const DiffusivityRequest& req);

struct BruteForceRequest {
    ModelParams params;
    EngineSettings engine;
    double horizon = 10.0;            ///< t [s]
    std::uint64_t trajectories = 1000;
    /// Start: noise x0 [s^-1/2] and velocity v0 [m/s]. NaN x0 means the
    /// paper's start, X = x* (PDMP: x_{k+ +1}), V = v0 = 0 by default.
    double x0 = std::numeric_limits<double>::quiet_NaN();
    double v0 = 0.0;
    double level = 0.95;
    RunControl control;
};

struct BruteForceResult {
    BruteForceRequest request;
    ResolvedEngine resolved;
    BruteForceEstimates estimates;
    RunTotals totals;
    double start_noise = 0; ///< x0 actually used [s^-1/2]
    std::vector<std::string> warnings;
};

BruteForceResult compute_bruteforce(const BruteForceRequest& req);
void validate(const BruteForceRequest& req);

} // namespace stickslip
