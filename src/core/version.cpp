// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/version.hpp"

#include <string>

#include "stickslip/config.hpp"
#include "stickslip_revision.h" // generated at build time by cmake/source_revision.cmake

namespace stickslip {

const char* version() { return STICKSLIP_VERSION_STRING; }
const char* source_revision() { return STICKSLIP_SOURCE_REVISION; }

const char* version_line() {
    static const std::string line = std::string("stickslip ") + version() + " (git " +
                                    (*source_revision() ? source_revision() : "unknown") + ")";
    return line.c_str();
}

} // namespace stickslip
