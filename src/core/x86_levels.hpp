// SPDX-License-Identifier: BSD-3-Clause
// x86_levels.hpp -- one source compiled per x86-64 level, chosen at run time.
//
// Why: the batched random numbers (rng_batch.cpp) and the SIMD lanes
// (resolvent_lanes.cpp) are loops the compiler vectorises; built once for
// baseline x86-64 they would get SSE2 only. With GCC's target_clones each is
// compiled for x86-64-v4 (AVX-512), x86-64-v3 (AVX2) and baseline, and the
// loader picks one for the CPU. Every clone computes the same integers and the
// same correctly rounded operations (no FMA: -ffp-contract=off), so the choice
// never changes a result. CMake defines STICKSLIP_RNG_TARGET_CLONES for these
// sources where its probe found support; elsewhere one portable version is built.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(STICKSLIP_RNG_TARGET_CLONES)
#define STICKSLIP_PER_X86_LEVEL 1
#define STICKSLIP_X86_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
// flatten: a clone gets its instruction set only in code inlined into it.
#define STICKSLIP_X86_CLONES_FLATTEN \
    __attribute__((flatten, target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define STICKSLIP_X86_CLONES
#define STICKSLIP_X86_CLONES_FLATTEN __attribute__((flatten))
#endif

namespace stickslip::detail {

/// The x86-64 level the clones run at on this CPU: 4 (AVX-512), 3 (AVX2), or
/// 0 (baseline, or a build without clones).
inline int x86_clone_level() {
#ifdef STICKSLIP_PER_X86_LEVEL
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v4")) return 4;
    if (__builtin_cpu_supports("x86-64-v3")) return 3;
#endif
    return 0;
}

} // namespace stickslip::detail
