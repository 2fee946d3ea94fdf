// SPDX-License-Identifier: BSD-3-Clause
// The generator of the chain on one grid, and its exact solution (chain.hpp).
//
// Rates, for a state at x node j (x_j) with velocity cell k:
//  * x moves (every state): the Ornstein-Uhlenbeck part -(x/tau) d/dx +
//    (1/tau^2) d^2/dx^2 as a birth-death chain with exponentially fitted
//    (Scharfetter-Gummel) rates on the uniform grid of spacing h,
//      up_j = (d/h^2) B(-P),  down_{j+1} = (d/h^2) B(P),  d = 1/tau^2,
//      P = -tau (x_{j+1}^2 - x_j^2)/2 (the potential drop of the Gaussian),
//    positive for any cell Peclet number, and in detailed balance with the
//    Gaussian weights exp(-tau x_j^2/2) exactly: the chain's x-marginal is the
//    discrete Gaussian whatever happens in v. No move out of the end nodes
//    (reflection). A sliding state keeps its v cell; a stuck state moves to the
//    stuck state of the next node while that node is in the band, and leaves
//    the band into the first sliding cell on the side it left by (past x*:
//    the first positive cell, the object starts moving up).
//  * v moves (sliding states): upwind finite volumes for the transport
//    d/dv[c f] with c = b(v) + a x_j - Delta sgn v evaluated at the faces:
//    across an interior face with c > 0 the cell below hops up at c/w_below,
//    with c < 0 the cell above hops down at |c|/w_above. Across the face at
//    v = 0, a cell whose flow points to 0 hops into the stuck state of its
//    node when the node is in the band, and otherwise through to the first
//    cell of the other half line (the flow there points away from 0). No flux
//    through the outermost faces.
// exp, expm1 and pow are the project's portable ones (portable_math.hpp):
// glibc chooses among variants at run time (FMA or not) that differ in the
// last bit, and every number of the solve followed the machine's choice
// (the Fig. 2 case's D differed in its 12th digit between two machines).
// Band membership is decided by node index (the band's edges are nodes), never
// by a floating comparison of the force with Delta. In the PDMP-lattice mode
// the x moves are the PDMP engine's jumps (rate 2/(tau delta)^2, up with
// probability (1 - tau delta x/2)/2, all of it inwards at the ends) and the
// stuck states those of its static band k- .. k+.
#include "deterministic/kolmogorov/chain.hpp"
#include "deterministic/spectral_resolvent.hpp"

#include "stickslip/engine.hpp"
#include "stickslip/kernels/pdmp.hpp"
#include "stickslip/random/portable_math.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace stickslip::detail::kolmogorov {

double bernoulli_weight(double z) {
    if (std::abs(z) < 1e-10) return 1.0 - 0.5 * z;
    if (z > 700.0) return z * portable_exp(-z);
    return z / portable_expm1(z);
}

ChainGrid make_grid(const ModelParams& p, const KolmogorovGrid& g) {
    ChainGrid grid;
    if (g.lattice_step > 0) {
        // The PDMP engine's own chain in x: its lattice, jump rate, up
        // probabilities, reflecting ends and static band, from the very
        // constants the engine computes (kernels/pdmp.hpp).
        EngineSettings engine;
        engine.grid = g.lattice_step;
        engine.lattice_bound = g.lattice_bound;
        const PdmpConstants c = make_pdmp_constants(p, engine);
        const std::size_t n = 2 * static_cast<std::size_t>(c.n_max) + 1;
        grid.x.resize(n);
        grid.up.resize(n);
        grid.down.resize(n);
        for (std::size_t j = 0; j < n; ++j) {
            const int i = static_cast<int>(j) - c.n_max;
            grid.x[j] = pdmp_noise(c, i);
            const double alpha = pdmp_up_probability(c, i);
            grid.up[j] = c.rate * alpha;
            grid.down[j] = c.rate * (1.0 - alpha);
        }
        grid.stuck_first = static_cast<std::size_t>(c.k_minus + c.n_max);
        grid.stuck_last = static_cast<std::size_t>(c.k_plus + c.n_max);
        grid.pdmp_lattice = true;
    } else {
        grid.x.resize(g.x_nodes);
        for (std::size_t j = 0; j < g.x_nodes; ++j)
            grid.x[j] = g.lower_threshold + (static_cast<double>(j) - static_cast<double>(g.band_first)) * g.x_spacing;
        const std::size_t band_last = g.band_first + g.band_intervals;
        grid.x[band_last] = g.upper_threshold; // exactly, not lower + n h rounded
        grid.stuck_first = g.band_first + 1;
        grid.stuck_last = band_last - 1;
        // Scharfetter-Gummel rates (file comment).
        grid.up.assign(g.x_nodes, 0.0);
        grid.down.assign(g.x_nodes, 0.0);
        const double d_over_h2 = 1.0 / (p.tau * p.tau * g.x_spacing * g.x_spacing);
        for (std::size_t j = 0; j + 1 < g.x_nodes; ++j) {
            const double drop = -0.5 * p.tau * (grid.x[j + 1] - grid.x[j]) * (grid.x[j + 1] + grid.x[j]);
            grid.up[j] = d_over_h2 * bernoulli_weight(-drop);
            grid.down[j + 1] = d_over_h2 * bernoulli_weight(drop);
        }
    }
    auto faces = [&](double end, std::size_t cells) {
        // Geometric stretching: f_k = end (e^{s k/m} - 1)/(e^s - 1), cells
        // growing by e^{s/m} from 0 outwards (a smooth map, so that refining m
        // keeps the error's expansion in 1/m).
        std::vector<double> f(cells + 1);
        const double s = g.v_stretch;
        for (std::size_t k = 0; k <= cells; ++k) {
            const double u = static_cast<double>(k) / static_cast<double>(cells);
            const double stretched = s > 0 ? portable_expm1(s * u) / portable_expm1(s) : u;
            f[k] = end * stretched * portable_pow(u, g.v_grading - 1.0);
        }
        f[cells] = end;
        return f;
    };
    grid.faces_pos = faces(g.v_upper, g.v_cells_pos);
    grid.faces_neg = faces(g.v_lower, g.v_cells_neg);
    return grid;
}

Chain build_chain(const ModelParams& p, const ChainGrid& grid, const DriftLaw& drift) {
    const std::size_t nx = grid.x.size(), mp = grid.cells_pos(), mn = grid.cells_neg();
    const double a = p.force_amplitude(), friction = p.friction;

    Chain chain;
    chain.first.resize(nx + 1);
    std::size_t n = 0;
    for (std::size_t j = 0; j < nx; ++j) {
        chain.first[j] = n;
        n += mn + mp + (grid.in_band(j) ? 1 : 0);
    }
    chain.first[nx] = n;
    chain.velocity.resize(n);
    chain.width.resize(n);
    chain.x_node.resize(n);
    chain.stuck.assign(n, false);

    // Index of negative cell k (k = 0 next to v = 0), the stuck state, positive cell k.
    auto neg = [&](std::size_t j, std::size_t k) { return chain.first[j] + (mn - 1 - k); };
    auto stuck = [&](std::size_t j) { return chain.first[j] + mn; };
    auto pos = [&](std::size_t j, std::size_t k) { return chain.first[j] + mn + (grid.in_band(j) ? 1 : 0) + k; };

    for (std::size_t j = 0; j < nx; ++j) {
        for (std::size_t k = 0; k < mn; ++k) {
            const std::size_t s = neg(j, k);
            chain.velocity[s] = 0.5 * (grid.faces_neg[k] + grid.faces_neg[k + 1]);
            chain.width[s] = grid.faces_neg[k] - grid.faces_neg[k + 1];
            chain.x_node[s] = j;
        }
        if (grid.in_band(j)) {
            chain.stuck[stuck(j)] = true;
            chain.x_node[stuck(j)] = j;
        }
        for (std::size_t k = 0; k < mp; ++k) {
            const std::size_t s = pos(j, k);
            chain.velocity[s] = 0.5 * (grid.faces_pos[k] + grid.faces_pos[k + 1]);
            chain.width[s] = grid.faces_pos[k + 1] - grid.faces_pos[k];
            chain.x_node[s] = j;
        }
    }
    // Pin chi at the stuck state nearest the middle of the band.
    chain.pinned = stuck((grid.stuck_first + grid.stuck_last) / 2);

    // Rates, row by row; each row's diagonal is minus the sum of its
    // off-diagonal entries accumulated in the order they are added.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(n * 5);
    std::vector<double> out(n, 0.0);
    auto rate = [&](std::size_t from, std::size_t to, double r) {
        if (r <= 0.0) return;
        entries.emplace_back(static_cast<int>(from), static_cast<int>(to), r);
        out[from] += r;
    };
    // The transitions that end a half long excursion (chain.hpp), each added
    // as a rate and recorded.
    const std::size_t below = grid.stuck_first - 1, above = grid.stuck_last + 1; // the band's edge nodes
    chain.plus_start = pos(above, 0);
    chain.minus_start = neg(below, 0);
    auto end = [&](std::vector<Chain::End>& ends, std::size_t from, std::size_t to, double r) {
        rate(from, to, r);
        if (r > 0.0) ends.push_back({from, r});
    };

    // x moves.
    for (std::size_t j = 0; j + 1 < nx; ++j) {
        const double up = grid.up[j], down = grid.down[j + 1];
        // Sliding states keep their cell.
        for (std::size_t k = 0; k < mn; ++k) {
            rate(neg(j, k), neg(j + 1, k), up);
            rate(neg(j + 1, k), neg(j, k), down);
        }
        for (std::size_t k = 0; k < mp; ++k) {
            rate(pos(j, k), pos(j + 1, k), up);
            rate(pos(j + 1, k), pos(j, k), down);
        }
        // Stuck states move along the band and leave it at its edges.
        if (grid.in_band(j)) {
            if (grid.in_band(j + 1)) rate(stuck(j), stuck(j + 1), up);
            else end(chain.minus_ends, stuck(j), pos(j + 1, 0), up); // stuck, and X reaches x*
        }
        if (grid.in_band(j + 1)) {
            if (grid.in_band(j)) rate(stuck(j + 1), stuck(j), down);
            else end(chain.plus_ends, stuck(j + 1), neg(j, 0), down); // stuck, and X reaches x-*
        }
    }

    // v moves.
    const double b0 = drift(0.0);
    for (std::size_t j = 0; j < nx; ++j) {
        const double force = a * grid.x[j];
        const bool band = grid.in_band(j);
        // Positive half line: c = b(v) + a x - Delta.
        for (std::size_t k = 1; k < mp; ++k) {
            const double c = drift(grid.faces_pos[k]) + force - friction;
            if (c > 0)
                rate(pos(j, k - 1), pos(j, k), c / chain.width[pos(j, k - 1)]);
            else
                rate(pos(j, k), pos(j, k - 1), -c / chain.width[pos(j, k)]);
        }
        // Negative half line: c = b(v) + a x + Delta.
        for (std::size_t k = 1; k < mn; ++k) {
            const double c = drift(grid.faces_neg[k]) + force + friction;
            if (c < 0)
                rate(neg(j, k - 1), neg(j, k), -c / chain.width[neg(j, k - 1)]);
            else
                rate(neg(j, k), neg(j, k - 1), c / chain.width[neg(j, k)]);
        }
        // The face v = 0. Inside the band both flows point to 0 (at an edge
        // one of them vanishes), or, with a static friction above the
        // friction, one of them may point away between the kinetic and the
        // static thresholds (no flux into the stuck state from that side);
        // above the band both point up, below it down.
        const double c_pos = b0 + force - friction, c_neg = b0 + force + friction;
        if (band) {
            rate(pos(j, 0), stuck(j), std::max(-c_pos, 0.0) / chain.width[pos(j, 0)]);
            rate(neg(j, 0), stuck(j), std::max(c_neg, 0.0) / chain.width[neg(j, 0)]);
        } else if (j > grid.stuck_last) {
            // On the PDMP lattice a landing from below at x_{k+ +1} arrives at
            // s+ and ends a -HLE; in the continuum a landing exactly at x* has
            // probability 0, and only a stuck path's exit ends it.
            const double r = std::max(c_neg, 0.0) / chain.width[neg(j, 0)];
            if (grid.pdmp_lattice && j == above) end(chain.minus_ends, neg(j, 0), pos(j, 0), r);
            else rate(neg(j, 0), pos(j, 0), r);
        } else {
            const double r = std::max(-c_pos, 0.0) / chain.width[pos(j, 0)];
            if (grid.pdmp_lattice && j == below) end(chain.plus_ends, pos(j, 0), neg(j, 0), r);
            else rate(pos(j, 0), neg(j, 0), r);
        }
    }

    for (std::size_t s = 0; s < n; ++s)
        entries.emplace_back(static_cast<int>(s), static_cast<int>(s), -out[s]);
    chain.generator.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    chain.generator.setFromTriplets(entries.begin(), entries.end());
    chain.generator.makeCompressed();
    return chain;
}

ChainSolution solve_chain(const Chain& chain) {
    using Matrix = Eigen::SparseMatrix<double>;
    const std::size_t n = chain.size(), k = chain.pinned;
    const auto shrink = [k](Eigen::Index i) { return static_cast<std::size_t>(i) > k ? i - 1 : i; };

    // A = Q without the pinned state's row and column; the pinned row of Q,
    // less its diagonal entry, is the right-hand side of the stationary problem.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(chain.generator.nonZeros()));
    Eigen::VectorXd pinned_row = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n - 1));
    for (Eigen::Index col = 0; col < chain.generator.outerSize(); ++col)
        for (Matrix::InnerIterator it(chain.generator, col); it; ++it) {
            const auto row = it.row();
            if (static_cast<std::size_t>(col) == k) continue;
            if (static_cast<std::size_t>(row) == k) {
                pinned_row[shrink(col)] = it.value();
                continue;
            }
            entries.emplace_back(static_cast<int>(shrink(row)), static_cast<int>(shrink(col)), it.value());
        }
    Matrix reduced(static_cast<Eigen::Index>(n - 1), static_cast<Eigen::Index>(n - 1));
    reduced.setFromTriplets(entries.begin(), entries.end());
    reduced.makeCompressed();

    // COLAMD (Eigen's default for SparseLU): on the x-major ordering it keeps
    // the factors at ~60 nonzeros per state; AMD on A^T + A took 38 times the
    // nonzeros and 150 times the time on 2.4e5 states (kolmogorov.hpp).
    Eigen::SparseLU<Matrix, Eigen::COLAMDOrdering<int>> lu;
    lu.compute(reduced);
    if (lu.info() != Eigen::Success)
        throw std::runtime_error("kolmogorov: the sparse LU factorisation failed: " + lu.lastErrorMessage());

    ChainSolution sol;
    sol.nonzeros_lu = static_cast<std::size_t>(lu.nnzL() + lu.nnzU());
    // pi^T Q = 0 with pi_k = 1: A^T pi_rest = -(row k of Q less its diagonal).
    const Eigen::VectorXd rest = lu.transpose().solve(Eigen::VectorXd(-pinned_row));
    sol.stationary.resize(n);
    double total = 1.0;
    for (std::size_t s = 0, r = 0; s < n; ++s) {
        if (s == k) {
            sol.stationary[s] = 1.0;
            continue;
        }
        sol.stationary[s] = rest[static_cast<Eigen::Index>(r++)];
        total += sol.stationary[s];
    }
    for (double& w : sol.stationary) w /= total;

    for (std::size_t s = 0; s < n; ++s) {
        sol.mobility += sol.stationary[s] * chain.velocity[s];
        if (chain.stuck[s]) sol.stuck_probability += sol.stationary[s];
    }
    // The mass at the domain's edges: the end x nodes, and each half line's
    // outermost cell (the first and the last state of a node).
    const std::size_t nodes = chain.first.size() - 1;
    for (std::size_t s = 0; s < n; ++s) {
        const std::size_t j = chain.x_node[s];
        const bool edge = j == 0 || j + 1 == nodes || s == chain.first[j] || s + 1 == chain.first[j + 1];
        if (edge) sol.tail_mass += sol.stationary[s];
    }
    for (std::size_t s = 0; s < n; ++s) {
        const double shift = chain.velocity[s] - sol.mobility;
        sol.velocity_variance += sol.stationary[s] * (shift * shift + chain.width[s] * chain.width[s] / 12.0);
    }

    // Q chi = -(g - M0) with chi_k = 0: drop row k (implied, as pi . (g - M0) = 0).
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(n - 1));
    for (std::size_t s = 0, r = 0; s < n; ++s)
        if (s != k) rhs[static_cast<Eigen::Index>(r++)] = -(chain.velocity[s] - sol.mobility);
    const Eigen::VectorXd chi_rest = lu.solve(rhs);
    sol.chi.assign(n, 0.0);
    for (std::size_t s = 0, r = 0; s < n; ++s)
        if (s != k) sol.chi[s] = chi_rest[static_cast<Eigen::Index>(r++)];

    for (std::size_t s = 0; s < n; ++s)
        sol.diffusivity += 2.0 * sol.stationary[s] * (chain.velocity[s] - sol.mobility) * sol.chi[s];

    // E[t1]. With f+(i) the mean time from state i to the next transition
    // that ends a +HLE (chain.plus_ends, all into minus_start), first-step
    // analysis gives Q f+ = -1 + phi+ f+(minus_start), phi+_i the rate of the
    // ending transitions out of i; multiplying by pi (pi^T Q = 0) gives
    // f+(minus_start) = 1/F+, F+ = sum pi_i phi+_i the stationary rate of the
    // ends (Kac). So Q f+ = -1 + phi+/F+, a Poisson problem like chi's, and
    // the same for f-. E[t1] = f+(plus_start) + f-(minus_start)
    //   = 1/F+ + 1/F- + w(plus_start) - w(minus_start),  w = f+ - f-,
    // with Q w = phi+/F+ - phi-/F-: one more solve with the same factors (the
    // right-hand side is orthogonal to pi, and the constant in w cancels).
    double flux_plus = 0, flux_minus = 0;
    for (const Chain::End& e : chain.plus_ends) flux_plus += sol.stationary[e.from] * e.rate;
    for (const Chain::End& e : chain.minus_ends) flux_minus += sol.stationary[e.from] * e.rate;
    if (flux_plus > 0 && flux_minus > 0) {
        // The pinned state's equation is dropped (implied), as for chi.
        Eigen::VectorXd w_rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n - 1));
        auto add = [&](std::size_t s, double v) {
            if (s != k) w_rhs[shrink(static_cast<Eigen::Index>(s))] += v;
        };
        for (const Chain::End& e : chain.plus_ends) add(e.from, e.rate / flux_plus);
        for (const Chain::End& e : chain.minus_ends) add(e.from, -e.rate / flux_minus);
        const Eigen::VectorXd w_rest = lu.solve(w_rhs);
        auto w = [&](std::size_t s) { return s == k ? 0.0 : w_rest[shrink(static_cast<Eigen::Index>(s))]; };
        sol.mean_duration = 1.0 / flux_plus + 1.0 / flux_minus + w(chain.plus_start) - w(chain.minus_start);
    } else {
        sol.mean_duration = std::numeric_limits<double>::infinity(); // no way out of a half: never ends
    }

    // The carre du champ of the x moves alone: the continuum's D = E[(2/tau^2)
    // chi_x^2]; the v moves add the upwind scheme's numerical diffusion.
    for (Eigen::Index col = 0; col < chain.generator.outerSize(); ++col)
        for (Matrix::InnerIterator it(chain.generator, col); it; ++it) {
            const auto from = static_cast<std::size_t>(it.row()), to = static_cast<std::size_t>(col);
            if (from == to || chain.x_node[from] == chain.x_node[to]) continue;
            const double jump = sol.chi[to] - sol.chi[from];
            sol.diffusivity_x += sol.stationary[from] * it.value() * jump * jump;
        }
    return sol;
}

std::vector<double> chain_spectrum(const Chain& chain, const ChainSolution& sol, const std::vector<double>& frequencies) {
    const std::size_t n = chain.size();
    std::vector<double> shifted(n), ones(n, 1.0);
    for (std::size_t i = 0; i < n; ++i) shifted[i] = chain.velocity[i] - sol.mobility;
    std::vector<double> out;
    out.reserve(frequencies.size());
    ResolventSolver resolvent(chain.generator, ones);
    for (double w : frequencies) {
        if (w == 0) {
            out.push_back(sol.diffusivity);
            continue;
        }
        const std::vector<std::complex<double>> phi = resolvent.solve(w, shifted);
        double sum = 0;
        for (std::size_t i = 0; i < n; ++i) sum += sol.stationary[i] * shifted[i] * phi[i].real();
        out.push_back(2.0 * sum);
    }
    return out;
}

} // namespace stickslip::detail::kolmogorov
