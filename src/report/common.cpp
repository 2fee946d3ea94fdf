// SPDX-License-Identifier: BSD-3-Clause
#include "report/common.hpp"
#include "report/fields_json.hpp"

#include <cmath>
#include <locale>

#include "core/format.hpp"
#include "stickslip/report.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/version.hpp"

namespace stickslip::detail {

// ---- JSON -------------------------------------------------------------------

ordered_json json_number(double x) {
    if (std::isnan(x)) return nullptr;
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    return x;
}

ordered_json estimate_json(const Estimate& e, bool with_ci) {
    if (e.kind == EstimateKind::Solved) return solved_estimate_json(e.value, e.error);
    if (e.kind == EstimateKind::Exact) return exact_estimate_json(e.value);
    ordered_json j;
    j["value"] = e.value;
    j["error"] = e.error;
    if (with_ci) {
        j["ci"] = {json_number(e.lo), json_number(e.hi)}; // D's upper end is "inf" when se >= D / q
        j["level"] = e.level;
    }
    j["kind"] = estimate_kind_sampled;
    return j;
}

ordered_json solved_estimate_json(double value, double error) {
    ordered_json j;
    j["value"] = json_number(value);
    j["error"] = json_number(error);
    j["kind"] = estimate_kind_solved;
    return j;
}

ordered_json exact_estimate_json(double value) {
    ordered_json j;
    j["value"] = json_number(value);
    j["error"] = 0.0;
    j["kind"] = estimate_kind_exact;
    return j;
}

ordered_json white_reference_json(double value, const ModelParams& p) {
    return p.has_drift_law() ? solved_estimate_json(value, std::nan("")) : exact_estimate_json(value);
}

ordered_json series_point(const char* key, double where, const Estimate& e) {
    ordered_json j;
    j[key] = where;
    if (e.kind != EstimateKind::Sampled) { // a solver's or a closed form's: no interval
        append_members(j, estimate_json(e));
        return j;
    }
    j["value"] = json_number(e.value);
    j["error"] = json_number(e.error);
    j["ci"] = {json_number(e.lo), json_number(e.hi)};
    j["kind"] = estimate_kind_sampled;
    return j;
}

ordered_json long_excursion_json(const LongExcursionEstimates& e) { return fields_json(e); }

ordered_json report_head(const char* quantity, const EngineSettings& s, const char* estimator,
                         const std::string* stop_rule) {
    ordered_json j;
    if (quantity) j["quantity"] = quantity;
    j["engine"] = to_string(s.engine);
    if (estimator) j["estimator"] = estimator;
    if (stop_rule) j["stop_rule"] = *stop_rule;
    return j;
}

void add_drift_law_json(ordered_json& j, const ModelParams& p) {
    // The law as given, so that the JSON reproduces the run exactly.
    if (!p.drift.empty()) j["drift"] = p.drift;
    if (!p.drift_params.empty()) j["drift_params"] = p.drift_params;
    if (!p.drift_table.empty()) {
        j["drift_table"] = p.drift_table;
        // The file as it was read, once (read_drift_inputs).
        if (!p.drift_table_digest.empty()) j["drift_table_digest"] = p.drift_table_digest;
    } else if (!p.drift_table_v.empty()) {
        j["drift_table"] = {{"v", p.drift_table_v}, {"b", p.drift_table_b}};
    }
    j["knots"] = p.knots;
}

ordered_json params_json(const RunSettings& r) {
    const ModelParams& p = r.params;
    ordered_json j;
    j["friction"] = p.friction;
    // Written only above the friction: equal, it is the one-coefficient model,
    // whose reports stay as they were.
    if (p.has_static_band()) j["static_friction"] = p.static_friction;
    j["noise"] = p.noise;
    j["tau"] = p.tau;
    if (p.has_drift_law()) {
        add_drift_law_json(j, p);
    } else {
        j["relaxation"] = json_number(p.relaxation);
        j["bias"] = p.bias;
    }
    if (!samples(r.engine)) return j; // a grid solver: no step, no seed
    if (!has_time_step(r.engine)) j["grid"] = r.engine.grid;
    else {
        j["dt"] = r.engine.dt;
        if (r.engine.dt_auto) j["dt_auto"] = true; // the step --dt auto chose (inclusion engine)
    }
    j["seed"] = r.control.seed;
    return j;
}

ordered_json nondimensional_json(const RunSettings& r) {
    const ModelParams nd = to_nondimensional(r.params);
    const Scales sc = scales_of(r.params);
    ordered_json j;
    if (r.params.has_static_band()) j["static_friction"] = nd.static_friction; // in units of the friction
    j["tau"] = nd.tau;
    if (!r.params.has_drift_law()) { // a law other than the affine one is given in SI only
        j["relaxation"] = json_number(nd.relaxation);
        j["bias"] = nd.bias;
    }
    if (!samples(r.engine)) {
        // a grid solver: no step
    } else if (!has_time_step(r.engine)) j["grid"] = r.engine.grid / sc.noise_level;
    else j["dt"] = r.engine.dt / sc.time;
    j["time_unit"] = sc.time;
    j["length_unit"] = sc.length;
    j["velocity_unit"] = sc.velocity;
    j["diffusivity_unit"] = sc.diffusivity;
    return j;
}

ordered_json nondimensional_json(const RunSettings& r, const NondimensionalValues& results) {
    ordered_json j = nondimensional_json(r);
    append_members(j, fields_json(results));
    return j;
}

ordered_json engine_details_json(const ResolvedEngine& e, const RunSettings& r) {
    ordered_json j;
    if (!r.params.white()) {
        j["upper_threshold"] = e.upper_threshold;
        j["lower_threshold"] = e.lower_threshold;
    }
    if (!has_time_step(r.engine)) {
        j["lattice_step"] = e.lattice_step;
        j["lattice_offset"] = e.lattice_offset;
        j["lattice_bound"] = e.lattice_bound;
        j["lattice_points"] = e.lattice_points;
        j["truncated_mass"] = e.truncated_mass;
        j["jump_rate"] = e.jump_rate;
    } else {
        j["scheme"] = to_string(r.engine.scheme);
        if (r.params.white()) j["white_level"] = e.white_level;
    }
    j["max_work_per_excursion"] = r.engine.max_work_per_excursion;
    return j;
}

ordered_json work_json(const RunWork& w, std::string_view unit) {
    FieldJsonStyle style;
    for (std::string_view count : {"steps", "events", "states"})
        if (count != unit) style.omit.push_back(count); // the one count this report's work is in
    return fields_json(w, style);
}

RunWork run_work(const EngineSettings& s, const RunTotals& t) {
    RunWork w;
    w.count_in(work_unit(s)) = t.work;
    w.seconds = t.seconds;
    w.threads = t.threads;
    w.threads_from = t.threads_from; // docs/guide.md, "Threads"
    w.resumed_samples = t.resumed;   // restored from a checkpoint
    return w;
}

ordered_json work_json(const EngineSettings& s, const RunTotals& t) { return work_json(run_work(s, t), work_unit(s)); }

namespace {

// A number of a setting's text: integers exactly (a 64-bit seed would not
// survive a double), the words "inf", "-inf", "auto" as strings.
ordered_json setting_number(const std::string& text) {
    if (text == "inf" || text == "-inf" || text == "auto") return text;
    if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos)
        if (const auto n = number_text::read_unsigned(text)) return *n;
    if (const auto x = number_text::read_double(text)) return *x;
    return text; // not a number's text: kept as it is rather than lost
}

} // namespace

ordered_json setting_json(const SettingEntry& s) {
    switch (s.kind) {
    case SettingKind::Flag: return s.text == "true";
    case SettingKind::Text: return s.text;
    case SettingKind::List: {
        if (s.text.empty()) return nullptr;
        if (s.text.find(':') != std::string::npos) return s.text; // lo:hi:n
        ordered_json list = ordered_json::array();
        std::size_t from = 0;
        for (std::size_t comma; (comma = s.text.find(',', from)) != std::string::npos; from = comma + 1)
            list.push_back(setting_number(s.text.substr(from, comma - from)));
        list.push_back(setting_number(s.text.substr(from)));
        return list;
    }
    case SettingKind::Number: break;
    }
    if (s.text.empty()) return nullptr;
    return setting_number(s.text);
}

ordered_json provenance_json(const std::string& command, const std::vector<SettingEntry>& settings) {
    ordered_json j;
    j["command"] = command.empty() ? ordered_json(nullptr) : ordered_json(command);
    ordered_json values = ordered_json::object();
    for (const SettingEntry& s : settings) values[s.info.name] = setting_json(s);
    j["settings"] = values;
    return j;
}

void add_report_tail(ordered_json& j, const ordered_json& provenance, const ordered_json* work,
                     const std::vector<std::string>& warnings, bool interrupted) {
    if (interrupted) j["interrupted"] = true;
    if (work) j["work"] = *work;
    j["warnings"] = warnings;
    append_members(j, provenance);
    j["version"] = version();
    if (*source_revision()) j["revision"] = source_revision();
}

void append_members(ordered_json& into, const ordered_json& from) {
    for (auto it = from.begin(); it != from.end(); ++it) into[it.key()] = it.value();
}

std::string dump(const ordered_json& j, int indent) { return j.dump(indent) + "\n"; }

// ---- tables -------------------------------------------------------------------

std::ostringstream report_stream() {
    std::ostringstream os;
    os.imbue(std::locale::classic()); // a host's global C++ locale must not group "10000" into "10.000"
    return os;
}

std::string relaxation_text(double relaxation) {
    return std::isinf(relaxation) ? std::string("inf") : format_number(relaxation) + " s";
}

std::string engine_line(const char* what, const EngineSettings& s, const std::string& extra) {
    std::ostringstream os = report_stream();
    os << "stickslip " << what << ": " << to_string(s.engine) << " engine";
    if (!samples(s)) { // a grid solver: its grid is reported with its results
        os << extra << "\n";
        return os.str();
    }
    os << ", "
       << (!has_time_step(s) ? "grid " + format_number(s.grid) + " s^-1/2" : (s.dt_auto && std::isnan(s.dt) ? std::string("dt auto, per point") : "dt " + format_number(s.dt) + " s" + (s.dt_auto ? " (auto)" : "")))
       << (!has_time_step(s) ? std::string()
           : s.scheme == Scheme::Auto   ? std::string(", scheme auto, per point") // a sweep's
                                        : ", " + to_string(s.scheme) + " scheme")
       << extra << "\n";
    return os.str();
}

std::string drift_law_text(const ModelParams& p) {
    if (!p.drift.empty())
        return "drift b(v) = " + p.drift + (p.drift_params.empty() ? "" : " with " + p.drift_params) + " m/s^2";
    if (!p.drift_table.empty()) return "drift b(v) from the table " + p.drift_table;
    return "drift b(v) from a table of " + std::to_string(p.drift_table_v.size()) + " rows";
}

std::string friction_text(const ModelParams& p) {
    std::string t = "friction " + format_number(p.friction) + " m/s^2";
    if (p.has_static_band()) t += " (static " + format_number(p.static_friction) + ")";
    return t;
}

std::string drift_text(const ModelParams& p) {
    if (p.has_drift_law()) return drift_law_text(p);
    return "relaxation " + relaxation_text(p.relaxation) + ", bias " + format_number(p.bias) + " m/s^2";
}

std::string param_line(const ModelParams& p, const EngineSettings& s) {
    std::ostringstream os = report_stream();
    os << friction_text(p) << ", noise " << format_number(p.noise) << " m^2/s^3, tau "
       << format_number(p.tau) << " s, ";
    os << drift_text(p) << "\n";
    const ModelParams nd = to_nondimensional(p);
    const Scales sc = scales_of(p);
    os << "nondimensional: tau' " << format_number(nd.tau);
    if (p.has_static_band()) os << ", static friction' " << format_number(nd.static_friction);
    if (!p.has_drift_law())
        os << ", relaxation' " << (std::isinf(nd.relaxation) ? std::string("inf") : format_number(nd.relaxation))
           << ", bias' " << format_number(nd.bias);
    if (!samples(s)) {
        // a grid solver: no step
    } else if (!has_time_step(s)) os << ", grid' " << format_number(s.grid / sc.noise_level);
    else os << ", dt' " << format_number(s.dt / sc.time);
    os << "  (time unit " << format_number(sc.time) << " s, length unit " << format_number(sc.length) << " m)\n";
    return os.str();
}

std::string work_line(std::uint64_t samples, const char* what, std::uint64_t seed, const EngineSettings& s,
                      const RunTotals& t, const std::string& extra) {
    std::ostringstream os = report_stream();
    os << samples << " " << what << " (seed " << seed << "), " << t.work
       << " " << work_unit(s) << ", " << format_number(t.seconds, 3) << " s on "
       << t.threads << " thread" << (t.threads > 1 ? "s" : "") << extra << "\n";
    return os.str();
}

std::string notes(const std::vector<std::string>& warnings) {
    std::string s;
    for (const auto& w : warnings) s += "note: " + w + "\n";
    return s;
}

std::string table_head(double level) {
    // Built with append: GCC 12 warns (-Wrestrict, a false positive) on " " + std::string.
    using number_text::pad;
    std::string interval = " ";
    interval.append(format_number(100 * level, 3)).append("% interval");
    return pad("quantity", -14) + " " + pad("value", 13) + "  " + pad("+- stderr", -13) + " " + pad(interval, -25) +
           "  " + pad("unit", -7) + " " + pad("nondim", 11) + "\n";
}

void table_row(std::ostringstream& os, const std::string& name, const Estimate& e, double unit,
               const std::string& units, bool ci) {
    using number_text::pad;
    std::string interval = pad("", 27);
    if (ci) // appended: GCC 12 warns (-Wrestrict, a false positive) on "[" + std::string
        interval = std::string("[").append(pad(format_number(e.lo), 11)).append(", ").append(pad(format_number(e.hi), 11)).append("]");
    os << pad(name, -14) << " " << pad(format_number(e.value), 13) << "  +- " << pad(format_number(e.error, 3), -10)
       << " " << interval << "  " << pad(units, -7) << " " << pad(format_number(e.value / unit), 11) << "\n";
}

std::string estimate_cell(const Estimate& e) {
    return number_text::pad(format_number(e.value), 12) + " +- " + number_text::pad(format_number(e.error, 3), -10);
}

// ---- CSV --------------------------------------------------------------------------

std::string csv_number(double x) {
    // The shortest text that reads back to the same double (at most 17
    // significant digits), as the JSON writes it: a CSV loses nothing.
    // Undefined values (a slope from one point) are an empty cell, never "nan".
    return format_setting(x);
}

std::string csv_estimate_header(const std::string& name) {
    return name + "," + name + "_error," + name + "_lo," + name + "_hi";
}

std::string csv_estimate(const Estimate& e) {
    return csv_number(e.value) + "," + csv_number(e.error) + "," + csv_number(e.lo) + "," + csv_number(e.hi);
}

std::string csv_provenance(const char* command_name, const std::string& command,
                           const std::vector<SettingEntry>& settings) {
    // Comment lines: pandas (comment="#"), numpy (genfromtxt) and R
    // (comment.char = "#") skip them; the revision has a line of its own, so
    // that outputs of two builds can be compared without it.
    std::string out = std::string("# stickslip ") + command_name + ", version " + version() + "\n";
    if (*source_revision()) out += std::string("# revision: ") + source_revision() + "\n";
    out += "# command: " + (command.empty() ? std::string("(a library call)") : printable_text(command)) + "\n";
    for (const SettingEntry& s : settings)
        if (std::string_view(s.info.name) == "seed") out += "# seed: " + s.text + "\n";
    out += "# settings: the lines below, less their '# ', are a --config file of this run\n";
    for (const SettingEntry& s : settings) out += "# " + printable_text(config_line(s, false)) + "\n";
    return out;
}

} // namespace stickslip::detail

namespace stickslip {

namespace {

// The first null (a NaN or inf that nlohmann wrote as null) below `j`, as a
// JSON path; empty when there is none.
std::string first_null(const nlohmann::json& j, const std::string& path) {
    if (j.is_null()) return path.empty() ? "." : path;
    if (j.is_number_float() && !std::isfinite(j.get<double>())) return path;
    if (j.is_object()) {
        for (auto it = j.begin(); it != j.end(); ++it) {
            // The settings may say "not applicable" with null (x0 of white
            // noise), and so may a sweep's fits, which need two (slope) or
            // three (exponent's chi2_per_dof) points, or for the approach to
            // white noise two to four resolved points and two taus that
            // bracket 1%: their inputs, the points' D and M0, are checked.
            if (path.empty() && (it.key() == "params" || it.key() == "nondimensional" || it.key() == "settings" ||
                                 it.key() == "command"))
                continue;
            if (it.key() == "slope" || it.key() == "exponents" || it.key() == "white_limits") continue;
            // A solver's value may have no error estimate (a density cell):
            // null is its "none".
            if (it.key() == "error" && j.value("kind", "") == std::string(detail::estimate_kind_solved)) continue;
            if (std::string bad = first_null(*it, path + "." + it.key()); !bad.empty()) return bad;
        }
    } else if (j.is_array()) {
        for (std::size_t i = 0; i < j.size(); ++i)
            if (std::string bad = first_null(j[i], path + "[" + std::to_string(i) + "]"); !bad.empty()) return bad;
    }
    return {};
}

} // namespace

void check_finite_result(const std::string& json) {
    const std::string bad = first_null(nlohmann::json::parse(json), "");
    if (!bad.empty())
        throw UntrustworthyResult("the result's " + bad.substr(bad[0] == '.' ? 1 : 0) +
                                  " is not a finite number: the settings take this run beyond what double precision "
                                  "or the samples can resolve (too few samples in a bin or lag, a step or value near "
                                  "1e308); nothing was written");
}

} // namespace stickslip
