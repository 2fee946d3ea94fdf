// SPDX-License-Identifier: BSD-3-Clause
// default_threads(): --threads 0 follows the CPUs this process is given (the
// affinity mask, a cgroup CPU quota, Slurm's CPUs per task, the MPI ranks on
// the node), not the machine's count, and the reports say which decided.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sched.h>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "stickslip/threads.hpp"

namespace {

using namespace stickslip;

// --- the rule -------------------------------------------------------------------------------

ThreadChoice choose(unsigned hardware, unsigned affinity, double quota = 0, unsigned slurm = 0, unsigned ranks = 0) {
    return default_threads(MachineShare{hardware, affinity, quota, slurm, ranks});
}

TEST(DefaultThreads, TakesTheTightestLimit) {
    EXPECT_EQ(choose(16, 16).threads, 16u);
    EXPECT_EQ(choose(16, 16).from, "hardware");
    EXPECT_EQ(choose(16, 0).threads, 16u); // affinity unknown
    EXPECT_EQ(choose(16, 1).threads, 1u);  // taskset -c 0
    EXPECT_EQ(choose(16, 1).from, "affinity");
    EXPECT_EQ(choose(16, 16, 2.0).threads, 2u); // cgroup v2 cpu.max "200000 100000"
    EXPECT_EQ(choose(16, 16, 2.0).from, "cpu-quota");
    EXPECT_EQ(choose(16, 16, 1.5).threads, 2u); // rounded up
    EXPECT_EQ(choose(16, 16, 0.1).threads, 1u);
    EXPECT_EQ(choose(16, 4, 8.0).threads, 4u); // the mask is tighter than the quota
    EXPECT_EQ(choose(16, 4, 8.0).from, "affinity");
    EXPECT_EQ(choose(16, 16, 0, 3).threads, 3u);
    EXPECT_EQ(choose(16, 16, 0, 3).from, "slurm");
    EXPECT_EQ(choose(0, 0).threads, 1u); // nothing known
    EXPECT_EQ(choose(0, 6).threads, 6u);
}

TEST(DefaultThreads, SharesTheNodeAmongUnboundRanks) {
    // mpirun -np 2 --bind-to none on 16 CPUs: 8 each.
    EXPECT_EQ(choose(16, 16, 0, 0, 2).threads, 8u);
    EXPECT_EQ(choose(16, 16, 0, 0, 2).from, "hardware+local-ranks");
    EXPECT_EQ(choose(16, 16, 4.0, 0, 2).threads, 2u); // a container's quota is shared too
    EXPECT_EQ(choose(16, 16, 4.0, 0, 2).from, "cpu-quota+local-ranks");
    EXPECT_EQ(choose(4, 4, 0, 0, 8).threads, 1u); // never below one
    // A rank bound to CPUs of its own (mpirun's default binding, --cpus-per-rank)
    // uses them; so does a Slurm task with its CPUs per task.
    EXPECT_EQ(choose(16, 8, 0, 0, 2).threads, 8u);
    EXPECT_EQ(choose(16, 8, 0, 0, 2).from, "affinity");
    EXPECT_EQ(choose(16, 16, 0, 4, 2).threads, 4u);
    EXPECT_EQ(choose(16, 16, 0, 4, 2).from, "slurm");
    EXPECT_EQ(choose(16, 16, 0, 0, 1).from, "hardware"); // one rank: nothing shared
}

// --- cgroups, from a fake file system -----------------------------------------------------------

struct FakeRoot {
    std::string path;
    FakeRoot() {
        char dir[] = "/tmp/stickslip_cgroup_XXXXXX";
        path = ::mkdtemp(dir) ? dir : "";
    }
    ~FakeRoot() {
        if (!path.empty()) (void)std::system(("rm -rf '" + path + "'").c_str());
    }
    void write(const std::string& file, const std::string& text) const {
        const std::string full = path + file;
        (void)std::system(("mkdir -p '" + full.substr(0, full.rfind('/')) + "'").c_str());
        std::ofstream(full) << text;
    }
};

const char* kMountinfoV2 = "24 1 0:22 / /sys/fs/cgroup rw,nosuid - cgroup2 cgroup2 rw,nsdelegate\n"
                           "25 1 0:23 / /proc rw - proc proc rw\n";

TEST(CgroupQuota, ReadsCgroupV2CpuMaxUpToTheRoot) {
    const FakeRoot root;
    ASSERT_FALSE(root.path.empty());
    root.write("/proc/self/mountinfo", kMountinfoV2);
    root.write("/proc/self/cgroup", "0::/user.slice/job/task\n");
    EXPECT_EQ(cgroup_cpu_quota(root.path), 0.0); // no cpu.max files: no limit
    root.write("/sys/fs/cgroup/user.slice/job/task/cpu.max", "max 100000\n");
    EXPECT_EQ(cgroup_cpu_quota(root.path), 0.0);
    root.write("/sys/fs/cgroup/user.slice/job/cpu.max", "300000 100000\n");
    EXPECT_DOUBLE_EQ(cgroup_cpu_quota(root.path), 3.0); // a parent's limit binds its children
    root.write("/sys/fs/cgroup/user.slice/job/task/cpu.max", "150000 100000\n");
    EXPECT_DOUBLE_EQ(cgroup_cpu_quota(root.path), 1.5); // the tightest
    root.write("/sys/fs/cgroup/cpu.max", "50000 100000\n");
    EXPECT_DOUBLE_EQ(cgroup_cpu_quota(root.path), 0.5);
}

TEST(CgroupQuota, ReadsANamespacedContainer) {
    // Inside a container with its own cgroup namespace, the process is at "/"
    // and the mount is the container's cgroup.
    const FakeRoot root;
    root.write("/proc/self/mountinfo", kMountinfoV2);
    root.write("/proc/self/cgroup", "0::/\n");
    root.write("/sys/fs/cgroup/cpu.max", "200000 100000\n");
    EXPECT_DOUBLE_EQ(cgroup_cpu_quota(root.path), 2.0);
}

TEST(CgroupQuota, ReadsCgroupV1CfsQuota) {
    const FakeRoot root;
    root.write("/proc/self/mountinfo",
               "30 22 0:27 / /sys/fs/cgroup rw - tmpfs tmpfs rw\n"
               "31 30 0:28 / /sys/fs/cgroup/cpu,cpuacct rw,nosuid - cgroup cgroup rw,cpu,cpuacct\n"
               "33 30 0:30 / /sys/fs/cgroup/memory rw - cgroup cgroup rw,memory\n");
    root.write("/proc/self/cgroup", "4:memory:/docker/abc\n3:cpu,cpuacct:/docker/abc\n");
    root.write("/sys/fs/cgroup/cpu,cpuacct/docker/abc/cpu.cfs_quota_us", "-1\n");
    root.write("/sys/fs/cgroup/cpu,cpuacct/docker/abc/cpu.cfs_period_us", "100000\n");
    EXPECT_EQ(cgroup_cpu_quota(root.path), 0.0); // -1: no limit
    root.write("/sys/fs/cgroup/cpu,cpuacct/docker/abc/cpu.cfs_quota_us", "250000\n");
    EXPECT_DOUBLE_EQ(cgroup_cpu_quota(root.path), 2.5);
}

TEST(CgroupQuota, ReadsAV1MountOfPartOfTheHierarchy) {
    // Docker without a cgroup namespace: the container's cgroup is mounted
    // (root /docker/abc) where the host's would be.
    const FakeRoot root;
    root.write("/proc/self/mountinfo", "31 30 0:28 /docker/abc /sys/fs/cgroup/cpu ro - cgroup cgroup rw,cpu\n");
    root.write("/proc/self/cgroup", "3:cpu:/docker/abc\n");
    root.write("/sys/fs/cgroup/cpu/cpu.cfs_quota_us", "100000\n");
    root.write("/sys/fs/cgroup/cpu/cpu.cfs_period_us", "100000\n");
    EXPECT_DOUBLE_EQ(cgroup_cpu_quota(root.path), 1.0);
}

TEST(CgroupQuota, NothingToReadIsNoLimit) {
    const FakeRoot root;
    EXPECT_EQ(cgroup_cpu_quota(root.path), 0.0);
    root.write("/proc/self/mountinfo", "garbage\n\n- - -\n");
    root.write("/proc/self/cgroup", "nonsense\n0::\n");
    EXPECT_EQ(cgroup_cpu_quota(root.path), 0.0);
    EXPECT_GE(cgroup_cpu_quota(), 0.0); // this machine's, whatever it is
}

// --- this process ---------------------------------------------------------------------------

/// Sets an environment variable for the test's lifetime.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value) ::setenv(name, value, 1);
        else ::unsetenv(name);
    }
    ~ScopedEnv() {
        if (old_) ::setenv(name_.c_str(), old_->c_str(), 1);
        else ::unsetenv(name_.c_str());
    }

private:
    std::string name_;
    std::optional<std::string> old_;
};

TEST(DefaultThreads, ReadsTheLaunchersEnvironment) {
    const ScopedEnv a("OMPI_COMM_WORLD_LOCAL_SIZE", nullptr), b("MPI_LOCALNRANKS", nullptr),
        c("MV2_COMM_WORLD_LOCAL_SIZE", nullptr), d("SLURM_STEP_TASKS_PER_NODE", nullptr), e("SLURM_NODEID", nullptr),
        f("SLURM_CPUS_PER_TASK", nullptr);
    EXPECT_EQ(inspect_machine().local_ranks, 0u);
    {
        const ScopedEnv ompi("OMPI_COMM_WORLD_LOCAL_SIZE", "2");
        EXPECT_EQ(inspect_machine().local_ranks, 2u);
    }
    {
        const ScopedEnv hydra("MPI_LOCALNRANKS", "3");
        EXPECT_EQ(inspect_machine().local_ranks, 3u);
    }
    {
        const ScopedEnv list("SLURM_STEP_TASKS_PER_NODE", "2(x3),1"), node("SLURM_NODEID", "3");
        EXPECT_EQ(inspect_machine().local_ranks, 1u);
        const ScopedEnv node1("SLURM_NODEID", "1");
        EXPECT_EQ(inspect_machine().local_ranks, 2u);
    }
    {
        const ScopedEnv cpus("SLURM_CPUS_PER_TASK", "3");
        EXPECT_EQ(inspect_machine().slurm_cpus, 3u);
        EXPECT_LE(default_threads().threads, 3u);
        const ScopedEnv junk("SLURM_CPUS_PER_TASK", "three");
        EXPECT_EQ(inspect_machine().slurm_cpus, 0u);
    }
}

std::optional<int> first_allowed_cpu() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (::sched_getaffinity(0, sizeof set, &set) != 0) return std::nullopt;
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
        if (CPU_ISSET(cpu, &set)) return cpu;
    return std::nullopt;
}

TEST(DefaultThreads, FollowsThisThreadsAffinityMask) {
    cpu_set_t saved;
    CPU_ZERO(&saved);
    ASSERT_EQ(::sched_getaffinity(0, sizeof saved, &saved), 0);
    const auto cpu = first_allowed_cpu();
    ASSERT_TRUE(cpu);
    EXPECT_EQ(inspect_machine().affinity, static_cast<unsigned>(CPU_COUNT(&saved)));
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(*cpu, &one);
    ASSERT_EQ(::sched_setaffinity(0, sizeof one, &one), 0);
    const MachineShare m = inspect_machine();
    const ThreadChoice c = default_threads();
    ::sched_setaffinity(0, sizeof saved, &saved);
    EXPECT_EQ(m.affinity, 1u);
    EXPECT_EQ(c.threads, 1u);
    if (m.hardware > 1) {
        EXPECT_EQ(c.from, "affinity");
    }
}

#ifdef STICKSLIP_CLI_PATH
/// stdout of a shell command, or nullopt when it fails.
std::optional<std::string> output_of(const std::string& command) {
    FILE* p = ::popen(command.c_str(), "r");
    if (!p) return std::nullopt;
    std::string out;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    return ::pclose(p) == 0 ? std::optional<std::string>(out) : std::nullopt;
}

TEST(DefaultThreads, TasksetRunReportsOneThread) {
    // The run used std::thread::hardware_concurrency() whatever taskset said.
    if (std::system("command -v taskset >/dev/null 2>&1") != 0) GTEST_SKIP() << "no taskset (util-linux)";
    const auto cpu = first_allowed_cpu();
    ASSERT_TRUE(cpu);
    const std::string run = std::string(STICKSLIP_CLI_PATH) +
                            " diffusivity --scheme resolvent --dt 1e-3 --excursions 1024 --format json --quiet";
    const auto pinned = output_of("taskset -c " + std::to_string(*cpu) + " " + run + " --threads 0");
    ASSERT_TRUE(pinned);
    const auto j = nlohmann::json::parse(*pinned);
    EXPECT_EQ(j["work"]["threads"], 1) << j["work"].dump();
    if (std::thread::hardware_concurrency() > 1) {
        EXPECT_EQ(j["work"]["threads_from"], "affinity") << j["work"].dump();
    }
    // Given a count, the run says so; with few blocks, that they limited it.
    const auto given = output_of(run + " --threads 2");
    ASSERT_TRUE(given);
    EXPECT_EQ(nlohmann::json::parse(*given)["work"]["threads_from"], "option");
    const auto small = output_of(std::string(STICKSLIP_CLI_PATH) +
                                 " diffusivity --scheme resolvent --dt 1e-3 --excursions 64 --threads 4 --format json "
                                 "--quiet");
    ASSERT_TRUE(small);
    const auto s = nlohmann::json::parse(*small);
    EXPECT_EQ(s["work"]["threads"], 1);
    EXPECT_EQ(s["work"]["threads_from"], "option+blocks");
}
#endif

} // namespace
