// SPDX-License-Identifier: BSD-3-Clause
// stickslip/sweep.hpp -- D, M0 and E[t1] over a grid of noise intensities and
// correlation times (the paper's Figs. 4 and 9), with the local log-log slope
// d log D / d log Gamma and, per tau, the fitted exponent of D ~ Gamma^alpha;
// per noise, D over its white-noise value and how the departure from it
// scales with tau' (SweepWhiteLimit: the paper's question, how white is white
// enough).
//
// A third axis, --vary NAME with --vary-values LIST, sweeps a named constant
// of the --drift expression (given as NAME=value in each point's
// drift_params, replacing a value given there): the points are then value-major, each value a whole
// (tau, noise) grid, and the exponents are fitted per (value, tau). Without
// it nothing changes, point numbers included. --vary static-friction sweeps
// the model's static friction (m s^-2, each value >= --friction) the same way.
//
// Independence: point number k uses the sample indices
// [k * 2^40, k * 2^40 + excursions) of the run's seed, so every point has its
// own streams, the points' errors are independent and the slope errors below
// are exact (to first order); any point can be recomputed alone
// with RunControl::first_index = k * 2^40.
//
// With --engine kolmogorov nothing is sampled: every point is the solver's
// diffusivity there (bit for bit `diffusivity --engine kolmogorov` at that
// point), and the slope and exponent errors are propagated from the
// estimated discretisation errors of D the same way, as a scale, not as a
// sampling distribution (no intervals).
#pragma once

/// \file
/// D, M0 and E[t1] over a grid of noise intensities and correlation times, with
/// slopes and exponents. The comment at the top of this header explains the
/// design.

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "stickslip/diffusivity.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/result_fields.hpp"

namespace stickslip {

/// First sample index of sweep point k.
inline constexpr std::uint64_t sweep_index_stride = std::uint64_t{1} << 40;

/// A sweep: RunSettings whose params give friction, relaxation and bias (its
/// noise and tau are replaced by the grid's), and whose control gives the seed
/// and threads. control.progress is used by a solved sweep (--engine
/// kolmogorov) only, with Progress counting points (done of total, before
/// each point and after the last; returning false cancels: RunCancelled); a
/// sampled sweep reports each point's excursions through point_progress.
/// `excursions` is per point.
struct SweepRequest : RunSettings, ExcursionSettings {
    static constexpr const char* command = "sweep"; ///< the CLI subcommand, and a checkpoint's name for it
    static constexpr bool resumable = true; ///< runs through the block driver: checkpoints, graceful stop
    /// Gamma values [m^2 s^-3], > 0 (sorted increasing in the result); the
    /// default, 3:10:5, is five log-spaced values from 3 to 10: with the
    /// default taus every point runs (about 8 s on 2 cores); below 3 at
    /// tau = 1 s E[t1] grows past 1000 s and the runaway guard refuses the
    /// default sweep.
    std::vector<double> noises = spaced_values(3.0, 10.0, 5);
    std::vector<double> taus = {0.125, 0.25, 0.5, 1.0}; ///< tau values [s], >= 0
    /// The estimator of D at every point (as DiffusivityRequest::estimator).
    Estimator estimator = Estimator::RenewalReward;
    /// The control variate at every point (as DiffusivityRequest::control_variate).
    ControlVariateMode control_variate = ControlVariateMode::Auto;
    /// Its pilot's excursions at every point (as DiffusivityRequest::control_variate_pilot).
    std::uint64_t control_variate_pilot = default_control_variate_pilot;
    /// With --engine kolmogorov: the target estimated relative discretisation
    /// error of D at every point (as DiffusivityRequest::rel_precision; 0 takes
    /// the solver's default, 1e-3). A Monte Carlo sweep has no precision mode
    /// and refuses a value > 0.
    double rel_precision = 0.0;
    /// A named constant of the --drift expression to sweep over ("" for none):
    /// every point's drift_params gains NAME=value for each of vary_values
    /// (replacing a value drift_params gives it, as a placeholder); or
    /// vary_static_friction, the model's static friction [m s^-2].
    std::string vary;
    /// The values of `vary` (in the constant's own units; sorted increasing
    /// in the result). Empty without --vary.
    std::vector<double> vary_values;
    /// Optional: the progress callback for point k of n, `point` saying where
    /// it is ("noise 2, tau 0.1"; with --vary "c 0.2, noise 2, tau 0.1").
    std::function<std::function<bool(const Progress&)>(std::size_t k, std::size_t n, const std::string& point)>
        point_progress;
};

/// The name --vary takes to sweep the static friction (ModelParams::static_friction).
inline constexpr const char* vary_static_friction = "static-friction";

/// The request's settings: RunSettings' with --noise and --tau taken as
/// lists, then ExcursionSettings', --estimator and the control variate's.
template <class Visitor>
void visit_settings(SweepRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), skip_settings(v, {"noise", "tau"}));
    v(NumberList{r.noises}, SettingInfo{"noise", "m^2 s^-3", "noise intensities Gamma: comma-separated or lo:hi:n (n log-spaced)"});
    v(NumberList{r.taus}, SettingInfo{"tau", "s", "correlation times: comma-separated or lo:hi:n (n log-spaced)"});
    visit_settings(static_cast<ExcursionSettings&>(r), v);
    v(r.estimator, SettingInfo{"estimator", "", "renewal (default) or paper (eq. 12)"});
    v(r.control_variate, control_variate_info);
    v(r.control_variate_pilot, control_variate_pilot_info);
    v(TextValue{r.vary}, SettingInfo{"vary", "",
                                     "a named constant of --drift to sweep over as a third axis, its values in "
                                     "--vary-values: --drift \"a*v - c*v^3\" --drift-params a=0.8 --vary c; or "
                                     "static-friction (m s^-2, each >= --friction)",
                                     "NAME"});
    v(NumberList{r.vary_values, true, true},
      SettingInfo{"vary-values", "", "values of the --vary constant: comma-separated or lo:hi:n (n evenly spaced)"});
    v(r.rel_precision, SettingInfo{"rel-precision", "",
                                   "with --engine kolmogorov: the target estimated relative error of D at every "
                                   "point (0: the solver's default, 1e-3; 0.01 is about 10 times faster)"});
}

/// One point (noise, tau) of a sweep: the diffusivity run there.
struct SweepPoint {
    /// @{
    /// The point: noise intensity Gamma [m^2 s^-3] and correlation time tau [s].
    double noise = 0, tau = 0;
    /// @}
    /// The value of the swept drift constant (SweepRequest::vary) at the
    /// point; NaN without --vary.
    double varied = std::numeric_limits<double>::quiet_NaN();
    /// D [m^2/s], M0 [m/s] and E[t1] [s] at the point (sampled; unset when
    /// `solution` holds the point).
    LongExcursionEstimates estimates;
    /// With --engine kolmogorov, the solver's result at the point: D, M0,
    /// P(V = 0) and E[t1], each with its estimated discretisation error (no
    /// samples, so no stop rule, step or scheme either).
    std::optional<KolmogorovResult> solution;
    /// The stop rule used there (ResolvedEngine::stop_rule): with the
    /// automatic rule it can change along the grid, as dt/tau does.
    std::string stop_rule;
    /// The inclusion engine's step at the point [s]: the request's, or with
    /// --dt auto the point's own (it follows tau and noise).
    double dt = 0;
    /// The inclusion engine's scheme at the point: the request's, or with
    /// Scheme::Auto the point's own (auto_scheme: it follows tau).
    Scheme scheme = Scheme::Event;
    /// Steps or events used at the point.
    std::uint64_t work = 0;
    /// Wall time of the point [s].
    double seconds = 0;
    /// d log D / d log Gamma at this point (central difference inside the
    /// grid, one-sided at its ends; NaN with a single noise value). Solved
    /// points: std_error is the error propagated from D's discretisation
    /// errors, and the interval is NaN (there is no sampling distribution).
    Estimate slope;
    /// D over white noise's D at the same point (the same model with tau =
    /// 0, by exact quadrature: white_noise_reference): how white the noise
    /// is, in D. Its error is D's (sampled: a standard error and interval;
    /// solved: the discretisation error, no interval).
    Estimate white_ratio;
    /// The point's own warnings (DiffusivityResult::warnings).
    std::vector<std::string> warnings;
    /// Solved: whether D's estimated error met the target at the point
    /// (KolmogorovResult::converged).
    bool precision_reached = false;

    /// The point's D [m^2/s], the solver's or the sampled one.
    const Estimate& diffusivity() const { return solution ? solution->diffusivity : estimates.diffusivity; }
    /// The point's M0 [m/s], the solver's or the sampled one.
    const Estimate& mobility() const { return solution ? solution->mobility : estimates.mobility; }
    /// The point's E[t1] [s], the solver's or the sampled one.
    const Estimate& mean_duration() const { return solution ? solution->mean_duration : estimates.mean_duration; }

    /// The fields, in report order (result_fields.hpp): the sampled
    /// estimates or the solver's in their place, the per-request ones
    /// FieldForm::Optional (the report says which it writes). The point's
    /// nondimensional values and work are written by the report.
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = SweepPoint;
        visit(&S::varied, FieldInfo{"varied", "", "the swept drift constant's value (absent without vary)",
                                    FieldForm::WhenSet});
        // tau first, as the grid runs (tau-major) and the CSV's columns have always been.
        visit(&S::tau, FieldInfo{"tau", "s", "the point's correlation time"});
        visit(&S::noise, FieldInfo{"noise", "m^2 s^-3", "the point's noise intensity"});
        visit(&S::stop_rule, FieldInfo{"stop_rule", "",
                                       "sampled: the stop rule used there (with the automatic rule it can change "
                                       "along the grid)",
                                       FieldForm::Optional});
        visit(&S::dt, FieldInfo{"dt", "s", "--dt auto on the inclusion engine: the point's own step",
                                FieldForm::Optional});
        visit(&S::scheme, FieldInfo{"scheme", "", "--scheme auto on the inclusion engine: the point's own scheme",
                                    FieldForm::Optional});
        visit(&S::estimates, FieldInfo{"estimates", "", "sampled: D, M0 and E[t1] at the point", FieldForm::Optional});
        visit(&S::solution, FieldInfo{"solution", "", "solved: D, M0, P(V = 0) and E[t1] at the point"});
        visit(&S::precision_reached, FieldInfo{"precision_reached", "",
                                               "solved: whether D's estimated error met the target at the point",
                                               FieldForm::Optional});
        visit(&S::slope, FieldInfo{"slope", "", "d log D / d log noise at the point (central difference inside the "
                                                "grid, one-sided at its ends; null with a single noise)",
                                   FieldForm::NoInterval});
        visit(&S::white_ratio, FieldInfo{"white_ratio", "",
                                         "D over white noise's D at the same point (exact quadrature): how white "
                                         "the noise is, in D"});
        visit(&S::work, FieldInfo{"work", "", "steps, events or grid states used at the point; the point's work",
                                  FieldForm::NotInBlock});
        visit(&S::seconds, FieldInfo{"seconds", "s", "wall time of the point; the point's work", FieldForm::NotInBlock});
    }
};

/// How D approaches its white-noise value as tau' -> 0 at one noise
/// intensity (and value of the swept constant): the answer to the source
/// paper's question, how small tau must be for the white-noise D to hold.
/// The relative departure delta = 1 - D/D_white of the points whose delta is
/// resolved (above 3 errors) and at most 0.1 (the near-white regime) is
/// fitted as delta = c1 tau'^p (weighted least squares in log-log, tau' =
/// tau friction^2/noise); and, to test for a tau'^(1/2) law (Doering, Hagan
/// and Levermore's, at absorbing boundaries), as delta = a tau'^(1/2) +
/// b tau' + c tau'^(3/2) (weighted linear least squares, 4 or more points).
struct SweepWhiteLimit {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    double varied = std::numeric_limits<double>::quiet_NaN();
    double noise = 0;
    double white_diffusivity = 0;
    Estimate exponent;
    Estimate coefficient;
    double chi2_per_dof = 0;
    Estimate half_order;
    Estimate first_order;
    Estimate three_half_order;
    int points = 0;
    double tau_within_percent = std::numeric_limits<double>::quiet_NaN();
    /// @}

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = SweepWhiteLimit;
        visit(&S::varied, FieldInfo{"varied", "", "the swept drift constant's value (NaN without vary)",
                                    FieldForm::WhenSet});
        visit(&S::noise, FieldInfo{"noise", "m^2 s^-3", "the noise intensity of these points"});
        visit(&S::white_diffusivity, FieldInfo{"white_diffusivity", "m^2/s", "D with white noise at this noise",
                                               FieldForm::Reference});
        visit(&S::exponent, FieldInfo{"exponent", "", "p of 1 - D/D_white = c1 tau'^p (NaN with fewer than 2 points)"});
        visit(&S::coefficient, FieldInfo{"coefficient", "", "c1, per unit tau'^p (NaN with fewer than 2 points)"});
        visit(&S::chi2_per_dof, FieldInfo{"chi2_per_dof", "", "of the power law (NaN with fewer than 3 points)"});
        visit(&S::half_order,
              FieldInfo{"half_order", "",
                        "a, the coefficient of tau'^(1/2) in the three-term fit: 0 within its error when there is no "
                        "tau'^(1/2) law (NaN with fewer than 4 points)"});
        visit(&S::first_order, FieldInfo{"first_order", "",
                                         "b, the coefficient of tau' in the three-term fit: the leading one when a is "
                                         "0 (NaN with fewer than 4 points)"});
        visit(&S::three_half_order,
              FieldInfo{"three_half_order", "",
                        "c, the coefficient of tau'^(3/2) in the three-term fit (NaN with fewer than 4 points)"});
        visit(&S::points, FieldInfo{"points", "", "points fitted"});
        visit(&S::tau_within_percent,
              FieldInfo{"tau_within_percent", "s",
                        "the tau below which D is within 1% of the white value, where 1 - D/D_white crosses 0.01 "
                        "between two points (log-log interpolation; NaN when no two neighbours bracket it)"});
    }
};

/// The power law D ~ Gamma^alpha fitted over the noises of one tau.
struct SweepExponent {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    double varied = std::numeric_limits<double>::quiet_NaN();
    double tau = 0;
    Estimate exponent;
    double chi2_per_dof = 0;
    int points = 0;
    /// @}

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = SweepExponent;
        visit(&S::varied, FieldInfo{"varied", "", "the swept drift constant's value of the fit (NaN without vary)",
                                    FieldForm::WhenSet});
        visit(&S::tau, FieldInfo{"tau", "s", "the correlation time of the fit"});
        visit(&S::exponent,
              FieldInfo{"exponent", "",
                        "alpha of D ~ noise^alpha, weighted least squares in log-log (solved points: weights and "
                        "error from D's discretisation errors)"});
        visit(&S::chi2_per_dof, FieldInfo{"chi2_per_dof", "",
                                          "of the power-law fit: >> 1 means no single power law (solved points: the "
                                          "residuals in units of D's discretisation errors)"});
        visit(&S::points, FieldInfo{"points", "", "points fitted (fewer than the noises when interrupted)"});
    }
};

/// What compute_sweep returns; report.hpp writes it.
struct SweepResult {
    /// The request, with its noises and taus sorted and duplicates removed.
    SweepRequest request;
    /// tau-major: for each tau, noises increasing (with --vary, all that
    /// for each value in turn)
    std::vector<SweepPoint> points;
    std::vector<SweepExponent> exponents; ///< one per tau and value (when >= 2 noises)
    /// One per noise and value with 2 or more tau > 0: D's approach to white noise.
    std::vector<SweepWhiteLimit> white_limits;
    /// Wall time of the whole sweep [s].
    double seconds = 0;
    bool interrupted = false;  ///< stopped early (RunControl::stop): the points run so far
    std::uint64_t resumed = 0; ///< excursions restored from a checkpoint
    /// The points' distinct warnings, an interrupted sweep, and few
    /// excursions per point.
    std::vector<std::string> warnings;

    /// Whether a drift constant is swept (--vary): a third axis.
    bool varies() const { return !request.vary.empty(); }
    /// Whether the points were solved (--engine kolmogorov), not sampled.
    bool solved() const { return !samples(request.engine); }
};

/// Every check of the sweep (InvalidParameter on the first problem): at least
/// one noise and one tau, no NaN, --vary naming a constant of the --drift
/// expression with at least one value, and
/// --vary-values only with --vary, at most 65536 points, at most 2^40
/// excursions per point, first_index 0, rel_precision only with the
/// Kolmogorov engine, then every point as a diffusivity request (the message
/// names the first bad point).
void validate(const SweepRequest& req);
/// Validates every point before running any, then runs them tau-major, each
/// on its own sample indices (top of the file), and fits the slopes and
/// exponents. RunControl::stop ends it after the point in progress (a
/// prefix of its excursions). With --engine kolmogorov every point is solved
/// (solve_kolmogorov) instead of sampled, and a stop ends the sweep after the
/// point in progress.
SweepResult compute_sweep(const SweepRequest& req);

} // namespace stickslip
