// SPDX-License-Identifier: BSD-3-Clause
// The progress line of long runs, on stderr.
#pragma once

#include <functional>
#include <string>

#include "stickslip/run_control.hpp"

namespace stickslip::cli {

/// Progress line on stderr, only when it is a terminal and not --quiet:
/// samples done of total, rate, time left; with level > 0 (long excursions)
/// also the current D and its interval, relative to D.
std::function<bool(const Progress&)> progress_line(bool quiet, const std::string& what, double level = 0.0);

/// The notes a run has before it starts (RunControl::notice: a coarse step, a
/// long run), as "note:" lines on stderr at once, under the same conditions
/// as the progress line; they are in the result's warnings either way.
std::function<void(const std::string&)> notice_line(bool quiet);

/// The note of a run predicted to last an hour or more (RunControl::long_run),
/// as one "stickslip: note:" line on stderr at once where notice_line shows
/// nothing (no terminal: a script, a batch job's log); nothing with --quiet.
std::function<void(const std::string&)> long_run_line(bool quiet);

} // namespace stickslip::cli
