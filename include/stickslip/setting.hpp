// SPDX-License-Identifier: BSD-3-Clause
// stickslip/setting.hpp -- one user setting: its name, unit and help, and its
// text form.
//
// Every setting a user can give (a model parameter, an engine setting, a run
// option, a field of a request) is declared once, as a struct member with its
// default, and described once, in that struct's visit_settings() right below
// it: the name, the unit and a one-line help that states the valid range. The
// name is the command-line flag (--name), the config-file key and, with '-'
// read as '_', the Python keyword. The command line, config files,
// --print-config and the Python module are all generated from these
// descriptions, and every value they take goes through the text conversions
// below, so a value is parsed, and a bad one refused, with the same words
// everywhere (InvalidParameter names the setting). Checks that involve more
// than one setting live in the struct's validate().
//
// A visitor is any callable `v(field, info)` taking, as `field`, a reference to
// a double, std::uint64_t, unsigned, int, bool or enum member, or one of the
// small reference wrappers below for settings whose text form is special.
#pragma once

/// \file
/// How each user setting is named, described, printed and parsed, once for the
/// CLI, config files and Python. The comment at the top of this header explains
/// the design.

#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "stickslip/errors.hpp"

namespace stickslip {

/// How a setting is named and explained wherever it appears.
struct SettingInfo {
    const char* name; ///< "max-steps": flag --max-steps, config key max-steps, Python max_steps
    const char* unit; ///< SI unit ("s", "m s^-2", ...); "" when it has none
    const char* help; ///< one line: what it is and its valid range
    /// The value's form in --help when it is not the type's ("NUM|inf"); nullptr: setting_form().
    const char* form = nullptr;
};

/// A number that may be left unset (stored as NaN): its default then depends
/// on other settings (e.g. a start velocity of one velocity unit). Text: empty
/// when unset.
struct OptionalNumber {
    /// The member it stands for; NaN means unset.
    double& value;
};

/// A number, or "auto": chosen by the library from other settings (e.g. the
/// time step from the model's time scales). Text: "auto" or the number.
struct NumberOrAuto {
    /// The member holding the number (kept, not used, while automatic).
    double& value;
    /// The member that says "auto".
    bool& automatic;
};

/// A random seed: a decimal integer in [0, 2^64), never rounded through a double.
struct SeedValue {
    /// The member it stands for (the Philox key of the run's streams).
    std::uint64_t& value;
};

/// A list of numbers. Text: comma-separated, or lo:hi:n for n values from lo
/// to hi, spaced evenly in log (lo, hi > 0) or, when `linear`, evenly.
struct NumberList {
    /// The member it stands for, in the order given (lo:hi:n: increasing from lo).
    std::vector<double>& values;
    /// lo:hi:n spaces the values evenly (true) or evenly in log (false: the
    /// default, for scale quantities such as noise intensities and times).
    bool linear = false;
    /// An empty text is the empty list (an optional axis, unset), not an error.
    bool may_be_empty = false;
};

/// A text: an expression, a path. Text: itself ("" when unset).
struct TextValue {
    /// The member it stands for.
    std::string& value;
};

/// A range lo,hi [m/s]; lo == hi == 0 means "automatic". Text: "lo,hi", or
/// empty for automatic.
struct NumberRange {
    /// The member holding the lower end [m/s].
    double& lo;
    /// The member holding the upper end [m/s].
    double& hi;
};

// ---- text forms -------------------------------------------------------------
// format_setting gives the shortest text that reads back to the same value
// (so `--print-config` then `--config` reproduces a run bit for bit);
// parse_setting reads it, throwing InvalidParameter(info.name, message) for
// anything that is not a value of the setting's type. Range checks are the
// struct's validate().

/// @name Text form of a setting's value
/// @{

/// The text of a value, as --print-config writes it and parse_setting reads
/// it back to the same value, bit for bit: the shortest round-trip decimal of
/// a double ("inf", "-inf"; NaN, i.e. unset, is ""), a plain decimal integer,
/// "true"/"false", and for the wrappers their text forms above (NumberList:
/// comma-separated, NumberRange: "lo,hi" or "" for automatic).
std::string format_setting(double x);
std::string format_setting(std::uint64_t x);
std::string format_setting(unsigned x);
std::string format_setting(int x);
std::string format_setting(bool x);
std::string format_setting(const OptionalNumber& x);
std::string format_setting(const NumberOrAuto& x);
std::string format_setting(const SeedValue& x);
std::string format_setting(const NumberList& x);
std::string format_setting(const NumberRange& x);
std::string format_setting(const TextValue& x);
/// @}

/// @name Reading a setting's value from text
/// @{

/// Reads `text` into `out`: the command line, config files and Python all
/// come through here. Throws InvalidParameter(info.name, message) for text
/// that is not a value of the type: not a number (or NaN) for a double; a
/// negative, fractional or too large value for an integer (all integer
/// settings are counts, >= 0; "1e6" is accepted); anything but decimal digits
/// for a seed; a bool other than true/True/1/yes/on or false/False/0/no/off;
/// "auto" makes a NumberOrAuto automatic, a number makes it that number;
/// a malformed list or range. "" unsets an OptionalNumber and makes a
/// NumberRange automatic. Range checks (e.g. friction > 0) are left to the
/// struct's validate().
void parse_setting(const SettingInfo& info, const std::string& text, double& out);
void parse_setting(const SettingInfo& info, const std::string& text, std::uint64_t& out);
void parse_setting(const SettingInfo& info, const std::string& text, unsigned& out);
void parse_setting(const SettingInfo& info, const std::string& text, int& out);
void parse_setting(const SettingInfo& info, const std::string& text, bool& out);
void parse_setting(const SettingInfo& info, const std::string& text, const OptionalNumber& out);
void parse_setting(const SettingInfo& info, const std::string& text, const NumberOrAuto& out);
void parse_setting(const SettingInfo& info, const std::string& text, const SeedValue& out);
void parse_setting(const SettingInfo& info, const std::string& text, const NumberList& out);
void parse_setting(const SettingInfo& info, const std::string& text, const NumberRange& out);
void parse_setting(const SettingInfo& info, const std::string& text, const TextValue& out);
/// @}

/// @name The form of a setting's value in --help
/// @{

/// What --help shows as the value's form, by the field's type: NUM (double,
/// OptionalNumber), INT (integers, SeedValue), LIST (NumberList), LO,HI
/// (NumberRange), NUM|auto (NumberOrAuto), the enums' choices, and "" for a bool (a flag without a
/// value). SettingInfo::form overrides it (e.g. NUM|inf).
const char* setting_form(const double&);
const char* setting_form(const std::uint64_t&);
const char* setting_form(const unsigned&);
const char* setting_form(const int&);
const char* setting_form(const bool&);
const char* setting_form(const OptionalNumber&);
const char* setting_form(const NumberOrAuto&);
const char* setting_form(const SeedValue&);
const char* setting_form(const NumberList&);
const char* setting_form(const NumberRange&);
const char* setting_form(const TextValue&);
/// @}

// ---- the settings of a request, as a config file and a report give them ----------

/// How a setting's value is written in a config file (--print-config) and in
/// a report's "settings": a number (integers included; "inf", "auto" and the
/// empty text of an unset value are its other forms), a text (an enum's
/// choice, an expression, a path: quoted), a list of numbers (NumberList,
/// NumberRange) or a flag (true/false).
enum class SettingKind { Number, Text, List, Flag };

/// The kind of a setting by its field's type (see SettingKind).
template <class Field>
constexpr SettingKind setting_kind() {
    using T = std::decay_t<Field>;
    if constexpr (std::is_same_v<T, bool>) return SettingKind::Flag;
    else if constexpr (std::is_enum_v<T> || std::is_same_v<T, TextValue>) return SettingKind::Text;
    else if constexpr (std::is_same_v<T, NumberList> || std::is_same_v<T, NumberRange>) return SettingKind::List;
    else return SettingKind::Number;
}

/// One setting of a request with its value: what --print-config writes on one
/// line, and what the reports' provenance ("settings" in JSON, the comment
/// lines of CSV) holds.
struct SettingEntry {
    SettingInfo info;  ///< its name, unit and help
    SettingKind kind;  ///< how its value is written
    std::string text;  ///< the value, format_setting()'s text ("" when unset)
};

/// Every setting of `request`, in the order of its visit_settings(): the one
/// list from which --print-config and every report's provenance are written.
template <class Request>
std::vector<SettingEntry> setting_entries(const Request& request) {
    Request copy = request; // visit_settings takes its request by reference, to write into it
    std::vector<SettingEntry> out;
    visit_settings(copy, [&](auto&& field, const SettingInfo& info) {
        out.push_back(SettingEntry{info, setting_kind<decltype(field)>(), format_setting(field)});
    });
    return out;
}

/// The setting as one line of a config file (TOML): `name = value`, the value
/// quoted for a text, "auto" or lo:hi:n, in brackets for a list; an unset
/// value (empty text: its default depends on other settings) as the comment
/// `# name = `. With `help`, padded and followed by `  # [unit] help`.
/// --print-config writes these lines, and so does a CSV report's header, so
/// that a config file made from either reproduces the run.
std::string config_line(const SettingEntry& setting, bool help = true);

/// `text` as a message may quote it: every control byte, and every byte that is
/// not part of valid UTF-8, written as \\xNN (so that a message stays one
/// readable line whatever a user or a file gave).
std::string printable_text(std::string_view text);

/// The length of the valid UTF-8 sequence that starts `text` (1 for ASCII), or
/// 0 when it does not start with one (a stray continuation byte, an overlong
/// form, a surrogate, a truncated sequence, or empty text).
std::size_t utf8_sequence_length(std::string_view text);

/// n values from lo to hi, spaced evenly in log (lo, hi > 0) or, when linear,
/// evenly; the endpoints are exact. What "lo:hi:n" means in a NumberList.
std::vector<double> spaced_values(double lo, double hi, std::uint64_t n, bool linear = false);

/// A visitor that passes every setting on to `inner` except those named in
/// `skipped` (e.g. a sweep takes --noise and --tau as lists, not as the model's
/// numbers). Make it in the call that uses it: it refers to the list.
template <class Visitor>
struct SkipSettings {
    /// The visitor that receives every setting not skipped.
    Visitor& inner;
    /// Names (SettingInfo::name) of the settings to skip. The list's storage
    /// is the caller's braced list: it lives only until the end of the full
    /// expression that made it.
    std::initializer_list<std::string_view> skipped;

    /// Passes (field, info) on to `inner` unless info.name is skipped.
    template <class Field>
    void operator()(Field&& field, const SettingInfo& info) const {
        for (auto s : skipped)
            if (s == info.name) return;
        inner(std::forward<Field>(field), info);
    }
};

/// SkipSettings for visitor `v` that skips the settings named in `skipped`,
/// e.g. visit_settings(r.params, skip_settings(v, {"tau"})).
template <class Visitor>
SkipSettings<Visitor> skip_settings(Visitor& v, std::initializer_list<std::string_view> skipped) {
    return SkipSettings<Visitor>{v, skipped};
}

} // namespace stickslip
