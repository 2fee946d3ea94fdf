// SPDX-License-Identifier: BSD-3-Clause
// stickslip/random/ziggurat.hpp -- standard normals and unit exponentials from
// 64-bit words: the ziggurat.
//
// Why a ziggurat: one inclusion step needs a pair of normals, and Box-Muller
// (a logarithm, a square root, a sine and a cosine per pair) cost about 4x the
// Philox block that fed it; the whole step was the transform. The ziggurat
// (Marsaglia & Tsang 2000, 256 layers, NumPy's 52-bit layout) turns one 64-bit
// word into an exact normal with a table lookup, a multiply and a compare in
// 98.5% of cases -- and that fast path has no branch that depends on earlier
// draws, so a batch of words converts with SIMD instructions (rng_batch.hpp).
//
// Word layout: bits 0-7 layer index, bit 8 sign, bits 9-60 the 52-bit position;
// bits 61-63 are unused. A word the fast path rejects (the top layer, a wedge
// between a rectangle and the curve, or the tail beyond zig_r) is resolved by
// the exact rejection steps, which draw further words from a source the caller
// supplies; CounterRng gives every rejected word its own retry substream, so a
// normal is a pure function of (seed, stream, draw number, half).
//
// Exactness: the fast path is one correctly rounded multiply of an exact
// integer, so the result is bitwise the same on every IEEE machine and SIMD
// width; the rare slow path takes exp and log once or twice, through
// kernel_below_exp and kernel_log (portable_math.hpp): glibc's on the host,
// the project's own on a CUDA device.
//
// Exponentials (the PDMP engine's waiting times): the same construction for
// the density exp(-x) on x > 0 (256 layers, tables zige_*), word layout bits
// 0-7 layer index, bits 8-60 the 53-bit position. It replaces -log(u); the
// rare slow path is kept out of line (inlined, it slowed the event loop by
// 12%). Timed alone in the PDMP kernel (bench: BM_PdmpEvents against
// BM_PdmpEventsLogWaits, one run) the two draws cost about the same, 1.0 to
// 1.15x; whole `stickslip diffusivity --engine pdmp` runs went from 3.7-4.1e7
// to 5.2-6.8e7 events/s on one thread with this change, so most of that gain
// is how the runner's event loop now compiles, not the logarithm. The fast
// path (97.8% of words) is a lookup, a multiply and a compare. The tail beyond
// zige_r is zige_r plus a fresh exponential (the density's memorylessness),
// taken as -log of a uniform; the wedges compare with exp(-x).
//
// GPU note: the functions are STICKSLIP_HD; device code reads the tables from
// a copy in global memory (detail/ziggurat_device_tables.hpp, read through the
// read-only cache: the lanes of a warp index them divergently, which
// __constant__ memory would serialise), made from these arrays at compile time.
#pragma once

/// \file
/// Standard normals and unit exponentials from 64-bit words: the ziggurat,
/// exact and SIMD-friendly.
/// The comment at the top of this header explains the design.

#include <cmath>
#include <cstdint>

#include <Random123/uniform.hpp>

#include "stickslip/config.hpp"
#include "stickslip/random/detail/exponential_ziggurat_tables.hpp"
#include "stickslip/random/detail/ziggurat_tables.hpp"
#include "stickslip/random/portable_math.hpp"
#if defined(__CUDACC__)
#include "stickslip/random/detail/ziggurat_device_tables.hpp"
#endif

/// The ziggurat table `name` (zig_k, zig_w, zig_f) as the current code sees
/// it: the host array, or its device copy in device code.
#if defined(__CUDA_ARCH__)
#define STICKSLIP_ZIG_TABLE(name) ::stickslip::detail::name##_device.v
#else
#define STICKSLIP_ZIG_TABLE(name) ::stickslip::detail::name
#endif

namespace stickslip {

/// Mask of the 52-bit position field (after shifting the word right by 9).
inline constexpr std::uint64_t ziggurat_position_mask = (std::uint64_t{1} << 52) - 1;

/// The fast path: writes the candidate normal for word r into x and returns true
/// when it is accepted (the point lies inside the layer's inner rectangle).
/// When it returns false, x must be passed through ziggurat_resolve.
STICKSLIP_HD inline bool ziggurat_fast(std::uint64_t r, double& x) {
    const unsigned idx = static_cast<unsigned>(r & 0xffu);
    const std::uint64_t pos = (r >> 9) & ziggurat_position_mask;
    const double a = static_cast<double>(static_cast<std::int64_t>(pos)) * STICKSLIP_ZIG_TABLE(zig_w)[idx];
    x = ((r >> 8) & 1u) ? -a : a;
    return pos < STICKSLIP_ZIG_TABLE(zig_k)[idx];
}

/// Exact resolution of a word the fast path rejected. `more()` returns fresh
/// independent 64-bit words; uniforms are u01 of a word, in (0, 1].
template <class WordSource>
STICKSLIP_HD inline double ziggurat_resolve(std::uint64_t r, WordSource& more) {
    for (;;) {
        double x;
        if (ziggurat_fast(r, x)) return x;
        const unsigned idx = static_cast<unsigned>(r & 0xffu);
        const bool negative = (r >> 8) & 1u;
        if (idx == 0) {
            // Tail beyond zig_r: Marsaglia's exponential rejection.
            for (;;) {
                const double xx = -detail::zig_inv_r * kernel_log(r123::u01<double>(more()));
                const double yy = -kernel_log(r123::u01<double>(more()));
                if (yy + yy > xx * xx) return negative ? -(detail::zig_r + xx) : detail::zig_r + xx;
            }
        }
        // Wedge: accept with the density's height against a uniform in the layer.
        const double y = (STICKSLIP_ZIG_TABLE(zig_f)[idx - 1] - STICKSLIP_ZIG_TABLE(zig_f)[idx]) *
                             r123::u01<double>(more()) +
                         STICKSLIP_ZIG_TABLE(zig_f)[idx];
        if (kernel_below_exp(y, -0.5 * x * x)) return x;
        r = more();
    }
}

/// Mask of the exponential ziggurat's 53-bit position field (after shifting
/// the word right by 8).
inline constexpr std::uint64_t exponential_ziggurat_position_mask = (std::uint64_t{1} << 53) - 1;

/// The exponential's fast path: writes the candidate for word r into x (>= 0)
/// and returns true when it is accepted (inside the layer's inner rectangle).
/// When it returns false, x must be passed through exponential_ziggurat_resolve.
STICKSLIP_HD inline bool exponential_ziggurat_fast(std::uint64_t r, double& x) {
    const unsigned idx = static_cast<unsigned>(r & 0xffu);
    const std::uint64_t pos = (r >> 8) & exponential_ziggurat_position_mask;
    x = static_cast<double>(static_cast<std::int64_t>(pos)) * STICKSLIP_ZIG_TABLE(zige_w)[idx];
    return pos < STICKSLIP_ZIG_TABLE(zige_k)[idx];
}

/// An exponential of mean 1 from word r, exactly: the fast path, else the
/// slow path fed by `more()`, which returns fresh independent 64-bit words;
/// uniforms are u01 of a word, in (0, 1].
template <class WordSource>
STICKSLIP_HD inline double exponential_ziggurat_resolve(std::uint64_t r, WordSource& more) {
    for (;;) {
        double x;
        if (exponential_ziggurat_fast(r, x)) return x;
        const unsigned idx = static_cast<unsigned>(r & 0xffu);
        if (idx == 0) return detail::zige_r - kernel_log(r123::u01<double>(more())); // the tail
        // Wedge: accept with the density's height against a uniform in the layer.
        const double y = (STICKSLIP_ZIG_TABLE(zige_f)[idx - 1] - STICKSLIP_ZIG_TABLE(zige_f)[idx]) *
                             r123::u01<double>(more()) +
                         STICKSLIP_ZIG_TABLE(zige_f)[idx];
        if (kernel_below_exp(y, -x)) return x;
        r = more();
    }
}

} // namespace stickslip
