// SPDX-License-Identifier: BSD-3-Clause
// The two grids of the near-white solver (near_white.hpp): the scaled noise
// z = sqrt(tau) X on nodes with its moment-exact birth-death chain, and the
// velocity cells graded towards v = 0. Nondimensional units (friction =
// noise = 1, theory.md section 3) throughout.
//
// Why the noise chain is built the way it is. As tau' -> 0 the force
// z/(sqrt(2) eps), eps = sqrt(tau'), becomes a white noise whose intensity is
// the force's integrated autocovariance, (1/eps^2) int_0^inf E[z(0) z(t)] dt.
// For a reversible chain with stationary weights w whose generator G maps the
// function z to -z/tau', that integral is sum_j w_j z_j (-G)^-1 z_j =
// tau' sum_j w_j z_j^2, so the intensity is sum w z^2: exactly the
// continuum's 1 (the noise) when sum w z^2 = 1. So the chain is
// made with (i) weights w: the Gaussian masses of the nodes' dual cells,
// tilted (w exp(mu z - lambda z^2), always positive) so that sum w = 1,
// sum w z = 0 and sum w z^2 = 1 exactly; (ii) edge conductances C_{j+1/2}
// fixed by G z = -z/tau' row by row, C_{j+1/2} (z_{j+1} - z_j) =
// -(1/tau') sum_{i <= j} w_i z_i, which is positive because the partial sums
// of a centred distribution's w z are negative; rates up_j = C/w_j and
// down_{j+1} = C/w_{j+1} (detailed balance with w). Then the white limit holds
// in z on any grid, however coarse: the asymptotic-preserving property that a
// uniform Scharfetter-Gummel grid in X (the present chain) lacks.
#pragma once

#include <cstddef>
#include <vector>

namespace stickslip::detail::near_white {

/// The nodes of the scaled noise z = sqrt(tau) X (a standard normal in the
/// stationary state) and the birth-death chain on them. Rates are per unit
/// of nondimensional time.
struct NoiseGrid {
    std::vector<double> z;      ///< nodes, increasing; the band's edges are nodes
    std::vector<double> weight; ///< stationary weights: sum 1, sum z w = 0, sum z^2 w = 1
    std::vector<double> up;     ///< rate of the move j -> j + 1 (0 at the top node)
    std::vector<double> down;   ///< rate of the move j -> j - 1 (0 at the bottom node)
    std::size_t band_lower = 0; ///< index of the node at the band's lower edge z-*
    std::size_t band_upper = 0; ///< index of the node at the band's upper edge z*

    std::size_t size() const { return z.size(); }
    /// Whether node j is strictly inside the static band (it carries a stuck state).
    bool in_band(std::size_t j) const { return j > band_lower && j < band_upper; }
};

/// How the noise nodes are laid out at level 0: the band [z_lower, z_upper]
/// in at least band_intervals equal intervals of at most max_spacing, then
/// intervals growing by `ratio` outwards from the band's edges up to
/// max_spacing, until |z| >= reach. Level l splits every interval in 2^l.
struct NoiseGridShape {
    int band_intervals = 4;
    double ratio = 2.0;
    double max_spacing = 0.5;
    double reach = 8.0;
};

/// The noise grid of `level` for the band [z_lower, z_upper] (z_lower <
/// z_upper, both nondimensional z) and tau' > 0.
NoiseGrid make_noise_grid(double tau, double z_lower, double z_upper, const NoiseGridShape& shape, int level);

/// How the velocity cells are laid out at level 0 on each half line: the
/// first cell next to v = 0 of width first_cell, each next one `ratio` times
/// wider, at most max_cell, until the range's end. Level l splits every cell
/// in 2^l.
struct VelocityGridShape {
    double first_cell = 1e-4;
    double ratio = 2.0;
    double max_cell = 0.4;
};

/// Faces of the cells on one half line, from 0 outwards: 0 = f_0 < f_1 <
/// ... < f_m = end (end > 0; the negative half line uses the same code with
/// its length and mirrors it).
std::vector<double> make_velocity_faces(double end, const VelocityGridShape& shape, int level);

} // namespace stickslip::detail::near_white
