// SPDX-License-Identifier: BSD-3-Clause
// Sample paths (`trajectory`): one long excursion or independent paths, as recorded points.
#include "stickslip/observables.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <optional>

#include "core/format.hpp"
#include "driver/block_driver.hpp"
#include "driver/result_checks.hpp"
#include "driver/step_check.hpp"
#include "driver/visit_engine.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/random/rng.hpp"

namespace stickslip {

namespace {

PreparedEngine prepare_request(const TrajectoryRequest& req_in) {
    const TrajectoryRequest req = with_resolved_engine(req_in);
    PreparedEngine engine = prepare_engine(req.params, req.engine);
    check_run_control(req.control);
    if (req.paths > 1000) throw InvalidParameter("paths", "paths must be at most 1000");
    if (!std::isfinite(req.horizon) || req.horizon <= 0) // in excursion mode too (unused, but checked)
        throw InvalidParameter("time", "time must be a finite number > 0 (s), got " + detail::format_number(req.horizon));
    if (!std::isfinite(req.every) || req.every < 0)
        throw InvalidParameter("every", "every must be a finite number >= 0 (s), got " + detail::format_number(req.every));
    detail::check_start(req.params, req.x0, req.v0);
    if (req.index > max_sample_index) throw InvalidParameter("index", "index must be < 2^56");
    if (req.max_points < 2)
        throw InvalidParameter("max-points", "max-points must be at least 2 (a path's start and end), got " +
                                                 std::to_string(req.max_points));
    // One long excursion (the default) must be able to end, like those of
    // `diffusivity`: `trajectory --dt 1e-308` ran for ever.
    if (req.paths == 0) detail::check_excursions_can_end(engine);
    if (req.paths > 0) {
        const double every = req.every > 0 ? req.every : req.horizon / 1000;
        if (req.horizon / every > static_cast<double>(req.max_points))
            throw InvalidParameter("every", "time / every exceeds " + std::to_string(req.max_points) +
                                                " points per path; record less often");
        if (has_time_step(req.engine) && req.horizon / req.engine.dt > 1e13)
            throw InvalidParameter("time", "time / dt exceeds 1e13 steps");
    }
    return engine;
}

void append(SamplePath& p, double t, double x, int mode, double v, double u) {
    p.t.push_back(t);
    p.x.push_back(x);
    p.mode.push_back(mode);
    p.v.push_back(v);
    p.u.push_back(u);
}

struct TooManyPoints {};

} // namespace

void validate(const TrajectoryRequest& req) { prepare_request(req); }

TrajectoryResult compute_trajectory(const TrajectoryRequest& req_in) {
    const TrajectoryRequest req = with_resolved_engine(req_in);
    const PreparedEngine prepared = prepare_request(req);
    TrajectoryResult out;
    out.request = req;
    out.resolved = prepared.resolved;
    // What the engine notes of its numerics (the drift law's knots, a coarse
    // step), as every sampled quantity reports it.
    out.warnings = prepared.notes;
    const std::uint64_t seed = req.control.seed;
    auto guard = [&](const SamplePath& p) {
        if (p.t.size() >= req.max_points) throw TooManyPoints{};
    };
    if (req.paths == 0) {
        // One long excursion, the one `diffusivity` runs as number `index`.
        SamplePath path;
        try {
            const auto add = [&](const detail::PathPoint& q) {
                guard(path);
                append(path, q.t, q.x, q.mode, q.v, q.u);
            };
            detail::visit_engine(prepared, [&](const auto& engine) {
                const ExcursionOutcome outcome = engine.excursion_path(seed, req.index, req.every, add);
                out.excursion = ExcursionRecord::of(outcome);
                if (!outcome.capped) { // the regeneration state that ends it
                    const detail::PathPoint q = engine.regeneration_point(outcome);
                    append(path, q.t, q.x, q.mode, q.v, q.u);
                }
            });
        } catch (const TooManyPoints&) {
            throw InvalidParameter("every", "the excursion has more than " + std::to_string(req.max_points) +
                                                " recorded points; record less often (--every)");
        }
        if (!out.excursion.complete)
            out.warnings.push_back("the excursion hit the runaway guard (--max-steps) and is incomplete");
        out.paths.push_back(std::move(path));
        return out;
    }
    // Independent paths on [0, horizon], recorded every `every` seconds.
    const double every = req.every > 0 ? req.every : req.horizon / 1000;
    out.request.every = every;
    const double x0 = std::isnan(req.x0) ? detail::default_start_noise(prepared) : req.x0;
    const auto npoints = static_cast<std::uint64_t>(std::floor(req.horizon / every * (1 + 1e-12))) + 1;
    for (std::uint64_t k = 0; k < req.paths; ++k) {
        SamplePath path;
        detail::visit_engine(prepared, [&](const auto& engine) {
            engine.path_on_grid(seed, k, x0, req.v0, every, npoints,
                                [&](const detail::PathPoint& q) { append(path, q.t, q.x, q.mode, q.v, q.u); },
                                out.warnings);
        });
        out.paths.push_back(std::move(path));
    }
    return out;
}

} // namespace stickslip
