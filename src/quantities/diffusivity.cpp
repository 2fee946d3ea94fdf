// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/diffusivity.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/sample_runs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

#include "core/format.hpp"
#include "stickslip/corrector.hpp"
#include "driver/result_checks.hpp"
#include "driver/step_check.hpp"
#include "quantities/solved.hpp"

namespace stickslip {

namespace {

void check_rel_precision(const DiffusivityRequest& req) {
    if (!std::isfinite(req.rel_precision) || req.rel_precision < 0 || req.rel_precision >= 1)
        throw InvalidParameter("rel-precision", "rel-precision must be in [0, 1) (0 = off), got " +
                                                    detail::format_number(req.rel_precision));
}

/// The checks of a request with the Kolmogorov engine.
void validate_solved(const DiffusivityRequest& req) {
    check_rel_precision(req);
    detail::refuse_sampling_settings(req);
    if (req.check_dt)
        throw InvalidParameter("check-dt", "check-dt needs the inclusion engine (the kolmogorov engine estimates "
                                           "its discretisation error itself)");
    detail::validate_solved(req, req.rel_precision);
}

/// D, M0 and P(V = 0) from the Kolmogorov solver: the method chosen at the top
/// of compute_diffusivity.
DiffusivityResult solve_diffusivity(const DiffusivityRequest& req) {
    validate_solved(req);
    DiffusivityResult out;
    out.request = req;
    out.solution = detail::solve(req, req.rel_precision, out.warnings);
    out.details = out.solution->details;
    out.estimates = detail::solved_long_excursion_estimates(*out.solution);
    return out;
}

} // namespace

std::string format_setting(ControlVariateMode m) { return m == ControlVariateMode::Off ? "off" : "auto"; }
void parse_setting(const SettingInfo& info, const std::string& text, ControlVariateMode& out) {
    if (text == "auto") out = ControlVariateMode::Auto;
    else if (text == "off") out = ControlVariateMode::Off;
    else
        throw InvalidParameter(info.name, std::string(info.name) + " must be 'auto' (the martingale control variate "
                                          "wherever a corrector exists) or 'off', got '" + text + "'");
}
const char* setting_form(const ControlVariateMode&) { return "auto|off"; }

PreparedEngine prepare(const DiffusivityRequest& req_in) {
    const DiffusivityRequest req = with_resolved_engine(req_in);
    PreparedEngine engine = prepare(static_cast<const RunSettings&>(req));
    validate(static_cast<const ExcursionSettings&>(req));
    check_rel_precision(req);
    if (req.control_variate_pilot == 1 || req.control_variate_pilot > max_control_variate_pilot)
        throw InvalidParameter("control-variate-pilot",
                               "control-variate-pilot must be 0 (coefficients fitted on the run itself) or "
                               "between 2 and 2^40 excursions, got " + std::to_string(req.control_variate_pilot));
    // D's relative half-width is about 7/sqrt(N) (measured at the Fig. 2
    // case, 95%): a target below 1e-7 needs more than 2^56 excursions, which
    // no run has (--rel-precision 5e-324 ran to --max-excursions, hours).
    if (req.rel_precision > 0 && req.rel_precision < 1e-7)
        throw InvalidParameter("rel-precision", "rel-precision " + detail::format_number(req.rel_precision) +
                                                    " cannot be reached: D's relative half-width falls like about "
                                                    "7/sqrt(N), so it needs " +
                                                    (std::isfinite(49 / req.rel_precision / req.rel_precision)
                                                         ? "about " + detail::format_number(
                                                                          49 / req.rel_precision / req.rel_precision, 2)
                                                         : std::string("unboundedly many")) +
                                                    " excursions, more than any run (2^56); use 1e-7 or more");
    if (req.rel_precision > 0 && req.max_excursions < req.excursions)
        throw InvalidParameter("max-excursions", "max-excursions must be >= excursions (got " +
                                                     std::to_string(req.max_excursions) + ")");
    detail::check_excursions_can_end(engine);
    detail::check_run_duration(engine, req.rel_precision > 0 ? req.max_excursions : req.excursions, req.control);
    if (req.check_dt) {
        if (!has_time_step(req.engine))
            throw InvalidParameter("check-dt", "check-dt needs the inclusion engine (the pdmp has no time step)");
        const std::uint64_t most = req.rel_precision > 0 ? req.max_excursions : req.excursions;
        if (req.control.first_index >= check_dt_first_index || most > check_dt_first_index)
            throw InvalidParameter("check-dt", "check-dt needs the run's sample indices below 2^55");
        try {
            prepare(check_dt_request(req, req.excursions));
        } catch (const InvalidParameter& e) {
            throw InvalidParameter("check-dt", "twice the step cannot be run: --" + e.parameter() + ": " + e.what());
        }
    }
    if (req.check_knots) {
        if (!req.params.has_drift_law())
            throw InvalidParameter("check-knots", "check-knots needs a drift law given by --drift or --drift-table "
                                                  "(the affine law has no knots)");
        const std::uint64_t most = req.rel_precision > 0 ? req.max_excursions : req.excursions;
        constexpr std::uint64_t room = std::uint64_t{1} << 54;
        if (req.control.first_index >= room || most > room)
            throw InvalidParameter("check-knots", "check-knots needs the run's sample indices below 2^54");
        try {
            prepare(check_knots_request(req, req.excursions));
        } catch (const InvalidParameter& e) {
            throw InvalidParameter("check-knots", "knots twice as far apart cannot be run: --" + e.parameter() + ": " +
                                                      e.what());
        }
    }
    return engine;
}

DiffusivityRequest check_knots_request(const DiffusivityRequest& req, std::uint64_t excursions) {
    DiffusivityRequest coarse = req;
    coarse.check_dt = coarse.check_knots = false;
    coarse.rel_precision = 0;
    coarse.excursions = excursions;
    coarse.engine = resolve_engine_settings(req.params, req.engine); // the same step as the main run
    coarse.engine.dt_auto = false;
    coarse.params.knots = (req.params.knots + 1) / 2;
    coarse.control.first_index = check_knots_first_index + req.control.first_index;
    return coarse;
}

DiffusivityRequest check_dt_request(const DiffusivityRequest& req, std::uint64_t excursions) {
    DiffusivityRequest coarse = req;
    coarse.check_dt = coarse.check_knots = false;
    coarse.rel_precision = 0;
    coarse.excursions = excursions;
    coarse.engine = resolve_engine_settings(req.params, req.engine);
    coarse.engine.dt *= 2;
    coarse.engine.dt_auto = false; // twice the step the main run takes
    coarse.control.first_index = check_dt_first_index + req.control.first_index;
    return coarse;
}

namespace {

/// The control variate's estimates at the pilot's coefficients, or with
/// coefficients fitted on `sums` themselves when there is no pilot.
ControlVariateEstimates control_variate_estimates(const ControlVariateSums& sums, double level,
                                                  const std::optional<ControlVariateCoefficients>& coefficients) {
    return coefficients ? estimate_control_variate(sums, level, *coefficients) : estimate_control_variate(sums, level);
}

/// The control variate's pilot (DiffusivityRequest::control_variate_pilot):
/// pilot_excursions(req) excursions under the key pilot_seed(seed), at the
/// run's own sample indices, with the run's corrector, at the coarser of the
/// run's step and the automatic one (a run at a fine step would otherwise pay
/// for its pilot at that step: any coefficients keep the estimates unbiased
/// and the interval honest, and the automatic step's are close to the run's);
/// its progress continues the line from `done` samples and `seconds` of
/// `total`. With `centres`, it sums the shape of the influence functions at
/// them (influence_tail.hpp).
RunTotals run_pilot(const DiffusivityRequest& req, const PreparedEngine& engine, const CorrectorTable& g,
                    std::uint64_t done, double seconds, std::uint64_t total, const InfluenceCentres* centres = nullptr) {
    RunControl ctl = req.control;
    ctl.seed = pilot_seed(req.control.seed);
    if (req.control.progress)
        ctl.progress = [&req, done, seconds, total](const Progress& p) {
            return req.control.progress(Progress{done + p.done, total, seconds + p.seconds, p.moments});
        };
    std::optional<PreparedEngine> coarser;
    if (has_time_step(engine.settings) && !engine.settings.dt_auto) {
        EngineSettings automatic = engine.settings;
        automatic.dt_auto = true;
        try {
            automatic = resolve_engine_settings(engine.model, automatic);
            if (automatic.dt > engine.settings.dt) {
                RunSettings pilot_settings = req;
                pilot_settings.engine = automatic;
                pilot_settings.engine.dt_auto = false;
                coarser = prepare(pilot_settings);
                if (!engine_has_martingale(*coarser)) coarser.reset();
            }
        } catch (const InvalidParameter&) { // no automatic step here: the pilot takes the run's
            coarser.reset();
        }
    }
    return run_long_excursions(coarser ? *coarser : engine, pilot_excursions(req), ctl, g, centres);
}

/// The --check-dt run (knots == false: as many excursions as `main` has, at
/// 2 dt) or the --check-knots run (knots twice as far apart), on independent
/// streams; its progress continues the main run's line. With the main run's
/// corrector `g` (nullptr: none), the check has the control variate too, so
/// that the difference compares like with like and is as sharp as its terms
/// (any g keeps the check unbiased; at 2 dt or other knots it is only a
/// little less close).
DiscretisationCheck run_check(const DiffusivityRequest& req, const DiffusivityResult& main,
                              std::vector<std::string>& warnings, bool& interrupted, bool knots,
                              const CorrectorTable* g, const std::optional<ControlVariateCoefficients>& coefficients) {
    const std::uint64_t n = main.monte_carlo().totals.requested;
    DiffusivityRequest coarse = knots ? check_knots_request(req, n) : check_dt_request(req, n);
    const char* flag = knots ? "--check-knots" : "--check-dt";
    const std::string coarser = knots ? "knots twice as far apart" : "2 dt";
    if (req.control.progress) {
        coarse.control.progress = [&req, &main, n](const Progress& p) {
            Progress q{n + p.done, 2 * n, main.monte_carlo().totals.seconds + p.seconds, &main.monte_carlo().totals.moments};
            return req.control.progress(q);
        };
    }
    const PreparedEngine engine = prepare(static_cast<const RunSettings&>(coarse));
    const RunTotals t = g ? run_long_excursions(engine, n, coarse.control, *g) : run_long_excursions(engine, n, coarse.control);
    std::vector<std::string> ignored; // the main run's warnings say it all
    try {
        detail::finish_long_excursion_run(engine, t, req.allow_capped, ignored);
    } catch (const UntrustworthyResult& e) {
        throw UntrustworthyResult(std::string("the ") + flag + " run at " + coarser + ": " + e.what());
    }
    LongExcursionEstimates est = estimate_long_excursion(t.moments, req.level, req.estimator);
    if (g) {
        const ControlVariateEstimates cv = control_variate_estimates(t.control_variate, req.level, coefficients);
        est.diffusivity = cv.diffusivity;
        est.mobility = cv.mobility;
    }
    detail::check_finite(est);
    DiscretisationCheck c;
    if (knots) {
        c.knots = req.params.knots;
        c.check_knots = coarse.params.knots;
    } else {
        c.dt = main.request.engine.dt;
        c.check_dt = coarse.engine.dt;
        c.steps = t.work;
    }
    c.excursions = t.moments.count();
    const auto& d = main.estimates.diffusivity;
    const auto& m = main.estimates.mobility;
    // Differences of independent runs: no interval (a difference's sign is the news).
    const double nan = std::numeric_limits<double>::quiet_NaN();
    c.diffusivity_difference = Estimate{est.diffusivity.value - d.value, std::hypot(est.diffusivity.error, d.error),
                                        nan, nan, req.level};
    c.mobility_difference =
        Estimate{est.mobility.value - m.value, std::hypot(est.mobility.error, m.error), nan, nan, req.level};
    if (t.interrupted) {
        interrupted = true;
        warnings.push_back(std::string("interrupted during the ") + flag + " run: its difference is from the first " +
                           std::to_string(c.excursions) + " of " + std::to_string(n) + " excursions at " + coarser);
    }
    using detail::format_number;
    // Significant at |z| > 3: a false alarm in about 0.3% of runs per quantity.
    for (const auto& [name, diff, se, value] :
         {std::tuple<const char*, double, double, double>{"D", c.diffusivity_difference.value,
                                                          c.diffusivity_difference.error, d.value},
          {"M0", c.mobility_difference.value, c.mobility_difference.error, m.value}}) {
        const double z = diff / se;
        if (std::fabs(z) > 3 && knots)
            warnings.push_back(std::string("the drift law's interpolation is visible: ") + name + " with " +
                               std::to_string(c.check_knots) + " knots differs from " + name + " with " +
                               std::to_string(c.knots) + " by " + format_number(100 * diff / std::fabs(value), 2) +
                               "% (z = " + format_number(z, 2) +
                               "); the interpolation error at the finer knots is about a quarter of that for a "
                               "smooth law, half of it at a kink: use more --knots");
        else if (std::fabs(z) > 3)
            warnings.push_back(std::string("the step's bias is visible: ") + name + " at 2 dt differs from " + name +
                               " at dt by " + format_number(100 * diff / std::fabs(value), 2) + "% (z = " +
                               format_number(z, 2) + "); for a first-order scheme the bias at dt is about that "
                               "difference (2.4 times it where D converges like sqrt(dt), white noise): use a "
                               "smaller --dt" +
                               more_accurate_scheme_advice(req.engine, req.params.tau));
    }
    return c;
}

std::uint64_t round_up_to_blocks(std::uint64_t n) { return (n + block_size - 1) / block_size * block_size; }

/// Precision on demand (DiffusivityRequest::rel_precision): batches of long
/// excursions at consecutive, block-aligned sample indices until the target.
RunTotals run_to_precision(const DiffusivityRequest& req, const PreparedEngine& engine, const CorrectorTable* g,
                           const std::optional<ControlVariateCoefficients>& coefficients,
                           const std::optional<InfluenceCentres>& centres, PrecisionOutcome& outcome) {
    RunTotals total;
    outcome.target = req.rel_precision;
    outcome.reached = false;
    outcome.batches = 0;
    outcome.max_excursions = req.max_excursions;
    std::uint64_t batch = std::min(round_up_to_blocks(req.excursions), req.max_excursions);
    std::uint64_t projected = batch;
    for (;;) {
        RunControl ctl = req.control;
        ctl.first_index = req.control.first_index + total.requested;
        if (req.control.progress) {
            ctl.progress = [&](const Progress& p) {
                BivariateMoments merged = total.moments; // for the progress line only: rounding does not matter
                if (p.moments) merged.merge(*p.moments);
                Progress q{total.requested + p.done, projected, total.seconds + p.seconds, &merged};
                return req.control.progress(q);
            };
        }
        const RunTotals t = g ? run_long_excursions(engine, batch, ctl, *g, centres ? &*centres : nullptr)
                              : run_long_excursions(engine, batch, ctl);
        total.sums.merge(t.sums); // exact: the batches' order and sizes leave no trace
        total.control_variate.merge(t.control_variate);
        total.moments = total.sums.moments();
        total.requested += t.requested;
        total.capped += t.capped;
        total.add_cost(t);
        total.threads = t.threads;
        total.threads_from = t.threads_from;
        total.interrupted = t.interrupted;
        ++outcome.batches;
        if (total.capped > 0 && !req.allow_capped) break; // reported by the caller
        std::uint64_t needed = batch;
        if (total.moments.count() >= 2) {
            // The interval the result reports: the control variate's when it runs.
            const Estimate est = g ? control_variate_estimates(total.control_variate, req.level, coefficients).diffusivity
                                   : estimate_long_excursion(total.moments, req.level, req.estimator).diffusivity;
            outcome.relative_half_width = relative_upper_half_width(est);
            if (outcome.relative_half_width <= req.rel_precision) {
                outcome.reached = true;
                break;
            }
            // Half-width ~ 1/sqrt(N): N_needed = N (rel/target)^2, with 10% to spare.
            const double n = static_cast<double>(total.moments.count());
            const double ratio = outcome.relative_half_width / req.rel_precision;
            const double more = std::isfinite(ratio) ? n * (1.1 * ratio * ratio - 1.0) : 4.0 * n;
            needed = static_cast<std::uint64_t>(std::clamp(more, 1.0, 4.0 * static_cast<double>(total.requested)));
        }
        if (total.interrupted) break; // reported by the caller
        if (total.requested >= req.max_excursions) break;
        batch = std::min(round_up_to_blocks(std::max<std::uint64_t>(needed, block_size)),
                         req.max_excursions - total.requested);
        projected = total.requested + batch;
    }
    return total;
}

} // namespace

void validate(const DiffusivityRequest& req) {
    if (!samples(req.engine)) validate_solved(req);
    else prepare(req);
}

DiffusivityResult compute_diffusivity(const DiffusivityRequest& req) {
    if (!samples(req.engine)) return solve_diffusivity(req); // the method, chosen once
    return compute_diffusivity(req, prepare(req));
}

DiffusivityResult compute_diffusivity(const DiffusivityRequest& req_in, const PreparedEngine& engine) {
    // The settings the engine was prepared with, resolved from its own model
    // (with_resolved_engine would make the law again, and could read another
    // from a table rewritten since).
    DiffusivityRequest req = req_in;
    req.engine = engine.settings;
    using detail::format_number;
    // The control variate: its corrector, made once per run, where there is one.
    std::string cv_off;
    if (req.control_variate == ControlVariateMode::Auto) {
        std::string why;
        if (req.estimator == Estimator::Paper) cv_off = "control variate off: it corrects the renewal estimator, not the paper's";
        else if (!engine_has_martingale(engine, &why) || !has_corrector(req.params, &why))
            cv_off = "control variate off: " + why;
    }
    const bool with_cv = req.control_variate == ControlVariateMode::Auto && cv_off.empty();
    const bool piloted = with_cv && req.control_variate_pilot > 0;
    const std::vector<std::string> notes =
        detail::start_notes(engine, req.excursions + (piloted ? pilot_excursions(req) : 0), req.control);
    DiffusivityResult out;
    out.request = req;
    out.monte_carlo().engine = engine.resolved;
    std::shared_ptr<const Corrector> corrector;
    double corrector_seconds = 0.0;
    std::vector<std::string> cv_notes;
    if (!cv_off.empty()) cv_notes.push_back(cv_off);
    if (with_cv) {
        const auto start = std::chrono::steady_clock::now();
        corrector = make_corrector(engine.model); // the run's law, as the engine has it
        corrector_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    const CorrectorTable* g = corrector ? &corrector->table : nullptr;
    // The coefficients' pilot: before the run when the stopping rule needs
    // them (--rel-precision), after it otherwise (an interrupted run keeps
    // its excursions and falls back to coefficients fitted on them). The
    // shape of D's influence function (influence_tail.hpp) needs a centre
    // fixed before the excursions it is measured on: the second of the two
    // runs measures it, at the first one's estimates.
    RunTotals pilot;
    bool pilot_ran = false;
    std::optional<ControlVariateCoefficients> coefficients;
    std::optional<InfluenceCentres> centres;
    const InfluenceTailSums* shape_plain = nullptr; // the sums the shape is read from
    const InfluenceTailSums* shape_cv = nullptr;
    const auto fit_pilot = [&] {
        pilot_ran = true;
        if (pilot.control_variate.count() >= 2) coefficients = fit_control_variate(pilot.control_variate);
    };
    RunTotals& totals = out.monte_carlo().totals;
    if (req.rel_precision > 0) {
        if (piloted) {
            pilot = run_pilot(req, engine, *g, 0, 0.0, pilot_excursions(req) + req.excursions);
            fit_pilot();
            if (coefficients) centres = influence_centres(pilot.control_variate, *coefficients);
        }
        if (!pilot.interrupted) totals = run_to_precision(req, engine, g, coefficients, centres, out.precision);
        else totals.interrupted = true;
        shape_plain = &totals.control_variate.plain_tail();
        shape_cv = &totals.control_variate.tail();
    } else if (g) {
        RunControl ctl = req.control; // the progress line counts the pilot's excursions too
        if (piloted && req.control.progress)
            ctl.progress = [&req](const Progress& p) {
                return req.control.progress(Progress{p.done, p.total + pilot_excursions(req), p.seconds, p.moments});
            };
        totals = run_long_excursions(engine, req.excursions, ctl, *g);
        if (piloted && !totals.interrupted) {
            // The run's centre, with its own fitted coefficient: the pilot's
            // estimates it, and any beta near the optimum describes the same tail.
            if (totals.control_variate.count() >= 2)
                centres = influence_centres(totals.control_variate, fit_control_variate(totals.control_variate));
            pilot = run_pilot(req, engine, *g, totals.requested, totals.seconds,
                              totals.requested + pilot_excursions(req), centres ? &*centres : nullptr);
            fit_pilot();
            shape_plain = &pilot.control_variate.plain_tail();
            shape_cv = &pilot.control_variate.tail();
        }
    } else totals = run_long_excursions(engine, req.excursions, req.control);
    if (pilot_ran) { // the pilot's cost is the run's
        totals.add_cost(pilot);
        totals.interrupted = totals.interrupted || pilot.interrupted;
    }
    // The shape of D's influence function, where a run measured it: it
    // replaces the general note on few excursions.
    const InfluenceShape shape = shape_cv ? shape_cv->shape() : InfluenceShape{};
    const InfluenceShape plain_shape = shape_plain ? shape_plain->shape() : InfluenceShape{};
    detail::finish_long_excursion_run(engine, totals, req.allow_capped, out.warnings, shape.samples > 0);
    out.estimates = estimate_long_excursion(totals.moments, req.level, req.estimator);
    detail::check_finite(out.estimates);
    if (piloted && !coefficients)
        out.warnings.push_back("the control variate's coefficients are fitted on the run's own excursions (its "
                               "pilot was " + std::string(pilot_ran ? "interrupted" : "not run: the run was interrupted") +
                               "): without drag the interval may cover well below its level");
    else if (piloted && pilot.interrupted)
        out.warnings.push_back("the control variate's pilot was interrupted: its coefficients are from " +
                               std::to_string(pilot.control_variate.count()) + " of " +
                               std::to_string(pilot_excursions(req)) + " excursions (the interval is "
                               "honest, only wider)");
    if (corrector) {
        const ControlVariateEstimates cv = control_variate_estimates(totals.control_variate, req.level, coefficients);
        ControlVariateReport r;
        r.source = corrector->source;
        r.grid = corrector->grid;
        r.corrector_seconds = corrector_seconds; // not corrector->seconds: a kept corrector cost nothing
        r.beta = cv.beta;
        r.beta_mobility = cv.beta_mobility;
        r.pilot_excursions = coefficients ? pilot.control_variate.count() : 0;
        r.variance_reduction = cv.variance_reduction;
        r.variance_reduction_mobility = cv.variance_reduction_mobility;
        r.plain_diffusivity = out.estimates.diffusivity;
        r.plain_mobility = out.estimates.mobility;
        if (shape.samples > 0) {
            r.shape_excursions = shape.samples;
            r.skewness = shape.skewness;
            r.excess_kurtosis = shape.excess_kurtosis;
            r.tail_index = shape.tail_index;
            r.tail_terms = shape.tail_terms;
            r.flagged = shape.tail_index < interval_flag_tail_index;
            if (r.flagged) out.warnings.push_back(detail::interval_flag_note(shape.samples, shape.tail_index, interval_flag_tail_index));
        }
        if (plain_shape.samples > 0) {
            r.plain_skewness = plain_shape.skewness;
            r.plain_excess_kurtosis = plain_shape.excess_kurtosis;
            r.plain_tail_index = plain_shape.tail_index;
            r.plain_tail_terms = plain_shape.tail_terms;
        }
        out.estimates.diffusivity = cv.diffusivity;
        out.estimates.mobility = cv.mobility;
        detail::check_finite(out.estimates);
        out.control_variate = r;
    }
    out.warnings.insert(out.warnings.end(), cv_notes.begin(), cv_notes.end());
    if (req.rel_precision > 0 && !out.precision.reached)
        out.warnings.push_back("precision target not reached: relative half-width " +
                               format_number(out.precision.relative_half_width, 3) + " > " +
                               format_number(req.rel_precision, 3) + " after " +
                               std::to_string(out.monte_carlo().totals.moments.count() + out.monte_carlo().totals.capped) + " excursions (" +
                               (out.monte_carlo().totals.interrupted ? "interrupted" : "--max-excursions") + ")");
    if (req.estimator == Estimator::Paper &&
        (out.estimates.mobility.lo > 0 || out.estimates.mobility.hi < 0))
        out.warnings.push_back("estimator 'paper' (eq. 12) is biased because the mobility is not 0; use 'renewal'");
    if (!req.check_dt)
        detail::note_precision_beyond_step(engine, req.engine.dt_auto,
                                           relative_upper_half_width(out.estimates.diffusivity), out.warnings);
    if (req.check_dt) {
        if (out.monte_carlo().totals.interrupted)
            out.warnings.push_back("the --check-dt run was not started: the run was interrupted");
        else
            out.discretisation = run_check(req, out, out.warnings, out.monte_carlo().totals.interrupted, false, g, coefficients);
    }
    if (req.check_knots) {
        if (out.monte_carlo().totals.interrupted)
            out.warnings.push_back("the --check-knots run was not started: the run was interrupted");
        else
            out.knots_check = run_check(req, out, out.warnings, out.monte_carlo().totals.interrupted, true, g, coefficients);
    }
    out.warnings.insert(out.warnings.begin(), notes.begin(), notes.end());
    return out;
}

} // namespace stickslip
