// SPDX-License-Identifier: BSD-3-Clause
// The Markov chain that discretises the generator of (X, V) on one grid
// (kolmogorov.hpp explains the scheme and why it is a chain), and the exact
// solution of that chain: its stationary law and its cell (Poisson) problem.
//
// Internal to the library: it speaks Eigen, which the public headers do not.
// The unit tests include it to check the generator itself.
#pragma once

#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

#include "stickslip/drift_input.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/params.hpp"

namespace stickslip::detail::kolmogorov {

/// The drift law b(v) [m s^-2] at a velocity v [m/s]: the run's law
/// (make_drift_law, drift_input.hpp: the affine law of relaxation and bias, or
/// the knots of --drift, --drift-table or a callable), made once when this is
/// constructed, so that a solve builds it once and not per evaluation. The one
/// place the solver evaluates the drift (the scheme needs b(v) only at the cell
/// faces and b(0); the automatic velocity range assumes b non-increasing with
/// drag).
struct DriftLaw {
    stickslip::DriftLaw law;
    explicit DriftLaw(const ModelParams& p) : law(make_drift_law(p)) {}
    explicit DriftLaw(const stickslip::DriftLaw& made) : law(made) {}
    double operator()(double v) const { return law(v); }
};

/// kolmogorov_grid with the drift law made already (solve_kolmogorov makes it
/// once per solve).
KolmogorovGrid make_kolmogorov_grid(const ModelParams& p, const KolmogorovSettings& s, int level,
                                    const DriftLaw& drift);

/// solve_kolmogorov_grid with the drift law made already.
KolmogorovGridSolution solve_grid(const ModelParams& p, const KolmogorovGrid& grid, const DriftLaw& drift);

/// The velocity spectrum S(w) [m^2/s] of one grid's chain at the angular
/// frequencies w [rad/s] (chain_spectrum).
std::vector<double> grid_spectrum(const ModelParams& p, const KolmogorovGrid& grid, const DriftLaw& drift,
                                  const std::vector<double>& frequencies);

/// One grid, resolved: the x nodes with the rates of the x moves between
/// them, which nodes carry a stuck state, and the faces of the velocity cells
/// on each half line. SI units.
struct ChainGrid {
    std::vector<double> x;          ///< x nodes [s^-1/2], increasing
    std::vector<double> up;         ///< rate of the x move from node j to j+1 [s^-1] (0 at the top)
    std::vector<double> down;       ///< rate of the x move from node j to j-1 [s^-1] (0 at the bottom)
    std::size_t stuck_first = 0;    ///< the first node with a stuck state
    std::size_t stuck_last = 0;     ///< the last node with a stuck state
    std::vector<double> faces_pos;  ///< 0 = f_0 < f_1 < ... < f_m [m/s]: faces of the cells on v > 0
    std::vector<double> faces_neg;  ///< 0 = g_0 > g_1 > ... > g_m [m/s]: faces of the cells on v < 0
    bool pdmp_lattice = false;      ///< whether x is the PDMP engine's lattice (KolmogorovGrid::lattice_step > 0)

    /// Whether node j carries a stuck state. On the Scharfetter-Gummel grid,
    /// the nodes strictly inside the band (kolmogorov.hpp: a stuck path leaves
    /// the band when X reaches an edge node); on the PDMP lattice, the nodes
    /// k- .. k+ of its static band.
    bool in_band(std::size_t j) const { return j >= stuck_first && j <= stuck_last; }
    std::size_t cells_pos() const { return faces_pos.size() - 1; }
    std::size_t cells_neg() const { return faces_neg.size() - 1; }
};

/// Builds the grid of one level from its geometry, for the model p (the x
/// rates depend on tau).
ChainGrid make_grid(const ModelParams& p, const KolmogorovGrid& g);

/// The generator of the chain on one grid and what each state stands for.
/// States are ordered x-major: for each x node, its negative cells from the
/// far end towards 0, then its stuck state (band nodes only), then its
/// positive cells from 0 outwards.
struct Chain {
    /// Q: off-diagonal entries are jump rates [s^-1] (>= 0), each diagonal
    /// entry minus the sum of its row's off-diagonal entries.
    Eigen::SparseMatrix<double> generator;
    std::vector<double> velocity;     ///< g = V in each state [m/s]: the cell's midpoint, 0 when stuck
    std::vector<double> width;        ///< the cell's width in v [m/s]; 0 for a stuck state
    std::vector<std::size_t> x_node;  ///< the state's x node
    std::vector<bool> stuck;          ///< whether the state is a stuck state
    std::vector<std::size_t> first;   ///< first state of each x node (and one past the last node)
    std::size_t pinned = 0;           ///< the state whose chi is pinned to 0 (a stuck state mid-band)

    /// A transition of the chain that ends a half long excursion: its state
    /// and rate [s^-1] (all of them lead to the state where the next half
    /// starts).
    struct End {
        std::size_t from;
        double rate;
    };
    /// Where a +HLE starts: the first positive cell at the band's upper edge
    /// node, where a stuck path that leaves the band upwards goes (the
    /// continuum's (x*, 0)); on the PDMP lattice its s+ = (x_{k+ +1}, +1, 0).
    std::size_t plus_start = 0;
    /// Where a -HLE starts, the mirror image: the first negative cell at the
    /// band's lower edge node.
    std::size_t minus_start = 0;
    /// The transitions into minus_start that end a +HLE: a stuck path
    /// leaving the band downwards (the continuum's "stuck, and X reaches
    /// x-*"); on the PDMP lattice also a landing from above at that node, as
    /// the PDMP engine ends it at any arrival at s- (pdmp_half).
    std::vector<End> plus_ends;
    /// The transitions into plus_start that end a -HLE (the mirror image).
    std::vector<End> minus_ends;

    std::size_t size() const { return velocity.size(); }
};

/// The chain of `grid` for the model p (validated by the caller, tau > 0),
/// the drift evaluated only through `drift`.
Chain build_chain(const ModelParams& p, const ChainGrid& grid, const DriftLaw& drift);

/// The exact solution of one chain.
struct ChainSolution {
    std::vector<double> stationary; ///< pi, sums to 1
    std::vector<double> chi;        ///< solution of Q chi = -(g - M0), chi[pinned] = 0
    double mobility = 0;            ///< M0 = pi . g [m/s]
    /// Var(V) = pi . (g - M0)^2 plus each sliding cell's own width^2/12 (V
    /// uniform within a cell) [m^2/s^2]
    double velocity_variance = 0;
    double diffusivity = 0;         ///< D = 2 pi . ((g - M0) chi) [m^2/s]
    double diffusivity_x = 0;       ///< sum pi_i Q_ij (chi_j - chi_i)^2 over the x moves only [m^2/s]
    double stuck_probability = 0;   ///< pi(S)
    double tail_mass = 0;           ///< mass on the two end x nodes and in the outermost v cell of each half line
    /// E[t1] of the chain [s]: the mean time from plus_start to a +HLE's end
    /// plus the mean time from minus_start to a -HLE's end (solve_chain).
    double mean_duration = 0;
    std::size_t nonzeros_lu = 0;    ///< nonzeros of the L and U factors
};

/// Solves pi^T Q = 0 and Q chi = -(g - M0) with one sparse LU factorisation
/// (COLAMD ordering) of Q less the pinned state's row and column, and with the
/// same factors the Poisson problem that gives E[t1] (solve_chain's comment).
ChainSolution solve_chain(const Chain& chain);

/// The chain's two-sided velocity spectrum S(w) [m^2/s] at the angular
/// frequencies w [rad/s] (each >= 0): 2 Re pi.((g - M0) phi) with
/// (i w - Q) phi = g - M0 (spectral_resolvent.hpp), one complex sparse LU per
/// frequency; S(0) is sol's D, the same solve.
std::vector<double> chain_spectrum(const Chain& chain, const ChainSolution& sol, const std::vector<double>& frequencies);

/// The Scharfetter-Gummel weight B(z) = z/(e^z - 1), B(0) = 1, without
/// cancellation for small |z| and without overflow for large |z|.
double bernoulli_weight(double z);

} // namespace stickslip::detail::kolmogorov
