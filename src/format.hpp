// SPDX-License-Identifier: BSD-3-Clause
// Internal: the one number formatter of the library's messages and reports.
#pragma once

#include <string>

namespace stickslip::detail {

/// x with `precision` significant digits, as printf's %g writes it ("0.0001",
/// "2.5e+08", "inf", "nan").
std::string format_number(double x, int precision = 6);

} // namespace stickslip::detail
