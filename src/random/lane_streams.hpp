// SPDX-License-Identifier: BSD-3-Clause
// lane_streams.hpp -- what the two SIMD lane kernels (resolvent_lanes.cpp,
// event_lanes.cpp) share: handing out a run's sample indices to lanes, and
// each lane's main-stream normals buffered by (half, step, lane).
//
// Why: both kernels advance eight excursions in lockstep, one main-stream
// draw per step each, so their normals sit in one buffer that the vector step
// reads lane by lane; a finished lane takes the next sample index. The lane
// groups keep their own arrays (the vector loops read them as fields of one
// object, which is what lets GCC vectorise them); these helpers fill them.
#pragma once

#include <atomic>
#include <cstdint>

#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"

namespace stickslip::detail {

/// Hands out the sample slots 0 .. count-1 of a run in order, until they are
/// used up or *cancel is set. Only a cancel that stops an excursion from
/// starting counts: one that arrives after the last has started leaves the
/// run complete.
class LaneDealer {
public:
    LaneDealer(std::uint64_t count, const std::atomic<bool>* cancel) : count_(count), cancel_(cancel) {}

    /// The next slot into `slot`; false when none is left or the run is cancelled.
    bool next(std::uint64_t& slot) {
        if (next_ < count_ && cancel_ && cancel_->load(std::memory_order_relaxed)) cancelled_ = true;
        if (cancelled_ || next_ >= count_) return false;
        slot = next_++;
        return true;
    }

    /// Whether a cancel stopped an excursion from starting.
    bool cancelled() const { return cancelled_; }

private:
    const std::uint64_t count_;
    const std::atomic<bool>* const cancel_;
    std::uint64_t next_ = 0;
    bool cancelled_ = false;
};

/// Normals of lane l of group g (its fields z[2][B][L], c2, c3, base) for the
/// draws base .. base+B-1 of its stream, from buffer position `from` on.
template <class Group>
void refill_lane_normals(Group& g, const CounterRng::Philox::key_type& key, int l, int from) {
    constexpr int B = rng_batch_size;
    std::uint32_t words[4][B];
    double normals[2][B];
    fill_normals(key, g.c2[l], g.c3[l], g.base[l], words, normals, from);
    for (int h = 0; h < 2; ++h)
        for (int i = from; i < B; ++i) g.z[h][i][l] = normals[h][i];
}

/// Points lane l of group g at the main stream (LongExcursion) of sample
/// `index`, its draw 0 at buffer position `phase` (B: at the next batch), and
/// buffers its normals.
template <class Group>
void start_lane_stream(Group& g, const CounterRng::Philox::key_type& key, int l, std::uint64_t index, int phase) {
    const auto ctr = CounterRng::make_counter(StreamPurpose::LongExcursion, index, 0);
    g.c2[l] = ctr.v[2];
    g.c3[l] = ctr.v[3];
    g.base[l] = std::uint64_t{0} - static_cast<std::uint64_t>(phase);
    if (phase < rng_batch_size) refill_lane_normals(g, key, l, phase);
}

} // namespace stickslip::detail
