// SPDX-License-Identifier: BSD-3-Clause
// Internal: what the numerics can honour, judged before a run from the
// model's time scales (issue "numbers you can trust by default").
//
// Two questions, answered from closed forms so that they cost nothing:
//
// * Does the step resolve the dynamics? The resolvent scheme's bias of D is
//   set by the step in friction times, dt' = dt / (noise / friction^2):
//   measured, white and near-white noise (tau' < 0.3) converge like
//   -0.39 sqrt(dt') (-3.9% at dt' = 1e-2, -28% at 0.5), coloured noise
//   (tau' >= 0.3, the paper's Fig. 2 case, drag included) like +0.35 dt'
//   (+1.1% at dt' = 0.03, +3% at 0.09). A step whose predicted bias exceeds
//   2% is warned about; one whose predicted bias exceeds 20%, or longer than
//   the friction time, is refused. The event scheme is exact within phases
//   but not across them: its step is judged against the reach its tables
//   measured (coloured noise: a note beyond tau, a refusal beyond 8 tau;
//   white noise: notes beyond relaxation/4 or half the friction time,
//   refusals beyond 2 relaxation or 2 friction times; see step_check.cpp).
//   The PDMP has no step.
//
// * Which step does --dt auto take? The largest at which the measured
//   convergence shows the scheme's bias of D below 0.1%: for the resolvent
//   scheme, the law above solved for 0.1%; for the event scheme, a fixed
//   fraction of the shortest time scale (engines/{resolvent,event}/*_steps.hpp).
//
// * Can an excursion finish? An excursion of coloured noise ends only when,
//   stuck, the noise has crossed the static band from one threshold to the
//   other, so it lasts at least about the mean first-passage time of the
//   Ornstein-Uhlenbeck noise from 0 to the thresholds, T(h) = tau sqrt(2 pi)
//   int_0^h exp(u^2/2) Phi(u) du with h the threshold in standard deviations
//   of the noise (exact for the OU process; Fig. 2 case: 3.1 s against the
//   measured E[t1] = 8.1 s). When even this lower bound needs more steps (or
//   PDMP events) than --max-steps allows, most excursions would run into the
//   guard: the run is refused at once, with the estimate, rather than after
//   an hour; when the run as a whole is predicted to be long, it says so.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engines/event/event_steps.hpp"
#include "engines/resolvent/resolvent_steps.hpp"
#include "stickslip/run.hpp"

namespace stickslip::detail {

/// Mean first-passage time [s] of the stationary OU noise (correlation time
/// tau [s]) from 0 to h standard deviations, h >= 0; +inf beyond h = 37.
double ou_first_passage_time(double h, double tau);

/// A lower bound of the mean duration E[t1] [s] of a long excursion of
/// coloured noise: the mean of T(h) over the two thresholds. 0 for white noise.
double excursion_duration_lower_bound(const Model& m);

/// Steps (inclusion) or events (PDMP) a long excursion needs at least, and
/// with sample_dt > 0 [s] (density, correlation) its samples, one unit each.
double excursion_work_lower_bound(const PreparedEngine& e, double sample_dt = 0.0);

/// Refuses (InvalidParameter "dt") a resolvent step whose predicted bias of D
/// exceeds 20% or that is longer than the friction time, and an event step far
/// beyond its measured reach; adds a note for a resolvent step whose predicted
/// bias exceeds 2% and an event step beyond its measured reach.
void check_step(const PreparedEngine& e, std::vector<std::string>& notes);

/// The relative precision of D [1] to which the automatic steps' bias of D
/// has been checked: the convergence tables of docs/validation.md ("Choosing
/// the step") resolve 0.3%.
inline constexpr double auto_step_checked_to = 0.003;

/// Adds a note when a run at an automatic step (`dt_auto`, an engine with a
/// step) reached a relative half-width of D below auto_step_checked_to: its
/// interval then says nothing about the step's bias, which can be as large
/// (measured on the Fig. 2 case with the event scheme: +0.18% +- 0.05% at its
/// former automatic step, relaxation/4; +0.06% +- 0.05% at relaxation/8).
void note_precision_beyond_step(const PreparedEngine& e, bool dt_auto, double relative_half_width,
                                std::vector<std::string>& notes);

/// The first words of that note, by which a sweep gathers its points' notes.
inline constexpr std::string_view precision_note_start = "D's relative half-width, ";

/// A sweep's one note for its `points` points that got that note, the
/// narrowest relative half-width among them `narrowest` [1].
std::string sweep_precision_note(std::size_t points, double narrowest);



/// Refuses (InvalidParameter "max-steps") a run of long excursions that
/// cannot end under the runaway guard (see the top of the file), and
/// (InvalidParameter "sample-dt") one whose samples every sample_dt > 0 [s]
/// alone would exceed the guard.
void check_excursions_can_end(const PreparedEngine& e, double sample_dt = 0.0);

/// What a run records along each excursion, for the prediction of its cost
/// (predict_run): nothing for `diffusivity`; `density` and `correlation`
/// sample the path, and `correlation` continues it past the excursion's end.
struct PathSampling {
    double interval = 0.0;   ///< a sample every `interval` [s] beyond the engine's steps (0: none, or at the steps)
    double per_sample = 0.0; ///< extra work of one sample [steps of the engine] (correlation: its lag products)
    double continued = 0.0;  ///< time [s] each path runs past its excursion's end (correlation: the largest lag)
};

/// The one prediction of a run's duration, made before its first block:
/// the mean duration of an excursion from the model's time scales (the
/// larger of 3 times the OU first-passage bound above and one friction time
/// noise/friction^2, which near-white and white noise reach), in steps or
/// events of the engine (its step, its event rate) plus its samples every
/// the path's samples (PathSampling: each excursion's path continued by
/// `continued`, a unit of work per sample every `interval`, `per_sample` more
/// per sample wherever taken), times a measured cost per step or event on one
/// core, times the
/// excursions, over the threads. Measured against real runs in
/// docs/validation.md (reliability): within a factor of 3 either way.
struct RunPrediction {
    double excursion_seconds = 0.0; ///< predicted mean duration E[t1] of one excursion [s] (model time)
    double work = 0.0;              ///< predicted steps or events (samples included) per excursion
    double seconds = 0.0;           ///< predicted wall time of the whole run [s] on `threads`
    unsigned threads = 1;           ///< the worker threads the run will use
    std::string cause;              ///< the setting that makes it long ("tau", "grid", "excursions"...)
};

/// The prediction of `samples` long excursions of `e` on the threads `ctl`
/// asks for (0: default_threads()).
RunPrediction predict_run(const PreparedEngine& e, std::uint64_t samples, const RunControl& ctl,
                          const PathSampling& sampling = {});

/// Predicted wall time [s] beyond which a run is refused as hopeless: two days.
inline constexpr double hopeless_seconds = 2 * 86400.0;

/// Refuses (InvalidParameter naming RunPrediction::cause) a run of `samples`
/// long excursions predicted to last more than hopeless_seconds, with the
/// prediction and what to change; unless only their number makes it long
/// (RunPrediction::cause "excursions"): such a run stops at any signal with
/// the result so far, and note_cost gives its duration.
void check_run_duration(const PreparedEngine& e, std::uint64_t samples, const RunControl& ctl,
                        const PathSampling& sampling = {});

/// A predicted duration [s] from which a run says so at once, terminal or
/// not (RunControl::long_run): an hour.
inline constexpr double long_run_seconds = 3600.0;

/// A note with the predicted duration when `samples` long excursions are
/// predicted to last a minute or more; nothing otherwise. From
/// long_run_seconds on, the note is also handed to ctl.long_run.
void note_cost(const PreparedEngine& e, std::uint64_t samples, const RunControl& ctl,
               std::vector<std::string>& notes, const PathSampling& sampling = {});

} // namespace stickslip::detail
