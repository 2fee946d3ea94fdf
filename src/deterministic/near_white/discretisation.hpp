// SPDX-License-Identifier: BSD-3-Clause
// The near-white solver's discretisation of the forward (Fokker-Planck)
// equation of (z, V) on one grid: the moment-exact noise chain in z
// (grids.hpp), upwind discontinuous Galerkin of degree 2 in v on each half
// line, one stuck state per node strictly inside the static band. Internal
// to the library (it speaks Eigen). Nondimensional units.
//
// The equation. With eps = sqrt(tau') the force is k z, k = 1/(sqrt(2) eps),
// and on the sliding set the density p_j(v) at noise node j moves by
//   d/dt p_j = -d/dv (c_j p_j) + sum_i (rate i -> j) p_i - (rates out of j) p_j,
//   c_j(v) = b(v) + k z_j - sgn v.
// On each velocity cell p_j is a polynomial of degree 2 (Legendre basis
// P_0, P_1, P_2 of the cell's reference coordinate xi in [-1, 1]); the weak
// form tested with the same polynomials takes the flux c p at each face from
// the cell upwind of it (Godunov). Why degree 2 and upwind: as eps -> 0 the
// cells next to v = 0 stop resolving the boundary layer, and only DG of
// degree >= 1 keeps the diffusion limit on such cells (Larsen, Morel and
// Miller 1987; Adams 2001; Guermond and Kanschat 2010); degree 2 costs
// little more than 1 per accuracy gained, and first-order upwinding (the
// present chain) has no diffusion limit at all.
//
// v = 0. At a node strictly inside the band both half lines flow into 0 and
// their flux feeds the node's stuck state (with a static friction above the
// friction, the band is the static one, and between the kinetic and the
// static thresholds one half line flows away from 0 and feeds nothing);
// elsewhere the face at 0 is an
// ordinary upwind face (the flow crosses it: from below above the band, from
// above below it; at an edge node one side's flow vanishes there). A stuck
// state follows the noise chain along the band and, when the chain leaves
// the band, enters the sliding cell next to 0 of the edge node, on the side of
// the force (a point mass at v = 0+ or 0-, tested against the polynomials).
// The edge nodes themselves carry no stuck state: a stuck path leaves the band
// when its noise reaches an edge (putting stuck states on the edges gave a
// first-order error in P(V = 0)).
//
// No flux through the outermost faces: the chain conserves mass (the range
// is checked by the mass it holds at its ends, near_white.cpp).
#pragma once

#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

#include "deterministic/near_white/grids.hpp"
#include "stickslip/drift_law.hpp"

namespace stickslip::detail::near_white {

/// Degrees of freedom per velocity cell (Legendre P_0, P_1, P_2).
inline constexpr std::size_t dofs_per_cell = 3;

/// One grid and where each unknown sits: for each noise node, its negative
/// cells from v = 0 outwards, its stuck state (band nodes only), its positive
/// cells from v = 0 outwards, each cell's three coefficients in a row.
struct Layout {
    NoiseGrid noise;
    std::vector<double> faces_pos; ///< 0 = f_0 < ... < f_m: the positive cells' faces
    std::vector<double> faces_neg; ///< 0 = g_0 < ... < g_m: the negative cells' faces, as distances from 0
    std::vector<std::size_t> first; ///< first unknown of each node (and one past the last)

    std::size_t cells_pos() const { return faces_pos.size() - 1; }
    std::size_t cells_neg() const { return faces_neg.size() - 1; }
    std::size_t size() const { return first.back(); }
    /// Unknown of coefficient m of negative cell c (c = 0 next to v = 0) at node j.
    std::size_t neg(std::size_t j, std::size_t c, std::size_t m) const { return first[j] + dofs_per_cell * c + m; }
    /// The stuck state of band node j.
    std::size_t stuck(std::size_t j) const { return first[j] + dofs_per_cell * cells_neg(); }
    /// Unknown of coefficient m of positive cell c at node j.
    std::size_t pos(std::size_t j, std::size_t c, std::size_t m) const {
        return first[j] + dofs_per_cell * cells_neg() + (noise.in_band(j) ? 1 : 0) + dofs_per_cell * c + m;
    }
};

/// The layout of a noise grid and the two half lines' faces.
Layout make_layout(NoiseGrid noise, std::vector<double> faces_pos, std::vector<double> faces_neg);

/// The forward operator A in weak form: (A p)_i is d/dt of the unknown's test
/// integral, int p phi_i over the cell for a sliding coefficient, the stuck
/// mass for a stuck state. The stationary law solves A p = 0; the mass,
/// sum over cells of h p_0 plus the stuck masses, is conserved (the rows of
/// the P_0 tests and the stuck rows sum to zero over each column).
/// `drift` is the nondimensional law b(v); tau' > 0.
Eigen::SparseMatrix<double> forward_operator(const Layout& layout, const DriftLaw& drift, double tau);

} // namespace stickslip::detail::near_white
