// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/setting.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/format.hpp"
#include "stickslip/number_text.hpp"

namespace stickslip {

namespace {

std::string quoted(const std::string& s) {
    // Appended: GCC 12 warns (-Wrestrict, a false positive) on "'" + std::string.
    return std::string("'").append(printable_text(s)).append("'");
}

[[noreturn]] void fail(const SettingInfo& info, const std::string& what) {
    throw InvalidParameter(info.name, std::string(info.name) + " " + what);
}

/// The exponent of a %e/%g number without '+' and leading zeros:
/// "1e-04" -> "1e-4", "3e+08" -> "3e8".
std::string tidy_exponent(std::string s) {
    const auto e = s.find('e');
    if (e == std::string::npos) return s;
    std::string mant = s.substr(0, e), exp = s.substr(e + 1);
    std::string sign;
    if (!exp.empty() && (exp[0] == '+' || exp[0] == '-')) {
        if (exp[0] == '-') sign = "-";
        exp.erase(0, 1);
    }
    while (exp.size() > 1 && exp[0] == '0') exp.erase(0, 1);
    return mant + "e" + sign + exp;
}

} // namespace

std::vector<double> spaced_values(double lo, double hi, std::uint64_t n, bool linear) {
    std::vector<double> out;
    out.reserve(n);
    for (std::uint64_t k = 0; k < n; ++k) {
        const double f = n == 1 ? 0.0 : static_cast<double>(k) / static_cast<double>(n - 1);
        out.push_back(linear ? lo + (hi - lo) * f : std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * f));
    }
    if (n > 0) out.front() = lo;
    if (n > 1) out.back() = hi;
    return out;
}

std::string printable_text(std::string_view text) {
    // A message is one line on a terminal: control bytes and broken UTF-8
    // (binary garbage in a config file) would garble or split it.
    std::string out;
    const auto escape = [&out](unsigned char c) { out.append("\\x").append(number_text::hex(c, 2)); };
    for (std::size_t k = 0; k < text.size();) {
        const auto c = static_cast<unsigned char>(text[k]);
        if (c < 0x80) {
            if (c < 0x20 || c == 0x7f) escape(c);
            else out += static_cast<char>(c);
            ++k;
            continue;
        }
        const std::size_t n = utf8_sequence_length(text.substr(k));
        if (n == 0) {
            escape(c);
            ++k;
        } else {
            out.append(text.substr(k, n));
            k += n;
        }
    }
    return out;
}

std::size_t utf8_sequence_length(std::string_view text) {
    if (text.empty()) return 0;
    const auto b = [&text](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char c = b(0);
    std::size_t n = 0;
    unsigned lo = 0x80, hi = 0xbf; // the range of the second byte (no overlong forms, no surrogates)
    if (c < 0x80) return 1;
    if (c >= 0xc2 && c <= 0xdf) n = 2;
    else if (c >= 0xe0 && c <= 0xef) {
        n = 3;
        if (c == 0xe0) lo = 0xa0;
        if (c == 0xed) hi = 0x9f;
    } else if (c >= 0xf0 && c <= 0xf4) {
        n = 4;
        if (c == 0xf0) lo = 0x90;
        if (c == 0xf4) hi = 0x8f;
    } else {
        return 0;
    }
    if (text.size() < n || b(1) < lo || b(1) > hi) return 0;
    for (std::size_t k = 2; k < n; ++k)
        if (b(k) < 0x80 || b(k) > 0xbf) return 0;
    return n;
}

// ---- formatting --------------------------------------------------------------

std::string format_setting(double x) {
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    if (std::isnan(x)) return "";
    // The shortest text that reads back exactly: the fewest significant
    // digits, written in fixed or scientific form, whichever is shorter
    // (1e-4 rather than 0.0001, 10 rather than 1e1).
    const auto reads_back = [x](const std::string& text) { return number_text::read_double(text) == x; };
    for (int digits = 1; digits <= 17; ++digits) {
        if (!reads_back(number_text::general(x, digits))) continue;
        std::string best = tidy_exponent(number_text::scientific(x, digits - 1));
        if (std::fabs(x) < 1e16) { // the fixed form, with as many decimals as it needs
            for (int decimals = 0; decimals <= 20; ++decimals) {
                const std::string f = number_text::fixed(x, decimals);
                if (reads_back(f)) {
                    if (f.size() <= best.size()) best = f;
                    break;
                }
            }
        }
        return best;
    }
    return detail::format_number(x, 17);
}

std::string format_setting(std::uint64_t x) { return std::to_string(x); }
std::string format_setting(unsigned x) { return std::to_string(x); }
std::string format_setting(int x) { return std::to_string(x); }
std::string format_setting(bool x) { return x ? "true" : "false"; }
std::string format_setting(const OptionalNumber& x) { return std::isnan(x.value) ? "" : format_setting(x.value); }
std::string format_setting(const NumberOrAuto& x) { return x.automatic ? "auto" : format_setting(x.value); }
std::string format_setting(const SeedValue& x) { return std::to_string(x.value); }

std::string format_setting(const NumberList& x) {
    // A list that lo:hi:n makes is written that way: shorter, and it reads
    // back to the same numbers.
    const auto& v = x.values;
    if (v.size() >= 3 && v.front() != v.back() && (x.linear || (v.front() > 0 && v.back() > 0)) &&
        spaced_values(v.front(), v.back(), v.size(), x.linear) == v)
        return format_setting(v.front()) + ":" + format_setting(v.back()) + ":" + std::to_string(v.size());
    std::string s;
    for (std::size_t k = 0; k < x.values.size(); ++k) {
        if (k) s += ',';
        s += format_setting(x.values[k]);
    }
    return s;
}

std::string format_setting(const NumberRange& x) {
    if (x.lo == 0 && x.hi == 0) return "";
    return format_setting(x.lo) + "," + format_setting(x.hi);
}

// ---- config lines ----------------------------------------------------------------

namespace {

/// `text` as a TOML basic string: quoted, with '"', '\\' and control
/// characters escaped (a Windows path or a quote in a drift expression
/// otherwise made --print-config write a file --config refused).
std::string toml_string(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (u < 0x20 || u == 0x7f) {
            static const char digits[] = "0123456789ABCDEF";
            out += "\\u00";
            out += digits[u >> 4];
            out += digits[u & 15];
        } else {
            out += c;
        }
    }
    return out + "\"";
}

} // namespace

std::string config_line(const SettingEntry& s, bool help) {
    const std::string& v = s.text;
    std::string line = s.info.name + std::string(" = ");
    if (v.empty() && s.kind != SettingKind::Text) {
        line = "# " + line; // unset: its default depends on other settings
    } else if (s.kind == SettingKind::Text) {
        line += toml_string(v);
    } else if (s.kind == SettingKind::List && v.find(':') != std::string::npos) {
        line += "\"" + v + "\""; // lo:hi:n
    } else if (s.kind == SettingKind::List) {
        line += "[";
        for (char c : v) line += c == ',' ? std::string(", ") : std::string(1, c);
        line += "]";
    } else if (v == "auto") {
        line += "\"auto\""; // a NumberOrAuto left to the library
    } else if (v.size() >= 19 && v.find_first_not_of("0123456789") == std::string::npos &&
               (v.size() > 19 || v > "9223372036854775807")) {
        line += toml_string(v); // a seed above TOML's 64-bit signed integers
    } else {
        line += v;
    }
    if (!help) return line;
    if (line.size() < 32) line.resize(32, ' ');
    line += "  # ";
    if (*s.info.unit) line.append("[").append(s.info.unit).append("] "); // not "[" + string: GCC 12's -Wrestrict
    return line + s.info.help;
}

// ---- parsing -------------------------------------------------------------------

void parse_setting(const SettingInfo& info, const std::string& text, double& out) {
    // Decimal only, whatever the locale: overflow is refused; underflow to a
    // subnormal or zero (5e-324, 1e-400) is the nearest double, as for any
    // decimal (settings that cannot take one say so in their validate()).
    const std::optional<double> x = number_text::read_double(text);
    if (!x) fail(info, "must be a number, got " + quoted(text));
    if (std::isnan(*x)) fail(info, "must be a number, got NaN");
    out = *x;
}

void parse_setting(const SettingInfo& info, const std::string& text, std::uint64_t& out) {
    // Plain digits are read exactly (seeds use all 64 bits); other forms (1e6)
    // through double, only where every integer is exact (below 2^53).
    if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos) {
        const std::optional<std::uint64_t> n = number_text::read_unsigned(text);
        if (!n) fail(info, "must be a non-negative integer below 2^64, got " + quoted(text));
        out = *n;
        return;
    }
    double x = 0;
    parse_setting(info, text, x); // accepts 1e6
    if (!(x >= 0) || x != std::floor(x) || x > 9007199254740992.0)
        fail(info, "must be a non-negative integer (digits, or a form like 1e6 up to 2^53), got " + quoted(text));
    out = static_cast<std::uint64_t>(x);
}

namespace {
template <class Int>
void parse_bounded(const SettingInfo& info, const std::string& text, Int& out) {
    std::uint64_t n = 0;
    parse_setting(info, text, n);
    const auto most = static_cast<std::uint64_t>(std::numeric_limits<Int>::max());
    if (n > most) fail(info, "must be at most " + std::to_string(most) + ", got " + quoted(text));
    out = static_cast<Int>(n);
}
} // namespace

void parse_setting(const SettingInfo& info, const std::string& text, unsigned& out) { parse_bounded(info, text, out); }
void parse_setting(const SettingInfo& info, const std::string& text, int& out) { parse_bounded(info, text, out); }

void parse_setting(const SettingInfo& info, const std::string& text, bool& out) {
    for (const char* t : {"true", "True", "1", "yes", "on"})
        if (text == t) {
            out = true;
            return;
        }
    for (const char* f : {"false", "False", "0", "no", "off"})
        if (text == f) {
            out = false;
            return;
        }
    fail(info, "must be true or false (also 1/0, yes/no, on/off), got " + quoted(text));
}

void parse_setting(const SettingInfo& info, const std::string& text, const OptionalNumber& out) {
    if (text.empty()) {
        out.value = std::numeric_limits<double>::quiet_NaN();
        return;
    }
    parse_setting(info, text, out.value);
}

void parse_setting(const SettingInfo& info, const std::string& text, const NumberOrAuto& out) {
    if (text == "auto") {
        out.automatic = true;
        return;
    }
    double x = 0;
    try {
        parse_setting(info, text, x);
    } catch (const InvalidParameter&) {
        fail(info, "must be a number or auto, got " + quoted(text));
    }
    out.value = x;
    out.automatic = false;
}

void parse_setting(const SettingInfo& info, const std::string& text, const SeedValue& out) {
    // Decimal digits only: no sign, no spaces, no octal/hex surprises ("010" is ten).
    const std::optional<std::uint64_t> x = number_text::read_unsigned(text);
    if (!x) fail(info, "must be an integer in [0, 2^64), got " + quoted(text));
    out.value = *x;
}

void parse_setting(const SettingInfo& info, const std::string& text, const NumberList& out) {
    const std::string name = info.name;
    std::vector<double> values;
    if (text.empty() && out.may_be_empty) {
        out.values.clear();
        return;
    }
    if (text.empty()) throw InvalidParameter(name, name + " must list at least one number");
    const auto colon = text.find(':');
    if (colon != std::string::npos) {
        const auto colon2 = text.find(':', colon + 1);
        const char* form = out.linear ? "lo:hi:n (n evenly spaced values)" : "lo:hi:n (n log-spaced values)";
        if (colon2 == std::string::npos || text.find(':', colon2 + 1) != std::string::npos)
            throw InvalidParameter(name, name + ": expected " + form + ", got " + quoted(text));
        double lo = 0, hi = 0;
        std::uint64_t n = 0;
        parse_setting(info, text.substr(0, colon), lo);
        parse_setting(info, text.substr(colon + 1, colon2 - colon - 1), hi);
        parse_setting(info, text.substr(colon2 + 1), n);
        const bool ok = std::isfinite(lo) && std::isfinite(hi) && (out.linear || (lo > 0 && hi > 0));
        if (!ok || n < 1 || n > 1000000)
            throw InvalidParameter(name, name + ": " + form + " needs finite lo, hi" + (out.linear ? "" : " > 0") +
                                             " and 1 <= n <= 1000000, got " + quoted(text));
        out.values = spaced_values(lo, hi, n, out.linear);
        return;
    }
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        double x = 0;
        parse_setting(info, item, x);
        values.push_back(x);
    }
    if (text.back() == ',') throw InvalidParameter(name, name + ": trailing comma in " + quoted(text));
    out.values = std::move(values);
}

void parse_setting(const SettingInfo& info, const std::string& text, const NumberRange& out) {
    if (text.empty()) {
        out.lo = out.hi = 0.0;
        return;
    }
    std::vector<double> v;
    parse_setting(info, text, NumberList{v, true});
    const std::string name = info.name;
    if (v.size() != 2) throw InvalidParameter(name, name + " must be 'lo,hi' in m/s, got " + quoted(text));
    if (!(v[0] < v[1])) throw InvalidParameter(name, name + " needs lo < hi, got " + quoted(text));
    out.lo = v[0];
    out.hi = v[1];
}

std::string format_setting(const TextValue& x) { return x.value; }

void parse_setting(const SettingInfo& info, const std::string& text, const TextValue& out) {
    // A text is checked where it is used (an expression by the parser, a path
    // when it is opened); here only that it is one readable line.
    for (unsigned char ch : text)
        if (ch < 0x20 || ch == 0x7f)
            throw InvalidParameter(info.name, std::string(info.name) + " must be one line of text, got " +
                                                  quoted(text));
    out.value = text;
}

// ---- forms for --help -------------------------------------------------------------

const char* setting_form(const double&) { return "NUM"; }
const char* setting_form(const std::uint64_t&) { return "INT"; }
const char* setting_form(const unsigned&) { return "INT"; }
const char* setting_form(const int&) { return "INT"; }
const char* setting_form(const bool&) { return ""; }
const char* setting_form(const OptionalNumber&) { return "NUM"; }
const char* setting_form(const NumberOrAuto&) { return "NUM|auto"; }
const char* setting_form(const SeedValue&) { return "INT"; }
const char* setting_form(const NumberList&) { return "LIST"; }
const char* setting_form(const NumberRange&) { return "LO,HI"; }
const char* setting_form(const TextValue&) { return "TEXT"; }

} // namespace stickslip
