// SPDX-License-Identifier: BSD-3-Clause
// Velocity statistics from every engine (observables.hpp explains the
// estimators). Every observable is a path functional accumulated by an observer
// passed to the engines' own kernels, so the excursions are exactly those of
// `diffusivity`; each command is written once, over the engine adapter that
// detail::visit_engine hands it (engines/visit_engine.hpp).
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
#include "engines/visit_engine.hpp"
#include "stickslip/analytic.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/random/rng.hpp"

namespace stickslip {

namespace {

constexpr int kMaxBins = 100000;
constexpr int kMaxLags = 2000;
constexpr std::uint64_t kMaxLagSamples = 4'000'000; // ring buffer (a power of two above): at most 32 MB per thread

void check_bins(const VelocityBins& b) {
    if (b.count < 1 || b.count > kMaxBins)
        throw InvalidParameter("bins", "bins must be between 1 and " + std::to_string(kMaxBins) + " (got " +
                                           std::to_string(b.count) + ")");
    if (!std::isfinite(b.lo) || !std::isfinite(b.hi) || (b.lo >= b.hi && !(b.lo == 0 && b.hi == 0)))
        throw InvalidParameter("range", "velocity range must be finite with lo < hi (or both 0 for automatic), got [" +
                                            detail::format_number(b.lo) + ", " + detail::format_number(b.hi) + "]");
    const double width = (b.hi - b.lo) / b.count;
    if (!(b.lo == 0 && b.hi == 0) && (!std::isfinite(width) || b.lo + width == b.lo || b.hi - width == b.hi))
        throw InvalidParameter("range", "velocity range [" + detail::format_number(b.lo) + ", " +
                                            detail::format_number(b.hi) + "] cannot be cut into " +
                                            std::to_string(b.count) +
                                            " bins in double precision (the width is infinite or too small)");
}

/// Sampling interval of a path observable [s].
/// The sampling interval that adds work of its own (an explicit --sample-dt
/// of the event scheme or the PDMP), 0 otherwise: the cost model's input.
double extra_sampling(const EngineSettings& s, double sample_dt) {
    return samples_at_steps(s) ? 0.0 : sample_dt;
}

double sampling_interval(const EngineSettings& s, double sample_dt) {
    if (!std::isfinite(sample_dt) || sample_dt < 0)
        throw InvalidParameter("sample-dt", "sample-dt must be a finite number >= 0 (s), got " +
                                                detail::format_number(sample_dt));
    if (samples_at_steps(s)) return s.dt;
    return sample_dt > 0 ? sample_dt : s.dt;
}

/// Sorts a velocity into the histogram layout [bins..., stuck, below, above].
struct BinIndex {
    double lo, hi, inv_width;
    int count;
    explicit BinIndex(const VelocityBins& b)
        : lo(b.lo), hi(b.hi), inv_width(b.count / (b.hi - b.lo)), count(b.count) {}
    int operator()(double v) const {
        if (v == 0.0) return count;
        if (v < lo) return count + 1;
        if (v >= hi) return count + 2;
        const int k = static_cast<int>((v - lo) * inv_width);
        return std::min(k, count - 1);
    }
};

VelocityHistogram make_histogram(const VelocityBins& b, const RatioMoments& m, std::size_t first, double level) {
    VelocityHistogram h;
    const double width = (b.hi - b.lo) / b.count;
    h.edges.resize(static_cast<std::size_t>(b.count) + 1);
    for (int k = 0; k <= b.count; ++k) h.edges[static_cast<std::size_t>(k)] = b.lo + width * k;
    h.edges.back() = b.hi;
    h.density.reserve(static_cast<std::size_t>(b.count));
    for (int k = 0; k < b.count; ++k) {
        Estimate e = m.estimate(first + static_cast<std::size_t>(k), level);
        e.value /= width;
        e.std_error /= width;
        e.lo /= width;
        e.hi /= width;
        h.density.push_back(e);
    }
    const std::size_t base = first + static_cast<std::size_t>(b.count);
    h.stuck = m.estimate(base, level);
    h.below = m.estimate(base + 1, level);
    h.above = m.estimate(base + 2, level);
    return h;
}

/// The random grid phase of excursion k, from its own stream (the excursion's
/// draws are untouched, so D stays that of `diffusivity`).
double sampling_phase(std::uint64_t seed, std::uint64_t k, double dt) {
    CounterRng rng(seed, StreamPurpose::SamplingPhase, k);
    return dt * (1.0 - rng.uniform()); // uniform() is in (0, 1]: phase in [0, dt)
}

/// The event scheme knows a white-noise path only at the ends of its pieces:
/// V between them is a Brownian bridge, which the interpolation that serves
/// coloured noise (V is smooth there) would flatten (measured: Var(V) 2.6%
/// low at dt' = 1/16). Refused for the stationary observables, which sample
/// paths on a grid (InvalidParameter "scheme").
void check_event_sampling(const RunSettings& r) {
    if (!samples_on_grid(r.engine, r.params.tau))
        throw InvalidParameter("scheme", "the event scheme does not sample white-noise paths on a grid (V between "
                                         "its events is a Brownian bridge); use --scheme resolvent, or `stickslip "
                                         "analytic` for the exact white-noise density and variance");
}

/// Long excursion k of `engine` (the one `diffusivity` runs) sampled every dt
/// [s] from `phase`: on_v(v) at every sample.
template <class Engine, class OnV>
ExcursionOutcome sampled_excursion(const Engine& engine, std::uint64_t seed, std::uint64_t k, double dt,
                                   double phase, OnV&& on_v) {
    return engine.sampled_excursion(seed, k, dt, phase, on_v, [] { return std::optional<std::uint64_t>{}; });
}

/// A report's note on how the path was sampled, if the engine has one.
void add_sampling_note(const std::string& note, std::vector<std::string>& warnings) {
    if (!note.empty()) warnings.push_back(note);
}

/// Standard deviation used by automatic ranges [m/s].
void auto_range(const ModelParams& p, double& lo, double& hi) {
    if (has_stationary_state(p)) {
        const WhiteNoiseReference w = white_noise_reference(p);
        const double sd = std::sqrt(w.variance);
        lo = w.mobility - 6 * sd;
        hi = w.mobility + 6 * sd;
    } else {
        const double s = 6 * p.noise / p.friction;
        lo = -s;
        hi = s;
    }
}

} // namespace

VelocityBins resolve_bins(const ModelParams& p, const VelocityBins& b) {
    check_bins(b);
    VelocityBins r = b;
    if (b.lo == 0 && b.hi == 0) auto_range(p, r.lo, r.hi);
    return r;
}

// ---- stationary density ------------------------------------------------------

namespace {

PreparedEngine prepare_request(const DensityRequest& req_in) {
    const DensityRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
    PreparedEngine engine = prepare(static_cast<const RunSettings&>(req));
    validate(static_cast<const ExcursionSettings&>(req));
    check_bins(req.bins);
    check_event_sampling(req);
    sampling_interval(req.engine, req.sample_dt);
    detail::check_excursions_can_end(engine, extra_sampling(req.engine, req.sample_dt));
    return engine;
}

} // namespace

void validate(const DensityRequest& req) { prepare_request(req); }

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
    out.resolved = prepared.resolved;
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
    out.totals = detail::run_blocks<Acc>(
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
    detail::finish_long_excursion_run(prepared, out.totals, req.allow_capped, out.warnings);
    out.estimates = estimate_long_excursion(out.totals.moments, req.level);
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

DensityResult compute_density(const DensityRequest& req_in) {
    const DensityRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
    const PreparedEngine prepared = prepare_request(req);
    const std::vector<std::string> notes =
        detail::start_notes(prepared, req.excursions, req.control, extra_sampling(req.engine, req.sample_dt));
    return detail::visit_engine(prepared, [&](const auto& engine) { return density_of(engine, req, prepared, notes); });
}

// ---- autocorrelation -------------------------------------------------------------

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
    return engine;
}

} // namespace

void validate(const CorrelationRequest& req) { prepare_request(req); }

CorrelationResult compute_correlation(const CorrelationRequest& req_in) {
    const CorrelationRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
    const PreparedEngine prepared = prepare_request(req);
    const std::vector<std::string> notes =
        detail::start_notes(prepared, req.excursions, req.control, extra_sampling(req.engine, req.sample_dt));
    CorrelationResult out;
    out.request = req;
    out.resolved = prepared.resolved;
    const double dt = sampling_interval(req.engine, req.sample_dt);
    const double max_lag = req.max_lag > 0 ? req.max_lag : 5 * scales_of(req.params).time;
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
    out.totals = detail::visit_engine(prepared, [&](const auto& engine) {
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
    detail::finish_long_excursion_run(prepared, out.totals, req.allow_capped, out.warnings);
    out.estimates = estimate_long_excursion(out.totals.moments, req.level);
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

// ---- transient ----------------------------------------------------------------------

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
    out.resolved = prepared.resolved;
    out.resolved.stop_rule = "none";
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
    out.totals = detail::visit_engine(prepared, [&](const auto& engine) {
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
    detail::note_interruption(out.totals, "trajectories", out.warnings);
    const RatioMoments total = exact.moments();
    for (std::size_t j = 0; j < nt; ++j) {
        out.first_moment.push_back(total.estimate(j, req.level));
        out.second_moment.push_back(total.estimate(nt + j, req.level));
        out.stuck.push_back(total.estimate(2 * nt + j, req.level));
        if (nh) out.density.push_back(make_histogram(bins, total, 3 * nt + j * nh, req.level));
    }
    const std::string lattice = detail::visit_engine(
        prepared, [&](const auto& engine) { return engine.lattice_note(out.resolved, false); });
    if (!lattice.empty()) out.warnings.push_back(lattice);
    out.warnings.insert(out.warnings.begin(), notes.begin(), notes.end());
    return out;
}

// ---- sample paths --------------------------------------------------------------------

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
                out.excursion = engine.excursion_path(seed, req.index, req.every, add);
                if (!out.excursion.capped) { // the regeneration state that ends it
                    const detail::PathPoint q = engine.regeneration_point(out.excursion);
                    append(path, q.t, q.x, q.mode, q.v, q.u);
                }
            });
        } catch (const TooManyPoints&) {
            throw InvalidParameter("every", "the excursion has more than " + std::to_string(req.max_points) +
                                                " recorded points; record less often (--every)");
        }
        if (out.excursion.capped)
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
