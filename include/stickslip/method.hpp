// SPDX-License-Identifier: BSD-3-Clause
// stickslip/method.hpp -- how a result was computed: by sampling or by a solver.
//
// Every quantity chooses its method once, at its top: Monte Carlo over one of
// the engines (long excursions, trajectories) or a deterministic solver (the
// white-noise closed forms and Fokker-Planck grid today; a Kolmogorov grid
// solver next). A result carries its estimates, which look the same whatever
// the method, and the method's details as a variant, so that the reports
// print what each method has: a sampled result its samples, engine, work and
// notes; a solved one its grid, domain and discretisation error, with no
// empty totals and no standard error it does not have. The method axis sits
// above the engines (ARCHITECTURE.md), so a new solver adds an alternative
// here, not a check in every report.
#pragma once

/// \file
/// The method details of a result. The comment at the top of this header
/// explains the design.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>

#include "stickslip/run.hpp"
#include "stickslip/stats/run_totals.hpp"

namespace stickslip {

/// A result computed by sampling.
struct MonteCarloDetails {
    /// The engine's resolved choices (stop rule, lattice, thresholds).
    ResolvedEngine engine;
    /// The samples: their exact sums, counts (requested, capped, resumed),
    /// work (steps or events), wall time and threads.
    RunTotals totals;
};

/// A result computed by a deterministic solver.
struct GridDetails {
    /// The solver: "closed form" (no grid) or "fokker-planck".
    std::string solver;
    /// Cells of its grid; 0 for a closed form.
    std::uint64_t cells = 0;
    double lower = 0; ///< lower end of the grid's domain in the velocity [m/s] (0: closed form)
    double upper = 0; ///< upper end of the grid's domain in the velocity [m/s] (0: closed form)
    /// Estimated relative discretisation error of its results; 0 where they
    /// are exact to rounding (closed forms).
    double discretisation_error = 0;
};

/// How a result was computed.
using MethodDetails = std::variant<MonteCarloDetails, GridDetails>;

/// What every result has besides its estimates: the details of its method.
/// Sampled by default (the first alternative).
struct MethodResult {
    /// The method and its details.
    MethodDetails details;

    /// Whether the result was sampled.
    bool sampled() const { return std::holds_alternative<MonteCarloDetails>(details); }
    /// The sampling details; std::logic_error for a solved result.
    MonteCarloDetails& monte_carlo() { return get<MonteCarloDetails>(); }
    /// The sampling details; std::logic_error for a solved result.
    const MonteCarloDetails& monte_carlo() const { return const_cast<MethodResult*>(this)->monte_carlo(); }
    /// The solver's details; std::logic_error for a sampled result.
    GridDetails& grid() { return get<GridDetails>(); }
    /// The solver's details; std::logic_error for a sampled result.
    const GridDetails& grid() const { return const_cast<MethodResult*>(this)->grid(); }

private:
    template <class D>
    D& get() {
        if (D* d = std::get_if<D>(&details)) return *d;
        throw std::logic_error("stickslip: the result was computed by another method");
    }
};

} // namespace stickslip
