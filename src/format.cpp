// SPDX-License-Identifier: BSD-3-Clause
#include "format.hpp"

#include <cstdio>

namespace stickslip::detail {

std::string format_number(double x, int precision) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", precision, x);
    return buf;
}

} // namespace stickslip::detail
