// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/threads.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sched.h>
#include <sstream>
#include <string_view>
#include <thread>
#include <vector>

#include "stickslip/number_text.hpp"

namespace stickslip {

namespace {

std::optional<std::string> read_text(const std::string& path) {
    std::ifstream in(path);
    if (!in) return std::nullopt;
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::vector<std::string> split(std::string_view s, char sep) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (;;) {
        const std::size_t k = s.find(sep, start);
        out.emplace_back(s.substr(start, k == std::string_view::npos ? std::string_view::npos : k - start));
        if (k == std::string_view::npos) return out;
        start = k + 1;
    }
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) s.pop_back();
    return s;
}

/// mountinfo writes a space in a path as \040 (and tab, newline, backslash likewise).
std::string unescape_mount_path(const std::string& s) {
    std::string out;
    for (std::size_t k = 0; k < s.size(); ++k) {
        if (s[k] == '\\' && k + 3 < s.size()) {
            const std::string digits = s.substr(k + 1, 3);
            if (digits.find_first_not_of("01234567") == std::string::npos) {
                out += static_cast<char>((digits[0] - '0') * 64 + (digits[1] - '0') * 8 + (digits[2] - '0'));
                k += 3;
                continue;
            }
        }
        out += s[k];
    }
    return out;
}

struct CgroupMount {
    std::string root;       ///< the hierarchy's path that is mounted
    std::string mountpoint; ///< where
};

/// The directory of cgroup `path` under a mount of its hierarchy.
std::string cgroup_dir(const std::string& prefix, const CgroupMount& m, const std::string& path) {
    std::string rel = path;
    if (m.root != "/" && rel.compare(0, m.root.size(), m.root) == 0) rel = rel.substr(m.root.size());
    else if (m.root != "/") rel = ""; // not under the mounted part (a namespace's view): its top is ours
    std::string dir = prefix + m.mountpoint + rel;
    while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
    return dir;
}

/// Calls `limit(dir)` for `dir` and each parent up to the mount point, and
/// returns the smallest positive limit found (0: none).
template <class Limit>
double tightest(const std::string& dir, const std::string& top, Limit limit) {
    double best = 0;
    std::string d = dir;
    for (;;) {
        const double q = limit(d);
        if (q > 0 && (best == 0 || q < best)) best = q;
        if (d.size() <= top.size()) return best;
        const auto slash = d.rfind('/');
        if (slash == std::string::npos || slash < top.size()) d = top;
        else d = d.substr(0, slash);
    }
}

double read_positive(const std::string& path) {
    const auto text = read_text(path);
    if (!text) return 0;
    const auto x = number_text::read_double(trimmed(*text));
    return x && *x > 0 && std::isfinite(*x) ? *x : 0;
}

/// cgroup v2: "max 100000" (no limit) or "QUOTA PERIOD" [us].
double cpu_max(const std::string& dir) {
    const auto text = read_text(dir + "/cpu.max");
    if (!text) return 0;
    const std::vector<std::string> f = split(trimmed(*text), ' ');
    if (f.size() != 2 || f[0] == "max") return 0;
    const auto quota = number_text::read_double(f[0]), period = number_text::read_double(f[1]);
    if (!quota || !period || !(*quota > 0) || !(*period > 0)) return 0;
    return *quota / *period;
}

/// cgroup v1: cpu.cfs_quota_us (-1: no limit) over cpu.cfs_period_us.
double cfs_quota(const std::string& dir) {
    const double quota = read_positive(dir + "/cpu.cfs_quota_us");
    const double period = read_positive(dir + "/cpu.cfs_period_us");
    return quota > 0 && period > 0 ? quota / period : 0;
}

unsigned affinity_count() {
    // Sized for machines beyond CPU_SETSIZE (1024): grow until the kernel's mask fits.
    for (int cpus = 1024; cpus <= (1 << 20); cpus *= 4) {
        cpu_set_t* set = CPU_ALLOC(cpus);
        if (!set) return 0;
        const std::size_t size = CPU_ALLOC_SIZE(cpus);
        CPU_ZERO_S(size, set);
        if (::sched_getaffinity(0, size, set) == 0) {
            const int n = CPU_COUNT_S(size, set);
            CPU_FREE(set);
            return n > 0 ? static_cast<unsigned>(n) : 0;
        }
        CPU_FREE(set);
        if (errno != EINVAL) return 0;
    }
    return 0;
}

unsigned env_count(const char* name) {
    const char* v = std::getenv(name);
    if (!v) return 0;
    const auto n = number_text::read_unsigned(v);
    return n && *n > 0 && *n < 1'000'000 ? static_cast<unsigned>(*n) : 0;
}

/// Slurm's tasks of this step on this node: SLURM_STEP_TASKS_PER_NODE is a
/// list such as "2(x3),1" (nodes 0-2 run 2 tasks, node 3 one), indexed by
/// SLURM_NODEID.
unsigned slurm_local_tasks() {
    const char* list = std::getenv("SLURM_STEP_TASKS_PER_NODE");
    const char* node = std::getenv("SLURM_NODEID");
    if (!list || !node) return 0;
    const auto id = number_text::read_unsigned(node);
    if (!id) return 0;
    std::uint64_t first = 0; // index of the first node of the current item
    for (const std::string& item : split(list, ',')) {
        const auto open = item.find("(x");
        const auto tasks = number_text::read_unsigned(item.substr(0, open));
        std::uint64_t repeat = 1;
        if (open != std::string::npos) {
            if (item.back() != ')') return 0;
            const auto r = number_text::read_unsigned(item.substr(open + 2, item.size() - open - 3));
            if (!r) return 0;
            repeat = *r;
        }
        if (!tasks) return 0;
        if (*id < first + repeat) return *tasks < 1'000'000 ? static_cast<unsigned>(*tasks) : 0;
        first += repeat;
    }
    return 0;
}

} // namespace

double cgroup_cpu_quota(const std::string& root) {
    const auto cgroups = read_text(root + "/proc/self/cgroup");
    const auto mountinfo = read_text(root + "/proc/self/mountinfo");
    if (!cgroups || !mountinfo) return 0;
    std::optional<CgroupMount> v2, v1;
    std::istringstream mounts(*mountinfo);
    for (std::string line; std::getline(mounts, line);) {
        // ID PARENT MAJ:MIN ROOT MOUNTPOINT OPTIONS [OPTIONAL...] - FSTYPE SOURCE SUPEROPTIONS
        const std::vector<std::string> f = split(line, ' ');
        const auto dash = std::find(f.begin(), f.end(), "-");
        if (f.size() < 5 || dash == f.end() || f.end() - dash < 4) continue;
        const std::string& type = *(dash + 1);
        const CgroupMount m{unescape_mount_path(f[3]), unescape_mount_path(f[4])};
        if (type == "cgroup2" && !v2) v2 = m;
        if (type == "cgroup" && !v1) {
            const std::vector<std::string> options = split(*(dash + 3), ',');
            if (std::find(options.begin(), options.end(), "cpu") != options.end()) v1 = m;
        }
    }
    double best = 0;
    const auto take = [&best](double q) {
        if (q > 0 && (best == 0 || q < best)) best = q;
    };
    std::istringstream lines(*cgroups);
    for (std::string line; std::getline(lines, line);) {
        // HIERARCHY:CONTROLLERS:PATH; v2 is "0::PATH".
        const auto c1 = line.find(':');
        const auto c2 = c1 == std::string::npos ? std::string::npos : line.find(':', c1 + 1);
        if (c2 == std::string::npos) continue;
        const std::string controllers = line.substr(c1 + 1, c2 - c1 - 1), path = line.substr(c2 + 1);
        if (controllers.empty() && line.compare(0, c1, "0") == 0 && v2) {
            const std::string top = root + v2->mountpoint;
            take(tightest(cgroup_dir(root, *v2, path), top, cpu_max));
        } else if (v1) {
            const std::vector<std::string> names = split(controllers, ',');
            if (std::find(names.begin(), names.end(), "cpu") == names.end()) continue;
            const std::string top = root + v1->mountpoint;
            take(tightest(cgroup_dir(root, *v1, path), top, cfs_quota));
        }
    }
    return best;
}

MachineShare inspect_machine() {
    MachineShare m;
    m.hardware = std::thread::hardware_concurrency();
    m.affinity = affinity_count();
    m.cpu_quota = cgroup_cpu_quota();
    m.slurm_cpus = env_count("SLURM_CPUS_PER_TASK");
    for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "MV2_COMM_WORLD_LOCAL_SIZE"})
        if ((m.local_ranks = env_count(name)) > 0) break;
    if (m.local_ranks == 0) m.local_ranks = slurm_local_tasks();
    return m;
}

ThreadChoice default_threads(const MachineShare& m) {
    ThreadChoice c;
    unsigned n = m.hardware > 0 ? m.hardware : std::max(m.affinity, 1u);
    c.from = "hardware";
    const bool bound = m.affinity > 0 && m.affinity < n; // the launcher (or taskset) gave this process its CPUs
    if (m.affinity > 0 && m.affinity < n) {
        n = m.affinity;
        c.from = "affinity";
    }
    if (m.cpu_quota > 0) {
        // Rounded up: a quota of 1.5 CPUs keeps two threads busy 75% of the time.
        const double q = std::ceil(m.cpu_quota);
        if (q < n) {
            n = static_cast<unsigned>(std::max(q, 1.0));
            c.from = "cpu-quota";
        }
    }
    if (m.slurm_cpus > 0 && m.slurm_cpus < n) {
        n = m.slurm_cpus;
        c.from = "slurm";
    }
    // The ranks of a job on one node share its CPUs, unless each has CPUs of
    // its own: Slurm's CPUs per task, or a binding to part of the machine.
    if (m.local_ranks > 1 && c.from != "slurm" && !bound) {
        n = std::max(1u, n / m.local_ranks);
        c.from += "+local-ranks";
    }
    c.threads = std::max(n, 1u);
    return c;
}

ThreadChoice default_threads() { return default_threads(inspect_machine()); }

} // namespace stickslip
