// SPDX-License-Identifier: BSD-3-Clause
// Internal: the parts of the reports of a solved result (--engine
// kolmogorov) that diffusivity and density share: each value with its
// estimated discretisation error ("value", "error"), the precision reached,
// the grid, and no samples, intervals or standard errors.
#pragma once

#include <sstream>
#include <string>

#include "report/common.hpp"
#include "stickslip/kolmogorov.hpp"

namespace stickslip::detail {

/// The head of a solved report: "quantity" (when given), "engine" and
/// "params" (the model, no step or seed).
ordered_json solved_head(const char* quantity, const RunSettings& r);
/// "diffusivity", "mobility", "stuck_probability", "mean_duration" (E[t1])
/// as {value, error};
/// "precision" {target, relative_error, reached}; "engine_details" {"method"
/// (the solver), "grid" (the finest grid, the grids solved, the stationary
/// mass at the domain's ends, and D from the x moves' carre du champ, the
/// solver's check)}.
void add_solved_estimates(ordered_json& j, const KolmogorovResult& s, const KolmogorovSettings& settings);
/// {seconds, threads}: the solver's wall time and threads.
ordered_json solved_work_json(const KolmogorovResult& s, const KolmogorovSettings& settings);
/// Column titles of the solved table: value, "+- error (discretisation)", unit, nondim.
std::string solved_table_head();
/// The rows of D, M0, P(V = 0) and E[t1], `sc` the nondimensional units.
void solved_table_rows(std::ostringstream& os, const KolmogorovResult& s, const Scales& sc);
/// "finest grid N states (...), K grids solved, T s on K threads; estimated
/// relative error of D: E% (target P%)\n".
std::string solved_work_line(const KolmogorovResult& s, const KolmogorovSettings& settings);

} // namespace stickslip::detail
