// SPDX-License-Identifier: BSD-3-Clause
// Shared helpers of the CLI end-to-end tests: run the built binary
// (STICKSLIP_CLI_PATH) in a child process with stdin from /dev/null and stdout
// and stderr captured in temporary files.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace clitest {

using nlohmann::json;
using Args = std::vector<std::string>;

struct Result {
    int code = -1; ///< exit status; 128 + signal if killed
    std::string out, err;
};

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// A fresh directory under the test temp dir, named stickslip_<tag>_XXXXXX.
inline std::string make_dir(const char* tag) {
    std::string base = ::testing::TempDir();
    if (base.empty()) base = "/tmp/";
    if (base.back() != '/') base += '/';
    std::string path = base + "stickslip_" + tag + "_XXXXXX";
    std::vector<char> buf(path.begin(), path.end());
    buf.push_back('\0');
    if (!::mkdtemp(buf.data())) throw std::runtime_error("mkdtemp failed for " + path);
    return buf.data();
}

/// The names in `dir` (without "." and ".."), sorted.
inline std::vector<std::string> list_dir(const std::string& dir) {
    std::vector<std::string> names;
    if (DIR* d = ::opendir(dir.c_str())) {
        while (dirent* e = ::readdir(d))
            if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") names.push_back(e->d_name);
        ::closedir(d);
    }
    std::sort(names.begin(), names.end());
    return names;
}

/// A directory of the test's own, removed with its entries (the tests make
/// no deeper ones) however the test ends, a failed ASSERT included.
struct Scratch {
    const std::string path;
    explicit Scratch(const char* tag) : path(make_dir(tag)) {}
    ~Scratch() {
        for (const auto& name : list_dir(path)) ::unlink((path + "/" + name).c_str());
        ::rmdir(path.c_str());
    }
    std::string operator/(const std::string& name) const { return path + "/" + name; }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
};

/// True once process `pid` holds a file open in `dir` (its output's or a
/// checkpoint's temporary, which has no name where the system allows:
/// /proc/PID/fd shows it as "DIR/#INODE (deleted)"); false if the process
/// ended first or nothing appeared within `seconds`.
inline bool holds_file_in(pid_t pid, const std::string& dir, double seconds = 30) {
    char* real = ::realpath(dir.c_str(), nullptr);
    const std::string prefix = std::string(real ? real : dir.c_str()) + "/";
    std::free(real);
    const std::string fds = "/proc/" + std::to_string(pid) + "/fd";
    for (int waited_ms = 0; waited_ms < seconds * 1000; waited_ms += 5) {
        for (const auto& fd : list_dir(fds)) {
            char buf[4096];
            const ssize_t n = ::readlink((fds + "/" + fd).c_str(), buf, sizeof buf);
            if (n > 0 && std::string(buf, static_cast<std::size_t>(n)).compare(0, prefix.size(), prefix) == 0)
                return true;
        }
        // Ended (a zombie, left for the caller to reap) or gone.
        const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
        const auto paren = stat.rfind(')');
        if (paren == std::string::npos || paren + 2 >= stat.size() || stat[paren + 2] == 'Z') return false;
        ::usleep(5000);
    }
    return false;
}

inline std::string temp_file(const char* tag) {
    std::string dir = ::testing::TempDir();
    if (dir.empty()) dir = "/tmp/";
    if (dir.back() != '/') dir += '/';
    std::string path = dir + "stickslip_cli_" + tag + "_XXXXXX";
    std::vector<char> buf(path.begin(), path.end());
    buf.push_back('\0');
    const int fd = ::mkstemp(buf.data());
    if (fd < 0) throw std::runtime_error("mkstemp failed for " + path);
    ::close(fd);
    return std::string(buf.data());
}

/// Runs `stickslip args...` without a shell.
inline Result run(const Args& args) {
    const std::string out_path = temp_file("out"), err_path = temp_file("err");
    std::vector<std::string> argv_s{STICKSLIP_CLI_PATH};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, out_path.c_str(), O_WRONLY | O_TRUNC, 0);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_TRUNC, 0);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    Result r;
    if (rc != 0) {
        ADD_FAILURE() << "cannot start " << argv[0] << ": " << std::strerror(rc);
    } else {
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    r.out = slurp(out_path);
    r.err = slurp(err_path);
    std::remove(out_path.c_str());
    std::remove(err_path.c_str());
    return r;
}

inline std::string describe(const Args& args) {
    std::string s = "stickslip";
    for (const auto& a : args) s += " " + a;
    return s;
}

inline bool has(const Args& args, const std::string& flag) {
    for (const auto& a : args)
        if (a == flag) return true;
    return false;
}

/// Adds fast settings, right after the subcommand, unless the arguments set
/// them already (CLI11 rejects repeated options), so that a case that wrongly
/// passes validation still finishes quickly.
inline Args fast(const Args& args) {
    if (args.empty() || (args[0] != "diffusivity" && args[0] != "bruteforce")) return args;
    Args extra;
    const bool pdmp = has(args, "pdmp");
    if (args[0] == "diffusivity" && !has(args, "--excursions")) extra.insert(extra.end(), {"--excursions", pdmp ? "300" : "200"});
    if (args[0] == "bruteforce") {
        if (!has(args, "--time")) extra.insert(extra.end(), {"--time", "1"});
        if (!has(args, "--trajectories")) extra.insert(extra.end(), {"--trajectories", "100"});
    }
    if (!pdmp && !has(args, "--dt")) extra.insert(extra.end(), {"--dt", "1e-3"});
    Args out{args[0]};
    out.insert(out.end(), extra.begin(), extra.end());
    out.insert(out.end(), args.begin() + 1, args.end());
    return out;
}

/// Runs, expects exit 0, nothing on stderr, and one JSON object on stdout.
inline std::optional<json> run_json(const Args& args) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 0) << describe(args) << "\nstderr: " << r.err;
    EXPECT_EQ(r.err, "") << describe(args) << ": no progress or notes on stderr when it is not a terminal";
    if (r.code != 0) return std::nullopt;
    try {
        return json::parse(r.out);
    } catch (const std::exception& e) {
        ADD_FAILURE() << describe(args) << ": stdout is not JSON (" << e.what() << "):\n" << r.out;
        return std::nullopt;
    }
}

/// The JSON less its timing ("work") and what says how the run was asked
/// for rather than what it computed: the command line and the thread count.
inline json without_work(json j) {
    j.erase("work");
    j.erase("command");
    if (j.contains("settings")) j["settings"].erase("threads");
    return j;
}

inline int count_lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

/// Starts `stickslip args...` in a child process: every signal at its
/// default (a test run from a background shell inherits SIGINT and SIGQUIT
/// ignored) except `ignored`, none blocked, stdin from /dev/null, stdout and
/// stderr to the given files, no core file (SIGQUIT, SIGXCPU and SIGXFSZ dump
/// core by default). For tests that signal or kill the run. With `pending`,
/// that signal is blocked and already sent when the command starts (pending
/// signals survive exec): a signal that surely comes before the run begins.
inline pid_t start(const Args& args, const std::string& out_path, const std::string& err_path, int ignored = 0,
                   int pending = 0) {
    std::vector<std::string> argv_s{STICKSLIP_CLI_PATH};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) { // only async-signal-safe calls until exec
        struct rlimit no_core {};
        ::setrlimit(RLIMIT_CORE, &no_core);
        for (int s = 1; s < NSIG; ++s)
            if (s != SIGKILL && s != SIGSTOP) ::signal(s, s == ignored ? SIG_IGN : SIG_DFL);
        sigset_t none;
        sigemptyset(&none);
        if (pending) sigaddset(&none, pending);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        if (pending) ::kill(::getpid(), pending);
        const int in = ::open("/dev/null", O_RDONLY);
        const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(in, STDIN_FILENO);
        ::dup2(out, STDOUT_FILENO);
        ::dup2(err, STDERR_FILENO);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    return pid;
}

/// The wait status of `pid`, or nothing if it still runs after `seconds`
/// (then it is killed: a test fails rather than hangs).
inline std::optional<int> wait_for_exit(pid_t pid, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    do {
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid) return status;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    } while (std::chrono::steady_clock::now() < end);
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    return std::nullopt;
}

/// `a` with `more` appended.
inline Args with(Args a, std::initializer_list<std::string> more) {
    a.insert(a.end(), more);
    return a;
}

/// lstat() of `path` (st_mode 0 when it does not exist).
inline struct stat lstat_of(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) st.st_mode = 0;
    return st;
}

/// A symlink's target, or "" when `path` is not one.
inline std::string link_of(const std::string& path) {
    char buf[4096];
    const ssize_t n = ::readlink(path.c_str(), buf, sizeof buf);
    return n < 0 ? std::string() : std::string(buf, static_cast<std::size_t>(n));
}

} // namespace clitest
