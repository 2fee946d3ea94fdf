// SPDX-License-Identifier: BSD-3-Clause
// End-to-end tests of what the files a run writes may destroy or leave
// behind: nothing. A checkpoint never replaces what is at its path unless that
// is a checkpoint of the same run (a FIFO or a device is refused, a symlink's
// target is written, another run's checkpoint or any other file is refused);
// --output and --checkpoint never name one file; an unwritable checkpoint path
// is bad input (exit 2) naming the path as given; a checkpoint write that
// fails during the run is a warning, and the result is still written; and a
// run killed by SIGKILL, which no handler sees, leaves no temporary file.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <sys/resource.h>
#include <sys/stat.h>
#include <thread>

#include "cli_support.hpp"

namespace {

using namespace clitest;
using nlohmann::json;

/// A run of a fraction of a second through the block driver.
const Args kSmall{"diffusivity", "--scheme", "resolvent", "--dt", "1e-2", "--excursions", "2000", "--quiet", "--format", "json"};

bool is_checkpoint(const std::string& text) {
    try {
        return json::parse(text).value("format", "") == "stickslip-checkpoint";
    } catch (const std::exception&) {
        return false;
    }
}

/// Exit 2, nothing on stdout, one line on stderr holding each of `needles`.
void expect_bad_input(const Result& r, std::initializer_list<std::string> needles, const std::string& what) {
    EXPECT_EQ(r.code, 2) << what << ": " << r.err;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(count_lines(r.err), 1) << what << ": " << r.err;
    for (const auto& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << what << ": no '" << n << "' in: " << r.err;
}

/// Waits until `path` exists or process `pid` has ended (not reaped).
bool wait_for_file(const std::string& path, pid_t pid) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < end) {
        if (::access(path.c_str(), F_OK) == 0) return true;
        siginfo_t info {}; // WNOWAIT: ended, but left for the caller to reap
        if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid)
            return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
}

// --- what is at the checkpoint's path -----------------------------------------------------------

// Guards against renaming a regular file over a FIFO (the old checkpoint
// writer did): refused before any work, the FIFO still a FIFO, nothing beside.
TEST(CliCheckpointPath, FifoIsRefusedAndStaysAFifo) {
    const Scratch dir("ckpt_fifo");
    const std::string fifo = dir / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    const Result r = run(with(kSmall, {"--checkpoint", fifo}));
    expect_bad_input(r, {"--checkpoint", "'" + fifo + "'", "FIFO"}, "a FIFO");
    EXPECT_TRUE(S_ISFIFO(lstat_of(fifo).st_mode)) << "the FIFO was replaced";
    EXPECT_EQ(list_dir(dir.path), std::vector<std::string>{"pipe"});
}

// Guards the device case (as root, the old writer replaced `--checkpoint
// /dev/null` for every program on the machine). Run against a node of our own
// where we may make one (root), never against the system's.
TEST(CliCheckpointPath, CharacterDeviceIsRefusedAndStaysADevice) {
    const Scratch dir("ckpt_dev");
    const std::string node = dir / "null";
    struct stat sys {};
    if (::stat("/dev/null", &sys) != 0 || !S_ISCHR(sys.st_mode)) GTEST_SKIP() << "no /dev/null to copy";
    if (::mknod(node.c_str(), S_IFCHR | 0666, sys.st_rdev) != 0)
        GTEST_SKIP() << "cannot make a device node here (" << std::strerror(errno) << "): needs root";
    const Result r = run(with(kSmall, {"--checkpoint", node}));
    expect_bad_input(r, {"--checkpoint", "'" + node + "'", "character device"}, "a character device");
    const struct stat after = lstat_of(node);
    EXPECT_TRUE(S_ISCHR(after.st_mode)) << "the device was replaced";
    EXPECT_EQ(after.st_rdev, sys.st_rdev);
    EXPECT_EQ(list_dir(dir.path), std::vector<std::string>{"null"});
}

// Guards a symlink (the old writer replaced the link by a regular file): the
// link stays a link, its target, missing at first, holds the checkpoint, and
// the link resumes the run.
TEST(CliCheckpointPath, SymlinkStaysALinkAndItsTargetIsWritten) {
    const Scratch dir("ckpt_link");
    const std::string link = dir / "run.ckpt";
    ASSERT_EQ(::symlink("saved.ckpt", link.c_str()), 0);
    const auto first = run(with(kSmall, {"--checkpoint", link}));
    EXPECT_EQ(first.code, 0) << first.err;
    EXPECT_TRUE(S_ISLNK(lstat_of(link).st_mode)) << "the link was replaced";
    EXPECT_EQ(link_of(link), "saved.ckpt");
    EXPECT_TRUE(is_checkpoint(slurp(dir / "saved.ckpt")));
    const auto resumed = run(with(kSmall, {"--checkpoint", link, "--resume", link}));
    EXPECT_EQ(resumed.code, 0) << resumed.err;
    EXPECT_EQ(resumed.err, "");
    EXPECT_TRUE(S_ISLNK(lstat_of(link).st_mode));
    EXPECT_EQ(list_dir(dir.path), (std::vector<std::string>{"run.ckpt", "saved.ckpt"}));
}

// --- what is already in the file -------------------------------------------------------------------

// Guards another run's saved work (the old writer overwrote it silently at
// the first checkpoint): a checkpoint of other settings, and a file that is
// no checkpoint at all, are refused before any work and kept byte for byte.
TEST(CliCheckpointPath, AnotherRunsCheckpointOrAnyOtherFileIsRefused) {
    const Scratch dir("ckpt_other");
    const std::string theirs = dir / "theirs.ckpt", notes = dir / "notes.txt";
    ASSERT_EQ(run(with(kSmall, {"--checkpoint", theirs})).code, 0);
    const std::string saved = slurp(theirs);
    ASSERT_TRUE(is_checkpoint(saved));
    const Result other = run(with(kSmall, {"--seed", "2", "--checkpoint", theirs}));
    expect_bad_input(other, {"--checkpoint", "'" + theirs + "'", "seed = 1, this run has seed = 2"}, "another seed");
    EXPECT_EQ(slurp(theirs), saved);

    { std::ofstream(notes) << "a week of notes\n"; }
    const Result foreign = run(with(kSmall, {"--checkpoint", notes}));
    expect_bad_input(foreign, {"--checkpoint", "'" + notes + "'", "not a stickslip checkpoint"}, "not a checkpoint");
    EXPECT_EQ(slurp(notes), "a week of notes\n");
    EXPECT_EQ(list_dir(dir.path), (std::vector<std::string>{"notes.txt", "theirs.ckpt"}));
}

// Guards the one file a run may start afresh over, a checkpoint of its own
// settings, and that it says so (one line, pointing at --resume), while the
// --resume file of the same path is no cause for a word.
TEST(CliCheckpointPath, ThisRunsOwnCheckpointIsOverwrittenWithAWarning) {
    const Scratch dir("ckpt_own");
    const std::string own = dir / "run.ckpt";
    ASSERT_EQ(run(with(kSmall, {"--checkpoint", own})).code, 0);
    const Result again = run(with(kSmall, {"--checkpoint", own}));
    EXPECT_EQ(again.code, 0) << again.err;
    EXPECT_EQ(count_lines(again.err), 1) << again.err;
    EXPECT_NE(again.err.find("warning: --checkpoint: '" + own + "'"), std::string::npos) << again.err;
    EXPECT_NE(again.err.find("--resume"), std::string::npos) << again.err;
    EXPECT_TRUE(is_checkpoint(slurp(own)));
    const Result resumed = run(with(kSmall, {"--checkpoint", own, "--resume", own}));
    EXPECT_EQ(resumed.code, 0) << resumed.err;
    EXPECT_EQ(resumed.err, "");
}

// Guards the result replacing the checkpoint at the end of a run (all that a
// long run may have): one path for --output and --checkpoint, however spelt,
// is refused before any work and creates nothing.
TEST(CliCheckpointPath, OutputAndCheckpointOnOneFileAreRefused) {
    const Scratch dir("ckpt_same");
    const std::string file = dir / "run.json";
    ASSERT_EQ(::symlink("run.json", (dir / "alias").c_str()), 0);
    for (const std::string& output : {file, dir.path + "/./run.json", dir / "alias"}) {
        const Result r = run(with(kSmall, {"--output", output, "--checkpoint", file}));
        expect_bad_input(r, {"--output", "'" + output + "'", "--checkpoint"}, output);
        EXPECT_EQ(list_dir(dir.path), std::vector<std::string>{"alias"}) << output;
    }
}

// Guards an unwritable checkpoint path: bad input (exit 2, not the old exit 1)
// found before any work, naming --checkpoint and the path the user gave (not
// a temporary's). A folder that is a file works as root too.
TEST(CliCheckpointPath, UnwritablePathIsBadInputNamingIt) {
    const Scratch dir("ckpt_unwritable");
    { std::ofstream(dir / "file") << "x\n"; }
    for (const std::string& path : {dir / "missing/run.ckpt", dir / "file/run.ckpt"}) {
        const Result r = run(with(kSmall, {"--checkpoint", path}));
        expect_bad_input(r, {"--checkpoint", "cannot write '" + path + "'"}, path);
    }
    EXPECT_EQ(list_dir(dir.path), std::vector<std::string>{"file"});
}

// --- during the run ---------------------------------------------------------------------------------

// Guards a checkpoint write that fails during the run (the old writer ended
// the run with exit 1 and no result): one warning naming --checkpoint and the
// path, and the complete result, exit 0. The checkpoint's folder is replaced
// by a file once the first checkpoint is written, which defeats root too.
TEST(CliCheckpointDuringRun, AFailedWriteWarnsAndTheResultIsStillWritten) {
    const Scratch dir("ckpt_midrun");
    const std::string sub = dir / "sub", ckpt = sub + "/run.ckpt", out = dir / "out.json";
    ASSERT_EQ(::mkdir(sub.c_str(), 0755), 0);
    const Args args{"diffusivity", "--scheme", "resolvent", "--dt", "1e-2", "--excursions", "400000", "--threads", "2",
                    "--quiet", "--format", "json", "--checkpoint", ckpt, "--checkpoint-every", "0.05", "--output", out};
    const pid_t pid = start(args, "/dev/null", dir / "err.txt");
    ASSERT_GT(pid, 0);
    const bool started = wait_for_file(ckpt, pid);
    // Moved rather than removed, so that the test cleans up what it made.
    const bool moved = ::rename(sub.c_str(), (dir / "moved").c_str()) == 0;
    { std::ofstream(sub) << "not a folder\n"; }
    const auto status = wait_for_exit(pid, 120);
    const std::string err = slurp(dir / "err.txt");
    ::unlink((dir / "moved/run.ckpt").c_str());
    ::rmdir((dir / "moved").c_str());
    ASSERT_TRUE(started && moved) << "the run wrote no first checkpoint: " << err;
    ASSERT_TRUE(status.has_value()) << "the run did not end";
    EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << "status " << *status << ": " << err;
    EXPECT_EQ(count_lines(err), 1) << err;
    EXPECT_NE(err.find("warning: --checkpoint: cannot write '" + ckpt + "'"), std::string::npos) << err;
    const json j = json::parse(slurp(out));
    EXPECT_EQ(j.at("completed").get<std::uint64_t>(), 400000u);
    EXPECT_FALSE(j.value("interrupted", false));
    EXPECT_EQ(list_dir(dir.path), (std::vector<std::string>{"err.txt", "out.json", "sub"}));
}

// --- SIGKILL ----------------------------------------------------------------------------------------

// Guards a run killed by SIGKILL, which no handler sees, while its --output
// temporary is open (the old named temporary stayed in 9 of 9 tries): nothing
// is left in the folder, again and again.
TEST(CliKilled, SigkillDuringARunLeavesNoOutputTemporary) {
    const Scratch dir("kill_output");
    const Args args{"diffusivity", "--scheme", "resolvent", "--dt", "1e-4", "--excursions", "100000000", "--quiet",
                    "--format", "json", "--output", dir / "out.json"};
    for (int attempt = 0; attempt < 4; ++attempt) {
        const pid_t pid = start(args, "/dev/null", "/dev/null");
        ASSERT_GT(pid, 0);
        const bool opened = holds_file_in(pid, dir.path);
        std::this_thread::sleep_for(std::chrono::milliseconds(40 * attempt)); // before any work, and during it
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
        ASSERT_TRUE(opened) << "attempt " << attempt << ": the run ended before opening its output";
        EXPECT_EQ(list_dir(dir.path), std::vector<std::string>{}) << "attempt " << attempt;
    }
}

// Guards the same for checkpoints, written every round (about every
// millisecond here, so that kills land while one is being written; the old
// writer's named temporaries stayed): after each kill the folder holds the
// checkpoint and at most the name of the one being renamed into place at that
// very instant (a few microseconds between linkat() and rename()), which the
// next write removes, since its process is gone.
TEST(CliKilled, SigkillDuringCheckpointWritesLeavesNoTemporary) {
    const Scratch dir("kill_ckpt");
    const std::string ckpt = dir / "run.ckpt";
    const Args args{"diffusivity", "--scheme", "resolvent", "--dt", "1e-2", "--excursions", "100000000", "--quiet",
                    "--format", "json", "--checkpoint", ckpt, "--resume", ckpt, "--checkpoint-every", "0.001"};
    for (int attempt = 0; attempt < 10; ++attempt) {
        const pid_t pid = start(args, "/dev/null", "/dev/null");
        ASSERT_GT(pid, 0);
        const bool started = wait_for_file(ckpt, pid);
        std::this_thread::sleep_for(std::chrono::milliseconds(100 + 23 * attempt));
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
        ASSERT_TRUE(started) << "attempt " << attempt << ": no checkpoint";
        EXPECT_TRUE(is_checkpoint(slurp(ckpt))) << "attempt " << attempt;
        const std::string in_rename = "." + std::to_string(pid) + ".";
        for (const auto& name : list_dir(dir.path)) {
            if (name == "run.ckpt") continue;
            EXPECT_TRUE(name.rfind("run.ckpt.tmp.", 0) == 0 && name.find(in_rename) != std::string::npos)
                << "attempt " << attempt << " left " << name;
        }
    }
    // One more run, stopped gracefully after a few writes.
    const pid_t pid = start(args, "/dev/null", "/dev/null");
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::kill(pid, SIGTERM);
    const auto status = wait_for_exit(pid, 30);
    ASSERT_TRUE(status.has_value());
    EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 143) << "status " << *status;
    EXPECT_EQ(list_dir(dir.path), std::vector<std::string>{"run.ckpt"});
}

} // namespace
