// SPDX-License-Identifier: BSD-3-Clause
// Internal: what the path quantities share (density, correlation, moments,
// trajectory; observables.hpp explains the estimators): the checks and the
// layout of velocity histograms, the sampling interval and its random phase,
// and the one call of an engine's sampled excursion. Every observable is a
// path functional accumulated by an observer passed to the engines' own
// kernels, so the excursions are exactly those of `diffusivity`; each command
// is written once, over the engine adapter that detail::visit_engine hands it
// (driver/visit_engine.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "stickslip/observables.hpp"
#include "stickslip/stats/estimators.hpp"

namespace stickslip::detail {

inline constexpr int kMaxBins = 100000;

/// InvalidParameter ("bins", "range") for a bin count outside 1 .. kMaxBins
/// or a range that cannot be cut into that many bins (lo == hi == 0: automatic).
void check_bins(const VelocityBins& b);

/// The sampling interval that adds work of its own (an explicit --sample-dt
/// of an engine that samples on a grid), 0 otherwise: the cost model's input.
double extra_sampling(const EngineSettings& s, double sample_dt);

/// Sampling interval of a path observable [s]: the step where the engine
/// samples at its steps, else --sample-dt (0: the step dt).
double sampling_interval(const EngineSettings& s, double sample_dt);

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

/// The histogram of layout BinIndex starting at component `first` of m.
VelocityHistogram make_histogram(const VelocityBins& b, const RatioMoments& m, std::size_t first, double level);

/// The random grid phase of excursion k [s], in [0, dt), from its own stream
/// (the excursion's draws are untouched, so D stays that of `diffusivity`).
double sampling_phase(std::uint64_t seed, std::uint64_t k, double dt);

/// InvalidParameter ("scheme") when the engine cannot sample the model's
/// paths on a grid (samples_on_grid, engine.hpp).
void check_event_sampling(const RunSettings& r);

/// Long excursion k of `engine` (the one `diffusivity` runs) sampled every dt
/// [s] from `phase`: on_v(v) at every sample.
template <class Engine, class OnV>
ExcursionOutcome sampled_excursion(const Engine& engine, std::uint64_t seed, std::uint64_t k, double dt,
                                   double phase, OnV&& on_v) {
    return engine.sampled_excursion(seed, k, dt, phase, on_v, [] { return std::optional<std::uint64_t>{}; });
}

/// A report's note on how the path was sampled, if the engine has one.
void add_sampling_note(const std::string& note, std::vector<std::string>& warnings);

} // namespace stickslip::detail
