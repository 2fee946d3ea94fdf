// SPDX-License-Identifier: BSD-3-Clause
// The atomic-file writer shared by --output and checkpoints
// (stickslip/detail/atomic_file.hpp), with the unnamed temporary and with the
// named fallback: the target changes only at commit, keeps its mode, and
// nothing is left behind by a discard, a failed commit, a signal handler's
// clean-up, or (removed by the next writer) a dead process.
#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <system_error>
#include <unistd.h>
#include <vector>

#include "stickslip/detail/atomic_file.hpp"

namespace {

using stickslip::detail::AtomicFile;
using stickslip::detail::FileTarget;
using Temporary = AtomicFile::Temporary;

std::vector<std::string> names_in(const std::string& dir) {
    std::vector<std::string> names;
    if (DIR* d = ::opendir(dir.c_str())) {
        while (const dirent* e = ::readdir(d))
            if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") names.push_back(e->d_name);
        ::closedir(d);
    }
    std::sort(names.begin(), names.end());
    return names;
}

std::string read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void put(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

mode_t mode_of(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 ? st.st_mode & 07777 : 0;
}

/// A directory of the test's own, emptied (one level deep) and removed at the end.
struct Dir {
    std::string path;
    Dir() {
        std::string base = ::testing::TempDir();
        if (base.empty() || base.back() != '/') base += '/';
        std::string t = base + "stickslip_atomic_XXXXXX";
        if (!::mkdtemp(t.data())) throw std::runtime_error("mkdtemp failed");
        path = t;
    }
    ~Dir() {
        for (const auto& n : names_in(path)) {
            const std::string p = path + "/" + n;
            for (const auto& m : names_in(p)) ::unlink((p + "/" + m).c_str());
            if (::unlink(p.c_str()) != 0) ::rmdir(p.c_str());
        }
        ::rmdir(path.c_str());
    }
    std::string operator/(const std::string& name) const { return path + "/" + name; }
};

/// A pid of this host that no process has: a child that has exited and been reaped.
pid_t dead_pid() {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    ::waitpid(pid, nullptr, 0);
    return pid;
}

class AtomicFileBoth : public ::testing::TestWithParam<Temporary> {};

// Guards the contract itself: the target is the old text until commit and the
// new text after, with nothing else in the folder at either moment (where the
// temporary is unnamed) or after (either way).
TEST_P(AtomicFileBoth, ReplacesAtCommitAndLeavesNothingElse) {
    const Dir dir;
    const std::string target = dir / "result.json";
    put(target, "old\n");
    {
        AtomicFile f(target, GetParam());
        f.write("new ");
        f.write("text\n");
        EXPECT_EQ(read(target), "old\n");
        if (f.unnamed()) {
            EXPECT_EQ(f.temporary_name(), "");
            EXPECT_EQ(names_in(dir.path), std::vector<std::string>{"result.json"});
        } else { // the fallback (asked for, or where the file system has no O_TMPFILE)
            EXPECT_EQ(names_in(dir.path).size(), 2u);
        }
        f.commit();
        EXPECT_EQ(read(target), "new text\n");
    }
    EXPECT_EQ(names_in(dir.path), std::vector<std::string>{"result.json"});
}

// Guards a run that fails: the target is untouched and the temporary gone.
TEST_P(AtomicFileBoth, DiscardLeavesTheTargetAsItWas) {
    const Dir dir;
    const std::string target = dir / "keep";
    put(target, "precious");
    {
        AtomicFile f(target, GetParam());
        f.write("half a result");
    }
    EXPECT_EQ(read(target), "precious");
    EXPECT_EQ(names_in(dir.path), std::vector<std::string>{"keep"});
}

// Guards the mode of a replaced file (a private 0600 file must not become
// world-readable) and of a new one (the umask, not the temporary's 0600).
TEST_P(AtomicFileBoth, KeepsTheModeOrFollowsTheUmask) {
    const Dir dir;
    const std::string kept = dir / "private", fresh = dir / "fresh";
    put(kept, "x");
    ASSERT_EQ(::chmod(kept.c_str(), 0600), 0);
    AtomicFile a(kept, GetParam());
    a.write("y");
    a.commit();
    EXPECT_EQ(mode_of(kept), 0600u);
    const mode_t old_umask = ::umask(027);
    AtomicFile b(fresh, GetParam());
    b.write("z");
    b.commit();
    ::umask(old_umask);
    EXPECT_EQ(mode_of(fresh), 0640u);
}

// Guards a commit that fails (here the target became a directory): a
// system_error naming the target, and no temporary left.
TEST_P(AtomicFileBoth, AFailedCommitThrowsAndLeavesNothing) {
    const Dir dir;
    const std::string target = dir / "t";
    AtomicFile f(target, GetParam());
    f.write("text");
    ASSERT_EQ(::mkdir(target.c_str(), 0755), 0);
    try {
        f.commit();
        ADD_FAILURE() << "the commit over a directory succeeded";
    } catch (const std::system_error& e) {
        EXPECT_NE(std::string(e.what()).find("'" + target + "'"), std::string::npos) << e.what();
        EXPECT_NE(e.code().value(), 0);
    }
    EXPECT_EQ(names_in(dir.path), std::vector<std::string>{"t"});
}

// Guards the clean-up of temporaries whose process is gone (a SIGKILL where
// no unnamed temporary could be had): the next writer of the target removes
// them, but not a live process's, nor another host's, nor another target's.
TEST_P(AtomicFileBoth, RemovesTheStaleTemporariesOfDeadProcesses) {
    const Dir dir;
    const std::string target = dir / "out.json";
    const std::string prefix = stickslip::detail::temporary_prefix(target);
    ASSERT_EQ(prefix.rfind(dir.path + "/out.json.tmp.", 0), 0u) << prefix;
    const std::string dead = prefix + std::to_string(dead_pid()) + ".0";
    const std::string live = prefix + std::to_string(::getppid()) + ".0";
    const std::string other_host = dir / "out.json.tmp.elsewhere.example.1.0";
    const std::string other_target = stickslip::detail::temporary_prefix(dir / "other") + std::to_string(dead_pid()) + ".0";
    for (const auto& p : {dead, live, other_host, other_target}) put(p, "x");
    AtomicFile f(target, GetParam());
    f.write("{}");
    f.commit();
    const auto names = names_in(dir.path);
    const auto has = [&](const std::string& p) {
        return std::find(names.begin(), names.end(), p.substr(p.rfind('/') + 1)) != names.end();
    };
    EXPECT_FALSE(has(dead)) << "a dead process's temporary stayed";
    EXPECT_TRUE(has(live));
    EXPECT_TRUE(has(other_host));
    EXPECT_TRUE(has(other_target));
    EXPECT_EQ(names.size(), 4u);
}

INSTANTIATE_TEST_SUITE_P(Temporaries, AtomicFileBoth, ::testing::Values(Temporary::unnamed_if_possible, Temporary::named),
                         [](const ::testing::TestParamInfo<Temporary>& p) {
                             return p.param == Temporary::named ? std::string("Named") : std::string("Unnamed");
                         });

// Guards what a signal handler relies on: a named temporary in flight is
// removed by remove_temporaries(), and its writer then leaves nothing either.
TEST(AtomicFile, RemoveTemporariesUnlinksANamedTemporaryInFlight) {
    const Dir dir;
    AtomicFile f(dir / "out", Temporary::named);
    ASSERT_NE(f.temporary_name(), "");
    EXPECT_EQ(::access(f.temporary_name().c_str(), F_OK), 0);
    stickslip::detail::remove_temporaries();
    EXPECT_EQ(names_in(dir.path), std::vector<std::string>{});
}

// Guards the opening errors: a missing folder and a folder that is a file
// throw at construction (before any work), naming the target.
TEST(AtomicFile, AnUnwritableFolderThrowsAtOnce) {
    const Dir dir;
    put(dir / "file", "x");
    for (const std::string& target : {dir / "missing/out", dir / "file/out"}) {
        for (Temporary how : {Temporary::unnamed_if_possible, Temporary::named}) {
            try {
                AtomicFile f(target, how);
                ADD_FAILURE() << target << " opened";
            } catch (const std::system_error& e) {
                EXPECT_TRUE(e.code().value() == ENOENT || e.code().value() == ENOTDIR) << e.what();
                EXPECT_NE(std::string(e.what()).find("'" + target + "'"), std::string::npos) << e.what();
            }
        }
    }
}

// Guards the resolution that keeps links links: a chain with relative targets
// leads to the file at its end, also when that does not exist yet.
TEST(ResolveTarget, FollowsAChainToAMissingFile) {
    const Dir dir;
    ASSERT_EQ(::mkdir((dir / "sub").c_str(), 0755), 0);
    ASSERT_EQ(::symlink("sub/end", (dir / "first").c_str()), 0);
    ASSERT_EQ(::symlink("first", (dir / "second").c_str()), 0);
    FileTarget t = stickslip::detail::resolve_target(dir / "second");
    EXPECT_EQ(t.error, 0);
    EXPECT_EQ(t.kind, FileTarget::Kind::missing);
    EXPECT_EQ(t.path, dir.path + "/sub/end");
    put(dir / "sub/end", "x");
    t = stickslip::detail::resolve_target(dir / "second");
    EXPECT_EQ(t.kind, FileTarget::Kind::regular);
    EXPECT_EQ(t.path, dir.path + "/sub/end");
    ASSERT_EQ(::symlink("loop", (dir / "loop").c_str()), 0);
    EXPECT_EQ(stickslip::detail::resolve_target(dir / "loop").error, ELOOP);
}

TEST(ResolveTarget, NamesFifosDirectoriesAndDescriptors) {
    const Dir dir;
    ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
    EXPECT_EQ(stickslip::detail::resolve_target(dir / "pipe").kind, FileTarget::Kind::fifo);
    EXPECT_EQ(stickslip::detail::resolve_target(dir.path).kind, FileTarget::Kind::directory);
    const FileTarget out = stickslip::detail::resolve_target("/dev/stdout");
    EXPECT_EQ(out.kind, FileTarget::Kind::descriptor);
    EXPECT_EQ(out.descriptor, STDOUT_FILENO);
    EXPECT_STREQ(stickslip::detail::describe(FileTarget::Kind::fifo), "a FIFO");
}

// Guards the comparison that refuses --output X --checkpoint X however X is
// spelt: "./", a link, a hard link; and distinct files are distinct.
TEST(ResolveTarget, SameFileSeesThroughSpellingsAndLinks) {
    const Dir dir;
    using stickslip::detail::resolve_target;
    using stickslip::detail::same_file;
    EXPECT_TRUE(same_file(resolve_target(dir / "new"), resolve_target(dir.path + "/./new")));
    EXPECT_FALSE(same_file(resolve_target(dir / "new"), resolve_target(dir / "other")));
    put(dir / "a", "x");
    ASSERT_EQ(::link((dir / "a").c_str(), (dir / "hard").c_str()), 0);
    ASSERT_EQ(::symlink("a", (dir / "soft").c_str()), 0);
    EXPECT_TRUE(same_file(resolve_target(dir / "a"), resolve_target(dir / "hard")));
    EXPECT_TRUE(same_file(resolve_target(dir / "a"), resolve_target(dir / "soft")));
    EXPECT_FALSE(same_file(resolve_target(dir / "a"), resolve_target(dir / "new")));
}

} // namespace
