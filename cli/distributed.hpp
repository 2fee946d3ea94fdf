// SPDX-License-Identifier: BSD-3-Clause
// Runs across processes (MPI). Built in with -DSTICKSLIP_MPI=ON; MPI is
// started only when the command is launched by mpirun/srun (so the same binary
// runs alone without an MPI runtime). Every process parses and validates the
// same flags and computes its share of the sample blocks; their exact sums are
// all-reduced at the end (a few kilobytes, whatever the run's size), so the
// result is bitwise that of one process with the same seed. Only the first
// process prints or writes.
#pragma once

#include "stickslip/run_control.hpp"

namespace stickslip::cli {

/// Starts MPI when launched by an MPI launcher and built with MPI support.
void start_distribution(int& argc, char**& argv);
/// Finalizes MPI if it was started.
void stop_distribution();
/// Ends every process at once after an error on one of them (MPI_Abort).
[[noreturn]] void abort_distribution(int code);
/// True when more than one process runs.
bool distributed();
/// True on the process that prints (rank 0, or a plain run).
bool is_root();
/// Makes a run's control split its blocks across the processes.
void distribute(RunControl& control);
/// True on every process when `ok` is true on every process (a collective
/// call in a distributed run): lets a check made by one process fail all.
bool all_ok(bool ok);

} // namespace stickslip::cli
