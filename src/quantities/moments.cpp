// SPDX-License-Identifier: BSD-3-Clause
// Transient velocity moments from a given start (`moments`; observables.hpp explains the estimators).
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
#include "quantities/path_sampling.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/random/rng.hpp"

namespace stickslip {

using detail::BinIndex;
using detail::check_bins;
using detail::make_histogram;

namespace {

/// The times of a transient request [s]: its own, or Table I's.
std::vector<double> transient_times(const MomentsRequest& req) {
    if (!req.times.empty()) return req.times;
    std::vector<double> times;
    const double unit = scales_of(req.params).time;
    for (double t : table_one_times) times.push_back(t * unit);
    return times;
}

PreparedEngine prepare_request(const MomentsRequest& req_in) {
    const MomentsRequest req = with_resolved_engine(req_in);
    PreparedEngine engine = prepare(static_cast<const RunSettings&>(req));
    if (req.trajectories < 2)
        throw InvalidParameter("trajectories",
                               "trajectories must be >= 2 (got " + std::to_string(req.trajectories) + ")");
    if (req.times.size() > 10000) throw InvalidParameter("times", "at most 10000 times");
    for (double t : req.times)
        if (!std::isfinite(t) || t < 0)
            throw InvalidParameter("times", "times must be finite and >= 0 (s), got " + detail::format_number(t));
    detail::check_start(req.params, req.x0, std::isnan(req.v0) ? 0.0 : req.v0);
    // Checked without --density too: a setting given is checked whether or
    // not this run uses it, as every other setting is.
    check_bins(req.bins);
    const std::vector<double> times = transient_times(req);
    if (req.with_density && static_cast<double>(times.size()) * (req.bins.count + 3) > 2e6)
        throw InvalidParameter("bins", "times x bins must be at most 2e6 for --density (use fewer times or bins)");
    const double tmax = *std::max_element(times.begin(), times.end());
    if (has_time_step(req.engine) && tmax / req.engine.dt > 1e13)
        throw InvalidParameter("times", "largest time / dt exceeds 1e13 steps");
    return engine;
}

} // namespace

void validate(const MomentsRequest& req) { prepare_request(req); }

MomentsResult compute_moments(const MomentsRequest& req_in) {
    const PreparedEngine prepared = prepare_request(req_in);
    const std::vector<std::string> notes = detail::start_notes(prepared, 0, req_in.control);
    // The defaults that depend on the model, resolved once: the report shows them.
    MomentsRequest req = with_resolved_engine(req_in);
    if (std::isnan(req.v0)) req.v0 = scales_of(req.params).velocity;
    req.times = transient_times(req);
    MomentsResult out;
    out.request = req;
    out.monte_carlo().engine = prepared.resolved;
    out.monte_carlo().engine.stop_rule = "none";
    std::vector<double> times = req.times;
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    const std::size_t nt = times.size();
    VelocityBins bins = req.bins;
    if (req.with_density) {
        // Automatic range: the start and the stationary spread, whichever is wider.
        bins = resolve_bins(req.params, req.bins);
        if (req.bins.lo == 0 && req.bins.hi == 0) {
            const double pad = 0.05 * (bins.hi - bins.lo);
            bins.lo = std::min(bins.lo, req.v0 - pad);
            bins.hi = std::max(bins.hi, req.v0 + pad);
        }
        out.request.bins = bins;
    }
    const std::size_t nh = req.with_density ? static_cast<std::size_t>(bins.count) + 3 : 0;
    // Layout per trajectory: [V(t_j)], [V(t_j)^2], [V(t_j) == 0], then per time the histogram.
    const std::size_t dim = 3 * nt + nt * nh;
    const BinIndex index(req.with_density ? bins : VelocityBins{0, 1, 1});
    const std::uint64_t seed = req.control.seed;
    const bool draw_x = std::isnan(req.x0) && !req.params.white();
    const double x_sd = req.params.white() ? 0.0 : 1.0 / std::sqrt(req.params.tau);

    auto record = [&](std::vector<double>& y, std::size_t j, double v) {
        y[j] = v;
        y[nt + j] = v * v;
        y[2 * nt + j] = v == 0.0 ? 1.0 : 0.0;
        if (nh) y[3 * nt + j * nh + static_cast<std::size_t>(index(v))] = 1.0;
    };
    auto make = [dim] { return RatioMoments(dim, false); };
    ExactRatioSums exact(dim, {});
    const auto start_x = [&](BatchedCounterRng& rng) {
        return draw_x ? x_sd * rng.normal2().x : (std::isnan(req.x0) ? 0.0 : req.x0);
    };
    out.monte_carlo().totals = detail::visit_engine(prepared, [&](const auto& engine) {
        // The times the engine's clock can stop at (rounded to its step or leaf).
        out.time = engine.clock_times(times, out.warnings);
        return detail::run_blocks<RatioMoments>(
            req.trajectories, req.control, make,
            [&](std::uint64_t k, RatioMoments& acc) {
                thread_local std::vector<double> y;
                y.assign(dim, 0.0);
                const ExcursionOutcome o = engine.path_at_times(seed, k, start_x, req.v0, times,
                                                                [&](std::size_t j, double v) { record(y, j, v); });
                acc.add(y.data(), 1.0);
                return o;
            },
            exact);
    });
    detail::note_interruption(out.monte_carlo().totals, "trajectories", out.warnings);
    const RatioMoments total = exact.moments();
    for (std::size_t j = 0; j < nt; ++j) {
        out.first_moment.push_back(total.estimate(j, req.level));
        out.second_moment.push_back(total.estimate(nt + j, req.level));
        out.stuck.push_back(total.estimate(2 * nt + j, req.level));
        if (nh) {
            out.density.push_back(make_histogram(bins, total, 3 * nt + j * nh, req.level));
            out.density.back().time = req.times[j];
        }
    }
    const std::string lattice = detail::visit_engine(
        prepared, [&](const auto& engine) { return engine.lattice_note(out.monte_carlo().engine, prepared.settings, prepared.model.params, false); });
    if (!lattice.empty()) out.warnings.push_back(lattice);
    out.warnings.insert(out.warnings.begin(), notes.begin(), notes.end());
    return out;
}

} // namespace stickslip
