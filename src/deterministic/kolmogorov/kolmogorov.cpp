// SPDX-License-Identifier: BSD-3-Clause
// The Kolmogorov grid solver's top level (kolmogorov.hpp): the grids of the
// refinement levels, one grid's solve, and the extrapolation over levels.
#include "stickslip/kolmogorov.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <future>
#include <limits>
#include <string>

#include "core/format.hpp"
#include "deterministic/kolmogorov/chain.hpp"
#include "stickslip/engine.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/kernels/pdmp.hpp"

namespace stickslip {

namespace {

using KolmogorovDrift = detail::kolmogorov::DriftLaw;

/// Where the flow c(v) = b(v) + force (decreasing in v with drag) stops the
/// velocity on the side `dir` (+1 or -1), looking no further than `limit`
/// [m/s]: the terminal velocity, or `limit` when the flow still drives the
/// velocity outwards there.
double stopping_velocity(const KolmogorovDrift& drift, double force, double dir, double limit) {
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
    return detail::kolmogorov::make_kolmogorov_grid(p, s, level, KolmogorovDrift{p});
}

KolmogorovGridSolution solve_kolmogorov_grid(const ModelParams& p, const KolmogorovGrid& grid) {
    return detail::kolmogorov::solve_grid(p, grid, KolmogorovDrift{p});
}

namespace detail::kolmogorov {

KolmogorovGrid make_kolmogorov_grid(const ModelParams& p, const KolmogorovSettings& s, int level,
                                    const DriftLaw& drift) {
    const double a = p.force_amplitude(), sd = 1.0 / std::sqrt(p.tau);
    KolmogorovGrid g;
    g.lower_threshold = (-p.friction - drift(0.0)) / a;
    g.upper_threshold = (p.friction - drift(0.0)) / a;
    const double band = g.upper_threshold - g.lower_threshold;
    const std::size_t scale = std::size_t{1} << level;
    const std::size_t coarse_band =
        s.band_intervals > 0 ? s.band_intervals / 4
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
    if (s.pdmp_grid > 0) {
        // The PDMP engine's lattice, the same at every level.
        EngineSettings engine;
        engine.grid = s.pdmp_grid;
        engine.lattice_bound = s.pdmp_lattice_bound;
        const PdmpConstants c = make_pdmp_constants(p, engine);
        g.lattice_step = c.delta;
        g.lattice_bound = c.n_max * c.delta;
        g.x_spacing = c.delta;
        g.lower_threshold = c.k_minus * c.delta;
        g.upper_threshold = c.k_plus * c.delta;
        g.band_intervals = static_cast<std::size_t>(c.k_plus - c.k_minus);
        g.band_first = static_cast<std::size_t>(c.k_minus + c.n_max);
        g.x_nodes = 2 * static_cast<std::size_t>(c.n_max) + 1;
    }

    // Velocity range. Without drag, the slip that a force a x sustains for
    // about tau reaches (a x + b(0) - friction) tau: twice that from the end
    // nodes (D, weighted by v^2 and long correlations, needs more of the tail
    // than the mass does: 2 was within 0.06% of 3 at tau' = 1). Near the
    // white-noise limit the velocity's own scale noise/friction takes over:
    // 10 of it is where Hayakawa's density for pure dry friction has fallen by
    // e^-20. Drag stops the velocity at the terminal velocity of the end node,
    // which no path can exceed.
    const double x_top = g.x_upper(), x_bottom = g.x_lower();
    const double push_up = std::max(a * x_top + drift(0.0) - p.friction, 0.0);
    const double push_down = std::max(-(a * x_bottom + drift(0.0) + p.friction), 0.0);
    const double white_scale = 10.0 * p.noise / p.friction;
    g.v_upper = s.v_upper > 0 ? s.v_upper
                              : stopping_velocity(drift, a * x_top - p.friction, +1.0, std::max(2.0 * push_up * p.tau, white_scale));
    g.v_lower = s.v_lower < 0 ? s.v_lower
                              : -stopping_velocity(drift, a * x_bottom + p.friction, -1.0, std::max(2.0 * push_down * p.tau, white_scale));
    const std::size_t coarse_cells = (s.v_cells > 0 ? s.v_cells : 128) / 8;
    g.v_cells_pos = g.v_cells_neg = coarse_cells * scale;
    g.v_stretch = s.v_stretch;
    g.v_grading = s.v_grading;
    return g;
}

KolmogorovGridSolution solve_grid(const ModelParams& p, const KolmogorovGrid& grid, const DriftLaw& drift) {
    const auto start = std::chrono::steady_clock::now();
    const ChainGrid chain_grid = make_grid(p, grid);
    const Chain chain = build_chain(p, chain_grid, drift);
    const ChainSolution sol = solve_chain(chain);

    KolmogorovGridSolution out;
    out.grid = grid;
    out.states = chain.size();
    out.lu_nonzeros = sol.nonzeros_lu;
    out.diffusivity = sol.diffusivity;
    out.diffusivity_x = sol.diffusivity_x;
    out.mobility = sol.mobility;
    out.stuck_probability = sol.stuck_probability;
    out.mean_duration = sol.mean_duration;

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

} // namespace detail::kolmogorov

namespace {

/// R0 from values at steps h, h/2, h/4 (, h/8) under R = R0 + C1 h + C2 h^2
/// (+ C3 h^3): first-order upwind transport has C1 != 0, the x moves often
/// C1 ~ 0. The error is the size of the last correction: the difference from
/// the extrapolation of one order less over the finer values. With four v
/// levels that estimate was sharp where three were not (pure dry friction,
/// tau' = 1: the three-level estimate 1.5% for an actual 0.1%, the four-level
/// one 0.12% for an actual 0.02%; kolmogorov_measurements.md).
struct Extrapolated {
    double value = 0, error = 0;
};
double first_order(double middle, double fine) { return 2.0 * fine - middle; }
double second_order(double coarse, double middle, double fine) { return (8.0 * fine - 6.0 * middle + coarse) / 3.0; }
Extrapolated richardson(double coarse, double middle, double fine) {
    const double value = second_order(coarse, middle, fine);
    return {value, std::abs(value - first_order(middle, fine))};
}
Extrapolated richardson(double coarsest, double coarse, double middle, double fine) {
    const double value = (64.0 * fine - 56.0 * middle + 14.0 * coarse - coarsest) / 21.0;
    return {value, std::abs(value - second_order(coarse, middle, fine))};
}

void validate_settings(const KolmogorovSettings& s) {
    auto require = [](bool ok, const char* name, const std::string& what) {
        if (!ok) throw InvalidParameter(name, std::string(name) + " must be " + what);
    };
    require(s.band_intervals == 0 || (s.band_intervals >= 4 && s.band_intervals % 4 == 0), "band_intervals",
            "0 (automatic) or a multiple of 4 (the x refinement takes a quarter of it), got " +
                std::to_string(s.band_intervals));
    require(s.v_cells == 0 || (s.v_cells >= 32 && s.v_cells % 8 == 0), "v_cells",
            "0 (automatic) or a multiple of 8 >= 32 (the v refinement takes an eighth of it), got " +
                std::to_string(s.v_cells));
    require(std::isfinite(s.x_range) && s.x_range >= 3, "x_range", ">= 3 standard deviations, got " + detail::format_number(s.x_range));
    require(std::isfinite(s.v_lower) && s.v_lower <= 0, "v_lower", "<= 0 m/s (0: automatic), got " + detail::format_number(s.v_lower));
    require(std::isfinite(s.v_upper) && s.v_upper >= 0, "v_upper", ">= 0 m/s (0: automatic), got " + detail::format_number(s.v_upper));
    require(std::isfinite(s.v_stretch) && s.v_stretch >= 0 && s.v_stretch <= 20, "v_stretch",
            "in [0, 20], got " + detail::format_number(s.v_stretch));
    require(std::isfinite(s.v_grading) && s.v_grading >= 1 && s.v_grading <= 5, "v_grading",
            "in [1, 5], got " + detail::format_number(s.v_grading));
    require(s.rel_precision > 0 && s.rel_precision < 1, "rel_precision", "in (0, 1), got " + detail::format_number(s.rel_precision));
    require(s.memory_budget > 0, "memory_budget", "> 0 bytes, got " + detail::format_number(s.memory_budget));
    require(s.time_budget > 0, "time_budget", "> 0 s, got " + detail::format_number(s.time_budget));
    require(s.threads == 1 || s.threads == 2, "threads", "1 or 2, got " + std::to_string(s.threads));
    require(std::isfinite(s.pdmp_grid) && s.pdmp_grid >= 0, "pdmp_grid",
            ">= 0 s^-1/2 (0: the continuum solver), got " + detail::format_number(s.pdmp_grid));
    require(std::isfinite(s.pdmp_lattice_bound) && s.pdmp_lattice_bound >= 0, "pdmp_lattice_bound",
            ">= 0 s^-1/2 (0: the engine's choice), got " + detail::format_number(s.pdmp_lattice_bound));
}

} // namespace

void validate_kolmogorov(const ModelParams& p, const KolmogorovSettings& s) {
    validate(p);
    if (p.white())
        throw InvalidParameter("tau", "the Kolmogorov grid solver needs coloured noise (tau > 0): for white noise "
                                      "(tau = 0) the velocity alone is Markov; use the exact white-noise references "
                                      "(`stickslip analytic`, white_noise_reference())");
    const double tau_prime = to_nondimensional(p).tau;
    if (tau_prime < kolmogorov_min_tau_prime)
        throw InvalidParameter("tau", "tau' = tau friction^2/noise = " + detail::format_number(tau_prime) +
                                          " is below " + detail::format_number(kolmogorov_min_tau_prime) +
                                          ", where the x grid of the Kolmogorov solver grows like 1/sqrt(tau') and its "
                                          "rates stiffen: use the inclusion engine (Monte Carlo), or for tau' -> 0 "
                                          "the white-noise references (`stickslip analytic`)");
    require_stationary_state(p);
    validate_settings(s);
}

KolmogorovResult solve_kolmogorov(const ModelParams& p, const KolmogorovSettings& settings) {
    validate_kolmogorov(p, settings);
    namespace k = detail::kolmogorov;
    const KolmogorovDrift drift{p}; // the run's law, made once for every grid of the solve
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };

    KolmogorovResult result;
    result.params = p;
    // Refinement levels of x and v (kolmogorov_grid); each round solves its
    // finest grid and, for the extrapolation, v cells halved once, twice and
    // three times at its x spacing and x spacing doubled once and twice at its
    // v cells.
    int level_x = 2, level_v = 3;
    for (int round = 0;; ++round) {
        const KolmogorovGrid finest_x = k::make_kolmogorov_grid(p, settings, level_x, drift);
        const KolmogorovGrid finest_v = k::make_kolmogorov_grid(p, settings, level_v, drift);
        auto grid = [&](int x_coarsening, int v_coarsening) {
            KolmogorovGrid g = finest_x;
            const std::size_t fx = std::size_t{1} << x_coarsening, fv = std::size_t{1} << v_coarsening;
            if (fx > 1 && g.lattice_step > 0) throw std::logic_error("kolmogorov: the PDMP lattice is not coarsened");
            g.band_intervals /= fx;
            g.band_first /= fx;
            g.x_nodes = (g.x_nodes - 1) / fx + 1;
            g.x_spacing = (g.upper_threshold - g.lower_threshold) / static_cast<double>(g.band_intervals);
            g.v_cells_pos = finest_v.v_cells_pos / fv;
            g.v_cells_neg = finest_v.v_cells_neg / fv;
            return g;
        };
        const double round_start = elapsed();
        // The finest grid costs about as much as the four others together: it
        // runs on a second thread while they run on this one.
        std::future<KolmogorovGridSolution> finest_solution;
        if (settings.threads > 1)
            finest_solution = std::async(std::launch::async, [&] { return k::solve_grid(p, grid(0, 0), drift); });
        // On the PDMP lattice x is not refined: no x levels.
        const bool lattice = settings.pdmp_grid > 0;
        std::vector<KolmogorovGridSolution> solved;
        for (auto [cx, cv] : {std::pair{2, 0}, {1, 0}, {0, 3}, {0, 2}, {0, 1}})
            if (!lattice || cx == 0) solved.push_back(k::solve_grid(p, grid(cx, cv), drift));
        solved.push_back(settings.threads > 1 ? finest_solution.get() : k::solve_grid(p, grid(0, 0), drift));
        const double round_seconds = elapsed() - round_start;
        // Peak memory: the finest grid's factors beside the largest other's.
        std::size_t other = 0;
        for (std::size_t i = 0; i + 1 < solved.size(); ++i) other = std::max(other, solved[i].lu_nonzeros);
        const double round_bytes =
            kolmogorov_bytes_per_lu_nonzero * static_cast<double>(solved.back().lu_nonzeros + other);

        // Independent corrections in the two directions, from the finest grid.
        const KolmogorovGridSolution& fine = solved.back();
        const std::size_t v0 = lattice ? 0 : 2; // the first v level in `solved`
        double x_error = 0, v_error = 0;
        auto estimate = [&](auto field, bool record) {
            const Extrapolated in_x = lattice ? Extrapolated{field(fine), 0.0}
                                              : richardson(field(solved[0]), field(solved[1]), field(fine));
            const Extrapolated in_v =
                richardson(field(solved[v0]), field(solved[v0 + 1]), field(solved[v0 + 2]), field(fine));
            if (record) x_error = in_x.error, v_error = in_v.error;
            return KolmogorovEstimate{in_x.value + in_v.value - field(fine), in_x.error + in_v.error};
        };
        result.diffusivity = estimate([](const KolmogorovGridSolution& s) { return s.diffusivity; }, true);
        result.diffusivity_x = estimate([](const KolmogorovGridSolution& s) { return s.diffusivity_x; }, false);
        result.mobility = estimate([](const KolmogorovGridSolution& s) { return s.mobility; }, false);
        result.stuck_probability = estimate([](const KolmogorovGridSolution& s) { return s.stuck_probability; }, false);
        result.mean_duration = estimate([](const KolmogorovGridSolution& s) { return s.mean_duration; }, false);
        for (auto& s : solved) result.levels.push_back(std::move(s));

        const double relative = result.diffusivity.error / std::abs(result.diffusivity.value);
        result.converged = relative <= settings.rel_precision;
        if (result.converged) break;
        // Refine v always (first-order transport: its error dominates), x only
        // while its error is more than a quarter of v's. Doubling one direction
        // doubles the states, both quadruples them; time grows faster than the
        // states (measured: up to 3 and 7 times a round's time).
        const bool refine_x = x_error > 0.25 * v_error;
        const double growth = refine_x ? 7.0 : 3.2;
        const bool over_memory = growth * round_bytes > settings.memory_budget;
        if (elapsed() + growth * round_seconds > settings.time_budget || over_memory) {
            result.note = "the estimated error of D, " + detail::format_number(relative, 3) +
                          " relative, is above rel_precision " + detail::format_number(settings.rel_precision, 3) +
                          ": the next refinement would exceed the " + (over_memory ? "memory" : "time") + " budget";
            break;
        }
        ++level_v;
        if (refine_x) ++level_x;
    }
    const KolmogorovGridSolution& fine = result.levels.back();
    result.seconds = elapsed();
    GridDetails details;
    details.solver = settings.pdmp_grid > 0 ? "kolmogorov (pdmp lattice in x)" : "kolmogorov";
    details.cells = fine.states;
    details.lower = fine.grid.v_lower;
    details.upper = fine.grid.v_upper;
    details.discretisation_error = result.diffusivity.error / std::abs(result.diffusivity.value);
    result.details = details;
    return result;
}

} // namespace stickslip
