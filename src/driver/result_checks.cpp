// SPDX-License-Identifier: BSD-3-Clause
#include "driver/result_checks.hpp"

#include <cmath>
#include <tuple>
#include <utility>

#include "core/format.hpp"
#include "driver/step_check.hpp"
#include "driver/visit_engine.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/prepared_engine.hpp"

namespace stickslip::detail {

void finish_long_excursion_run(const PreparedEngine& e, const RunTotals& totals, bool allow_capped,
                               std::vector<std::string>& warnings, bool diagnosed) {
    const ModelParams& p = e.model.params;
    const EngineSettings& s = e.settings;
    const ResolvedEngine& resolved = e.resolved;
    const std::uint64_t done = totals.moments.count();
    note_interruption(totals, "excursions", warnings);
    if (totals.capped > 0) {
        const std::string msg = std::to_string(totals.capped) + " of " + std::to_string(totals.requested) +
                                " excursions hit the runaway guard of " + std::to_string(s.max_work_per_excursion) +
                                " " + work_unit(s) +
                                " and were dropped: the estimates are biased towards short excursions";
        if (!allow_capped) throw CappedExcursions(msg + " (raise --max-steps, or pass --allow-capped)");
        warnings.push_back(msg);
    }
    if (done < 2) throw CappedExcursions("fewer than 2 excursions completed; nothing to estimate");
    if (!(totals.moments.mean_y() > 0)) {
        // Every excursion ended at its first step: t = 0 and U = 0 for all, so
        // D and M0 would be 0/0. The step cannot see the noise cross the band.
        const ModelParams nd0 = to_nondimensional(p);
        std::string why = "every excursion ended within its first step (mean duration 0 s), so the estimates "
                          "would be 0/0: ";
        if (has_time_step(s) && !p.white() && nd0.tau < 0.1)
            why += "at tau' = " + format_number(nd0.tau) + " the noise crosses the static band faster than dt = " +
                   format_number(s.dt) + " s resolves; the noise is practically white: use --tau 0, or a much "
                                         "smaller --dt";
        else
            why += "the step does not resolve this model; use a much smaller --dt or the pdmp engine";
        throw UntrustworthyResult(why);
    }
    // What each engine notes of its own numerics (engines/<engine>/<engine>_engine.hpp).
    const auto [lattice, duration, coarse] = visit_engine(e, [&](const auto& engine) {
        return std::tuple{engine.lattice_note(resolved, e.settings, p, true), engine.mean_duration_note(p),
                          engine.coarse_against_tau(p)};
    });
    if (!lattice.empty()) warnings.push_back(lattice);
    if (done < few_excursions && !diagnosed)
        warnings.push_back("only " + std::to_string(done) +
                           " excursions (fewer than 5000): U is heavy-tailed, so the standard errors are "
                           "themselves uncertain; use 10000 or more for reliable intervals");
    const ModelParams nd = to_nondimensional(p);
    if (!duration.empty()) warnings.push_back(duration);
    if (p.white() && p.has_static_band())
        warnings.push_back(white_noise_static_friction_note() + "; a time step holds it for O(dt) at a landing, a "
                                                                "difference that vanishes as dt -> 0");
    if (p.white())
        warnings.push_back("white noise: mean_duration is the cycle time between the velocity levels +-" +
                           format_number(resolved.white_level) + " m/s, not a stick-slip excursion");
    else if (nd.tau < 0.1 || coarse)
        warnings.push_back("mean_duration depends on the discretisation and the stop rule when tau' < 0.1 or dt "
                           "is not << tau; report it with that caveat, not as a check");
}

namespace {
/// What a flagged interval means and what to do, said once for a run and a sweep.
constexpr const char* interval_flag_advice =
    " (Hill's estimate: a tail this heavy makes the run's own standard error unreliable); more excursions narrow "
    "the interval without making its level exact (88-93% for 95% measured at 20000 excursions on such models): "
    "compare runs with other seeds, or take --level 0.99";
} // namespace

std::string interval_flag_note(std::uint64_t excursions, double tail_index, double threshold) {
    return std::string(interval_flag_note_start) + ": the tail of its influence function, measured on " +
           std::to_string(excursions) + " excursions, has index " + format_number(tail_index, 3) + " < " +
           format_number(threshold, 3) + interval_flag_advice;
}

std::string sweep_interval_flag_note(std::size_t points, std::size_t total, double threshold) {
    return "at " + std::to_string(points) + " of " + std::to_string(total) + " points " +
           std::string(interval_flag_note_start) + ": the tail of its influence function has index < " +
           format_number(threshold, 3) + interval_flag_advice;
}

void check_finite(const LongExcursionEstimates& est) {
    for (const auto& [name, x] : {std::pair<const char*, const Estimate*>{"D", &est.diffusivity},
                                  {"M0", &est.mobility}, {"E[t1]", &est.mean_duration}})
        if (!std::isfinite(x->value) || !std::isfinite(x->error))
            throw UntrustworthyResult(std::string("the estimate of ") + name + " (" + format_number(x->value) +
                                      " +- " + format_number(x->error) +
                                      ") is not a finite number: the model's scales overflow double precision "
                                      "in this run; rescale friction and noise towards 1");
}

std::vector<std::string> start_notes(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl,
                                     const PathSampling& sampling) {
    std::vector<std::string> notes = e.notes;
    if (excursions > 0) note_cost(e, excursions, ctl, notes, sampling);
    if (ctl.notice)
        for (const auto& n : notes) ctl.notice(n);
    return notes;
}

void note_interruption(const RunTotals& totals, const char* samples, std::vector<std::string>& warnings) {
    if (!totals.interrupted) return;
    const std::uint64_t done = totals.moments.count() + totals.capped;
    if (totals.moments.count() < 2) throw RunInterrupted(totals.moments.count(), totals.requested, samples);
    warnings.push_back("interrupted: the result is from the first " + std::to_string(done) + " of " +
                       std::to_string(totals.requested) + " " + samples +
                       " (whole blocks in index order, so unbiased; the intervals are wider)");
}

void check_start(const ModelParams& p, double x0, double v0) {
    if (!std::isfinite(v0)) throw InvalidParameter("v0", "v0 must be a finite number (m/s)");
    if (std::isinf(x0)) throw InvalidParameter("x0", "x0 must be a finite number (s^-1/2)");
    // Found by the extreme-value sweep (tests/cli/extreme_values.py): a start
    // near 1e308 gave NaN means with exit 0 (bruteforce, moments).
    const double v_unit = scales_of(p).velocity;
    if (std::fabs(v0) > max_start_magnitude || std::fabs(v0) / v_unit > max_start_magnitude)
        throw InvalidParameter("v0", "v0 = " + format_number(v0) +
                                         " m/s: its square (E[V^2], U^2) would overflow double precision; |v0| "
                                         "must be at most 1e100, in m/s and in units of noise/friction");
    // The exact white-noise references take any finite bias; a path's
    // velocities (bias x relaxation, squared) overflow beyond this.
    if (std::fabs(p.bias) > max_start_magnitude * p.friction)
        throw InvalidParameter("bias", "bias = " + format_number(p.bias) +
                                           " m s^-2 is more than 1e100 times the friction: the velocities of a path "
                                           "would overflow double precision");
    const double sd = p.white() ? 1.0 : 1.0 / std::sqrt(p.tau);
    if (std::isfinite(x0) && (std::fabs(x0) > max_start_magnitude || std::fabs(x0) / sd > max_start_magnitude))
        throw InvalidParameter("x0", "x0 = " + format_number(x0) +
                                         " s^-1/2: the velocities it drives would overflow double precision; |x0| "
                                         "must be at most 1e100, in s^-1/2 and in standard deviations 1/sqrt(tau)");
}

double default_start_noise(const PreparedEngine& e) {
    if (e.model.params.white()) return 0.0;
    return visit_engine(e, [&](const auto& engine) { return engine.default_start_noise(e.model); });
}

} // namespace stickslip::detail
