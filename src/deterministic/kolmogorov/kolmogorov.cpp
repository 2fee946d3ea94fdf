// SPDX-License-Identifier: BSD-3-Clause
// The Kolmogorov grid solver's top level (kolmogorov.hpp): the grids of the
// refinement levels, one grid's solve, and the extrapolation over levels.
#include "stickslip/kolmogorov.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "core/format.hpp"
#include "deterministic/kolmogorov/chain.hpp"
#include "stickslip/errors.hpp"

namespace stickslip {

namespace {

using detail::kolmogorov::DriftLaw;

/// Where the flow c(v) = b(v) + force (decreasing in v with drag) stops the
/// velocity on the side `dir` (+1 or -1), looking no further than `limit`
/// [m/s]: the terminal velocity, or `limit` when the flow still drives the
/// velocity outwards there.
double stopping_velocity(const DriftLaw& drift, double force, double dir, double limit) {
    auto outward = [&](double v) { return dir * (drift(dir * v) + force) > 0; };
    if (outward(limit)) return limit;
    double lo = 0, hi = limit;
    for (int k = 0; k < 200 && hi - lo > 1e-12 * limit; ++k) {
        const double mid = 0.5 * (lo + hi);
        (outward(mid) ? lo : hi) = mid;
    }
    return hi;
}

} // namespace

KolmogorovGrid kolmogorov_grid(const ModelParams& p, const KolmogorovSettings& s, int level) {
    const DriftLaw drift{p};
    const double a = p.force_amplitude(), sd = 1.0 / std::sqrt(p.tau);
    KolmogorovGrid g;
    g.lower_threshold = (-p.friction - drift(0.0)) / a;
    g.upper_threshold = (p.friction - drift(0.0)) / a;
    const double band = g.upper_threshold - g.lower_threshold;
    const std::size_t scale = std::size_t{1} << level;
    const std::size_t coarse_band =
        s.band_intervals > 0 ? s.band_intervals
                             : static_cast<std::size_t>(std::max(2.0, std::ceil(band / (0.25 * std::min(band, sd)))));
    const double coarse_h = band / static_cast<double>(coarse_band);
    const double reach = s.x_range * sd;
    const auto beyond = [&](double distance) {
        return static_cast<std::size_t>(std::max(1.0, std::ceil(distance / coarse_h)));
    };
    const std::size_t below = beyond(g.lower_threshold + reach), above = beyond(reach - g.upper_threshold);
    g.band_intervals = coarse_band * scale;
    g.x_spacing = band / static_cast<double>(g.band_intervals);
    g.band_first = below * scale;
    g.x_nodes = (below + coarse_band + above) * scale + 1;

    // Velocity range: without drag the slip a force a x sustains for about tau
    // reaches (a x + b(0) - friction) tau; drag stops it at its terminal velocity.
    const double x_top = g.x_upper(), x_bottom = g.x_lower();
    const double push_up = std::max(a * x_top + drift(0.0) - p.friction, 0.0);
    const double push_down = std::max(-(a * x_bottom + drift(0.0) + p.friction), 0.0);
    const double floor = 0.05 * a * sd * p.tau; // a range even when the force can hardly slide
    g.v_upper = s.v_upper > 0 ? s.v_upper
                              : stopping_velocity(drift, a * x_top - p.friction, +1.0, std::max(push_up * p.tau, floor));
    g.v_lower = s.v_lower < 0 ? s.v_lower
                              : -stopping_velocity(drift, a * x_bottom + p.friction, -1.0, std::max(push_down * p.tau, floor));
    const std::size_t coarse_cells = s.v_cells > 0 ? s.v_cells : 16;
    g.v_cells_pos = g.v_cells_neg = coarse_cells * scale;
    g.v_stretch = s.v_stretch;
    g.v_grading = s.v_grading;
    return g;
}

KolmogorovGridSolution solve_kolmogorov_grid(const ModelParams& p, const KolmogorovGrid& grid) {
    namespace k = detail::kolmogorov;
    const auto start = std::chrono::steady_clock::now();
    const k::ChainGrid chain_grid = k::make_grid(grid);
    const k::Chain chain = k::build_chain(p, chain_grid, k::DriftLaw{p});
    const k::ChainSolution sol = k::solve_chain(chain);

    KolmogorovGridSolution out;
    out.grid = grid;
    out.states = chain.size();
    out.lu_nonzeros = sol.nonzeros_lu;
    out.diffusivity = sol.diffusivity;
    out.diffusivity_x = sol.diffusivity_x;
    out.mobility = sol.mobility;
    out.stuck_probability = sol.stuck_probability;

    // The v-marginal density of the sliding states, and the mass at the ends.
    const std::size_t mn = chain_grid.cells_neg(), mp = chain_grid.cells_pos(), nx = chain_grid.x.size();
    out.velocity_faces.resize(mn + mp + 1);
    for (std::size_t i = 0; i <= mn; ++i) out.velocity_faces[i] = chain_grid.faces_neg[mn - i];
    for (std::size_t i = 1; i <= mp; ++i) out.velocity_faces[mn + i] = chain_grid.faces_pos[i];
    out.velocity_density.assign(mn + mp, 0.0);
    for (std::size_t s = 0; s < chain.size(); ++s) {
        const std::size_t j = chain.x_node[s];
        const bool end_node = j == 0 || j + 1 == nx;
        if (chain.stuck[s]) {
            if (end_node) out.tail_mass += sol.stationary[s];
            continue;
        }
        // Column in the increasing order of velocity_faces.
        const std::size_t offset = s - chain.first[j];
        const std::size_t column = offset < mn ? offset : offset - (chain_grid.in_band(j) ? 1 : 0);
        out.velocity_density[column] += sol.stationary[s] / chain.width[s];
        if (end_node || column == 0 || column + 1 == mn + mp) out.tail_mass += sol.stationary[s];
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace stickslip
