// Internal: checks and warnings shared by every long-excursion computation
// (diffusivity, stationary density, correlation), so they say the same thing.
#pragma once

#include <string>
#include <vector>

#include "stickslip/diffusivity.hpp"

namespace stickslip::detail {

/// Throws CappedExcursions when excursions hit the runaway guard (unless
/// allowed: then warns) or fewer than 2 completed; adds the standard warnings
/// (truncated PDMP lattice, few excursions, meaning of mean_duration).
void finish_long_excursion_run(const ModelParams& p, const EngineSettings& s, const ResolvedEngine& resolved,
                               const RunTotals& totals, bool allow_capped, std::vector<std::string>& warnings);

/// Checks a trajectory start: v0 [m/s] finite ("v0"); x0 [s^-1/2] finite or
/// NaN, which means "the default start" ("x0").
void check_start(double x0, double v0);

} // namespace stickslip::detail
