// SPDX-License-Identifier: BSD-3-Clause
// One grid's stationary law, D, M0, P(V = 0) and E[t1] (grid_solve.hpp).
#include "deterministic/near_white/grid_solve.hpp"
#include "deterministic/spectral_resolvent.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace stickslip::detail::near_white {

namespace {

using Matrix = Eigen::SparseMatrix<double>;
using Vector = Eigen::VectorXd;

/// int_{-1}^{1} xi P_n P_m dxi: what the factor v - M0 adds to a cell's mass
/// matrix beyond its midpoint (xi P_0 = P_1, xi P_1 = (2 P_2 + P_0)/3).
constexpr double xi_moment[3][3] = {{0, 2.0 / 3.0, 0}, {2.0 / 3.0, 0, 4.0 / 15.0}, {0, 4.0 / 15.0, 0}};

/// The sparse LU of the reduced operator, with its two solves. No scaling:
/// equilibrating rows (or rows and columns) before the factorisation, tried
/// because the rates span 1e-1 to 1e13 as tau' falls, lost digits instead
/// (D at tau' = 1e-6 off by 0.2-0.5% where the unscaled weak form keeps 1e-6):
/// the weak form's rows already carry the cells' widths.
class SparseFactors {
public:
    explicit SparseFactors(const Matrix& a) {
        lu_.compute(a);
        if (lu_.info() != Eigen::Success)
            throw std::runtime_error("near-white solver: the sparse LU factorisation failed: " + lu_.lastErrorMessage());
    }
    /// x with A x = b.
    Vector solve(const Vector& b) { return lu_.solve(b); }
    /// y with A^T y = c.
    Vector solve_transpose(const Vector& c) { return lu_.transpose().solve(c); }
    std::size_t nonzeros() { return static_cast<std::size_t>(lu_.nnzL() + lu_.nnzU()); }

private:
    Eigen::SparseLU<Matrix, Eigen::COLAMDOrdering<int>> lu_;
};

} // namespace

GridSolution solve_grid(const Layout& l, const DriftLaw& drift, double tau, std::vector<double>* chi_out,
                        const std::vector<double>* frequencies) {
    const auto start = std::chrono::steady_clock::now();
    const Matrix a = forward_operator(l, drift, tau);
    const NoiseGrid& g = l.noise;
    const std::size_t n = l.size(), nodes = g.size(), mn = l.cells_neg(), mp = l.cells_pos();
    const std::size_t k = l.stuck((g.band_lower + g.band_upper) / 2);
    const auto shrink = [k](std::size_t i) { return i > k ? i - 1 : i; };

    // A less row and column k; column k, less its row k, is the stationary
    // problem's right-hand side (p_k = 1).
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(a.nonZeros()));
    Vector column_k = Vector::Zero(static_cast<Eigen::Index>(n - 1));
    for (Eigen::Index col = 0; col < a.outerSize(); ++col)
        for (Matrix::InnerIterator it(a, col); it; ++it) {
            const auto row = static_cast<std::size_t>(it.row()), c = static_cast<std::size_t>(col);
            if (row == k) continue;
            if (c == k) {
                column_k[static_cast<Eigen::Index>(shrink(row))] = it.value();
                continue;
            }
            entries.emplace_back(static_cast<int>(shrink(row)), static_cast<int>(shrink(c)), it.value());
        }
    Matrix reduced(static_cast<Eigen::Index>(n - 1), static_cast<Eigen::Index>(n - 1));
    reduced.setFromTriplets(entries.begin(), entries.end());
    reduced.makeCompressed();
    SparseFactors lu(reduced);

    auto expand = [&](const Vector& rest, double pinned) {
        std::vector<double> out(n);
        for (std::size_t i = 0; i < n; ++i) out[i] = i == k ? pinned : rest[static_cast<Eigen::Index>(shrink(i))];
        return out;
    };
    auto reduce = [&](const std::vector<double>& full) {
        Vector out(static_cast<Eigen::Index>(n - 1));
        for (std::size_t i = 0; i < n; ++i)
            if (i != k) out[static_cast<Eigen::Index>(shrink(i))] = full[i];
        return out;
    };

    // The cells in increasing v: (width, midpoint) and each unknown's
    // functionals: its mass and its int v.
    std::vector<double> mass(n, 0.0), first_moment(n, 0.0);
    auto each_cell = [&](auto&& visit) { // visit(node, cell index in increasing v, lo, hi, unknown of P_0)
        for (std::size_t j = 0; j < nodes; ++j) {
            for (std::size_t c = 0; c < mn; ++c)
                visit(j, mn - 1 - c, -l.faces_neg[c + 1], -l.faces_neg[c], l.neg(j, c, 0));
            for (std::size_t c = 0; c < mp; ++c) visit(j, mn + c, l.faces_pos[c], l.faces_pos[c + 1], l.pos(j, c, 0));
        }
    };
    each_cell([&](std::size_t, std::size_t, double lo, double hi, std::size_t u) {
        const double h = hi - lo, mid = 0.5 * (lo + hi);
        mass[u] = h;
        first_moment[u] = h * mid;
        first_moment[u + 1] = h * h / 6.0;
    });
    for (std::size_t j = 0; j < nodes; ++j)
        if (g.in_band(j)) mass[l.stuck(j)] = 1.0;
    auto dot = [](const std::vector<double>& x, const std::vector<double>& y) {
        double s = 0;
        for (std::size_t i = 0; i < x.size(); ++i) s += x[i] * y[i];
        return s;
    };

    GridSolution sol;
    sol.states = n;
    sol.lu_nonzeros = lu.nonzeros();

    std::vector<double> p = expand(lu.solve(Vector(-column_k)), 1.0);
    const double total = dot(mass, p);
    for (double& x : p) x /= total;
    sol.mobility = dot(first_moment, p);
    // E[V^2]: int_K v^2 p dv = h (mid^2 p0 + mid h p1/3 + h^2 (p0/3 + 2 p2/15)/4).
    double second_moment = 0;
    each_cell([&](std::size_t, std::size_t, double lo, double hi, std::size_t u) {
        const double h = hi - lo, mid = 0.5 * (lo + hi);
        second_moment += h * (mid * mid * p[u] + mid * h * p[u + 1] / 3.0 +
                              0.25 * h * h * (p[u] / 3.0 + 2.0 * p[u + 2] / 15.0));
    });
    sol.velocity_variance = second_moment - sol.mobility * sol.mobility;
    for (std::size_t j = 0; j < nodes; ++j)
        if (g.in_band(j)) {
            sol.stuck_probability += p[l.stuck(j)];
            sol.stuck_mass.push_back(p[l.stuck(j)]);
            sol.stuck_z.push_back(g.z[j]);
        }

    // Poisson, forward form: A r = -s, s the weak form of (v - M0) p.
    std::vector<double> s(n, 0.0);
    each_cell([&](std::size_t, std::size_t, double lo, double hi, std::size_t u) {
        const double h = hi - lo, shift = 0.5 * (lo + hi) - sol.mobility;
        for (std::size_t m = 0; m < dofs_per_cell; ++m) {
            double value = shift * p[u + m] * h / static_cast<double>(2 * m + 1);
            for (std::size_t q = 0; q < dofs_per_cell; ++q) value += 0.25 * h * h * xi_moment[q][m] * p[u + q];
            s[u + m] = value;
        }
    });
    for (std::size_t j = 0; j < nodes; ++j)
        if (g.in_band(j)) s[l.stuck(j)] = -sol.mobility * p[l.stuck(j)];
    for (double& x : s) x = -x;
    std::vector<double> r = expand(lu.solve(reduce(s)), 0.0);
    const double r_mass = dot(mass, r);
    for (std::size_t i = 0; i < n; ++i) r[i] -= r_mass * p[i];
    sol.diffusivity = 2.0 * dot(first_moment, r);
    if (frequencies) {
        // The forward resolvent (grid_solve.hpp): -s is the weak form of
        // (v - M0) p; R has no mass for w > 0, so 2 int (v - M0) R = 2 int v R.
        std::vector<double> weight(n, 0.0), weak(n);
        each_cell([&](std::size_t, std::size_t, double lo, double hi, std::size_t u) {
            for (std::size_t m = 0; m < dofs_per_cell; ++m) weight[u + m] = (hi - lo) / static_cast<double>(2 * m + 1);
        });
        for (std::size_t j = 0; j < nodes; ++j)
            if (g.in_band(j)) weight[l.stuck(j)] = 1.0;
        for (std::size_t i = 0; i < n; ++i) weak[i] = -s[i];
        ResolventSolver resolvent(a, weight);
        for (double w : *frequencies) {
            if (w == 0) {
                sol.spectrum.push_back(sol.diffusivity);
                continue;
            }
            const std::vector<std::complex<double>> big_r = resolvent.solve(w, weak);
            double sum = 0;
            for (std::size_t i = 0; i < n; ++i) sum += first_moment[i] * big_r[i].real();
            sol.spectrum.push_back(2.0 * sum);
        }
    }

    // The backward solution chi: A^T chi = -c, c the weak form of v - M0
    // (its P_0, P_1 tests: h (mid - M0), h^2/6; -M0 on a stuck state). Then
    // the noise moves' carre du champ (grid_solve.hpp): per node and move, the
    // flux p_j rate times (chi_j' - chi_j)^2 over each cell, by 4-point Gauss
    // (the integrand is of degree 6); for a stuck state leaving the band, the
    // jump to chi at the point v = 0+- of the edge node.
    std::vector<double> shifted_velocity(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) shifted_velocity[i] = -(first_moment[i] - sol.mobility * mass[i]);
    const std::vector<double> chi = expand(lu.solve_transpose(reduce(shifted_velocity)), 0.0);
    {
        static const double gx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
        static const double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
        auto value = [&](const std::vector<double>& f, std::size_t u, double xi) {
            return f[u] + f[u + 1] * xi + f[u + 2] * 0.5 * (3 * xi * xi - 1);
        };
        double sum = 0;
        for (std::size_t j = 0; j < nodes; ++j) {
            for (const auto& [to, rate] : {std::pair{j + 1, g.up[j]}, std::pair{j - 1, g.down[j]}}) {
                if (rate == 0.0) continue;
                for (std::size_t cell = 0; cell < mn + mp; ++cell) {
                    const bool positive = cell >= mn;
                    const std::size_t k_ = positive ? cell - mn : cell;
                    const double h = positive ? l.faces_pos[k_ + 1] - l.faces_pos[k_] : l.faces_neg[k_ + 1] - l.faces_neg[k_];
                    const std::size_t here = positive ? l.pos(j, k_, 0) : l.neg(j, k_, 0);
                    const std::size_t there = positive ? l.pos(to, k_, 0) : l.neg(to, k_, 0);
                    double cell_sum = 0;
                    for (int q = 0; q < 4; ++q) {
                        const double jump = value(chi, there, gx[q]) - value(chi, here, gx[q]);
                        cell_sum += gw[q] * value(p, here, gx[q]) * jump * jump;
                    }
                    sum += rate * 0.5 * h * cell_sum;
                }
                if (g.in_band(j)) {
                    double target = 0;
                    if (g.in_band(to)) target = chi[l.stuck(to)];
                    else if (to > j)
                        target = chi[l.pos(to, 0, 0)] - chi[l.pos(to, 0, 1)] + chi[l.pos(to, 0, 2)];
                    else
                        target = chi[l.neg(to, 0, 0)] + chi[l.neg(to, 0, 1)] + chi[l.neg(to, 0, 2)];
                    const double jump = target - chi[l.stuck(j)];
                    sum += p[l.stuck(j)] * rate * jump * jump;
                }
            }
        }
        sol.diffusivity_noise = sum;
    }
    if (chi_out) *chi_out = chi;

    // Where D lives: the share of 2 int v r from the outer tenth of each half line.
    double outer = 0;
    const double v_top = l.faces_pos.back(), v_bottom = -l.faces_neg.back();
    each_cell([&](std::size_t, std::size_t, double lo, double hi, std::size_t u) {
        if (hi > 0.9 * v_top || lo < 0.9 * v_bottom) outer += 2.0 * (first_moment[u] * r[u] + first_moment[u + 1] * r[u + 1]);
    });
    sol.tail_diffusivity = std::abs(outer) / std::abs(sol.diffusivity);

    // The density of V, per cell in increasing v, and the mass at the ends.
    sol.velocity_faces.reserve(mn + mp + 1);
    for (std::size_t f = mn + 1; f-- > 1;) sol.velocity_faces.push_back(-l.faces_neg[f]);
    for (std::size_t f = 0; f <= mp; ++f) sol.velocity_faces.push_back(l.faces_pos[f]);
    sol.velocity_density.assign(mn + mp, 0.0);
    each_cell([&](std::size_t j, std::size_t column, double lo, double hi, std::size_t u) {
        sol.velocity_density[column] += p[u];
        if (j == 0 || j + 1 == nodes || column == 0 || column + 1 == mn + mp) sol.tail_mass += p[u] * (hi - lo);
    });

    // E[t1] by Kac's formula (grid_solve.hpp; kolmogorov/chain.cpp derives
    // it): a +HLE ends when a stuck state at the band's lowest node moves to
    // the edge below, a -HLE at the highest node moving above. With F+- the
    // stationary rates of those moves, E[t1] = 1/F+ + 1/F- + w(start+) -
    // w(start-), L w = phi+/F+ - phi-/F-, w a backward function: A^T w = G.
    const std::size_t lowest = l.stuck(g.band_lower + 1), highest = l.stuck(g.band_upper - 1);
    const double rate_plus = g.down[g.band_lower + 1], rate_minus = g.up[g.band_upper - 1];
    const double flux_plus = p[lowest] * rate_plus, flux_minus = p[highest] * rate_minus;
    if (flux_plus > 0 && flux_minus > 0) {
        std::vector<double> rhs(n, 0.0);
        rhs[lowest] += rate_plus / flux_plus;
        rhs[highest] -= rate_minus / flux_minus;
        const std::vector<double> w = expand(lu.solve_transpose(reduce(rhs)), 0.0);
        // The starts: a point mass at v = 0+ at the upper edge node, 0- at the lower one.
        double start_plus = 0, start_minus = 0;
        for (std::size_t m = 0; m < dofs_per_cell; ++m) {
            start_plus += w[l.pos(g.band_upper, 0, m)] * (m == 1 ? -1.0 : 1.0);
            start_minus += w[l.neg(g.band_lower, 0, m)];
        }
        sol.mean_duration = 1.0 / flux_plus + 1.0 / flux_minus + start_plus - start_minus;
    } else {
        sol.mean_duration = std::numeric_limits<double>::infinity();
    }
    sol.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return sol;
}

} // namespace stickslip::detail::near_white
