// SPDX-License-Identifier: BSD-3-Clause
// Ctrl-C keeps what was computed. While a run is in progress, the first
// SIGINT, SIGTERM or SIGHUP asks it to stop gracefully (RunControl::stop): no
// new block is started, the blocks in flight finish, and the command writes
// the result of the prefix of blocks completed, marked "interrupted", and the
// checkpoint if one was asked for; it then exits 128 + the signal (130 for
// SIGINT, 143 for SIGTERM, 129 for SIGHUP). Blocks still in flight 5 s after the signal are
// dropped (the result is of those finished before). A second signal at least a second after the
// first aborts at once (one within the second is the same request delivered
// again, to the process and to its group, as GNU timeout does): the temporary
// output file is removed and the process dies by that signal, leaving no
// partial file.
#pragma once

#include <atomic>

namespace stickslip::cli {

/// Installs the handlers for its lifetime (only for signals at their default
/// action: an ignored SIGINT, as in a background job, stays ignored), and for
/// the rest of the process once a stop signal came (a repeat of it must not
/// kill the process after its result is written). Install
/// before CleanupOnSignals (output.hpp), so that its handlers leave these three
/// signals to it.
class StopOnSignals {
public:
    StopOnSignals();
    ~StopOnSignals();
    StopOnSignals(const StopOnSignals&) = delete;
    StopOnSignals& operator=(const StopOnSignals&) = delete;

    /// Set by the first signal; give it to RunControl::stop.
    static const std::atomic<bool>* flag();
    /// Set 5 s after the first signal if the run has not stopped by then;
    /// give it to RunControl::cancel: with the stop flag set, the blocks in
    /// flight are dropped and the result is of those finished before.
    static const std::atomic<bool>* drop_flag();
    /// The first signal received (0: none).
    static int signal();
};

/// While one lives, a computation polls StopOnSignals::flag(): the first
/// signal stops it gracefully. Outside it (parsing, validation, commands
/// that do not poll, writing the result) a signal ends the process at once,
/// by that signal, leaving no partial file.
class GracefulStop {
public:
    GracefulStop();
    ~GracefulStop();
    GracefulStop(const GracefulStop&) = delete;
    GracefulStop& operator=(const GracefulStop&) = delete;
};

/// The exit code of a run stopped by `signal`: 128 + signal.
inline int exit_code_of_signal(int signal) { return 128 + signal; }

} // namespace stickslip::cli
