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
#include <optional>
#include <stdexcept>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "distributed.hpp"
#include "setting_flags.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/setting.hpp"

namespace stickslip::cli {

void add_output_flags(CLI::App* app, OutputFlags& o) {
    app->add_option("--format", o.format, "table (human), json (one object) or csv (header + rows; notes go to stderr)")
        ->type_name("table|json|csv")
        ->capture_default_str();
    app->add_option("--output", o.output,
                    "write the result to FILE instead of stdout; a regular file atomically (a temporary beside it, "
                    "renamed into place: nothing left behind on failure, mode and owner kept, a symlink's target "
                    "replaced), a device, FIFO or /dev/stdout written directly")
        ->type_name("FILE");
    o.quiet_flag = app->add_flag("--quiet")->description("no progress line on stderr");
}

void read_output_flags(OutputFlags& o) { o.quiet = o.quiet_flag && flag_value(*o.quiet_flag, "quiet"); }

namespace {

std::string cannot(const std::string& path, int err) { return "cannot write '" + path + "': " + std::strerror(err); }

// --- the temporary file and the signals that would leave it behind ------------------------

/// The temporary output file of this process, removed by the signal handler
/// (a fixed buffer and a flag: only async-signal-safe work in the handler).
char g_temp_path[PATH_MAX] = {0};
volatile std::sig_atomic_t g_temp_armed = 0;

/// The signals that end a process by default and come from outside it (a
/// user, a shell, a batch system's limits, a closed pipe). SIGKILL cannot be
/// caught, and after a fault (SIGSEGV, SIGBUS...) the process state cannot be
/// trusted to clean up.
constexpr int kSignals[] = {SIGINT,  SIGTERM, SIGHUP,  SIGQUIT, SIGUSR1,   SIGUSR2,
                            SIGPIPE, SIGALRM, SIGXCPU, SIGXFSZ, SIGVTALRM, SIGPROF};
struct sigaction g_previous[std::size(kSignals)];
bool g_installed[std::size(kSignals)] = {};

} // namespace

void remove_output_temporary() noexcept {
    if (g_temp_armed) ::unlink(g_temp_path);
}

namespace {

extern "C" void remove_temp_and_reraise(int sig) {
    if (g_temp_armed) ::unlink(g_temp_path);
    // SA_RESETHAND has put back the default action, and the signal is blocked
    // while the handler runs: raised again, it kills the process by this very
    // signal as soon as the handler returns (the exit status a parent sees is
    // unchanged).
    ::raise(sig);
}

void install_handlers() {
    for (std::size_t i = 0; i < std::size(kSignals); ++i) {
        struct sigaction current {};
        if (g_installed[i] || ::sigaction(kSignals[i], nullptr, &current) != 0) continue;
        // Only signals left at their default: one ignored (nohup's SIGHUP, a
        // parent's SIGPIPE) must stay harmless, and one someone else handles
        // is theirs to act on.
        if ((current.sa_flags & SA_SIGINFO) || current.sa_handler != SIG_DFL) continue;
        struct sigaction sa {};
        sa.sa_handler = remove_temp_and_reraise;
        sigemptyset(&sa.sa_mask);
        for (int s : kSignals) sigaddset(&sa.sa_mask, s); // a second signal must not cut the unlink short
        sa.sa_flags = SA_RESETHAND;
        if (::sigaction(kSignals[i], &sa, &g_previous[i]) == 0) g_installed[i] = true;
    }
}

void restore_handlers() {
    for (std::size_t i = 0; i < std::size(kSignals); ++i)
        if (g_installed[i]) {
            ::sigaction(kSignals[i], &g_previous[i], nullptr);
            g_installed[i] = false;
        }
}

// --- what --output names ------------------------------------------------------------------------

/// The descriptor that /dev/stdout, /dev/fd/N, /proc/self/fd/N... stand for,
/// or -1. Written through the descriptor itself rather than reopened, so that
/// `--output /dev/stdout >> log` appends where the shell put us instead of
/// overwriting log from its start.
int descriptor_alias(const std::string& p) {
    if (p == "/dev/stdin") return STDIN_FILENO;
    if (p == "/dev/stdout") return STDOUT_FILENO;
    if (p == "/dev/stderr") return STDERR_FILENO;
    for (const std::string& prefix :
         {std::string("/dev/fd/"), std::string("/proc/self/fd/"), std::string("/proc/thread-self/fd/"),
          "/proc/" + std::to_string(::getpid()) + "/fd/"}) {
        if (p.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string n = p.substr(prefix.size());
        const std::optional<std::uint64_t> fd = number_text::read_unsigned(n);
        if (!fd || *fd > 999'999'999) return -1;
        return static_cast<int>(*fd);
    }
    return -1;
}

struct Resolved {
    int descriptor = -1; ///< >= 0: an alias of this process's descriptor
    std::string path;    ///< the object itself (not a symlink), or where it is to be created
    bool exists = false;
    struct stat st {};
    int error = 0; ///< errno of a path that cannot be resolved
};

/// Follows a chain of symlinks by hand rather than by realpath(), because a
/// link whose target does not exist yet still names where the file goes: the
/// link must stay a link, and the file appear at its target.
Resolved resolve(const std::string& path) {
    Resolved r;
    std::string p = path;
    for (int hops = 0; hops <= 40; ++hops) { // the kernel's own limit (ELOOP)
        if ((r.descriptor = descriptor_alias(p)) >= 0) return r;
        struct stat ls {};
        if (::lstat(p.c_str(), &ls) != 0) {
            if (errno != ENOENT) r.error = errno;
            r.path = p; // missing: created there (if its directory exists, which opening the temporary checks)
            return r;
        }
        if (!S_ISLNK(ls.st_mode)) {
            r.path = p;
            r.exists = true;
            r.st = ls;
            return r;
        }
        char buf[PATH_MAX];
        const ssize_t n = ::readlink(p.c_str(), buf, sizeof buf);
        if (n < 0 || n == static_cast<ssize_t>(sizeof buf)) {
            r.error = n < 0 ? errno : ENAMETOOLONG;
            return r;
        }
        std::string next(buf, static_cast<std::size_t>(n));
        // A relative target is relative to the link's directory, which the
        // kernel resolves from the link's own path just as it would.
        if (next.front() != '/') {
            const auto slash = p.rfind('/');
            if (slash != std::string::npos) next = p.substr(0, slash + 1) + next;
        }
        // A /proc magic link (/proc/PID/fd/N of a pipe or socket: "pipe:[123]")
        // names no path; what it points to is reached only through the link.
        struct stat followed {};
        if (::lstat(next.c_str(), &ls) != 0 && errno == ENOENT && ::stat(p.c_str(), &followed) == 0) {
            r.exists = true;
            r.st = followed;
            r.path = p;
            if (S_ISREG(followed.st_mode)) {
                char* real = ::realpath(p.c_str(), nullptr);
                if (!real) {
                    r.error = errno;
                    return r;
                }
                r.path = real;
                std::free(real);
            }
            return r;
        }
        p = std::move(next);
    }
    r.error = ELOOP;
    return r;
}

/// Takes a result that a failure of changes nothing (glibc warns on a plain
/// (void) cast of these calls).
void best_effort(int) {}

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

// --- Output ---------------------------------------------------------------------------------------

Output::Output(const OutputFlags& o) : format_(o.format), path_(o.output), quiet_(o.quiet) {
    if (format_ != "table" && format_ != "json" && format_ != "csv")
        throw InvalidParameter("format", "format must be 'table', 'json' or 'csv', got '" + format_ + "'");
    if (path_.empty()) return;
    // Only the first process writes; every process learns whether it can, so
    // that a bad path stops them all before any work.
    std::string error;
    if (is_root()) {
        const Resolved r = resolve(path_);
        if (r.error) {
            error = cannot(path_, r.error);
        } else if (r.descriptor >= 0) {
            const int flags = ::fcntl(r.descriptor, F_GETFL);
            if (flags < 0 || (flags & O_ACCMODE) == O_RDONLY) error = cannot(path_, EBADF);
            sink_ = Sink::descriptor;
            descriptor_ = r.descriptor;
        } else if (r.exists && S_ISDIR(r.st.st_mode)) {
            error = "'" + path_ + "' is a directory";
        } else if (r.exists && !S_ISREG(r.st.st_mode)) {
            // Opened only at commit: a FIFO's open waits for its reader, which
            // may well start after us.
            if (!writable(r.path)) error = cannot(path_, errno);
            sink_ = Sink::direct;
            target_ = r.path;
        } else if (r.exists && !writable(r.path)) {
            // Replacing a file one may not write would bypass its permissions.
            error = cannot(path_, errno);
        } else {
            sink_ = Sink::atomic;
            target_ = r.path;
            open_temporary(error);
        }
    }
    if (!all_ok(error.empty())) {
        discard(); // the path of another process failed: ours must not stay behind
        throw InvalidParameter("output", error.empty() ? "cannot write '" + path_ + "'" : error);
    }
}

void Output::open_temporary(std::string& error) {
    // Beside the target, not the link, so that rename() stays within one
    // directory (atomic) and replaces the target rather than the link.
    temp_ = target_ + ".tmp." + std::to_string(::getpid());
    // Read here, before any worker thread exists: umask() can only be read by
    // setting it.
    umask_ = ::umask(0);
    ::umask(umask_);
    // Armed before the file exists, so that no instant has it unguarded.
    if (temp_.size() < sizeof g_temp_path) {
        std::memcpy(g_temp_path, temp_.c_str(), temp_.size() + 1);
        g_temp_armed = 1;
        install_handlers();
    }
    // 0600 until commit: a half-written result is nobody else's to read.
    // O_EXCL so that a symlink planted at the temporary's name is not followed.
    const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC;
    fd_ = ::open(temp_.c_str(), flags, 0600);
    if (fd_ < 0 && errno == EEXIST) { // left by a run killed by SIGKILL that had our pid
        ::unlink(temp_.c_str());
        fd_ = ::open(temp_.c_str(), flags, 0600);
    }
    if (fd_ < 0) {
        error = cannot(path_, errno);
        temp_.clear(); // not ours: nothing to remove
    }
}

void Output::discard() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!temp_.empty()) ::unlink(temp_.c_str());
    temp_.clear();
    g_temp_armed = 0;
    restore_handlers();
}

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
    write_all(fd_, text);
    // The replacement takes the mode and owner of the file it replaces, read
    // now rather than at the start (they may have changed during the run); a
    // new file gets what any program would create.
    mode_t mode = 0666 & ~umask_;
    struct stat st {};
    if (::stat(target_.c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
        mode = st.st_mode & 07777;
        if ((st.st_uid != ::geteuid() || st.st_gid != ::getegid()) && ::fchown(fd_, st.st_uid, st.st_gid) != 0) {
            // Only root gives a file away: keep at least the group where we
            // belong to it, and no set-id bit on a file whose owner changed.
            best_effort(::fchown(fd_, static_cast<uid_t>(-1), st.st_gid));
            mode &= ~static_cast<mode_t>(S_ISUID | S_ISGID);
        }
    }
    // Ignored when refused: some file systems (vfat, some network mounts) have
    // no modes, and a 0600 result is better than none.
    best_effort(::fchmod(fd_, mode));
    const bool synced = ::fsync(fd_) == 0;
    const int sync_errno = errno;
    const bool closed = ::close(fd_) == 0;
    const int close_errno = errno;
    fd_ = -1;
    if (!synced || !closed) throw std::runtime_error(cannot(path_, !synced ? sync_errno : close_errno));
    if (::rename(temp_.c_str(), target_.c_str()) != 0)
        throw std::runtime_error("cannot rename '" + temp_ + "' to '" + target_ + "': " + std::strerror(errno));
    temp_.clear();
    // The rename itself is durable only once the directory is synced; best
    // effort, the result is in place either way.
    const auto slash = target_.rfind('/');
    const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : target_.substr(0, slash);
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        best_effort(::fsync(dfd));
        ::close(dfd);
    }
    g_temp_armed = 0;
    restore_handlers();
}

} // namespace stickslip::cli
