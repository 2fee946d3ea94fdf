// SPDX-License-Identifier: BSD-3-Clause
#include "quantities/path_sampling.hpp"

#include <algorithm>
#include <cmath>

#include "core/format.hpp"
#include "stickslip/analytic.hpp"
#include "stickslip/random/rng.hpp"

namespace stickslip {
namespace detail {

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


namespace {

/// e with its interval cut to [lo, hi], the range the quantity is known to lie
/// in: a density is >= 0 and a probability in [0, 1], which the normal
/// (delta-method) interval of a small or near-empty bin ignores.
Estimate within(Estimate e, double lo, double hi) {
    e.lo = std::max(e.lo, lo);
    e.hi = std::min(e.hi, hi);
    return e;
}

} // namespace

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
        e.error /= width;
        e.lo /= width;
        e.hi /= width;
        h.density.push_back(within(e, 0.0, HUGE_VAL));
    }
    const std::size_t base = first + static_cast<std::size_t>(b.count);
    h.stuck = within(m.estimate(base, level), 0.0, 1.0);
    h.below = within(m.estimate(base + 1, level), 0.0, 1.0);
    h.above = within(m.estimate(base + 2, level), 0.0, 1.0);
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


/// A report's note on how the path was sampled, if the engine has one.
void add_sampling_note(const std::string& note, std::vector<std::string>& warnings) {
    if (!note.empty()) warnings.push_back(note);
}

namespace {

/// The automatic histogram range [m/s]: six standard deviations about the mean.
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
} // namespace detail

VelocityBins resolve_bins(const ModelParams& p, const VelocityBins& b) {
    detail::check_bins(b);
    VelocityBins r = b;
    if (b.lo == 0 && b.hi == 0) detail::auto_range(p, r.lo, r.hi);
    return r;
}

} // namespace stickslip
