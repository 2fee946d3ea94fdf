// SPDX-License-Identifier: BSD-3-Clause
// Reports of results solved by the Kolmogorov engine (diffusivity, density):
// each value with its estimated discretisation error, the grid, and no
// samples, intervals or standard errors, which a solver does not have
// (method.hpp). The sampled reports (excursions.cpp, observables.cpp) hand a
// solved result over to these at their top.
#include "report/solved.hpp"

#include <cmath>

#include "core/format.hpp"
#include "stickslip/diffusivity.hpp"
#include "report/fields_json.hpp"
#include "stickslip/number_text.hpp"

namespace stickslip::detail {

namespace {

/// "value +- error" in the columns of the solved table.
void solved_row(std::ostringstream& os, const std::string& name, const Estimate& e, double unit,
                const std::string& units) {
    using number_text::pad;
    os << pad(name, -14) << " " << pad(format_number(e.value), 13) << "  +- " << pad(format_number(e.error, 3), -22)
       << "  " << pad(units, -7) << " " << pad(format_number(e.value / unit), 11) << "\n";
}

double relative_error(const KolmogorovResult& s) { return s.diffusivity.error / std::abs(s.diffusivity.value); }

} // namespace

ordered_json solved_head(const char* quantity, const RunSettings& r) {
    ordered_json j = report_head(quantity, r.engine, nullptr, nullptr);
    j["params"] = params_json(r);
    return j;
}

void add_solved_estimates(ordered_json& j, const KolmogorovResult& s, const KolmogorovSettings& settings) {
    append_members(j, fields_json(s));
    PrecisionOutcome precision;
    precision.target = settings.rel_precision;
    precision.relative_error = relative_error(s);
    precision.reached = s.converged;
    precision.batches = 0; // no sampling
    j["precision"] = fields_json(precision);
    ordered_json details;
    details["method"] = s.grid().solver;
    details["grid"] = fields_json(grid_span(s));
    j["engine_details"] = details;
}

ordered_json solved_work_json(const KolmogorovResult& s, const KolmogorovSettings& settings) {
    RunWork work;
    work.seconds = s.seconds;
    work.threads = static_cast<std::uint64_t>(settings.threads);
    return work_json(work, "");
}

std::string solved_table_head() {
    using number_text::pad;
    return pad("quantity", -14) + " " + pad("value", 13) + "  " + pad("+- error (discretisation)", -25) + "  " +
           pad("unit", -7) + " " + pad("nondim", 11) + "\n";
}

void solved_table_rows(std::ostringstream& os, const KolmogorovResult& s, const Scales& sc) {
    solved_row(os, "diffusivity D", s.diffusivity, sc.diffusivity, "m^2/s");
    solved_row(os, "mobility M0", s.mobility, sc.velocity, "m/s");
    solved_row(os, "P(V = 0)", s.stuck_probability, 1.0, "");
    solved_row(os, "mean E[t1]", s.mean_duration, sc.time, "s");
}

std::string solved_work_line(const KolmogorovResult& s, const KolmogorovSettings& settings) {
    const KolmogorovGridSpan span = grid_span(s);
    const KolmogorovGrid& fine = s.levels.back().grid;
    std::ostringstream os = report_stream();
    os << s.levels.size() << " grids solved, the finest " << span.x_nodes << " x nodes and " << span.v_cells
       << " velocity cells on [" << format_number(fine.v_lower) << ", " << format_number(fine.v_upper)
       << "] m/s, the largest " << span.largest_states << " states; "
       << format_number(s.seconds, 3) << " s on " << settings.threads << " thread" << (settings.threads > 1 ? "s" : "")
       << "; estimated relative error of D: " << format_number(100 * relative_error(s), 3) << "% (target "
       << format_number(100 * settings.rel_precision, 3) << "%)\n";
    return os.str();
}

} // namespace stickslip::detail
