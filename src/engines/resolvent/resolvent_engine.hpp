// SPDX-License-Identifier: BSD-3-Clause
// Internal: the inclusion engine's resolvent scheme behind the one engine
// interface (EngineAdapter, driver/visit_engine.hpp). The paper's Algorithm
// 3, corrected: the state is known at the steps only, so its paths are
// sampled at every step (its own grid: a --sample-dt does not apply) and its
// clock is the step dt.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/format.hpp"
#include "engines/path_point.hpp"
#include "engines/resolvent/resolvent_steps.hpp"
#include "stickslip/kernels/resolvent.hpp"
#include "stickslip/kernels/resolvent_lanes.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "stickslip/engine.hpp"

namespace stickslip::detail {

class ResolventEngine {
public:
    explicit ResolventEngine(const ResolventConstants& c) : c_(c) {}
    const ResolventConstants& constants() const { return c_; }

    static constexpr const char* work_unit = "steps";
    /// Work units per second on one core, for predicting a run's length only
    /// (measured on the CLI, docs/validation.md, reliability): the resolvent scheme 5e7 to 1e8 steps per second (64 excursions at tau 1e-6: 1.0e8).
    static constexpr double work_per_second = 5e7;
    /// The setting that sets its resolution, which a long run may be blamed on.
    static constexpr const char* resolution_setting = "dt";
    /// Whether a long run is blamed on the resolution before the model: never
    /// for the step (the cause falls through to tau, friction, noise, then "dt").
    static bool resolution_chosen(const EngineSettings&) { return false; }
    /// The time quantum of its paths [s]: the step.
    double clock() const { return c_.h; }

    bool long_excursions(std::uint64_t seed, std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                         const std::atomic<bool>* cancel) const {
        return resolvent_long_excursions(c_, seed, first, count, out, cancel);
    }

    /// long_excursions with the martingale of the corrector g in each outcome
    /// (kernels/corrector.hpp).
    bool long_excursions_with(std::uint64_t seed, std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                              const std::atomic<bool>* cancel, const CorrectorTable& g) const {
        return resolvent_long_excursions_with(c_, seed, first, count, out, cancel, g);
    }

    ExcursionOutcome trajectory(std::uint64_t seed, std::uint64_t k, double x0, double v0, double horizon) const {
        const std::uint64_t nsteps = bruteforce_steps(horizon, c_.h);
        BatchedCounterRng rng(seed, StreamPurpose::BruteForce, k);
        return resolvent_trajectory(c_, x0, v0, nsteps, rng);
    }

    /// Long excursion k sampled at every step (dt and phase do not apply: the
    /// scheme knows the path at its steps only); the continuation is the
    /// process itself: the following long excursions (same kernel: threshold
    /// restarts and skipped detecting steps included), cut after `more()`
    /// further steps.
    template <class OnV, class More>
    ExcursionOutcome sampled_excursion(std::uint64_t seed, std::uint64_t k, double /*dt*/, double /*phase*/,
                                       OnV&& on_v, More&& more) const {
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, k);
        auto observe = [&](double, double v) { on_v(v); };
        ExcursionOutcome o = resolvent_long_excursion(c_, rng, observe);
        if (o.capped) return o;
        const std::optional<std::uint64_t> more_samples = more();
        if (!more_samples) return o;
        const std::uint64_t extra = *more_samples;
        ResolventConstants next = c_;
        std::uint64_t remaining = extra;
        while (remaining > 0) {
            next.max_steps = remaining;
            remaining -= std::min(remaining, resolvent_long_excursion(next, rng, observe).work);
        }
        o.work += extra;
        return o;
    }

    /// Long excursion `index` as a path: every step (every == 0) or every
    /// round(every / dt) steps.
    template <class F>
    ExcursionOutcome excursion_path(std::uint64_t seed, std::uint64_t index, double every, F&& f) const {
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, index);
        const auto stride = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(every / c_.h)));
        std::uint64_t n = 0;
        double u = 0.0;
        return resolvent_long_excursion(c_, rng, [&](double x, double v) {
            if (n % stride == 0) f(PathPoint{static_cast<double>(n) * c_.h, x, mode_of(v), v, u});
            u += c_.h * v;
            ++n;
        });
    }
    PathPoint regeneration_point(const ExcursionOutcome& o) const {
        return {o.duration, c_.white ? 0.0 : c_.x_up, c_.white ? 1 : 0, c_.white ? c_.level : 0.0, o.displacement};
    }

    /// Times rounded to whole steps of dt, with a warning when that moved any.
    std::vector<double> clock_times(const std::vector<double>& times, std::vector<std::string>& warnings) const {
        std::vector<std::uint64_t> steps;
        for (double t : times) steps.push_back(steps_of(t));
        std::vector<double> out;
        for (std::uint64_t n : steps) out.push_back(static_cast<double>(n) * c_.h);
        if (std::adjacent_find(steps.begin(), steps.end()) != steps.end())
            warnings.push_back("some times round to the same step of dt; their rows are identical");
        for (std::size_t j = 0; j < times.size(); ++j)
            if (std::fabs(out[j] - times[j]) > 1e-9 * std::max(times[j], c_.h)) {
                warnings.push_back("times rounded to whole steps of dt = " + format_number(c_.h) + " s");
                break;
            }
        return out;
    }

    template <class StartX, class Record>
    ExcursionOutcome path_at_times(std::uint64_t seed, std::uint64_t k, StartX&& start_x, double v0,
                                   const std::vector<double>& times, Record&& record) const {
        BatchedCounterRng rng(seed, StreamPurpose::Observable, k);
        // times are sorted: the step of the next one is all the walk needs
        // (no per-trajectory array).
        const std::size_t nt = times.size();
        double x = start_x(rng);
        double v = v0;
        std::size_t j = 0;
        std::uint64_t n = 0, next = steps_of(times[0]);
        const ExcursionOutcome o = resolvent_path(c_, x, v, steps_of(times.back()), rng, [&](double, double vn) {
            while (j < nt && next == n) {
                record(j, vn);
                if (++j < nt) next = steps_of(times[j]);
            }
            ++n;
        });
        while (j < nt) record(j++, v);
        return o;
    }

    template <class F>
    void path_on_grid(std::uint64_t seed, std::uint64_t k, double x0, double v0, double every, std::uint64_t npoints,
                      F&& f, std::vector<std::string>& warnings) const {
        BatchedCounterRng rng(seed, StreamPurpose::BruteForce, k);
        const auto stride = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(every / c_.h)));
        const std::uint64_t nsteps = (npoints - 1) * stride;
        double x = x0, v = v0, u = 0.0;
        std::uint64_t n = 0;
        resolvent_path(c_, x, v, nsteps, rng, [&](double xn, double vn) {
            if (n % stride == 0) f(PathPoint{static_cast<double>(n) * c_.h, xn, mode_of(vn), vn, u});
            u += c_.h * vn;
            ++n;
        });
        f(PathPoint{static_cast<double>(nsteps) * c_.h, x, mode_of(v), v, u});
        if (k == 0 && std::fabs(static_cast<double>(stride) * c_.h - every) > 1e-9 * every)
            warnings.push_back("recording interval rounded to " + std::to_string(stride) + " steps of dt");
    }

    /// Work [steps] of a path of duration t [s].
    double work_for(double t) const { return t / c_.h; }
    static std::string lattice_note(const ResolvedEngine&, const EngineSettings&, const ModelParams&, bool) {
        return {};
    }
    static std::string mean_duration_note(const ModelParams&) { return {}; }
    /// The step against the scheme's measured bias law (driver/step_check.hpp).
    void check_step(const Model& m, std::vector<std::string>& notes) const {
        check_resolvent_step(m, c_.h, notes);
    }
    /// Whether its step is not small against tau (or the noise is white):
    /// then P(V = 0) carries the scheme's O(dt) quantisation of V near 0 and
    /// E[t1] depends on the step and the stop rule.
    bool coarse_against_tau(const ModelParams& p) const { return p.white() || c_.h > 0.01 * p.tau; }

    double default_start_noise(const Model& m) const { return m.upper_threshold(); }

    /// Nothing to say: the scheme samples at its own steps.
    static std::string sampling_note(double) { return {}; }

private:
    static int mode_of(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }
    std::uint64_t steps_of(double t) const { return static_cast<std::uint64_t>(std::llround(t / c_.h)); }

    const ResolventConstants& c_;
};

} // namespace stickslip::detail
