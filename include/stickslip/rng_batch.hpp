// stickslip/rng_batch.hpp -- CounterRng's draws, generated 32 at a time.
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

#include "rng.hpp"

namespace stickslip {

namespace detail {
/// Blocks per refill of BatchedCounterRng.
inline constexpr int rng_batch_size = 32;

/// Philox blocks j0 .. j0+31 of the stream (key, counter words c2, c3) into
/// words[w][i] (word w of block j0+i).
void philox_batch(std::uint32_t key0, std::uint32_t key1, std::uint64_t j0, std::uint32_t c2, std::uint32_t c3,
                  std::uint32_t (*words)[rng_batch_size]);

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

    /// One uniform in (0, 1]; the same as CounterRng::uniform.
    double uniform() {
        const Philox::ctr_type b = next_block();
        return r123::u01<double>(CounterRng::join(b.v[0], b.v[1]));
    }

    /// The side uniform of the last draw; the same as CounterRng::side_uniform.
    double side_uniform() const { return CounterRng::side_uniform_of(key_, ctr_.v[2], ctr_.v[3], draws() - 1); }

    /// The event scheme's side draw of the last draw; the same as CounterRng::side_draw.
    NormalPair side_draw() const { return CounterRng::side_draw_of(key_, ctr_.v[2], ctr_.v[3], draws() - 1); }

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
};

/// The inclusion engine's stream: CounterRng's numbers, normals batched.
using BatchedCounterRng = BatchedStream<true>;
/// The PDMP engine's stream: CounterRng's uniforms, batched.
using BatchedUniformRng = BatchedStream<false>;

extern template class BatchedStream<true>;
extern template class BatchedStream<false>;

} // namespace stickslip
