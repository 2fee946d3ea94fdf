// SPDX-License-Identifier: BSD-3-Clause
// Assembly of the near-white solver's forward operator (discretisation.hpp).
#include "deterministic/near_white/discretisation.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace stickslip::detail::near_white {

namespace {

/// Legendre polynomial P_m(xi), m = 0, 1, 2.
double legendre(std::size_t m, double xi) { return m == 0 ? 1.0 : (m == 1 ? xi : 0.5 * (3.0 * xi * xi - 1.0)); }
/// P_m(+1) and P_m(-1): the traces at a cell's upper and lower face.
constexpr std::array<double, 3> at_upper{1.0, 1.0, 1.0};
constexpr std::array<double, 3> at_lower{1.0, -1.0, 1.0};

/// int_{-1}^{1} b(v(xi)) P_n(xi) P_m'(xi) dxi for the cell [lo, hi], as
/// out[m][n] (row m = 0 is zero: P_0' = 0). b is affine on each piece, so
/// three Gauss points per piece inside the cell are exact (degree 4).
std::array<std::array<double, 3>, 3> drift_volume(const DriftLaw& b, double lo, double hi) {
    static const double gx[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    static const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    std::array<std::array<double, 3>, 3> out{};
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    auto integrate = [&](double a, double c) { // sub-interval [a, c] of the cell, in v
        for (int q = 0; q < 3; ++q) {
            const double v = 0.5 * (a + c) + 0.5 * (c - a) * gx[q];
            const double xi = (v - mid) / half;
            const double weight = gw[q] * (c - a) / (hi - lo); // dxi = 2 dv/(hi - lo), over [-1, 1]: weights sum to 2
            const double bv = b(v) * weight;
            for (std::size_t n = 0; n < 3; ++n) {
                const double pn = legendre(n, xi);
                out[1][n] += bv * pn;            // P_1' = 1
                out[2][n] += bv * pn * 3.0 * xi; // P_2' = 3 xi
            }
        }
    };
    if (b.affine()) {
        integrate(lo, hi);
    } else {
        double a = lo;
        for (int j = b.piece(lo); j < b.pieces() && a < hi; ++j) {
            const double c = std::min(hi, b.piece_upper(j));
            if (c > a) integrate(a, c);
            a = c;
        }
    }
    return out;
}

} // namespace

Layout make_layout(NoiseGrid noise, std::vector<double> faces_pos, std::vector<double> faces_neg) {
    Layout l;
    l.noise = std::move(noise);
    l.faces_pos = std::move(faces_pos);
    l.faces_neg = std::move(faces_neg);
    const std::size_t n = l.noise.size();
    l.first.resize(n + 1);
    std::size_t next = 0;
    for (std::size_t j = 0; j < n; ++j) {
        l.first[j] = next;
        next += dofs_per_cell * (l.cells_neg() + l.cells_pos()) + (l.noise.in_band(j) ? 1 : 0);
    }
    l.first[n] = next;
    return l;
}

Eigen::SparseMatrix<double> forward_operator(const Layout& l, const DriftLaw& drift, double tau) {
    const NoiseGrid& g = l.noise;
    const std::size_t nodes = g.size(), mn = l.cells_neg(), mp = l.cells_pos();
    const double k = 1.0 / std::sqrt(2.0 * tau); // force per unit z
    const double b0 = drift(0.0);

    std::vector<Eigen::Triplet<double>> t;
    t.reserve(l.size() * 14);
    auto add = [&](std::size_t row, std::size_t col, double value) {
        if (value != 0.0) t.emplace_back(static_cast<int>(row), static_cast<int>(col), value);
    };

    // The cells of both half lines in increasing v, as (lower face, upper
    // face, unknown of coefficient 0 at node 0 less first[0]); the same at
    // every node, so the drift's volume integrals are computed once.
    struct Cell {
        double lo, hi;
        std::size_t offset; // of coefficient 0 from first[j] (on the positive side, for a node without stuck state)
        bool positive;
    };
    std::vector<Cell> cells;
    for (std::size_t c = mn; c-- > 0;) cells.push_back({-l.faces_neg[c + 1], -l.faces_neg[c], dofs_per_cell * c, false});
    for (std::size_t c = 0; c < mp; ++c)
        cells.push_back({l.faces_pos[c], l.faces_pos[c + 1], dofs_per_cell * (mn + c), true});
    std::vector<std::array<std::array<double, 3>, 3>> volume(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) volume[i] = drift_volume(drift, cells[i].lo, cells[i].hi);

    for (std::size_t j = 0; j < nodes; ++j) {
        const bool band = g.in_band(j);
        const double force = k * g.z[j];
        auto at = [&](std::size_t node, std::size_t i, std::size_t m) {
            return l.first[node] + cells[i].offset + (cells[i].positive && g.in_band(node) ? 1 : 0) + m;
        };
        auto unknown = [&](std::size_t i, std::size_t m) { return at(j, i, m); };

        // The noise chain: every sliding coefficient moves with its node
        // (the same cells at every node); the mass matrix h/(2m + 1) is
        // diagonal in the Legendre basis.
        for (std::size_t i = 0; i < cells.size(); ++i) {
            const double h = cells[i].hi - cells[i].lo;
            for (std::size_t m = 0; m < dofs_per_cell; ++m) {
                const double mass = h / static_cast<double>(2 * m + 1);
                const std::size_t me = unknown(i, m);
                if (j + 1 < nodes) {
                    add(me, me, -g.up[j] * mass);
                    add(at(j + 1, i, m), me, g.up[j] * mass);
                }
                if (j > 0) {
                    add(me, me, -g.down[j] * mass);
                    add(at(j - 1, i, m), me, g.down[j] * mass);
                }
            }
        }
        // Stuck states: along the band, and out of it at its edges into the
        // cell next to 0 on the force's side (a point mass at v = 0+-).
        if (band) {
            const std::size_t s = l.stuck(j);
            add(s, s, -(g.up[j] + g.down[j]));
            if (g.in_band(j + 1)) add(l.stuck(j + 1), s, g.up[j]);
            else
                for (std::size_t m = 0; m < dofs_per_cell; ++m) add(l.pos(j + 1, 0, m), s, g.up[j] * at_lower[m]);
            if (g.in_band(j - 1)) add(l.stuck(j - 1), s, g.down[j]);
            else
                for (std::size_t m = 0; m < dofs_per_cell; ++m) add(l.neg(j - 1, 0, m), s, g.down[j] * at_upper[m]);
        }

        // Transport in v. Volume terms: int c p phi_m' dv with c = b(v) +
        // force - sgn v; the constant part's int P_n P_m' dxi is 2 for (m, n)
        // = (1, 0) and (2, 1).
        for (std::size_t i = 0; i < cells.size(); ++i) {
            const double constant = force - (cells[i].positive ? 1.0 : -1.0);
            for (std::size_t m = 1; m < dofs_per_cell; ++m)
                for (std::size_t n = 0; n < dofs_per_cell; ++n) {
                    const double value = volume[i][m][n] + (n + 1 == m ? 2.0 * constant : 0.0);
                    add(unknown(i, m), unknown(i, n), value);
                }
        }
        // Faces between cells of one half line: the flux c p from the cell
        // upwind, leaving the lower cell (-F P_m(+1)) and entering the upper
        // one (+F P_m(-1)).
        auto face = [&](std::size_t lower, std::size_t upper, double c) {
            const std::size_t from = c > 0 ? lower : upper;
            const std::array<double, 3>& trace = c > 0 ? at_upper : at_lower;
            for (std::size_t n = 0; n < dofs_per_cell; ++n) {
                const double flux = c * trace[n];
                for (std::size_t m = 0; m < dofs_per_cell; ++m) {
                    add(unknown(lower, m), unknown(from, n), -flux * at_upper[m]);
                    add(unknown(upper, m), unknown(from, n), flux * at_lower[m]);
                }
            }
        };
        for (std::size_t i = 0; i + 1 < cells.size(); ++i) {
            if (!cells[i].positive && cells[i + 1].positive) continue; // v = 0, below
            const double v = cells[i].hi;
            face(i, i + 1, drift(v) + force - (cells[i].positive ? 1.0 : -1.0));
        }
        // The face v = 0 (discretisation.hpp).
        const std::size_t below = mn - 1, above = mn; // the cells next to 0
        const double c_neg = b0 + force + 1.0, c_pos = b0 + force - 1.0;
        if (band) {
            const std::size_t s = l.stuck(j);
            for (std::size_t n = 0; n < dofs_per_cell; ++n) {
                // Between the kinetic and the static thresholds one flow points
                // away from 0 (a static friction above the kinetic one): no flux.
                const double out_below = std::max(c_neg, 0.0) * at_upper[n]; // c_neg > 0: leaves the negative cell upwards
                const double out_above = std::max(-c_pos, 0.0) * at_lower[n]; // c_pos < 0: leaves the positive cell downwards
                for (std::size_t m = 0; m < dofs_per_cell; ++m) {
                    add(unknown(below, m), unknown(below, n), -out_below * at_upper[m]);
                    add(unknown(above, m), unknown(above, n), -out_above * at_lower[m]);
                }
                add(s, unknown(below, n), out_below);
                add(s, unknown(above, n), out_above);
            }
        } else {
            face(below, above, c_neg > 0 ? c_neg : c_pos);
        }
    }
    Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(l.size()), static_cast<Eigen::Index>(l.size()));
    a.setFromTriplets(t.begin(), t.end());
    a.makeCompressed();
    return a;
}

} // namespace stickslip::detail::near_white
