// SPDX-License-Identifier: BSD-3-Clause
// End-to-end tests of what --output writes to when FILE is not a plain new
// file: a FIFO, a device, /dev/stdout, a symlink chain, an existing file with
// its own mode and owner, and a run ended by a signal or by an error. The rule
// they check: a regular file is replaced atomically (the temporary in the
// real target's folder, its mode and owner kept, nothing left behind whatever
// ends the run); anything else is written through and stays what it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <dirent.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <thread>

#include "cli_support.hpp"

namespace {

using namespace clitest;
using nlohmann::json;

/// A run that takes well under a second and prints one JSON object.
const Args kQuick{"analytic", "--friction", "1", "--noise", "1", "--relaxation", "inf", "--bias", "0", "--format", "json"};

Args writing_to(const std::string& path) {
    Args a = kQuick;
    a.insert(a.end(), {"--output", path});
    return a;
}

bool is_json_object(const std::string& text) {
    try {
        return json::parse(text).is_object();
    } catch (const std::exception&) {
        return false;
    }
}

// --- written through: FIFO, devices, /dev/stdout ------------------------------------------------

// Guards against replacing a FIFO by a regular file (the old rename did): the
// reader at the other end must get the JSON, and the FIFO stay a FIFO.
TEST(CliOutputThrough, FifoIsWrittenAndStaysAFifo) {
    const Scratch scratch("fifo");
    const std::string dir = scratch.path, fifo = dir + "/pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    // Both ends are held by the test before the run: the command's open then
    // succeeds at once, and closing our own writer afterwards gives the reader
    // its end of file even if the command replaced the FIFO instead of
    // writing it (the test then fails rather than hangs).
    const int in = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(in, 0) << std::strerror(errno);
    const int keep = ::open(fifo.c_str(), O_WRONLY);
    ASSERT_GE(keep, 0) << std::strerror(errno);
    ::fcntl(in, F_SETFL, ::fcntl(in, F_GETFL) & ~O_NONBLOCK);
    std::string received;
    std::thread reader([&] {
        char buf[4096];
        ssize_t n;
        while ((n = ::read(in, buf, sizeof buf)) > 0) received.append(buf, static_cast<std::size_t>(n));
    });
    const Result r = run(writing_to(fifo));
    ::close(keep);
    reader.join();
    ::close(in);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(is_json_object(received)) << "the reader got:\n" << received;
    EXPECT_TRUE(S_ISFIFO(lstat_of(fifo).st_mode)) << "the FIFO was replaced";
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{"pipe"}) << "no temporary beside the FIFO";
}

// Guards a socket file (a log collector's): open() cannot write it, so the
// command must connect to it; the listener gets the JSON and the socket file
// is still a socket.
TEST(CliOutputThrough, SocketIsWrittenAndStaysASocket) {
    const Scratch scratch("sock");
    const std::string dir = scratch.path, path = dir + "/s";
    sockaddr_un addr {};
    addr.sun_family = AF_UNIX;
    if (path.size() >= sizeof addr.sun_path) GTEST_SKIP() << "temporary directory too deep for a socket path";
    std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
    const int listener = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(listener, 0) << std::strerror(errno);
    ASSERT_EQ(::bind(listener, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0) << std::strerror(errno);
    ASSERT_EQ(::listen(listener, 1), 0);
    // Woken once the command has ended: by then its connection, if it made
    // one, is queued, and if it made none the test fails rather than hangs.
    int wake[2];
    ASSERT_EQ(::pipe(wake), 0);
    std::string received;
    std::thread server([&] {
        pollfd p[2] = {{listener, POLLIN, 0}, {wake[0], POLLIN, 0}};
        if (::poll(p, 2, -1) < 1 || !(p[0].revents & POLLIN)) return;
        const int conn = ::accept(listener, nullptr, nullptr);
        if (conn < 0) return;
        char buf[4096];
        ssize_t n;
        while ((n = ::read(conn, buf, sizeof buf)) > 0) received.append(buf, static_cast<std::size_t>(n));
        ::close(conn);
    });
    const Result r = run(writing_to(path));
    EXPECT_EQ(::write(wake[1], "", 1), 1);
    server.join();
    ::close(listener);
    ::close(wake[0]);
    ::close(wake[1]);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(is_json_object(received)) << "the listener got:\n" << received;
    EXPECT_TRUE(S_ISSOCK(lstat_of(path).st_mode)) << "the socket was replaced";
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{"s"});
}

/// Where a device test may point --output without risk: the system node
/// itself when this process cannot replace it anyway, else (root, who could:
/// a regression once replaced this machine's /dev/null by a regular file) a
/// node of the same device made in `dir`. Empty when neither is possible.
std::string device_to_test(const std::string& dir, const std::string& system_path) {
    const struct stat sys = lstat_of(system_path);
    if (!S_ISCHR(sys.st_mode)) return {};
    if (::access("/dev", W_OK) != 0) return system_path;
    const std::string own = dir + system_path.substr(system_path.rfind('/'));
    if (::mknod(own.c_str(), S_IFCHR | 0666, sys.st_rdev) != 0) return {};
    const int fd = ::open(own.c_str(), O_WRONLY); // a nodev mount refuses it
    if (fd < 0) {
        ::unlink(own.c_str());
        return {};
    }
    ::close(fd);
    return own;
}

/// The same for /dev/stdout: as root, a link of our own to what it links to.
std::string stdout_to_test(const std::string& dir) {
    const struct stat sys = lstat_of("/dev/stdout");
    if (sys.st_mode == 0) return {};
    if (::access("/dev", W_OK) != 0) return "/dev/stdout";
    if (!S_ISLNK(sys.st_mode)) return {};
    const std::string own = dir + "/stdout";
    return ::symlink(link_of("/dev/stdout").c_str(), own.c_str()) == 0 ? own : std::string();
}

// Guards the error path of a device that refuses the write: a clear one-line
// error naming the path and the reason, exit 1 (not a crash, not exit 0), and
// the device left a character device.
TEST(CliOutputThrough, DevFullIsAnErrorAndStaysADevice) {
    const Scratch scratch("full");
    const std::string dir = scratch.path, full = device_to_test(dir, "/dev/full");
    if (full.empty()) GTEST_SKIP() << "no /dev/full to test safely here";
    const struct stat before = lstat_of(full);
    const Result r = run(writing_to(full));
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("cannot write '" + full + "': No space left on device"), std::string::npos) << r.err;
    const struct stat after = lstat_of(full);
    EXPECT_TRUE(S_ISCHR(after.st_mode)) << full << " was replaced";
    EXPECT_EQ(after.st_rdev, before.st_rdev);
    if (full != "/dev/full") {
        EXPECT_EQ(list_dir(dir), std::vector<std::string>{"full"}) << "no temporary beside the device";
    }
}

// Guards the worst case of the old rename, run as root: /dev/null replaced by
// a regular file holding our JSON, for every program on the machine.
TEST(CliOutputThrough, DevNullStaysADevice) {
    const Scratch scratch("null");
    const std::string dir = scratch.path, null = device_to_test(dir, "/dev/null");
    if (null.empty()) GTEST_SKIP() << "no /dev/null to test safely here";
    const struct stat before = lstat_of(null);
    const Result r = run(writing_to(null));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, "");
    const struct stat after = lstat_of(null);
    EXPECT_TRUE(S_ISCHR(after.st_mode)) << null << " was replaced";
    EXPECT_EQ(after.st_rdev, before.st_rdev);
}

// Guards /dev/stdout (a symlink into /proc/self/fd): the text reaches the
// captured stdout (a regular file here, which a resolve-and-rename would have
// replaced behind the harness's back) and the link itself is untouched.
TEST(CliOutputThrough, DevStdoutReachesStdout) {
    const Scratch scratch("stdout");
    const std::string dir = scratch.path, path = stdout_to_test(dir);
    if (path.empty()) GTEST_SKIP() << "no /dev/stdout to test safely here";
    const struct stat before = lstat_of(path);
    const std::string link = S_ISLNK(before.st_mode) ? link_of(path) : "";
    const Result r = run(writing_to(path));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(is_json_object(r.out)) << "stdout:\n" << r.out;
    const struct stat after = lstat_of(path);
    EXPECT_EQ(after.st_mode, before.st_mode);
    EXPECT_EQ(after.st_ino, before.st_ino);
    if (S_ISLNK(before.st_mode)) {
        EXPECT_EQ(link_of(path), link);
    }
}

// Guards writing /dev/stdout through the descriptor the shell gave (as
// `... --output /dev/stdout >> log` means): reopening it would start at
// offset 0 and overwrite what the log held.
TEST(CliOutputThrough, DevStdoutAppendsWhereTheShellPutsIt) {
    const Scratch scratch("append");
    const std::string dir = scratch.path, log = dir + "/log", path = stdout_to_test(dir);
    if (path.empty()) GTEST_SKIP() << "no /dev/stdout to test safely here";
    { std::ofstream(log) << "an earlier line of the log\n"; }
    std::vector<std::string> argv_s{STICKSLIP_CLI_PATH};
    for (const auto& a : writing_to(path)) argv_s.push_back(a);
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_APPEND, 0);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    ASSERT_EQ(rc, 0) << std::strerror(rc);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    const std::string text = slurp(log), head = "an earlier line of the log\n";
    ASSERT_EQ(text.compare(0, head.size(), head), 0) << "the log lost its start:\n" << text;
    EXPECT_TRUE(is_json_object(text.substr(head.size()))) << text;
}

// --- symlinks --------------------------------------------------------------------------------------

// Guards that a link chain stays a chain: the old rename put a regular file
// in place of the first link. Relative targets (resolved from each link's own
// directory), a final target missing at first and then present with mode 600,
// and no temporary left beside the links or the target.
TEST(CliOutputSymlink, ChainStaysLinksAndTheTargetIsWritten) {
    const Scratch links_dir("links"), targets_dir("targets");
    const std::string links = links_dir.path, targets = targets_dir.path;
    const std::string target_name = targets.substr(targets.rfind('/') + 1);
    const std::string to_target = "../" + target_name + "/result.json";
    ASSERT_EQ(::symlink(to_target.c_str(), (links + "/first").c_str()), 0);
    ASSERT_EQ(::symlink("first", (links + "/second").c_str()), 0);

    // The target does not exist yet: the chain still says where it goes.
    const Result created = run(writing_to(links + "/second"));
    EXPECT_EQ(created.code, 0) << created.err;
    EXPECT_TRUE(is_json_object(slurp(targets + "/result.json")));

    // It exists now, with a mode of its own that the replacement must keep.
    EXPECT_EQ(::chmod((targets + "/result.json").c_str(), 0600), 0);
    const Result replaced = run(writing_to(links + "/second"));
    EXPECT_EQ(replaced.code, 0) << replaced.err;
    EXPECT_TRUE(is_json_object(slurp(targets + "/result.json")));
    EXPECT_EQ(lstat_of(targets + "/result.json").st_mode & 07777, 0600u);

    EXPECT_TRUE(S_ISLNK(lstat_of(links + "/first").st_mode));
    EXPECT_TRUE(S_ISLNK(lstat_of(links + "/second").st_mode));
    EXPECT_EQ(link_of(links + "/first"), to_target);
    EXPECT_EQ(link_of(links + "/second"), "first");
    EXPECT_EQ(list_dir(links), (std::vector<std::string>{"first", "second"}));
    EXPECT_EQ(list_dir(targets), std::vector<std::string>{"result.json"});
}

// --- an existing file: mode, owner, permissions ------------------------------------------------------

// Guards the mode of a file that already exists (the old temporary's 0644
// made a private 600 file world-readable) and of a new one, which must follow
// the umask like any program's (not stay the temporary's private 0600).
TEST(CliOutputFile, ModeIsKeptAndANewFileFollowsTheUmask) {
    const Scratch scratch("mode");
    const std::string dir = scratch.path, kept = dir + "/private.json", fresh = dir + "/fresh.json";
    { std::ofstream(kept) << "old\n"; }
    ASSERT_EQ(::chmod(kept.c_str(), 0600), 0);
    const Result r = run(writing_to(kept));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(is_json_object(slurp(kept)));
    EXPECT_EQ(lstat_of(kept).st_mode & 07777, 0600u);

    const mode_t old_umask = ::umask(027); // inherited by the child
    const Result n = run(writing_to(fresh));
    ::umask(old_umask);
    EXPECT_EQ(n.code, 0) << n.err;
    EXPECT_EQ(lstat_of(fresh).st_mode & 07777, 0640u);
    EXPECT_EQ(list_dir(dir), (std::vector<std::string>{"fresh.json", "private.json"}));
}

// Guards the owner and group of an existing file, which a rename of a file of
// our own would silently take over (only root may give a file away).
TEST(CliOutputFile, OwnerIsKeptWhenPermitted) {
    if (::geteuid() != 0) GTEST_SKIP() << "only root may keep another user's ownership";
    const Scratch scratch("owner");
    const std::string dir = scratch.path, file = dir + "/theirs.json";
    { std::ofstream(file) << "old\n"; }
    const uid_t uid = 65534;
    const gid_t gid = 65534;
    ASSERT_EQ(::chown(file.c_str(), uid, gid), 0) << std::strerror(errno);
    ASSERT_EQ(::chmod(file.c_str(), 0640), 0);
    const Result r = run(writing_to(file));
    EXPECT_EQ(r.code, 0) << r.err;
    const struct stat st = lstat_of(file);
    EXPECT_EQ(st.st_uid, uid);
    EXPECT_EQ(st.st_gid, gid);
    EXPECT_EQ(st.st_mode & 07777, 0640u);
}

// Guards that a run that fails (capped excursions: exit 3, thrown after the
// temporary was opened) leaves an existing file byte for byte and mode for
// mode as it was, and no temporary.
TEST(CliOutputFile, FailedRunLeavesTheFileByteIdentical) {
    const Scratch scratch("failed");
    const std::string dir = scratch.path, file = dir + "/keep.json";
    static const char kOld[] = "previous\0result\n\xff"; // a NUL and a non-UTF-8 byte: compared as bytes
    const std::string old(kOld, sizeof kOld - 1);
    { std::ofstream(file, std::ios::binary) << old; }
    ASSERT_EQ(::chmod(file.c_str(), 0604), 0);
    const Result r = run({"diffusivity", "--excursions", "200", "--scheme", "resolvent", "--dt", "1e-3", "--max-steps", "4000", "--output", file});
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_EQ(slurp(file), old);
    EXPECT_EQ(lstat_of(file).st_mode & 07777, 0604u);
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{"keep.json"});
}

// Guards the checks made before any work (the run asked for would take
// hours): a directory, also behind a symlink, is bad input (exit 2, one line
// naming --output), and so is an unwritable directory.
TEST(CliOutputFile, DirectoryOrUnwritableDirectoryFailsBeforeAnyWork) {
    const Scratch scratch("bad");
    const std::string dir = scratch.path;
    ASSERT_EQ(::symlink(dir.c_str(), (dir + "/self").c_str()), 0);
    const Args hours{"diffusivity", "--excursions", "1e9", "--scheme", "resolvent", "--dt", "1e-4", "--quiet", "--output"};
    for (const std::string& path : {dir, dir + "/self"}) {
        Args a = hours;
        a.push_back(path);
        const Result r = run(a);
        EXPECT_EQ(r.code, 2) << path << ": " << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("--output"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
    }
    if (::geteuid() != 0) { // root writes anywhere
        const std::string locked = dir + "/locked";
        ASSERT_EQ(::mkdir(locked.c_str(), 0500), 0);
        Args a = hours;
        a.push_back(locked + "/x.json");
        const Result r = run(a);
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_TRUE(list_dir(locked).empty());
        ::rmdir(locked.c_str());
    }
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{"self"});
}

// --- signals ---------------------------------------------------------------------------------------

/// Starts a run that would take hours, writing DIR/out.json, with every
/// signal at its default (a test run from a background shell inherits SIGINT
/// and SIGQUIT ignored) except `ignored`, and no core file (SIGQUIT, SIGXCPU
/// and SIGXFSZ dump core by default).
pid_t start_long_run(const std::string& dir, int ignored = 0) {
    return start({"diffusivity", "--excursions", "100000000", "--scheme", "resolvent", "--dt", "1e-4", "--output",
                  dir + "/out.json", "--quiet"},
                 "/dev/null", "/dev/null", ignored);
}

/// Waits until the run has opened its temporary in DIR (it does so before
/// any work), or the process has ended.
bool wait_for_temporary(const std::string& dir, pid_t pid) { return holds_file_in(pid, dir); }

struct Sig {
    int number;
    const char* name;
};

// SIGINT, SIGTERM and SIGHUP stop a run gracefully (it writes the result so
// far and exits 130/143/129; a second one aborts like these): CliStop in
// checkpoint_cli_test.cpp.
const Sig kTerminating[] = {{SIGQUIT, "QUIT"}, {SIGUSR1, "USR1"},   {SIGUSR2, "USR2"},
                            {SIGPIPE, "PIPE"}, {SIGALRM, "ALRM"}, {SIGXCPU, "XCPU"},   {SIGXFSZ, "XFSZ"},
                            {SIGVTALRM, "VTALRM"}, {SIGPROF, "PROF"}};

void PrintTo(const Sig& s, std::ostream* os) { *os << "SIG" << s.name; }

class CliOutputSignal : public ::testing::TestWithParam<Sig> {};

// Guards each catchable terminating signal (the old handler knew only SIGINT
// and SIGTERM): the temporary is removed (or never had a name), and the
// process still dies by that very signal, as a parent (a shell, a batch
// system) expects.
TEST_P(CliOutputSignal, LeavesNoTemporaryAndDiesByTheSignal) {
    const int sig = GetParam().number;
    const Scratch scratch("signal");
    const std::string dir = scratch.path;
    const pid_t pid = start_long_run(dir);
    ASSERT_GT(pid, 0);
    if (!wait_for_temporary(dir, pid)) {
        const auto status = wait_for_exit(pid, 0);
        FAIL() << "no temporary appeared" << (status ? " (the run ended early)" : "");
    }
    ASSERT_EQ(::kill(pid, sig), 0);
    const auto status = wait_for_exit(pid, 20);
    ASSERT_TRUE(status.has_value()) << "SIG" << GetParam().name << " did not end the run";
    EXPECT_TRUE(WIFSIGNALED(*status) && WTERMSIG(*status) == sig)
        << "status " << *status << ": expected death by SIG" << GetParam().name;
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{}) << "left behind after SIG" << GetParam().name;
}

INSTANTIATE_TEST_SUITE_P(All, CliOutputSignal, ::testing::ValuesIn(kTerminating),
                         [](const ::testing::TestParamInfo<Sig>& p) { return std::string(p.param.name); });

// Guards the other half of keeping the old semantics: a signal the run was
// started with ignored (nohup's SIGHUP) stays ignored rather than becoming
// fatal because we took it over for the clean-up.
TEST(CliOutputSignalIgnored, AnIgnoredSignalStaysIgnored) {
    const Scratch scratch("nohup");
    const std::string dir = scratch.path;
    const pid_t pid = start_long_run(dir, SIGHUP);
    ASSERT_GT(pid, 0);
    ASSERT_TRUE(wait_for_temporary(dir, pid));
    ASSERT_EQ(::kill(pid, SIGHUP), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    int status = 0;
    const pid_t ended = ::waitpid(pid, &status, WNOHANG);
    EXPECT_EQ(ended, 0) << "SIGHUP ended a run that ignores it";
    if (ended == 0) {
        ::kill(pid, SIGQUIT); // (SIGTERM would now stop it gracefully and write the result)
        EXPECT_TRUE(wait_for_exit(pid, 20).has_value());
    }
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{});
}

} // namespace

namespace {

// Issue 50, item 3: --output naming an input of the run (the --drift-table or
// --config file, or a link to one) replaced it with the result, exit 0.
TEST(CliOutputOverInput, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
    const clitest::Scratch dir("over_input");
    const std::string table = dir / "law.csv", other = dir / "other.csv", link = dir / "link.csv";
    const std::string law = "v,b\n-10,3\n0,0.342\n10,-3\n";
    { std::ofstream(table) << law; }
    { std::ofstream(other) << law; }
    ASSERT_EQ(::symlink(other.c_str(), link.c_str()), 0);
    const clitest::Result print = clitest::run({"diffusivity", "--print-config"});
    const std::string config = dir / "run.toml";
    { std::ofstream(config) << print.out; }
    struct Case {
        clitest::Args args;
        std::string kept, flag;
    };
    const std::vector<Case> cases{
        {{"diffusivity", "--drift-table", table, "--excursions", "100", "--output", table}, table, "--drift-table"},
        {{"diffusivity", "--drift-table", other, "--excursions", "100", "--output", link}, other, "--drift-table"},
        {{"diffusivity", "--config", config, "--excursions", "100", "--output", config}, config, "--config"},
        {{"diffusivity", "--config", config, "--print-config", "--output", config}, config, "--config"}};
    for (const Case& c : cases) {
        const std::string before = clitest::slurp(c.kept);
        const clitest::Result r = clitest::run(c.args);
        EXPECT_EQ(r.code, 2) << clitest::describe(c.args) << "\n" << r.err;
        EXPECT_EQ(clitest::count_lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("is also the " + c.flag + " file"), std::string::npos) << r.err;
        EXPECT_EQ(clitest::slurp(c.kept), before) << c.kept;
    }
}

} // namespace
