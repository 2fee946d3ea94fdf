// SPDX-License-Identifier: BSD-3-Clause
// The exact solution of the near-white discretisation on one grid: the
// stationary law, the Poisson (cell) problem that gives D, and the Kac
// problem that gives E[t1], with one sparse LU factorisation. Nondimensional
// units. Internal to the library.
//
// One factorisation for every solve: the operator A (discretisation.hpp) less
// one row and one column, those of a stuck state mid-band (a dense
// normalisation row instead ruined the fill). The stationary law p solves
// A p = 0 with that state's mass pinned, then normalised. The Poisson problem
// in forward form, A r = -(v - M0) p with total mass of r zero, gives
// D = 2 int v r (equal to the backward form 2 E[(V - M0) chi] with L chi =
// -(v - M0), by duality, on the discrete operator too). E[t1] comes from the
// backward (transposed) problem of Kac's formula, as in the present chain
// (kolmogorov/chain.cpp): the mean times to the transitions that end a half
// excursion, which here are a stuck state's moves out of the band.
#pragma once

#include <cstddef>
#include <vector>

#include "deterministic/near_white/discretisation.hpp"

namespace stickslip::detail::near_white {

/// What one grid gives, nondimensional.
struct GridSolution {
    double diffusivity = 0;       ///< D
    double mobility = 0;          ///< M0
    double velocity_variance = 0; ///< the stationary Var(V)
    double stuck_probability = 0; ///< P(V = 0)
    double mean_duration = 0;     ///< E[t1] (inf when a half excursion cannot end)
    /// Mass on the two end noise nodes and in the outermost cell of each half
    /// line: a check that the domain is wide enough.
    double tail_mass = 0;
    /// The share of D's integrand 2 v r in the outermost tenth of each half
    /// line's range, |2 int v r| there over D: a check that the range holds D.
    double tail_diffusivity = 0;
    /// The noise moves' carre du champ of the backward solution chi (L chi =
    /// -(v - M0)): sum over the noise chain's moves of their stationary flux
    /// times the square of chi's jump. The continuum's D is exactly that
    /// (the noise enters only through z); on the grid it lacks the upwind
    /// faces' dissipation, so it tends to D from another side: a check.
    double diffusivity_noise = 0;
    std::size_t states = 0;      ///< unknowns
    std::size_t lu_nonzeros = 0; ///< nonzeros of the LU factors
    double seconds = 0;          ///< wall time of building and solving [s]
    /// Faces of the velocity cells in increasing v, 0 among them.
    std::vector<double> velocity_faces;
    /// The stationary density of V on the sliding states, each cell's mean
    /// over the cell (sums to 1 - stuck_probability when multiplied by widths).
    std::vector<double> velocity_density;
    /// The stuck states' mass per band node (the noise's law while stuck,
    /// times P(V = 0)), and those nodes' z.
    std::vector<double> stuck_mass, stuck_z;
    /// The two-sided velocity spectrum S(w) at the frequencies asked of
    /// solve_grid (empty otherwise): 2 int v R with (i w M - A) R = s, M the
    /// weak form's diagonal mass (h/(2m+1) per coefficient, 1 per stuck
    /// state) and s the weak form of (v - M0) p (spectral_resolvent.hpp);
    /// S(0) is D.
    std::vector<double> spectrum;
};

/// Solves one grid. `drift` is the nondimensional law, tau' > 0. With `chi`
/// given, it receives the backward solution chi (one value per unknown: the
/// Legendre coefficients of chi on each cell, chi itself on a stuck state),
/// pinned to 0 at the stuck state mid-band. With `frequencies` given
/// (nondimensional angular frequencies, each >= 0), it fills spectrum.
/// std::runtime_error when a factorisation fails.
GridSolution solve_grid(const Layout& layout, const DriftLaw& drift, double tau, std::vector<double>* chi = nullptr,
                        const std::vector<double>* frequencies = nullptr);

} // namespace stickslip::detail::near_white
