// SPDX-License-Identifier: BSD-3-Clause
#include "core/format.hpp"

#include "stickslip/number_text.hpp"

namespace stickslip::detail {

std::string format_number(double x, int precision) { return number_text::general(x, precision); }

} // namespace stickslip::detail
