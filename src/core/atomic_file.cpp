// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/detail/atomic_file.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <fstream>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <system_error>
#include <unistd.h>

namespace stickslip::detail {

namespace {

[[noreturn]] void fail(int err, const std::string& what) {
    throw std::system_error(err, std::generic_category(), what);
}

/// Takes a result whose failure changes nothing (glibc warns on a plain
/// (void) cast of these calls).
void best_effort(long) {}

// --- the temporaries in flight, for a signal handler ---------------------------------------------

// Fixed buffers and lock-free flags: the handler may run at any instant, on
// any thread, and may only read memory and call unlink().
constexpr int kSlots = 16;
char g_names[kSlots][PATH_MAX];
std::atomic<int> g_slot_state[kSlots]; // 0 free, 1 being filled, 2 armed
static_assert(std::atomic<int>::is_always_lock_free, "a signal handler reads the slots");

/// Registers `name` for remove_temporaries(); -1 when it cannot (no slot
/// free, a name too long): the stale-temporary clean-up then catches it later.
int arm(const std::string& name) {
    if (name.size() >= PATH_MAX) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = 0;
        if (!g_slot_state[i].compare_exchange_strong(expected, 1)) continue;
        std::memcpy(g_names[i], name.c_str(), name.size() + 1);
        g_slot_state[i].store(2, std::memory_order_release);
        return i;
    }
    return -1;
}

void disarm(int& slot) {
    if (slot >= 0) g_slot_state[slot].store(0, std::memory_order_release);
    slot = -1;
}

// --- names --------------------------------------------------------------------------------------

std::string directory_of(const std::string& path) {
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

std::string base_of(const std::string& path) {
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string host_name() {
    char buf[256] = {0};
    if (::gethostname(buf, sizeof buf - 1) != 0 || buf[0] == '\0') return "localhost";
    std::string h(buf);
    for (char& c : h)
        if (c == '/') c = '_';
    return h;
}

/// The process's umask, without setting it where /proc tells it (umask()
/// can only be read by changing it, a race with any thread creating a file).
mode_t current_umask() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("Umask:", 0) == 0) return static_cast<mode_t>(std::strtoul(line.c_str() + 6, nullptr, 8));
    const mode_t u = ::umask(022);
    ::umask(u);
    return u;
}

bool alive(pid_t pid) { return ::kill(pid, 0) == 0 || errno != ESRCH; }

/// Removes the temporaries of `target` whose process, on this host, is gone
/// (killed by SIGKILL where no unnamed temporary could be had, or in the
/// instant between naming and renaming one).
void remove_stale(const std::string& target) {
    const std::string dir = directory_of(target), prefix = base_of(temporary_prefix(target));
    DIR* d = ::opendir(dir.c_str());
    if (!d) return;
    while (const dirent* e = ::readdir(d)) {
        const std::string name = e->d_name;
        if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
        // The rest is exactly "<pid>.<n>": anything else is not ours.
        const std::string rest = name.substr(prefix.size());
        const auto dot = rest.find('.');
        if (dot == 0 || dot == std::string::npos || dot + 1 == rest.size() || dot > 9) continue;
        if (rest.find_first_not_of("0123456789.") != std::string::npos || rest.find('.', dot + 1) != std::string::npos)
            continue;
        const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dot)));
        if (pid <= 0 || pid == ::getpid() || alive(pid)) continue;
        best_effort(::unlinkat(::dirfd(d), name.c_str(), 0));
    }
    ::closedir(d);
}

// --- what a path names --------------------------------------------------------------------------

/// The descriptor that /dev/stdout, /dev/fd/N, /proc/self/fd/N... stand for,
/// or -1. Written through the descriptor itself rather than reopened, so that
/// `--output /dev/stdout >> log` appends where the shell put it instead of
/// overwriting the log from its start.
int descriptor_alias(const std::string& p) {
    if (p == "/dev/stdin") return STDIN_FILENO;
    if (p == "/dev/stdout") return STDOUT_FILENO;
    if (p == "/dev/stderr") return STDERR_FILENO;
    for (const std::string& prefix :
         {std::string("/dev/fd/"), std::string("/proc/self/fd/"), std::string("/proc/thread-self/fd/"),
          "/proc/" + std::to_string(::getpid()) + "/fd/"}) {
        if (p.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string n = p.substr(prefix.size());
        if (n.empty() || n.size() > 9 || n.find_first_not_of("0123456789") != std::string::npos) return -1;
        return std::stoi(n);
    }
    return -1;
}

void fill(FileTarget& t, const struct stat& st) {
    using K = FileTarget::Kind;
    t.kind = S_ISREG(st.st_mode)    ? K::regular
             : S_ISDIR(st.st_mode)  ? K::directory
             : S_ISCHR(st.st_mode)  ? K::character_device
             : S_ISBLK(st.st_mode)  ? K::block_device
             : S_ISFIFO(st.st_mode) ? K::fifo
                                    : K::socket;
    t.device = static_cast<std::uint64_t>(st.st_dev);
    t.inode = static_cast<std::uint64_t>(st.st_ino);
    t.size = static_cast<std::uint64_t>(st.st_size);
}

/// `path` with its directory made canonical, for comparing two paths of
/// which one or both do not exist yet.
std::string canonical_location(const std::string& path) {
    const std::string dir = directory_of(path), base = base_of(path);
    char* real = ::realpath(dir.c_str(), nullptr);
    if (!real) return path;
    std::string out(real);
    std::free(real);
    return (out == "/" ? "" : out) + "/" + base;
}

} // namespace

FileTarget resolve_target(const std::string& path) {
    FileTarget r;
    std::string p = path;
    for (int hops = 0; hops <= 40; ++hops) { // the kernel's own limit (ELOOP)
        if ((r.descriptor = descriptor_alias(p)) >= 0) {
            r.kind = FileTarget::Kind::descriptor;
            return r;
        }
        struct stat ls {};
        if (::lstat(p.c_str(), &ls) != 0) {
            if (errno != ENOENT) r.error = errno;
            r.path = p; // missing: created there (if its directory exists, which opening the temporary checks)
            return r;
        }
        if (!S_ISLNK(ls.st_mode)) {
            r.path = p;
            fill(r, ls);
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
            fill(r, followed);
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

const char* describe(FileTarget::Kind kind) {
    switch (kind) {
    case FileTarget::Kind::missing: return "a new file";
    case FileTarget::Kind::regular: return "a regular file";
    case FileTarget::Kind::directory: return "a directory";
    case FileTarget::Kind::character_device: return "a character device";
    case FileTarget::Kind::block_device: return "a block device";
    case FileTarget::Kind::fifo: return "a FIFO";
    case FileTarget::Kind::socket: return "a socket";
    case FileTarget::Kind::descriptor: return "a file descriptor of this process";
    }
    return "a file";
}

bool same_file(const FileTarget& a, const FileTarget& b) {
    if (a.kind == FileTarget::Kind::descriptor || b.kind == FileTarget::Kind::descriptor)
        return a.kind == b.kind && a.descriptor == b.descriptor;
    if (a.exists() && b.exists()) return a.device == b.device && a.inode == b.inode;
    if (a.exists() != b.exists()) return false;
    return canonical_location(a.path) == canonical_location(b.path);
}

std::string temporary_prefix(const std::string& target) {
    const std::string dir = directory_of(target), host = host_name();
    std::string base = base_of(target);
    // Room for ".tmp.<host>.<pid>.<n>" within a file name's 255 bytes.
    const std::size_t room = 255 - std::min<std::size_t>(host.size(), 64) - 5 - 1 - 10 - 1 - 10;
    if (base.size() > room) base.resize(room);
    return (target.find('/') == std::string::npos ? "" : dir == "/" ? "/" : dir + "/") + base + ".tmp." +
           host.substr(0, 64) + ".";
}

void remove_temporaries() noexcept {
    for (int i = 0; i < kSlots; ++i)
        if (g_slot_state[i].load(std::memory_order_acquire) == 2) ::unlink(g_names[i]);
}

// --- AtomicFile ---------------------------------------------------------------------------------

struct AtomicFile::State {
    std::string target, temp; ///< temp: the temporary's name while it has one
    int fd = -1;
    int slot = -1; ///< the registry slot of `temp`
    bool unnamed = false;
};

namespace {

/// A fresh name for a temporary of `target`: unique within the process, so
/// that two writers of one target (tests do it) do not collide.
std::string fresh_name(const std::string& target) {
    static std::atomic<unsigned> counter{0};
    return temporary_prefix(target) + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

/// Creates the named temporary `name`, 0600 (a half-written result is nobody
/// else's to read), O_EXCL so that a link planted at that name is not followed.
int create_named(const std::string& name) {
    const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC;
    int fd = ::open(name.c_str(), flags, 0600);
    if (fd < 0 && errno == EEXIST) { // left by a process killed by SIGKILL that had our pid
        ::unlink(name.c_str());
        fd = ::open(name.c_str(), flags, 0600);
    }
    return fd;
}

/// Gives the unnamed file `fd` the name `name` (linkat cannot replace a file,
/// hence a name of our own first and a rename after).
int link_unnamed(int fd, const std::string& name) {
    const std::string self = "/proc/self/fd/" + std::to_string(fd);
    for (int attempt = 0; attempt < 2; ++attempt) {
        if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return 0;
        if (errno == ENOENT) // no /proc: the privileged way, if we have it
            if (::linkat(fd, "", AT_FDCWD, name.c_str(), AT_EMPTY_PATH) == 0) return 0;
        if (errno != EEXIST || attempt > 0) return -1;
        ::unlink(name.c_str()); // a dead process that had our pid
    }
    return -1;
}

} // namespace

AtomicFile::AtomicFile(std::string target, Temporary how) : s_(std::make_unique<State>()) {
    s_->target = std::move(target);
    const std::string dir = directory_of(s_->target);
    remove_stale(s_->target);
#ifdef O_TMPFILE
    if (how == Temporary::unnamed_if_possible) {
        const int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
        if (fd >= 0) {
            // It can be given a name only through /proc (or by a privileged
            // process): without either, a named temporary from the start.
            struct stat st {};
            const std::string self = "/proc/self/fd/" + std::to_string(fd);
            if (::stat(self.c_str(), &st) == 0 || ::geteuid() == 0) {
                s_->fd = fd;
                s_->unnamed = true;
                return;
            }
            ::close(fd);
        } else if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL && errno != ENOSYS) {
            // The directory itself is the problem (missing, not writable, read-only...).
            fail(errno, "cannot write '" + s_->target + "'");
        }
    }
#else
    (void)how;
#endif
    s_->temp = fresh_name(s_->target);
    s_->slot = arm(s_->temp); // before the file exists, so that no instant has it unguarded
    s_->fd = create_named(s_->temp);
    if (s_->fd < 0) {
        const int err = errno;
        disarm(s_->slot);
        s_->temp.clear(); // not ours: nothing to remove
        fail(err, "cannot write '" + s_->target + "'");
    }
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
    if (!s_) return;
    if (s_->fd >= 0) ::close(s_->fd);
    s_->fd = -1;
    if (!s_->temp.empty()) ::unlink(s_->temp.c_str());
    s_->temp.clear();
    disarm(s_->slot);
}

void AtomicFile::write(std::string_view text) {
    if (s_->fd < 0) fail(EBADF, "cannot write '" + s_->target + "'");
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t w = ::write(s_->fd, text.data() + done, text.size() - done);
        if (w < 0) {
            if (errno == EINTR) continue;
            fail(errno, "cannot write '" + s_->target + "'");
        }
        done += static_cast<std::size_t>(w);
    }
}

void AtomicFile::commit() {
    const std::string what = "cannot write '" + s_->target + "'";
    if (s_->fd < 0) fail(EBADF, what);
    try {
        // The replacement takes the mode and owner of the file it replaces,
        // read now rather than at the start (they may have changed meanwhile);
        // a new file gets what any program would create.
        mode_t mode = 0666 & ~current_umask();
        struct stat st {};
        if (::stat(s_->target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
            mode = st.st_mode & 07777;
            if ((st.st_uid != ::geteuid() || st.st_gid != ::getegid()) &&
                ::fchown(s_->fd, st.st_uid, st.st_gid) != 0) {
                // Only root gives a file away: keep at least the group where
                // we belong to it, and no set-id bit on a file whose owner
                // changed.
                best_effort(::fchown(s_->fd, static_cast<uid_t>(-1), st.st_gid));
                mode &= ~static_cast<mode_t>(S_ISUID | S_ISGID);
            }
        }
        // Ignored when refused: some file systems (vfat, some network mounts)
        // have no modes, and a 0600 result is better than none.
        best_effort(::fchmod(s_->fd, mode));
        if (::fsync(s_->fd) != 0) fail(errno, what);
        if (s_->unnamed) {
            s_->temp = fresh_name(s_->target);
            s_->slot = arm(s_->temp);
            if (link_unnamed(s_->fd, s_->temp) != 0) {
                const int err = errno;
                disarm(s_->slot);
                s_->temp.clear();
                fail(err, what);
            }
            s_->unnamed = false;
        }
        // Renamed before the close, to keep the instant in which a SIGKILL
        // would leave the name behind as short as can be; the data is synced
        // already, so a close cannot lose it.
        if (::rename(s_->temp.c_str(), s_->target.c_str()) != 0) fail(errno, what);
    } catch (...) {
        discard();
        throw;
    }
    s_->temp.clear();
    disarm(s_->slot);
    ::close(s_->fd);
    s_->fd = -1;
    // The rename itself is durable only once the directory is synced; best
    // effort, the file is in place either way.
    const int dfd = ::open(directory_of(s_->target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        best_effort(::fsync(dfd));
        ::close(dfd);
    }
}

bool AtomicFile::unnamed() const { return s_->unnamed; }
const std::string& AtomicFile::temporary_name() const { return s_->temp; }
const std::string& AtomicFile::target() const { return s_->target; }

void write_file_atomically(const std::string& target, std::string_view text) {
    AtomicFile f(target);
    f.write(text);
    f.commit();
}

} // namespace stickslip::detail
