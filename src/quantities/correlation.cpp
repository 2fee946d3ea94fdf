// SPDX-License-Identifier: BSD-3-Clause
// The stationary velocity autocorrelation (`correlation`; observables.hpp explains the estimators).
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

using detail::add_sampling_note;
using detail::check_event_sampling;
using detail::extra_sampling;
using detail::sampling_interval;
using detail::sampling_phase;

namespace {
constexpr int kMaxLags = 2000;
constexpr std::uint64_t kMaxLagSamples = 4'000'000; // ring buffer (a power of two above): at most 32 MB per thread
/// The work of one lag product (a ring-buffer load, a multiply-add) in steps
/// of the engine, for the run's predicted duration (detail::predict_run):
/// measured on white noise at the defaults (resolvent scheme, 2000
/// excursions, one thread): 17.9 s with 2 lags, 39.7 s with 51, 1.64e9 steps
/// each, so 0.27 ns a product against 10.9 ns a step.
constexpr double kLagProductCost = 0.025;

/// What the run's paths record, for its predicted duration: each path runs
/// the largest lag past its excursion, and each sample costs its lag products.
detail::PathSampling path_sampling(const CorrelationRequest& req, double dt, double max_lag) {
    const double lags = std::min<double>(req.lags, std::floor(max_lag / dt)) + 1;
    return {.interval = extra_sampling(req.engine, req.sample_dt),
            .per_sample = kLagProductCost * lags,
            .continued = max_lag};
}
} // namespace

namespace {

PreparedEngine prepare_request(const CorrelationRequest& req_in) {
    const CorrelationRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
    PreparedEngine engine = prepare(static_cast<const RunSettings&>(req));
    validate(static_cast<const ExcursionSettings&>(req));
    check_event_sampling(req);
    if (req.lags < 1 || req.lags > kMaxLags)
        throw InvalidParameter("lags", "lags must be between 1 and " + std::to_string(kMaxLags));
    if (!std::isfinite(req.max_lag) || req.max_lag < 0)
        throw InvalidParameter("max-lag", "max-lag must be a finite number >= 0 (s), got " +
                                              detail::format_number(req.max_lag));
    const double dt = sampling_interval(req.engine, req.sample_dt);
    const double max_lag = req.max_lag > 0 ? req.max_lag : 5 * scales_of(req.params).time;
    if (max_lag / dt > static_cast<double>(kMaxLagSamples))
        throw InvalidParameter("max-lag", "max-lag / sampling interval exceeds " + std::to_string(kMaxLagSamples) +
                                              " samples; use a shorter --max-lag (pdmp: or a coarser --sample-dt)");
    detail::check_excursions_can_end(engine, extra_sampling(req.engine, req.sample_dt));
    detail::check_run_duration(engine, req.excursions, req.control, path_sampling(req, dt, max_lag));
    return engine;
}

} // namespace

void validate(const CorrelationRequest& req) { prepare_request(req); }

CorrelationResult compute_correlation(const CorrelationRequest& req_in) {
    const CorrelationRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
    const PreparedEngine prepared = prepare_request(req);
    const double dt = sampling_interval(req.engine, req.sample_dt);
    const double max_lag = req.max_lag > 0 ? req.max_lag : 5 * scales_of(req.params).time;
    const std::vector<std::string> notes =
        detail::start_notes(prepared, req.excursions, req.control, path_sampling(req, dt, max_lag));
    CorrelationResult out;
    out.request = req;
    out.monte_carlo().engine = prepared.resolved;
    out.request.max_lag = max_lag;
    // Lags on the sampling grid, distinct, increasing, starting at 0.
    std::vector<std::uint64_t> lag_steps;
    for (int j = 0; j <= req.lags; ++j) {
        const auto l = static_cast<std::uint64_t>(std::llround(max_lag * j / req.lags / dt));
        if (lag_steps.empty() || l > lag_steps.back()) lag_steps.push_back(l);
    }
    const std::size_t nl = lag_steps.size();
    const std::uint64_t lmax = lag_steps.back();
    // Ring buffer of the last lmax + 1 samples; a power of two so that the
    // index is a mask, not a division, in the per-sample loop over lags.
    std::uint64_t ring = 1;
    while (ring < lmax + 1) ring <<= 1;
    const std::uint64_t mask = ring - 1;
    for (auto l : lag_steps) out.lag.push_back(static_cast<double>(l) * dt);
    const std::size_t dim = nl + 1; // [lag products..., V]
    const std::uint64_t seed = req.control.seed;

    // Per-excursion state of the lag products: ring buffer of past samples.
    struct LagState {
        std::vector<double> buf, y;
        std::uint64_t m = 0;          // samples seen
        std::uint64_t limit = ~0ull;  // start indices must be < limit (excursion length once known)
    };
    auto push = [&lag_steps, nl, mask](LagState& st, double v) {
        st.buf[st.m & mask] = v;
        for (std::size_t j = 0; j < nl; ++j) {
            const std::uint64_t l = lag_steps[j];
            if (st.m < l) break;
            const std::uint64_t start = st.m - l;
            if (start < st.limit) st.y[j] += st.buf[start & mask] * v;
        }
        if (st.m < st.limit) st.y[nl] += v;
        ++st.m;
    };
    // The covariances the estimates need: every lag with lag 0 and with V.
    const std::vector<std::size_t> columns{0, nl};
    auto make = [dim, &columns] { return RatioMoments(dim, columns); };
    ExactRatioSums exact(dim, columns);
    auto reset = [&](LagState& st) {
        st.buf.assign(ring, 0.0);
        st.y.assign(dim, 0.0);
        st.m = 0;
        st.limit = ~0ull;
    };
    out.monte_carlo().totals = detail::visit_engine(prepared, [&](const auto& engine) {
        return detail::run_blocks<RatioMoments>(
            req.excursions, req.control, make,
            [&](std::uint64_t k, RatioMoments& acc) {
                thread_local LagState st;
                reset(st);
                const ExcursionOutcome o = engine.sampled_excursion(
                    seed, k, dt, sampling_phase(seed, k, dt), [&](double v) { push(st, v); },
                    [&]() -> std::optional<std::uint64_t> {
                        if (st.m == 0) return std::nullopt;
                        // Continue past the excursion's end until every lag of every start is seen.
                        st.limit = st.m;
                        return lmax;
                    });
                if (o.capped || st.m == 0) return o;
                acc.add(st.y.data(), static_cast<double>(st.limit));
                return o;
            },
            exact);
    });
    const RatioMoments total = exact.moments();
    detail::finish_long_excursion_run(prepared, out.monte_carlo().totals, req.allow_capped, out.warnings);
    out.estimates = estimate_long_excursion(out.monte_carlo().totals.moments, req.level);
    detail::check_finite(out.estimates);
    const std::size_t iu = nl;
    const double m = total.ratio(iu);
    out.mean = total.estimate(iu, req.level);
    const double h0 = total.ratio(0) - m * m;
    for (std::size_t j = 0; j < nl; ++j) {
        out.autocorrelation.push_back(total.estimate(j, req.level));
        const double hj = total.ratio(j) - m * m;
        // h_j = R_j - R_U^2: gradient 1 on j, -2m on U.
        const double var_h = total.delta_variance({{j, 1.0}, {iu, -2 * m}});
        out.covariance.push_back(make_interval(hj, std::sqrt(var_h), req.level));
        // rho_j = h_j / h_0: gradient 1/h0 on j, -h_j/h0^2 on 0, 2m (h_j - h0)/h0^2 on U;
        // rho_0 is identically 1.
        const double var_r =
            j == 0 ? 0.0
                   : total.delta_variance({{j, 1 / h0}, {0, -hj / (h0 * h0)}, {iu, 2 * m * (hj - h0) / (h0 * h0)}});
        out.normalised.push_back(make_interval(hj / h0, std::sqrt(var_r), req.level));
    }
    add_sampling_note(detail::visit_engine(prepared, [dt](const auto& engine) { return engine.sampling_note(dt); }),
                      out.warnings);
    out.warnings.insert(out.warnings.begin(), notes.begin(), notes.end());
    return out;
}

} // namespace stickslip
