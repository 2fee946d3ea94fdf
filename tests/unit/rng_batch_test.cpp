// SPDX-License-Identifier: BSD-3-Clause
// Batched streams (rng_batch.hpp) and the ziggurat (ziggurat.hpp).
//
// BatchedCounterRng and BatchedUniformRng promise CounterRng's numbers bit for
// bit: the same blocks, the same normals (a word the ziggurat's fast path
// rejects is resolved from the same retry substream), the same uniforms, side
// uniforms and draw counts, for any mix of calls and across refills. These tests
// compare them on many streams, check that the comparison reached the slow path
// (wedges, top layer and tail), and check the building blocks on their own:
// philox_batch against Random123 across the carry of the draw counter's low
// word, ziggurat_fast_batch and fill_normals against the scalar code, the
// ziggurat tables against their definition (scripts/dev/make_ziggurat_tables.py)
// and the fast path on hand-made words.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "stickslip/random/ziggurat.hpp"

namespace ss = stickslip;
namespace zd = stickslip::detail;

namespace {

constexpr int kBatch = zd::rng_batch_size;

std::uint64_t bits_of(double d) { return std::bit_cast<std::uint64_t>(d); }

/// SplitMix64: a fixed pseudo-random pattern for the tests themselves.
struct SplitMix {
    std::uint64_t s;
    std::uint64_t operator()() {
        std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
};

struct StreamId {
    std::uint64_t seed;
    ss::StreamPurpose purpose;
    std::uint64_t index;
};

std::string where(const StreamId& s) {
    return "seed " + std::to_string(s.seed) + ", purpose " + std::to_string(static_cast<unsigned>(s.purpose)) +
           ", index " + std::to_string(s.index);
}

/// 64 streams: several seeds, all purposes, small and large indices.
std::vector<StreamId> many_streams() {
    const ss::StreamPurpose purposes[] = {ss::StreamPurpose::LongExcursion, ss::StreamPurpose::BruteForce,
                                          ss::StreamPurpose::Observable, ss::StreamPurpose::SamplingPhase,
                                          ss::StreamPurpose::Test};
    const std::uint64_t indices[] = {0, 1, 2, 31, 32, 1000, (std::uint64_t{1} << 32) + 5, ss::max_sample_index};
    const std::uint64_t seeds[] = {1, 12345, (std::uint64_t{1} << 40) + 7, 0xfedcba9876543210ull};
    std::vector<StreamId> out;
    for (int k = 0; out.size() < 64; ++k)
        out.push_back({seeds[k % 4], purposes[(k / 4) % 5], indices[(k * 3 + k / 8) % 8]});
    return out;
}

/// Word of the ziggurat layout: bits 0-7 layer, bit 8 sign, bits 9-60 position, 61-63 unused.
std::uint64_t zig_word(unsigned idx, unsigned sign, std::uint64_t pos, unsigned top = 0) {
    return std::uint64_t{idx & 0xffu} | (std::uint64_t{sign & 1u} << 8) | ((pos & ss::ziggurat_position_mask) << 9) |
           (std::uint64_t{top & 7u} << 61);
}

/// A word source that replays a fixed list and counts what it handed out; past
/// the list it hands out pseudo-random words, so that a faulty resolution that
/// asks for more words ends (and fails the count check) instead of looping.
struct ScriptedWords {
    std::vector<std::uint64_t> words;
    std::size_t used = 0;
    SplitMix fallback{99};
    std::uint64_t operator()() { return used < words.size() ? words[used++] : (++used, fallback()); }
};

} // namespace

// ---------------------------------------------------------------------------
// BatchedCounterRng vs CounterRng

// uniform2 from both streams, compared bit for bit (fatal on a difference).
template <class A, class B>
void expect_same_uniform2(A& ref, B& bat, const std::string& at) {
    double a0, a1, c0, c1;
    ref.uniform2(a0, a1);
    bat.uniform2(c0, c1);
    ASSERT_EQ(bits_of(a0), bits_of(c0)) << at;
    ASSERT_EQ(bits_of(a1), bits_of(c1)) << at;
}

TEST(BatchedCounterRng, Normal2BitwiseEqualToCounterRngAndReachesTheSlowPath) {
    const int draws = 1000; // 64 x 1000 blocks: 128000 words, about 1900 fast-path rejections, 33 in the tail
    long rejected = 0, tail = 0, top_layer = 0, wedge = 0;
    for (const StreamId& s : many_streams()) {
        ss::CounterRng ref(s.seed, s.purpose, s.index), raw(s.seed, s.purpose, s.index);
        ss::BatchedCounterRng bat(s.seed, s.purpose, s.index);
        for (int j = 0; j < draws; ++j) {
            const auto b = raw.next_block();
            const std::uint64_t w[2] = {ss::CounterRng::join(b.v[0], b.v[1]), ss::CounterRng::join(b.v[2], b.v[3])};
            for (std::uint64_t word : w) {
                double x;
                if (ss::ziggurat_fast(word, x)) continue;
                ++rejected;
                const unsigned idx = static_cast<unsigned>(word & 0xffu);
                if (idx == 0) // the base strip rejects exactly beyond zig_r
                    ++tail;
                else if (idx == 1)
                    ++top_layer;
                else
                    ++wedge;
            }
            const ss::NormalPair a = ref.normal2(), c = bat.normal2();
            ASSERT_EQ(bits_of(a.x), bits_of(c.x)) << where(s) << ", draw " << j << " x: " << a.x << " vs " << c.x;
            ASSERT_EQ(bits_of(a.y), bits_of(c.y)) << where(s) << ", draw " << j << " y: " << a.y << " vs " << c.y;
            ASSERT_EQ(ref.draws(), bat.draws()) << where(s);
        }
    }
    std::cout << "[measured] slow-path words: " << rejected << " (wedges " << wedge << ", top layer " << top_layer
              << ", tail " << tail << ") of " << 64 * draws * 2 << " words" << std::endl;
    // Expected: 1.5% of 128000 = 1900; top layer 1/256 -> 500; tail 2.6e-4 -> 33.
    EXPECT_GE(rejected, 1000);
    EXPECT_GE(wedge, 500);
    EXPECT_GE(top_layer, 200);
    EXPECT_GE(tail, 5);
}

TEST(BatchedCounterRng, InterleavedCallsBitwiseEqualToCounterRng) {
    // normal2 / uniform / uniform2 / next_block in a fixed pseudo-random pattern,
    // about 600 draws per stream (19 refills), with draws() and side_uniform()
    // compared after every call.
    int counts[4] = {0, 0, 0, 0};
    const auto streams = many_streams();
    for (std::size_t n = 0; n < 16; ++n) {
        const StreamId& s = streams[n * 4 + n % 4];
        ss::CounterRng ref(s.seed, s.purpose, s.index);
        ss::BatchedCounterRng bat(s.seed, s.purpose, s.index);
        SplitMix pattern{0x1234 + n};
        for (int k = 0; k < 600; ++k) {
            const int op = static_cast<int>(pattern() % 4);
            ++counts[op];
            const std::string at = where(s) + ", call " + std::to_string(k) + " (op " + std::to_string(op) + ")";
            switch (op) {
            case 0: {
                const auto a = ref.normal2(), c = bat.normal2();
                ASSERT_EQ(bits_of(a.x), bits_of(c.x)) << at;
                ASSERT_EQ(bits_of(a.y), bits_of(c.y)) << at;
                break;
            }
            case 1:
                ASSERT_EQ(bits_of(ref.uniform()), bits_of(bat.uniform())) << at;
                break;
            case 2: {
                expect_same_uniform2(ref, bat, at);
                if (::testing::Test::HasFatalFailure()) return;
                break;
            }
            default: {
                const auto a = ref.next_block(), c = bat.next_block();
                for (int w = 0; w < 4; ++w) ASSERT_EQ(a.v[w], c.v[w]) << at << ", word " << w;
            }
            }
            ASSERT_EQ(ref.draws(), bat.draws()) << at;
            ASSERT_EQ(bat.draws(), static_cast<std::uint64_t>(k + 1)) << at;
            ASSERT_EQ(bits_of(ref.side_uniform()), bits_of(bat.side_uniform())) << at;
        }
    }
    for (int c : counts) EXPECT_GT(c, 2000); // every kind of call was made
}

TEST(BatchedCounterRng, SideUniformIsTheSideBlockOfTheLastDraw) {
    ss::BatchedCounterRng bat(99, ss::StreamPurpose::LongExcursion, 3);
    const auto ctr = ss::CounterRng::make_counter(ss::StreamPurpose::LongExcursion, 3, 0);
    const auto key = ss::CounterRng::make_key(99);
    for (std::uint64_t j = 0; j < 70; ++j) {
        bat.normal2();
        // Documented layout: counter {j lo, 2^30 | j hi, index, purpose}.
        const r123::Philox4x32::ctr_type side = {
            {static_cast<std::uint32_t>(j), 0x40000000u | static_cast<std::uint32_t>(j >> 32), ctr.v[2], ctr.v[3]}};
        const auto b = r123::Philox4x32()(side, key);
        EXPECT_EQ(bits_of(bat.side_uniform()), bits_of(r123::u01<double>(ss::CounterRng::join(b.v[0], b.v[1]))))
            << "draw " << j;
        EXPECT_EQ(bits_of(bat.side_uniform()), bits_of(ss::CounterRng::side_uniform_of(key, ctr.v[2], ctr.v[3], j)));
    }
}

TEST(BatchedUniformRng, BitwiseEqualToCounterRng) {
    int n = 0;
    for (const StreamId& s : many_streams()) {
        if (++n % 4 != 0) continue; // 16 streams
        ss::CounterRng ref(s.seed, s.purpose, s.index);
        ss::BatchedUniformRng bat(s.seed, s.purpose, s.index);
        SplitMix pattern{s.seed ^ s.index};
        for (int k = 0; k < 300; ++k) {
            const std::string at = where(s) + ", call " + std::to_string(k);
            switch (pattern() % 3) {
            case 0: {
                expect_same_uniform2(ref, bat, at);
                if (::testing::Test::HasFatalFailure()) return;
                break;
            }
            case 1:
                ASSERT_EQ(bits_of(ref.uniform()), bits_of(bat.uniform())) << at;
                break;
            default: {
                const auto a = ref.next_block(), c = bat.next_block();
                for (int w = 0; w < 4; ++w) ASSERT_EQ(a.v[w], c.v[w]) << at << ", word " << w;
            }
            }
            ASSERT_EQ(ref.draws(), bat.draws()) << at;
            ASSERT_EQ(bits_of(ref.side_uniform()), bits_of(bat.side_uniform())) << at;
        }
    }
}

TEST(BatchedStream, FreshStreamStartsAtDrawZero) {
    ss::BatchedCounterRng a(5, ss::StreamPurpose::Test, 6);
    ss::BatchedUniformRng b(5, ss::StreamPurpose::Test, 6);
    EXPECT_EQ(a.draws(), 0u);
    EXPECT_EQ(b.draws(), 0u);
    for (int k = 1; k <= 2 * kBatch + 1; ++k) {
        a.next_block();
        b.next_block();
        EXPECT_EQ(a.draws(), static_cast<std::uint64_t>(k));
        EXPECT_EQ(b.draws(), static_cast<std::uint64_t>(k));
    }
}

TEST(BatchedStream, ResetGivesAFreshStream) {
    // Reset mid-batch, at a batch boundary, to the same and to another stream,
    // and from a default-constructed object.
    for (int used : {0, 1, 17, kBatch, kBatch + 5, 3 * kBatch}) {
        ss::BatchedCounterRng n(77, ss::StreamPurpose::LongExcursion, 8);
        ss::BatchedUniformRng u(77, ss::StreamPurpose::LongExcursion, 8);
        for (int k = 0; k < used; ++k) {
            n.normal2();
            u.uniform();
        }
        for (const StreamId& s : {StreamId{77, ss::StreamPurpose::LongExcursion, 8},
                                  StreamId{78, ss::StreamPurpose::BruteForce, (std::uint64_t{1} << 33) + 1}}) {
            n.reset(s.seed, s.purpose, s.index);
            u.reset(s.seed, s.purpose, s.index);
            EXPECT_EQ(n.draws(), 0u);
            EXPECT_EQ(u.draws(), 0u);
            ss::CounterRng ref_n(s.seed, s.purpose, s.index), ref_u(s.seed, s.purpose, s.index);
            for (int k = 0; k < 2 * kBatch + 3; ++k) {
                const auto a = ref_n.normal2(), c = n.normal2();
                ASSERT_EQ(bits_of(a.x), bits_of(c.x)) << "used " << used << ", " << where(s) << ", draw " << k;
                ASSERT_EQ(bits_of(a.y), bits_of(c.y)) << "used " << used << ", " << where(s) << ", draw " << k;
                ASSERT_EQ(bits_of(ref_u.uniform()), bits_of(u.uniform())) << "used " << used << ", draw " << k;
            }
            // Leave the stream mid-batch again before the next reset.
            for (int k = 0; k < used; ++k) {
                n.next_block();
                u.next_block();
            }
        }
    }
    ss::BatchedCounterRng d;
    d.reset(3, ss::StreamPurpose::Observable, 4);
    ss::CounterRng ref(3, ss::StreamPurpose::Observable, 4);
    for (int k = 0; k < kBatch + 1; ++k) {
        const auto a = ref.normal2(), c = d.normal2();
        ASSERT_EQ(bits_of(a.x), bits_of(c.x)) << "default-constructed, draw " << k;
        ASSERT_EQ(bits_of(a.y), bits_of(c.y)) << "default-constructed, draw " << k;
    }
}

// ---------------------------------------------------------------------------
// Building blocks

TEST(PhiloxBatch, EqualsRandom123OnTheDocumentedCounterLayout) {
    // Counter {j lo, j hi, index lo, (index hi & 0xffffff) | purpose << 24}, key {seed lo, seed hi}.
    // j0 = 2^32 - 5: block 5 of the batch carries into counter word 1.
    const std::uint64_t seed = 0x0123456789abcdefull, index = (std::uint64_t{0xabcdef} << 32) | 0x13579bdfu;
    const auto purpose = ss::StreamPurpose::Observable;
    const std::uint32_t c2 = static_cast<std::uint32_t>(index);
    const std::uint32_t c3 = static_cast<std::uint32_t>(index >> 32) | (std::uint32_t{3} << 24);
    const auto ctr0 = ss::CounterRng::make_counter(purpose, index, 0);
    ASSERT_EQ(ctr0.v[2], c2);
    ASSERT_EQ(ctr0.v[3], c3);
    const r123::Philox4x32::key_type key = {{0x89abcdefu, 0x01234567u}};
    for (std::uint64_t j0 : {std::uint64_t{0}, (std::uint64_t{1} << 32) - 5, (std::uint64_t{7} << 32) - 31,
                             ss::max_draws - kBatch}) {
        std::uint32_t words[4][kBatch];
        zd::philox_batch(key.v[0], key.v[1], j0, c2, c3, words);
        for (int i = 0; i < kBatch; ++i) {
            const std::uint64_t j = j0 + static_cast<std::uint64_t>(i);
            const r123::Philox4x32::ctr_type ctr = {
                {static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(j >> 32), c2, c3}};
            const auto want = r123::Philox4x32()(ctr, key);
            const auto want2 = r123::Philox4x32()(ss::CounterRng::make_counter(purpose, index, j),
                                                  ss::CounterRng::make_key(seed));
            for (int w = 0; w < 4; ++w) {
                EXPECT_EQ(words[w][i], want.v[w]) << "j0 " << j0 << ", slot " << i << ", word " << w;
                EXPECT_EQ(want2.v[w], want.v[w]) << "make_counter/make_key layout, j " << j;
            }
        }
        if (j0 == (std::uint64_t{1} << 32) - 5) {
            // The test covers the carry: slots 0-4 have j hi = 0, slots 5+ have j hi = 1.
            const r123::Philox4x32::ctr_type no_carry = {{0u, 0u, c2, c3}};
            const auto wrong = r123::Philox4x32()(no_carry, key);
            EXPECT_NE(words[0][5], wrong.v[0]);
        }
    }
}

TEST(ZigguratFastBatch, EqualsScalarFastPathOnHandMadeAndRandomWords) {
    std::vector<std::uint64_t> w;
    for (unsigned idx : {0u, 1u, 2u, 3u, 100u, 128u, 254u, 255u})
        for (unsigned sign : {0u, 1u}) {
            const std::uint64_t k = zd::zig_k[idx];
            for (std::uint64_t pos : {std::uint64_t{0}, std::uint64_t{1}, k > 0 ? k - 1 : 0, k, k + 1,
                                      ss::ziggurat_position_mask})
                w.push_back(zig_word(idx, sign, pos, idx % 8));
        }
    SplitMix rnd{42};
    while (w.size() % (2 * kBatch) != 0) w.push_back(rnd());
    for (int k = 0; k < 20 * 2 * kBatch; ++k) w.push_back(rnd());
    int total_rejected = 0;
    for (std::size_t start = 0; start < w.size(); start += 2 * kBatch) {
        std::uint32_t words[4][kBatch];
        for (int i = 0; i < kBatch; ++i)
            for (int half = 0; half < 2; ++half) {
                const std::uint64_t r = w[start + 2 * static_cast<std::size_t>(i) + static_cast<std::size_t>(half)];
                words[2 * half][i] = static_cast<std::uint32_t>(r);
                words[2 * half + 1][i] = static_cast<std::uint32_t>(r >> 32);
            }
        double normals[2][kBatch];
        std::uint8_t rejected[2][kBatch];
        const int bad = zd::ziggurat_fast_batch(words, normals, rejected);
        int count = 0;
        for (int i = 0; i < kBatch; ++i)
            for (int half = 0; half < 2; ++half) {
                const std::uint64_t r = w[start + 2 * static_cast<std::size_t>(i) + static_cast<std::size_t>(half)];
                double x;
                const bool ok = ss::ziggurat_fast(r, x);
                EXPECT_EQ(rejected[half][i], ok ? 0 : 1) << "word " << std::hex << r;
                count += ok ? 0 : 1;
                if (ok) {
                    EXPECT_EQ(bits_of(normals[half][i]), bits_of(x)) << "word " << std::hex << r;
                }
            }
        EXPECT_EQ(bad, count);
        total_rejected += bad;
    }
    EXPECT_GT(total_rejected, 40); // the hand-made words alone reject 8 x 2 x 3 - 2 x 2 - 2 times
}

TEST(FillNormals, EqualsCounterRngAcrossTheLowWordCarry) {
    // fill_normals at j0 = 2^32 - 5 (blocks on both sides of the carry, so the
    // retry substreams see j hi = 0 and 1) against CounterRng::normal_of_word.
    long rejected = 0, rejected_after_carry = 0;
    const std::uint64_t j0 = (std::uint64_t{1} << 32) - 5;
    for (const StreamId& s : many_streams()) {
        const ss::CounterRng ref(s.seed, s.purpose, s.index);
        const auto key = ss::CounterRng::make_key(s.seed);
        const auto ctr = ss::CounterRng::make_counter(s.purpose, s.index, 0);
        for (std::uint64_t start : {j0, j0 + 2 * kBatch}) {
            std::uint32_t words[4][kBatch];
            double normals[2][kBatch];
            zd::fill_normals(key, ctr.v[2], ctr.v[3], start, words, normals);
            std::uint32_t words_from[4][kBatch];
            double normals_from[2][kBatch];
            const int from = 11;
            zd::fill_normals(key, ctr.v[2], ctr.v[3], start, words_from, normals_from, from);
            for (int i = 0; i < kBatch; ++i) {
                const std::uint64_t j = start + static_cast<std::uint64_t>(i);
                const auto b = r123::Philox4x32()(ss::CounterRng::make_counter(s.purpose, s.index, j), key);
                for (unsigned half = 0; half < 2; ++half) {
                    ASSERT_EQ(words[2 * half][i], b.v[2 * half]);
                    ASSERT_EQ(words[2 * half + 1][i], b.v[2 * half + 1]);
                    const std::uint64_t word = ss::CounterRng::join(b.v[2 * half], b.v[2 * half + 1]);
                    double x;
                    if (!ss::ziggurat_fast(word, x)) {
                        ++rejected;
                        if ((j >> 32) != 0) ++rejected_after_carry;
                    }
                    const double want = ref.normal_of_word(word, j, half);
                    ASSERT_EQ(bits_of(normals[half][i]), bits_of(want)) << where(s) << ", j " << j << ", half " << half;
                    if (i >= from) {
                        ASSERT_EQ(bits_of(normals_from[half][i]), bits_of(want)) << "from = " << from;
                    }
                }
            }
        }
    }
    std::cout << "[measured] fill_normals: " << rejected << " slow-path words, " << rejected_after_carry
              << " with j >= 2^32" << std::endl;
    EXPECT_GE(rejected, 20);
    EXPECT_GE(rejected_after_carry, 10);
}

TEST(FillNormals, RetrySubstreamDependsOnDrawAndHalf) {
    // The same rejected word resolved for different (j, half) must generally give
    // different normals: the retry substream is a function of both (and of j's
    // high word, which the batch must pass through).
    const auto key = ss::CounterRng::make_key(2024);
    const auto ctr = ss::CounterRng::make_counter(ss::StreamPurpose::Test, 1, 0);
    const std::uint64_t word = zig_word(0, 0, ss::ziggurat_position_mask); // tail: always the slow path
    const double a = ss::CounterRng::resolve_rejected(key, ctr.v[2], ctr.v[3], 5, 0, word);
    const double b = ss::CounterRng::resolve_rejected(key, ctr.v[2], ctr.v[3], 5, 1, word);
    const double c = ss::CounterRng::resolve_rejected(key, ctr.v[2], ctr.v[3], 6, 0, word);
    const double d = ss::CounterRng::resolve_rejected(key, ctr.v[2], ctr.v[3], (std::uint64_t{1} << 32) + 5, 0, word);
    for (double v : {a, b, c, d}) EXPECT_GT(v, zd::zig_r);
    EXPECT_NE(a, b);
    EXPECT_NE(a, c);
    EXPECT_NE(a, d);
}

TEST(RngBatch, IsaIsOneOfTheThree) {
    const std::string isa = zd::rng_batch_isa();
    std::cout << "[measured] rng_batch_isa() = " << isa << std::endl;
    EXPECT_TRUE(isa == "avx512" || isa == "avx2" || isa == "baseline") << isa;
}

// ---------------------------------------------------------------------------
// Ziggurat tables (definition: scripts/dev/make_ziggurat_tables.py)
//   x_i = zig_w[i] 2^52 (i >= 1) is the right edge of layer i, x_255 = zig_r,
//   f_i = zig_f[i] = exp(-x_i^2 / 2), f_0 = 1; every layer has the area
//   V = r f(r) + sqrt(pi/2) erfc(r / sqrt 2): layer i >= 1 is the rectangle
//   x_i (f_(i-1) - f_i), layer 0 the strip of width q = zig_w[0] 2^52 and height
//   f(r) (the bottom rectangle plus the tail). zig_k[i] = floor(2^52 x_(i-1) / x_i),
//   zig_k[0] = floor(2^52 r / q), zig_k[1] = 0.

namespace {
constexpr double two52 = 4503599627370496.0; // 2^52

double layer_area() {
    const double r = zd::zig_r;
    return r * std::exp(-0.5 * r * r) + std::sqrt(std::numbers::pi / 2) * std::erfc(r / std::numbers::sqrt2);
}
} // namespace

TEST(ZigguratTables, MonotoneAndAnchored) {
    EXPECT_EQ(zd::zig_k[1], 0u);
    EXPECT_EQ(zd::zig_f[0], 1.0);
    for (int i = 2; i < 256; ++i) EXPECT_LT(zd::zig_w[i - 1], zd::zig_w[i]) << "zig_w not increasing at " << i;
    for (int i = 1; i < 256; ++i) EXPECT_LT(zd::zig_f[i], zd::zig_f[i - 1]) << "zig_f not decreasing at " << i;
    for (int i = 0; i < 256; ++i) {
        EXPECT_GT(zd::zig_f[i], 0.0);
        EXPECT_LE(zd::zig_k[i], ss::ziggurat_position_mask) << i;
    }
    // The bottom edge is zig_r: zig_w[255] = fl(r / 2^52) = fl(r) / 2^52 exactly.
    EXPECT_EQ(zd::zig_w[255] * two52, zd::zig_r);
    EXPECT_NEAR(zd::zig_w[255] * two52, 3.6541528853610088, 1e-15 * zd::zig_r);
    // exp(-r^2/2) in long double where it is wider, so that the check is not
    // limited by the rounding of r^2 in double (7e-16 relative to f(r)).
    const long double r = zd::zig_r;
    const double f_r = static_cast<double>(std::exp(-0.5L * r * r));
    EXPECT_NEAR(zd::zig_f[255], f_r, 1e-15 * f_r);
    EXPECT_DOUBLE_EQ(zd::zig_inv_r, 1.0 / zd::zig_r);
    // The base strip is wider than the bottom rectangle (it holds the tail too).
    EXPECT_GT(zd::zig_w[0] * two52, zd::zig_r);
}

TEST(ZigguratTables, DensityAtEveryEdge) {
    for (int i = 1; i < 256; ++i) {
        const double x = zd::zig_w[i] * two52;
        const double f = std::exp(-0.5 * x * x);
        EXPECT_NEAR(zd::zig_f[i], f, 4e-15 * f) << "layer " << i << ", x = " << x;
    }
}

TEST(ZigguratTables, EveryLayerHasTheSameArea) {
    const double V = layer_area();
    double worst = 0;
    for (int i = 1; i < 256; ++i) {
        const double x = zd::zig_w[i] * two52;
        const double area = x * (zd::zig_f[i - 1] - zd::zig_f[i]);
        worst = std::max(worst, std::fabs(area / V - 1));
        EXPECT_NEAR(area, V, 1e-12 * V) << "layer " << i;
    }
    // Layer 0: strip of width q and height f(r) = bottom rectangle + tail.
    const double q = zd::zig_w[0] * two52;
    EXPECT_NEAR(q * zd::zig_f[255], V, 1e-12 * V);
    // The top layer closes: x_1 (1 - f(x_1)) = V (its left edge is x_0 = 0).
    const double x1 = zd::zig_w[1] * two52;
    EXPECT_NEAR(x1 * (1 - std::exp(-0.5 * x1 * x1)), V, 1e-12 * V);
    // 256 layers cover the half normal's area sqrt(pi/2) plus the wedges above the curve.
    EXPECT_GT(256 * V, std::sqrt(std::numbers::pi / 2));
    EXPECT_LT(256 * V, 1.01 * std::sqrt(std::numbers::pi / 2));
    std::cout << "[measured] ziggurat layer area V = " << V << ", worst relative deviation " << worst << std::endl;
}

TEST(ZigguratTables, AcceptBoundsAreTheEdgeRatios) {
    for (int i = 2; i < 256; ++i) {
        const double ratio = zd::zig_w[i - 1] / zd::zig_w[i] * two52;
        EXPECT_LE(std::fabs(static_cast<double>(zd::zig_k[i]) - ratio), 4.0) << "layer " << i;
        // Fast-accepted positions stay left of the layer above's edge.
        EXPECT_LT(static_cast<double>(zd::zig_k[i] - 1) * zd::zig_w[i], zd::zig_w[i - 1] * two52) << i;
    }
    const double ratio0 = zd::zig_r / (zd::zig_w[0] * two52) * two52;
    EXPECT_LE(std::fabs(static_cast<double>(zd::zig_k[0]) - ratio0), 4.0);
    EXPECT_LT(static_cast<double>(zd::zig_k[0] - 1) * zd::zig_w[0], zd::zig_r);
    EXPECT_GE(static_cast<double>(zd::zig_k[0]) * zd::zig_w[0], zd::zig_r * (1 - 1e-15));
}

// ---------------------------------------------------------------------------
// ziggurat_fast and ziggurat_resolve on hand-made words

TEST(Ziggurat, FieldsOfTheWord) {
    double x = 1.0;
    // Position 0: +0 or -0 by the sign bit (layer 5: accepted).
    EXPECT_TRUE(ss::ziggurat_fast(zig_word(5, 0, 0), x));
    EXPECT_EQ(bits_of(x), bits_of(0.0));
    EXPECT_TRUE(ss::ziggurat_fast(zig_word(5, 1, 0), x));
    EXPECT_EQ(bits_of(x), bits_of(-0.0));
    // Position p of layer i: p * zig_w[i], sign from bit 8; bits 61-63 ignored.
    for (unsigned idx : {0u, 2u, 7u, 100u, 255u})
        for (unsigned top : {0u, 5u, 7u}) {
            const std::uint64_t p = 123456789;
            ASSERT_LT(p, zd::zig_k[idx]);
            EXPECT_TRUE(ss::ziggurat_fast(zig_word(idx, 0, p, top), x));
            EXPECT_EQ(x, 123456789.0 * zd::zig_w[idx]);
            EXPECT_TRUE(ss::ziggurat_fast(zig_word(idx, 1, p, top), x));
            EXPECT_EQ(x, -123456789.0 * zd::zig_w[idx]);
        }
    // The word is read as documented (not, e.g., index from the high bits).
    EXPECT_TRUE(ss::ziggurat_fast(0x0000000000000207ull, x)); // idx 7, sign 0, pos 1
    EXPECT_EQ(x, zd::zig_w[7]);
    EXPECT_TRUE(ss::ziggurat_fast(0xe000000000000307ull, x)); // idx 7, sign 1, pos 1, top bits set
    EXPECT_EQ(x, -zd::zig_w[7]);
}

TEST(Ziggurat, AcceptsExactlyInsideTheRectangle) {
    double x;
    // Layer 1 (the top) has no rectangle: every position is rejected.
    for (std::uint64_t p : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{1} << 40, ss::ziggurat_position_mask})
        for (unsigned sign : {0u, 1u}) EXPECT_FALSE(ss::ziggurat_fast(zig_word(1, sign, p), x)) << p;
    for (unsigned idx = 0; idx < 256; ++idx) {
        if (idx == 1) continue;
        const std::uint64_t k = zd::zig_k[idx];
        for (unsigned sign : {0u, 1u}) {
            EXPECT_TRUE(ss::ziggurat_fast(zig_word(idx, sign, k - 1), x)) << "layer " << idx;
            EXPECT_EQ(x, (sign ? -1.0 : 1.0) * static_cast<double>(k - 1) * zd::zig_w[idx]) << "layer " << idx;
            EXPECT_FALSE(ss::ziggurat_fast(zig_word(idx, sign, k), x)) << "layer " << idx;
            EXPECT_EQ(x, (sign ? -1.0 : 1.0) * static_cast<double>(k) * zd::zig_w[idx]) << "layer " << idx;
            EXPECT_FALSE(ss::ziggurat_fast(zig_word(idx, sign, ss::ziggurat_position_mask), x)) << "layer " << idx;
        }
    }
}

TEST(Ziggurat, ResolveOfAnAcceptedWordDrawsNothing) {
    ScriptedWords src{{}};
    const std::uint64_t w = zig_word(42, 1, 987654321);
    double x;
    ASSERT_TRUE(ss::ziggurat_fast(w, x));
    EXPECT_EQ(bits_of(ss::ziggurat_resolve(w, src)), bits_of(x));
    EXPECT_EQ(src.used, 0u);
}

TEST(Ziggurat, ResolveWedge) {
    double x;
    // Just right of layer 100's rectangle, a tiny uniform puts the point under the curve: accept x.
    const std::uint64_t edge = zig_word(100, 1, zd::zig_k[100]);
    ASSERT_FALSE(ss::ziggurat_fast(edge, x));
    ScriptedWords low{{0ull}};
    EXPECT_EQ(bits_of(ss::ziggurat_resolve(edge, low)), bits_of(x));
    EXPECT_EQ(low.used, 1u);
    // At the layer's right edge, a uniform of 1 puts it above the curve: reject and
    // take the next word from the source (here one the fast path accepts).
    const std::uint64_t right = zig_word(100, 0, ss::ziggurat_position_mask);
    const std::uint64_t next = zig_word(7, 1, 12345);
    double x_next;
    ASSERT_TRUE(ss::ziggurat_fast(next, x_next));
    ScriptedWords high{{~0ull, next}};
    EXPECT_EQ(bits_of(ss::ziggurat_resolve(right, high)), bits_of(x_next));
    EXPECT_EQ(high.used, 2u);
    // Top layer, position 0 (x = 0, density 1): accepted by the wedge test.
    ScriptedWords mid{{std::uint64_t{1} << 63}};
    EXPECT_EQ(bits_of(ss::ziggurat_resolve(zig_word(1, 1, 0), mid)), bits_of(-0.0));
}

TEST(Ziggurat, ResolveTail) {
    // Layer 0 beyond r: x = r + xx with xx = -log(u1) / r, accepted when 2 (-log u2) > xx^2.
    const std::uint64_t half_word = std::uint64_t{1} << 63; // u01 = 0.5 (+2^-65, rounded away)
    const double xx = -zd::zig_inv_r * std::log(r123::u01<double>(half_word));
    // First pair: u1 = 2^-65 (xx = 12.3) and u2 = 0.5: rejected; second pair accepted.
    ScriptedWords src{{0ull, half_word, half_word, 0ull}};
    const double z = ss::ziggurat_resolve(zig_word(0, 1, ss::ziggurat_position_mask), src);
    EXPECT_EQ(src.used, 4u);
    EXPECT_EQ(z, -(zd::zig_r + xx));
    EXPECT_LT(z, -zd::zig_r);
    ScriptedWords src2{{half_word, 0ull}};
    EXPECT_EQ(ss::ziggurat_resolve(zig_word(0, 0, zd::zig_k[0]), src2), zd::zig_r + xx);
    EXPECT_EQ(src2.used, 2u);
}

// ---------------------------------------------------------------------------
// The exponential ziggurat (the PDMP engine's waiting times).
// Tables (definition: scripts/dev/make_ziggurat_tables.py --exponential):
//   x_i = zige_w[i] 2^53 (i >= 1), x_255 = zige_r, f_i = zige_f[i] = exp(-x_i),
//   f_0 = 1; every layer has the area V = r e^-r + e^-r (layer 0: the strip of
//   width q = zige_w[0] 2^53 and height f(r), the bottom rectangle plus the
//   tail); zige_k[i] = floor(2^53 x_(i-1) / x_i), zige_k[0] = floor(2^53 r / q).

namespace {
constexpr double two53 = 9007199254740992.0; // 2^53

/// Word of the exponential layout: bits 0-7 layer, bits 8-60 position, 61-63 unused.
std::uint64_t exp_word(unsigned idx, std::uint64_t pos, unsigned top = 0) {
    return std::uint64_t{idx & 0xffu} | ((pos & ss::exponential_ziggurat_position_mask) << 8) |
           (std::uint64_t{top & 7u} << 61);
}
} // namespace

TEST(ExponentialZigguratTables, MonotoneAnchoredAndOfEqualAreas) {
    EXPECT_EQ(zd::zige_k[1], 0u);
    EXPECT_EQ(zd::zige_f[0], 1.0);
    for (int i = 2; i < 256; ++i) EXPECT_LT(zd::zige_w[i - 1], zd::zige_w[i]) << i;
    for (int i = 0; i < 256; ++i) EXPECT_LE(zd::zige_k[i], ss::exponential_ziggurat_position_mask) << i;
    EXPECT_EQ(zd::zige_w[255] * two53, zd::zige_r);
    const double r = zd::zige_r, V = r * std::exp(-r) + std::exp(-r);
    for (int i = 1; i < 256; ++i) {
        const double x = zd::zige_w[i] * two53;
        EXPECT_NEAR(zd::zige_f[i], std::exp(-x), 4e-15 * std::exp(-x)) << "layer " << i;
        EXPECT_NEAR(x * (zd::zige_f[i - 1] - zd::zige_f[i]), V, 1e-12 * V) << "layer " << i;
    }
    EXPECT_NEAR(zd::zige_w[0] * two53 * zd::zige_f[255], V, 1e-12 * V); // base strip = rectangle + tail
    const double x1 = zd::zige_w[1] * two53;
    EXPECT_NEAR(x1 * (1 - std::exp(-x1)), V, 1e-12 * V); // the top layer closes
    EXPECT_GT(256 * V, 1.0);                              // the density's area, plus the wedges
    EXPECT_LT(256 * V, 1.02);
    for (int i = 2; i < 256; ++i) {
        EXPECT_LE(std::fabs(static_cast<double>(zd::zige_k[i]) - zd::zige_w[i - 1] / zd::zige_w[i] * two53), 4.0) << i;
        // Fast-accepted positions stay inside the rectangle (with 53-bit positions
        // the largest may round onto its edge x_(i-1)).
        EXPECT_LE(static_cast<double>(zd::zige_k[i] - 1) * zd::zige_w[i], zd::zige_w[i - 1] * two53) << i;
    }
    EXPECT_LT(static_cast<double>(zd::zige_k[0] - 1) * zd::zige_w[0], zd::zige_r);
    EXPECT_GE(static_cast<double>(zd::zige_k[0]) * zd::zige_w[0], zd::zige_r * (1 - 1e-15));
}

TEST(ExponentialZiggurat, ReadsTheWordAsDocumentedAndAcceptsInsideTheRectangle) {
    double x = -1.0;
    EXPECT_TRUE(ss::exponential_ziggurat_fast(exp_word(5, 0), x));
    EXPECT_EQ(bits_of(x), bits_of(0.0));
    for (unsigned idx : {0u, 2u, 7u, 100u, 255u})
        for (unsigned top : {0u, 7u}) {
            EXPECT_TRUE(ss::exponential_ziggurat_fast(exp_word(idx, 123456789, top), x));
            EXPECT_EQ(x, 123456789.0 * zd::zige_w[idx]);
        }
    EXPECT_TRUE(ss::exponential_ziggurat_fast(0x0000000000000107ull, x)); // idx 7, pos 1
    EXPECT_EQ(x, zd::zige_w[7]);
    for (std::uint64_t p : {std::uint64_t{0}, std::uint64_t{1} << 40, ss::exponential_ziggurat_position_mask})
        EXPECT_FALSE(ss::exponential_ziggurat_fast(exp_word(1, p), x)) << p; // the top layer has no rectangle
    for (unsigned idx = 0; idx < 256; ++idx) {
        if (idx == 1) continue;
        const std::uint64_t k = zd::zige_k[idx];
        EXPECT_TRUE(ss::exponential_ziggurat_fast(exp_word(idx, k - 1), x)) << idx;
        EXPECT_EQ(x, static_cast<double>(k - 1) * zd::zige_w[idx]) << idx;
        EXPECT_FALSE(ss::exponential_ziggurat_fast(exp_word(idx, k), x)) << idx;
    }
}

TEST(ExponentialZiggurat, ResolvesWedgesAndTheTail) {
    double x;
    // An accepted word draws nothing.
    ScriptedWords none{{}};
    ASSERT_TRUE(ss::exponential_ziggurat_fast(exp_word(42, 987654321), x));
    EXPECT_EQ(bits_of(ss::exponential_ziggurat_resolve(exp_word(42, 987654321), none)), bits_of(x));
    EXPECT_EQ(none.used, 0u);
    // Just right of layer 100's rectangle, a tiny uniform lies under the curve: accept.
    const std::uint64_t edge = exp_word(100, zd::zige_k[100]);
    ASSERT_FALSE(ss::exponential_ziggurat_fast(edge, x));
    ScriptedWords low{{0ull}};
    EXPECT_EQ(bits_of(ss::exponential_ziggurat_resolve(edge, low)), bits_of(x));
    EXPECT_EQ(low.used, 1u);
    // At the layer's right edge a uniform of 1 lies above it: reject, take the next word.
    const std::uint64_t next = exp_word(7, 12345);
    double x_next;
    ASSERT_TRUE(ss::exponential_ziggurat_fast(next, x_next));
    ScriptedWords high{{~0ull, next}};
    EXPECT_EQ(bits_of(ss::exponential_ziggurat_resolve(exp_word(100, ss::exponential_ziggurat_position_mask), high)),
              bits_of(x_next));
    EXPECT_EQ(high.used, 2u);
    // The tail: r - log(u), one word.
    const std::uint64_t half_word = std::uint64_t{1} << 63;
    ScriptedWords tail{{half_word}};
    const double t = ss::exponential_ziggurat_resolve(exp_word(0, ss::exponential_ziggurat_position_mask), tail);
    EXPECT_EQ(t, zd::zige_r - std::log(r123::u01<double>(half_word)));
    EXPECT_EQ(tail.used, 1u);
}

TEST(BatchedUniformRng, ExponentialUniformBitwiseEqualToCounterRngAndReachesTheSlowPath) {
    int slow = 0, tail = 0;
    for (const StreamId& s : many_streams()) {
        ss::CounterRng ref(s.seed, s.purpose, s.index), raw(s.seed, s.purpose, s.index);
        ss::BatchedUniformRng bat(s.seed, s.purpose, s.index);
        for (int k = 0; k < 2000; ++k) {
            const std::string at = where(s) + ", draw " + std::to_string(k);
            double e0, u0, e1, u1;
            ref.exponential_uniform(e0, u0);
            bat.exponential_uniform(e1, u1);
            ASSERT_EQ(bits_of(e0), bits_of(e1)) << at;
            ASSERT_EQ(bits_of(u0), bits_of(u1)) << at;
            ASSERT_EQ(ref.draws(), bat.draws()) << at;
            // The block's words: the exponential of the first, the uniform of the second.
            const auto b = raw.next_block();
            const std::uint64_t w0 = ss::CounterRng::join(b.v[0], b.v[1]);
            double x;
            if (!ss::exponential_ziggurat_fast(w0, x)) {
                ++slow;
                tail += (w0 & 0xffu) == 0 ? 1 : 0;
            } else {
                ASSERT_EQ(bits_of(e0), bits_of(x)) << at;
            }
            ASSERT_EQ(bits_of(u0), bits_of(r123::u01<double>(ss::CounterRng::join(b.v[2], b.v[3])))) << at;
            ASSERT_GE(e0, 0.0) << at;
        }
    }
    // 128000 words: 2.2% take the slow path (1 - the rectangles' share), ~1/40 of those the base layer.
    EXPECT_GT(slow, 500);
    EXPECT_GT(tail, 0);
    std::cout << "[measured] exponential ziggurat: " << slow << " of 128000 words on the slow path, " << tail
              << " in the base layer" << std::endl;
}
