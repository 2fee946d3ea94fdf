// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/device_excursions.hpp -- the per-thread loop of the CUDA backend,
// written once for the device and the host.
//
// Why: the CUDA kernels (src/engines/cuda/long_excursions.cu) must compute the same
// long excursions as the CPU engine, bit for bit. Everything they do per
// thread is here, as STICKSLIP_HD code over the engine's own step kernels
// (resolvent.hpp, event_scheme.hpp) and random streams (CounterRng, one
// stream per excursion index), so that the host tests (tests/gpu_host, label
// gpu-host) compile exactly this loop as host code and check it against the
// CPU engine on every machine, with or without CUDA: the kernels stay one code.
//
// How a device thread works: it takes the index of its next excursion from a
// shared counter (`next`, an atomic add on the device), runs that excursion
// to its end and writes the outcome to out[index], and takes another until
// the indices run out. Excursions have very unequal lengths, so a thread that
// finishes early starts the next one at once instead of idling until its
// warp's longest excursion ends, and the two halves of an excursion share one
// step loop (a state machine, as the SIMD lanes of resolvent_lanes.hpp do),
// so a warp's threads stay on the same instructions whatever half each is in.
// An outcome depends only on its index, so neither the order in which
// excursions are taken nor the thread that runs one can change a bit; the
// host merges the outcomes per block of 64 in index order, as the CPU engine
// does (run_blocks).
//
// The one difference between the device and the host is the transcendental
// functions (portable_math.hpp): the device computes exp, log and log1p with
// the project's own implementation, the host with glibc unless built with
// STICKSLIP_PORTABLE_MATH.
#pragma once

/// \file
/// The per-thread loop of the CUDA backend (long excursions of the inclusion
/// engine, both schemes), host- and device-callable. The comment at the top of
/// this header explains the design.

#include <cstdint>

#include "stickslip/config.hpp"
#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/kernels/resolvent.hpp"
#include "stickslip/random/rng.hpp"

namespace stickslip {

/// One device thread's share of the long excursions first .. first+count-1
/// of the inclusion engine (resolvent scheme, step kind K, c's): while next()
/// gives an i < count, excursion first + i on the stream (seed,
/// LongExcursion, first + i) into out[i], bitwise
/// resolvent_long_excursion(c, CounterRng(seed, LongExcursion, first + i)).
/// next() must hand out 0, 1, 2, ... across all threads, each value once.
template <StepKind K, class Next>
STICKSLIP_HD inline void device_resolvent_worker(const ResolventConstants& c, std::uint64_t seed,
                                                 std::uint64_t first, std::uint64_t count, Next& next,
                                                 ExcursionOutcome* out) {
    std::uint64_t i = next();
    if (i >= count) return;
    CounterRng rng(seed, StreamPurpose::LongExcursion, first + i);
    ResolventWalk w;
    resolvent_walk_start_half(c, w, +1);
    NoPathObserver none;
    for (;;) {
        const WalkStatus st = resolvent_walk_step_as<K>(c, w, rng, none);
        if (st == WalkStatus::Running) continue;
        if (st == WalkStatus::HalfDone && w.dir > 0) { // the +HLE is over: the -HLE follows
            w.first = w.steps;
            resolvent_walk_start_half(c, w, -1);
            continue;
        }
        out[i] = resolvent_walk_outcome(c, w, st == WalkStatus::Capped);
        i = next();
        if (i >= count) return;
        rng = CounterRng(seed, StreamPurpose::LongExcursion, first + i);
        w = ResolventWalk{};
        resolvent_walk_start_half(c, w, +1);
    }
}

/// device_resolvent_worker for c's step kind (with_step_kind): for host code;
/// the CUDA backend launches one kernel per kind.
template <class Next>
STICKSLIP_HD inline void device_resolvent_worker(const ResolventConstants& c, std::uint64_t seed,
                                                 std::uint64_t first, std::uint64_t count, Next& next,
                                                 ExcursionOutcome* out) {
    with_step_kind(c, [&](auto kind) { device_resolvent_worker<kind.value>(c, seed, first, count, next, out); });
}

/// The same for the event scheme: excursion first + i on the streams (seed,
/// LongExcursion, first + i) and (seed, Refinement, first + i) into out[i],
/// bitwise event_long_excursion(c, rng, ref) with those streams.
template <class Next>
STICKSLIP_HD inline void device_event_worker(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                             std::uint64_t count, Next& next, ExcursionOutcome* out) {
    std::uint64_t i = next();
    if (i >= count) return;
    CounterRng rng(seed, StreamPurpose::LongExcursion, first + i);
    CounterRng ref(seed, StreamPurpose::Refinement, first + i);
    EventWalk w;
    event_start_half(c, w, +1);
    NoPieceObserver none;
    for (;;) {
        const EventStatus st = event_step(c, w, 0, rng, ref, none);
        if (st == EventStatus::Running) continue;
        if (st == EventStatus::HalfDone && w.dir > 0) {
            w.first = w.t;
            event_start_half(c, w, -1);
            continue;
        }
        out[i] = event_walk_outcome(c, w, st == EventStatus::Capped);
        i = next();
        if (i >= count) return;
        rng = CounterRng(seed, StreamPurpose::LongExcursion, first + i);
        ref = CounterRng(seed, StreamPurpose::Refinement, first + i);
        w = EventWalk{};
        event_start_half(c, w, +1);
    }
}

} // namespace stickslip
