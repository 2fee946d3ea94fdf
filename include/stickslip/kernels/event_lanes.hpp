// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/event_lanes.hpp -- eight long excursions of the event scheme in
// SIMD lanes.
//
// Why: most steps of the event scheme are quiet -- a stuck step whose noise
// stays far inside the band, or a sliding step whose velocity stays far from
// 0 -- and then the step is one exact Gaussian update (phase_law.hpp) and a
// test. One excursion at a time, a core spends most of such a step on the
// chain of dependent operations and on branches; eight excursions side by
// side make it a few vector instructions, and their normals (and, for the
// sliding lanes, their side draws) are generated 32 draws at a time
// (rng_batch.hpp).
//
// How: as resolvent_lanes.hpp. The eight excursions advance in lockstep, one
// draw per step each. Each vector step applies the whole step to every lane
// where it is quiet (detail::stuck_step_is_quiet, detail::slide_step_is_quiet:
// sufficient conditions of event_colored_step's own decisions, the first one
// also its own first test); a lane where anything else
// can happen -- an event, a refinement, the step cap -- is left untouched and
// redone by event_colored_step itself, with the same draw and the lane's own
// refinement stream. A finished lane takes the next excursion. The outcomes
// are therefore bitwise those of event_long_excursion
// (tests/unit/event_lanes_test.cpp), on any instruction set: the file is
// compiled with -ffp-contract=off, once per x86-64 level.
//
// Coloured noise only; white noise runs the one-excursion kernel, and so do
// steps longer than relaxation/16 (many of them are not quiet: measured
// slower in lanes, see lanes_pay in event_lanes.cpp) and every machine where the
// lane step is not vectorised (resolvent_lanes_vectorised). Host only.
#pragma once

/// \file
/// Eight long excursions of the event scheme in SIMD lanes, bitwise equal to
/// one at a time. The comment at the top of this header explains the design.

#include <atomic>
#include <cstdint>

#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/excursion.hpp"

namespace stickslip {

/// Runs the event scheme's long excursions of the sample indices from first
/// to first+count-1, with the streams (seed, LongExcursion, index) and (seed,
/// Refinement, index), and writes excursion first+i to out[i]: bitwise what
/// event_long_excursion(c, CounterRng(seed, LongExcursion, first+i),
/// CounterRng(seed, Refinement, first+i)) returns. Stops starting new
/// excursions once *cancel is set and then returns false (out is incomplete);
/// returns true when all are done.
bool event_long_excursions(const EventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                           ExcursionOutcome* out, const std::atomic<bool>* cancel = nullptr);

/// event_long_excursions (coloured noise) with the martingale of the
/// corrector g in each outcome: bitwise what event_long_excursion_with
/// returns, in SIMD lanes where event_long_excursions runs them (each lane
/// keeps its own M and Q); U and t bitwise those of event_long_excursions.
bool event_long_excursions_with(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                std::uint64_t count, ExcursionOutcome* out, const std::atomic<bool>* cancel,
                                const CorrectorTable& g);

namespace detail {
/// event_long_excursions with the lanes forced on any machine (white noise
/// still runs one excursion at a time): the same results. For tests.
bool event_long_excursions_in_lanes(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                    std::uint64_t count, ExcursionOutcome* out,
                                    const std::atomic<bool>* cancel = nullptr);
/// event_long_excursions_with with the lanes forced on any machine (white
/// noise one excursion at a time), for the same tests.
bool event_long_excursions_in_lanes_with(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                         std::uint64_t count, ExcursionOutcome* out,
                                         const std::atomic<bool>* cancel, const CorrectorTable& g);
} // namespace detail

} // namespace stickslip
