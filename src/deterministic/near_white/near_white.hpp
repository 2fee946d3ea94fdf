// SPDX-License-Identifier: BSD-3-Clause
// The near-white Kolmogorov solver: D, M0, P(V = 0), E[t1] and the stationary
// velocity density for every tau' > 0, with a number of unknowns that stays
// bounded as tau' -> 0 (theory.md, "Every correlation time"). One of the
// Kolmogorov engine's two discretisations (kolmogorov.hpp chooses).
//
// Why a second discretisation. With eps = sqrt(tau') and z = sqrt(tau) X (a
// standard normal), the generator is eps^-2 (OU in z) + eps^-1 (z/sqrt 2) d/dv
// + (b - sgn v) d/dv: the diffusive scaling of kinetic theory. The present
// chain (kolmogorov/), uniform in X and first-order upwind in v, cannot follow
// it: its X range grows like 1/eps while the static band stays fixed, and
// first-order upwinding has no diffusion limit, so below tau' = 0.05 it gave
// confident, wrong answers. Here:
//  * z on nodes with the band's edges among them, fine across the band and
//    growing geometrically outwards, with a birth-death chain whose weights
//    and rates reproduce the force's white-noise intensity exactly on any grid
//    (grids.hpp);
//  * v by upwind discontinuous Galerkin of degree 2 on cells graded
//    geometrically from 1e-4 min(eps, eps^3) at v = 0 (the layer where stuck
//    phases start and end; eps^3 is the velocity the force changes in the
//    stuck phases' time eps^4: with cells of a fraction of eps only, P(V = 0)
//    at tau' = 1e-4 was 4 times too small), which keeps the diffusion limit on
//    cells that do not resolve the layer (discretisation.hpp);
//  * one sparse LU per grid for the stationary, Poisson and Kac problems
//    (grid_solve.hpp).
// The count of unknowns grows only with log(1/eps) (the graded cells).
//
// Extrapolation and error. The z direction converges at second order (the
// chain's moments are exact, its spacing is not), the v direction at third
// to fifth (measured), and their mixed term is small (measured 2e-7 relative
// of D). So the two directions are extrapolated separately on sequences of
// three levels that are coarse in the other direction (the combination
// technique), with the corner grid where they meet subtracted:
//   Q = R_z(at v level av) + R_v(at z level az) - Q(az, av).
// In z, R is Richardson's for second order, Q2 + (Q2 - Q1)/3, with half the
// last difference as its error (a faster apparent rate was luck: E[t1] of the
// Fig. 2 law at tau' = 0.05 showed 18, then moved 4 times the error Aitken's
// rate gave). In v, Aitken's extrapolation (ratio of successive differences
// rho, capped at 16 so that a sequence that crosses its limit by chance is
// not trusted) with the size of its correction |Q2 - Q1|/(rho - 1) as error.
// A ratio below 2, no convergence seen, is not extrapolated. The
// mixed term is measured on one more grid (az + 1, av + 1) and charged three
// times (it reached 1e-5 of D at tau' = 0.0015, 2e-7 at 0.01). Each error is
// added, and rounds refine the direction that holds the largest part of D's
// error (the mixed one by moving the corner in z or in v, the cheaper) until
// it is below the target or a budget stops it.
#pragma once

#include "deterministic/near_white/discretisation.hpp"
#include "stickslip/drift_law.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/params.hpp"

namespace stickslip::detail::near_white {

/// A model in the solver's nondimensional form, with the layout of its
/// grids at level 0 (near_white.cpp says how each is chosen).
struct Problem {
    double tau = 0;                  ///< tau'
    DriftLaw drift;                  ///< b'(v') (friction = noise = 1)
    double z_lower = 0, z_upper = 0; ///< the band's edges in z
    double v_lower = 0, v_upper = 0; ///< the velocity range (v_lower < 0 < v_upper)
    NoiseGridShape noise;
    VelocityGridShape velocity;
};

/// The problem of p (SI, valid, tau > 0) with its drift law `law` (SI).
Problem make_problem(const ModelParams& p, const DriftLaw& law);

/// The grid of the z level lz and the v level lv.
Layout make_level_layout(const Problem& problem, int lz, int lv);

/// solve_kolmogorov with the near-white discretisation; `law` is the run's
/// drift law in SI units (made once by the caller). p valid, tau > 0,
/// settings validated.
KolmogorovResult solve(const ModelParams& p, const KolmogorovSettings& settings, const DriftLaw& law);

} // namespace stickslip::detail::near_white
