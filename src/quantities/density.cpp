// SPDX-License-Identifier: BSD-3-Clause
// The stationary velocity density (`density`; observables.hpp explains the estimators).
#include "stickslip/observables.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "core/format.hpp"
#include "driver/block_driver.hpp"
#include "driver/result_checks.hpp"
#include "driver/step_check.hpp"
#include "driver/visit_engine.hpp"
#include "quantities/path_sampling.hpp"
#include "quantities/solved.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/random/rng.hpp"

namespace stickslip {

using detail::add_sampling_note;
using detail::BinIndex;
using detail::check_bins;
using detail::check_event_sampling;
using detail::extra_sampling;
using detail::make_histogram;
using detail::sampled_excursion;
using detail::sampling_interval;
using detail::sampling_phase;

namespace {

PreparedEngine prepare_request(const DensityRequest& req_in) {
    const DensityRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
    PreparedEngine engine = prepare(static_cast<const RunSettings&>(req));
    validate(static_cast<const ExcursionSettings&>(req));
    check_bins(req.bins);
    check_event_sampling(req);
    sampling_interval(req.engine, req.sample_dt);
    detail::check_excursions_can_end(engine, extra_sampling(req.engine, req.sample_dt));
    detail::check_run_duration(engine, req.excursions, req.control,
                               {.interval = extra_sampling(req.engine, req.sample_dt)});
    return engine;
}

} // namespace

void validate(const DensityRequest& req) {
    if (!samples(req.engine)) {
        detail::refuse_sampling_settings(req);
        detail::validate_solved(req, 0.0);
    }
    else prepare_request(req);
}

namespace {

/// Velocity range seen by the first excursions (a deterministic pilot of the
/// same streams): automatic histogram ranges that fit colored noise, whose
/// velocities are far smaller than the white-noise spread.
template <class Engine>
bool pilot_range(const DensityRequest& req, const Engine& engine, double dt, double& lo, double& hi) {
    // Minimum and maximum are order-free as they are. The pilot runs whole on
    // every process of a distributed run, so all of them get the same range.
    struct Range {
        double lo = 0, hi = 0;
        void add_block(const Range& b) {
            lo = std::min(lo, b.lo);
            hi = std::max(hi, b.hi);
        }
        void merge(const Range& b) { add_block(b); }
        // Only for a checkpoint (the pilot is never split across processes).
        std::size_t words() const { return 2; }
        void to_words(std::uint64_t* w) const {
            w[0] = std::bit_cast<std::uint64_t>(lo);
            w[1] = std::bit_cast<std::uint64_t>(hi);
        }
        void assign_words(const std::uint64_t* w) {
            lo = std::bit_cast<double>(w[0]);
            hi = std::bit_cast<double>(w[1]);
        }
    };
    RunControl ctl = req.control;
    ctl.progress = nullptr;
    ctl.rank = 0;
    ctl.ranks = 1;
    Range total;
    const std::uint64_t n = std::min<std::uint64_t>(req.excursions, 256);
    const std::uint64_t seed = req.control.seed;
    detail::run_blocks<Range>(
        n, ctl, [] { return Range{}; },
        [&](std::uint64_t k, Range& r) {
            return sampled_excursion(engine, seed, k, dt, 0.0, [&](double v) {
                r.lo = std::min(r.lo, v);
                r.hi = std::max(r.hi, v);
            });
        },
        total);
    if (!(total.hi > total.lo)) return false;
    const double pad = 0.1 * (total.hi - total.lo);
    lo = total.lo - pad;
    hi = total.hi + pad;
    return true;
}

} // namespace

namespace {

template <class Engine>
DensityResult density_of(const Engine& engine, const DensityRequest& req, const PreparedEngine& prepared,
                         const std::vector<std::string>& notes) {
    DensityResult out;
    out.request = req;
    out.monte_carlo().engine = prepared.resolved;
    const double dt = sampling_interval(req.engine, req.sample_dt);
    VelocityBins bins = resolve_bins(req.params, req.bins);
    if (req.bins.lo == 0 && req.bins.hi == 0) pilot_range(req, engine, dt, bins.lo, bins.hi);
    out.request.bins = bins;
    const BinIndex index(bins);
    const std::size_t nh = static_cast<std::size_t>(bins.count) + 3;
    const std::uint64_t seed = req.control.seed;

    struct Acc {
        RatioMoments hist; // [bins..., stuck, below, above] / t
        RatioMoments mom;  // [V, V^2] / t, with their covariance
    };
    struct Total {
        ExactRatioSums hist, mom;
        void add_block(const Acc& a) {
            hist.add_block(a.hist);
            mom.add_block(a.mom);
        }
        void merge(const Total& o) {
            hist.merge(o.hist);
            mom.merge(o.mom);
        }
        std::size_t words() const { return hist.words() + mom.words(); }
        void to_words(std::uint64_t* w) const {
            hist.to_words(w);
            mom.to_words(w + hist.words());
        }
        void assign_words(const std::uint64_t* w) {
            hist.assign_words(w);
            mom.assign_words(w + hist.words());
        }
    };
    auto make = [nh] { return Acc{RatioMoments(nh, false), RatioMoments(2, std::vector<std::size_t>{0})}; };
    // Per-excursion sums in units of the sampling interval (it cancels in every ratio).
    auto finish = [](Acc& acc, std::vector<double>& y, double m[2], std::uint64_t samples) {
        acc.hist.add(y.data(), static_cast<double>(samples));
        acc.mom.add(m, static_cast<double>(samples));
    };
    Total exact{ExactRatioSums(nh, {}), ExactRatioSums(2, {0})};
    out.monte_carlo().totals = detail::run_blocks<Acc>(
        req.excursions, req.control, make,
        [&](std::uint64_t k, Acc& acc) {
            thread_local std::vector<double> y;
            y.assign(nh, 0.0);
            double m[2] = {0.0, 0.0};
            std::uint64_t samples = 0;
            const ExcursionOutcome o = sampled_excursion(engine, seed, k, dt, sampling_phase(seed, k, dt), [&](double v) {
                y[static_cast<std::size_t>(index(v))] += 1.0;
                m[0] += v;
                m[1] += v * v;
                ++samples;
            });
            if (!o.capped && samples > 0) finish(acc, y, m, samples);
            return o;
        },
        exact);
    const Acc total{exact.hist.moments(), exact.mom.moments()};
    detail::finish_long_excursion_run(prepared, out.monte_carlo().totals, req.allow_capped, out.warnings);
    out.estimates = estimate_long_excursion(out.monte_carlo().totals.moments, req.level);
    detail::check_finite(out.estimates);
    out.histogram = make_histogram(bins, total.hist, 0, req.level);
    out.mean = total.mom.estimate(0, req.level);
    // Var = R_2 - R_1^2; gradient (-2 R_1, 1).
    const double r1 = total.mom.ratio(0), r2 = total.mom.ratio(1);
    out.variance = make_interval(r2 - r1 * r1, std::sqrt(total.mom.delta_variance({{0, -2 * r1}, {1, 1.0}})),
                                 req.level);
    if (engine.coarse_against_tau(req.params))
        out.warnings.push_back("dt is not << tau: P(V = 0) includes the scheme's O(dt) quantisation of V near 0 "
                               "(a few 1e-3 at dt' = 1e-3); refine dt to see the physical atom");
    const double outside = out.histogram.below.value + out.histogram.above.value;
    if (outside > 1e-3)
        out.warnings.push_back("probability " + detail::format_number(outside) +
                               " of V lies outside the histogram range; widen --range");
    add_sampling_note(engine.sampling_note(dt), out.warnings);
    out.warnings.insert(out.warnings.begin(), notes.begin(), notes.end());
    return out;
}

} // namespace

namespace {

/// The stationary density from the Kolmogorov solver's grid with the finest
/// velocity cells: the method chosen at the top of compute_density.
DensityResult solve_density(const DensityRequest& req) {
    validate(req);
    DensityResult out;
    out.request = req;
    out.solution = detail::solve(req, 0.0, out.warnings);
    out.details = out.solution->details;
    // The stationary mean and variance of V, with their discretisation errors.
    out.mean = out.solution->mobility;
    out.variance = out.solution->velocity_variance;
    out.estimates = detail::solved_long_excursion_estimates(*out.solution);
    out.histogram.stuck = out.solution->stuck_probability;
    const KolmogorovGridSolution& fine = out.solution->levels.back();
    out.warnings.push_back("the density is that of the solver's grid with the finest velocity cells, one value per cell (" +
                           std::to_string(fine.velocity_density.size()) +
                           " cells, graded towards v = 0; --bins and --range do not apply): a grid value has no "
                           "standard error, and its discretisation error is estimated only for D, M0, P(V = 0) and E[t1]. "
                           "It integrates to 1 less that grid's own P(V = 0), " +
                           detail::format_number(fine.stuck_probability) + "; the P(V = 0) reported is extrapolated");
    return out;
}

} // namespace

DensityResult compute_density(const DensityRequest& req_in) {
    if (!samples(req_in.engine)) return solve_density(req_in); // the method, chosen once
    const DensityRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
    const PreparedEngine prepared = prepare_request(req);
    const std::vector<std::string> notes =
        detail::start_notes(prepared, req.excursions, req.control, {.interval = extra_sampling(req.engine, req.sample_dt)});
    return detail::visit_engine(prepared, [&](const auto& engine) { return density_of(engine, req, prepared, notes); });
}

} // namespace stickslip
