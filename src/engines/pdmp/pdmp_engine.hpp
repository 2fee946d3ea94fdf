// SPDX-License-Identifier: BSD-3-Clause
// Internal: the PDMP engine behind the one engine interface (EngineAdapter,
// driver/visit_engine.hpp). Exact event-driven paths: between events the
// state follows a closed-form flow, so the path is known at any time and is
// sampled on a grid by the one grid sampler; there is no time step, and the
// work is counted in events.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <boost/math/special_functions/erf.hpp>

#include "core/format.hpp"
#include "engines/grid_sampler.hpp"
#include "engines/path_point.hpp"
#include "stickslip/kernels/pdmp.hpp"
#include "stickslip/engine.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"

namespace stickslip::detail {

class PdmpEngine {
public:
    explicit PdmpEngine(const PdmpConstants& c) : c_(c) {}
    const PdmpConstants& constants() const { return c_; }

    /// What the work of a run counts.
    static constexpr const char* work_unit = "events";
    /// Work units per second on one core, for predicting a run's length only
    /// (measured on the CLI, docs/validation.md, reliability): the PDMP 1.4e7 events per second.
    static constexpr double work_per_second = 1.4e7;
    /// The setting that sets its resolution, which a long run may be blamed on.
    static constexpr const char* resolution_setting = "grid";
    /// Whether a long run is blamed on the resolution before the model: when
    /// the lattice step is not the default one.
    static bool resolution_chosen(const EngineSettings& s) { return s.grid != EngineSettings{}.grid; }
    /// The time quantum of its paths [s]: none, the PDMP runs in continuous time.
    double clock() const { return 0.0; }

    /// Long excursions first .. first+count-1, streams (seed, LongExcursion,
    /// index), into out; false when *cancel was set (checked before every one).
    bool long_excursions(std::uint64_t seed, std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                         const std::atomic<bool>* cancel) const {
        for (std::uint64_t i = 0; i < count; ++i) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return false;
            BatchedUniformRng rng(seed, StreamPurpose::LongExcursion, first + i);
            out[i] = pdmp_long_excursion(c_, rng);
        }
        return true;
    }

    /// long_excursions with the martingale of the corrector g in each outcome
    /// (pdmp_long_excursion_with).
    bool long_excursions_with(std::uint64_t seed, std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                              const std::atomic<bool>* cancel, const CorrectorTable& g) const {
        for (std::uint64_t i = 0; i < count; ++i) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return false;
            BatchedUniformRng rng(seed, StreamPurpose::LongExcursion, first + i);
            out[i] = pdmp_long_excursion_with(c_, rng, g);
        }
        return true;
    }

    /// Brute-force trajectory k on [0, horizon] [s] from (x0, v0).
    ExcursionOutcome trajectory(std::uint64_t seed, std::uint64_t k, double x0, double v0, double horizon) const {
        BatchedUniformRng rng(seed, StreamPurpose::BruteForce, k);
        return pdmp_trajectory(c_, x0, v0, horizon, rng);
    }

    /// A piece of the path as the kernels observe it: the state at its start,
    /// its start time t0 [s], displacement u0 [m] and duration [s].
    struct Piece {
        const PdmpState& s;
        double t0, u0, dur;
    };
    double piece_end(const Piece& p, double offset) const { return offset + p.t0 + p.dur; }
    template <class F>
    void sample_piece(const Piece& p, double g, double offset, F& f) const {
        double v = 0.0, u = p.u0;
        pdmp_flow_state(c_, p.s, g - offset - p.t0, v, u);
        f(pdmp_noise(c_, p.s.i), p.s.y, v, u);
    }

    /// Long excursion k (the one `diffusivity` runs) sampled on the grid phase
    /// + n dt: on_v(v) at each grid time; then, unless it was capped,
    /// `more()` samples more of the process after its end (from the
    /// regeneration state s+) when `more()` returns a count rather than
    /// std::nullopt. Returns the excursion's outcome, its work including the
    /// continuation's.
    template <class OnV, class More>
    ExcursionOutcome sampled_excursion(std::uint64_t seed, std::uint64_t k, double dt, double phase, OnV&& on_v,
                                       More&& more) const {
        BatchedUniformRng rng(seed, StreamPurpose::LongExcursion, k); // uniforms only: no ziggurat
        auto sampler = grid_sampler(*this, dt, [&](double, int, double v, double) { on_v(v); }, phase);
        auto observe = [&](const PdmpState& s, double t0, double u0, double dur) { sampler(Piece{s, t0, u0, dur}); };
        ExcursionOutcome o = pdmp_long_excursion(c_, rng, observe);
        if (o.capped) return o;
        const std::optional<std::uint64_t> more_samples = more();
        if (!more_samples) return o;
        const std::uint64_t extra = *more_samples;
        sampler.offset = o.duration;
        sampler.stop_at = sampler.next + extra;
        PdmpState s{c_.k_plus + 1, +1, 0.0};
        const double horizon = sampler.phase + static_cast<double>(sampler.stop_at + 1) * dt - o.duration;
        o.work += pdmp_path(c_, s, horizon, rng, observe).work;
        return o;
    }

    /// Long excursion `index` as a path: f(point) at every event (every == 0)
    /// or on the grid n * every; the regeneration state that ends it is
    /// regeneration_point(outcome).
    template <class F>
    ExcursionOutcome excursion_path(std::uint64_t seed, std::uint64_t index, double every, F&& f) const {
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, index);
        if (every > 0) {
            auto sampler = point_sampler(*this, every, f);
            return pdmp_long_excursion(c_, rng, [&](const PdmpState& s, double t0, double u0, double dur) {
                sampler(Piece{s, t0, u0, dur});
            });
        }
        return pdmp_long_excursion(c_, rng, [&](const PdmpState& s, double t0, double u0, double) {
            f(PathPoint{t0, pdmp_noise(c_, s.i), s.y, s.v, u0});
        });
    }
    PathPoint regeneration_point(const ExcursionOutcome& o) const {
        return {o.duration, pdmp_noise(c_, c_.k_plus + 1), 1, 0.0, o.displacement};
    }

    /// The times a path from a given state can be seen at: exactly those asked.
    std::vector<double> clock_times(const std::vector<double>& times, std::vector<std::string>&) const {
        return times;
    }

    /// Path k from (x0 = start_x(rng), v0), streams (seed, Observable, k):
    /// record(j, V(times[j])) for the sorted clock_times `times`.
    template <class StartX, class Record>
    ExcursionOutcome path_at_times(std::uint64_t seed, std::uint64_t k, StartX&& start_x, double v0,
                                   const std::vector<double>& times, Record&& record) const {
        BatchedCounterRng rng(seed, StreamPurpose::Observable, k);
        const double x0 = start_x(rng);
        PdmpState s = pdmp_initial_state(c_, x0, v0);
        const std::size_t nt = times.size();
        const double horizon = times.back();
        std::size_t j = 0;
        while (j < nt && times[j] == 0.0) record(j++, v0);
        ExcursionOutcome o;
        o.duration = horizon;
        if (horizon > 0) {
            o = pdmp_path(c_, s, horizon, rng, [&](const PdmpState& st, double t0, double, double dur) {
                while (j < nt && times[j] < t0 + dur) {
                    double v = 0.0, du = 0.0;
                    pdmp_flow_state(c_, st, times[j] - t0, v, du);
                    record(j++, v);
                }
            });
        }
        while (j < nt) record(j++, s.v);
        return o;
    }

    /// Independent path k (streams (seed, BruteForce, k)) from (x0, v0),
    /// f(point) at the times 0, every, ..., (npoints - 1) every [s].
    template <class F>
    void path_on_grid(std::uint64_t seed, std::uint64_t k, double x0, double v0, double every, std::uint64_t npoints,
                      F&& f, std::vector<std::string>&) const {
        BatchedCounterRng rng(seed, StreamPurpose::BruteForce, k);
        PdmpState s = pdmp_initial_state(c_, x0, v0);
        auto sampler = point_sampler(*this, every, f);
        sampler.stop_at = npoints;
        const double horizon = static_cast<double>(npoints - 1) * every;
        const ExcursionOutcome o = pdmp_path(c_, s, horizon, rng, [&](const PdmpState& st, double t0, double u0,
                                                                      double dur) { sampler(Piece{st, t0, u0, dur}); });
        if (sampler.next < npoints) f(PathPoint{horizon, pdmp_noise(c_, s.i), s.y, s.v, o.displacement});
    }

    /// Work [events] of a path of duration t [s], on average at least.
    double work_for(double t) const { return t * c_.rate; }
    /// Step checks: none (no step).
    void check_step(const Model&, std::vector<std::string>&) const {}
    /// Whether its step blurs the noise at the scale of tau: no step.
    bool coarse_against_tau(const ModelParams&) const { return false; }
    /// A note when the lattice is truncated (stationary noise mass beyond +-L
    /// above 1e-9); `detailed`: with that mass, as the long-excursion reports
    /// say. The cure names what set L: --lattice-bound when given (its note
    /// blamed the grid), else the grid (tau*grid*L < 2 bounds the lattice).
    static std::string lattice_note(const ResolvedEngine& r, const EngineSettings& s, const ModelParams& p,
                                    bool detailed) {
        constexpr double negligible = 1e-9; // stationary mass beyond +-L: erfc(L sqrt(tau/2))
        if (!(r.truncated_mass > negligible)) return {};
        const std::string cure =
            s.lattice_bound > 0 ? "raise --lattice-bound (the mass is below 1e-9 from L = " +
                                      format_number(boost::math::erfc_inv(negligible) * std::sqrt(2.0 / p.tau), 3) +
                                      " s^-1/2 on; tau*grid*L must stay below 2, so a finer --grid may be needed too)"
                                : "use a finer grid";
        return "the pdmp lattice is truncated at L = " + format_number(r.lattice_bound) + " s^-1/2" +
               (detailed ? " (tau*grid*L < 2): stationary noise mass beyond +-L is " + format_number(r.truncated_mass)
                         : std::string()) +
               "; " + cure;
    }
    /// What E[t1] of this engine means, for coloured noise. With a static band
    /// the regeneration states are the static edges themselves (the lattice is
    /// shifted onto them: kernels/pdmp.hpp), so E[t1] has no such offset.
    static std::string mean_duration_note(const ModelParams& p) {
        if (p.white() || p.has_static_band()) return {};
        return "pdmp mean_duration runs between the lattice points beyond the thresholds: it exceeds the "
               "continuum E[t1] by a few % (about 12% at tau = 1 s, grid 0.125); halve --grid to see it "
               "converge. D and M0 are not affected";
    }

    /// The start noise of a path when none is given [s^-1/2]: the lattice
    /// point just above the upper threshold (with a static band, the upper edge).
    double default_start_noise(const Model&) const { return pdmp_noise(c_, c_.k_plus + 1); }

    /// What a report of a path sampled every dt [s] says about the sampling.
    static std::string sampling_note(double dt) {
        return "pdmp path sampled every " + format_number(dt) +
               " s (--sample-dt) with a random phase per excursion: unbiased Riemann sums on that grid";
    }

private:
    const PdmpConstants& c_;
};

} // namespace stickslip::detail
