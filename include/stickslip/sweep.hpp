// stickslip/sweep.hpp -- D, M0 and E[t1] over a grid of noise intensities and
// correlation times (the paper's Figs. 4 and 9), with the local log-log slope
// d log D / d log Gamma and, per tau, the fitted exponent of D ~ Gamma^alpha.
//
// Independence: point number k uses the sample indices
// [k * 2^40, k * 2^40 + excursions) of the run's seed, so every point has its
// own streams, the points' errors are independent and the slope errors below
// are exact (to first order); any point can be recomputed alone
// with RunControl::first_index = k * 2^40.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "diffusivity.hpp"

namespace stickslip {

/// First sample index of sweep point k.
inline constexpr std::uint64_t sweep_index_stride = std::uint64_t{1} << 40;

struct SweepRequest {
    ModelParams params;            ///< friction, relaxation, bias (noise and tau come from the grid)
    EngineSettings engine;
    std::vector<double> noises;    ///< Gamma values [m^2 s^-3], > 0 (sorted increasing in the result)
    std::vector<double> taus;      ///< tau values [s], >= 0
    std::uint64_t excursions = 10000; ///< per point
    double level = 0.95;
    Estimator estimator = Estimator::RenewalReward;
    RunControl control;            ///< seed and threads (control.progress is not used)
    bool allow_capped = false;
    /// Optional: the progress callback for point k of n at (noise, tau).
    std::function<std::function<bool(const Progress&)>(std::size_t k, std::size_t n, double noise, double tau)>
        point_progress;
};

struct SweepPoint {
    double noise = 0, tau = 0;
    LongExcursionEstimates estimates;
    std::string stop_rule;
    std::uint64_t work = 0;
    double seconds = 0;
    /// d log D / d log Gamma at this point (central difference inside the
    /// grid, one-sided at its ends; NaN with a single noise value).
    Estimate slope;
    std::vector<std::string> warnings;
};

struct SweepExponent {
    double tau = 0;
    Estimate exponent;  ///< alpha of D ~ Gamma^alpha, weighted least squares in log-log
    double chi2_per_dof = 0; ///< of the power-law fit: >> 1 means no single power law
    int points = 0;
};

struct SweepResult {
    SweepRequest request;
    std::vector<SweepPoint> points; ///< tau-major: for each tau, noises increasing
    std::vector<SweepExponent> exponents; ///< one per tau (when >= 2 noises)
    double seconds = 0;
    std::vector<std::string> warnings;
};

void validate(const SweepRequest& req);
SweepResult compute_sweep(const SweepRequest& req);

} // namespace stickslip
