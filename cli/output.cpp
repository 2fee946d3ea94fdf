// SPDX-License-Identifier: BSD-3-Clause
#include "output.hpp"

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <system_error>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "distributed.hpp"
#include "setting_flags.hpp"
#include "stickslip/detail/atomic_file.hpp"
#include "stickslip/setting.hpp"

namespace stickslip::cli {

void add_output_flags(CLI::App* app, OutputFlags& o) {
    app->add_option("--format", o.format, "table (human), json (one object) or csv (header + rows; notes go to stderr)")
        ->type_name("table|json|csv")
        ->capture_default_str();
    app->add_option("--output", o.output,
                    "write the result to FILE instead of stdout; a regular file atomically (a temporary in its folder, "
                    "renamed into place: nothing left behind on failure or kill, mode and owner kept, a symlink's "
                    "target replaced), a device, FIFO or /dev/stdout written directly")
        ->type_name("FILE");
    o.quiet_flag = app->add_flag("--quiet")->description("no progress line on stderr");
}

void read_output_flags(OutputFlags& o) { o.quiet = o.quiet_flag && flag_value(*o.quiet_flag, "quiet"); }

namespace {

std::string cannot(const std::string& path, int err) { return "cannot write '" + path + "': " + std::strerror(err); }

// --- the signals that would leave a named temporary behind -----------------------------------

/// The signals that end a process by default and come from outside it (a
/// user, a shell, a batch system's limits, a closed pipe). SIGKILL cannot be
/// caught (an unnamed temporary needs no handler), and after a fault
/// (SIGSEGV, SIGBUS...) the process state cannot be trusted to clean up.
constexpr int kSignals[] = {SIGINT,  SIGTERM, SIGHUP,  SIGQUIT, SIGUSR1,   SIGUSR2,
                            SIGPIPE, SIGALRM, SIGXCPU, SIGXFSZ, SIGVTALRM, SIGPROF};
struct sigaction g_previous[std::size(kSignals)];
bool g_installed[std::size(kSignals)] = {};

extern "C" void remove_temporaries_and_reraise(int sig) {
    detail::remove_temporaries();
    // SA_RESETHAND has put back the default action, and the signal is blocked
    // while the handler runs: raised again, it kills the process by this very
    // signal as soon as the handler returns (the exit status a parent sees is
    // unchanged).
    ::raise(sig);
}

/// A descriptor for writing a device, FIFO or socket file in place, or -1
/// with errno set. A socket cannot be open()ed (ENXIO): it is connected to,
/// as a stream (a log collector's) or else as datagrams (syslog-style).
int open_in_place(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISSOCK(st.st_mode))
        return ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    sockaddr_un addr {};
    addr.sun_family = AF_UNIX;
    if (path.size() >= sizeof addr.sun_path) {
        errno = ENAMETOOLONG;
        return -1;
    }
    std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
    for (int type : {SOCK_STREAM, SOCK_SEQPACKET, SOCK_DGRAM}) {
        const int fd = ::socket(AF_UNIX, type | SOCK_CLOEXEC, 0);
        if (fd < 0) return -1;
        if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0) return fd;
        const int err = errno;
        ::close(fd);
        errno = err;
        if (err != EPROTOTYPE) return -1;
    }
    return -1;
}

bool writable(const std::string& path) { return ::faccessat(AT_FDCWD, path.c_str(), W_OK, AT_EACCESS) == 0; }

} // namespace

void remove_output_temporary() noexcept { detail::remove_temporaries(); }

CleanupOnSignals::CleanupOnSignals() {
    for (std::size_t i = 0; i < std::size(kSignals); ++i) {
        struct sigaction current {};
        if (g_installed[i] || ::sigaction(kSignals[i], nullptr, &current) != 0) continue;
        // Only signals left at their default: one ignored (nohup's SIGHUP, a
        // parent's SIGPIPE) must stay harmless, and one someone else handles
        // (StopOnSignals' SIGINT and SIGTERM) is theirs to act on.
        if ((current.sa_flags & SA_SIGINFO) || current.sa_handler != SIG_DFL) continue;
        struct sigaction sa {};
        sa.sa_handler = remove_temporaries_and_reraise;
        sigemptyset(&sa.sa_mask);
        for (int s : kSignals) sigaddset(&sa.sa_mask, s); // a second signal must not cut the clean-up short
        sa.sa_flags = SA_RESETHAND;
        if (::sigaction(kSignals[i], &sa, &g_previous[i]) == 0) g_installed[i] = true;
    }
}

CleanupOnSignals::~CleanupOnSignals() {
    for (std::size_t i = 0; i < std::size(kSignals); ++i)
        if (g_installed[i]) {
            ::sigaction(kSignals[i], &g_previous[i], nullptr);
            g_installed[i] = false;
        }
}

// --- Output ---------------------------------------------------------------------------------------

Output::Output(const OutputFlags& o) : format_(o.format), path_(o.output), quiet_(o.quiet) {
    if (format_ != "table" && format_ != "json" && format_ != "csv")
        throw InvalidParameter("format", "format must be 'table', 'json' or 'csv', got '" + format_ + "'");
    if (path_.empty()) return;
    // Only the first process writes; every process learns whether it can, so
    // that a bad path stops them all before any work.
    std::string error;
    if (is_root()) {
        using Kind = detail::FileTarget::Kind;
        const detail::FileTarget t = detail::resolve_target(path_);
        if (t.error) {
            error = cannot(path_, t.error);
        } else if (t.kind == Kind::descriptor) {
            const int flags = ::fcntl(t.descriptor, F_GETFL);
            if (flags < 0 || (flags & O_ACCMODE) == O_RDONLY) error = cannot(path_, EBADF);
            sink_ = Sink::descriptor;
            descriptor_ = t.descriptor;
        } else if (t.kind == Kind::directory) {
            error = "'" + path_ + "' is a directory";
        } else if (t.exists() && t.kind != Kind::regular) {
            // Opened only at commit: a FIFO's open waits for its reader, which
            // may well start after us.
            if (!writable(t.path)) error = cannot(path_, errno);
            sink_ = Sink::direct;
            target_ = t.path;
        } else if (t.exists() && !writable(t.path)) {
            // Replacing a file one may not write would bypass its permissions.
            error = cannot(path_, errno);
        } else {
            // The temporary goes beside the target, not the link, so that the
            // rename stays within one directory and replaces the target.
            sink_ = Sink::atomic;
            target_ = t.path;
            try {
                file_ = std::make_unique<detail::AtomicFile>(target_);
            } catch (const std::system_error& e) {
                error = cannot(path_, e.code().value());
            }
        }
    }
    if (!all_ok(error.empty())) {
        discard(); // the path of another process failed: ours must not stay behind
        throw InvalidParameter("output", error.empty() ? "cannot write '" + path_ + "'" : error);
    }
}

void Output::discard() noexcept { file_.reset(); }

Output::~Output() { discard(); }

void Output::write_all(int fd, const std::string& text) const {
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t w = ::write(fd, text.data() + done, text.size() - done);
        if (w < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error(cannot(path_, errno));
        }
        done += static_cast<std::size_t>(w);
    }
}

void Output::commit(const std::string& text, const std::vector<std::string>& warnings) {
    if (!is_root()) return;
    for (const auto& w : warnings) std::fprintf(stderr, "stickslip: note: %s\n", w.c_str());
    switch (sink_) {
    case Sink::standard_output:
        std::cout << text << std::flush;
        if (!std::cout) throw std::runtime_error("cannot write to stdout");
        return;
    case Sink::descriptor:
        // Whatever the streams still hold goes first, in order.
        std::cout.flush();
        std::fflush(nullptr);
        write_all(descriptor_, text);
        return;
    case Sink::direct: {
        const int fd = open_in_place(target_);
        if (fd < 0) throw std::runtime_error(cannot(path_, errno));
        try {
            write_all(fd, text);
        } catch (...) {
            ::close(fd);
            throw;
        }
        if (::close(fd) != 0 && errno != EINTR) throw std::runtime_error(cannot(path_, errno));
        return;
    }
    case Sink::atomic:
        commit_atomic(text);
        if (!quiet_ && isatty(STDERR_FILENO)) std::fprintf(stderr, "wrote %s\n", path_.c_str());
        return;
    }
}

void Output::commit_atomic(const std::string& text) {
    try {
        file_->write(text);
        file_->commit();
    } catch (const std::system_error& e) {
        file_.reset();
        throw std::runtime_error(cannot(path_, e.code().value()));
    }
    file_.reset();
}

void refuse_shared_paths(const OutputFlags& output, const CheckpointOptions& checkpoint) {
    if (checkpoint.path.empty() && checkpoint.resume.empty()) return;
    const detail::FileTarget out = detail::resolve_target(output.output);
    if (output.output.empty() || out.error) return; // Output says what is wrong with it
    // The result would replace the checkpoint when the run ends: the saved
    // state, which may be all that a long run has, would be gone.
    if (!checkpoint.path.empty()) {
        const detail::FileTarget c = detail::resolve_target(checkpoint.path);
        if (!c.error && detail::same_file(out, c))
            throw InvalidParameter("output", "'" + output.output + "' is also the --checkpoint file '" +
                                                 checkpoint.path + "'; give them different paths");
    }
    if (!checkpoint.resume.empty()) {
        const detail::FileTarget r = detail::resolve_target(checkpoint.resume);
        if (!r.error && detail::same_file(out, r))
            throw InvalidParameter("output", "'" + output.output + "' is also the --resume file '" +
                                                 checkpoint.resume + "'; give them different paths");
    }
}

void refuse_output_over_inputs(const OutputFlags& output,
                               const std::vector<std::pair<std::string, std::string>>& inputs) {
    if (output.output.empty()) return;
    const detail::FileTarget out = detail::resolve_target(output.output);
    if (out.error) return; // Output says what is wrong with it
    for (const auto& [flag, path] : inputs) {
        if (path.empty()) continue;
        const detail::FileTarget in = detail::resolve_target(path);
        if (!in.error && detail::same_file(out, in))
            throw InvalidParameter("output", "'" + output.output + "' is also the --" + flag + " file '" + path +
                                                 "': the result would replace it; give another --output");
    }
}

} // namespace stickslip::cli
