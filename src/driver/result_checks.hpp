// SPDX-License-Identifier: BSD-3-Clause
// Internal: checks and warnings shared by every long-excursion computation
// (diffusivity, stationary density, correlation), so they say the same thing.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "driver/step_check.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/run.hpp"
#include "stickslip/stats/run_totals.hpp"

namespace stickslip::detail {

/// Below this many excursions the standard error of D is itself too noisy to
/// trust (U is heavy-tailed); the reports say so.
inline constexpr std::uint64_t few_excursions = 5000;

/// Throws CappedExcursions when excursions hit the runaway guard (unless
/// allowed: then warns) or fewer than 2 completed, UntrustworthyResult when
/// every excursion ended within its first step; adds the standard warnings
/// (interrupted run, truncated PDMP lattice, few excursions unless the run
/// measured the shape of its influence function (`diagnosed`: its own note
/// then says whether the interval holds), meaning of mean_duration).
void finish_long_excursion_run(const PreparedEngine& e, const RunTotals& totals, bool allow_capped,
                               std::vector<std::string>& warnings, bool diagnosed = false);

/// The note of a run whose D interval is flagged (ControlVariateReport::
/// flagged): the tail of D's influence function, measured on `excursions`,
/// has index `tail_index` below `threshold` (interval_flag_tail_index).
std::string interval_flag_note(std::uint64_t excursions, double tail_index, double threshold);
/// The first words of that note, by which a sweep gathers its points' notes.
inline constexpr std::string_view interval_flag_note_start = "D's interval may cover well below its level";
/// A sweep's one note for its `points` of `total` points whose interval is flagged.
std::string sweep_interval_flag_note(std::size_t points, std::size_t total, double threshold);

/// Throws UntrustworthyResult when an estimate or its standard error is not
/// a finite number (naming it), so that no NaN is ever reported as a result.
void check_finite(const LongExcursionEstimates& est);

/// The notes of a run about to start (the engine's, and for `excursions` > 0
/// long excursions the predicted cost, the path's samples included:
/// predict_run), each passed to RunControl::notice.
std::vector<std::string> start_notes(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl,
                                     const PathSampling& sampling = {});

/// A run stopped early (RunControl::stop): throws RunInterrupted when fewer
/// than 2 of its `samples` ("excursions", "trajectories") completed, else adds
/// the warning that says the result is from a prefix of the run.
void note_interruption(const RunTotals& totals, const char* samples, std::vector<std::string>& warnings);

/// Largest |v0| (in m/s and in velocity units noise/friction) and |x0| (in
/// s^-1/2 and in standard deviations 1/sqrt(tau)) a trajectory may start
/// from: the squares and fourth powers the estimators form stay within
/// double's range.
inline constexpr double max_start_magnitude = 1e100;

/// Checks a trajectory start of model `p`: v0 [m/s] finite and at most
/// max_start_magnitude ("v0"); x0 [s^-1/2] NaN, which means "the default
/// start", or finite and at most max_start_magnitude ("x0"); |bias| at most
/// max_start_magnitude frictions ("bias").
void check_start(const ModelParams& p, double x0, double v0);

/// The default start of a trajectory's noise [s^-1/2] (x0 NaN): 0 for white
/// noise, else the upper threshold x* (PDMP: the first lattice point above it).
double default_start_noise(const PreparedEngine& e);

} // namespace stickslip::detail
