// SPDX-License-Identifier: BSD-3-Clause
// Reports of parameter sweeps (report.hpp): JSON, table, CSV.
#include <cmath>

#include "core/format.hpp"
#include "report/common.hpp"
#include "report/fields_csv.hpp"
#include "report/fields_json.hpp"
#include "report/solved.hpp"
#include "stickslip/drift_input.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/report.hpp"

namespace stickslip {

using namespace detail;

// ---- sweep ------------------------------------------------------------------------------------

namespace {

/// --dt auto on the inclusion engine: every point has its own step (SweepPoint::dt).
bool dt_per_point(const EngineSettings& s) { return s.dt_auto && has_time_step(s); }

/// --scheme auto on the inclusion engine: every point has its own scheme (SweepPoint::scheme).
bool scheme_per_point(const EngineSettings& s) { return s.scheme == Scheme::Auto && has_time_step(s); }

/// "friction F m/s^2, DRIFT\n\n", with the swept constant when there is one.
std::string model_line(const SweepResult& r) {
    const auto& q = r.request;
    std::string vary;
    if (r.varies()) {
        vary = ", " + q.vary + " swept over ";
        for (std::size_t k = 0; k < q.vary_values.size(); ++k)
            vary += (k ? ", " : "") + format_number(q.vary_values[k]);
    }
    ModelParams shown = q.params; // the swept constant's value, if drift_params gives one, is a placeholder
    if (r.varies() && q.vary != vary_static_friction)
        shown.drift_params = drift_params_without(shown.drift_params, q.vary);
    return friction_text(q.params) + ", " + drift_text(shown) + vary + "\n\n";
}

/// The swept constant's column of a table (name, then the point's value), or "".
std::string varied_head(const SweepResult& r) {
    return r.varies() ? number_text::pad(r.request.vary, 10) + " " : std::string();
}
std::string varied_cell(const SweepResult& r, double varied) {
    return r.varies() ? number_text::pad(format_number(varied, 4), 10) + " " : std::string();
}

/// An exponent's line head: "  [NAME X, ]tau T s: ".
std::string exponent_head(const SweepResult& r, const SweepExponent& e) {
    using number_text::pad;
    return "  " + (r.varies() ? r.request.vary + " " + pad(format_number(e.varied, 4), -10) + " " : std::string()) +
           "tau " + pad(format_number(e.tau, 4), 10) + " s: ";
}

/// The fitted exponents and D's approach to white noise per noise, each
/// element its struct's declared fields (fields_json).
template <class Item>
ordered_json declared_list_json(const SweepResult& r, const std::vector<Item>& items) {
    const FieldJsonStyle style{&r.request.params};
    ordered_json out = ordered_json::array();
    for (const Item& each : items) out.push_back(fields_json(each, style));
    return out;
}

/// The table's lines on D's approach to white noise, or "".
std::string white_limits_text(const SweepResult& r) {
    // Only the noises with something to say: a fit, or the 1% point bracketed.
    std::vector<const SweepWhiteLimit*> shown;
    for (const auto& w : r.white_limits)
        if (w.points >= 2 || !std::isnan(w.tau_within_percent)) shown.push_back(&w);
    if (shown.empty()) return {};
    using number_text::fixed;
    std::ostringstream os = report_stream();
    os << "\nD against its white-noise value per noise (1 - D/D_white = c1 tau'^p, tau' = tau friction^2/noise, "
          "fitted where resolved and at most 10%; and as a tau'^(1/2) + b tau' + c tau'^(3/2)):\n";
    for (const SweepWhiteLimit* each : shown) {
        const SweepWhiteLimit& w = *each;
        os << "  " << (r.varies() ? r.request.vary + " " + format_number(w.varied, 4) + ", " : std::string())
           << "noise " << format_number(w.noise, 4) << ": D_white " << format_number(w.white_diffusivity, 6)
           << " m^2/s; ";
        if (w.points >= 2)
            os << "p = " << fixed(w.exponent.value, 3) << " +- " << format_number(w.exponent.error, 2)
               << ", c1 = " << format_number(w.coefficient.value, 4) << " +- " << format_number(w.coefficient.error, 2)
               << " over " << w.points << " points";
        else
            os << "fewer than 2 points resolved for a fit";
        if (!std::isnan(w.chi2_per_dof)) os << " (chi2/dof " << format_number(w.chi2_per_dof, 2) << ")";
        if (!std::isnan(w.half_order.value))
            os << "; a = " << format_number(w.half_order.value, 3) << " +- " << format_number(w.half_order.error, 2)
               << ", b = " << format_number(w.first_order.value, 4) << " +- " << format_number(w.first_order.error, 2)
               << ", c = " << format_number(w.three_half_order.value, 3) << " +- "
               << format_number(w.three_half_order.error, 2);
        os << "; within 1% of white below tau = "
           << (std::isnan(w.tau_within_percent) ? std::string("- (not bracketed by the taus)")
                                                : format_number(w.tau_within_percent, 3) + " s")
           << "\n";
    }
    return os.str();
}

// The reports of a sweep solved by the Kolmogorov engine: each value with its
// estimated discretisation error, no samples, stop rules, steps or intervals.

/// The sweep's "params": the model's, its noise and tau replaced by the
/// grid's "noises" and "taus" (appended last), then with --vary the swept
/// constant's name "vary" and its "vary_values".
ordered_json sweep_params_json(const SweepRequest& q) {
    auto params = params_json(q);
    params.erase("noise");
    params.erase("tau");
    params["noises"] = q.noises;
    params["taus"] = q.taus;
    if (!q.vary.empty()) {
        params["vary"] = q.vary;
        params["vary_values"] = q.vary_values;
    }
    return params;
}

/// The point's model (the sweep's with its noise and tau; the swept drift
/// constant does not enter the scales).
ModelParams point_params(const SweepResult& r, const SweepPoint& p) {
    ModelParams mp = r.request.params;
    mp.noise = p.noise;
    mp.tau = p.tau;
    return mp;
}

/// What a sweep's points leave out: the block and fields of the method not
/// used, and a step and scheme of their own, which points have only with
/// --dt auto / --scheme auto on the inclusion engine.
std::vector<std::string_view> point_omissions(const SweepResult& r) {
    if (r.solved()) return {"stop_rule", "dt", "scheme", "estimates"};
    std::vector<std::string_view> omit{"solution", "precision_reached"};
    if (!dt_per_point(r.request.engine)) omit.push_back("dt");
    if (!scheme_per_point(r.request.engine)) omit.push_back("scheme");
    return omit;
}

/// The points' JSON: each point's declared fields (SweepPoint::fields), its
/// nondimensional values and its work.
ordered_json points_json(const SweepResult& r) {
    const FieldJsonStyle style{nullptr, point_omissions(r)};
    const std::string_view unit = r.solved() ? "states" : work_unit(r.request.engine);
    ordered_json points = ordered_json::array();
    for (const auto& p : r.points) {
        const Scales sc = scales_of(point_params(r, p));
        ordered_json o = fields_json(p, style);
        NondimensionalValues values =
            NondimensionalValues::of(sc, p.diffusivity().value, p.mobility().value, p.mean_duration().value);
        values.tau = p.tau / sc.time;
        o["nondimensional"] = fields_json(values);
        RunWork work;
        work.count_in(unit) = p.work;
        work.seconds = p.seconds;
        o["work"] = work_json(work, unit);
        points.push_back(o);
    }
    return points;
}

/// "value +- error" in a column of the solved sweep table.
std::string solved_cell(const Estimate& e) {
    using number_text::pad;
    return pad(format_number(e.value, 6), 12) + " +- " + pad(format_number(e.error, 2), -8);
}

std::string solved_table(const SweepResult& r) {
    const auto& q = r.request;
    std::ostringstream os = report_stream();
    const double target = q.rel_precision > 0 ? q.rel_precision : KolmogorovSettings{}.rel_precision;
    os << engine_line("sweep", q.engine,
                      ", no sampling: the Kolmogorov equations at every point, target error of D " +
                          format_number(100 * target, 3) + "%");
    os << model_line(r);
    using number_text::fixed;
    using number_text::pad;
    os << varied_head(r) << pad("tau [s]", 10) << " " << pad("noise", 10) << "  " << pad("D [m^2/s]", -24) << " "
       << pad("M0 [m/s]", -24) << " " << pad("E[t1] [s]", -24) << " " << pad("P(V = 0)", -10) << " "
       << pad("dlogD/dlogGamma", -20) << " " << pad("D/D_white", -20) << "\n";
    for (const auto& p : r.points) {
        const KolmogorovResult& s = *p.solution;
        const std::string slope = std::isnan(p.slope.value)
                                      ? std::string("-")
                                      : pad(fixed(p.slope.value, 4), 7) + " +- " + pad(format_number(p.slope.error, 2), -8);
        os << varied_cell(r, p.varied) << pad(format_number(p.tau, 4), 10) << " " << pad(format_number(p.noise, 4), 10)
           << "  "
           << solved_cell(s.diffusivity) << " " << solved_cell(s.mobility) << " " << solved_cell(s.mean_duration) << " "
           << pad(format_number(s.stuck_probability.value, 4), -10) << " " << pad(slope, -20) << " "
           << fixed(p.white_ratio.value, 6) << " +- " << format_number(p.white_ratio.error, 2) << "\n";
    }
    if (!r.exponents.empty()) {
        os << "\nfitted D ~ noise^alpha per " << (r.varies() ? r.request.vary + " and " : "") << "tau (least squares in log-log, weighted by the discretisation errors):\n";
        for (const auto& e : r.exponents)
            os << exponent_head(r, e) << "alpha = " << fixed(e.exponent.value, 4)
               << " +- " << format_number(e.exponent.error, 2) << " over " << e.points << " points\n";
    }
    os << white_limits_text(r);
    os << "\n" << r.points.size() << " points in " << format_number(r.seconds, 3)
       << " s (the errors are estimated discretisation errors, not standard errors)\n"
       << notes(r.warnings);
    return os.str();
}

/// A sweep's CSV: one row per point, the point's declared columns
/// (SweepPoint::fields, less what this sweep leaves out), then its
/// nondimensional tau and D (and a solved point's grid states).
std::string points_csv(const SweepResult& r) {
    FieldCsvStyle style{point_omissions(r), r.solved()};
    if (!r.varies()) style.omit.push_back("varied");
    std::ostringstream os = report_stream();
    os << fields_csv_header<SweepPoint>(style) << ",tau_nondim,diffusivity_nondim" << (r.solved() ? ",states" : "")
       << "\n";
    for (const auto& p : r.points) {
        const Scales sc = scales_of(point_params(r, p));
        os << fields_csv_row(p, style) << "," << csv_number(p.tau / sc.time) << ","
           << csv_number(p.diffusivity().value / sc.diffusivity);
        if (r.solved()) os << "," << p.work;
        os << "\n";
    }
    return csv_provenance(r.request) + os.str();
}

} // namespace

std::string to_json(const SweepResult& r, int indent) {
    const auto& q = r.request;
    const std::string estimator = to_string(q.estimator);
    ordered_json j = report_head("sweep", q.engine, r.solved() ? nullptr : estimator.c_str(), nullptr);
    auto params = sweep_params_json(q);
    if (r.solved()) {
        params["rel_precision"] = q.rel_precision;
    } else {
        if (dt_per_point(q.engine)) params.erase("dt"); // each point's own: points[k].dt
        params["excursions"] = q.excursions;
        params["level"] = q.level;
    }
    j["params"] = params;
    if (r.solved()) j["engine_details"] = {{"method", "kolmogorov"}};
    j["points"] = points_json(r);
    j["exponents"] = declared_list_json(r, r.exponents);
    j["white_limits"] = declared_list_json(r, r.white_limits);
    RunWork w;
    w.seconds = r.seconds;
    w.resumed_samples = r.resumed;
    const ordered_json work = work_json(w, "");
    add_report_tail(j, r.request, &work, r.warnings, r.interrupted);
    return dump(j, indent);
}

std::string to_table(const SweepResult& r) {
    if (r.solved()) return solved_table(r);
    const auto& q = r.request;
    std::ostringstream os = report_stream();
    os << engine_line("sweep", q.engine,
                      ", " + std::to_string(q.excursions) + " excursions per point, estimator " +
                          to_string(q.estimator));
    os << model_line(r);
    using number_text::fixed;
    using number_text::pad;
    os << varied_head(r) << pad("tau [s]", 10) << " " << pad("noise", 10) << "  " << pad("D [m^2/s]", -25) << " " << pad("M0 [m/s]", -25)
       << " " << pad("E[t1] [s]", -20) << " " << pad("dlogD/dlogGamma", -20) << " " << pad("D/D_white", -18) << "\n";
    for (const auto& p : r.points) {
        const std::string slope = std::isnan(p.slope.value)
                                      ? std::string("-")
                                      : pad(fixed(p.slope.value, 3), 7) + " +- " + pad(fixed(p.slope.error, 3), -7);
        os << varied_cell(r, p.varied) << pad(format_number(p.tau, 4), 10) << " " << pad(format_number(p.noise, 4), 10)
           << "  "
           << estimate_cell(p.estimates.diffusivity) << " " << estimate_cell(p.estimates.mobility) << " "
           << pad(format_number(p.estimates.mean_duration.value, 4), 10) << " +- "
           << pad(format_number(p.estimates.mean_duration.error, 2), -7) << " " << pad(slope, -20) << " "
           << fixed(p.white_ratio.value, 4) << " +- " << pad(format_number(p.white_ratio.error, 2), -7);
        if (dt_per_point(q.engine)) os << "  dt " << format_number(p.dt) << " s";
        if (scheme_per_point(q.engine)) os << "  " << to_string(p.scheme);
        os << "\n";
    }
    if (!r.exponents.empty()) {
        os << "\nfitted D ~ noise^alpha per " << (r.varies() ? r.request.vary + " and " : "") << "tau (weighted least squares in log-log):\n";
        for (const auto& e : r.exponents) {
            const std::string chi2 = std::isnan(e.chi2_per_dof) ? "-" : format_number(e.chi2_per_dof, 2);
            os << exponent_head(r, e) << "alpha = " << fixed(e.exponent.value, 3)
               << " +- " << fixed(e.exponent.error, 3) << " (chi2/dof " << chi2 << " over " << e.points
               << " points)\n";
        }
    }
    os << white_limits_text(r);
    os << "\n" << r.points.size() << " points in " << format_number(r.seconds, 3) << " s (seed " << q.control.seed << ")\n"
       << notes(r.warnings);
    return os.str();
}

std::string to_csv(const SweepResult& r) { return points_csv(r); }

} // namespace stickslip
