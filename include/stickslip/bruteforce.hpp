// stickslip/bruteforce.hpp -- the brute-force run (the paper's eq. 13):
// D_t = var U(t)/t from independent trajectories on [0, t], biased against D by
// O(1/t); there for comparison with the long-excursion estimator
// (diffusivity.hpp).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "estimators.hpp"
#include "run.hpp"

namespace stickslip {

struct BruteForceRequest : RunSettings {
    static constexpr const char* command = "bruteforce"; ///< the CLI subcommand, and a checkpoint's name for it
    static constexpr bool resumable = true; ///< runs through the block driver: checkpoints, graceful stop
    double horizon = 10.0;            ///< t [s]
    std::uint64_t trajectories = 1000;
    /// Start: noise x0 [s^-1/2] and velocity v0 [m/s]. NaN x0 means the
    /// paper's start, X = x* (PDMP: x_{k+ +1}), V = v0 = 0 by default.
    double x0 = std::numeric_limits<double>::quiet_NaN();
    double v0 = 0.0;
};

template <class Visitor>
void visit_settings(BruteForceRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), v);
    v(r.horizon, SettingInfo{"time", "s", "horizon t, > 0"});
    v(r.trajectories, SettingInfo{"trajectories", "", "number N' of trajectories (>= 2)"});
    v(OptionalNumber{r.x0}, SettingInfo{"x0", "s^-1/2",
                                        "initial noise X(0); default: the upper threshold x* (pdmp: the first lattice "
                                        "point above it, where the object starts moving)"});
    v(r.v0, SettingInfo{"v0", "m/s", "initial velocity"});
}

struct BruteForceResult {
    BruteForceRequest request;
    ResolvedEngine resolved;
    BruteForceEstimates estimates;
    RunTotals totals;
    double start_noise = 0; ///< x0 actually used [s^-1/2]
    std::vector<std::string> warnings;
};

void validate(const BruteForceRequest& req);
/// Validates the request (once), runs the trajectories, estimates.
BruteForceResult compute_bruteforce(const BruteForceRequest& req);

} // namespace stickslip
