// SPDX-License-Identifier: BSD-3-Clause
#include "interrupt.hpp"

#include <csignal>
#include <pthread.h>
#include <cstring>
#include <cstdint>
#include <ctime>
#include <iterator>
#include <unistd.h>

#include "distributed.hpp"
#include "output.hpp"

namespace stickslip::cli {

namespace {

static_assert(std::atomic<bool>::is_always_lock_free, "the handler sets an atomic<bool>");
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;
volatile std::sig_atomic_t g_announce = 0; ///< this process prints the one line
// Whether a computation that polls the stop flag is running (GracefulStop).
// Outside one nothing would ever read the flag: parsing, reading a config
// from /dev/zero, `analytic`, or writing to a FIFO nobody reads ignored the
// first SIGINT and SIGTERM and, within the grace below, the second too.
volatile std::sig_atomic_t g_graceful = 0;
// When the first signal came (CLOCK_MONOTONIC, ns; written by the handler
// only, which blocks both signals while it runs).
volatile std::int64_t g_first_ns = 0;

/// A second signal this soon after the first is the same request, not an
/// abort: GNU timeout, `kill -- -PGID` and batch systems deliver one signal to
/// the process and again to its group within microseconds, and counting that
/// as "abort" lost the whole result in 3 of 8 `timeout -s INT` runs.
constexpr std::int64_t kGraceNs = 1'000'000'000;

std::int64_t now_ns() {
    struct timespec ts {};
    ::clock_gettime(CLOCK_MONOTONIC, &ts); // async-signal-safe (POSIX)
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

/// Seconds the blocks in flight get to finish after the first signal; then
/// they are dropped (RunControl::cancel with RunControl::stop set: the result
/// is of the blocks finished before), so that a run whose blocks take minutes
/// (a PDMP at tau 1e-3, a tiny --sample-dt) still stops at once.
constexpr unsigned kFinishSeconds = 5;
std::atomic<bool> g_drop{false};

extern "C" void on_alarm(int) { g_drop = true; }

// SIGALRM is ours only between a first stop signal and the end of the run:
// before that it keeps its default (a SIGALRM ends the process and the
// output's clean-up removes the temporary, as for any terminating signal).
struct sigaction g_previous_alarm;
volatile std::sig_atomic_t g_alarm_installed = 0;

/// Starts the deadline for the blocks in flight. Async-signal-safe
/// (sigaction and alarm are, POSIX).
void start_finish_deadline() {
    struct sigaction alarm_action {};
    alarm_action.sa_handler = on_alarm;
    sigemptyset(&alarm_action.sa_mask);
    alarm_action.sa_flags = SA_RESTART;
    if (::sigaction(SIGALRM, &alarm_action, &g_previous_alarm) == 0) g_alarm_installed = 1;
    ::alarm(kFinishSeconds);
}

void end_finish_deadline() {
    ::alarm(0);
    if (g_alarm_installed) {
        ::sigaction(SIGALRM, &g_previous_alarm, nullptr);
        g_alarm_installed = 0;
    }
}

// SIGHUP too: a closed terminal or an ssh session dropped is a request to
// stop, and it lost the whole result (issue 50); nohup's ignored SIGHUP stays
// ignored (only signals at their default action are taken).
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[std::size(kSignals)];
bool g_installed[std::size(kSignals)] = {};

/// Ends the process by `sig`, leaving no partial output: the temporaries are
/// removed, the default action restored and the signal raised again (it is
/// delivered when the handler returns). Async-signal-safe.
void abort_by(int sig) {
    remove_output_temporary();
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    ::sigaction(sig, &dfl, nullptr);
    ::raise(sig);
}

void say(const char* text) {
    if (g_announce && ::write(STDERR_FILENO, text, std::strlen(text)) < 0) return;
}

extern "C" void on_stop_signal(int sig) {
    // The first one again, through the group, even if the run it stopped
    // has since finished and is writing its result.
    if (g_stop && now_ns() - g_first_ns < kGraceNs) return;
    if (!g_graceful) { // nothing polls the flag: end now, as by default
        g_stop = true;
        g_signal = sig;
        abort_by(sig);
        return;
    }
    if (!g_stop.exchange(true)) { // the first: stop gracefully
        g_signal = sig;
        g_first_ns = now_ns();
        say("\nstickslip: stopping: finishing the blocks in flight (at most 5 s, then they are dropped), then "
            "writing the result so far (another signal, a second or more later, aborts)\n");
        start_finish_deadline();
        return;
    }
    abort_by(sig); // a second, later one
}

} // namespace

StopOnSignals::StopOnSignals() {
    g_stop = false;
    g_signal = 0;
    g_first_ns = 0;
    g_announce = is_root() ? 1 : 0;
    g_drop = false;
    for (std::size_t i = 0; i < std::size(kSignals); ++i) {
        struct sigaction current {};
        if (::sigaction(kSignals[i], nullptr, &current) != 0) continue;
        if ((current.sa_flags & SA_SIGINFO) || current.sa_handler != SIG_DFL) continue;
        struct sigaction sa {};
        sa.sa_handler = on_stop_signal;
        sigemptyset(&sa.sa_mask);
        for (int s : kSignals) sigaddset(&sa.sa_mask, s);
        sa.sa_flags = SA_RESTART;
        if (::sigaction(kSignals[i], &sa, &g_previous[i]) == 0) g_installed[i] = true;
    }
}

StopOnSignals::~StopOnSignals() {
    // Stopped by a signal: the handlers stay, so that the same request
    // delivered again (to the process group, a few ms later) still finds
    // them when the result is already written and the process is ending; a
    // restored default action would kill it by that repeat, after its
    // result, with the wrong status (seen in CI: two SIGINTs 5 ms apart).
    if (g_stop) return;
    for (std::size_t i = 0; i < std::size(kSignals); ++i)
        if (g_installed[i]) {
            ::sigaction(kSignals[i], &g_previous[i], nullptr);
            g_installed[i] = false;
        }
}

GracefulStop::GracefulStop() {
    g_graceful = 1;
    // A launcher may start the process with these signals blocked (an
    // inherited mask): a stop request would then wait for ever. Unblocked
    // here, one sent before the run began is honoured as it begins (the run
    // stops before its first block and says so), and the worker threads,
    // started later, inherit the mask.
    sigset_t set;
    sigemptyset(&set);
    for (int s : kSignals) sigaddset(&set, s);
    ::pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}
GracefulStop::~GracefulStop() {
    g_graceful = 0;
    end_finish_deadline();
}

const std::atomic<bool>* StopOnSignals::flag() { return &g_stop; }
int StopOnSignals::signal() { return g_signal; }
const std::atomic<bool>* StopOnSignals::drop_flag() { return &g_drop; }

} // namespace stickslip::cli
