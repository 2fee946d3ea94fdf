// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/bruteforce.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/sample_runs.hpp"

#include <cmath>

#include "core/format.hpp"
#include "driver/result_checks.hpp"

namespace stickslip {

namespace {
/// Below this many trajectories the fourth-moment standard error of D_t is noise.
constexpr std::uint64_t kFewTrajectories = 100;
} // namespace

namespace {

/// Every check of a request, once; returns its prepared engine.
PreparedEngine prepare_request(const BruteForceRequest& req_in) {
    const BruteForceRequest req = with_resolved_engine(req_in);
    PreparedEngine engine = prepare(static_cast<const RunSettings&>(req));
    if (!std::isfinite(req.horizon) || req.horizon <= 0)
        throw InvalidParameter("time", "time must be a finite number > 0 (s), got " + detail::format_number(req.horizon));
    if (req.trajectories < 2)
        throw InvalidParameter("trajectories",
                               "trajectories must be >= 2 (got " + std::to_string(req.trajectories) + ")");
    detail::check_start(req.params, req.x0, req.v0);
    if (has_time_step(req.engine)) bruteforce_steps(req.horizon, req.engine.dt);
    return engine;
}

} // namespace

void validate(const BruteForceRequest& req) { prepare_request(req); }

BruteForceResult compute_bruteforce(const BruteForceRequest& req_in) {
    const BruteForceRequest req = with_resolved_engine(req_in);
    const PreparedEngine engine = prepare_request(req);
    const std::vector<std::string> notes = detail::start_notes(engine, 0, req.control);
    BruteForceResult out;
    out.request = req;
    out.monte_carlo().engine = engine.resolved;
    out.monte_carlo().engine.stop_rule = "none"; // brute force needs no regeneration test
    const double x0 = std::isnan(req.x0) ? detail::default_start_noise(engine) : req.x0;
    out.start_noise = x0;
    out.monte_carlo().totals = run_bruteforce(engine, req.horizon, x0, req.v0, req.trajectories, req.control);
    detail::note_interruption(out.monte_carlo().totals, "trajectories", out.warnings);
    // The inclusion engine simulates a whole number of steps: use the time it
    // actually simulated, and say so when it differs from the request.
    const double simulated = out.monte_carlo().totals.moments.mean_y();
    if (std::fabs(simulated - req.horizon) > 1e-9 * req.horizon)
        out.warnings.push_back("time rounded to a whole number of steps: " + detail::format_number(simulated) + " s simulated");
    out.estimates = estimate_bruteforce(out.monte_carlo().totals.moments, simulated, req.level);
    const std::uint64_t n = out.monte_carlo().totals.moments.count();
    if (n < kFewTrajectories)
        out.warnings.push_back("only " + std::to_string(n) + " trajectories: the standard error of D_t comes from "
                               "their fourth moment and is unreliable below " + std::to_string(kFewTrajectories) +
                               (n == 2 ? std::string(" (with 2 it is 0 by construction)") : std::string()) +
                               "; use 1000 or more");
    out.warnings.push_back("brute force estimates D_t = var U(t)/t, biased against D by O(1/t) (relative bias shrinks "
                           "like E[t1]/t); use `stickslip diffusivity` for an unbiased estimate");
    out.warnings.insert(out.warnings.begin(), notes.begin(), notes.end());
    return out;
}

} // namespace stickslip
