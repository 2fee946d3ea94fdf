// SPDX-License-Identifier: BSD-3-Clause
// stickslip/observables.hpp -- velocity statistics from both engines, with
// error bars (theory.md, section 1, "quantities of interest").
//
// Stationary quantities (velocity density, atom at V = 0, autocorrelation,
// normalised covariance) are renewal-reward ratios over long excursions: for a
// path functional g, lim (1/T) int_0^T g(s) ds = E[int_0^{t1} g(s) ds] / E[t1],
// because the process regenerates at the start of every excursion. There is
// no burn-in and no initial-condition bias; the interval comes from the delta
// method (RatioMoments). The excursions are exactly those of `diffusivity`
// with the same seed (same streams, same stop rule), so D, M0 and E[t1] come
// for free and agree with it bit for bit.
//
// Autocorrelation: int_0^{t1} V(s) V(s + r) ds needs the path up to t1 + r,
// past the end of the excursion. The path after a regeneration is a fresh copy
// of the process started at the regeneration state, so each excursion is
// continued for max lag with its own stream; the estimator stays exact.
//
// Transient quantities (p(v,t|v_i), E[V(t)|v_i]) are plain means over
// independent trajectories from V(0) = v_i with X(0) drawn from its stationary
// law N(0, 1/tau) (the paper's Fig. 7 / Table I set-up), or a given X(0).
//
// Sampling: the inclusion engine observes V at the start of every step
// (weight dt, the same left-point rule as the displacement). The PDMP engine is
// exact between events; its path is sampled on a grid of spacing sample_dt
// with a random phase per excursion (its own stream, SamplingPhase), which
// makes the Riemann sums unbiased estimates of the time integrals for any
// sample_dt: a coarse grid costs precision, not accuracy. Transient times are
// exact for the PDMP and rounded to whole steps for the inclusion engine.
#pragma once

/// \file
/// Velocity statistics with error bars: stationary density, autocorrelation,
/// transient moments, sample paths. The comment at the top of this header
/// explains the design.

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "stickslip/diffusivity.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/method.hpp"
#include "stickslip/result_fields.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/params.hpp"
#include "stickslip/run.hpp"

namespace stickslip {

/// Velocity bins [m/s]: `count` equal bins on [lo, hi]. lo == hi == 0 chooses
/// the range: for the stationary density, the velocities seen by the first 256
/// excursions (same streams; so deterministic) padded by 10% on each side; for
/// transient densities, the white-noise (Hayakawa) mean -+ 6 standard
/// deviations (or -+ 6 noise/friction), widened to hold v0.
struct VelocityBins {
    /// @{
    /// The binned velocity range [lo, hi] [m/s], lo < hi; lo == hi == 0:
    /// automatic (above).
    double lo = 0.0, hi = 0.0;
    /// @}
    /// Number of equal bins, 1 to 100000.
    int count = 80;
};

/// The bins as settings: --bins (count) and --range (lo,hi); `range_help`
/// says what the automatic range is for the request at hand.
template <class Visitor>
void visit_settings(VelocityBins& b, Visitor&& v, const char* range_help) {
    v(b.count, SettingInfo{"bins", "", "number of equal velocity bins, 1 to 100000"});
    v(NumberRange{b.lo, b.hi}, SettingInfo{"range", "m/s", range_help});
}

/// A density histogram with error bars. `density[k]` estimates the density of
/// the continuous part of the law of V on [edges[k], edges[k+1]) [s/m]: the
/// atom at V = 0 is excluded and reported in `stuck` (probability), so that
/// sum(density * width) + stuck + below + above = 1.
struct VelocityHistogram {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    std::vector<double> edges;
    std::vector<Estimate> density;
    Estimate stuck;
    Estimate below, above;
    double time = std::numeric_limits<double>::quiet_NaN();
    /// @}

    /// The velocities [m/s] whose probability `mass` (one of this
    /// histogram's estimates) is, as {lo, hi}: {0, 0} for P(V = 0),
    /// {-inf, edges[0]} below the bins, {edges[-1], inf} above; NaN for an
    /// estimate that is none of them (the histogram's CSV rows).
    std::array<double, 2> support(const Estimate& mass) const {
        constexpr double inf = std::numeric_limits<double>::infinity();
        if (&mass == &stuck) return {0.0, 0.0};
        if (&mass == &below && !edges.empty()) return {-inf, edges.front()};
        if (&mass == &above && !edges.empty()) return {edges.back(), inf};
        return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
    }

    /// The fields, in report order (result_fields.hpp): the bins (JSON
    /// "bins", each {lo, hi, value, error, kind}), then the mass outside them
    /// and P(V = 0) (a stationary density's beside the histogram: the
    /// solver's is a quantity of its own).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = VelocityHistogram;
        visit(&S::edges, FieldInfo{"edges", "m/s", "the bin edges (one more than the bins)", FieldForm::Edges});
        visit(&S::density, FieldInfo{"bins", "s/m",
                                     "the density of the continuous part of the law of V on each bin [lo, hi) (the "
                                     "atom at V = 0 excluded)",
                                     FieldForm::NoInterval});
        visit(&S::below, FieldInfo{"below", "", "P(V < edges[0], V != 0)", FieldForm::NoInterval});
        visit(&S::above, FieldInfo{"above", "", "P(V >= edges[-1], V != 0)", FieldForm::NoInterval});
        visit(&S::stuck, FieldInfo{"stuck_probability", "",
                                   "P(V = 0), the object sticks (coloured noise only); a stationary density's is "
                                   "reported beside its histogram",
                                   FieldForm::Optional});
        visit(&S::time, FieldInfo{"time", "s", "moments --density: the time t of this histogram of V(t) (NaN for "
                                               "a stationary density)",
                                  FieldForm::WhenSet});
    }
};

// ---- stationary density --------------------------------------------------

/// A stationary-density run (`stickslip density`): the histogram of V over
/// long excursions (renewal-reward ratios, no burn-in), P(V = 0), the
/// stationary mean and variance, and D, M0, E[t1] of the same excursions.
struct DensityRequest : RunSettings, ExcursionSettings {
    static constexpr const char* command = "density"; ///< the CLI subcommand, and a checkpoint's name for it
    static constexpr bool resumable = true; ///< runs through the block driver: checkpoints, graceful stop
    /// The histogram's bins; automatic range by default (a pilot run of 256
    /// excursions).
    VelocityBins bins;
    /// PDMP sampling interval [s]; 0 uses engine.dt. Ignored by the inclusion engine.
    double sample_dt = 0.0;
};

/// --sample-dt of the stationary observables.
inline constexpr SettingInfo sample_dt_info{
    "sample-dt", "s", "pdmp and --scheme event: sampling interval of the path; 0 = --dt (the resolvent scheme samples every step)"};

/// The request's settings: RunSettings', ExcursionSettings', --bins,
/// --range and --sample-dt.
template <class Visitor>
void visit_settings(DensityRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), v);
    visit_settings(static_cast<ExcursionSettings&>(r), v);
    visit_settings(r.bins, v,
                   "velocity range 'lo,hi'; default: the velocities seen by the first 256 excursions, padded by 10%");
    v(r.sample_dt, sample_dt_info);
}

/// What compute_density returns; report.hpp writes it.
struct DensityResult : MethodResult {
    /// The request, with the bins resolved (an automatic range replaced by
    /// the one used).
    DensityRequest request;
    /// The stationary density of V [s/m] with P(V = 0) and the tails.
    VelocityHistogram histogram;
    /// The stationary moments, each one's unit and meaning declared in
    /// fields() below.
    /// @{
    Estimate mean;
    Estimate variance;
    /// @}
    LongExcursionEstimates estimates; ///< D, M0, E[t1] of the same excursions
    /// Notes for the user, one sentence each: those of DiffusivityResult, and
    /// on the sampling of the path, P(V = 0) and mass outside the range.
    std::vector<std::string> warnings;
    /// With --engine kolmogorov, the solver's result (details then hold its
    /// GridDetails): the density is its finest grid's,
    /// solution->levels.back().velocity_density on velocity_faces, one value
    /// per velocity cell with no standard error (the grid's cells, not
    /// `bins`), and P(V = 0), D and M0 with their estimated discretisation
    /// errors. Of the members above, mean, variance, estimates and
    /// histogram.stuck then hold the solver's values (Estimates of kind
    /// Solved), so that they are where a sampled run has them; the
    /// histogram's bins are unset. Empty for a sampled result.
    std::optional<KolmogorovResult> solution;

    /// The fields, in report order (result_fields.hpp); the histogram, the
    /// long-excursion estimates and the solver's result are written by hand.
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = DensityResult;
        visit(&S::mean, FieldInfo{"mean", "m/s", "the stationary mean velocity E[V] = M0"});
        visit(&S::variance, FieldInfo{"variance", "m^2/s^2", "the stationary variance of the velocity Var(V)"});
    }
};

/// Every check of the request (InvalidParameter on the first problem): the
/// shared settings, excursions >= 2, the bins (1 to 100000; a finite range
/// with lo < hi, or automatic), sample_dt finite and >= 0, and that
/// excursions can end within the work cap.
void validate(const DensityRequest& req);
/// Validates the request (once) and runs it: a pilot of 256 excursions when
/// the range is automatic, then the excursions of the histogram. Throws
/// CappedExcursions as compute_diffusivity does. With --engine kolmogorov
/// nothing is sampled: the Kolmogorov equations are solved (solve_kolmogorov,
/// its default precision) and the result's `solution` holds the density.
DensityResult compute_density(const DensityRequest& req);

// ---- stationary autocorrelation ---------------------------------------------

/// A stationary-autocorrelation run (`stickslip correlation`): <V(0)V(r)>,
/// the covariance h(r) and h(r)/h(0) at equally spaced lags, as
/// renewal-reward ratios over long excursions, each continued past its end
/// by the largest lag with its own stream.
struct CorrelationRequest : RunSettings, ExcursionSettings {
    static constexpr const char* command = "correlation"; ///< the CLI subcommand, and a checkpoint's name for it
    static constexpr bool resumable = true; ///< runs through the block driver: checkpoints, graceful stop
    double max_lag = 0.0; ///< largest lag r [s]; 0 chooses 5 time units noise/friction^2
    int lags = 50;        ///< lags 0, max_lag/lags, ..., max_lag (rounded to the sampling grid)
    double sample_dt = 0.0; ///< PDMP sampling interval [s]; 0 uses engine.dt
};

/// The request's settings: RunSettings', ExcursionSettings', --max-lag,
/// --lags and --sample-dt.
template <class Visitor>
void visit_settings(CorrelationRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), v);
    visit_settings(static_cast<ExcursionSettings&>(r), v);
    v(r.max_lag, SettingInfo{"max-lag", "s", "largest lag r; 0 = 5 time units (noise/friction^2)"});
    v(r.lags, SettingInfo{"lags", "", "number of lag intervals, 1 to 2000: lags 0, max/lags, ..., max"});
    v(r.sample_dt, sample_dt_info);
}

/// What compute_correlation returns; report.hpp writes it.
struct CorrelationResult : MethodResult {
    /// The request, with max_lag resolved (0 replaced by the lag used).
    CorrelationRequest request;
    /// The lags and the series along them, each one's unit and meaning
    /// declared in fields() below.
    /// @{
    std::vector<double> lag;
    std::vector<Estimate> autocorrelation;
    std::vector<Estimate> covariance;
    std::vector<Estimate> normalised;
    Estimate mean;
    /// @}
    /// D, M0 and E[t1] of the same excursions.
    LongExcursionEstimates estimates;
    /// Notes for the user, one sentence each: those of DiffusivityResult, and
    /// on the sampling of the path.
    std::vector<std::string> warnings;

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = CorrelationResult;
        visit(&S::lag, FieldInfo{"lag", "s", "the lags r (multiples of the sampling interval)", FieldForm::Axis});
        visit(&S::autocorrelation, FieldInfo{"autocorrelation", "m^2/s^2", "<V(0)V(r)> at each lag"});
        visit(&S::covariance, FieldInfo{"covariance", "m^2/s^2", "h(r) = <V(0)V(r)> - M0^2 at each lag"});
        visit(&S::normalised, FieldInfo{"normalised_covariance", "", "h(r)/h(0) at each lag"});
        visit(&S::mean, FieldInfo{"mean", "m/s", "the stationary mean velocity E[V] = M0, from the same excursions"});
    }
};

/// Every check of the request (InvalidParameter on the first problem): the
/// shared settings, excursions >= 2, lags 1 to 2000, max_lag finite and >= 0
/// and at most 4e6 sampling intervals, and that excursions can end within
/// the work cap.
void validate(const CorrelationRequest& req);
/// Validates the request (once) and runs it. Throws CappedExcursions as
/// compute_diffusivity does.
CorrelationResult compute_correlation(const CorrelationRequest& req);

// ---- transient statistics ------------------------------------------------------

/// A transient run (`stickslip moments`): E[V(t)|v0], E[V(t)^2|v0],
/// P(V(t) = 0) and optionally the density of V(t), as plain means over
/// independent trajectories from V(0) = v0.
struct MomentsRequest : RunSettings {
    static constexpr const char* command = "moments"; ///< the CLI subcommand, and a checkpoint's name for it
    static constexpr bool resumable = true; ///< runs through the block driver: checkpoints, graceful stop
    /// Initial velocity v_i [m/s]; NaN: one velocity unit, noise/friction.
    double v0 = std::numeric_limits<double>::quiet_NaN();
    /// Initial noise X(0) [s^-1/2]; NaN draws it from the stationary law
    /// N(0, 1/tau) independently for each trajectory. Ignored for white noise.
    double x0 = std::numeric_limits<double>::quiet_NaN();
    /// t >= 0 [s], any order; empty: Table I's t' = 0.05, 0.125, 0.25, 0.5, 1,
    /// 2.5 time units (noise/friction^2).
    std::vector<double> times;
    /// Number of independent trajectories, >= 2.
    std::uint64_t trajectories = 10000;
    bool with_density = false;       ///< also histogram V(t) at every time
    /// The bins of the densities (with_density); automatic: around the
    /// white-noise law, widened to hold v0 (VelocityBins).
    VelocityBins bins;
};

/// The request's settings: RunSettings', --v0, --x0, --times,
/// --trajectories, --density, --bins and --range.
template <class Visitor>
void visit_settings(MomentsRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), v);
    v(OptionalNumber{r.v0}, SettingInfo{"v0", "m/s", "initial velocity v0; default: 1 velocity unit, noise/friction"});
    v(OptionalNumber{r.x0}, SettingInfo{"x0", "s^-1/2", "initial noise X(0); default: drawn from N(0, 1/tau) per trajectory"});
    v(NumberList{r.times}, SettingInfo{"times", "s",
                                       "times t >= 0, comma-separated or lo:hi:n (log-spaced); default: Table I's t' = "
                                       "0.05, 0.125, 0.25, 0.5, 1, 2.5 time units (noise/friction^2)"});
    v(r.trajectories, SettingInfo{"trajectories", "", "number of independent trajectories (>= 2)"});
    v(r.with_density, SettingInfo{"density", "", "also estimate the density of V(t) at every time (histogram)"});
    visit_settings(r.bins, v, "velocity range 'lo,hi' of --density; default: automatic");
}

/// Table I's times t' = 0.05, 0.125, 0.25, 0.5, 1, 2.5, in time units
/// (noise/friction^2): the default times of a transient request.
inline constexpr double table_one_times[] = {0.05, 0.125, 0.25, 0.5, 1.0, 2.5};

/// What compute_moments returns; report.hpp writes it. Every series is
/// aligned with `time`.
struct MomentsResult : MethodResult {
    /// The request, with its defaults resolved: v0, the times (as given, or
    /// Table I's in seconds; those used, rounded and sorted, are in `time`)
    /// and the density's bins.
    MomentsRequest request;
    /// The times and the series along them, each one's unit and meaning
    /// declared in fields() below.
    /// @{
    std::vector<double> time;
    std::vector<Estimate> first_moment;
    std::vector<Estimate> second_moment;
    std::vector<Estimate> stuck;
    /// @}
    std::vector<VelocityHistogram> density; ///< per time, when requested
    /// Notes for the user, one sentence each (a step too coarse, times
    /// rounded to steps, an interrupted run, ...).
    std::vector<std::string> warnings;

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = MomentsResult;
        visit(&S::time, FieldInfo{"time", "s", "the times t actually used (sorted; inclusion: whole steps)",
                                  FieldForm::Axis});
        visit(&S::first_moment, FieldInfo{"first_moment", "m/s", "E[V(t) | v0] at each time"});
        visit(&S::second_moment, FieldInfo{"second_moment", "m^2/s^2", "E[V(t)^2 | v0] at each time"});
        visit(&S::stuck, FieldInfo{"stuck_probability", "", "P(V(t) = 0) at each time"});
    }
};

/// Every check of the request (InvalidParameter on the first problem): the
/// shared settings, trajectories >= 2, at most 10000 times, each finite and
/// >= 0, a finite start, the bins with with_density (and times x bins at most
/// 2e6), and the inclusion engine's largest time within 1e13 steps.
void validate(const MomentsRequest& req);
/// Validates the request (once) and runs the trajectories.
MomentsResult compute_moments(const MomentsRequest& req);

// ---- sample paths ------------------------------------------------------------

/// One recorded path: columns of equal length.
struct SamplePath {
    std::vector<double> t; ///< time [s]
    std::vector<double> x; ///< the paper's noise X [s^-1/2] (0 for white noise)
    std::vector<int> mode; ///< -1 / 0 / +1: negative-dynamic / static / positive-dynamic
    std::vector<double> v; ///< velocity [m/s]
    std::vector<double> u; ///< displacement [m]
};

/// A sample-path run (`stickslip trajectory`): either one long excursion,
/// exactly as the diffusivity run draws it, or independent paths of a given
/// length. The confidence level is not used.
struct TrajectoryRequest : RunSettings {
    static constexpr const char* command = "trajectory"; ///< the CLI subcommand, and a checkpoint's name for it
    /// Excursion mode (paths == 0): long excursion number `index` of stream
    /// `control.seed`, the very excursion `diffusivity` runs with that index.
    std::uint64_t index = 0;
    /// Path mode (paths > 0): this many independent paths on [0, horizon] from
    /// (x0, v0), x0 NaN = the paper's start x* (PDMP: first lattice point above).
    std::uint64_t paths = 0;
    double horizon = 2.0; ///< [s], path mode
    /// Path mode: the initial noise X(0) [s^-1/2]; NaN: the upper threshold x*
    /// (PDMP: the first lattice point above it). Ignored for white noise.
    double x0 = std::numeric_limits<double>::quiet_NaN();
    /// Path mode: the initial velocity V(0) [m/s].
    double v0 = 0.0;
    /// Recording interval [s]: 0 records every step (inclusion) or event (PDMP)
    /// in excursion mode, and horizon/1000 in path mode.
    double every = 0.0;
    std::uint64_t max_points = 5'000'000; ///< refuse to record more points than this per path
};

/// The request's settings: RunSettings' without --level, then --index,
/// --paths, --time, --x0, --v0, --every and --max-points.
template <class Visitor>
void visit_settings(TrajectoryRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), skip_settings(v, {"level"}));
    v(r.index, SettingInfo{"index", "", "excursion number (excursion mode)"});
    v(r.paths, SettingInfo{"paths", "", "number of independent paths, at most 1000 (0 = one long excursion instead)"});
    v(r.horizon, SettingInfo{"time", "s", "path length (path mode)"});
    v(OptionalNumber{r.x0}, SettingInfo{"x0", "s^-1/2",
                                        "initial noise X(0) (path mode); default: the upper threshold x* = "
                                        "(friction - b(0))/sqrt(noise/2), where a stuck object starts sliding up"});
    v(r.v0, SettingInfo{"v0", "m/s", "initial velocity (path mode)"});
    v(r.every, SettingInfo{"every", "s",
                           "recording interval; 0 = every step (inclusion) or event (pdmp) of an excursion, time/1000 "
                           "for paths"});
    v(r.max_points, SettingInfo{"max-points", "", "refuse to record more points than this per path"});
}

/// One long excursion as `trajectory` reports it (excursion mode): what the
/// kernel's ExcursionOutcome says of it, less the estimators' internals.
struct ExcursionRecord {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    double displacement = 0.0;
    double duration = 0.0;
    double first_half_duration = 0.0;
    bool complete = true;
    std::uint64_t work = 0;
    /// @}

    /// The record of a kernel's outcome.
    static ExcursionRecord of(const ExcursionOutcome& e) {
        return ExcursionRecord{e.displacement, e.duration, e.first_half, !e.capped, e.work};
    }

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = ExcursionRecord;
        visit(&S::displacement, FieldInfo{"displacement", "m", "excursion mode: U of the excursion"});
        visit(&S::duration, FieldInfo{"duration", "s", "excursion mode: its duration t1"});
        visit(&S::first_half_duration,
              FieldInfo{"first_half_duration", "s", "excursion mode: the duration of its first half-excursion"});
        visit(&S::complete, FieldInfo{"complete", "",
                                      "excursion mode: False if it hit the runaway guard (max_steps), when U and t1 "
                                      "mean nothing"});
        visit(&S::work, FieldInfo{"work", "", "excursion mode: steps or events used", FieldForm::NotInBlock});
    }
};

/// What compute_trajectory returns; report.hpp writes it.
struct TrajectoryResult {
    /// The request; in path mode with `every` resolved (0 replaced by the
    /// interval used).
    TrajectoryRequest request;
    /// The engine's resolved details.
    ResolvedEngine resolved;
    /// The recorded paths: one in excursion mode, `paths` in path mode.
    std::vector<SamplePath> paths;
    ExcursionRecord excursion; ///< excursion mode: its U, t and work
    /// Notes for the user, one sentence each.
    std::vector<std::string> warnings;
};

/// Every check of the request (InvalidParameter on the first problem): the
/// model and engine, threads, paths at most 1000, a finite horizon > 0 in
/// path mode, every finite and >= 0, a finite start, index < 2^56, and at
/// most max_points points per path (as far as can be told before running).
void validate(const TrajectoryRequest& req);
/// Validates the request (once) and records the path(s). Throws
/// InvalidParameter ("every") when an excursion turns out to need more than
/// max_points points.
TrajectoryResult compute_trajectory(const TrajectoryRequest& req);

/// The bins actually used for a request (resolves automatic ranges).
VelocityBins resolve_bins(const ModelParams& p, const VelocityBins& b);

/// @name The names before the requests were named after their commands
/// The requests and results of `density` and `moments` under the names they
/// had before they were named after their commands.
/// @{
using StationaryDensityRequest = DensityRequest; ///< DensityRequest under its earlier name
using StationaryDensityResult = DensityResult;   ///< DensityResult under its earlier name
using TransientRequest = MomentsRequest;         ///< MomentsRequest under its earlier name
using TransientResult = MomentsResult;           ///< MomentsResult under its earlier name
/// compute_density under its earlier name.
inline DensityResult compute_stationary_density(const DensityRequest& r) { return compute_density(r); }
/// compute_moments under its earlier name.
inline MomentsResult compute_transient(const MomentsRequest& r) { return compute_moments(r); }
/// @}

} // namespace stickslip
