// The progress line of long runs, on stderr.
#pragma once

#include <functional>
#include <string>

#include "stickslip/runner.hpp"

namespace stickslip::cli {

/// Progress line on stderr, only when it is a terminal and not --quiet:
/// samples done of total, rate, time left; with level > 0 (long excursions)
/// also the current D and the relative half-width of its interval.
std::function<bool(const Progress&)> progress_line(bool quiet, const std::string& what, double level = 0.0);

} // namespace stickslip::cli
