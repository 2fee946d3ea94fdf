// SPDX-License-Identifier: BSD-3-Clause
#include "progress.hpp"

#include <cstdio>
#include <unistd.h>

#include "distributed.hpp"
#include "stickslip/estimators.hpp"

namespace stickslip::cli {

std::function<bool(const Progress&)> progress_line(bool quiet, const std::string& what, double level) {
    if (quiet || !isatty(STDERR_FILENO) || distributed()) return {}; // no interleaved lines from many processes
    return [what, level](const Progress& pr) {
        const double rate = pr.seconds > 0 ? static_cast<double>(pr.done) / pr.seconds : 0.0;
        const double left = rate > 0 ? static_cast<double>(pr.total - pr.done) / rate : 0.0;
        std::string estimate;
        if (level > 0 && pr.moments && pr.moments->count() >= 2) {
            const auto e = estimate_long_excursion(*pr.moments, level);
            const double d = e.diffusivity.value;
            char buf[96];
            // D's interval is asymmetric (never negative): both ends, relative to D.
            std::snprintf(buf, sizeof buf, ", D = %.4g [-%.2g%%, +%.2g%%]", d,
                          d > 0 ? 100 * (d - e.diffusivity.lo) / d : 0.0,
                          d > 0 ? 100 * (e.diffusivity.hi - d) / d : 0.0);
            estimate = buf;
        }
        std::fprintf(stderr, "\r%llu/%llu %s%s, %.0f/s, %.1f s elapsed, ~%.0f s left   ",
                     static_cast<unsigned long long>(pr.done), static_cast<unsigned long long>(pr.total), what.c_str(),
                     estimate.c_str(), rate, pr.seconds, left);
        if (pr.done == pr.total) std::fprintf(stderr, "\n");
        std::fflush(stderr);
        return true;
    };
}

std::function<void(const std::string&)> notice_line(bool quiet) {
    if (quiet || !isatty(STDERR_FILENO) || distributed()) return {};
    return [](const std::string& note) { std::fprintf(stderr, "note: %s\n", note.c_str()); };
}

} // namespace stickslip::cli
