// SPDX-License-Identifier: BSD-3-Clause
// The Kolmogorov grid solver's top level (kolmogorov.hpp): the grids of the
// refinement levels, one grid's solve, and the extrapolation over levels.
#include "stickslip/kolmogorov.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/format.hpp"
#include "core/memory.hpp"
#include "deterministic/grid_tasks.hpp"
#include "deterministic/kolmogorov/chain.hpp"
#include "deterministic/near_white/near_white.hpp"
#include "stickslip/drift_input.hpp"
#include "stickslip/engine.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/random/portable_math.hpp"
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

KolmogorovGridSpan grid_span(const KolmogorovResult& r) {
    KolmogorovGridSpan span;
    for (const KolmogorovGridSolution& s : r.levels) {
        span.largest_states = std::max(span.largest_states, s.states);
        span.x_nodes = std::max(span.x_nodes, s.grid.x_nodes);
        span.v_cells = std::max(span.v_cells, s.grid.v_cells_neg + s.grid.v_cells_pos);
        span.tail_mass = std::max(span.tail_mass, s.tail_mass);
    }
    const KolmogorovGrid& last = r.levels.back().grid;
    span.x_lower = last.x_lower();
    span.x_upper = last.x_upper();
    span.v_lower = last.v_lower;
    span.v_upper = last.v_upper;
    span.grids_solved = r.levels.size();
    span.diffusivity_x = r.diffusivity_x;
    return span;
}

KolmogorovGridSolution solve_kolmogorov_grid(const ModelParams& p, const KolmogorovGrid& grid) {
    return detail::kolmogorov::solve_grid(p, grid, KolmogorovDrift{p});
}

namespace detail::kolmogorov {

KolmogorovGrid make_kolmogorov_grid(const ModelParams& p, const KolmogorovSettings& s, int level,
                                    const DriftLaw& drift) {
    const double a = p.force_amplitude(), sd = 1.0 / std::sqrt(p.tau);
    KolmogorovGrid g;
    // The band is the static one: the stuck line spans it (chain.cpp).
    const double band_friction = p.static_friction_level();
    g.lower_threshold = (-band_friction - drift(0.0)) / a;
    g.upper_threshold = (band_friction - drift(0.0)) / a;
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
        g.lower_threshold = pdmp_noise(c, c.k_minus);
        g.upper_threshold = pdmp_noise(c, c.k_plus);
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

std::vector<double> grid_spectrum(const ModelParams& p, const KolmogorovGrid& grid, const DriftLaw& drift,
                                  const std::vector<double>& frequencies) {
    const Chain chain = build_chain(p, make_grid(p, grid), drift);
    return chain_spectrum(chain, solve_chain(chain), frequencies);
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
    out.velocity_variance = sol.velocity_variance;
    out.stuck_probability = sol.stuck_probability;
    out.mean_duration = sol.mean_duration;

    // The v-marginal density of the sliding states, and the mass at the ends.
    const std::size_t mn = chain_grid.cells_neg(), mp = chain_grid.cells_pos();
    out.velocity_faces.resize(mn + mp + 1);
    for (std::size_t i = 0; i <= mn; ++i) out.velocity_faces[i] = chain_grid.faces_neg[mn - i];
    for (std::size_t i = 1; i <= mp; ++i) out.velocity_faces[mn + i] = chain_grid.faces_pos[i];
    out.velocity_density.assign(mn + mp, 0.0);
    out.tail_mass = sol.tail_mass;
    for (std::size_t s = 0; s < chain.size(); ++s) {
        if (chain.stuck[s]) continue;
        // Column in the increasing order of velocity_faces.
        const std::size_t j = chain.x_node[s];
        const std::size_t offset = s - chain.first[j];
        const std::size_t column = offset < mn ? offset : offset - (chain_grid.in_band(j) ? 1 : 0);
        out.velocity_density[column] += sol.stationary[s] / chain.width[s];
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace detail::kolmogorov

namespace {

/// R0 from values at steps h, h/2, h/4, h/8 under R = R0 + C1 h + C2 h^2 +
/// C3 h^3, fitted exactly. The error is the size of the last correction: the
/// difference from the fit of one order less through the three finer values.
/// In v (first-order upwind transport, C1 != 0) three levels' estimate was
/// 9 times the actual error and four levels' about 7 times (pure dry friction,
/// tau' = 1: 0.93% for 0.10%, 0.12% for 0.017%); in x the scheme is second
/// order (successive differences shrink 3.4, 3.7, 4.0-fold), where three
/// levels' estimate, blind to that, was 10-100 times the actual error and four
/// levels' 1.3-2.5 times (kolmogorov_measurements.md).
struct Extrapolated {
    double value = 0, error = 0;
};
double second_order(double coarse, double middle, double fine) { return (8.0 * fine - 6.0 * middle + coarse) / 3.0; }
Extrapolated richardson(double coarsest, double coarse, double middle, double fine) {
    const double value = (64.0 * fine - 56.0 * middle + 14.0 * coarse - coarsest) / 21.0;
    return {value, std::abs(value - second_order(coarse, middle, fine))};
}

/// Where a solve stands: the x levels kx - 3 .. kx are solved at the v level
/// av (the x sequence), the v levels kv - 3 .. kv at the x level ax (the v
/// sequence), and the six grids (ax - 1 .. ax + 1, av or av + 1) for the mixed
/// term and the check of its model. On the PDMP lattice only the v sequence
/// exists (x is not refined).
struct Levels {
    int ax = 1, av = 2, kx = 3, kv = 4;
};

/// The grid with the x spacing of level lx and the velocity cells of level lv.
using GridKey = std::pair<int, int>;

std::vector<GridKey> grids_needed(const Levels& l, bool lattice) {
    std::vector<GridKey> keys;
    for (int v = l.kv - 3; v <= l.kv; ++v) keys.push_back({lattice ? 0 : l.ax, v});
    if (lattice) return keys;
    for (int x = l.kx - 3; x <= l.kx; ++x) keys.push_back({x, l.av});
    for (int x = l.ax - 1; x <= l.ax + 1; ++x)
        for (int v = l.av; v <= l.av + 1; ++v) keys.push_back({x, v});
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
}

/// The time budget's clock: modelled seconds, a function of the grids alone,
/// so that where a solve stops, and so its result, is the same on every
/// machine, load and thread count (measured seconds made the last round
/// depend on them). A grid of n states is modelled as taking
/// kSecondsPerState18 n^1.8 s: its time grows like n^1.6-1.75 whichever
/// direction is refined, more with two solves sharing the memory bandwidth;
/// measured on 2 cores with two grids at once (Fig. 2 and pure dry friction,
/// tau' = 0.1 to 1, 3e4 to 1.3e5 states), seconds / n^1.8 was 0.7e-9 to
/// 2.1e-9, so 1.6e-9 puts most solves' wall time below the modelled one.
constexpr double kSecondsPerState18 = 1.6e-9;
double modelled_seconds(double n) { return kSecondsPerState18 * portable_pow(n, 1.8); }
/// A round's modelled duration: its grids two at a time (whatever the thread
/// count, which must not change the result), so the longest grid or half
/// their sum.
double modelled_round(const std::vector<double>& states) {
    double sum = 0, longest = 0;
    for (double n : states) {
        const double t = modelled_seconds(n);
        sum += t;
        longest = std::max(longest, t);
    }
    return std::max(longest, sum / 2.0);
}
/// Predicted LU nonzeros of a grid of n states from the largest grid solved
/// so far (n_ref states, z_ref nonzeros; both a function of the grids alone):
/// they grow like n^1-1.3.
double predicted_nonzeros(double n, double n_ref, double z_ref) { return z_ref * portable_pow(n / n_ref, 1.3); }

} // namespace

void validate(const KolmogorovSettings& s) {
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
    require(s.frequencies.size() <= kolmogorov_max_frequencies, "frequencies",
            "at most " + std::to_string(kolmogorov_max_frequencies) + " values, got " + std::to_string(s.frequencies.size()));
    for (double w : s.frequencies)
        require(std::isfinite(w) && w >= 0, "frequencies", "finite and >= 0 rad/s, got " + detail::format_number(w));
    require(std::isfinite(s.pdmp_lattice_bound) && s.pdmp_lattice_bound >= 0, "pdmp_lattice_bound",
            ">= 0 s^-1/2 (0: the engine's choice), got " + detail::format_number(s.pdmp_lattice_bound));
}

namespace {

/// Bytes per state of the chain's first round before any is solved: its LU
/// keeps about 60 nonzeros per state (16 bytes each), with the generator.
constexpr double kChainBytesPerStateFirstRound = 1.5e3;

/// The mass at the chain's range's edges above which the automatic choice
/// takes the near-white discretisation (solve_kolmogorov).
constexpr double kChainEdgeMass = 1e-8;

/// The stationary probabilities that the noise lies inside the static band
/// and beyond it (either side), each without cancellation.
struct BandMasses {
    double inside = 0, outside = 0;
};
BandMasses band_masses(const Model& model) {
    const double s = std::sqrt(model.params.tau / 2.0); // X has standard deviation 1/sqrt(tau): erfc(x s) is 2 P(Z > x sqrt(tau))
    const double lo = model.lower_threshold() * s, hi = model.upper_threshold() * s;
    BandMasses m;
    m.outside = 0.5 * (std::erfc(hi) + std::erfc(-lo));
    m.inside = lo >= 0 ? 0.5 * (std::erfc(lo) - std::erfc(hi))
                       : (hi <= 0 ? 0.5 * (std::erfc(-hi) - std::erfc(-lo)) : 1.0 - m.outside);
    return m;
}

/// The setting to name for a model beyond the solver's reach: the first of
/// tau, friction, noise, bias that differs from the default model's.
const char* setting_to_change(const ModelParams& p) {
    const ModelParams defaults;
    if (p.tau != defaults.tau) return "tau";
    if (p.friction != defaults.friction) return "friction";
    if (p.noise != defaults.noise) return "noise";
    return "bias";
}

/// The grids resolve the rarer of the two phases, sliding (the noise beyond
/// the static band) or stuck (inside it), down to a stationary probability of
/// kRarestPhase: beyond, their rates and masses span more than double
/// precision keeps (pure dry friction at tau' = 100, 3e-45 of the time
/// sliding: D = -7.7e-23 "to 100%", E[t1] inf; --tau 1e6 and --bias 1e6 took
/// 24 GB before they were killed).
constexpr double kRarestPhase = 1e-12;
void check_noise_band(const Model& model) {
    const ModelParams& p = model.params;
    const BandMasses m = band_masses(model);
    const char* name = setting_to_change(p);
    auto probability = [](double x) { return x > 0 ? detail::format_number(x, 2) : std::string("below 1e-300"); };
    if (!(m.outside >= kRarestPhase))
        throw InvalidParameter(name, "the noise leaves the static band with probability " + probability(m.outside) +
                                         " in the stationary state, below the " + detail::format_number(kRarestPhase) +
                                         " the Kolmogorov engine's grids resolve: the object is stuck all but that "
                                         "fraction of the time, so D and M0 vanish to double precision and a long "
                                         "excursion practically never ends; change --" + std::string(name) +
                                         " (tau' = tau friction^2/noise is " +
                                         detail::format_number(to_nondimensional(p).tau, 3) + ")");
    // Inside: a band far in the noise's tail (|b(0)| above the friction), not a
    // narrow one about 0, which near-white noise has and the solver takes.
    const bool band_holds_zero = model.lower_threshold() <= 0 && model.upper_threshold() >= 0;
    if (!band_holds_zero && !(m.inside >= kRarestPhase))
        throw InvalidParameter(name, "the noise is inside the static band with probability " + probability(m.inside) +
                                         " in the stationary state, below the " + detail::format_number(kRarestPhase) +
                                         " the Kolmogorov engine's grids resolve: the object practically never sticks, "
                                         "so a long excursion (which ends stuck) practically never ends; change --" +
                                         std::string(name));
}

} // namespace

namespace {
/// resolved_discretisation, with `drag_at_both_ends()` asked only when it decides.
template <class DragAtBothEnds>
KolmogorovDiscretisation choose_discretisation(const ModelParams& p, const KolmogorovSettings& s,
                                               DragAtBothEnds&& drag_at_both_ends) {
    if (s.discretisation != KolmogorovDiscretisation::Automatic) return s.discretisation;
    if (s.pdmp_grid > 0) return KolmogorovDiscretisation::Chain; // the chain's own mode
    if (to_nondimensional(p).tau < kolmogorov_near_white_below) return KolmogorovDiscretisation::NearWhite;
    // Without drag at both ends the chain's velocity range is a guess from
    // tau and the near-white discretisation reached smaller errors sooner
    // (kolmogorov.hpp, top).
    return drag_at_both_ends() ? KolmogorovDiscretisation::Chain : KolmogorovDiscretisation::NearWhite;
}
} // namespace

KolmogorovDiscretisation resolved_discretisation(const ModelParams& p, const KolmogorovSettings& s) {
    return choose_discretisation(p, s, [&] { return has_drag_at_both_ends(p); });
}

KolmogorovDiscretisation resolved_discretisation(const Model& m, const KolmogorovSettings& s) {
    return choose_discretisation(m.params, s, [&] { return has_drag_at_both_ends(m); });
}

bool has_drag_at_both_ends(const ModelParams& p) {
    return p.has_drift_law() ? has_drag_at_both_ends(make_model(p)) : std::isfinite(p.relaxation);
}

bool has_drag_at_both_ends(const Model& m) {
    if (!m.params.has_drift_law()) return std::isfinite(m.params.relaxation);
    const DriftLaw& b = *m.law;
    return b.piece_slope(0) < 0 && b.piece_slope(b.pieces() - 1) < 0;
}

void validate_kolmogorov(const ModelParams& p, const KolmogorovSettings& s) { validate_kolmogorov(make_model(p), s); }

void validate_kolmogorov(const Model& m, const KolmogorovSettings& s) {
    const ModelParams& p = m.params;
    if (p.white())
        throw InvalidParameter("tau", "the Kolmogorov grid solver needs coloured noise (tau > 0): for white noise "
                                      "(tau = 0) the velocity alone is Markov; use the exact white-noise references "
                                      "(`stickslip analytic`, white_noise_reference())");
    const double tau_prime = to_nondimensional(p).tau;
    const KolmogorovDiscretisation d = resolved_discretisation(m, s);
    // Within rounding of the limit is at it: tau' = 0.04999999999999999 from
    // SI units was refused as "0.05 is below 0.05".
    if (d == KolmogorovDiscretisation::Chain && tau_prime < kolmogorov_chain_min_tau_prime * (1 - 1e-9))
        throw InvalidParameter("tau", "tau' = tau friction^2/noise = " + detail::format_number(tau_prime) +
                                          " is below " + detail::format_number(kolmogorov_chain_min_tau_prime) +
                                          ", where the upwind chain's x grid grows like 1/sqrt(tau') and its "
                                          "rates stiffen: use the near-white discretisation, which takes every tau'");
    if (d == KolmogorovDiscretisation::NearWhite && s.pdmp_grid > 0)
        throw InvalidParameter("pdmp_grid", "the PDMP lattice mode belongs to the upwind chain, not to the "
                                            "near-white discretisation");
    require_stationary_state(m);
    validate(s);
    check_noise_band(m);
}

namespace {
/// solve_kolmogorov after its validation (below).
KolmogorovResult solve_validated(const Model& m, const KolmogorovSettings& settings);
} // namespace

KolmogorovResult solve_kolmogorov(const ModelParams& p, const KolmogorovSettings& settings) {
    return solve_kolmogorov(make_model(p), settings);
}

KolmogorovResult solve_kolmogorov(const Model& m, const KolmogorovSettings& settings) {
    validate_kolmogorov(m, settings);
    try {
        return solve_validated(m, settings);
    } catch (const std::bad_alloc&) {
        throw std::runtime_error("out of memory in the Kolmogorov engine's sparse LU: its grids need more than the " +
                                 detail::format_number(detail::usable_memory_bytes() / 1e9, 2) +
                                 " GB this process may still take (a larger --rel-precision needs fewer grids; or raise the limit)");
    }
}

namespace {

KolmogorovResult solve_validated(const Model& m, const KolmogorovSettings& settings) {
    const ModelParams& p = m.params;
    const DriftLaw& law = *m.law; // the run's law, made once for every grid of the solve
    if (resolved_discretisation(m, settings) == KolmogorovDiscretisation::NearWhite)
        return detail::near_white::solve(p, settings, law);
    namespace k = detail::kolmogorov;
    const KolmogorovDrift drift{law};
    // The chain's velocity range comes from the terminal velocity of its end
    // nodes' force, capped by a guess from tau: a weakly confining law (weak
    // drag, or a bias near the friction) reaches far beyond it, and the
    // chain then solved a cut problem with a tiny claimed error (issue 50: D
    // 352 where Monte Carlo gives 919 +- 52, and 466 for about 4600). Its
    // coarsest grid's mass at the range's edges tells (5e-12 on the Fig. 2
    // case, 0.04-0.06 on those): above kChainEdgeMass, the automatic choice
    // takes the near-white discretisation, whose range follows the law.
    if (settings.discretisation == KolmogorovDiscretisation::Automatic && settings.pdmp_grid == 0) {
        const double edge = k::solve_grid(p, k::make_kolmogorov_grid(p, settings, 0, drift), drift).tail_mass;
        if (edge > kChainEdgeMass) {
            KolmogorovResult r = detail::near_white::solve(p, settings, law);
            const std::string why = "the upwind chain's velocity range held " + detail::format_number(edge, 2) +
                                    " of the mass at its edges (its coarsest grid): solved with the near-white "
                                    "discretisation, whose range follows the drift law";
            r.note = r.note.empty() ? why : why + "; " + r.note;
            return r;
        }
    }
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };

    KolmogorovResult result;
    result.params = p;
    const bool lattice = settings.pdmp_grid > 0;
    auto make_grid = [&](GridKey key) {
        KolmogorovGrid g = k::make_kolmogorov_grid(p, settings, key.first, drift);
        const KolmogorovGrid v = k::make_kolmogorov_grid(p, settings, key.second, drift);
        g.v_cells_pos = v.v_cells_pos;
        g.v_cells_neg = v.v_cells_neg;
        return g;
    };
    auto states_of = [&](GridKey key) {
        const KolmogorovGrid g = make_grid(key);
        return static_cast<double>(g.x_nodes) * static_cast<double>(g.v_cells_pos + g.v_cells_neg);
    };
    std::map<GridKey, KolmogorovGridSolution> solved;
    double modelled = 0; // the budget's clock: modelled seconds of the rounds solved
    // The largest grid solved: the reference of the cost predictions.
    auto largest = [&]() -> const KolmogorovGridSolution& {
        const KolmogorovGridSolution* best = &solved.begin()->second;
        for (const auto& [key, s] : solved)
            if (s.states > best->states) best = &s;
        return *best;
    };
    // Solves the grids not solved yet, largest first, on settings.threads
    // threads (each grid is one sequential factorisation); a stop (when
    // `stoppable`: after the first round, which any result needs) starts no
    // further grid. Whether the round is complete.
    auto solve_missing = [&](const std::vector<GridKey>& keys, bool stoppable) {
        std::vector<GridKey> todo;
        for (GridKey key : keys)
            if (!solved.count(key)) todo.push_back(key);
        std::sort(todo.begin(), todo.end(), [&](GridKey a, GridKey b) { return states_of(a) > states_of(b); });
        std::vector<KolmogorovGridSolution> out(todo.size());
        // A stop starts no further grid; a grid not started keeps states == 0.
        detail::run_grid_tasks(todo.size(), settings.threads, stoppable ? settings.stop : nullptr,
                       [&](std::size_t i) { out[i] = k::solve_grid(p, make_grid(todo[i]), drift); });
        std::vector<double> sizes;
        bool complete = true;
        for (std::size_t i = 0; i < todo.size(); ++i) {
            if (out[i].states == 0) { // not started: a stop
                complete = false;
                continue;
            }
            sizes.push_back(static_cast<double>(out[i].states));
            solved.emplace(todo[i], std::move(out[i]));
        }
        modelled += modelled_round(sizes);
        return complete;
    };

    // The two directions are extrapolated separately, each on a sequence of
    // grids that is coarse in the other direction (the combination technique):
    //   D0 = D_v(ax) + D_x(av) - D(ax, av) - c(ax, av),
    // D_v(ax) the v extrapolation at the x level ax, D_x(av) the x
    // extrapolation at the v level av, and c the mixed term that the errors'
    // sum misses. Measured, c goes like hx^2 hv for D, M0 and E[t1] (it fell
    // 4-fold when ax rose and 2-fold when av rose: Fig. 4 at tau = 1 s, pure dry
    // friction), so the mixed difference m = D(ax, av) - D(ax+1, av) -
    // D(ax, av+1) + D(ax+1, av+1) = 3c/8 gives c, and the error of that
    // correction is taken as its difference from the first-order model's
    // (c = 4m): 4|m|/3, an overestimate (the corrected values moved 6-10 times
    // less when refined). The same difference one x level coarser checks the
    // model per quantity (below). So the grids that cost most, fine in one
    // direction, are coarse in the other (kolmogorov_measurements.md).
    Levels at;
    // One first round for every target: the Fig. 4 plane at 1% with the v
    // sequence a level coarser took 30 s instead of 48 s, but M0's estimate
    // fell short of its distance to the 0.1% value at one point in 40 (1.1
    // times); 32 velocity cells at the corner, 14 s, fell short for D, M0
    // and E[t1] (up to 3 times).
    if (lattice) at.ax = 0, at.kv = 3; // v levels 0-3: the lattice is fine in x already
    // Memory: the budget, or what this process may still take if less; the
    // first round must fit (else one line before any work: under `ulimit -v`
    // the LU died inside Eigen with "double free or corruption").
    const double usable = detail::usable_memory_bytes();
    const double memory_budget = std::min(settings.memory_budget, usable);
    {
        std::vector<double> first;
        for (GridKey key : grids_needed(at, lattice)) first.push_back(states_of(key));
        std::sort(first.rbegin(), first.rend());
        const double bytes = kChainBytesPerStateFirstRound * (first[0] + (first.size() > 1 ? first[1] : 0.0));
        if (bytes > usable)
            throw std::runtime_error("out of memory: the Kolmogorov engine's first grids need about " +
                                     detail::format_number(bytes / 1e9, 2) + " GB, more than the " +
                                     detail::format_number(usable / 1e9, 2) + " GB this process may still take");
    }
    Levels finished; // the last round whose estimates are in result
    auto interrupted = [&] {
        result.interrupted = true;
        result.note = "interrupted: the estimates are those of the rounds of grids finished before the stop "
                      "(estimated relative error of D " +
                      detail::format_number(result.diffusivity.error / std::abs(result.diffusivity.value), 3) +
                      ", target " + detail::format_number(settings.rel_precision, 3) + ")";
    };
    // The extrapolated estimate of one quantity from its values on the grids
    // of the round `at` (value(key)); `record`: keep the parts of its error
    // for the refinement (D's).
    double x_error = 0, v_error = 0, mixed_error = 0;
    auto extrapolated = [&](auto value, bool record) {
        const int vx = lattice ? 0 : at.ax;
        const Extrapolated in_v = richardson(value({vx, at.kv - 3}), value({vx, at.kv - 2}),
                                             value({vx, at.kv - 1}), value({vx, at.kv}));
        if (lattice) {
            if (record) v_error = in_v.error;
            return solved_estimate(in_v.value, in_v.error);
        }
        const Extrapolated in_x = richardson(value({at.kx - 3, at.av}), value({at.kx - 2, at.av}),
                                             value({at.kx - 1, at.av}), value({at.kx, at.av}));
        const double corner = value({at.ax, at.av});
        auto mixed_at = [&](int x) {
            return value({x, at.av}) - value({x + 1, at.av}) - value({x, at.av + 1}) +
                   value({x + 1, at.av + 1});
        };
        const double mixed = mixed_at(at.ax);
        // The model c ~ hx^2 hv is checked per quantity one x level
        // coarser: where m did not shrink at least 3-fold there (P(V = 0):
        // 1.2-fold on the Fig. 2 case, where D, M0 and E[t1] shrank 3.3-
        // 6.6-fold), the charge is 8|m|, covering an x order down to 1/4.
        const bool model_holds = std::abs(mixed_at(at.ax - 1)) >= 3.0 * std::abs(mixed);
        const double mixed_charge = (model_holds ? 4.0 / 3.0 : 8.0) * std::abs(mixed);
        if (record) x_error = in_x.error, v_error = in_v.error, mixed_error = mixed_charge;
        return solved_estimate(in_x.value + in_v.value - corner + 8.0 * mixed / 3.0,
                               in_x.error + in_v.error + mixed_charge);
    };
    for (bool first = true;; first = false) {
        if (!solve_missing(grids_needed(at, lattice), !first)) {
            at = finished;
            interrupted();
            break;
        }
        finished = at;

        auto estimate = [&](auto field, bool record) {
            return extrapolated([&](GridKey key) { return field(solved.at(key)); }, record);
        };
        result.diffusivity = estimate([](const KolmogorovGridSolution& s) { return s.diffusivity; }, true);
        result.diffusivity_x = estimate([](const KolmogorovGridSolution& s) { return s.diffusivity_x; }, false);
        result.mobility = estimate([](const KolmogorovGridSolution& s) { return s.mobility; }, false);
        result.velocity_variance = estimate([](const KolmogorovGridSolution& s) { return s.velocity_variance; }, false);
        result.stuck_probability = estimate([](const KolmogorovGridSolution& s) { return s.stuck_probability; }, false);
        result.mean_duration = estimate([](const KolmogorovGridSolution& s) { return s.mean_duration; }, false);

        const double relative = result.diffusivity.error / std::abs(result.diffusivity.value);
        result.converged = relative <= settings.rel_precision;
        if (result.converged) break;
        if (settings.stop && settings.stop->load()) {
            interrupted();
            break;
        }
        // Refine every part whose error is above a third of the target, and
        // the largest in any case: one level finer in x (the x extrapolation's
        // error fell about 4-fold per level), in v (8- to 10-fold), or for the
        // mixed term the cheaper per error removed of ax + 1 (the v sequence at
        // half the x spacing: c / 4) and av + 1 (the x sequence at twice the
        // v cells: c / 2).
        const double share = settings.rel_precision * std::abs(result.diffusivity.value) / 3.0;
        const double top = std::max({x_error, v_error, mixed_error});
        Levels next = at;
        if (v_error > share || v_error == top) ++next.kv;
        if (!lattice && (x_error > share || x_error == top)) ++next.kx;
        if (!lattice && (mixed_error > share || mixed_error == top)) {
            auto cost = [&](const Levels& l) {
                double sum = 0;
                for (GridKey key : grids_needed(l, lattice))
                    if (!solved.count(key)) sum += portable_pow(states_of(key), 2.0);
                return sum;
            };
            Levels finer_x = next, finer_v = next;
            ++finer_x.ax;
            ++finer_v.av;
            next = cost(finer_x) / 0.75 <= cost(finer_v) / 0.5 ? finer_x : finer_v;
        }
        // The budgets: the round's modelled time, and its memory predicted
        // from the largest grid solved so far (two grids at once, whatever
        // the thread count, so that the result does not depend on it).
        const KolmogorovGridSolution& ref = largest();
        const double n_ref = static_cast<double>(ref.states);
        std::vector<double> sizes;
        double largest_nonzeros = 0, second_nonzeros = 0;
        for (GridKey key : grids_needed(next, lattice)) {
            if (solved.count(key)) continue;
            const double n = states_of(key);
            sizes.push_back(n);
            const double z = predicted_nonzeros(n, n_ref, static_cast<double>(ref.lu_nonzeros));
            if (z > largest_nonzeros) second_nonzeros = largest_nonzeros, largest_nonzeros = z;
            else second_nonzeros = std::max(second_nonzeros, z);
        }
        const double round_bytes = kolmogorov_bytes_per_lu_nonzero * (largest_nonzeros + second_nonzeros);
        const bool over_memory = round_bytes > memory_budget;
        if (modelled + modelled_round(sizes) > settings.time_budget || over_memory) {
            result.note = "the estimated error of D, " + detail::format_number(relative, 3) +
                          " relative, is above rel_precision " + detail::format_number(settings.rel_precision, 3) +
                          ": the next refinement would exceed the " + (over_memory ? "memory" : "time") + " budget";
            break;
        }
        at = next;
    }
    // The spectrum, on the grids of the last round and extrapolated like D:
    // its frequencies do not steer the refinement (D's error does), and a
    // grid's complex solves are made only once the round is known.
    if (!settings.frequencies.empty()) {
        const auto spectra = detail::spectra_on_grids(grids_needed(at, lattice), settings.threads, settings.stop,
                                                      [&](GridKey key) {
                                                          return k::grid_spectrum(p, make_grid(key), drift,
                                                                                  settings.frequencies);
                                                      });
        if (!spectra) {
            interrupted();
            result.note += "; stopped before the spectrum was solved";
        } else {
            for (std::size_t f = 0; f < settings.frequencies.size(); ++f)
                result.spectrum.push_back(extrapolated([&](GridKey key) { return spectra->at(key)[f]; }, false));
        }
    }
    // The grids solved, the v sequence's finest last (its velocity density
    // is the one reported).
    const GridKey finest_v{lattice ? 0 : at.ax, at.kv};
    for (auto& [key, s] : solved)
        if (key != finest_v) result.levels.push_back(std::move(s));
    result.levels.push_back(std::move(solved.at(finest_v)));
    const KolmogorovGridSolution& fine = result.levels.back();
    result.seconds = elapsed();
    GridDetails details;
    details.solver = settings.pdmp_grid > 0 ? "kolmogorov (pdmp lattice in x)" : "kolmogorov";
    details.cells = grid_span(result).largest_states;
    details.lower = fine.grid.v_lower;
    details.upper = fine.grid.v_upper;
    details.discretisation_error = result.diffusivity.error / std::abs(result.diffusivity.value);
    result.details = details;
    return result;
}

} // namespace

} // namespace stickslip
