// SPDX-License-Identifier: BSD-3-Clause
// How much memory this process may still take: the grid solvers size their
// work by it, so that a solve under a tight limit (ulimit -v, a small
// machine) is refused up front instead of dying inside the sparse LU (under
// `ulimit -v 160000` Eigen's factorisation aborted with "double free or
// corruption", or threw a bare std::bad_alloc).
#pragma once

namespace stickslip::detail {

/// Bytes this process may still allocate: the smaller of what its address
/// space limit (RLIMIT_AS) leaves beyond its present size and the machine's
/// available memory (MemAvailable); +inf where neither is known.
double usable_memory_bytes();

} // namespace stickslip::detail
