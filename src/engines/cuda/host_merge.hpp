// SPDX-License-Identifier: BSD-3-Clause
// Internal: per-excursion outcomes merged into a run's totals exactly as the
// CPU engine merges them (src/driver/block_driver.hpp): blocks of block_size
// consecutive indices of the run, each accumulated in index order into a
// BivariateMoments of the uncapped (U, t), then added into the exact sums.
// Plain C++ (used by gpu_check and by the gpu-host tests, with or without CUDA).
#pragma once

#include <cstdint>

#include "stickslip/excursion.hpp"
#include "stickslip/stats/moment_sums.hpp"
#include "stickslip/stats/run_totals.hpp"

namespace stickslip::cuda {

/// Totals of the n outcomes out[0 .. n) of a run's excursions 0 .. n-1 (the
/// blocks are those of the run: out[0] is its first sample).
inline RunTotals merge_outcomes(const ExcursionOutcome* out, std::uint64_t n) {
    RunTotals t;
    t.requested = n;
    for (std::uint64_t lo = 0; lo < n; lo += block_size) {
        const std::uint64_t hi = lo + block_size < n ? lo + block_size : n;
        BivariateMoments block;
        for (std::uint64_t k = lo; k < hi; ++k) {
            t.work += out[k].work;
            if (out[k].capped) ++t.capped;
            else block.add(out[k].displacement, out[k].duration);
        }
        t.sums.add_block(block);
    }
    t.moments = t.sums.moments();
    return t;
}

} // namespace stickslip::cuda
