// Internal: the one number formatter for messages (errors and warnings).
#pragma once

#include <sstream>
#include <string>

namespace stickslip::detail {

inline std::string format_number(double x, int precision = 6) {
    std::ostringstream os;
    os.precision(precision);
    os << x;
    return os.str();
}

} // namespace stickslip::detail
