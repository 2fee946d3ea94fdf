// SPDX-License-Identifier: BSD-3-Clause
// Internal: what every report shares, so all outputs agree: the JSON head
// (quantity, engine, estimator, stop rule), the parameter and nondimensional
// blocks, the tail (engine details, work, warnings, version and source
// revision), the table's head and work lines, and the number formats of
// tables and CSV.
#pragma once

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/report.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/run.hpp"
#include "stickslip/stats/run_totals.hpp"
#include "stickslip/setting.hpp"

namespace stickslip::detail {

using nlohmann::ordered_json;

// ---- JSON -------------------------------------------------------------------

/// A number, "inf"/"-inf" for infinities, null for NaN (JSON has neither).
ordered_json json_number(double x);
/// Every estimate of every report, whatever the method, is a JSON object with
/// the same paths: "value", "error" (its uncertainty in the value's unit) and
/// "kind", which says what "error" is: "sampled" (a standard error, with "ci"
/// [lo, hi] at "level" beside it), "solved" (the estimated discretisation
/// error of a solver, null where it has none) or "exact" (a closed form to
/// rounding: error 0). A script reads value and error under every engine.
/// @{
inline constexpr const char* estimate_kind_sampled = "sampled";
inline constexpr const char* estimate_kind_solved = "solved";
inline constexpr const char* estimate_kind_exact = "exact";
/// @}
/// e as its kind says: {value, error, ci, level, kind: "sampled"} (without ci
/// and level when !with_ci; error the standard error), solved_estimate_json or
/// exact_estimate_json.
ordered_json estimate_json(const Estimate& e, bool with_ci = true);
/// {value, error, kind: "solved"}: a solver's value and its estimated
/// discretisation error (NaN, written null, where it has none).
ordered_json solved_estimate_json(double value, double error);
/// {value, error: 0, kind: "exact"}.
ordered_json exact_estimate_json(double value);
/// A white-noise reference value of model p (analytic, a sweep's D_white):
/// exact_estimate_json for the affine law's closed forms, a solved estimate
/// with no error estimate (null) for a drift law's quadrature.
ordered_json white_reference_json(double value, const ModelParams& p);
/// {key: where, value, error, ci, kind: "sampled"}: one point of a series (null for NaN).
ordered_json series_point(const char* key, double where, const Estimate& e);
/// {diffusivity, mobility, mean_duration, completed}: the declared fields (fields_json).
ordered_json long_excursion_json(const LongExcursionEstimates& e);

/// The head of a report: "quantity" (when given), "engine", "estimator" (when
/// given) and "stop_rule" (when given).
ordered_json report_head(const char* quantity, const EngineSettings& s, const char* estimator,
                         const std::string* stop_rule);
/// The model, the engine's step (dt or grid) and the seed.
ordered_json params_json(const RunSettings& r);
/// The nondimensional block: tau, relaxation, bias, dt or grid, and the units.
ordered_json nondimensional_json(const RunSettings& r);
/// The same, then the results' nondimensional values (those set).
ordered_json nondimensional_json(const RunSettings& r, const NondimensionalValues& results);
/// engine_details: the thresholds, the PDMP lattice or the white level, the guard.
ordered_json engine_details_json(const ResolvedEngine& e, const RunSettings& r);
/// A setting's value as the JSON's "settings" give it: a number (an integer
/// exactly, "inf", "-inf" and "auto" as strings), a string, a bool, a list of
/// numbers (a lo:hi:n list as its string), null when unset.
ordered_json setting_json(const SettingEntry& s);
/// The provenance of a report: "command" (what asked for the run, null when
/// not known) and "settings" (every setting, as --print-config gives them).
ordered_json provenance_json(const std::string& command, const std::vector<SettingEntry>& settings);
/// The tail of a report: "interrupted": true for a run stopped early, "work"
/// (when `work` is not null), "warnings", the provenance, "version" and, when
/// the build knows it, "revision".
void add_report_tail(ordered_json& j, const ordered_json& provenance, const ordered_json* work,
                     const std::vector<std::string>& warnings, bool interrupted = false);
/// add_report_tail with the provenance of `request`.
template <class Request>
void add_report_tail(ordered_json& j, const Request& request, const ordered_json* work,
                     const std::vector<std::string>& warnings, bool interrupted = false) {
    add_report_tail(j, provenance_json(request.command_line, setting_entries(request)), work, warnings, interrupted);
}
/// The work block of w (RunWork::fields), its count under `unit` ("steps",
/// "events", "states"; "" for none).
ordered_json work_json(const RunWork& w, std::string_view unit);
/// A sampled run's work: its count under the engine's unit (steps or
/// events), seconds, threads, threads_from, and resumed_samples when some
/// were restored from a checkpoint.
RunWork run_work(const EngineSettings& s, const RunTotals& t);
/// work_json of run_work(s, t), under the engine's unit.
ordered_json work_json(const EngineSettings& s, const RunTotals& t);
/// Every member of `from` appended to `into`, in order.
void append_members(ordered_json& into, const ordered_json& from);
/// The text of a JSON report.
std::string dump(const ordered_json& j, int indent);

// ---- tables -------------------------------------------------------------------

/// The stream every text report is written into: the classic locale, whatever
/// the global C++ locale of the host program (numbers themselves are written
/// by stickslip/number_text.hpp).
std::ostringstream report_stream();

/// "friction F m/s^2", with " (static S)" when the static friction is higher.
std::string friction_text(const ModelParams& p);

/// "stickslip WHAT: ENGINE engine, dt X s" + extra + "\n".
std::string engine_line(const char* what, const EngineSettings& s, const std::string& extra);
/// The drift law's settings as the JSON's params give them (drift,
/// drift_params, drift_table as a path or as {"v", "b"} rows, knots), so that
/// the JSON reproduces the run; for p with a drift law.
void add_drift_law_json(ordered_json& j, const ModelParams& p);
/// The drift law as the reports name it: "drift b(v) = EXPR m/s^2", or its table.
std::string drift_law_text(const ModelParams& p);
/// The drift as the reports' model lines give it: drift_law_text, or
/// "relaxation R, bias B m/s^2" for the affine law of those settings.
std::string drift_text(const ModelParams& p);
/// The physical and nondimensional parameter lines.
std::string param_line(const ModelParams& p, const EngineSettings& s);
/// "N WHAT (seed S), W steps, T s on K threads" + extra + "\n".
std::string work_line(std::uint64_t samples, const char* what, std::uint64_t seed, const EngineSettings& s,
                      const RunTotals& t, const std::string& extra = "");
/// One "note: ..." line per warning.
std::string notes(const std::vector<std::string>& warnings);
/// Column titles of the estimate tables, with the interval's level.
std::string table_head(double level);
/// One estimate row: value, stderr, interval (if ci), unit, value / unit.
void table_row(std::ostringstream& os, const std::string& name, const Estimate& e, double unit,
               const std::string& units, bool ci = true);
/// "value +- stderr" in fixed columns.
std::string estimate_cell(const Estimate& e);
/// "inf" written as "inf", else x with 6 significant digits and its unit.
std::string relaxation_text(double relaxation);

// ---- CSV --------------------------------------------------------------------------

/// A CSV cell: 12 significant digits, "inf"/"-inf", and empty for NaN (never "nan").
std::string csv_number(double x);
/// "name,name_error,name_lo,name_hi" (the error column: the standard error).
std::string csv_estimate_header(const std::string& name);
/// value,stderr,lo,hi.
std::string csv_estimate(const Estimate& e);
/// The comment lines that open every CSV report: the program, its version
/// and revision, the command, the seed (when the request has one) and every
/// setting as a line of a config file, each line behind "# " (so that those
/// lines, less their "# ", are a --config file that reproduces the run).
std::string csv_provenance(const char* command_name, const std::string& command,
                           const std::vector<SettingEntry>& settings);
/// csv_provenance of `request`.
template <class Request>
std::string csv_provenance(const Request& request) {
    return csv_provenance(Request::command, request.command_line, setting_entries(request));
}

} // namespace stickslip::detail
