// SPDX-License-Identifier: BSD-3-Clause
// stickslip/drift_input.hpp -- a user's drift law (expression, table, callable)
// made into the knots the engines run (drift_law.hpp), once per run.
//
// The law is sampled, never evaluated in a kernel. Its knots are uniform with
// one of them at v = 0, where friction makes the force jump anyway: b(0), which
// sets the noise thresholds x* and x-*, is then the law's own value, and the
// friction kink and a knot coincide. The range is chosen from the model so that
// the velocities a run reaches lie inside the knots (beyond them the outer
// pieces continue the law): the larger of
//  * where the white-noise potential (2/noise) int (b - friction sgn v) has
//    fallen 36 below its maximum (density < e^-36), and
//  * for coloured noise, the terminal velocities under a force 6 standard
//    deviations of a X (or that force held for 3 tau),
// widened by a quarter. The interpolation error is measured at the middle of
// every piece against the law itself and reported.
#pragma once

/// \file
/// Making the run's drift law from the model's parameters. The comment at the
/// top of this header explains the design.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/drift_law.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

/// How the run's law was made from the user's input.
struct DriftLawReport {
    std::string source;          ///< "affine", "expression", "table" or "function"
    std::string text;            ///< the law as given: the expression, the table's path, "b = -v/relaxation + bias"
    double interpolation_error = 0.0; ///< max |b - interpolant| at the pieces' midpoints [m s^-2]
    double lower = 0.0;               ///< first knot [m/s]
    double upper = 0.0;               ///< last knot [m/s]
    int knots = 0;                    ///< knots used (0: affine)
    std::vector<std::string> notes;   ///< e.g. the knot count a finer interpolation needs
};

/// The run's law: the affine law of relaxation and bias when p gives no other
/// law, else the knots of p.drift, p.drift_table or p.drift_function (in that
/// order of precedence; give one). Throws InvalidParameter naming the setting
/// ("drift", "drift-table", "knots") for input that does not parse, names
/// another variable, is not finite on the range, a table that is not sorted,
/// has duplicates, NaN or fewer than two rows, and a law that does not confine
/// the velocity (no stationary state). `report`, when given, says how the law
/// was made.
///
/// Made once per inputs: the laws of the last few distinct inputs are kept
/// (thread-safe), so the many parts of one run that need the law (the
/// engine's constants, the thresholds, the step choices, the quadrature, the
/// chain, the corrector) share the one made first, bit for bit the same as a
/// new one. A callable law (drift_function) and a table path whose rows are
/// not read yet (read_drift_inputs) are made anew at each call.
DriftLaw make_drift_law(const ModelParams& p, DriftLawReport* report = nullptr);

/// How many non-affine laws make_drift_law has made in this process (not
/// counting those it served again): what the test that a run makes its law
/// once reads.
std::uint64_t drift_laws_made();

/// The named constants of a drift expression (every name but v that it uses,
/// sorted), e.g. {"a", "c"} for "a*v - c*v^3". Throws InvalidParameter("drift",
/// ...) when the text does not parse.
std::vector<std::string> drift_expression_constants(const std::string& text);

/// --drift-params text ("a=0.8,c=0.5": comma-separated NAME=NUM items)
/// without the item of `name` (items trimmed; one without '=' is kept, for
/// the law's parser to refuse).
std::string drift_params_without(const std::string& params, const std::string& name);
/// --drift-params text with `name` set to `value` (its item replaced, or
/// appended), the value written as the shortest text that reads back to the
/// same double: what a sweep over `name` gives each point.
std::string drift_params_with(const std::string& params, const std::string& name, double value);

/// The note a run gives on its law: "drift law (SOURCE) TEXT: interpolated on N
/// knots over [lower, upper] m/s, off by at most E m s^-2".
std::string drift_law_note(const DriftLawReport& law);

/// The rows of a table file: one "v,b" pair per line (SI: m/s, m s^-2), '#'
/// comments, blank lines and one header line of non-numbers allowed. Throws
/// InvalidParameter("drift-table", ...) when the file cannot be read, is larger
/// than drift_table_max_bytes or holds more than drift_table_max_rows rows, or a
/// row is not two numbers. With `digest`, it receives the digest of the bytes
/// read (FNV-1a, 64 bits, as "fnv1a64:" and 16 hex digits).
void read_drift_table(const std::string& path, std::vector<double>& v, std::vector<double>& b,
                      std::string* digest = nullptr);

/// Most bytes a --drift-table file may have (checked before anything else is
/// done: `--drift-table /dev/zero` filled 1 GB in 3 s).
inline constexpr std::size_t drift_table_max_bytes = 16u << 20;
/// Most rows a --drift-table file may have (a 1e6-row table cost 29 s; the
/// interpolant has at most 2049 knots anyway).
inline constexpr std::size_t drift_table_max_rows = 100000;

/// Reads the model's input files once: a --drift-table path becomes its rows
/// (p.drift_table_v, drift_table_b) and its digest (p.drift_table_digest), the
/// path kept for the reports. Every later make_drift_law then uses the rows, so
/// a command reads the file once however often it makes the law (it was
/// opened 32 times in one run, and a table replaced meanwhile mixed two laws),
/// and a pipe or /dev/stdin serves as a table. Does nothing when the rows are
/// already there or there is no file. Throws as read_drift_table.
void read_drift_inputs(ModelParams& p);

} // namespace stickslip
