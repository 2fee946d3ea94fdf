// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/random/rng_batch.hpp"

#include <bit>
#include <cstring>

#include "core/x86_levels.hpp"

namespace stickslip {

namespace detail {

STICKSLIP_X86_CLONES
void philox_batch(std::uint32_t key0, std::uint32_t key1, std::uint64_t j0, std::uint32_t c2, std::uint32_t c3,
                  std::uint32_t (*words)[rng_batch_size], std::uint32_t hi_mask, std::uint32_t hi_tag) {
    constexpr int n = rng_batch_size;
    std::uint32_t a[n], b[n], c[n], d[n];
    for (int i = 0; i < n; ++i) {
        const std::uint64_t j = j0 + static_cast<std::uint64_t>(i);
        a[i] = static_cast<std::uint32_t>(j);
        b[i] = (static_cast<std::uint32_t>(j >> 32) & hi_mask) | hi_tag;
        c[i] = c2;
        d[i] = c3;
    }
    // Philox4x32-10 (Salmon et al. 2011), the rounds of Random123's philox.h
    // written over 32 counters at once; tests compare with r123::Philox4x32.
    std::uint32_t ka = key0, kb = key1;
    for (int round = 0; round < 10; ++round) {
        for (int i = 0; i < n; ++i) {
            const std::uint64_t p0 = std::uint64_t{0xD2511F53u} * a[i];
            const std::uint64_t p1 = std::uint64_t{0xCD9E8D57u} * c[i];
            const std::uint32_t na = static_cast<std::uint32_t>(p1 >> 32) ^ b[i] ^ ka;
            const std::uint32_t nc = static_cast<std::uint32_t>(p0 >> 32) ^ d[i] ^ kb;
            b[i] = static_cast<std::uint32_t>(p1);
            d[i] = static_cast<std::uint32_t>(p0);
            a[i] = na;
            c[i] = nc;
        }
        ka += 0x9E3779B9u;
        kb += 0xBB67AE85u;
    }
    for (int i = 0; i < n; ++i) {
        words[0][i] = a[i];
        words[1][i] = b[i];
        words[2][i] = c[i];
        words[3][i] = d[i];
    }
}

STICKSLIP_X86_CLONES
int ziggurat_fast_batch(const std::uint32_t (*words)[rng_batch_size], double (*normals)[rng_batch_size],
                        std::uint8_t (*rejected)[rng_batch_size]) {
    constexpr int n = rng_batch_size;
    // Ziggurat fast path (ziggurat.hpp), branch-free: sign by flipping the sign bit.
    int bad = 0;
    for (int half = 0; half < 2; ++half) {
        const std::uint32_t* lo = words[2 * half];
        const std::uint32_t* hi = words[2 * half + 1];
        for (int i = 0; i < n; ++i) {
            const std::uint64_t r = (static_cast<std::uint64_t>(hi[i]) << 32) | lo[i];
            const std::uint64_t idx = r & 0xffu;
            const std::uint64_t pos = (r >> 9) & ziggurat_position_mask;
            const double x = static_cast<double>(static_cast<std::int64_t>(pos)) * zig_w[idx];
            normals[half][i] = std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) ^ ((r >> 8) << 63));
            const std::uint8_t rej = pos >= zig_k[idx];
            rejected[half][i] = rej;
            bad += rej;
        }
    }
    return bad;
}

const char* rng_batch_isa() {
    switch (x86_clone_level()) {
    case 4: return "avx512";
    case 3: return "avx2";
    default: return "baseline";
    }
}

} // namespace detail

void detail::fill_normals(const CounterRng::Philox::key_type& key, std::uint32_t c2, std::uint32_t c3,
                          std::uint64_t j0, std::uint32_t (*words)[rng_batch_size],
                          double (*normals)[rng_batch_size], int from) {
    constexpr int n = rng_batch_size;
    philox_batch(key.v[0], key.v[1], j0, c2, c3, words);
    alignas(8) std::uint8_t rejected[2][n];
    if (ziggurat_fast_batch(words, normals, rejected) == 0) return;
    for (unsigned half = 0; half < 2; ++half)
        for (int i0 = 0; i0 < n; i0 += 8) {
            std::uint64_t any; // eight flags at once: most groups have none
            std::memcpy(&any, &rejected[half][i0], 8);
            if (any == 0) continue;
            for (int i = i0 < from ? from : i0; i < i0 + 8; ++i)
                if (rejected[half][i])
                    normals[half][i] = CounterRng::resolve_rejected(
                        key, c2, c3, j0 + static_cast<std::uint64_t>(i), half,
                        CounterRng::join(words[2 * half][i], words[2 * half + 1][i]));
        }
}

void detail::fill_side_draws(const CounterRng::Philox::key_type& key, std::uint32_t c2, std::uint32_t c3,
                             std::uint64_t j0, double (*side)[rng_batch_size], int from) {
    constexpr int n = rng_batch_size;
    std::uint32_t words[4][n];
    philox_batch(key.v[0], key.v[1], j0, c2, c3, words, 0x7fffu, 0x40000000u);
    double normals[2][n];
    alignas(8) std::uint8_t rejected[2][n];
    const bool any = ziggurat_fast_batch(words, normals, rejected) != 0; // (half 1 is not used)
    for (int i = 0; i < n; ++i) {
        side[0][i] = normals[0][i];
        side[1][i] = r123::u01<double>(CounterRng::join(words[2][i], words[3][i]));
    }
    if (!any) return;
    for (int i = from; i < n; ++i) // the rare rejection: its own retry substream, as the scalar draw
        if (rejected[0][i]) side[0][i] = CounterRng::side_draw_of(key, c2, c3, j0 + static_cast<std::uint64_t>(i)).x;
}

template <bool WithNormals>
void BatchedStream<WithNormals>::refill() {
    if constexpr (WithNormals)
        detail::fill_normals(key_, ctr_.v[2], ctr_.v[3], base_, words_, normals_);
    else
        detail::philox_batch(key_.v[0], key_.v[1], base_, ctr_.v[2], ctr_.v[3], words_);
    base_ += batch;
    pos_ = 0;
}

template class BatchedStream<true>;
template class BatchedStream<false>;

} // namespace stickslip
