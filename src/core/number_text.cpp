// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/number_text.hpp"

#include <charconv>
#include <cstddef>
#include <system_error>

namespace stickslip::number_text {

namespace {

/// Whether a decimal number that std::from_chars found out of range is tiny
/// (underflow) rather than huge: from the power of ten of its leading nonzero
/// digit plus its exponent. std::from_chars leaves the value unset in both
/// cases, and only overflow is an error here.
bool underflows(std::string_view t) {
    std::size_t k = 0;
    if (k < t.size() && (t[k] == '-' || t[k] == '+')) ++k;
    long long integer_digits = 0, digits = 0, first_nonzero = -1;
    bool in_fraction = false;
    for (; k < t.size() && t[k] != 'e' && t[k] != 'E'; ++k) {
        if (t[k] == '.') {
            in_fraction = true;
            continue;
        }
        if (first_nonzero < 0 && t[k] != '0') first_nonzero = digits;
        ++digits;
        if (!in_fraction) ++integer_digits;
    }
    if (first_nonzero < 0) return true; // all zeros: zero, whatever the exponent
    long long exponent = 0;
    if (k < t.size()) { // after 'e': from_chars has checked the digits
        ++k;
        bool negative = false;
        if (k < t.size() && (t[k] == '-' || t[k] == '+')) negative = t[k++] == '-';
        for (; k < t.size(); ++k)
            if (exponent < 1'000'000'000'000) exponent = exponent * 10 + (t[k] - '0');
        if (negative) exponent = -exponent;
    }
    return integer_digits - 1 - first_nonzero + exponent < 0;
}

template <class T, class... Format>
std::string to_text(T x, Format... format) {
    std::string out(64, '\0');
    for (;;) {
        const auto r = std::to_chars(out.data(), out.data() + out.size(), x, format...);
        if (r.ec == std::errc()) {
            out.resize(static_cast<std::size_t>(r.ptr - out.data()));
            return out;
        }
        out.resize(out.size() * 4); // "%.20f" of 1e300 needs 321 characters
    }
}

} // namespace

std::optional<double> read_double(std::string_view text) {
    std::string_view t = text;
    // from_chars takes '-' but not '+', which strtod (and users) take.
    if (!t.empty() && t[0] == '+') {
        t.remove_prefix(1);
        if (!t.empty() && (t[0] == '+' || t[0] == '-')) return std::nullopt;
    }
    if (t.empty()) return std::nullopt;
    double x = 0;
    const char* end = t.data() + t.size();
    const auto r = std::from_chars(t.data(), end, x, std::chars_format::general);
    if (r.ptr != end) return std::nullopt;
    if (r.ec == std::errc::result_out_of_range) {
        if (!underflows(t)) return std::nullopt;
        return t[0] == '-' ? -0.0 : 0.0;
    }
    if (r.ec != std::errc()) return std::nullopt;
    return x;
}

std::optional<std::uint64_t> read_unsigned(std::string_view text) {
    if (text.empty()) return std::nullopt;
    for (const char c : text)
        if (c < '0' || c > '9') return std::nullopt; // from_chars alone would take a leading '-'
    std::uint64_t x = 0;
    const char* end = text.data() + text.size();
    const auto r = std::from_chars(text.data(), end, x, 10);
    if (r.ec != std::errc() || r.ptr != end) return std::nullopt;
    return x;
}

std::string general(double x, int precision) {
    return to_text(x, std::chars_format::general, precision < 0 ? 6 : precision);
}

std::string general(long double x, int precision) {
    return to_text(x, std::chars_format::general, precision < 0 ? 6 : precision);
}

std::string scientific(double x, int precision) {
    return to_text(x, std::chars_format::scientific, precision < 0 ? 6 : precision);
}

std::string fixed(double x, int decimals) { return to_text(x, std::chars_format::fixed, decimals < 0 ? 6 : decimals); }

std::string hex(std::uint64_t x, int digits) {
    std::string s = to_text(x, 16);
    if (static_cast<int>(s.size()) < digits) s.insert(0, static_cast<std::size_t>(digits) - s.size(), '0');
    return s;
}

std::string pad(std::string_view text, int width) {
    std::string s(text);
    const std::size_t w = static_cast<std::size_t>(width < 0 ? -width : width);
    if (s.size() >= w) return s;
    if (width > 0) s.insert(0, w - s.size(), ' ');
    else s.append(w - s.size(), ' ');
    return s;
}

} // namespace stickslip::number_text
