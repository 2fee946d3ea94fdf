// SPDX-License-Identifier: BSD-3-Clause
#include "progress.hpp"

#include <cstdint>
#include <cstdio>
#include <unistd.h>

#include "distributed.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/number_text.hpp"

namespace stickslip::cli {

std::function<bool(const Progress&)> progress_line(bool quiet, const std::string& what, double level) {
    if (quiet || !isatty(STDERR_FILENO) || distributed()) return {}; // no interleaved lines from many processes
    // The rate is this process's own: a resumed run starts with samples done
    // in no time, and the first report comes before any block has finished;
    // until one has, the time left is unknown, not "~0 s" (a near-white run
    // of 12 hours said "~0 s left" for its first minutes).
    struct Start {
        bool seen = false;
        std::uint64_t done = 0;
        double seconds = 0.0;
    };
    return [what, level, start = Start{}](const Progress& pr) mutable {
        using number_text::fixed;
        using number_text::general;
        if (!start.seen) start = Start{true, pr.done, pr.seconds};
        const bool moved = pr.done > start.done && pr.seconds > start.seconds;
        const double rate =
            moved ? static_cast<double>(pr.done - start.done) / (pr.seconds - start.seconds) : 0.0;
        const double left = moved ? static_cast<double>(pr.total - pr.done) / rate : 0.0;
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
                (moved ? (rate >= 10 ? fixed(rate, 0) : general(rate, 2)) + "/s, " : std::string()) +
                fixed(pr.seconds, 1) + " s elapsed, ";
        if (moved || pr.done == pr.total) {
            line += '~';
            line += fixed(left, 0) + " s left   ";
        } else {
            line += "estimating...   ";
        }
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

std::function<void(const std::string&)> long_run_line(bool quiet) {
    // On a terminal notice_line shows every note, this one among them; one
    // process of a distributed run speaks for all (the first rank).
    if (quiet || isatty(STDERR_FILENO) || !is_root()) return {};
    return [](const std::string& note) {
        std::fprintf(stderr, "stickslip: note: %s\n", note.c_str());
        std::fflush(stderr);
    };
}

} // namespace stickslip::cli
