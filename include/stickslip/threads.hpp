// SPDX-License-Identifier: BSD-3-Clause
// stickslip/threads.hpp -- how many worker threads a run takes by default.
//
// std::thread::hardware_concurrency() counts the machine's CPUs, not the ones
// this process is given: under `taskset -c 0`, a container's CPU quota, a
// batch system's allocation or `mpirun -np 2` on one node, a run that took it
// would start more threads than it can run at once, and they would take turns
// on the CPUs it has (slower, and unfair to whoever shares the node).
// default_threads() takes the smallest of what the machine has, the affinity
// mask, the cgroup's CPU bandwidth quota and Slurm's CPUs per task, and shares
// it among the MPI ranks on the node when the launcher has not bound each rank
// to CPUs of its own. It says which of these decided, for the reports
// (`work.threads_from`). The thread count never changes a result's bits.
#pragma once

/// \file
/// The default number of worker threads (RunControl::threads = 0): the CPUs
/// this process may actually use, and how that was found.

#include <string>

namespace stickslip {

/// What default_threads() reads of the machine this process runs on. Zero
/// means unknown or no limit.
struct MachineShare {
    unsigned hardware = 0;   ///< CPUs of the machine (std::thread::hardware_concurrency())
    unsigned affinity = 0;   ///< CPUs in this process's affinity mask (sched_getaffinity)
    double cpu_quota = 0;    ///< cgroup CPU bandwidth limit, in CPUs (cpu.max, cfs_quota_us / cfs_period_us)
    unsigned slurm_cpus = 0; ///< SLURM_CPUS_PER_TASK
    unsigned local_ranks = 0; ///< processes of this MPI (or Slurm) job on this node
};

/// A thread count and what decided it.
struct ThreadChoice {
    unsigned threads = 1; ///< >= 1
    /// "hardware", "affinity", "cpu-quota" or "slurm", with "+local-ranks"
    /// when it was shared among the ranks on the node; "option" for a count the
    /// caller gave (RunControl::threads > 0).
    std::string from = "hardware";
};

/// The CPUs this process may use, as default_threads() counts them: the
/// smallest of `m.hardware`, `m.affinity`, the quota rounded up and
/// `m.slurm_cpus` (those that are known), divided by `m.local_ranks` (at
/// least 1 each) when the count is the node's rather than this process's own:
/// not when it comes from Slurm's CPUs per task or from an affinity mask
/// narrower than the machine (a launcher's binding of this rank).
ThreadChoice default_threads(const MachineShare& m);

/// default_threads(inspect_machine()): what RunControl::threads = 0 means.
ThreadChoice default_threads();

/// This process's machine share, read now: hardware_concurrency(), the
/// affinity mask, the cgroup quota (cgroup_cpu_quota()), SLURM_CPUS_PER_TASK,
/// and the ranks on this node from the launcher's environment
/// (OMPI_COMM_WORLD_LOCAL_SIZE, MPI_LOCALNRANKS, MV2_COMM_WORLD_LOCAL_SIZE,
/// or Slurm's SLURM_STEP_TASKS_PER_NODE at SLURM_NODEID).
MachineShare inspect_machine();

/// The CPU bandwidth limit of this process's cgroup and its ancestors, in
/// CPUs (the tightest), or 0 when there is none: cgroup v2 `cpu.max`, v1
/// `cpu.cfs_quota_us / cpu.cfs_period_us`, found through /proc/self/cgroup and
/// /proc/self/mountinfo. `root` is prefixed to every path read (tests give a
/// directory that stands for "/").
double cgroup_cpu_quota(const std::string& root = "");

} // namespace stickslip
