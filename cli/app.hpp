// SPDX-License-Identifier: BSD-3-Clause
// The whole `stickslip` command as a function (run.cpp): what main() calls,
// and what the in-process fuzz targets (tests/fuzz/) call with argument
// vectors of their own.
#pragma once

namespace stickslip::cli {

/// Parses `argv`, runs the chosen subcommand, prints or writes its result and
/// maps errors to the exit code it returns: 0 ok, 1 I/O or internal error, 2
/// bad input (one line on stderr, nothing on stdout), 3 an untrustworthy run,
/// 130 or 143 a run stopped by SIGINT or SIGTERM (its result so far written).
/// Expects the process split to be started (start_distribution) when MPI is used.
int run_command(int argc, char** argv);

} // namespace stickslip::cli
