// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kolmogorov.hpp -- D, M0, P(V = 0) and the stationary velocity law
// with coloured noise, without sampling: the Kolmogorov equations of (X, V)
// solved on a grid.
//
// Why. (X, V) is a two-dimensional Markov process, so its mobility, its
// diffusivity and its stationary law are linear-algebra problems. Monte Carlo
// pays for D with variance (U^2 per excursion is heavy-tailed: 0.3% on the
// Fig. 2 case takes ~4e6 long excursions); a grid pays with a discretisation
// error that shrinks with the grid and can be extrapolated and estimated.
//
// The equations (theory.md's convention: tau dX = -X dt + sqrt(2) dW, force
// a X with a = sqrt(noise/2)). The generator is
//   sliding (v != 0):  L f = -(x/tau) f_x + (1/tau^2) f_xx + (b(v) + a x - Delta sgn v) f_v,
//   stuck (v = 0, |b(0) + a x| <= Delta):  L f = -(x/tau) f_x + (1/tau^2) f_xx;
// a path reaching v = 0 sticks if |b(0) + a x| <= Delta and passes through
// otherwise; a stuck path leaves at the band's edges x* = (Delta - b(0))/a
// (upwards) and x-* = (-Delta - b(0))/a (downwards). With pi the stationary
// law and g(x, v) = v: M0 = E_pi[V], P(V = 0) = pi(stuck), and with chi the
// solution of the cell problem L chi = -(g - M0), D = 2 E_pi[(V - M0) chi]
// (= lim Var(U(t))/t, the project's D).
//
// The discretisation is itself a Markov chain (Kushner and Dupuis's
// "Markov chain approximation"), so the discrete problem has a stationary law
// that is a probability vector and a D that is exactly lim Var(U)/t of the
// chain:
//  * x: a uniform grid with the band's edges x-* and x* on nodes, covering
//    +-x_range standard deviations of X (1/sqrt(tau)). The Ornstein-Uhlenbeck
//    part is a birth-death chain with exponentially fitted (Scharfetter-
//    Gummel) rates, positive at any cell Peclet number and in detailed balance
//    with the Gaussian on the nodes; reflecting at the ends.
//  * v: finite volumes on each half line, from 0 to a range set by the drift
//    law (the terminal velocity of the end x node with drag; without drag
//    twice the slip the end node's force sustains for tau, or 10 noise/friction
//    near the white-noise limit), graded at 0 (faces end (k/m)^q, q = 3) where
//    the velocity density is singular; transport of b(v) + a x - Delta sgn v
//    by upwinding.
//  * stuck states: one per x node strictly inside the band. The band's edge
//    nodes are exits, as Brownian motion leaves the band when it hits an edge:
//    with edge nodes stuck, P(V = 0) converged to first order in the x spacing;
//    with them open, to second order (0.0023, 0.00045, 0.00008 on halving,
//    tau' = 1). A sliding cell next to 0 whose flow points to 0 feeds the
//    stuck state of its node, or passes to the other half line outside the band.
// Everything is solved in SI units; the drift enters only through one small
// function of v (detail::kolmogorov::DriftLaw), the run's drift law
// (make_drift_law: the affine law, or --drift, --drift-table, a callable),
// made once per solve.
//
// Solving. pi^T Q = 0 and Q chi = -(g - M0) share one sparse LU factorisation
// of Q less one row and column (chi is pinned to 0 at a stuck state mid-band;
// the dropped equation is implied because pi . (g - M0) = 0), the first by a
// transposed solve. The LU is Eigen's SparseLU (header-only, MPL-2.0, Debian
// libeigen3-dev) with its COLAMD column ordering: on the x-major ordering of
// the states it keeps about 60 nonzeros per state (2.4e5 states: 1.5e7
// nonzeros, 4 s on one core), while Eigen's AMD ordering of A^T + A took 38
// times the nonzeros and 150 times the time (583 s) on the same matrix.
//
// Accuracy. Upwind transport is first order in the v cells (Godunov: a chain,
// i.e. a monotone linear scheme, cannot do better) and its numerical
// diffusion adds to D; in x the scheme is second order. The two directions
// are extrapolated separately, each over four levels on a sequence of grids
// that is coarse in the other direction (the combination technique): v at a
// coarse x spacing, x at 64 velocity cells per half line; R0 + C1 h + C2 h^2 +
// C3 h^3 is fitted exactly and the error estimate is the size of the last
// correction (the difference from the fit of one order less). Their sum less
// the corner grid, where the sequences meet, is the limit but for a mixed term
// c that the errors' sum misses: for D, M0 and E[t1] it goes like hx^2 hv
// (measured: it fell 4-fold when the corner's x spacing was halved and 2-fold
// when its v cells were), so four grids around the corner give and remove it,
// and its error is charged as the difference from a first-order model of it.
// Two more coarse grids check that model per quantity: P(V = 0)'s mixed term
// barely shrinks with x at these levels (the stuck states need x and v fine
// together), so its charge is larger and its estimate is the loosest. The
// estimates are added. No grid is fine in both directions, so a round costs a
// fraction of one whose finest grid is (the first version's: 9 s for the Fig.
// 2 case, now 1 s). Rounds refine what is above a third of the target (one
// level of x, of v, or the corner where the mixed term is cheapest to reduce)
// until the estimated relative error of D is below rel_precision or the next
// round would exceed the time or memory budget (a note then says so). The
// time budget counts modelled seconds, a function of the grids' sizes alone
// (kolmogorov.cpp), so where a solve stops, and so its result, is the same on
// every machine, load and thread count. The
// carre du champ of chi over the x moves alone, E[(2/tau^2) chi_x^2], is a
// second estimator of D with the same limit and a different error (the v
// moves' numerical diffusion is absent from it); it is extrapolated the same
// way as a check. Measured (docs/kolmogorov_measurements.md): the Fig. 2 and
// driven cases to an estimated 0.03% and 0.003% in about 1 s on 2 cores, within
// 0.02% and 0.04% of the control-variate Monte Carlo references; pure dry
// friction at tau' = 1 to 0.07% in 4 s (within 0.02% of its reference), at
// tau' = 0.1 to 0.3% in 4 s, where the next round would exceed the budget.
//
// E[t1], the mean duration of a long excursion, needs no sampling either:
// the mean time to a transition that ends a half excursion solves a Poisson
// problem whose right-hand side is the stationary rate of those transitions
// (Kac's formula), so the two halves take one more solve with the factors
// already made (chain.cpp), and the value is extrapolated like D.
//
// The PDMP lattice mode (KolmogorovSettings::pdmp_grid) keeps the PDMP
// engine's own chain in x, its lattice and jump rates, and refines only v:
// the result is the PDMP's D, M0 and P(V = 0) at that grid, a sharp check
// against its Monte Carlo (driven case at grid 0.2: within 0.7 standard
// errors of 0.2%).
//
// Limits of this discretisation. The near-white limit is singular for an x
// grid (its range grows like 1/sqrt(tau') while the band stays fixed): below
// tau' = kolmogorov_chain_min_tau_prime = 0.05 it is refused, because there its
// affordable grids gave confident, wrong answers (tau' = 0.03: D = 2.07 with
// an estimated 1.8%, where D must lie between its tau' = 0.1 value 1.06 and
// the white-noise 1.25).
//
// Every tau' > 0: the near-white discretisation. A second discretisation of
// the same equations, in src/deterministic/near_white/ (near_white.hpp says
// why and how): the scaled noise z = sqrt(tau) X on graded nodes with a chain
// that keeps the white-noise intensity exactly, discontinuous Galerkin of
// degree 2 in v on cells graded to the layer at v = 0, so that the unknowns
// stay bounded as tau' -> 0 and the limit is the white-noise quadrature.
// solve_kolmogorov chooses (KolmogorovDiscretisation::Automatic): the
// near-white discretisation below tau' = kolmogorov_near_white_below = 0.1 and
// for laws without drag, the chain for laws with drag above it. Measured side
// by side on pure dry friction and on the Fig. 2 law at tau' = 0.05 to 5
// (docs/kolmogorov_measurements.md), the two agree within their estimates
// everywhere; with drag the chain reached smaller errors in the same time
// from tau' = 0.1 up, without drag the near-white one (at tau' = 0.1 the chain
// stopped at its budget with 0.31% where the near-white one gave 0.09% in
// 0.9 s; at tau' = 1, 0.074% in 3 s against 0.034% in 2.8 s). A weakly
// confining law with drag (weak drag, a bias near the friction) reaches
// beyond the chain's velocity range: the mass at its coarsest grid's edges
// says so, and the near-white discretisation, whose range follows the law,
// takes over (solve_kolmogorov). Below tau' =
// kolmogorov_white_limit_below = 1e-6 the grid's rates (up to 1/(tau' h^2))
// cost the LU its digits, and the white-noise quadrature, whose distance to
// the coloured D is bounded by what the grid measures at 1e-6, gives D and M0
// (near_white.cpp). White noise itself (tau = 0) is refused: the velocity
// alone is Markov and the exact one-dimensional references apply
// (analytic.hpp, white_noise_reference).
#pragma once

/// \file
/// A grid solver for the stationary Kolmogorov equations of (X, V): D, M0,
/// P(V = 0) and the stationary velocity density, with an estimated
/// discretisation error. The comment at the top of this header explains the
/// design.

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "stickslip/method.hpp"
#include "stickslip/result_fields.hpp"
#include "stickslip/model.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

/// The geometry of one grid, in SI units. solve_kolmogorov chooses it from
/// KolmogorovSettings; solve_kolmogorov_grid takes it as it is.
struct KolmogorovGrid {
    double lower_threshold = 0;   ///< x-* = (-friction - b(0))/a [s^-1/2], a node (an exit of the stuck states)
    double upper_threshold = 0;   ///< x* = (friction - b(0))/a [s^-1/2], a node (an exit of the stuck states)
    double x_spacing = 0;         ///< h = (x* - x-*)/band_intervals [s^-1/2]
    std::size_t band_intervals = 0; ///< grid intervals across the static band (>= 2; its interior nodes carry stuck states)
    std::size_t band_first = 0;   ///< index of the node x-*: nodes x-* + (j - band_first) h
    std::size_t x_nodes = 0;      ///< number of x nodes
    double v_lower = 0;           ///< lower end of the velocity range [m/s], < 0
    double v_upper = 0;           ///< upper end of the velocity range [m/s], > 0
    std::size_t v_cells_neg = 0;  ///< velocity cells on [v_lower, 0)
    std::size_t v_cells_pos = 0;  ///< velocity cells on (0, v_upper]
    double v_stretch = 0;         ///< s: faces at end u^{q-1} (e^{s u} - 1)/(e^s - 1), u = k/m (s = 0: end u^q)
    double v_grading = 1;         ///< q >= 1: grading of the cells at v = 0
    /// > 0: the x nodes are the PDMP engine's lattice of this step delta
    /// [s^-1/2] with its jump rates and static band k- .. k+ (the thresholds
    /// above are then its nodes k- delta and k+ delta, x_spacing = delta);
    /// 0: the uniform Scharfetter-Gummel grid.
    double lattice_step = 0;
    double lattice_bound = 0;     ///< the PDMP lattice's half-width L [s^-1/2] (0: as the engine chooses)

    /// The near-white grids' nodes are not uniform (x_spacing is then the
    /// band's): their lowest node [s^-1/2]; 0 on a uniform grid.
    double graded_x_lower = 0;
    /// The near-white grids' highest node [s^-1/2]; 0 on a uniform grid.
    double graded_x_upper = 0;

    /// The lowest x node [s^-1/2].
    double x_lower() const {
        return graded_x_lower < graded_x_upper ? graded_x_lower : lower_threshold - static_cast<double>(band_first) * x_spacing;
    }
    /// The highest x node [s^-1/2].
    double x_upper() const {
        return graded_x_lower < graded_x_upper ? graded_x_upper : x_lower() + static_cast<double>(x_nodes - 1) * x_spacing;
    }
};

/// The exact solution of the chain on one grid.
struct KolmogorovGridSolution {
    KolmogorovGrid grid;            ///< the grid
    std::size_t states = 0;         ///< states of the chain (unknowns)
    std::size_t lu_nonzeros = 0;    ///< nonzeros of the sparse LU factors (kolmogorov_bytes_per_lu_nonzero each)
    double diffusivity = 0;         ///< D of the chain [m^2/s]
    double diffusivity_x = 0;       ///< the x moves' carre du champ of chi [m^2/s] (D less the upwind diffusion)
    double mobility = 0;            ///< M0 of the chain [m/s]
    double velocity_variance = 0;   ///< the stationary Var(V) of the grid [m^2/s^2]
    double stuck_probability = 0;   ///< P(V = 0) of the chain
    /// E[t1] of the chain, the mean duration of a long excursion [s] (a +HLE
    /// from (x*, 0) until stuck at x-*, then the mirror image), by one more
    /// Poisson solve with the same factors (chain.cpp)
    double mean_duration = 0;
    /// Stationary mass on the end x nodes and in the outermost v cell of each
    /// half line: a check that the domain is wide enough.
    double tail_mass = 0;
    double seconds = 0;             ///< wall time of building and solving [s]
    /// Faces of the velocity cells, increasing, 0 among them [m/s].
    std::vector<double> velocity_faces;
    /// The stationary velocity density of the sliding states, one value per
    /// cell (its mass divided by its width) [s/m]; the stuck states' atom at
    /// v = 0 is stuck_probability. Integrates to 1 - stuck_probability.
    std::vector<double> velocity_density;
};

/// The discretisation of the Kolmogorov equations (the header's comment).
enum class KolmogorovDiscretisation {
    Automatic, ///< the near-white one below tau' = kolmogorov_near_white_below, the chain above
    Chain,     ///< the upwind Markov chain on a uniform X grid (tau' >= kolmogorov_chain_min_tau_prime)
    NearWhite, ///< the moment-exact noise chain in z with DG in v (every tau' > 0)
};

/// The most frequencies one solve takes (KolmogorovSettings::frequencies):
/// each is a complex factorisation of every grid of the last round.
inline constexpr std::size_t kolmogorov_max_frequencies = 200;

/// Resolution and budget of solve_kolmogorov. Zero means automatic where said.
/// Invalid values throw InvalidParameter named after the field.
struct KolmogorovSettings {
    /// x intervals across the static band at refinement level 2 (a multiple
    /// of 4: level 0 has a quarter; 0: automatic, the spacing a quarter of the
    /// smaller of the band and X's standard deviation 1/sqrt(tau), at least 2
    /// intervals at level 0).
    std::size_t band_intervals = 0;
    /// Velocity cells per half line at refinement level 3 (a multiple of 8,
    /// >= 32: level 0 has an eighth; 0: automatic, 128).
    std::size_t v_cells = 0;
    double x_range = 7.0;           ///< x nodes cover +-x_range standard deviations of X (1/sqrt(tau))
    double v_lower = 0;             ///< lower end of the velocity range [m/s] (< 0; 0: auto)
    double v_upper = 0;             ///< upper end of the velocity range [m/s] (> 0; 0: auto)
    double v_stretch = 0.0;         ///< stretching of the velocity cells (KolmogorovGrid::v_stretch)
    double v_grading = 3.0;         ///< grading of the velocity cells at 0 (KolmogorovGrid::v_grading)
    double rel_precision = 1e-3;    ///< target estimated relative error of D, in (0, 1)
    /// Bytes the factorisations of a round may take at once [bytes]: no round is
    /// started whose predicted peak, two factorisations at once whatever the
    /// thread count (so that the result does not depend on it), exceeds it.
    double memory_budget = 2e9;
    /// Seconds the whole solve may take [s], in modelled seconds: a grid of n
    /// states counts 1.6e-9 n^1.8 s and a round's grids two at a time, which is
    /// about the wall time on 2 cores (measured: 0.4 to 1.3 times it), and no
    /// round is started whose modelled end is later. Modelled, not measured,
    /// so that the result does not depend on the machine, its load or the
    /// thread count: a slower machine, a debug or sanitizer build, or one
    /// thread (about twice the modelled time) takes longer instead, and
    /// nothing stops a solve on wall time.
    double time_budget = 10.0;
    /// threads (1 or 2: two grids of a round solved at once); the result is
    /// the same for both
    int threads = 2;
    /// > 0: keep the PDMP engine's own chain in x, its lattice of step
    /// pdmp_grid [s^-1/2] (`--grid`), and refine only v: the result is then the
    /// PDMP's D, M0 and P(V = 0) at that grid, to compare with its Monte Carlo
    /// within the standard error (a sharp check of the v discretisation and of
    /// the extrapolation). 0: the continuum solver.
    double pdmp_grid = 0;
    double pdmp_lattice_bound = 0;  ///< the PDMP lattice's L [s^-1/2] (`--lattice-bound`; 0: the engine's choice)
    /// Which discretisation (the chain alone has the PDMP lattice mode; band_intervals,
    /// v_cells, x_range, v_lower, v_upper, v_stretch and v_grading are the chain's).
    KolmogorovDiscretisation discretisation = KolmogorovDiscretisation::Automatic;
    /// Angular frequencies w [rad/s], each finite and >= 0, at most
    /// kolmogorov_max_frequencies, at which to solve the two-sided velocity
    /// spectrum S(w) (KolmogorovResult::spectrum); empty: none. Each costs one
    /// complex sparse LU per grid of the last round (about 3 times a real
    /// one), after the rounds, which D's error alone chooses.
    std::vector<double> frequencies;
    /// Optional stop flag (RunControl::stop: Ctrl-C, SIGTERM), polled between
    /// rounds of grids: once set, the solve returns the estimates of the
    /// rounds finished (at least the first), marked interrupted.
    const std::atomic<bool>* stop = nullptr;
};

/// Throws InvalidParameter, named after the field, for an invalid setting
/// (solve_kolmogorov's own check, also of a caller that solves no grid).
void validate(const KolmogorovSettings& settings);

/// The discretisation that solve_kolmogorov runs for p (SI) and settings:
/// Chain or NearWhite, never Automatic. Automatic takes the near-white one
/// below tau' = kolmogorov_near_white_below or where the law has no drag at
/// either end (has_drag_at_both_ends), the chain otherwise; solve_kolmogorov
/// still turns from the chain to the near-white one when the chain's
/// velocity range proves too short for the law (its note says so).
KolmogorovDiscretisation resolved_discretisation(const ModelParams& p, const KolmogorovSettings& settings);
/// resolved_discretisation on a model made once (model.hpp).
KolmogorovDiscretisation resolved_discretisation(const Model& m, const KolmogorovSettings& settings);

/// Whether p's drift law pulls back with a negative slope beyond both ends
/// (drag: the affine law with a finite relaxation, a law's outer pieces).
bool has_drag_at_both_ends(const ModelParams& p);
/// has_drag_at_both_ends on a model made once (model.hpp).
bool has_drag_at_both_ends(const Model& m);

/// What solve_kolmogorov returns. details holds GridDetails (solver
/// "kolmogorov", the largest grid's states, the velocity range and the
/// relative error estimate of D).
struct KolmogorovResult : MethodResult {
    ModelParams params;                  ///< the model, SI units
    Estimate diffusivity;      ///< D [m^2/s]
    Estimate mobility;         ///< M0 [m/s]
    /// The stationary Var(V) [m^2/s^2], extrapolated like D (the mean E[V] is M0).
    Estimate velocity_variance;
    Estimate stuck_probability; ///< P(V = 0)
    /// E[t1], the mean duration of a long excursion [s], extrapolated like D
    /// (the continuum's; a time-stepping scheme's depends on its step and stop
    /// rule: compare at steps well below tau)
    Estimate mean_duration;
    /// D from the x moves' carre du champ of chi, E[(2/tau^2) chi_x^2], extrapolated
    /// like D: the same continuum limit with a different discretisation error,
    /// a check on the extrapolation [m^2/s].
    Estimate diffusivity_x;
    /// The grids solved, each once: those of the last round's x sequence, v
    /// sequence and mixed term, and those of earlier rounds. The last one is
    /// the v sequence's finest (the finest velocity cells, coarse in x): its
    /// velocity_density is the stationary density reported.
    std::vector<KolmogorovGridSolution> levels;
    /// The two-sided velocity spectrum S(w) = int over all t of C(t)
    /// e^{-i w t} dt [m^2/s], C the stationary autocovariance of V, at
    /// KolmogorovSettings::frequencies (empty without them): one complex
    /// resolvent solve per grid and frequency, extrapolated over the last
    /// round's grids like D. S(0) = D (Green-Kubo in the project's convention).
    std::vector<Estimate> spectrum;
    bool converged = false;              ///< whether D's estimated error is below rel_precision
    /// Stopped by KolmogorovSettings::stop before the target: the estimates
    /// of the rounds finished (the note says so).
    bool interrupted = false;
    std::string note;                    ///< why not, or other remarks; empty when none
    double seconds = 0;                  ///< wall time [s]

    /// The quantities every solved report gives, in report order
    /// (result_fields.hpp): each with its discretisation error, no interval.
    /// The grid, the other estimates and the precision are written by hand.
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = KolmogorovResult;
        visit(&S::diffusivity, FieldInfo{"diffusivity", "m^2/s", "D, the effective diffusivity", FieldForm::NoInterval});
        visit(&S::mobility, FieldInfo{"mobility", "m/s", "M0, the mean velocity", FieldForm::NoInterval});
        visit(&S::stuck_probability,
              FieldInfo{"stuck_probability", "", "P(V = 0), the stationary probability of sticking", FieldForm::NoInterval});
        visit(&S::mean_duration,
              FieldInfo{"mean_duration", "s", "E[t1], the mean duration of a long excursion", FieldForm::NoInterval});
    }
};

/// Bytes of memory per nonzero of the LU factors, for the memory budget
/// (value, row index and the supernodal structure's overhead; measured).
inline constexpr double kolmogorov_bytes_per_lu_nonzero = 16.0;

/// The smallest nondimensional tau' = tau friction^2/noise the upwind chain
/// takes (the near-white discretisation takes every tau' > 0).
inline constexpr double kolmogorov_chain_min_tau_prime = 0.05;

/// Below this tau', KolmogorovDiscretisation::Automatic takes the near-white
/// discretisation; from it up, the upwind chain (the header's comment says why).
inline constexpr double kolmogorov_near_white_below = 0.1;

/// Below this tau', the near-white solver gives the white-noise quadrature for
/// D and M0 with the bound that its grids measure at this tau' (near_white.cpp).
inline constexpr double kolmogorov_white_limit_below = 1e-6;

/// What the grids of a solve spanned (no one grid is fine in both
/// directions): the solved reports' engine_details.grid.
struct KolmogorovGridSpan {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    std::size_t largest_states = 0;
    std::size_t x_nodes = 0;
    double x_lower = 0, x_upper = 0;
    std::size_t v_cells = 0;
    double v_lower = 0, v_upper = 0;
    std::size_t grids_solved = 0;
    double tail_mass = 0;
    Estimate diffusivity_x;
    /// @}

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = KolmogorovGridSpan;
        visit(&S::largest_states, FieldInfo{"states", "", "states of the largest grid solved"});
        visit(&S::x_nodes, FieldInfo{"x_nodes", "", "noise nodes of the finest noise spacing solved"});
        visit(&S::x_lower, FieldInfo{"x_lower", "s^-1/2", "the lowest noise node of the last grid"});
        visit(&S::x_upper, FieldInfo{"x_upper", "s^-1/2", "the highest noise node of the last grid"});
        visit(&S::v_cells, FieldInfo{"v_cells", "", "velocity cells (both half lines) of the finest velocity cells solved"});
        visit(&S::v_lower, FieldInfo{"v_lower", "m/s", "the lowest velocity face of the last grid"});
        visit(&S::v_upper, FieldInfo{"v_upper", "m/s", "the highest velocity face of the last grid"});
        visit(&S::grids_solved, FieldInfo{"grids_solved", "", "grids solved, each once"});
        visit(&S::tail_mass, FieldInfo{"tail_mass", "", "the largest mass any grid holds in its outermost cells"});
        visit(&S::diffusivity_x,
              FieldInfo{"diffusivity_x", "m^2/s",
                        "D from the noise moves' carre du champ, extrapolated like D: the same limit with another "
                        "discretisation error, a check on the extrapolation"});
    }
};

/// The span of r.levels (not empty); the last grid's ranges.
KolmogorovGridSpan grid_span(const KolmogorovResult& r);

/// Solves the chain on one given grid, without extrapolation: D, M0,
/// P(V = 0) and E[t1] exact for the chain, the stationary velocity density. SI units;
/// p must be valid with tau > 0 (validate_kolmogorov), the grid as
/// kolmogorov_grid makes it (band_intervals >= 2, cells >= 1 on each side).
/// std::runtime_error if the factorisation fails.
KolmogorovGridSolution solve_kolmogorov_grid(const ModelParams& p, const KolmogorovGrid& grid);

/// The grid of refinement level `level` >= 0 that solve_kolmogorov uses, in
/// both directions: level 0 has a quarter of settings.band_intervals and an
/// eighth of settings.v_cells (or of their automatic values), and each level
/// doubles both. The x domain and the velocity range are the same at every
/// level. solve_kolmogorov combines the x spacing of one level with the v
/// cells of another (its first round: x levels 0-3 at v level 2, v levels 1-4
/// at x level 1).
KolmogorovGrid kolmogorov_grid(const ModelParams& p, const KolmogorovSettings& settings, int level);

/// Throws InvalidParameter for what solve_kolmogorov refuses: an invalid
/// model (validate), white noise ("tau"), the chain asked for below
/// kolmogorov_chain_min_tau_prime ("tau"), no stationary state ("bias"),
/// invalid settings (the field's name).
void validate_kolmogorov(const ModelParams& p, const KolmogorovSettings& settings);
/// validate_kolmogorov on a model made once (model.hpp; valid already).
void validate_kolmogorov(const Model& m, const KolmogorovSettings& settings);

/// D [m^2/s], M0 [m/s], P(V = 0) and E[t1] [s] of p (SI units) by rounds of grid
/// refinement and Richardson extrapolation, each with its estimated
/// discretisation error, until the error of D is below
/// settings.rel_precision or a budget stops it (converged false, note says
/// why). Throws InvalidParameter as validate_kolmogorov.
KolmogorovResult solve_kolmogorov(const ModelParams& p, const KolmogorovSettings& settings = {});
/// solve_kolmogorov on a model made once (model.hpp): every grid of the solve
/// takes its law.
KolmogorovResult solve_kolmogorov(const Model& m, const KolmogorovSettings& settings = {});

} // namespace stickslip
