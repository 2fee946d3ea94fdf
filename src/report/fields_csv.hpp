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

#include <cstdint>
#include <string>
#include <type_traits>

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

/// The header cells of T's columns, comma-separated (no line end).
template <DeclaredFields T> std::string fields_csv_header() {
    std::string out;
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(std::declval<T>().*member)>;
        if (f.form == FieldForm::NotInBlock) return;
        if (!out.empty()) out += ",";
        const std::string name = field_flat_name(f);
        if constexpr (std::is_same_v<Value, Estimate>)
            out += f.form == FieldForm::NoInterval ? name + "," + name + "_error" : csv_estimate_header(name);
        else
            out += name;
    });
    return out;
}

/// The cells of x under fields_csv_header<T>(), comma-separated.
template <DeclaredFields T> std::string fields_csv_row(const T& x) {
    std::string out;
    bool first = true;
    T::fields([&](auto member, const FieldInfo& f) {
        using Value = std::remove_cvref_t<decltype(x.*member)>;
        if (f.form == FieldForm::NotInBlock) return;
        if (!first) out += ",";
        first = false;
        const Value& v = x.*member;
        if constexpr (std::is_same_v<Value, Estimate>)
            out += f.form == FieldForm::NoInterval ? csv_number(v.value) + "," + csv_number(v.error)
                                                   : csv_estimate(v);
        else if constexpr (std::is_same_v<Value, double>) out += csv_number(v);
        else if constexpr (std::is_same_v<Value, bool>) out += v ? "true" : "false";
        else if constexpr (std::is_same_v<Value, std::string>) out += csv_text(v);
        else if constexpr (std::is_enum_v<Value>) out += to_string(v);
        else {
            static_assert(std::is_integral_v<Value>, "result_fields.hpp: a declared field of a type the CSV writer "
                                                     "does not know");
            if (f.form != FieldForm::WhenSet || v != 0) out += std::to_string(v);
        }
    });
    return out;
}

} // namespace stickslip::detail
