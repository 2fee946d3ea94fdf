// SPDX-License-Identifier: BSD-3-Clause
// Internal header of the `stickslip` Python module (pybind11): the pieces the
// translation units share. The module is a thin layer over the library: every
// computation goes through the same request/compute/report functions as the
// CLI, so results (and their JSON, via report.hpp) are the CLI's.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stickslip/stats/estimators.hpp"
#include "stickslip/params.hpp"

namespace stickslip::python {

namespace py = pybind11;

/// A copy of `v` as a new 1-D NumPy array (float64, or int64 for ints).
py::array_t<double> to_array(const std::vector<double>& v);
py::array_t<std::int64_t> to_array(const std::vector<int>& v);

/// A Python value as the text of a setting (setting.hpp): numbers by their
/// repr (which reads back exactly), booleans as True/False, strings as they
/// are, sequences (lists, tuples, NumPy arrays) as comma-separated items.
std::string setting_text(const py::handle& v);

/// json.loads(text).
py::object json_loads(const std::string& text);

/// A run of estimates with the same confidence level, shown to Python as
/// arrays (`value`, `stderr`, `lo`, `hi`, `ci` of shape (n, 2)).
struct EstimateSeries {
    std::vector<Estimate> items;
    double level = 0.95;
    /// The arrays' shape ((n_tau, n_noise) for a sweep); empty: (n,).
    std::vector<py::ssize_t> shape;
};

/// A note of the library as Python says it: every flag of a setting
/// (--max-steps) written as its keyword (max_steps), from the one table that
/// visit_settings generates (keyword_table()).
std::string python_text(const std::string& note);
/// The table: flag ("--max-steps") -> keyword ("max_steps"), for every
/// setting of every request (the model's included: Params' keywords) and the
/// checkpoint flags.
const std::vector<std::pair<std::string, std::string>>& keyword_table();

/// Writes `bytes` to `path` as the CLI writes --output: a regular file (or a
/// new one) atomically, a device or FIFO directly (detail/atomic_file.hpp).
void write_output_file(const std::string& path, std::string_view bytes);

/// Python repr of a float ("inf" written as float('inf')).
std::string float_repr(double x);

void bind_core(py::module_& m);     // exceptions, Params, Scales, Estimate, EstimateSeries
void bind_results(py::module_& m);  // the result classes of the simulations
void bind_requests(py::module_& m); // the request structures and run()
void bind_analytic(py::module_& m); // closed forms and white-noise references

} // namespace stickslip::python
