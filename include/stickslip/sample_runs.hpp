// SPDX-License-Identifier: BSD-3-Clause
// stickslip/sample_runs.hpp -- parallel, reproducible Monte Carlo runs: long
// excursions, brute-force trajectories, and the generic block driver under
// them (src/driver/sample_runs.cpp, block_driver.hpp).
//
// Sample k (a long excursion or a brute-force trajectory) draws only from the
// stream (seed, purpose, k); blocks of samples are merged into exact,
// order-free sums (stats/run_totals.hpp), so every result is bitwise identical
// for any thread count, any split of the blocks across processes (reduced in
// any order) and any interruption and resumption of a run (run_control.hpp).
#pragma once

/// \file
/// The run loops of the Monte Carlo engines. The comment at the top of this
/// header explains the design.

#include <cstdint>
#include <functional>
#include <string>

#include "stickslip/excursion.hpp"
#include "stickslip/kernels/corrector.hpp"
#include "stickslip/params.hpp"
#include "stickslip/run_control.hpp"
#include "stickslip/stats/run_totals.hpp"

namespace stickslip {

struct PreparedEngine; // prepared_engine.hpp

/// N long excursions of a prepared engine (run.hpp), which is trusted.
RunTotals run_long_excursions(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl);
/// The same with the martingale of the corrector g accumulated in every
/// excursion (kernels/corrector.hpp) into RunTotals::control_variate; U and t,
/// and so `sums`, are bitwise those of the plain run. The engine must have a
/// martingale kernel (engine_has_martingale), else std::logic_error. With
/// `centres`, RunTotals::control_variate also sums the shape of the plain
/// and the control variate's influence functions at them (influence_tail.hpp).
RunTotals run_long_excursions(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl,
                              const CorrectorTable& g, const InfluenceCentres* centres = nullptr);
/// Whether the prepared engine's kernels accumulate a martingale: the PDMP,
/// the inclusion engine's resolvent scheme, and its event scheme with
/// coloured noise; otherwise *why (if given) says why not, for a note.
bool engine_has_martingale(const PreparedEngine& e, std::string* why = nullptr);
/// The same, preparing (and so validating) the engine first.
RunTotals run_long_excursions(const ModelParams& p, const EngineSettings& s, std::uint64_t excursions,
                              const RunControl& ctl);

/// N brute-force trajectories on [0, horizon] from noise x0 [s^-1/2] and
/// velocity v0 [m/s], of a prepared engine. Moments are of (U(horizon), horizon).
RunTotals run_bruteforce(const PreparedEngine& e, double horizon, double x0, double v0, std::uint64_t trajectories,
                         const RunControl& ctl);
/// The same, preparing (and so validating) the engine and the start first.
RunTotals run_bruteforce(const ModelParams& p, const EngineSettings& s, double horizon, double x0,
                         double v0, std::uint64_t trajectories, const RunControl& ctl);

/// Generic driver used by both: calls sample(index) for every index in
/// [first_index, first_index + n) in parallel; blocks are merged exactly.
RunTotals run_samples(std::uint64_t n, const RunControl& ctl,
                      const std::function<ExcursionOutcome(std::uint64_t)>& sample);

} // namespace stickslip
