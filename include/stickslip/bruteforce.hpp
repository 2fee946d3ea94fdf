// SPDX-License-Identifier: BSD-3-Clause
// stickslip/bruteforce.hpp -- the brute-force run (the paper's eq. 13):
// D_t = var U(t)/t from independent trajectories on [0, t], biased against D by
// O(1/t); there for comparison with the long-excursion estimator
// (diffusivity.hpp).
#pragma once

/// \file
/// The brute-force run: D_t = var U(t)/t from independent trajectories on [0,
/// t]. The comment at the top of this header explains the design.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "stickslip/stats/estimators.hpp"
#include "stickslip/method.hpp"
#include "stickslip/run.hpp"

namespace stickslip {

/// A brute-force run (`stickslip bruteforce`): N' independent trajectories
/// on [0, horizon] from (x0, v0), then D_t and M0_t.
struct BruteForceRequest : RunSettings {
    static constexpr const char* command = "bruteforce"; ///< the CLI subcommand, and a checkpoint's name for it
    static constexpr bool resumable = true; ///< runs through the block driver: checkpoints, graceful stop
    double horizon = 10.0;            ///< t [s]
    /// Number N' of independent trajectories, >= 2.
    std::uint64_t trajectories = 1000;
    /// Start: noise x0 [s^-1/2] and velocity v0 [m/s]. NaN x0 means the
    /// paper's start, X = x* (PDMP: x_{k+ +1}), V = v0 = 0 by default.
    double x0 = std::numeric_limits<double>::quiet_NaN();
    /// Initial velocity V(0) [m/s] of every trajectory.
    double v0 = 0.0;
};

/// The request's settings: RunSettings', then --time, --trajectories, --x0
/// and --v0.
template <class Visitor>
void visit_settings(BruteForceRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), v);
    v(r.horizon, SettingInfo{"time", "s", "horizon t, > 0"});
    v(r.trajectories, SettingInfo{"trajectories", "", "number N' of trajectories (>= 2)"});
    v(OptionalNumber{r.x0}, SettingInfo{"x0", "s^-1/2",
                                        "initial noise X(0); default: the upper threshold x* = (friction - "
                                        "b(0))/sqrt(noise/2), where a stuck object starts sliding up (pdmp: the "
                                        "first lattice point above it)"});
    v(r.v0, SettingInfo{"v0", "m/s", "initial velocity"});
}

/// What compute_bruteforce returns; report.hpp writes it.
struct BruteForceResult : MethodResult {
    /// The request, as run.
    BruteForceRequest request;
    /// D_t [m^2/s] and M0_t [m/s] with their intervals.
    BruteForceEstimates estimates;
    double start_noise = 0; ///< x0 actually used [s^-1/2]
    /// Notes for the user, one sentence each: always that D_t is biased by
    /// O(1/t); a step too coarse, the horizon rounded to whole steps, an
    /// interrupted run.
    std::vector<std::string> warnings;
};

/// Every check of the request (InvalidParameter on the first problem): the
/// shared settings (validate(const RunSettings&)), a finite horizon > 0 (the
/// inclusion engine: 1 to 1e13 steps of dt), trajectories >= 2, and a
/// finite v0 and x0 (or NaN).
void validate(const BruteForceRequest& req);
/// Validates the request (once), runs the trajectories, estimates.
BruteForceResult compute_bruteforce(const BruteForceRequest& req);

} // namespace stickslip
