// SPDX-License-Identifier: BSD-3-Clause
// Internal: the JSON block of a struct that declares its fields
// (result_fields.hpp), written from the declaration alone, so that a new field
// reaches the JSON without a line here. What a field's value cannot say by
// itself (which model a white-noise reference belongs to) comes from the
// report, in FieldJsonStyle.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "report/common.hpp"
#include "stickslip/result_fields.hpp"

namespace stickslip::detail {

/// What a report tells fields_json about itself.
struct FieldJsonStyle {
    /// The report's model, for FieldForm::Reference fields (white_reference_json).
    const ModelParams* model = nullptr;
    /// The fields (by declared name) this report leaves out: a method's or a
    /// request's (FieldForm::Optional).
    std::vector<std::string_view> omit = {};

    /// Whether the report leaves the field out.
    bool omits(const FieldInfo& info) const { return omitted(omit, info); }
};

/// One field's value as JSON (the member types result_fields.hpp allows).
template <class Value>
ordered_json field_value_json(const Value& x, const FieldInfo& info, const FieldJsonStyle& style) {
    if constexpr (std::is_same_v<Value, Estimate>) {
        return estimate_json(x, info.form != FieldForm::NoInterval); // as its kind says
    } else if constexpr (std::is_same_v<Value, double>) {
        if (info.form == FieldForm::Reference) {
            // A report that writes a reference must say whose: a missing model
            // is the writer's bug, refused loudly rather than dereferenced.
            if (!style.model)
                throw std::logic_error(std::string("fields_json: the white-noise reference '") + info.name +
                                       "' needs the report's model (FieldJsonStyle::model)");
            return white_reference_json(x, *style.model);
        }
        return json_number(x);
    } else if constexpr (std::is_enum_v<Value>) {
        return to_string(x); // its name, as the settings write it
    } else {
        static_assert(std::is_same_v<Value, int> || std::is_same_v<Value, std::uint64_t> ||
                          std::is_same_v<Value, bool> || std::is_same_v<Value, std::string>,
                      "result_fields.hpp: a declared field of a type the JSON writer does not know");
        return x;
    }
}

/// The object at a dotted name's owner ("plain.diffusivity" -> j["plain"]),
/// made when absent, and the last part of the name.
inline ordered_json& field_owner(ordered_json& j, std::string_view& name) {
    ordered_json* at = &j;
    for (auto dot = name.find('.'); dot != std::string_view::npos; dot = name.find('.')) {
        at = &(*at)[std::string(name.substr(0, dot))];
        name.remove_prefix(dot + 1);
    }
    return *at;
}

/// The JSON block of x: its declared fields in order, less those reported
/// elsewhere (FieldForm::NotInBlock) and unset ones (FieldForm::WhenSet: a
/// number NaN, an integer 0, a text empty).
template <DeclaredFields T> ordered_json fields_json(const T& x, const FieldJsonStyle& style = {}) {
    ordered_json j = ordered_json::object();
    const DeclaredAxis axis = declared_axis(x);
    T::fields([&](auto member, const FieldInfo& info) {
        const auto& value = x.*member;
        if (info.form == FieldForm::NotInBlock || info.form == FieldForm::Axis || info.form == FieldForm::Edges ||
            style.omits(info))
            return;
        using Value = std::decay_t<decltype(value)>;
        if constexpr (inlined_block<Value>::value) {
            // A declared struct's block, in this one's place (when present).
            if (const auto* inner = inlined_value(value)) append_members(j, fields_json(*inner, style));
        } else if constexpr (std::is_same_v<Value, std::vector<double>>) {
            return; // an axis is the key of the series' points, not a key of its own
        } else if constexpr (std::is_same_v<Value, std::vector<Estimate>>) {
            // A series: its points along the axis, each keyed by the axis' name,
            // or on the bins, each keyed by its edges.
            if (!axis.values || axis.points() != value.size())
                throw std::logic_error(std::string("fields_json: the series '") + info.name +
                                       "' has no axis of its length (FieldForm::Axis or Edges)");
            ordered_json points = ordered_json::array();
            for (std::size_t k = 0; k < value.size(); ++k) {
                const std::vector<double>& at = *axis.values;
                if (!axis.edges) {
                    points.push_back(series_point(info.point_key ? info.point_key : axis.name, at[k], value[k]));
                    continue;
                }
                ordered_json bin;
                bin["lo"] = at[k];
                bin["hi"] = at[k + 1];
                append_members(bin, estimate_json(value[k], info.form != FieldForm::NoInterval));
                points.push_back(std::move(bin));
            }
            std::string_view name = info.name;
            field_owner(j, name)[std::string(name)] = std::move(points);
        } else {
            if constexpr (std::is_same_v<Value, double>) {
                if (info.form == FieldForm::WhenSet && std::isnan(value)) return;
            } else if constexpr (std::is_integral_v<Value> && !std::is_same_v<Value, bool>) {
                if (info.form == FieldForm::WhenSet && value == 0) return;
            } else if constexpr (std::is_same_v<Value, std::string>) {
                if (info.form == FieldForm::WhenSet && value.empty()) return;
            }
            std::string_view name = info.name;
            ordered_json& owner = field_owner(j, name);
            owner[std::string(name)] = field_value_json(value, info, style);
        }
    });
    return j;
}

} // namespace stickslip::detail
