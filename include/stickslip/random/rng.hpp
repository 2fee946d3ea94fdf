// SPDX-License-Identifier: BSD-3-Clause
// stickslip/random/rng.hpp -- counter-based random streams.
//
// Why counter-based: every excursion (or brute-force trajectory) k owns the
// stream (seed, purpose, k). Its random numbers depend on nothing else, so a
// result is bitwise identical for any number of threads and any split of the
// sample indices across processes. (A GPU port would reproduce the fast path
// exactly; the ziggurat's rare slow path calls exp/log, whose last bit may
// differ between libm and CUDA, see ziggurat.hpp.)
//
// Layout, after HOOMD-blue's RandomNumbers.h: the *key* is static (the user's
// 64-bit seed); the *counter* is dynamic: two words hold the sample index
// (56 bits) and the purpose (8 bits), two words hold the draw number within the
// sample. The generator is Random123's Philox4x32-10, which passes BigCrush;
// each call yields 128 bits.
//
// Normals come from the ziggurat (ziggurat.hpp): draw j of a stream gives the
// pair (N(word 0), N(word 1)) of its two 64-bit words. A word the ziggurat's
// fast path rejects (1.5%) is resolved with words from its own retry substream,
// counter {j lo, 2^31 | half << 30 | attempt << 15 | j hi, index, purpose}, so
// every normal is a pure function of (seed, purpose, index, j, half): a batched
// generator (rng_batch.hpp) reproduces CounterRng bit for bit. A step that
// needs one more uniform besides its normals (the inclusion engine's bridge
// test) takes it from the side block of its draw, counter {j lo, 2^30 | j hi,
// index, purpose}, so every colored-noise step consumes exactly one block of
// the main stream (a white-noise step uses one normal, half a block) and
// excursions can advance in lockstep (resolvent_lanes.hpp). The PDMP engine
// takes an exponential (the exponential ziggurat, rejected words resolved from
// the same retry substream as a normal's first word) and a uniform per draw. This needs
// j < 2^47 draws per stream (max_draws); the engines cap their work far below.
#pragma once

/// \file
/// Counter-based random streams (Philox4x32-10): the numbers of sample k depend
/// only on (seed, purpose, k). The comment at the top of this header explains
/// the design.

#include <cmath>
#include <concepts>
#include <cstdint>

#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include "stickslip/config.hpp"
#include "stickslip/random/ziggurat.hpp"

namespace stickslip {

/// Which computation a stream belongs to, so that different computations with
/// the same seed and index never share random numbers.
enum class StreamPurpose : std::uint32_t {
    /// Long excursions: diffusivity, density, correlation (which continues
    /// each excursion past its end on the same stream), sweep, trajectory's
    /// excursion mode.
    LongExcursion = 1,
    /// Independent trajectories from a given start: bruteforce, and the paths
    /// of trajectory's path mode.
    BruteForce = 2,
    /// The transient statistics' trajectories (moments).
    Observable = 3,
    SamplingPhase = 4, ///< random phase of a PDMP path's sampling grid (observables)
    Refinement = 5,    ///< the event scheme's refinement midpoints, one draw per midpoint, in order
    /// Reserved for tests, so that they never share a production stream.
    Test = 255,
};

/// Largest sample index a stream can take (56 bits).
inline constexpr std::uint64_t max_sample_index = (std::uint64_t{1} << 56) - 1;

/// Draws a stream may make (2^47): the retry substream of the normals keeps the
/// draw number's high word in 15 bits.
inline constexpr std::uint64_t max_draws = std::uint64_t{1} << 47;

/// A pair of doubles (two normals), usable on host and device.
struct NormalPair {
    /// @{
    /// The two values; independent standard normals, except for side_draw(),
    /// whose y is a uniform in (0, 1].
    double x, y;
    /// @}
};

/// The random stream (seed, purpose, index): Philox4x32-10 keyed by the seed,
/// counted by the draw number (layout at the top of this header). Every
/// number it gives is a pure function of (seed, purpose, index, draw), so
/// sample k of a run gets the same numbers whichever thread or process runs
/// it. A small value type (key and counter, 24 bytes), cheap to create per
/// sample; host and device.
class CounterRng {
public:
    /// Random123's Philox4x32-10: 4 x 32-bit counter, 2 x 32-bit key, 10 rounds.
    using Philox = r123::Philox4x32;

    /// The fresh stream `index` (< 2^56, max_sample_index) of computation
    /// `purpose` under the user's seed: draw 0 comes next.
    STICKSLIP_HD CounterRng(std::uint64_t seed, StreamPurpose purpose, std::uint64_t index)
        : key_(make_key(seed)), ctr_(make_counter(purpose, index, 0)) {}

    /// The Philox key of a seed.
    STICKSLIP_HD static Philox::key_type make_key(std::uint64_t seed) {
        return {{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}};
    }

    /// The counter of draw j of stream (purpose, index).
    STICKSLIP_HD static Philox::ctr_type make_counter(StreamPurpose purpose, std::uint64_t index,
                                                      std::uint64_t j) {
        return {{static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(j >> 32),
                 static_cast<std::uint32_t>(index),
                 static_cast<std::uint32_t>((index >> 32) & 0x00ffffffu) |
                     (static_cast<std::uint32_t>(purpose) << 24)}};
    }

    /// The normal of a 64-bit word whose ziggurat fast path rejected it: the
    /// exact slow path, fed by the retry substream of (draw j, half) of the
    /// stream whose key and counter words 2, 3 are given.
    STICKSLIP_HD static double resolve_rejected(const Philox::key_type& key, std::uint32_t c2, std::uint32_t c3,
                                                std::uint64_t j, unsigned half, std::uint64_t word) {
        RetryWords more = RetryWords::of(key, c2, c3, j, half, 0u);
        return ziggurat_resolve(word, more);
    }

    /// The unit exponential of word 0 of draw j of the stream whose key and
    /// counter words 2, 3 are given: the exponential ziggurat, a rejected word
    /// resolved from the retry substream of (draw j, half 0), as a normal's
    /// would be (a stream takes normals or exponentials from a draw, never both).
    STICKSLIP_HD static double exponential_of_word(const Philox::key_type& key, std::uint32_t c2, std::uint32_t c3,
                                                   std::uint64_t j, std::uint64_t word) {
        double x;
        if (exponential_ziggurat_fast(word, x)) [[likely]] return x;
        return exponential_rejected(key, c2, c3, j, word);
    }

    /// exponential_of_word's slow path, out of line.
    STICKSLIP_HD STICKSLIP_PM_NOINLINE static double exponential_rejected(const Philox::key_type& key, std::uint32_t c2,
                                                                          std::uint32_t c3, std::uint64_t j,
                                                                          std::uint64_t word) {
        RetryWords more = RetryWords::of(key, c2, c3, j, 0u, 0u);
        return exponential_ziggurat_resolve(word, more);
    }

    /// The normal of word `word` of draw j, half `half` of this stream.
    STICKSLIP_HD double normal_of_word(std::uint64_t word, std::uint64_t j, unsigned half) const {
        double x;
        if (ziggurat_fast(word, x)) return x;
        return resolve_rejected(key_, ctr_.v[2], ctr_.v[3], j, half, word);
    }

    /// 128 fresh random bits; advances the draw counter by one.
    STICKSLIP_HD Philox::ctr_type next_block() {
        Philox::ctr_type out = Philox()(ctr_, key_);
        if (++ctr_.v[0] == 0u) ++ctr_.v[1];
        return out;
    }

    /// Number of 128-bit blocks drawn so far.
    STICKSLIP_HD std::uint64_t draws() const {
        return (static_cast<std::uint64_t>(ctr_.v[1]) << 32) | ctr_.v[0];
    }

    /// Two independent standard normals: the ziggurat of the block's two 64-bit words.
    STICKSLIP_HD NormalPair normal2() {
        const std::uint64_t j = draws();
        const Philox::ctr_type b = next_block();
        return {normal_of_word(join(b.v[0], b.v[1]), j, 0), normal_of_word(join(b.v[2], b.v[3]), j, 1)};
    }

    /// An exponential of mean 1 and an independent uniform in (0, 1] from one
    /// draw: the exponential of its first 64-bit word (exponential_of_word),
    /// the uniform of its second (as uniform2's second). The PDMP engine's
    /// waiting time and jump direction.
    STICKSLIP_HD void exponential_uniform(double& e, double& u) {
        const std::uint64_t j = draws();
        const Philox::ctr_type b = next_block();
        e = exponential_of_word(key_, ctr_.v[2], ctr_.v[3], j, join(b.v[0], b.v[1]));
        u = r123::u01<double>(join(b.v[2], b.v[3]));
    }

    /// The side uniform of draw j, in (0, 1]: independent of the draw's own block.
    STICKSLIP_HD static double side_uniform_of(const Philox::key_type& key, std::uint32_t c2, std::uint32_t c3,
                                               std::uint64_t j) {
        const Philox::ctr_type ctr = {{static_cast<std::uint32_t>(j),
                                       0x40000000u | (static_cast<std::uint32_t>(j >> 32) & 0x7fffu), c2, c3}};
        const Philox::ctr_type b = Philox()(ctr, key);
        return r123::u01<double>(join(b.v[0], b.v[1]));
    }

    /// The side block of draw j as the event scheme uses it: a normal from its
    /// first word (a rejected word is resolved from its own retry substream,
    /// attempts from 2^14 on, apart from the main draws' retries) and a uniform
    /// in (0, 1] from its second.
    STICKSLIP_HD static NormalPair side_draw_of(const Philox::key_type& key, std::uint32_t c2, std::uint32_t c3,
                                                std::uint64_t j) {
        const Philox::ctr_type ctr = {{static_cast<std::uint32_t>(j),
                                       0x40000000u | (static_cast<std::uint32_t>(j >> 32) & 0x7fffu), c2, c3}};
        const Philox::ctr_type b = Philox()(ctr, key);
        double x;
        const std::uint64_t word = join(b.v[0], b.v[1]);
        if (!ziggurat_fast(word, x)) {
            RetryWords more = RetryWords::of(key, c2, c3, j, 0u, 0x4000u);
            x = ziggurat_resolve(word, more);
        }
        return {x, r123::u01<double>(join(b.v[2], b.v[3]))};
    }

    /// The event scheme's side draw of the last draw: {normal, uniform}.
    STICKSLIP_HD NormalPair side_draw() const { return side_draw_of(key_, ctr_.v[2], ctr_.v[3], draws() - 1); }

    /// The side uniform of the last draw (call after at least one draw).
    STICKSLIP_HD double side_uniform() const { return side_uniform_of(key_, ctr_.v[2], ctr_.v[3], draws() - 1); }

    /// Two independent uniforms in (0, 1] with 53 significant bits.
    STICKSLIP_HD void uniform2(double& u0, double& u1) {
        Philox::ctr_type b = next_block();
        u0 = r123::u01<double>(join(b.v[0], b.v[1]));
        u1 = r123::u01<double>(join(b.v[2], b.v[3]));
    }

    /// One uniform in (0, 1].
    STICKSLIP_HD double uniform() {
        Philox::ctr_type b = next_block();
        return r123::u01<double>(join(b.v[0], b.v[1]));
    }

    /// The 64-bit word hi 2^32 + lo of two 32-bit Philox words.
    STICKSLIP_HD static std::uint64_t join(std::uint32_t lo, std::uint32_t hi) {
        return (static_cast<std::uint64_t>(hi) << 32) | lo;
    }

private:
    /// Words of the retry substream of one rejected normal, two per Philox call.
    struct RetryWords {
        Philox::key_type key;
        Philox::ctr_type ctr;
        Philox::ctr_type block;
        std::uint32_t j_hi;
        unsigned half;
        std::uint32_t attempt;
        int pos;
        /// The retry substream of (draw j, half) of the stream whose key and
        /// counter words 2, 3 are given, its attempts counted from `first` on.
        STICKSLIP_HD static RetryWords of(const Philox::key_type& key, std::uint32_t c2, std::uint32_t c3,
                                          std::uint64_t j, unsigned half, std::uint32_t first) {
            return {key, {{static_cast<std::uint32_t>(j), 0u, c2, c3}}, {}, static_cast<std::uint32_t>(j >> 32), half,
                    first, 4};
        }
        STICKSLIP_HD std::uint64_t operator()() {
            if (pos == 4) {
                attempt = (attempt + 1) & 0x7fffu; // wraps after 2^15 rejections in a row: probability < 1e-5000
                ctr.v[1] = 0x80000000u | (static_cast<std::uint32_t>(half) << 30) | (attempt << 15) |
                           (j_hi & 0x7fffu);
                block = Philox()(ctr, key);
                pos = 0;
            }
            const std::uint64_t w = join(block.v[pos], block.v[pos + 1]);
            pos += 2;
            return w;
        }
    };

    Philox::key_type key_;
    Philox::ctr_type ctr_;
};

/// @name The stream protocols
/// What a kernel asks of its random stream: the PDMP engine uniforms only
/// (UniformStream), the time-stepping schemes pairs of normals too
/// (GaussianStream). CounterRng and the batched streams of rng_batch.hpp
/// model them; any stream that does must give the same numbers for the same
/// (seed, purpose, index), whoever draws them.
/// @{
template <class R>
concept UniformStream = requires(R& r) {
    { r.uniform() } -> std::same_as<double>;
};
template <class R>
concept GaussianStream = UniformStream<R> && requires(R& r) {
    { r.normal2() } -> std::same_as<NormalPair>;
};
/// @}
static_assert(GaussianStream<CounterRng>);

} // namespace stickslip
