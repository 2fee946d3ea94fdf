// SPDX-License-Identifier: BSD-3-Clause
// Internal: the one number formatter of the library's messages and reports.
#pragma once

#include <string>

namespace stickslip::detail {

/// x with `precision` significant digits, as printf's %g writes it in the C
/// locale ("0.0001", "2.5e+08", "inf", "nan"), whatever the process's locale:
/// number_text::general under the name the reports have always used.
std::string format_number(double x, int precision = 6);

} // namespace stickslip::detail
