// SPDX-License-Identifier: BSD-3-Clause
// Internal: the inclusion engine's event scheme behind the one engine
// interface (EngineAdapter, driver/visit_engine.hpp). Exact Gaussian steps
// within a phase, events at their times: its paths are pieces whose ends are
// exact, sampled on a grid by the one grid sampler through the scheme's own
// cubic of each piece; its clock counts leaves (dt / 2^event_depth).
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/format.hpp"
#include "engines/grid_sampler.hpp"
#include "engines/path_point.hpp"
#include "engines/event/event_steps.hpp"
#include "stickslip/kernels/event_lanes.hpp"
#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"

namespace stickslip::detail {

class EventEngine {
public:
    explicit EventEngine(const EventConstants& c) : c_(c) {}
    const EventConstants& constants() const { return c_; }

    static constexpr const char* work_unit = "steps";
    /// Work units per second on one core, for predicting a run's length only
    /// (measured on the CLI, docs/validation.md, reliability): the event scheme 5e6 steps per second (its refinements included).
    static constexpr double work_per_second = 5e6;
    /// The setting that sets its resolution, which a long run may be blamed on.
    static constexpr const char* resolution_setting = "dt";
    /// Whether a long run is blamed on the resolution before the model: never
    /// for the step (the cause falls through to tau, friction, noise, then "dt").
    static bool resolution_chosen(const EngineSettings&) { return false; }
    /// The time quantum of its paths [s]: a leaf.
    double clock() const { return c_.leaf; }

    bool long_excursions(std::uint64_t seed, std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                         const std::atomic<bool>* cancel) const {
        return event_long_excursions(c_, seed, first, count, out, cancel);
    }

    /// Why these constants have no martingale kernel, or nullptr when they
    /// have one (white noise's velocity levels have none).
    const char* no_martingale() const {
        return c_.white ? "the event scheme has no martingale for white noise (use --scheme resolvent)" : nullptr;
    }

    /// long_excursions with the martingale of the corrector g in each outcome
    /// (kernels/corrector.hpp).
    bool long_excursions_with(std::uint64_t seed, std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                              const std::atomic<bool>* cancel, const CorrectorTable& g) const {
        return event_long_excursions_with(c_, seed, first, count, out, cancel, g);
    }

    ExcursionOutcome trajectory(std::uint64_t seed, std::uint64_t k, double x0, double v0, double horizon) const {
        const auto at = static_cast<std::uint64_t>(std::llround(horizon / c_.leaf));
        BatchedCounterRng rng(seed, StreamPurpose::BruteForce, k);
        BatchedCounterRng ref(seed, StreamPurpose::Refinement, k);
        EventWalk w = event_walk_from(c_, x0, v0);
        NoPieceObserver none;
        ExcursionOutcome o;
        o.capped = event_advance_to(c_, w, at, rng, ref, none) == EventStatus::Capped;
        o.displacement = w.u;
        o.duration = c_.leaf * static_cast<double>(w.t);
        o.work = w.steps + w.midpoints;
        return o;
    }

    /// V [m/s] at fraction q of a piece of length len [s]: the scheme's own
    /// cubic Hermite interpolant of the piece's exact ends and of its slopes
    /// there, dV/dt = bias + a X - phase friction - V/tauL (detail::cubic_ends,
    /// the one its landing test bounds), never of the wrong sign; 0 through a
    /// stuck piece. Linear interpolation left out the curvature that the
    /// noise's drift over the piece gives V, and so lifted the normalised
    /// covariance at lags of one or two steps (z = 3.95 at lag 0.025 s, Fig. 5
    /// case at tau = 0.25 s and the automatic step 0.0156 s;
    /// docs/validation.md). X and U are interpolated linearly.
    double velocity(const EventPiece& p, double len, double q) const {
        if (p.phase == 0) return 0.0;
        const double s = p.phase;
        const double sv = cubic_through(cubic_ends(c_.amp, c_.inv_relaxation, len, p.x0, p.v0, p.x1, p.v1, s,
                                                   c_.bias - s * c_.friction))
                              .at(q);
        return sv > 0.0 ? s * sv : 0.0;
    }
    double piece_end(const EventPiece& p, double offset) const {
        return offset + c_.leaf * static_cast<double>(p.t1);
    }
    template <class F>
    void sample_piece(const EventPiece& p, double g, double offset, F& f) const {
        const double t0 = offset + c_.leaf * static_cast<double>(p.t0), t1 = piece_end(p, offset);
        const double q = t1 > t0 ? (g - t0) / (t1 - t0) : 0.0;
        f(p.x0 + (p.x1 - p.x0) * q, p.phase, velocity(p, t1 - t0, q), p.u0 + (p.u1 - p.u0) * q);
    }

    /// As PdmpEngine::sampled_excursion; the continuation runs new long
    /// excursions from s+ after each regeneration.
    template <class OnV, class More>
    ExcursionOutcome sampled_excursion(std::uint64_t seed, std::uint64_t k, double dt, double phase, OnV&& on_v,
                                       More&& more) const {
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, k);
        BatchedCounterRng ref(seed, StreamPurpose::Refinement, k);
        auto sampler = grid_sampler(*this, dt, [&](double, int, double v, double) { on_v(v); }, phase);
        ExcursionOutcome o = event_long_excursion(c_, rng, ref, sampler);
        if (o.capped) return o;
        const std::optional<std::uint64_t> more_samples = more();
        if (!more_samples) return o;
        const std::uint64_t extra = *more_samples;
        sampler.offset = o.duration;
        sampler.stop_at = sampler.next + extra;
        o.work += continue_path(rng, ref, sampler, [&] { return sampler.next < sampler.stop_at; });
        return o;
    }

    template <class F>
    ExcursionOutcome excursion_path(std::uint64_t seed, std::uint64_t index, double every, F&& f) const {
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, index);
        BatchedCounterRng ref(seed, StreamPurpose::Refinement, index);
        if (every > 0) {
            auto sampler = point_sampler(*this, every, f);
            return event_long_excursion(c_, rng, ref, sampler);
        }
        // Every piece's start, so events are in the path at their times.
        return event_long_excursion(c_, rng, ref, [&](const EventPiece& p) {
            f(PathPoint{c_.leaf * static_cast<double>(p.t0), p.x0, p.phase, p.v0, p.u0});
        });
    }
    PathPoint regeneration_point(const ExcursionOutcome& o) const {
        return {o.duration, c_.white ? 0.0 : c_.x_up, 1, c_.white ? c_.level : 0.0, o.displacement};
    }

    /// Times rounded to the scheme's clock (a leaf; exact to half a leaf).
    std::vector<double> clock_times(const std::vector<double>& times, std::vector<std::string>&) const {
        std::vector<double> out;
        for (double t : times) out.push_back(static_cast<double>(leaves(t)) * c_.leaf);
        return out;
    }

    /// Exact times (to a leaf): the walk advances to each time in turn.
    template <class StartX, class Record>
    ExcursionOutcome path_at_times(std::uint64_t seed, std::uint64_t k, StartX&& start_x, double v0,
                                   const std::vector<double>& times, Record&& record) const {
        BatchedCounterRng rng(seed, StreamPurpose::Observable, k);
        BatchedCounterRng ref(seed, StreamPurpose::Refinement, k);
        const double x = start_x(rng);
        EventWalk w = event_walk_from(c_, x, v0);
        NoPieceObserver none;
        ExcursionOutcome o;
        for (std::size_t j = 0; j < times.size(); ++j) {
            if (event_advance_to(c_, w, leaves(times[j]), rng, ref, none) == EventStatus::Capped) {
                o.capped = true;
                break;
            }
            record(j, w.v);
        }
        o.duration = c_.leaf * static_cast<double>(w.t);
        o.displacement = w.u;
        o.work = w.steps + w.midpoints;
        return o;
    }

    template <class F>
    void path_on_grid(std::uint64_t seed, std::uint64_t k, double x0, double v0, double every, std::uint64_t npoints,
                      F&& f, std::vector<std::string>& warnings) const {
        BatchedCounterRng rng(seed, StreamPurpose::BruteForce, k);
        BatchedCounterRng ref(seed, StreamPurpose::Refinement, k);
        EventWalk w = event_walk_from(c_, x0, v0);
        NoPieceObserver none;
        for (std::uint64_t i = 0; i < npoints; ++i) {
            const auto at = static_cast<std::uint64_t>(std::llround(static_cast<double>(i) * every / c_.leaf));
            if (event_advance_to(c_, w, at, rng, ref, none) == EventStatus::Capped) break;
            f(PathPoint{c_.leaf * static_cast<double>(w.t), w.x, w.phase, w.v, w.u});
        }
        // The walk's clock counts leaves (dt / 2^event_depth), so a grid time
        // that is not a whole number of them is rounded to the nearest.
        const double leaves_per_point = every / c_.leaf;
        if (k == 0 && std::fabs(leaves_per_point - std::round(leaves_per_point)) > 1e-9 * leaves_per_point)
            warnings.push_back("recorded times rounded to the event scheme's clock, dt/" +
                               std::to_string(std::llround(c_.h / c_.leaf)) + " = " + format_number(c_.leaf) +
                               " s (at most half that off)");
    }

    /// Work [steps] of a path of duration t [s].
    double work_for(double t) const { return t / c_.h; }
    static std::string lattice_note(const ResolvedEngine&, const EngineSettings&, const ModelParams&, bool) {
        return {};
    }
    static std::string mean_duration_note(const ModelParams&) { return {}; }
    /// The step against the scheme's measured reach (driver/step_check.hpp).
    void check_step(const Model& m, std::vector<std::string>& notes) const { check_event_step(m, c_.h, notes); }
    /// Whether its step blurs the noise at the scale of tau: its steps are exact.
    bool coarse_against_tau(const ModelParams&) const { return false; }

    double default_start_noise(const Model& m) const { return m.upper_threshold(); }

    static std::string sampling_note(double dt) {
        return "event-scheme path sampled every " + format_number(dt) +
               " s (--sample-dt) with a random phase per excursion, V interpolated within pieces";
    }

private:
    std::uint64_t leaves(double t) const { return static_cast<std::uint64_t>(std::llround(t / c_.leaf)); }

    /// Runs the walk on (a new long excursion from s+ after each
    /// regeneration) until `more()` is false: the continuation of a path past
    /// the end of its excursion. Returns the work done.
    template <class Rng, class RefRng, class Observer, class More>
    std::uint64_t continue_path(Rng& rng, RefRng& ref, Observer& observe, More more) const {
        EventWalk w;
        event_start_half(c_, w, +1);
        while (more()) {
            const EventStatus st = event_step(c_, w, 0, rng, ref, observe);
            if (st == EventStatus::Capped) break;
            if (st == EventStatus::HalfDone) event_start_half(c_, w, -w.dir);
        }
        return w.steps + w.midpoints;
    }

    const EventConstants& c_;
};

} // namespace stickslip::detail
