// SPDX-License-Identifier: BSD-3-Clause
// Reports of the exact white-noise references (report.hpp): JSON, table, CSV.
#include <cmath>

#include "core/format.hpp"
#include "report/common.hpp"
#include "report/fields_csv.hpp"
#include "report/fields_json.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/report.hpp"

namespace stickslip {

using namespace detail;

// ---- white-noise references ---------------------------------------------------------------

std::string to_json(const WhiteNoiseResult& r, int indent) {
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    const bool law = q.params.has_drift_law();
    ordered_json j;
    j["quantity"] = "white_noise_reference";
    append_members(j, fields_json(r.reference, FieldJsonStyle{&q.params}));
    const GridDetails& g = r.grid();
    if (!q.times.empty()) {
        j["times"] = q.times;
        j["v0"] = q.v0;
        append_members(j, fields_json(r)); // the series, with the sampled ones' paths
    }
    if (!q.velocities.empty()) {
        j["velocities"] = q.velocities;
        j["stationary_density"] = r.stationary_density;
        if (!q.times.empty()) j["transient_density"] = r.transient_density;
    }
    ordered_json params;
    params["friction"] = q.params.friction;
    params["noise"] = q.params.noise;
    if (law) {
        add_drift_law_json(params, q.params);
    } else {
        params["relaxation"] = json_number(q.params.relaxation);
        params["bias"] = q.params.bias;
    }
    j["params"] = params;
    const ModelParams nd = to_nondimensional(q.params);
    ordered_json ndj;
    if (!law) {
        ndj["relaxation"] = json_number(nd.relaxation);
        ndj["bias"] = nd.bias;
    }
    ndj["time_unit"] = sc.time;
    ndj["velocity_unit"] = sc.velocity;
    ndj["diffusivity_unit"] = sc.diffusivity;
    NondimensionalValues values =
        NondimensionalValues::of(sc, r.reference.diffusivity, r.reference.mobility, std::nan(""));
    values.variance = r.reference.variance / (sc.velocity * sc.velocity);
    append_members(ndj, fields_json(values));
    j["nondimensional"] = ndj;
    if (law || !q.times.empty()) {
        ordered_json details;
        details["method"] = g.solver;
        if (g.cells > 0)
            details["grid"] = {{"cells", g.cells},
                               {"lower", g.lower},
                               {"upper", g.upper},
                               {"discretisation_error", g.discretisation_error}};
        j["engine_details"] = details;
    }
    add_report_tail(j, r.request, nullptr, r.warnings);
    return dump(j, indent);
}

std::string to_table(const WhiteNoiseResult& r) {
    const auto& q = r.request;
    const Scales sc = scales_of(q.params);
    std::ostringstream os = report_stream();
    os << "stickslip analytic: exact white-noise references\n";
    os << friction_text(q.params) << ", noise " << format_number(q.params.noise)
       << " m^2/s^3, ";
    os << drift_text(q.params) << "\n\n";
    using number_text::pad;
    const auto row = [&os](const char* name, double value, const char* unit, double nondim) {
        os << pad(name, -16) << " " << pad(format_number(value, 10), 15) << " " << pad(unit, -8) << " "
           << pad(format_number(nondim, 10), 15) << "\n";
    };
    row("mobility M0", r.reference.mobility, "m/s", r.reference.mobility / sc.velocity);
    row("diffusivity D", r.reference.diffusivity, "m^2/s", r.reference.diffusivity / sc.diffusivity);
    row("variance Var(V)", r.reference.variance, "m^2/s^2", r.reference.variance / (sc.velocity * sc.velocity));
    os << "(last column: nondimensional)\n";
    if (!q.times.empty()) {
        const GridDetails& g = r.grid();
        os << "\n" << g.solver << "; v0 = " << format_number(q.v0) << " m/s\n";
        if (g.cells > 0)
            os << g.cells << " cells on [" << format_number(g.lower) << ", " << format_number(g.upper)
               << "] m/s, relative discretisation error about " << format_number(g.discretisation_error) << "\n";
        os << pad("t [s]", 14) << " " << pad("E[V(t)|v0] [m/s]", 18) << " " << pad("<V(t)V(0)> [m^2/s^2]", 22) << "\n";
        for (std::size_t k = 0; k < q.times.size(); ++k)
            os << pad(format_number(q.times[k]), 14) << " " << pad(format_number(r.first_moment[k].value, 10), 18) << " "
               << pad(format_number(r.autocorrelation[k].value, 10), 22) << "\n";
    }
    os << notes(r.warnings);
    return os.str();
}

std::string to_csv(const WhiteNoiseResult& r) {
    std::ostringstream os = report_stream();
    const FieldCsvStyle style{.solved = true}; // the series are exact or solved: a value and its error
    os << fields_csv_header<WhiteNoiseReference>();
    if (!r.times.empty()) os << "," << series_csv_header<WhiteNoiseResult>(style);
    os << "\n";
    // The references on every row of the series (one row without times).
    const std::string head = fields_csv_row(r.reference);
    os << (r.times.empty() ? head + "\n" : series_csv_rows(r, style, head + ","));
    return csv_provenance(r.request) + os.str();
}

} // namespace stickslip
