// SPDX-License-Identifier: BSD-3-Clause
// stickslip/number_text.hpp -- numbers to text and back, whatever the locale.
//
// printf, strtod and iostreams follow the process's locale: under a
// comma-decimal LC_NUMERIC (de_DE, fr_FR, ...), which a host program such as
// Python may set, strtod stops at the '.' of "0.9" and snprintf writes "0,9"
// into a CSV file. Every number the library, the command and the Python module
// read or write goes through these functions instead, which are built on
// std::from_chars and std::to_chars and so ignore the locale. The printf-style
// writers give exactly the text printf gives in the C locale (both round
// correctly), so replacing printf by them changed no printed number.
#pragma once

/// \file
/// Locale-independent reading and writing of numbers (std::from_chars and
/// std::to_chars), with printf's formats reproduced exactly.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

/// Locale-independent reading and writing of numbers (number_text.hpp).
namespace stickslip::number_text {

/// @name Reading
/// @{

/// A decimal number, the whole text and nothing else: an optional sign, digits
/// with at most one '.', an optional exponent (e or E, optionally signed); or
/// inf, infinity or nan in any case, optionally signed (NaN is returned: the
/// caller decides whether it is a value). No spaces, no hexadecimal ("0x10"),
/// no decimal comma. A value too large for a double is refused (nullopt); one
/// too small becomes the nearest double (a subnormal, or zero with its sign),
/// as strtod gives it.
std::optional<double> read_double(std::string_view text);

/// Decimal digits only (no sign, no spaces), below 2^64.
std::optional<std::uint64_t> read_unsigned(std::string_view text);
/// @}

/// @name Writing (printf's formats in the C locale)
/// @{

/// x as printf's "%.*g" writes it with this precision ("0.0001", "2.5e+08",
/// "inf", "-nan"); a negative precision is 6, as in printf.
std::string general(double x, int precision = 6);
/// The same for a long double ("%.*Lg").
std::string general(long double x, int precision = 6);
/// x as printf's "%.*e" writes it ("2.500e+08").
std::string scientific(double x, int precision);
/// x as printf's "%.*f" writes it ("0.125", "12").
std::string fixed(double x, int decimals);
/// x in hexadecimal, lowercase, zero-padded to at least `digits` digits
/// (printf's "%0*llx").
std::string hex(std::uint64_t x, int digits = 1);
/// `text` padded with spaces to |width| characters, as printf's "%*s": on the
/// left for width > 0 (right-justified), on the right for width < 0; never cut.
std::string pad(std::string_view text, int width);
/// @}

} // namespace stickslip::number_text
