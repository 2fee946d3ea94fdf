// SPDX-License-Identifier: BSD-3-Clause
// The corrector's tables from the near-white solver's chi (corrector_table.hpp).
#include "deterministic/near_white/corrector_table.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "deterministic/near_white/grid_solve.hpp"
#include "deterministic/near_white/near_white.hpp"
#include "stickslip/drift_law_quadrature.hpp"

namespace stickslip::detail::near_white {

namespace {

constexpr int kVelocityNodes = 1025; // of the sliding table
constexpr int kMostNoiseNodes = 4097; // of the sliding table in x
constexpr double kTableDrop = 25;     // the v range: white noise's density e^-25 of its peak

/// chi at node j and velocity v (nondimensional) from its Legendre coefficients.
double chi_at(const Layout& l, const std::vector<double>& chi, std::size_t j, double v) {
    const bool positive = v >= 0;
    const std::vector<double>& faces = positive ? l.faces_pos : l.faces_neg;
    const double a = std::abs(v);
    std::size_t c = static_cast<std::size_t>(std::upper_bound(faces.begin(), faces.end(), a) - faces.begin());
    c = std::clamp<std::size_t>(c, 1, faces.size() - 1) - 1;
    const double lo = faces[c], hi = faces[c + 1];
    double xi = std::clamp((a - lo) / (hi - lo) * 2.0 - 1.0, -1.0, 1.0);
    if (!positive) xi = -xi; // a negative cell runs from -faces[c + 1] (xi = -1) to -faces[c]
    const std::size_t u = positive ? l.pos(j, c, 0) : l.neg(j, c, 0);
    return chi[u] + chi[u + 1] * xi + chi[u + 2] * 0.5 * (3.0 * xi * xi - 1.0);
}

} // namespace

std::shared_ptr<Corrector> make_corrector(const ModelParams& p, const DriftLaw& law) {
    const Problem pr = make_problem(p, law);
    const Layout l = make_level_layout(pr, 1, 1);
    std::vector<double> chi;
    const GridSolution sol = solve_grid(l, pr.drift, pr.tau, &chi);
    const NoiseGrid& g = l.noise;
    const Scales sc = scales_of(p);
    const double root_tau = std::sqrt(p.tau);
    const double to_g = sc.length * root_tau; // d chi / dX = u0 sqrt(tau) d chi'/dz

    auto c = std::make_shared<Corrector>();
    c->source = "kolmogorov";
    c->diffusivity = sol.diffusivity * sc.diffusivity;

    // Sliding: chi_z at the midpoints between nodes, linear between them, on
    // a uniform grid in z whose spacing is the band's (capped).
    const std::size_t nodes = g.size();
    std::vector<double> mids(nodes - 1);
    for (std::size_t j = 0; j + 1 < nodes; ++j) mids[j] = 0.5 * (g.z[j] + g.z[j + 1]);
    const double band_h = g.z[g.band_lower + 1] - g.z[g.band_lower];
    const double z_first = mids.front(), z_last = mids.back();
    const int nx = static_cast<int>(std::min<double>(kMostNoiseNodes, std::ceil((z_last - z_first) / band_h) + 1));
    const double dz = (z_last - z_first) / (nx - 1);
    const DriftLawWhiteNoise white(pr.drift, 1.0, 1.0);
    const double v_lo = std::max(white.lower_end(kTableDrop), pr.v_lower);
    const double v_hi = std::min(white.upper_end(kTableDrop), pr.v_upper);
    const double dv = (v_hi - v_lo) / (kVelocityNodes - 1);
    // The difference quotients per interval, at each table velocity.
    std::vector<double> quotient((nodes - 1) * kVelocityNodes);
    for (std::size_t j = 0; j + 1 < nodes; ++j)
        for (int k = 0; k < kVelocityNodes; ++k) {
            const double v = v_lo + k * dv;
            quotient[j * kVelocityNodes + static_cast<std::size_t>(k)] =
                (chi_at(l, chi, j + 1, v) - chi_at(l, chi, j, v)) / (g.z[j + 1] - g.z[j]);
        }
    c->slide.resize(static_cast<std::size_t>(nx) * kVelocityNodes);
    for (int i = 0; i < nx; ++i) {
        const double z = z_first + i * dz;
        std::size_t j = static_cast<std::size_t>(std::upper_bound(mids.begin(), mids.end(), z) - mids.begin());
        j = std::clamp<std::size_t>(j, 1, mids.size() - 1) - 1;
        const double f = std::clamp((z - mids[j]) / (mids[j + 1] - mids[j]), 0.0, 1.0);
        for (int k = 0; k < kVelocityNodes; ++k) {
            const double a = quotient[j * kVelocityNodes + static_cast<std::size_t>(k)];
            const double b = quotient[(j + 1) * kVelocityNodes + static_cast<std::size_t>(k)];
            c->slide[static_cast<std::size_t>(i) * kVelocityNodes + static_cast<std::size_t>(k)] = to_g * (a + f * (b - a));
        }
    }
    // Stuck: along the band, from its lower edge to its upper one; at an edge
    // a stuck path starts to slide, so chi there is the sliding chi at v = 0-
    // (lower edge) or 0+ (upper edge).
    std::vector<double> line;
    for (std::size_t j = g.band_lower; j <= g.band_upper; ++j) {
        if (j == g.band_lower) line.push_back(chi[l.neg(j, 0, 0)] + chi[l.neg(j, 0, 1)] + chi[l.neg(j, 0, 2)]);
        else if (j == g.band_upper) line.push_back(chi[l.pos(j, 0, 0)] - chi[l.pos(j, 0, 1)] + chi[l.pos(j, 0, 2)]);
        else line.push_back(chi[l.stuck(j)]);
    }
    for (std::size_t j = 0; j + 1 < line.size(); ++j) c->stuck.push_back(to_g * (line[j + 1] - line[j]) / band_h);
    if (c->stuck.size() < 2) c->stuck.push_back(c->stuck.back());

    CorrectorTable& t = c->table;
    t.nx = nx;
    t.nv = kVelocityNodes;
    t.x_first = z_first / root_tau;
    t.inv_dx = root_tau / dz;
    t.v_first = v_lo * sc.velocity;
    t.inv_dv = 1.0 / (dv * sc.velocity);
    t.ns = static_cast<int>(c->stuck.size());
    t.s_first = (g.z[g.band_lower] + 0.5 * band_h) / root_tau;
    t.inv_ds = root_tau / band_h;
    c->grid = "near-white z " + std::to_string(nodes) + " nodes, v " + std::to_string(l.cells_neg()) + " + " +
              std::to_string(l.cells_pos()) + " cells; table " + std::to_string(nx) + " x " + std::to_string(kVelocityNodes);
    return c;
}

} // namespace stickslip::detail::near_white
