#include "output.hpp"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

#include "distributed.hpp"
#include "stickslip/setting.hpp"

namespace stickslip::cli {

void add_output_flags(CLI::App* app, OutputFlags& o) {
    app->add_option("--format", o.format, "table (human), json (one object) or csv (header + rows; notes go to stderr)")
        ->type_name("table|json|csv")
        ->capture_default_str();
    app->add_option("--output", o.output,
                    "write the result to FILE instead of stdout (atomically: a temporary file renamed into place, "
                    "nothing left behind on failure)")
        ->type_name("FILE");
    app->add_flag("--quiet", o.quiet, "no progress line on stderr");
}

namespace {

/// The temporary output file of this process, removed by the signal handler
/// (a fixed buffer: only async-signal-safe calls in the handler).
char g_temp_path[4096] = {0};

extern "C" void remove_temp_and_reraise(int sig) {
    if (g_temp_path[0]) ::unlink(g_temp_path);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

} // namespace

Output::Output(const OutputFlags& o) : format_(o.format), path_(o.output), quiet_(o.quiet) {
    if (format_ != "table" && format_ != "json" && format_ != "csv")
        throw InvalidParameter("format", "format must be 'table', 'json' or 'csv', got '" + format_ + "'");
    if (path_.empty()) return;
    // Only the first process writes; every process learns whether it can, so
    // that a bad path stops them all before any work.
    std::string error;
    if (is_root()) {
        struct stat st {};
        if (::stat(path_.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
            error = "'" + path_ + "' is a directory";
        } else {
            // The temporary lives in the target's directory so that rename() is atomic.
            temp_ = path_ + ".tmp." + std::to_string(::getpid());
            fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
            if (fd_ < 0) error = "cannot write '" + path_ + "': " + std::strerror(errno);
        }
    }
    if (!all_ok(error.empty()))
        throw InvalidParameter("output", error.empty() ? "cannot write '" + path_ + "'" : error);
    if (fd_ >= 0 && temp_.size() < sizeof g_temp_path) {
        // Ctrl-C or a kill during a long run must not leave the temporary behind.
        std::memcpy(g_temp_path, temp_.c_str(), temp_.size() + 1);
        std::signal(SIGINT, remove_temp_and_reraise);
        std::signal(SIGTERM, remove_temp_and_reraise);
    }
}

Output::~Output() {
    if (fd_ >= 0) {
        ::close(fd_);
        ::unlink(temp_.c_str());
    }
    g_temp_path[0] = '\0';
}

void Output::commit(const std::string& text, const std::vector<std::string>& warnings) {
    if (!is_root()) return;
    for (const auto& w : warnings) std::fprintf(stderr, "stickslip: note: %s\n", w.c_str());
    if (path_.empty()) {
        std::cout << text << std::flush;
        if (!std::cout) throw std::runtime_error("cannot write to stdout");
        return;
    }
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t w = ::write(fd_, text.data() + done, text.size() - done);
        if (w < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error("cannot write '" + temp_ + "': " + std::strerror(errno));
        }
        done += static_cast<std::size_t>(w);
    }
    const bool synced = ::fsync(fd_) == 0;
    const int sync_errno = errno;
    const bool closed = ::close(fd_) == 0;
    const int close_errno = errno;
    fd_ = -1;
    if (!synced || !closed) {
        const std::string err = std::strerror(!synced ? sync_errno : close_errno);
        ::unlink(temp_.c_str());
        throw std::runtime_error("cannot write '" + temp_ + "': " + err);
    }
    if (::rename(temp_.c_str(), path_.c_str()) != 0) {
        const std::string err = std::strerror(errno);
        ::unlink(temp_.c_str());
        throw std::runtime_error("cannot rename '" + temp_ + "' to '" + path_ + "': " + err);
    }
    if (!quiet_ && isatty(STDERR_FILENO)) std::fprintf(stderr, "wrote %s\n", path_.c_str());
}

} // namespace stickslip::cli
