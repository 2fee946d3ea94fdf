// SPDX-License-Identifier: BSD-3-Clause
// Internal header of the `stickslip` Python module (pybind11): the pieces the
// translation units share. The module is a thin layer over the library: every
// computation goes through the same request/compute/report functions as the
// CLI, so results (and their JSON, via report.hpp) are the CLI's.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "stickslip/kolmogorov.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/params.hpp"
#include "stickslip/result_fields.hpp"

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

/// Raises stickslip.UntrustworthyResultError with message `what` and the
/// result attached as its `result` attribute.
[[noreturn]] void raise_untrustworthy(const std::string& what, py::object result);

/// A run of estimates of one kind (and, sampled, one confidence level), shown
/// to Python as arrays (`value`, `error`, `stderr`, `lo`, `hi`, `ci` of shape
/// (n, 2)). Sampled or solved alike: the kind is the items' own.
struct EstimateSeries {
    std::vector<Estimate> items;
    /// The confidence level of sampled items; NaN for solved ones.
    double level = 0.95;
    /// The arrays' shape ((n_tau, n_noise) for a sweep); empty: (n,).
    std::vector<py::ssize_t> shape;

    /// The items' kind (they share one); sampled when there is none.
    EstimateKind kind() const { return items.empty() ? EstimateKind::Sampled : items.front().kind; }
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

/// The renderings shared by every result class R (to_json, to_dict, to_table,
/// to_csv: the CLI's, report.hpp, which the caller includes), its warnings in
/// Python's words and its provenance (meta).
template <class R, class Cls>
void add_renderings(Cls& cls) {
    cls.def(
           "to_json", [](const R& r, int indent) { return to_json(r, indent); }, py::arg("indent") = 2,
           "The CLI's --format json output (indent -1: one line).")
        .def(
            "to_dict", [](const R& r) { return json_loads(to_json(r, -1)); },
            "json.loads(self.to_json()): exactly the object the CLI prints with --format json.")
        .def("to_table", [](const R& r) { return to_table(r); }, "The CLI's --format table output.")
        .def("to_csv", [](const R& r) { return to_csv(r); },
             "The CLI's --format csv output: '#' comment lines (version, revision, command, seed, settings), "
             "then a header line and the rows.")
        .def_property_readonly(
            "warnings",
            [](const R& r) {
                std::vector<std::string> out;
                for (const std::string& w : r.warnings) out.push_back(python_text(w));
                return out;
            },
            "Notes on the result (list of str), as in the CLI output with the settings named by their Python "
            "keywords; the keyword functions and run() also raise each as a StickslipWarning.")
        .def_property_readonly(
            "meta",
            [](const R& r) {
                py::dict all = json_loads(to_json(r, -1));
                py::dict meta;
                for (const char* key : {"command", "settings", "version", "revision"})
                    if (all.contains(key)) meta[key] = all[key];
                return meta;
            },
            "What produced the result, as its JSON and CSV give it: {'command' (the call, or None), 'settings' "
            "(every setting, as --print-config writes them), 'version', 'revision' (when known)}.");
}

// ---- results that declare their fields (result_fields.hpp) ---------------------------------

/// A declared field's docstring: its help, then its unit in brackets.
std::string field_doc(const FieldInfo& f);
/// The Python type of a member (float, int, bool, str or Estimate; an enum
/// is its name, str; an axis a NumPy array, a series an EstimateSeries) and
/// its JSON kind (number, integer, count: an unsigned integer, boolean,
/// string, estimate, axis, series).
template <class Value> std::array<const char*, 2> field_types() {
    if constexpr (std::is_same_v<Value, Estimate>) return {"Estimate", "estimate"};
    else if constexpr (std::is_same_v<Value, std::vector<double>>) return {"FloatArray", "axis"};
    else if constexpr (std::is_same_v<Value, std::vector<Estimate>>) return {"EstimateSeries", "series"};
    else if constexpr (std::is_same_v<Value, double>) return {"float", "number"};
    else if constexpr (std::is_same_v<Value, bool>) return {"bool", "boolean"};
    else if constexpr (std::is_integral_v<Value> && std::is_unsigned_v<Value>) return {"int", "count"};
    else if constexpr (std::is_integral_v<Value>) return {"int", "integer"};
    else if constexpr (std::is_enum_v<Value>) return {"str", "string"};
    else {
        static_assert(std::is_same_v<Value, std::string>, "a declared field of a type Python does not know");
        return {"str", "string"};
    }
}

/// A series as Python sees it: its estimates, at their level (NaN when
/// empty or solved).
inline EstimateSeries estimate_series(const std::vector<Estimate>& items) {
    const bool sampled = !items.empty() && items.front().kind == EstimateKind::Sampled;
    return EstimateSeries{items, sampled ? items.front().level : std::numeric_limits<double>::quiet_NaN(), {}};
}

/// What _result_fields() tells the stub and schema generators of a declared
/// struct: its Python class ("" when Python sees it as a dict of its JSON
/// block) and its JSON Schema definition, then per field its name, unit,
/// help, Python type, form (result_fields.hpp's FieldForm, in lower case)
/// and JSON kind. A struct whose block is merged into reports' top level
/// names those reports' definitions, comma-separated, after "merged:".
struct DeclaredStruct {
    std::string python_class, schema_definition;
    /// Per field: name, unit, help, Python type, form, JSON kind, a series'
    /// point key ("" for its axis' name). Plain
    /// strings, not Python objects: the list outlives the interpreter.
    std::vector<std::array<std::string, 7>> fields;
};
/// Every struct bind_fields or note_declared was given, in that order.
std::vector<DeclaredStruct>& declared_structs();

/// T's fields as _result_fields() lists them, an inlined struct's in its
/// place (each "optional" where the struct may be absent).
template <DeclaredFields T> void list_declared_fields(std::vector<std::array<std::string, 7>>& out, bool optional) {
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(std::declval<T>().*member)>;
        static constexpr const char* forms[] = {"value", "no_interval", "reference", "when_set",
                                                "not_in_block", "axis", "edges", "optional"};
        if constexpr (inlined_block<Value>::value) {
            list_declared_fields<typename inlined_block<Value>::type>(
                out, optional || f.form == FieldForm::Optional || !DeclaredFields<Value>);
        } else {
            const auto types = field_types<Value>();
            const bool keep_form =
                f.form == FieldForm::NotInBlock || f.form == FieldForm::Axis || f.form == FieldForm::Edges;
            const char* form = optional && !keep_form ? "optional" : forms[static_cast<int>(f.form)];
            out.push_back({f.name, f.unit, f.help, types[0], form, types[1], f.point_key ? f.point_key : ""});
        }
    });
}

/// Records T's declaration for _result_fields() (declared_structs()).
template <DeclaredFields T> void note_declared(const std::string& python_class, const std::string& schema_definition) {
    DeclaredStruct d{python_class, schema_definition, {}};
    list_declared_fields<T>(d.fields, false);
    declared_structs().push_back(std::move(d));
}

/// The read-only properties of a bound class, one per declared field, with
/// the declaration's docstrings; and the record for _result_fields().
template <DeclaredFields T, class Cls> Cls& bind_fields(Cls& cls, const std::string& python_class,
                                                         const std::string& schema_definition) {
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(std::declval<T>().*member)>;
        const std::string name = field_flat_name(f), doc = field_doc(f); // pybind11 copies both
        if constexpr (std::is_same_v<Value, std::vector<double>>)
            cls.def_property_readonly(name.c_str(), [member](const T& x) { return to_array(x.*member); }, doc.c_str());
        else if constexpr (std::is_same_v<Value, std::vector<Estimate>>)
            cls.def_property_readonly(name.c_str(), [member](const T& x) { return estimate_series(x.*member); },
                                      doc.c_str());
        else
            cls.def_readonly(name.c_str(), member, doc.c_str());
    });
    note_declared<T>(python_class, schema_definition);
    return cls;
}

/// The declared fields (result_fields.hpp) of the part get(r) of a result, as
/// properties of the result (an enum as its name), with the declaration's
/// docstrings: D, M0, E[t1] and the excursions completed of the long
/// excursions behind a result, D_t and U(t)/t of brute force, the white-noise references of analytic.
template <class Cls, class Get>
void add_declared_fields(Cls& cls, Get get) {
    using R = typename Cls::type;
    using T = std::remove_cvref_t<decltype(get(std::declval<const R&>()))>;
    T::fields([&](auto member, const FieldInfo& f) {
        cls.def_property_readonly(
            field_flat_name(f).c_str(),
            [get, member](const R& r) {
                const auto& value = get(r).*member;
                if constexpr (std::is_enum_v<std::remove_cvref_t<decltype(value)>>) return to_string(value);
                else return value;
            },
            field_doc(f).c_str());
    });
}

/// "['a'] help [unit]; ['plain']['b'] ...": the keys of T's JSON block (a
/// dict in Python) with their help, for the docstring of the property that
/// returns it.
template <DeclaredFields T> std::string block_doc() {
    std::string out;
    T::fields([&](auto, const FieldInfo& f) {
        if (f.form == FieldForm::NotInBlock) return;
        if (!out.empty()) out += "; ";
        std::string key = "['";
        for (const char* c = f.name; *c; ++c) key += *c == '.' ? std::string("']['") : std::string(1, *c);
        out += key + "'] " + field_doc(f);
    });
    return out;
}

void bind_core(py::module_& m);     // exceptions, Params, Scales, Estimate, EstimateSeries
void bind_results(py::module_& m);  // the result classes of the simulations
void bind_requests(py::module_& m); // the request structures and run()
void bind_analytic(py::module_& m); // closed forms and white-noise references
void bind_pickling(py::module_& m); // pickling of every class above that holds a value (pickling.cpp)

} // namespace stickslip::python
