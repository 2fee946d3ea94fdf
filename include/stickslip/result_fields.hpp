// SPDX-License-Identifier: BSD-3-Clause
// stickslip/result_fields.hpp -- a result's fields, declared once beside its
// struct: name, unit, help and how the reports show it.
//
// A result's field used to be spelled five times: the struct member, the JSON
// writer, the Python property and its docstring, the pickling list and the
// JSON Schema; a new field touched all five and a missed one went unnoticed
// until a user's script met it. setting.hpp solved this for the inputs; this
// header does it for the outputs. A struct declares its fields in a static
// member function fields(visit), right below its members, in report order:
//
//     template <class Visit> static constexpr void fields(Visit&& visit) {
//         visit(&SweepExponent::tau, FieldInfo{"tau", "s", "the correlation time of the fit"});
//         ...
//     }
//
// and everything else is generated from that list: the JSON block
// (report/fields_json.hpp), the Python class's properties with their
// docstrings and pickling (python/src/), the type stubs and the JSON Schema's
// definition of the block (python/tools/make_stubs.py and make_schema.py, whose
// --check the tests run). A table keeps its hand layout: it is prose for
// people, not an interface.
//
// The member types a declaration may use are those the writers know: double,
// int, std::uint64_t, bool, std::string, an enum with a to_string (its name)
// and Estimate; and for a result along an axis (lags, times) the axis, a
// std::vector<double> declared FieldForm::Axis (at most one per struct), and
// its series, each a std::vector<Estimate> of the axis' length. A series is
// written as JSON points {axis: x, value, error, ci, kind}, as CSV rows (one
// per point, the axis first) and in Python as an EstimateSeries; the axis is
// the points' key, the CSV's first column and a NumPy array. A member that is
// itself a declared struct (or a std::optional of one) is inlined: its block
// is written in its place (when present), as a sweep point holds either the
// sampled estimates or the solver's. Declaration
// order is the order the JSON prints; changing it changes the reports (a
// CHANGELOG entry).
#pragma once

/// \file
/// How each result field is named, described and shown, once for the JSON,
/// Python, pickling, stubs and schema. The comment at the top of this header
/// explains the design.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace stickslip {

/// How a field appears in its struct's JSON block (and so in the schema).
enum class FieldForm {
    /// As it is: a number (inf as "inf", NaN as null), an integer, a boolean,
    /// a text, or an Estimate {value, error, ci, level, kind} (under a solved
    /// method {value, error, kind}).
    Value,
    /// An Estimate without its interval: {value, error, kind}.
    NoInterval,
    /// A number that is a white-noise reference of the report's model: an
    /// exact estimate for the affine law's closed forms, a solved one (error
    /// null) for a drift law's quadrature.
    Reference,
    /// A number written only when it is not NaN, an integer only when it is
    /// not 0, a text only when it is not empty (a sweep's varied constant,
    /// which is NaN without --vary; the parts of a check that only one kind of
    /// check sets; a work block's thread count, which a sweep has not); not
    /// required by the schema.
    WhenSet,
    /// Kept, pickled and given to Python, but reported elsewhere than in this
    /// struct's block (e.g. a time that belongs in the report's "work").
    NotInBlock,
    /// The axis (a std::vector<double>) that the struct's series run along:
    /// not a key of its own in JSON, but the key of every series point (its
    /// name, "lag" or "time"), and the CSV's first column.
    Axis,
    /// The bin edges (a std::vector<double>, one more than the bins) that the
    /// struct's series are densities on: each point is a bin, keyed "lo" and
    /// "hi" in JSON; not a key of its own.
    Edges,
    /// Written unless the report leaves it out (FieldJsonStyle::omit: a sweep
    /// point's own step only with --dt auto, its stop rule only when sampled);
    /// not required by the schema.
    Optional,
};

/// A result field's description: what the reports call it and say about it.
struct FieldInfo {
    /// Its name in JSON, CSV and Python (snake_case). A dot nests in JSON:
    /// "plain.diffusivity" is {"plain": {"diffusivity": ...}}; Python and the
    /// CSV, where names cannot nest, call it "plain_diffusivity"
    /// (field_flat_name).
    const char* name;
    /// Its SI unit ("m^2/s", "s", ...), or "" for a pure number.
    const char* unit;
    /// One sentence for docstrings and the schema.
    const char* help;
    /// How its struct's JSON block shows it.
    FieldForm form = FieldForm::Value;
    /// A series' point key where it is not its axis' name: analytic's
    /// autocorrelation runs along its times but is keyed "lag", as the
    /// sampled autocorrelation is (one path per quantity). nullptr: the axis'.
    const char* point_key = nullptr;
};

/// A field's name where names cannot nest (Python attributes, CSV columns):
/// its name with '.' read as '_' ("plain.diffusivity" -> "plain_diffusivity").
inline std::string field_flat_name(const FieldInfo& f) {
    std::string name = f.name;
    for (char& c : name)
        if (c == '.') c = '_';
    return name;
}

/// Whether a report that leaves out the fields named in `omit` (its
/// FieldForm::Optional ones, a block of the method it did not use) leaves
/// out f: what the JSON and CSV writers' styles ask.
inline bool omitted(const std::vector<std::string_view>& omit, const FieldInfo& f) {
    for (std::string_view name : omit)
        if (name == f.name) return true;
    return false;
}

/// A visitor that accepts any field: the test of DeclaredFields.
struct AnyFieldVisitor {
    /// Takes any member pointer and its description, and does nothing.
    template <class Member> constexpr void operator()(Member, const FieldInfo&) const {}
};

/// A struct that declares its fields: T::fields(visit) calls
/// visit(&T::member, FieldInfo{...}) once per field, in report order.
template <class T>
concept DeclaredFields = requires(AnyFieldVisitor v) { T::fields(v); };

/// Whether a member type is a declared struct written in its owner's place
/// (T, or std::optional<T>, with T declaring its fields).
template <class Value> struct inlined_block : std::bool_constant<DeclaredFields<Value>> {
    using type = Value; ///< the declared struct
};
/// The same for an optional block (written when present).
template <class Value> struct inlined_block<std::optional<Value>> : std::bool_constant<DeclaredFields<Value>> {
    using type = Value; ///< the declared struct
};

/// The declared struct behind an inlined member, or nullptr when absent.
template <class Value> const typename inlined_block<Value>::type* inlined_value(const Value& x) {
    if constexpr (DeclaredFields<Value>) return &x;
    else return x ? &*x : nullptr;
}

/// Where a struct's series lie: along its axis (FieldForm::Axis, points
/// keyed by the axis' name) or on its bins (FieldForm::Edges, points keyed
/// "lo" and "hi").
struct DeclaredAxis {
    const std::vector<double>* values = nullptr; ///< the axis, or the edges; nullptr when none
    const char* name = nullptr;                  ///< its declared name
    bool edges = false;                          ///< FieldForm::Edges: one more value than points

    /// The points a series along it has.
    std::size_t points() const {
        if (!values) return 0;
        return edges ? (values->empty() ? 0 : values->size() - 1) : values->size();
    }
};

/// x's axis (its FieldForm::Axis or FieldForm::Edges member); values nullptr
/// when T declares none.
template <DeclaredFields T> DeclaredAxis declared_axis(const T& x) {
    DeclaredAxis out;
    T::fields([&](auto member, const FieldInfo& info) {
        using Value = std::remove_cvref_t<decltype(x.*member)>;
        if constexpr (std::is_same_v<Value, std::vector<double>>)
            if (info.form == FieldForm::Axis || info.form == FieldForm::Edges)
                out = DeclaredAxis{&(x.*member), info.name, info.form == FieldForm::Edges};
    });
    return out;
}

} // namespace stickslip
