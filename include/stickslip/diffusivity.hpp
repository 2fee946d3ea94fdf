// SPDX-License-Identifier: BSD-3-Clause
// stickslip/diffusivity.hpp -- the long-excursion diffusivity run: D, M0 and
// E[t1] with their intervals, and everything a report needs (resolved
// settings, work, warnings). The CLI and the Python module are thin layers
// over compute_diffusivity and report.hpp.
#pragma once

/// \file
/// The long-excursion diffusivity run: D, M0 and E[t1] with their intervals.
/// The comment at the top of this header explains the design.

#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "stickslip/errors.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/method.hpp"
#include "stickslip/result_fields.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/run.hpp"

namespace stickslip {

/// Whether a diffusivity run uses the martingale control variate (theory.md,
/// section 12): Auto uses it wherever a corrector exists (the PDMP, the
/// inclusion engine's resolvent scheme, and its event scheme with coloured
/// noise; tau' >= 1e-6 or white noise); Off gives the plain estimator alone.
enum class ControlVariateMode { Auto, Off };

/// @name Text form of the control-variate mode as a setting
/// @{

/// As for the other setting types (setting.hpp): "auto" or "off".
std::string format_setting(ControlVariateMode m);
void parse_setting(const SettingInfo& info, const std::string& text, ControlVariateMode& out);
const char* setting_form(const ControlVariateMode&);
/// @}

/// Excursions of the control variate's pilot by default (DiffusivityRequest::control_variate_pilot).
inline constexpr std::uint64_t default_control_variate_pilot = 8192;

/// A diffusivity run (`stickslip diffusivity`): N long excursions of the
/// engine, then D, M0 and E[t1] with their intervals (estimators.hpp). The
/// fields are the shared settings (RunSettings, ExcursionSettings) plus the
/// estimator and the precision-on-demand mode below.
struct DiffusivityRequest : RunSettings, ExcursionSettings {
    static constexpr const char* command = "diffusivity"; ///< the CLI subcommand, and a checkpoint's name for it
    static constexpr bool resumable = true; ///< runs through the block driver: checkpoints, graceful stop
    /// How D is estimated from the excursions: the renewal-reward estimator
    /// (correct for any mobility) unless the paper's numbers are wanted.
    Estimator estimator = Estimator::RenewalReward;
    /// Precision on demand: when > 0, run in batches until the upper
    /// half-width of D's interval, hi - D, is at most rel_precision * D, or
    /// max_excursions have run.
    /// The first batch has `excursions` (rounded up to whole blocks of 64);
    /// each later one is sized from the current half-width (half-width ~
    /// 1/sqrt(N)), at most 4x what has run.
    /// Batches start at block-aligned sample indices, so the result is
    /// deterministic and thread-invariant. Caveat (sequential stopping): N
    /// depends on the data, so the interval's coverage is slightly below its
    /// nominal level; with few, large batches the effect is small.
    /// With the Kolmogorov engine: the target estimated relative
    /// discretisation error of D (KolmogorovSettings::rel_precision; 0 takes
    /// that setting's default).
    double rel_precision = 0.0;
    std::uint64_t max_excursions = 100'000'000; ///< cap of the precision-on-demand mode
    /// The step's bias made visible (inclusion engine): after the run, run
    /// as many excursions again at twice the step, on independent streams
    /// (sample indices from check_dt_first_index on), and report the
    /// difference of D and M0 (DiffusivityResult::discretisation).
    bool check_dt = false;
    /// The drift law's interpolation made visible (--drift, --drift-table):
    /// run as many excursions again with knots twice as far apart ((knots +
    /// 1)/2 knots on the same range), on independent streams (sample indices
    /// from check_knots_first_index on), and report the difference of D and
    /// M0 (DiffusivityResult::knots_check).
    bool check_knots = false;
    /// The martingale control variate (theory.md, section 12): with Auto, D
    /// and M0 are the control-variate estimates wherever a corrector exists,
    /// the plain ones beside them (DiffusivityResult::control_variate); the
    /// random draws, and so the plain estimates, are the same either way.
    ControlVariateMode control_variate = ControlVariateMode::Auto;
    /// Excursions of the control variate's pilot: the coefficients beta and
    /// beta' are fitted on an independent run of this many excursions (key
    /// pilot_seed(seed), the run's sample indices), not on the excursions they
    /// correct, so that the interval covers what it says without drag too
    /// (docs/validation.md, "Why D's interval under-covers without drag":
    /// at 2000 excursions, fitted on the run itself the interval covers
    /// 82-94% there, with the pilot 92-95%; smaller pilots cover less). At most four
    /// times the run's excursions (pilot_excursions), at the coarser of the
    /// run's step and the automatic one. 0: fitted on the run itself (the
    /// interval before this setting). Its cost is reported in the run's work.
    std::uint64_t control_variate_pilot = default_control_variate_pilot;
};

/// Most excursions of a control variate's pilot, 2^40: a sweep point's pilot
/// stays within its point's sample indices (sweep_index_stride).
inline constexpr std::uint64_t max_control_variate_pilot = std::uint64_t{1} << 40;

/// The excursions of a request's pilot: control_variate_pilot, but at most
/// four times the run's own (the first batch's under --rel-precision), so that
/// a small run pays at most four times its cost for its coefficients.
constexpr std::uint64_t pilot_excursions(const DiffusivityRequest& r) {
    return r.control_variate_pilot < 4 * r.excursions ? r.control_variate_pilot : 4 * r.excursions;
}

/// The Philox key of the control variate's pilot under the user's `seed`
/// (DiffusivityRequest::control_variate_pilot): splitmix64's finaliser of the
/// seed, a bijection, so no two seeds share a pilot, and the pilot shares no
/// stream with its own run (Philox's streams under different keys are
/// independent). It coincides with the main streams of another seed only if
/// a user runs that seed, pilot_seed(seed), too.
constexpr std::uint64_t pilot_seed(std::uint64_t seed) {
    std::uint64_t z = seed + 0x9E3779B97F4A7C15u;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/// First sample index of the --check-dt run, 2^55: disjoint from the main
/// run's indices (which the precision mode keeps below max_excursions).
inline constexpr std::uint64_t check_dt_first_index = std::uint64_t{1} << 55;
/// First sample index of the --check-knots run, 2^55 + 2^54: disjoint from
/// both while the run has fewer than 2^54 excursions (checked), and below the
/// index limit of 2^56.
inline constexpr std::uint64_t check_knots_first_index = (std::uint64_t{1} << 55) + (std::uint64_t{1} << 54);

/// --control-variate, for `diffusivity` and every point of a `sweep`.
inline constexpr SettingInfo control_variate_info{
    "control-variate", "",
    "auto (default): estimate D and M0 with a martingale control variate wherever a corrector exists (coloured "
    "noise with tau' >= 1e-6, or white noise with the resolvent scheme), typically 20-60 times less variance; off: "
    "the plain estimator alone. The plain estimates are reported either way"};
/// --control-variate-pilot, for `diffusivity` and every point of a `sweep`.
inline constexpr SettingInfo control_variate_pilot_info{
    "control-variate-pilot", "",
    "excursions of an independent pilot run on which the control variate's coefficients are fitted (8192 by "
    "default, at most 4 times --excursions, at the coarser of --dt and the automatic step); 0 fits them on the "
    "run's own excursions. Measured without drag at 2000 excursions, D's 95% interval covers 92-95% with the "
    "pilot, 82-94% with 0"};

/// The request's settings: RunSettings', ExcursionSettings', then
/// --estimator, --rel-precision and --max-excursions.
template <class Visitor>
void visit_settings(DiffusivityRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), v);
    visit_settings(static_cast<ExcursionSettings&>(r), v);
    v(r.estimator, SettingInfo{"estimator", "",
                               "renewal (default, correct) or paper (eq. 12, Var U/E t: biased when M0 != 0; for "
                               "reproducing the paper's numbers only)"});
    v(r.rel_precision, SettingInfo{"rel-precision", "",
                                   "precision on demand: run in batches (the first of --excursions) until the upper "
                                   "half-width of D's interval (hi - D) is at most this fraction of D, e.g. 0.01; 0 = "
                                   "off. The stopping "
                                   "time depends on the data, so the interval's coverage is slightly below --level. "
                                   "With --engine kolmogorov: the target estimated relative error of D (0: the solver's default)"});
    v(r.max_excursions, SettingInfo{"max-excursions", "", "cap of --rel-precision: most excursions in all"});
    v(r.check_dt, SettingInfo{"check-dt", "",
                              "also run as many excursions at twice --dt on independent streams and report the "
                              "difference of D and M0 (inclusion engine): the step's bias, with its standard error"});
    v(r.check_knots, SettingInfo{"check-knots", "",
                                 "also run as many excursions with the drift law's knots twice as far apart, on "
                                 "independent streams, and report the difference of D and M0 (--drift, "
                                 "--drift-table): the interpolation's effect, with its standard error"});
    v(r.control_variate, control_variate_info);
    v(r.control_variate_pilot, control_variate_pilot_info);
}

/// The --check-dt comparison: the same estimates at twice the step (and the
/// --check-knots one: with knots twice as far apart; then dt == check_dt and
/// knots, check_knots give the knot counts).
struct DiscretisationCheck {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    int knots = 0;
    int check_knots = 0;
    double dt = std::numeric_limits<double>::quiet_NaN();
    double check_dt = std::numeric_limits<double>::quiet_NaN();
    std::uint64_t excursions = 0;
    std::uint64_t steps = 0;
    Estimate diffusivity_difference;
    Estimate mobility_difference;
    /// @}

    /// The fields, in report order (result_fields.hpp). A --check-dt run sets
    /// dt, check_dt and steps, a --check-knots run knots and check_knots.
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = DiscretisationCheck;
        visit(&S::knots, FieldInfo{"knots", "", "--check-knots: the run's knots", FieldForm::WhenSet});
        visit(&S::check_knots, FieldInfo{"check_knots", "", "--check-knots: the coarse run's knots (about half)",
                                         FieldForm::WhenSet});
        visit(&S::dt, FieldInfo{"dt", "s", "--check-dt: the run's step", FieldForm::WhenSet});
        visit(&S::check_dt, FieldInfo{"check_dt", "s", "--check-dt: twice it", FieldForm::WhenSet});
        visit(&S::excursions, FieldInfo{"excursions", "", "excursions completed by the coarse run"});
        visit(&S::steps, FieldInfo{"steps", "", "--check-dt: steps made by the coarse run", FieldForm::WhenSet});
        visit(&S::diffusivity_difference,
              FieldInfo{"diffusivity", "m^2/s",
                        "D of the coarse run minus D of the run, with the standard error of the difference (the runs "
                        "are independent: their standard errors add in quadrature)",
                        FieldForm::NoInterval});
        visit(&S::mobility_difference,
              FieldInfo{"mobility", "m/s", "M0 of the coarse run minus M0 of the run, with its standard error",
                        FieldForm::NoInterval});
    }
};

/// D's interval is flagged (ControlVariateReport::flagged, and a note) when
/// the tail index of its influence function, as a run measures it (Hill's,
/// from the sqrt(N) largest of N terms: biased low at a few thousand), is
/// below this. Read off 300 runs per case at N = 200, 500 and 2000
/// (docs/validation.md, "The run's own diagnosis"): it flags at least 90% of
/// the runs whose interval misses at N = 200-500 wherever the coverage is
/// below 93%, and few runs with drag, where the interval is nominal.
inline constexpr double interval_flag_tail_index = 2.25;

/// How the control variate of a diffusivity run went (theory.md, section 12).
struct ControlVariateReport {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    std::string source;
    std::string grid;
    double corrector_seconds = 0;
    double beta = 0;
    double beta_mobility = 0;
    std::uint64_t pilot_excursions = 0;
    double variance_reduction = 0;
    double variance_reduction_mobility = 0;
    Estimate plain_diffusivity;
    Estimate plain_mobility;
    /// @}
    /// The shape of D_cv's influence function and of the plain D's
    /// (influence_tail.hpp), measured on whichever of the run and its pilot ran
    /// second, at the estimates of the first (a fixed number of excursions:
    /// the pilot's, at the run's estimates and its fitted beta;
    /// --rel-precision: the run's, at the pilot's); NaN and 0 (not written)
    /// without a pilot or when the second was not run. Units and meanings in
    /// fields() below.
    /// @{
    std::uint64_t shape_excursions = 0;
    double skewness = std::numeric_limits<double>::quiet_NaN();
    double excess_kurtosis = std::numeric_limits<double>::quiet_NaN();
    double tail_index = std::numeric_limits<double>::quiet_NaN();
    std::uint64_t tail_terms = 0;
    double plain_skewness = std::numeric_limits<double>::quiet_NaN();
    double plain_excess_kurtosis = std::numeric_limits<double>::quiet_NaN();
    double plain_tail_index = std::numeric_limits<double>::quiet_NaN();
    std::uint64_t plain_tail_terms = 0;
    /// @}
    /// The interval of D is flagged: tail_index < interval_flag_tail_index.
    bool flagged = false;

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = ControlVariateReport;
        visit(&S::source, FieldInfo{"source", "",
                                    "where the corrector came from: 'kolmogorov' (a coarse grid solve) or "
                                    "'closed-form' (white noise)"});
        visit(&S::grid, FieldInfo{"grid", "", "the corrector's grid, in words"});
        visit(&S::corrector_seconds,
              FieldInfo{"corrector_seconds", "s",
                        "wall time this run spent making the corrector (about 0 when the process had made it for "
                        "the same model already); reported in the run's work",
                        FieldForm::NotInBlock});
        visit(&S::beta, FieldInfo{"beta", "", "coefficient of C = M^2 - Q in D's estimate"});
        visit(&S::beta_mobility, FieldInfo{"beta_mobility", "", "coefficient of M in M0's estimate"});
        visit(&S::pilot_excursions,
              FieldInfo{"pilot_excursions", "",
                        "completed excursions of the independent pilot run the coefficients were fitted on (0: "
                        "fitted on the run's own excursions, whose interval under-covers without drag)"});
        visit(&S::variance_reduction,
              FieldInfo{"variance_reduction", "",
                        "variance of the plain estimator of D over the control variate's, from the same excursions: "
                        "the factor of excursions saved at equal error"});
        visit(&S::variance_reduction_mobility,
              FieldInfo{"variance_reduction_mobility", "", "the same for M0"});
        visit(&S::plain_diffusivity, FieldInfo{"plain.diffusivity", "m^2/s", "D without the control variate"});
        visit(&S::plain_mobility, FieldInfo{"plain.mobility", "m/s", "M0 without the control variate"});
        visit(&S::shape_excursions,
              FieldInfo{"influence.excursions", "",
                        "excursions the shape of D's influence function is measured on: the pilot's (at the run's "
                        "estimates), or with --rel-precision the run's (at the pilot's)",
                        FieldForm::WhenSet});
        visit(&S::skewness, FieldInfo{"influence.skewness", "", "skewness of D's influence function",
                                      FieldForm::WhenSet});
        visit(&S::excess_kurtosis,
              FieldInfo{"influence.excess_kurtosis", "",
                        "its excess kurtosis (not a stable number where tail_index < 4)", FieldForm::WhenSet});
        visit(&S::tail_index,
              FieldInfo{"influence.tail_index", "",
                        "Hill's estimate of alpha in P(|influence| > x) ~ x^-alpha from its tail_terms (sqrt of the "
                        "excursions) largest terms: below 4 no fourth moment, below 2 no variance; biased low from "
                        "a few thousand excursions (docs/validation.md)",
                        FieldForm::WhenSet});
        visit(&S::tail_terms, FieldInfo{"influence.tail_terms", "", "terms Hill's estimate is from", FieldForm::WhenSet});
        visit(&S::flagged,
              FieldInfo{"influence.flagged", "",
                        "D's interval may cover well below its level: tail_index below 2.25 (a note says so; "
                        "docs/validation.md, \"The run's own diagnosis\")"});
        visit(&S::plain_skewness, FieldInfo{"plain.influence.skewness", "", "the same for the plain D", FieldForm::WhenSet});
        visit(&S::plain_excess_kurtosis,
              FieldInfo{"plain.influence.excess_kurtosis", "", "the same for the plain D", FieldForm::WhenSet});
        visit(&S::plain_tail_index,
              FieldInfo{"plain.influence.tail_index", "", "the same for the plain D", FieldForm::WhenSet});
        visit(&S::plain_tail_terms,
              FieldInfo{"plain.influence.tail_terms", "", "the same for the plain D", FieldForm::WhenSet});
    }
};

/// How a precision-on-demand run ended.
struct PrecisionOutcome {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    double target = 0.0;
    double relative_error = std::numeric_limits<double>::quiet_NaN();
    double relative_half_width = std::numeric_limits<double>::quiet_NaN();
    bool reached = true;
    int batches = 1;
    std::uint64_t max_excursions = 0;
    /// @}

    /// The fields, in report order (result_fields.hpp). A sampled run sets
    /// relative_half_width, batches and max_excursions, a solver
    /// relative_error: the same block, with what each method knows.
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = PrecisionOutcome;
        visit(&S::target, FieldInfo{"target", "", "the requested relative half-width of D's interval (0: mode off)"});
        visit(&S::relative_error, FieldInfo{"relative_error", "",
                                            "solved: D's estimated relative discretisation error",
                                            FieldForm::WhenSet});
        visit(&S::relative_half_width, FieldInfo{"relative_half_width", "",
                                                 "sampled: the relative half-width (hi - D)/D achieved",
                                                 FieldForm::WhenSet});
        visit(&S::reached, FieldInfo{"reached", "",
                                     "whether the target was met (true when the mode is off); if not, a warning "
                                     "says why (max_excursions, interrupted)"});
        visit(&S::batches, FieldInfo{"batches", "", "sampled: batches of excursions run (1 when the mode is off)",
                                     FieldForm::WhenSet});
        visit(&S::max_excursions, FieldInfo{"max_excursions", "", "sampled: the request's cap on excursions",
                                            FieldForm::WhenSet});
    }
};

/// What compute_diffusivity returns; report.hpp writes it as JSON, a table
/// or CSV.
struct DiffusivityResult : MethodResult {
    /// The request, as run.
    DiffusivityRequest request;
    /// D [m^2/s], M0 [m/s] and E[t1] [s] with their intervals.
    LongExcursionEstimates estimates;
    /// How the precision-on-demand mode ended (target 0: it was off).
    PrecisionOutcome precision;
    /// Notes for the user, one sentence each: a step too coarse, fewer than
    /// 5000 excursions, capped excursions (with allow_capped), a truncated
    /// PDMP lattice, caveats on E[t1], the paper's estimator with M0 != 0, a
    /// precision target not reached, an interrupted run.
    std::vector<std::string> warnings;
    /// The --check-dt comparison (request.check_dt), when it ran.
    std::optional<DiscretisationCheck> discretisation;
    /// The --check-knots comparison (request.check_knots), when it ran.
    std::optional<DiscretisationCheck> knots_check;
    /// With --engine kolmogorov, the solver's result (details then hold its
    /// GridDetails): D, M0 and P(V = 0) each with its estimated discretisation
    /// error, and the grids solved. `estimates` then holds the solver's D, M0
    /// and E[t1] (Estimates of kind Solved; no excursions completed), so that
    /// they are where a sampled run has them; `precision` is unset (a solved
    /// result has no samples, intervals or standard errors).
    /// Empty for a sampled result.
    std::optional<KolmogorovResult> solution;
    /// When the control variate ran (request.control_variate, and a
    /// corrector): `estimates` then holds D and M0 with it (E[t1] is
    /// unchanged), and this says how, with the plain estimates.
    std::optional<ControlVariateReport> control_variate;
};

/// The request of the --check-dt run of `req`: `excursions` at 2 dt, from
/// sample index check_dt_first_index + req.control.first_index, without
/// precision mode or a check of its own.
DiffusivityRequest check_dt_request(const DiffusivityRequest& req, std::uint64_t excursions);

/// The request of the --check-knots run of `req`: `excursions` with (knots +
/// 1)/2 knots at the main run's step, from sample index
/// check_knots_first_index + req.control.first_index.
DiffusivityRequest check_knots_request(const DiffusivityRequest& req, std::uint64_t excursions);

/// Every check of a request, once (InvalidParameter on the first problem);
/// returns the engine prepared for it. A sampling engine only (the Kolmogorov
/// engine is refused: it has no engine to prepare).
PreparedEngine prepare(const DiffusivityRequest& req);
/// prepare(req), for its checks alone.
void validate(const DiffusivityRequest& req);

/// Validates the request (once), runs, estimates. Throws CappedExcursions
/// when excursions hit the guard and !allow_capped. With --engine kolmogorov
/// (engine.engine == Engine::Kolmogorov) nothing is sampled: the Kolmogorov
/// equations are solved (solve_kolmogorov) to the relative precision
/// rel_precision of D (0: the solver's default), and the result's `solution`
/// holds D, M0 and P(V = 0) with their estimated discretisation errors.
DiffusivityResult compute_diffusivity(const DiffusivityRequest& req);

/// The same without the validation, on an engine prepared from the request's
/// params and engine settings (run.hpp): for callers that have validated the
/// request already (a sweep checks every point before running any).
DiffusivityResult compute_diffusivity(const DiffusivityRequest& req, const PreparedEngine& engine);

} // namespace stickslip
