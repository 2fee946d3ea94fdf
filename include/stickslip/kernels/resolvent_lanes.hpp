// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/resolvent_lanes.hpp -- eight long excursions in SIMD lanes.
//
// Why: a colored-noise step is a short chain of dependent floating-point
// operations on (X, V), and 89% of the Fig. 2 case's steps are stuck steps
// that end the same way. One excursion at a time, a core spends a third of a
// step's time on this chain and on tests; eight excursions side by side make
// the common step a few vector instructions, leaving the random numbers
// (rng_batch.hpp) as nearly the whole cost.
//
// How: the eight excursions advance in lockstep, one main-stream block per
// step each (the bridge test's extra uniform comes from a side block, see
// rng.hpp), so their normals sit in one buffer indexed (half, step, lane). Each
// vector step applies the plain step (free flight, soft threshold, X update)
// to every lane where it is certain to be what the one-excursion kernel does;
// a lane where anything else can happen -- the half ends, the bridge test
// needs its uniform, the step cap -- is left untouched and redone by
// resolvent_walk_step_as itself. A finished lane takes the next excursion.
// The outcomes are therefore bitwise those of resolvent_long_excursion with
// CounterRng (tests/unit/resolvent_lanes_test.cpp), on any instruction set:
// the file is compiled with -ffp-contract=off, once per x86-64 level.
//
// With a corrector (the control variate, kernels/corrector.hpp) each lane also
// sums its martingale M and Q, step by step as the one-excursion kernel does.
//
// Colored noise only; white noise runs the one-excursion kernel, and so does
// every machine where the lane step is not vectorised (it is for AVX-512 with
// GCC 12; AVX2 and older x86-64 get the one-excursion kernel). Host only.
#pragma once

/// \file
/// Eight long excursions of the inclusion engine in SIMD lanes, bitwise equal
/// to one at a time. The comment at the top of this header explains the design.

#include <atomic>
#include <cstdint>

#include "stickslip/excursion.hpp"
#include "stickslip/kernels/resolvent.hpp"

namespace stickslip {

/// Excursions in flight per thread in resolvent_long_excursions.
inline constexpr int lane_count = 8;

/// Runs the long excursions of sample indices first .. first+count-1, streams
/// (seed, LongExcursion, index), and writes excursion first+i to out[i]:
/// bitwise what resolvent_long_excursion(c, CounterRng(seed, LongExcursion,
/// first+i)) returns. Stops starting new excursions once *cancel is set and
/// then returns false (out is incomplete); returns true when all are done
/// (also when the cancel comes after the last excursion has started).
bool resolvent_long_excursions(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first,
                               std::uint64_t count, ExcursionOutcome* out,
                               const std::atomic<bool>* cancel = nullptr);

/// resolvent_long_excursions with the martingale of the corrector g in each
/// outcome: bitwise what resolvent_long_excursion_with returns, in SIMD lanes
/// where resolvent_long_excursions runs them (each lane keeps its own M and
/// Q); U and t bitwise those of resolvent_long_excursions.
bool resolvent_long_excursions_with(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first,
                                    std::uint64_t count, ExcursionOutcome* out, const std::atomic<bool>* cancel,
                                    const CorrectorTable& g);

/// Whether resolvent_long_excursions runs SIMD lanes on this machine (x86-64
/// with AVX-512 and a GCC build); otherwise it runs the one-excursion kernel,
/// with the same results.
bool resolvent_lanes_vectorised();

/// A short description of the colored-noise kernel in use, for reports.
const char* resolvent_kernel_name();

namespace detail {
/// resolvent_long_excursions with the lanes forced on any machine (white
/// noise still runs the one-excursion kernel): the same results, slower where
/// the lane step is not vectorised. For tests, so that the lane code is
/// checked on every instruction set, not only where it is the default.
bool resolvent_long_excursions_in_lanes(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first,
                                        std::uint64_t count, ExcursionOutcome* out,
                                        const std::atomic<bool>* cancel = nullptr);
/// resolvent_long_excursions_with with the lanes forced on any machine (white
/// noise and a knots law run one excursion at a time), for the same tests.
bool resolvent_long_excursions_in_lanes_with(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first,
                                             std::uint64_t count, ExcursionOutcome* out,
                                             const std::atomic<bool>* cancel, const CorrectorTable& g);
} // namespace detail

} // namespace stickslip
