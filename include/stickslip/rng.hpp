// stickslip/rng.hpp -- counter-based random streams.
//
// Why counter-based: every excursion (or brute-force trajectory) k owns the
// stream (seed, purpose, k). Its random numbers depend on nothing else, so a
// result is bitwise identical for any number of threads and any split of the
// sample indices across processes or GPU threads.
//
// Layout, after HOOMD-blue's RandomNumbers.h: the *key* is static (the user's
// 64-bit seed); the *counter* is dynamic: two words hold the sample index
// (56 bits) and the purpose (8 bits), two words hold the draw number within the
// sample. The generator is Random123's Philox4x32-10, which passes BigCrush and
// costs about 1 ns per call; each call yields 128 bits.
#pragma once

#include <cmath>
#include <cstdint>

#include <Random123/boxmuller.hpp>
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include "config.hpp"

namespace stickslip {

/// Which computation a stream belongs to, so that different computations with
/// the same seed and index never share random numbers.
enum class StreamPurpose : std::uint32_t {
    LongExcursion = 1,
    BruteForce = 2,
    Observable = 3,
    SamplingPhase = 4, ///< random phase of a PDMP path's sampling grid (observables)
    Test = 255,
};

/// Largest sample index a stream can take (56 bits).
inline constexpr std::uint64_t max_sample_index = (std::uint64_t{1} << 56) - 1;

class CounterRng {
public:
    using Philox = r123::Philox4x32;

    STICKSLIP_HD CounterRng(std::uint64_t seed, StreamPurpose purpose, std::uint64_t index) {
        key_ = {{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}};
        ctr_ = {{0u, 0u, static_cast<std::uint32_t>(index),
                 static_cast<std::uint32_t>((index >> 32) & 0x00ffffffu) |
                     (static_cast<std::uint32_t>(purpose) << 24)}};
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

    /// Two independent standard normals (Box-Muller on two 64-bit uniforms).
    STICKSLIP_HD r123::double2 normal2() {
        Philox::ctr_type b = next_block();
        return r123::boxmuller(join(b.v[0], b.v[1]), join(b.v[2], b.v[3]));
    }

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

private:
    STICKSLIP_HD static std::uint64_t join(std::uint32_t lo, std::uint32_t hi) {
        return (static_cast<std::uint64_t>(hi) << 32) | lo;
    }

    Philox::key_type key_;
    Philox::ctr_type ctr_;
};

} // namespace stickslip
