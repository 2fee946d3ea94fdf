// SPDX-License-Identifier: BSD-3-Clause
#include "core/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace stickslip::detail {

double usable_memory_bytes() {
    double usable = HUGE_VAL;
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
        double size = 0; // the address space already taken (/proc/self/statm: pages)
        std::ifstream statm("/proc/self/statm");
        double pages = 0;
        if (statm >> pages) size = pages * static_cast<double>(::sysconf(_SC_PAGESIZE));
        usable = std::min(usable, std::max(0.0, static_cast<double>(limit.rlim_cur) - size));
    }
    std::ifstream meminfo("/proc/meminfo");
    for (std::string line; std::getline(meminfo, line);) {
        if (line.rfind("MemAvailable:", 0) != 0) continue;
        std::istringstream fields(line.substr(13));
        double kib = 0;
        if (fields >> kib) usable = std::min(usable, kib * 1024.0);
        break;
    }
    return usable;
}

} // namespace stickslip::detail
