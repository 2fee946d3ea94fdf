// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kolmogorov.hpp -- D, M0, P(V = 0) and the stationary velocity law
// with coloured noise, without sampling: the Kolmogorov equations of (X, V)
// solved on a grid (theory.md, section "Kolmogorov equations").
//
// PLACEHOLDER: the full account is written below the declarations once measured.
#pragma once

/// \file
/// A grid solver for the stationary Kolmogorov equations of (X, V): D, M0,
/// P(V = 0) and the stationary velocity density, with an estimated
/// discretisation error. The comment at the top of this header explains the
/// design.

#include <cstddef>
#include <string>
#include <vector>

#include "stickslip/method.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

/// The geometry of one grid, in SI units. solve_kolmogorov chooses it from
/// KolmogorovSettings; solve_kolmogorov_grid takes it as it is.
struct KolmogorovGrid {
    double lower_threshold = 0;   ///< x-* = (-friction - b(0))/a [s^-1/2], a node
    double upper_threshold = 0;   ///< x* = (friction - b(0))/a [s^-1/2], a node
    double x_spacing = 0;         ///< h = (x* - x-*)/band_intervals [s^-1/2]
    std::size_t band_intervals = 0; ///< grid intervals across the static band (>= 2)
    std::size_t band_first = 0;   ///< index of the node x-*: nodes x-* + (j - band_first) h
    std::size_t x_nodes = 0;      ///< number of x nodes
    double v_lower = 0;           ///< lower end of the velocity range [m/s], < 0
    double v_upper = 0;           ///< upper end of the velocity range [m/s], > 0
    std::size_t v_cells_neg = 0;  ///< velocity cells on [v_lower, 0)
    std::size_t v_cells_pos = 0;  ///< velocity cells on (0, v_upper]
    double v_stretch = 0;         ///< s: faces at end u^{q-1} (e^{s u} - 1)/(e^s - 1), u = k/m (s = 0: end u^q)
    double v_grading = 1;         ///< q >= 1: grading of the cells at v = 0

    /// The lowest x node [s^-1/2].
    double x_lower() const { return lower_threshold - static_cast<double>(band_first) * x_spacing; }
    /// The highest x node [s^-1/2].
    double x_upper() const { return x_lower() + static_cast<double>(x_nodes - 1) * x_spacing; }
};

/// The exact solution of the chain on one grid.
struct KolmogorovGridSolution {
    KolmogorovGrid grid;            ///< the grid
    std::size_t states = 0;         ///< states of the chain (unknowns)
    std::size_t lu_nonzeros = 0;    ///< nonzeros of the sparse LU factors (memory ~ 12 bytes each)
    double diffusivity = 0;         ///< D of the chain [m^2/s]
    double diffusivity_x = 0;       ///< the x moves' carre du champ of chi [m^2/s] (D less the upwind diffusion)
    double mobility = 0;            ///< M0 of the chain [m/s]
    double stuck_probability = 0;   ///< P(V = 0) of the chain
    double tail_mass = 0;           ///< stationary mass on the end x nodes and outermost v cells
    double seconds = 0;             ///< wall time of building and solving [s]
    std::vector<double> velocity_faces;   ///< faces of the velocity cells, increasing [m/s]
    std::vector<double> velocity_density; ///< v-marginal density of the sliding states per cell [s/m]
};

/// Resolution and budget of solve_kolmogorov. Zero means automatic where said.
struct KolmogorovSettings {
    std::size_t band_intervals = 0; ///< x intervals across the static band on the coarsest grid (0: auto)
    std::size_t v_cells = 0;        ///< velocity cells per half line on the coarsest grid (0: auto)
    double x_range = 7.0;           ///< x nodes cover +-x_range standard deviations of X (1/sqrt(tau))
    double v_lower = 0;             ///< lower end of the velocity range [m/s] (< 0; 0: auto)
    double v_upper = 0;             ///< upper end of the velocity range [m/s] (> 0; 0: auto)
    double v_stretch = 0.0;         ///< stretching of the velocity cells (KolmogorovGrid::v_stretch)
    double v_grading = 3.0;         ///< grading of the velocity cells at 0 (KolmogorovGrid::v_grading)
    double rel_precision = 1e-3;    ///< target relative error of D
    double memory_budget = 2e9;     ///< bytes the factorisation may take
    double time_budget = 10.0;      ///< seconds the whole solve may take
    int threads = 2;                ///< threads (1 or 2: the finest grid of a round beside the others)
};

/// A value with its estimated discretisation error (an absolute error, in the
/// value's unit).
struct KolmogorovEstimate {
    double value = 0; ///< extrapolated value
    double error = 0; ///< estimated absolute error of value
};

/// What solve_kolmogorov returns. details holds GridDetails (solver
/// "kolmogorov", the finest grid's states, its velocity range and the relative
/// error estimate of D).
struct KolmogorovResult : MethodResult {
    ModelParams params;                  ///< the model, SI units
    KolmogorovEstimate diffusivity;      ///< D [m^2/s]
    KolmogorovEstimate mobility;         ///< M0 [m/s]
    KolmogorovEstimate stuck_probability; ///< P(V = 0)
    /// D from the x moves' carre du champ of chi, E[(2/tau^2) chi_x^2], extrapolated
    /// like D: the same continuum limit with a different discretisation error,
    /// a check on the extrapolation [m^2/s].
    KolmogorovEstimate diffusivity_x;
    std::vector<KolmogorovGridSolution> levels; ///< the grids solved, coarse to fine
    bool converged = false;              ///< whether D's estimated error is below rel_precision
    std::string note;                    ///< why not, or other remarks; empty when none
    double seconds = 0;                  ///< wall time [s]
};

/// Bytes of memory per nonzero of the LU factors, for the memory budget
/// (value, row index and the supernodal structure's overhead; measured).
inline constexpr double kolmogorov_bytes_per_lu_nonzero = 16.0;

/// The smallest nondimensional tau' = tau friction^2/noise the solver takes.
inline constexpr double kolmogorov_min_tau_prime = 0.05;

/// Solves the chain on one given grid (SI units; p validated, tau > 0).
KolmogorovGridSolution solve_kolmogorov_grid(const ModelParams& p, const KolmogorovGrid& grid);

/// The grid of refinement level `level` (0: coarsest; each level halves the
/// x spacing and the velocity cells' widths) that solve_kolmogorov uses.
KolmogorovGrid kolmogorov_grid(const ModelParams& p, const KolmogorovSettings& settings, int level);

/// Throws InvalidParameter for what solve_kolmogorov refuses.
void validate_kolmogorov(const ModelParams& p, const KolmogorovSettings& settings);

/// D, M0 and P(V = 0) of p by grid refinement and extrapolation.
KolmogorovResult solve_kolmogorov(const ModelParams& p, const KolmogorovSettings& settings = {});

} // namespace stickslip
