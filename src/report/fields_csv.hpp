// SPDX-License-Identifier: BSD-3-Clause
// Internal: the CSV columns of a struct that declares its fields
// (result_fields.hpp), header and row from the declaration alone, so that a
// new field reaches the CSV without a line here. An estimate takes the
// columns NAME, NAME_error, NAME_lo, NAME_hi (without its interval: NAME,
// NAME_error), as csv_estimate_header says; a dotted name's dots become '_';
// a field reported elsewhere (FieldForm::NotInBlock) has no column, and one
// written only when set (FieldForm::WhenSet) always has one (a CSV's columns
// do not vary by row), empty when unset (a number NaN, an integer 0).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string_view>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "report/common.hpp"
#include "stickslip/result_fields.hpp"

namespace stickslip::detail {

/// A text as one CSV cell: quoted (quotes doubled) when it holds a comma, a
/// quote or a line end (RFC 4180).
inline std::string csv_text(const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

/// What a report tells the CSV writers about itself.
struct FieldCsvStyle {
    /// The fields (by declared name) this report leaves out (FieldForm::Optional,
    /// a WhenSet field it never sets, the block of the method it did not use).
    std::vector<std::string_view> omit = {};
    /// A solver's report: an estimate takes NAME, NAME_error (no interval).
    bool solved = false;
    /// Put before every column's name: a block's path where the CSV is flat
    /// ("discretisation_" for the --check-dt block, as its JSON path
    /// discretisation.NAME reads with '.' as '_').
    std::string prefix = {};

    /// Whether the report leaves the field out.
    bool omits(const FieldInfo& info) const { return omitted(omit, info); }
};

/// Whether an estimate field's CSV cells include its interval: not for
/// FieldForm::NoInterval, nor in a solver's report.
inline bool csv_interval(const FieldInfo& f, const FieldCsvStyle& style) {
    return f.form != FieldForm::NoInterval && !style.solved;
}

/// An estimate's header cells: NAME, NAME_error, NAME_lo, NAME_hi, or
/// without its interval (csv_interval) NAME, NAME_error.
inline std::string estimate_csv_header(const std::string& name, const FieldInfo& f, const FieldCsvStyle& style) {
    return csv_interval(f, style) ? csv_estimate_header(name) : name + "," + name + "_error";
}

/// An estimate's cells: value, error and, with its interval, lo, hi.
inline std::string estimate_csv_cells(const Estimate& e, bool interval) {
    return interval ? csv_estimate(e) : csv_number(e.value) + "," + csv_number(e.error);
}

/// An estimate field's cells under estimate_csv_header.
inline std::string estimate_csv_cells(const Estimate& e, const FieldInfo& f, const FieldCsvStyle& style) {
    return estimate_csv_cells(e, csv_interval(f, style));
}

/// The header cells of T's columns, comma-separated (no line end); an
/// inlined block's columns in its place.
template <DeclaredFields T> std::string fields_csv_header(const FieldCsvStyle& style = {}) {
    std::string out;
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(std::declval<T>().*member)>;
        if (f.form == FieldForm::NotInBlock || style.omits(f)) return;
        std::string cells;
        const std::string name = style.prefix + field_flat_name(f);
        if constexpr (inlined_block<Value>::value)
            cells = fields_csv_header<typename inlined_block<Value>::type>(style);
        else if constexpr (std::is_same_v<Value, Estimate>)
            cells = estimate_csv_header(name, f, style);
        else
            cells = name;
        if (cells.empty()) return;
        if (!out.empty()) out += ",";
        out += cells;
    });
    return out;
}

/// The cells of x under fields_csv_header<T>(style), comma-separated; an
/// absent inlined block's cells empty.
template <DeclaredFields T> std::string fields_csv_row(const T& x, const FieldCsvStyle& style = {}) {
    std::string out;
    bool first = true;
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(x.*member)>;
        if (f.form == FieldForm::NotInBlock || style.omits(f)) return;
        const Value& v = x.*member;
        std::string cells;
        if constexpr (inlined_block<Value>::value) {
            using Block = typename inlined_block<Value>::type;
            const std::string head = fields_csv_header<Block>(style);
            if (head.empty()) return;
            if (const Block* inner = inlined_value(v)) cells = fields_csv_row(*inner, style);
            else cells = std::string(static_cast<std::size_t>(std::count(head.begin(), head.end(), ',')), ',');
        } else if constexpr (std::is_same_v<Value, Estimate>) {
            cells = estimate_csv_cells(v, f, style);
        } else if constexpr (std::is_same_v<Value, double>) cells = csv_number(v);
        else if constexpr (std::is_same_v<Value, bool>) cells = v ? "true" : "false";
        else if constexpr (std::is_same_v<Value, std::string>) cells = csv_text(v);
        else if constexpr (std::is_enum_v<Value>) cells = to_string(v);
        else {
            static_assert(std::is_integral_v<Value>, "result_fields.hpp: a declared field of a type the CSV writer "
                                                     "does not know");
            if (f.form != FieldForm::WhenSet || v != 0) cells = std::to_string(v);
        }
        if (!first) out += ",";
        first = false;
        out += cells;
    });
    return out;
}

/// The header line's cells of the CSV of T's series (a struct with an axis,
/// result_fields.hpp): the axis, then each series' estimate columns (as
/// estimate_csv_header), in declaration order; T's other fields have no
/// column (no line end).
template <DeclaredFields T> std::string series_csv_header(const FieldCsvStyle& style = {}) {
    std::string out;
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(std::declval<T>().*member)>;
        if constexpr (std::is_same_v<Value, std::vector<double>>) {
            if (f.form == FieldForm::Axis) out = field_flat_name(f) + out; // first, wherever declared
        } else if constexpr (std::is_same_v<Value, std::vector<Estimate>>) {
            out += ',';
            out += estimate_csv_header(field_flat_name(f), f, style);
        }
    });
    return out;
}

/// The rows of that CSV, one per point of the axis, each with its line end
/// and, when given, `head` (cells of the report's own, comma-ended) first.
template <DeclaredFields T>
std::string series_csv_rows(const T& x, const FieldCsvStyle& style = {}, const std::string& head = "") {
    const DeclaredAxis declared = declared_axis(x);
    // A histogram's CSV (bins on edges) is histogram_csv_rows'.
    if (declared.edges) throw std::logic_error("series_csv_rows: series on bin edges: histogram_csv_rows");
    const std::vector<double>* axis = declared.values;
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(x.*member)>;
        if constexpr (std::is_same_v<Value, std::vector<Estimate>>)
            if (!axis || (x.*member).size() != axis->size())
                throw std::logic_error(std::string("series_csv_rows: the series '") + f.name +
                                       "' has no axis of its length (FieldForm::Axis)");
    });
    std::string out;
    for (std::size_t k = 0; axis && k < axis->size(); ++k) {
        out += head + csv_number((*axis)[k]);
        T::fields([&](auto member, const FieldInfo& f) {
            using Value = std::remove_cvref_t<decltype(x.*member)>;
            if constexpr (std::is_same_v<Value, std::vector<Estimate>>) {
                out += ',';
                out += estimate_csv_cells((x.*member)[k], f, style);
            }
        });
        out += "\n";
    }
    return out;
}

/// The header line's cells of a histogram's CSV (a struct whose series lie on
/// bin edges, FieldForm::Edges): kind, v_lo, v_hi and an estimate's columns,
/// value, error, lo, hi (a solver's report: value, error); no line end.
inline std::string histogram_csv_header(const FieldCsvStyle& style = {}) {
    return std::string("kind,v_lo,v_hi,value,error") + (style.solved ? "" : ",lo,hi");
}

/// The rows of that CSV (a long table: one quantity per row, its velocities
/// in v_lo, v_hi): one per bin of each series (kind: the series' name), then
/// one per other estimate of x not left out (kind: its name; its velocities
/// from x.support(estimate), the set of V it is the probability of), in
/// declaration order; `head` (cells of the report's own, comma-ended) first.
/// Its other fields (a moments histogram's time) have no row: the report puts
/// them in `head`. Every row has the interval columns, a field's FieldForm::NoInterval
/// notwithstanding: a long table's columns do not vary by row, and its
/// interval names no key (the JSON's bin keys lo and hi are the edges).
template <DeclaredFields T>
std::string histogram_csv_rows(const T& x, const FieldCsvStyle& style = {}, const std::string& head = "") {
    const DeclaredAxis edges = declared_axis(x);
    if (!edges.values || !edges.edges) throw std::logic_error("histogram_csv_rows: a struct without bin edges");
    const bool interval = !style.solved; // every row's, whatever the field's form (above)
    std::string out;
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(x.*member)>;
        if (f.form == FieldForm::NotInBlock || style.omits(f)) return;
        const std::string kind = field_flat_name(f);
        if constexpr (std::is_same_v<Value, std::vector<Estimate>>) {
            const std::vector<Estimate>& bins = x.*member;
            if (bins.size() != edges.points())
                throw std::logic_error("histogram_csv_rows: the series '" + kind + "' has not one bin per edge pair");
            for (std::size_t k = 0; k < bins.size(); ++k)
                out += head + kind + "," + csv_number((*edges.values)[k]) + "," + csv_number((*edges.values)[k + 1]) +
                       "," + estimate_csv_cells(bins[k], interval) + "\n";
        } else if constexpr (std::is_same_v<Value, Estimate>) {
            const auto [lo, hi] = x.support(x.*member);
            out += head + kind + "," + csv_number(lo) + "," + csv_number(hi) + "," +
                   estimate_csv_cells(x.*member, interval) + "\n";
        }
    });
    return out;
}

} // namespace stickslip::detail
