// SPDX-License-Identifier: BSD-3-Clause
#include "progress.hpp"

#include <cstdio>
#include <unistd.h>

#include "distributed.hpp"
#include "stickslip/estimators.hpp"
#include "stickslip/number_text.hpp"

namespace stickslip::cli {

std::function<bool(const Progress&)> progress_line(bool quiet, const std::string& what, double level) {
    if (quiet || !isatty(STDERR_FILENO) || distributed()) return {}; // no interleaved lines from many processes
    return [what, level](const Progress& pr) {
        using number_text::fixed;
        using number_text::general;
        const double rate = pr.seconds > 0 ? static_cast<double>(pr.done) / pr.seconds : 0.0;
        const double left = rate > 0 ? static_cast<double>(pr.total - pr.done) / rate : 0.0;
        std::string estimate;
        if (level > 0 && pr.moments && pr.moments->count() >= 2) {
            const auto e = estimate_long_excursion(*pr.moments, level);
            const double d = e.diffusivity.value;
            // D's interval is asymmetric (never negative): both ends, relative to D.
            estimate = ", D = " + general(d, 4) + " [-" + general(d > 0 ? 100 * (d - e.diffusivity.lo) / d : 0.0, 2) +
                       "%, +" + general(d > 0 ? 100 * (e.diffusivity.hi - d) / d : 0.0, 2) + "%]";
        }
        std::string line = "\r"; // appended: GCC 12 warns (-Wrestrict, a false positive) on "\r" + std::string
        line += std::to_string(pr.done) + "/" + std::to_string(pr.total) + " " + what + estimate + ", " +
                fixed(rate, 0) + "/s, " + fixed(pr.seconds, 1) + " s elapsed, ~" + fixed(left, 0) + " s left   ";
        std::fputs(line.c_str(), stderr);
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
