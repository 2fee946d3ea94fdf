// SPDX-License-Identifier: BSD-3-Clause
// stickslip/random/rng_batch.hpp -- CounterRng's draws, generated 32 at a time.
//
// Why: a scalar Philox call and a scalar ziggurat leave most of a core idle; the
// same work over 32 consecutive counters of one stream is a loop without
// dependencies that the compiler turns into SIMD instructions (AVX-512, AVX2 or
// SSE2, chosen at run time on x86-64; plain code elsewhere). BatchedCounterRng
// has CounterRng's interface and returns the same numbers bit for bit -- draw j
// is the same block, and a rejected ziggurat word is resolved from the same
// retry substream -- so a kernel gives the same result with either, and thread
// counts or process splits never matter. A tested guarantee
// (tests/unit/rng_batch_test.cpp).
//
// Host only (the buffer is about 1 KB); GPU code uses CounterRng.
#pragma once

/// \file
/// CounterRng's stream generated 32 draws at a time (SIMD), bit for bit the
/// same numbers. The comment at the top of this header explains the design.

#include <cstdint>
#include <type_traits>

#include "stickslip/random/rng.hpp"

namespace stickslip {

namespace detail {
/// Blocks per refill of BatchedCounterRng.
inline constexpr int rng_batch_size = 32;

/// Philox blocks j0 .. j0+31 of the stream (key, counter words c2, c3) into
/// words[w][i] (word w of block j0+i). Counter word 1 of block j is
/// ((j >> 32) & hi_mask) | hi_tag: the main draws with the defaults, the side
/// blocks of CounterRng::side_draw_of with mask 0x7fff and tag 0x40000000.
void philox_batch(std::uint32_t key0, std::uint32_t key1, std::uint64_t j0, std::uint32_t c2, std::uint32_t c3,
                  std::uint32_t (*words)[rng_batch_size], std::uint32_t hi_mask = 0xffffffffu,
                  std::uint32_t hi_tag = 0u);

/// The ziggurat fast path of the two 64-bit words of each block into
/// normals[half][i], with rejected[half][i] = 1 where it rejected (the normal
/// there is a placeholder). Returns the number of rejections.
int ziggurat_fast_batch(const std::uint32_t (*words)[rng_batch_size], double (*normals)[rng_batch_size],
                        std::uint8_t (*rejected)[rng_batch_size]);

/// Blocks j0 .. j0+31 into words and their exact normals into normals[half][i]:
/// philox_batch, ziggurat_fast_batch, then the slow path for each rejected word
/// of slot i >= from (slots below `from` are left unresolved: the caller does
/// not use them).
void fill_normals(const CounterRng::Philox::key_type& key, std::uint32_t c2, std::uint32_t c3, std::uint64_t j0,
                  std::uint32_t (*words)[rng_batch_size], double (*normals)[rng_batch_size], int from = 0);

/// The side draws of draws j0 .. j0+31 (the event scheme's third normal and
/// uniform of each step): side[0][i] and side[1][i] are bitwise
/// CounterRng::side_draw_of(key, c2, c3, j0+i).x and .y, for slots i >= from
/// (the slots below are left unresolved, as in fill_normals).
void fill_side_draws(const CounterRng::Philox::key_type& key, std::uint32_t c2, std::uint32_t c3, std::uint64_t j0,
                     double (*side)[rng_batch_size], int from = 0);

/// Name of the instruction set the batch runs on here ("avx512", "avx2" or "baseline").
const char* rng_batch_isa();
} // namespace detail

/// CounterRng's stream, buffered 32 draws at a time. WithNormals: every refill
/// also converts the blocks to normals (inclusion engine); without, uniforms
/// and raw blocks only (PDMP engine), and normal2() does not exist.
template <bool WithNormals>
class BatchedStream {
public:
    /// The generator, CounterRng's.
    using Philox = CounterRng::Philox;
    /// Draws generated per refill (32).
    static constexpr int batch = detail::rng_batch_size;

    /// The fresh stream (seed, purpose, index), as CounterRng's constructor.
    BatchedStream(std::uint64_t seed, StreamPurpose purpose, std::uint64_t index) { reset(seed, purpose, index); }
    /// The stream (seed 0, purpose 0, index 0), a placeholder until reset() (for arrays of streams).
    BatchedStream() = default;

    /// Makes this the fresh stream (seed, purpose, index).
    void reset(std::uint64_t seed, StreamPurpose purpose, std::uint64_t index) {
        key_ = CounterRng::make_key(seed);
        ctr_ = CounterRng::make_counter(purpose, index, 0);
        base_ = 0;
        pos_ = batch;
        side_base_ = 0;
    }

    /// Two independent standard normals; the same as CounterRng::normal2.
    /// A member template, so that the explicit instantiation of
    /// BatchedStream<false> leaves it out (Clang before 15 instantiates
    /// members whose constraint fails).
    template <bool W = WithNormals>
    NormalPair normal2()
        requires W
    {
        if (pos_ == batch) refill();
        const NormalPair z{normals_[0][pos_], normals_[1][pos_]};
        ++pos_;
        return z;
    }

    /// 128 fresh random bits; the same as CounterRng::next_block.
    Philox::ctr_type next_block() {
        if (pos_ == batch) refill();
        const Philox::ctr_type b = {{words_[0][pos_], words_[1][pos_], words_[2][pos_], words_[3][pos_]}};
        ++pos_;
        return b;
    }

    /// Two uniforms in (0, 1]; the same as CounterRng::uniform2.
    void uniform2(double& u0, double& u1) {
        const Philox::ctr_type b = next_block();
        u0 = r123::u01<double>(CounterRng::join(b.v[0], b.v[1]));
        u1 = r123::u01<double>(CounterRng::join(b.v[2], b.v[3]));
    }

    /// An exponential of mean 1 and a uniform in (0, 1]; the same as
    /// CounterRng::exponential_uniform.
    void exponential_uniform(double& e, double& u) {
        const std::uint64_t j = draws();
        const Philox::ctr_type b = next_block();
        e = CounterRng::exponential_of_word(key_, ctr_.v[2], ctr_.v[3], j, CounterRng::join(b.v[0], b.v[1]));
        u = r123::u01<double>(CounterRng::join(b.v[2], b.v[3]));
    }

    /// One uniform in (0, 1]; the same as CounterRng::uniform.
    double uniform() {
        const Philox::ctr_type b = next_block();
        return r123::u01<double>(CounterRng::join(b.v[0], b.v[1]));
    }

    /// The side uniform of the last draw; the same as CounterRng::side_uniform.
    double side_uniform() const { return CounterRng::side_uniform_of(key_, ctr_.v[2], ctr_.v[3], draws() - 1); }

    /// The event scheme's side draw of the last draw; the same as
    /// CounterRng::side_draw. The side draws of the buffered batch are
    /// generated together on the first call in it (from the last draw on):
    /// the event scheme asks for them on most of its draws when it slides or
    /// refines.
    template <bool W = WithNormals>
    NormalPair side_draw()
        requires W
    {
        if (base_ == 0) return CounterRng::side_draw_of(key_, ctr_.v[2], ctr_.v[3], draws() - 1); // (no draw yet)
        const int i = pos_ - 1;
        if (side_base_ != base_) {
            detail::fill_side_draws(key_, ctr_.v[2], ctr_.v[3], base_ - batch, side_, i);
            side_base_ = base_;
        }
        return {side_[0][i], side_[1][i]};
    }

    /// Number of 128-bit blocks drawn so far.
    std::uint64_t draws() const { return base_ + static_cast<std::uint64_t>(pos_) - batch; }

private:
    void refill();

    Philox::key_type key_{};
    Philox::ctr_type ctr_{};        ///< words 2, 3 identify the stream
    std::uint64_t base_ = 0;        ///< draw number after the buffered batch
    int pos_ = batch;               ///< next unread slot; batch = empty
    std::uint32_t words_[4][batch];
    struct Empty {};
    [[no_unique_address]] std::conditional_t<WithNormals, double[2][batch], Empty> normals_;
    /// Side draws (normal, uniform) of the buffered batch, valid from the
    /// slot of the first side_draw() in it on, when side_base_ == base_.
    [[no_unique_address]] std::conditional_t<WithNormals, double[2][batch], Empty> side_;
    std::uint64_t side_base_ = 0;
};

/// The inclusion engine's stream: CounterRng's numbers, normals batched.
using BatchedCounterRng = BatchedStream<true>;
/// The PDMP engine's stream: CounterRng's uniforms and exponentials, batched.
using BatchedUniformRng = BatchedStream<false>;

extern template class BatchedStream<true>;
extern template class BatchedStream<false>;

static_assert(GaussianStream<BatchedCounterRng> && UniformStream<BatchedUniformRng>);

} // namespace stickslip
