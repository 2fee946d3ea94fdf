// SPDX-License-Identifier: BSD-3-Clause
// The near-white solver's top level (near_white.hpp): the model in
// nondimensional form, the grids of each level, the rounds of refinement and
// the extrapolation.
#include "deterministic/near_white/near_white.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/format.hpp"
#include "core/memory.hpp"
#include "deterministic/grid_tasks.hpp"
#include "deterministic/near_white/grid_solve.hpp"
#include "stickslip/analytic.hpp"
#include "stickslip/drift_law_quadrature.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/random/portable_math.hpp"

namespace stickslip::detail::near_white {

namespace {

/// Phi has fallen this far below its peak at the velocity range's ends
/// (white noise's density e^-40 of its peak; widened below when the grid's
/// own tails say so).
constexpr double kRangeDrop = 40;

/// Where the flow b(v) + force - sgn v stops the velocity on the side `dir`,
/// looking no further than `limit`: the terminal velocity with drag, or limit.
double stopping_velocity(const DriftLaw& b, double force, double dir, double limit) {
    auto outward = [&](double v) { return dir * (b(dir * v) + force - dir) > 0; };
    if (outward(limit)) return limit;
    double lo = 0, hi = limit;
    for (int k = 0; k < 200 && hi - lo > 1e-12 * limit; ++k) {
        const double mid = 0.5 * (lo + hi);
        (outward(mid) ? lo : hi) = mid;
    }
    return hi;
}

/// A grid of the z level lz and the v level lv.
using GridKey = std::pair<int, int>;

GridSolution solve_level(const Problem& pr, GridKey key) {
    return solve_grid(make_level_layout(pr, key.first, key.second), pr.drift, pr.tau);
}

/// The unknowns of a grid, without building it.
double states_of(const Problem& pr, GridKey key) {
    const NoiseGrid noise = make_noise_grid(pr.tau, pr.z_lower, pr.z_upper, pr.noise, key.first);
    const double cells = static_cast<double>(make_velocity_faces(pr.v_upper, pr.velocity, key.second).size() +
                                             make_velocity_faces(-pr.v_lower, pr.velocity, key.second).size() - 2);
    return static_cast<double>(noise.size()) * dofs_per_cell * cells +
           static_cast<double>(noise.band_upper - noise.band_lower - 1);
}

/// The budget's clock, modelled seconds from a grid's unknowns alone (so that
/// where a solve stops, and its result, is the same on every machine, load
/// and thread count). Measured on 2 cores, one grid at a time, 2e4 to 5e5
/// unknowns: building, factorising and four solves took 0.9 to 1.6 times
/// 4e-7 n^1.3 s.
double modelled_seconds(double n) { return 6e-7 * portable_pow(n, 1.3); }
/// A round's grids two at a time (whatever the thread count).
double modelled_round(const std::vector<double>& states) {
    double sum = 0, longest = 0;
    for (double n : states) {
        const double t = modelled_seconds(n);
        sum += t;
        longest = std::max(longest, t);
    }
    return std::max(longest, sum / 2.0);
}
/// Bytes per unknown of the first round's grids, before any is solved: the
/// LU's nonzeros (measured 70 to 180 per unknown, 16 bytes each) with the
/// operator and its copies.
constexpr double kBytesPerStateFirstRound = 3.5e3;
/// Nonzeros of the LU factors predicted from the largest grid solved.
double predicted_nonzeros(double n, double n_ref, double z_ref) { return z_ref * portable_pow(n / n_ref, 1.2); }

/// Aitken's extrapolation of a sequence of three levels (near_white.hpp).
struct Extrapolated {
    double value = 0, error = 0;
};
Extrapolated aitken(double q0, double q1, double q2) {
    const double d1 = q1 - q0, d2 = q2 - q1;
    if (d2 == 0.0) return {q2, std::abs(d1) / 16.0};
    const double rho = d1 / d2;
    if (!(rho >= 2.0)) return {q2, std::abs(d1) + std::abs(d2)}; // no convergence seen (also NaN)
    const double correction = d2 / (std::min(rho, 16.0) - 1.0);
    return {q2 + correction, std::abs(correction)};
}

/// Richardson's extrapolation of a second-order sequence (the z direction):
/// the value Q2 + (Q2 - Q1)/3 and, as its error, half the last difference,
/// 1.5 times that correction. The order is the chain's, not the sequence's:
/// a ratio of differences far above 4 was luck (E[t1] of the Fig. 2 law at
/// tau' = 0.05: 18, then the next levels moved it 4 times Aitken's error);
/// below 2, no convergence is seen and both differences are charged.
Extrapolated second_order(double q0, double q1, double q2) {
    const double d1 = q1 - q0, d2 = q2 - q1;
    if (d2 == 0.0) return {q2, std::abs(d1) / 8.0};
    if (!(d1 / d2 >= 2.0)) return {q2, std::abs(d1) + std::abs(d2)};
    return {q2 + d2 / 3.0, 0.5 * std::abs(d2)};
}

/// Where a solve stands: the z levels kz - 2 .. kz at the v level av, the v
/// levels kv - 2 .. kv at the z level az, and the mixed term's grid
/// (az + 1, av + 1).
struct Levels {
    int az = 0, av = 0, kz = 2, kv = 2;
};

std::vector<GridKey> grids_needed(const Levels& l) {
    std::vector<GridKey> keys;
    for (int z = l.kz - 2; z <= l.kz; ++z) keys.push_back({z, l.av});
    for (int v = l.kv - 2; v <= l.kv; ++v) keys.push_back({l.az, v});
    keys.push_back({l.az, l.av});
    keys.push_back({l.az + 1, l.av});
    keys.push_back({l.az, l.av + 1});
    keys.push_back({l.az + 1, l.av + 1});
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
}

/// The parts of one quantity's estimate.
struct Parts {
    Estimate estimate;
    double z_error = 0, v_error = 0, mixed_error = 0;
};

/// White noise's standard deviation of V (nondimensional), by the midpoint
/// rule on 4096 cells of [lower, upper] with the project's portable exp: it
/// sets the cells' widths, so it must be the same bits on every machine
/// (glibc's exp is chosen at run time among variants that differ in the last
/// bit); its accuracy does not matter.
double white_spread(const DriftLaw& b, double lower, double upper) {
    constexpr int cells = 4096;
    const double h = (upper - lower) / cells;
    std::vector<double> phi(cells);
    const DriftPotential potential(b);
    double top = -HUGE_VAL;
    for (int i = 0; i < cells; ++i) {
        const double v = lower + (i + 0.5) * h;
        phi[static_cast<std::size_t>(i)] = 2.0 * (potential(v) - std::abs(v));
        top = std::max(top, phi[static_cast<std::size_t>(i)]);
    }
    double m0 = 0, m1 = 0, m2 = 0;
    for (int i = 0; i < cells; ++i) {
        const double v = lower + (i + 0.5) * h, w = portable_exp(std::max(phi[static_cast<std::size_t>(i)] - top, -700.0));
        m0 += w;
        m1 += w * v;
        m2 += w * v * v;
    }
    return std::sqrt(std::max(m2 / m0 - (m1 / m0) * (m1 / m0), 0.0));
}

} // namespace

Problem make_problem(const ModelParams& p, const DriftLaw& law) {
    const Scales sc = scales_of(p);
    Problem pr;
    pr.tau = p.tau / sc.time;
    pr.drift = scaled_drift_law(law, sc.velocity, sc.acceleration);
    const double eps = std::sqrt(pr.tau), b0 = pr.drift(0.0);
    // The band is the static one (static friction over friction; 1 unless set).
    const double band = p.static_friction_level() / p.friction;
    pr.z_lower = std::sqrt(2.0) * eps * (-band - b0);
    pr.z_upper = std::sqrt(2.0) * eps * (band - b0);

    // The velocity range: where white noise's density has fallen e^-40 (the
    // near-white limit), or the slip that the largest force on the noise grid
    // sustains for twice tau' (long correlation times), which drag stops at
    // its terminal velocity. The cells' largest width follows the white
    // noise's spread of V (0.4 at friction = noise = 1 without drag).
    const DriftLawWhiteNoise white(pr.drift, 1.0, 1.0);
    pr.v_lower = white.lower_end(kRangeDrop);
    pr.v_upper = white.upper_end(kRangeDrop);
    const double reach = std::max({pr.noise.reach, pr.z_upper + 1.0, -pr.z_lower + 1.0});
    const double force = reach / (std::sqrt(2.0) * eps);
    const double push_up = force + b0 - 1.0, push_down = force - b0 - 1.0;
    if (push_up > 0)
        pr.v_upper = std::max(pr.v_upper, stopping_velocity(pr.drift, force, +1.0, 2.0 * push_up * pr.tau));
    if (push_down > 0)
        pr.v_lower = std::min(pr.v_lower, -stopping_velocity(pr.drift, -force, -1.0, 2.0 * push_down * pr.tau));
    pr.velocity.max_cell = 0.8 * white_spread(pr.drift, pr.v_lower, pr.v_upper) / std::sqrt(0.5);
    pr.velocity.first_cell = 1e-4 * std::min(eps, eps * eps * eps);
    return pr;
}

Layout make_level_layout(const Problem& pr, int lz, int lv) {
    return make_layout(make_noise_grid(pr.tau, pr.z_lower, pr.z_upper, pr.noise, lz),
                       make_velocity_faces(pr.v_upper, pr.velocity, lv), make_velocity_faces(-pr.v_lower, pr.velocity, lv));
}

namespace {

/// Below tau' = kolmogorov_white_limit_below: the white-noise quadrature for D
/// and M0, with the distance the grids measure at that tau' (plus their own
/// error) as the bound, scaled by sqrt(tau'/tau'_limit): the slowest approach
/// known for coloured noise (Doering, Hagan and Levermore's tau^(1/2) at
/// absorbing boundaries); the solver's own fits give tau'^1 here (theory.md).
/// P(V = 0) falls faster (measured like tau'^2.5): 0, bounded by its value at
/// the limit. E[t1] grows like tau'^(-1/2) (measured from 1e-4 to 1e-7): that
/// law from the limit, with an error as large as the value.
KolmogorovResult white_limit(const ModelParams& p, const KolmogorovSettings& settings, const DriftLaw& law) {
    const auto start = std::chrono::steady_clock::now();
    const Scales sc = scales_of(p);
    const double tau_prime = p.tau / sc.time;
    ModelParams at_limit = p;
    at_limit.tau = kolmogorov_white_limit_below * sc.time;
    KolmogorovResult r = solve(at_limit, settings, law);
    // The affine law's closed forms where they exist (the same numbers as
    // `analytic`); a law's quadrature with the law made already.
    const WhiteNoiseReference white = p.has_drift_law() ? DriftLawWhiteNoise(law, p.friction, p.noise).reference()
                                                        : white_noise_reference(p);
    const double shrink = std::sqrt(tau_prime / kolmogorov_white_limit_below);
    auto bounded = [&](const Estimate& e, double limit) {
        return solved_estimate(limit, (std::abs(e.value - limit) + e.error) * shrink);
    };
    r.params = p;
    // The spectrum has no white-noise quadrature here: its values at the
    // limit tau', their error widened by D's relative distance there from its
    // white-noise value (the colour's share, which shrinks with tau').
    const double colour = std::abs(r.diffusivity.value - white.diffusivity) / std::abs(white.diffusivity);
    for (Estimate& e : r.spectrum) e = solved_estimate(e.value, e.error + colour * std::abs(e.value));
    r.diffusivity = bounded(r.diffusivity, white.diffusivity);
    r.diffusivity_x = bounded(r.diffusivity_x, white.diffusivity);
    r.mobility = bounded(r.mobility, white.mobility);
    r.velocity_variance = bounded(r.velocity_variance, white.variance);
    r.stuck_probability = solved_estimate(0.0, r.stuck_probability.value + r.stuck_probability.error);
    const double duration = r.mean_duration.value / shrink;
    r.mean_duration = solved_estimate(duration, duration);
    const double relative = r.diffusivity.error / std::abs(r.diffusivity.value);
    r.converged = relative <= settings.rel_precision;
    r.note = "tau' = " + format_number(tau_prime) + " is below " + format_number(kolmogorov_white_limit_below) +
             ": D and M0 are the white-noise values, their error the distance the grids measured at tau' = " +
             format_number(kolmogorov_white_limit_below) + " times sqrt(tau'/" +
             format_number(kolmogorov_white_limit_below) + "); P(V = 0) is bounded by its value there and E[t1] "
             "follows its measured law tau'^-1/2 from there (error: the value itself)" +
             (r.spectrum.empty() ? std::string()
                                 : "; the spectrum is the one at tau' = " + format_number(kolmogorov_white_limit_below) +
                                       ", its error widened by D's relative distance there from the white-noise value") +
             (r.note.empty() ? std::string() : "; at the limit: " + r.note);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.grid().discretisation_error = relative;
    return r;
}

} // namespace

KolmogorovResult solve(const ModelParams& p, const KolmogorovSettings& settings, const DriftLaw& law) {
    const auto start = std::chrono::steady_clock::now();
    if (p.tau / scales_of(p).time < kolmogorov_white_limit_below) return white_limit(p, settings, law);
    Problem pr = make_problem(p, law);
    const Scales sc = scales_of(p);

    // Memory: the budget, or what this process may still take if less; the
    // first round, which every result needs, must fit (else one line, before
    // any work: under `ulimit -v` the LU died inside Eigen).
    const double usable = usable_memory_bytes();
    const double memory_budget = std::min(settings.memory_budget, usable);
    {
        std::vector<double> first;
        for (GridKey key : grids_needed(Levels{})) first.push_back(states_of(pr, key));
        std::sort(first.rbegin(), first.rend());
        const double bytes = kBytesPerStateFirstRound * (first[0] + first[1]);
        if (bytes > usable)
            throw std::runtime_error("out of memory: the Kolmogorov engine's first grids need about " +
                                     format_number(bytes / 1e9, 2) + " GB, more than the " +
                                     format_number(usable / 1e9, 2) + " GB this process may still take");
    }

    // The velocity range, checked on the coarsest grid: widened while the
    // mass in its outer cells or D's share from its outer tenth is not
    // negligible (a weakly confined law's slips reach far beyond white
    // noise's range when tau' is large); what is left is added to every
    // estimated error below (the truncation's part).
    std::map<GridKey, GridSolution> solved;
    double truncation = 0;
    for (int widen = 0;; ++widen) {
        GridSolution coarse = solve_level(pr, {0, 0});
        const bool holds = coarse.tail_mass < 1e-12 && coarse.tail_diffusivity < 1e-7;
        if (holds || widen == 6) {
            if (!holds) truncation = std::max(coarse.tail_mass, coarse.tail_diffusivity);
            solved.emplace(GridKey{0, 0}, std::move(coarse));
            break;
        }
        pr.v_lower *= 1.5;
        pr.v_upper *= 1.5;
    }

    double modelled = 0;
    // Solves the grids of a round not solved yet, largest first, two at a
    // time; a stop (when `stoppable`: every round after the first, which any
    // result needs) starts no further grid. Whether the round is complete.
    auto solve_missing = [&](const std::vector<GridKey>& keys, bool stoppable) {
        std::vector<GridKey> todo;
        for (GridKey key : keys)
            if (!solved.count(key)) todo.push_back(key);
        std::sort(todo.begin(), todo.end(),
                  [&](GridKey a, GridKey b) { return states_of(pr, a) > states_of(pr, b); });
        std::vector<GridSolution> out(todo.size());
        // A stop starts no further grid; a grid not started keeps states == 0.
        run_grid_tasks(todo.size(), settings.threads, stoppable ? settings.stop : nullptr,
                       [&](std::size_t i) { out[i] = solve_level(pr, todo[i]); });
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

    KolmogorovResult result;
    result.params = p;
    Levels at, finished; // the round being solved, the last one whose estimates are in result
    Parts d_parts;
    auto interrupted = [&] {
        result.interrupted = true;
        result.note = "interrupted: the estimates are those of the rounds of grids finished before the stop "
                      "(estimated relative error of D " +
                      format_number(result.diffusivity.error / std::abs(result.diffusivity.value), 3) + ", target " +
                      format_number(settings.rel_precision, 3) + ")";
    };
    // The extrapolated estimate of one quantity from its values q(z, v) on
    // the grids of the round `at`, with the parts of its error.
    auto combined = [&](auto q) {
        const Extrapolated in_z = second_order(q(at.kz - 2, at.av), q(at.kz - 1, at.av), q(at.kz, at.av));
        const Extrapolated in_v = aitken(q(at.az, at.kv - 2), q(at.az, at.kv - 1), q(at.az, at.kv));
        const double mixed = q(at.az, at.av) - q(at.az + 1, at.av) - q(at.az, at.av + 1) + q(at.az + 1, at.av + 1);
        Parts out;
        out.z_error = in_z.error;
        out.v_error = in_v.error;
        out.mixed_error = 3.0 * std::abs(mixed);
        out.estimate = solved_estimate(in_z.value + in_v.value - q(at.az, at.av), out.z_error + out.v_error + out.mixed_error);
        return out;
    };
    // An estimate in SI units (unit: the quantity's), with the velocity
    // range's truncation added to its error.
    auto scaled = [truncation](Parts x, double unit) {
        return solved_estimate(x.estimate.value * unit,
                               (x.estimate.error + truncation * std::abs(x.estimate.value)) * unit);
    };
    for (bool first = true;; first = false) {
        if (!solve_missing(grids_needed(at), !first)) {
            at = finished;
            interrupted();
            break;
        }
        finished = at;
        auto parts = [&](auto field) {
            return combined([&](int z, int v) { return field(solved.at({z, v})); });
        };
        d_parts = parts([](const GridSolution& s) { return s.diffusivity; });
        result.diffusivity = scaled(d_parts, sc.diffusivity);
        result.diffusivity_x = scaled(parts([](const GridSolution& s) { return s.diffusivity_noise; }), sc.diffusivity);
        result.mobility = scaled(parts([](const GridSolution& s) { return s.mobility; }), sc.velocity);
        result.velocity_variance =
            scaled(parts([](const GridSolution& s) { return s.velocity_variance; }), sc.velocity * sc.velocity);
        result.stuck_probability = scaled(parts([](const GridSolution& s) { return s.stuck_probability; }), 1.0);
        result.mean_duration = scaled(parts([](const GridSolution& s) { return s.mean_duration; }), sc.time);

        const double relative = result.diffusivity.error / std::abs(result.diffusivity.value);
        result.converged = relative <= settings.rel_precision;
        if (result.converged) break;
        if (settings.stop && settings.stop->load()) {
            interrupted();
            break;
        }
        // Refine the direction that holds the most of D's error and any
        // other above a third of the target; the mixed term by moving the
        // corner one level finer in z or in v, whichever new grids cost less
        // (the term shrinks in both). When that round would exceed a budget,
        // the largest part alone (a tight target puts every part above its
        // share, and refining all at once stopped solves early).
        const double share = settings.rel_precision * std::abs(d_parts.estimate.value) / 3.0;
        const double top = std::max({d_parts.z_error, d_parts.v_error, d_parts.mixed_error});
        auto refined = [&](bool all) {
            Levels next = at;
            auto take = [&](double part) { return part == top || (all && part > share); };
            if (take(d_parts.z_error)) ++next.kz;
            if (take(d_parts.v_error)) ++next.kv;
            if (take(d_parts.mixed_error)) {
                Levels in_z = next, in_v = next;
                ++in_z.az;
                in_z.kz = std::max(in_z.kz, in_z.az + 2);
                ++in_v.av;
                in_v.kv = std::max(in_v.kv, in_v.av + 2);
                auto cost = [&](const Levels& l) {
                    double sum = 0;
                    for (GridKey key : grids_needed(l))
                        if (!solved.count(key)) sum += modelled_seconds(states_of(pr, key));
                    return sum;
                };
                next = cost(in_z) <= cost(in_v) ? in_z : in_v;
            }
            return next;
        };
        double n_ref = 0, z_ref = 0;
        for (const auto& [key, s] : solved)
            if (static_cast<double>(s.states) > n_ref) n_ref = static_cast<double>(s.states), z_ref = static_cast<double>(s.lu_nonzeros);
        // Which budget a round of `next` would exceed: "" when none.
        auto exceeds = [&](const Levels& next) -> std::string {
            std::vector<double> sizes;
            double largest = 0, second = 0;
            for (GridKey key : grids_needed(next)) {
                if (solved.count(key)) continue;
                const double n = states_of(pr, key);
                sizes.push_back(n);
                const double z = predicted_nonzeros(n, n_ref, z_ref);
                if (z > largest) second = largest, largest = z;
                else second = std::max(second, z);
            }
            if (kolmogorov_bytes_per_lu_nonzero * (largest + second) > memory_budget) return "memory";
            if (modelled + modelled_round(sizes) > settings.time_budget) return "time";
            return "";
        };
        Levels next = refined(true);
        std::string over = exceeds(next);
        if (!over.empty()) {
            next = refined(false);
            over = exceeds(next);
        }
        if (!over.empty()) {
            result.note = "the estimated error of D, " + format_number(relative, 3) + " relative, is above rel_precision " +
                          format_number(settings.rel_precision, 3) + ": the next refinement would exceed the " + over +
                          " budget";
            break;
        }
        at = next;
    }

    // The spectrum, on the grids of the last round and extrapolated like D
    // (kolmogorov.cpp says why after the rounds).
    if (!settings.frequencies.empty()) {
        std::vector<double> scaled_w;
        for (double w : settings.frequencies) scaled_w.push_back(w * sc.time);
        const auto spectra = spectra_on_grids(grids_needed(at), settings.threads, settings.stop, [&](GridKey key) {
            return solve_grid(make_level_layout(pr, key.first, key.second), pr.drift, pr.tau, nullptr, &scaled_w)
                .spectrum;
        });
        if (!spectra) {
            interrupted();
            result.note += "; stopped before the spectrum was solved";
        } else {
            for (std::size_t f = 0; f < scaled_w.size(); ++f)
                result.spectrum.push_back(
                    scaled(combined([&](int z, int v) { return spectra->at({z, v})[f]; }), sc.diffusivity));
        }
    }
    if (truncation > 0) {
        const std::string cut = "the velocity range [" + format_number(pr.v_lower * sc.velocity, 4) + ", " +
                                format_number(pr.v_upper * sc.velocity, 4) + "] m/s still holds " +
                                format_number(truncation, 2) +
                                " of the mass or of D at its edges after widening: added to every error";
        result.note = result.note.empty() ? cut : cut + "; " + result.note;
    }
    // The grids solved, the v sequence's finest last (its density is reported).
    const GridKey finest_v{at.az, at.kv};
    auto published = [&](GridKey key, const GridSolution& s) {
        KolmogorovGridSolution out;
        const NoiseGrid noise = make_noise_grid(pr.tau, pr.z_lower, pr.z_upper, pr.noise, key.first);
        KolmogorovGrid& g = out.grid;
        const double to_x = sc.noise_level / std::sqrt(pr.tau); // x = z / sqrt(tau) in SI
        g.lower_threshold = pr.z_lower * to_x;
        g.upper_threshold = pr.z_upper * to_x;
        g.band_intervals = noise.band_upper - noise.band_lower;
        g.band_first = noise.band_lower;
        g.x_nodes = noise.size();
        g.x_spacing = (noise.z[noise.band_lower + 1] - noise.z[noise.band_lower]) * to_x;
        g.graded_x_lower = noise.z.front() * to_x;
        g.graded_x_upper = noise.z.back() * to_x;
        g.v_lower = pr.v_lower * sc.velocity;
        g.v_upper = pr.v_upper * sc.velocity;
        g.v_cells_neg = static_cast<std::size_t>(std::count_if(s.velocity_faces.begin(), s.velocity_faces.end(),
                                                               [](double v) { return v < 0; }));
        g.v_cells_pos = s.velocity_faces.size() - 1 - g.v_cells_neg;
        out.states = s.states;
        out.lu_nonzeros = s.lu_nonzeros;
        out.diffusivity = s.diffusivity * sc.diffusivity;
        out.diffusivity_x = s.diffusivity_noise * sc.diffusivity;
        out.mobility = s.mobility * sc.velocity;
        out.velocity_variance = s.velocity_variance * sc.velocity * sc.velocity;
        out.stuck_probability = s.stuck_probability;
        out.mean_duration = s.mean_duration * sc.time;
        out.tail_mass = s.tail_mass;
        out.seconds = s.seconds;
        out.velocity_faces.reserve(s.velocity_faces.size());
        for (double v : s.velocity_faces) out.velocity_faces.push_back(v * sc.velocity);
        for (double d : s.velocity_density) out.velocity_density.push_back(d / sc.velocity);
        return out;
    };
    for (const auto& [key, s] : solved)
        if (key != finest_v) result.levels.push_back(published(key, s));
    result.levels.push_back(published(finest_v, solved.at(finest_v)));
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    GridDetails details;
    details.solver = "kolmogorov (near-white: noise chain in z, DG in v)";
    details.cells = grid_span(result).largest_states;
    details.lower = pr.v_lower * sc.velocity;
    details.upper = pr.v_upper * sc.velocity;
    details.discretisation_error = result.diffusivity.error / std::abs(result.diffusivity.value);
    result.details = details;
    return result;
}

} // namespace stickslip::detail::near_white
