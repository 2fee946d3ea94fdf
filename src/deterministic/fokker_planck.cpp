// SPDX-License-Identifier: BSD-3-Clause
// Fokker-Planck solver for the white-noise velocity (fokker_planck.hpp).
//
// Everything below works in the nondimensional system (friction = noise = 1,
// so the diffusion coefficient is 1/2); the public functions convert.
//
// The scheme is a master equation on the cells: mu_i is the probability of
// cell i, and probability hops i -> i+1 at rate up_i, i -> i-1 at rate down_i.
// With phi the stationary potential, phi_i = phi(v_i) at the centre v_i, and
//   J_i  = int_{cell i} exp(-(phi(v) - phi_i)) dv               (~ h)
//   I_i  = int_{v_i}^{v_{i+1}} exp(phi(v) - phi_i) dv           (~ h)
//   I'_i = int_{v_i}^{v_{i+1}} exp(phi(v) - phi_{i+1}) dv       (~ h)
// the exponentially fitted conductance (D/Z) e^{-phi_i}/I_i divided by the cell
// masses m_i = e^{-phi_i} J_i / Z gives up_i = D/(I_i J_i) and
// down_{i+1} = D/(I'_i J_{i+1}). Every factor is referred to a nearby phi_i, so
// nothing overflows or underflows however far into the tails the grid reaches,
// and m_i up_i = m_{i+1} down_{i+1} holds identically (detailed balance with
// the exact cell probabilities). For pure diffusion up = down = D/h^2.
#include "stickslip/fokker_planck.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <complex>
#include <numeric>
#include <type_traits>

#include "core/format.hpp"

namespace stickslip {

namespace detail {

struct FokkerPlanckGrid {
    double first_face = 0, h = 0;
    std::vector<double> centre;    // v_i
    std::vector<double> phi;       // potential at v_i
    std::vector<double> spread;    // J_i
    std::vector<double> mean_v;    // mean velocity of cell i under p_s
    std::vector<double> mass;      // m_i, stationary cell probability
    std::vector<double> up, down;  // hopping rates to i+1 and i-1

    std::size_t size() const { return centre.size(); }
};

} // namespace detail

namespace {

using Grid = detail::FokkerPlanckGrid;
using Rule = boost::math::quadrature::gauss<double, 10>;
constexpr double kDiffusion = 0.5; // Gamma/2 in nondimensional units
constexpr double kRise = 30.0;     // potential rise that bounds the interval (mass beyond ~e^-30)

/// int_a^b f(v) dv for f smooth except at v = 0 and varying like
/// exp(+-phi): panels split at 0, each spanning a change of phi of about 1.
template <class F>
double integrate(const HayakawaDensity& d, double a, double b, F f) {
    auto piece = [&](double left, double right) {
        const double m = std::clamp(d.mode(), left, right);
        const double variation = d.potential(left) + d.potential(right) - 2.0 * d.potential(m);
        const int panels = static_cast<int>(std::min(std::ceil(variation), 1e5)) + 1;
        const double width = (right - left) / panels;
        double s = 0.0;
        for (int j = 0; j < panels; ++j)
            s += Rule::integrate(f, left + j * width, j + 1 == panels ? right : left + (j + 1) * width);
        return s;
    };
    if (a < 0.0 && b > 0.0) return piece(a, 0.0) + piece(0.0, b);
    return piece(a, b);
}

/// The velocity beyond `from` (in direction dir = +-1, away from the mode)
/// where the potential reaches `level`.
double reach(const HayakawaDensity& d, double from, double dir, double level) {
    double step = 1.0, inner = from, outer = from + dir * step;
    while (d.potential(outer) < level) {
        inner = outer;
        step *= 2;
        outer = from + dir * step;
    }
    for (int k = 0; k < 200 && inner != outer; ++k) {
        const double mid = 0.5 * (inner + outer);
        if (mid == inner || mid == outer) break;
        (d.potential(mid) < level ? inner : outer) = mid;
    }
    return outer;
}

std::shared_ptr<const Grid> build_grid(const HayakawaDensity& d, double lo, double hi, double h) {
    auto g = std::make_shared<Grid>();
    // Faces at integer multiples of h: v = 0 is a face whatever lo and hi are.
    const auto first = static_cast<long>(std::floor(lo / h)), last = static_cast<long>(std::ceil(hi / h));
    const auto n = static_cast<std::size_t>(last - first);
    g->first_face = static_cast<double>(first) * h;
    g->h = h;
    auto face = [&](std::size_t i) { return static_cast<double>(first + static_cast<long>(i)) * h; };
    g->centre.resize(n);
    g->phi.resize(n);
    g->spread.resize(n);
    g->mean_v.resize(n);
    g->mass.resize(n);
    g->up.assign(n, 0.0);
    g->down.assign(n, 0.0);
    const double peak = d(d.mode()); // 1/Z
    for (std::size_t i = 0; i < n; ++i) {
        const double a = face(i), b = face(i + 1), c = 0.5 * (a + b), phi_c = d.potential(c);
        const double spread = integrate(d, a, b, [&](double v) { return std::exp(-(d.potential(v) - phi_c)); });
        const double first_moment =
            integrate(d, a, b, [&](double v) { return v * std::exp(-(d.potential(v) - phi_c)); });
        g->centre[i] = c;
        g->phi[i] = phi_c;
        g->spread[i] = spread;
        g->mean_v[i] = first_moment / spread;
        g->mass[i] = spread * std::exp(-phi_c) * peak;
    }
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double a = g->centre[i], b = g->centre[i + 1];
        const double from_left = integrate(d, a, b, [&](double v) { return std::exp(d.potential(v) - g->phi[i]); });
        const double from_right =
            integrate(d, a, b, [&](double v) { return std::exp(d.potential(v) - g->phi[i + 1]); });
        g->up[i] = kDiffusion / (from_left * g->spread[i]);
        g->down[i + 1] = kDiffusion / (from_right * g->spread[i + 1]);
    }
    return g;
}

/// Theta-scheme steps (I - theta dt A) mu' = (I + (1 - theta) dt A) mu for the
/// generator A of the chain, by the Thomas algorithm. A has zero column sums
/// (probability is conserved) and non-negative off-diagonal entries, so
/// I - theta dt A is a column diagonally dominant M-matrix: no pivoting is
/// needed, and backward Euler keeps probabilities non-negative.
///
/// Speed: the two sweeps of the Thomas algorithm are recurrences whose
/// latency, not arithmetic, is the cost. They are stored pre-divided (one
/// multiply-add per cell) and advanced two cells at a time,
///   y_{i+1} = (r_{i+1} - l_{i+1} r_i) + (l_{i+1} l_i) y_{i-1},
/// with the bracket computed beforehand in a vectorisable pass, which halves
/// the dependency chain. Factorising (a division in the recurrence) costs
/// several solves, so the two most recently used factorisations are kept,
/// keyed by theta*dt: the nominal step, and the odd one that lands on a
/// requested time.
class Stepper {
public:
    explicit Stepper(const Grid& g)
        : n_(g.size()), below_(n_, 0.0), above_(n_, 0.0), out_(n_), work_(n_), pair_(n_) {
        for (std::size_t i = 0; i < n_; ++i) {
            if (i > 0) below_[i] = g.up[i - 1];        // inflow from cell i-1
            if (i + 1 < n_) above_[i] = g.down[i + 1]; // inflow from cell i+1
            out_[i] = g.up[i] + g.down[i];
        }
    }

    void step(std::vector<double>& mu, double dt, double theta) {
        const double implicit = theta * dt, explicit_part = (1.0 - theta) * dt;
        const Factor& f = factor(implicit);
        const std::size_t n = n_;
        double* y = work_.data();
        double* pair = pair_.data();
        const double* m = mu.data();
        const double* inv = f.inv_den.data();
        const double* lower = f.lower.data();
        const double* upper = f.upper.data();
        // Right-hand side, pre-divided by the pivots.
        y[0] = (m[0] + explicit_part * (above_[0] * m[1] - out_[0] * m[0])) * inv[0];
        for (std::size_t i = 1; i + 1 < n; ++i)
            y[i] = (m[i] + explicit_part * (below_[i] * m[i - 1] + above_[i] * m[i + 1] - out_[i] * m[i])) * inv[i];
        y[n - 1] = (m[n - 1] + explicit_part * (below_[n - 1] * m[n - 2] - out_[n - 1] * m[n - 1])) * inv[n - 1];
        // Forward sweep y_i -= l_i y_{i-1}, two cells per link of the chain.
        for (std::size_t i = 2; i < n; ++i) pair[i] = y[i] - lower[i] * y[i - 1];
        std::size_t i = 1;
        for (; i + 1 < n; i += 2) {
            const double previous = y[i - 1];
            y[i] -= lower[i] * previous;
            y[i + 1] = pair[i + 1] + f.lower2[i + 1] * previous;
        }
        if (i < n) y[i] -= lower[i] * y[i - 1];
        // Backward sweep x_i = y_i - u_i x_{i+1}, likewise.
        for (std::size_t k = 0; k + 1 < n; ++k) pair[k] = y[k] - upper[k] * y[k + 1];
        std::size_t k = n - 1;
        for (; k >= 2; k -= 2) {
            const double next = y[k];
            y[k - 1] -= upper[k - 1] * next;
            y[k - 2] = pair[k - 2] + f.upper2[k - 2] * next;
        }
        if (k == 1) y[0] -= upper[0] * y[1];
        mu.swap(work_);
    }

private:
    struct Factor {
        double key = -1.0;
        std::vector<double> lower, upper, inv_den;
        std::vector<double> lower2, upper2; // l_i l_{i-1} and u_i u_{i+1}
    };

    const Factor& factor(double implicit) {
        if (cache_[0].key == implicit) return cache_[0];
        std::swap(cache_[0], cache_[1]); // most recently used first
        Factor& f = cache_[0];
        if (f.key == implicit) return f;
        f.lower.resize(n_);
        f.upper.resize(n_);
        f.inv_den.resize(n_);
        f.lower2.assign(n_, 0.0);
        f.upper2.assign(n_, 0.0);
        // Row i: -implicit*below_i x_{i-1} + (1 + implicit*out_i) x_i - implicit*above_i x_{i+1}.
        double upper_prev = 0.0;
        for (std::size_t i = 0; i < n_; ++i) {
            const double sub = -implicit * below_[i];
            f.inv_den[i] = 1.0 / (1.0 + implicit * out_[i] - sub * upper_prev);
            f.lower[i] = sub * f.inv_den[i];
            f.upper[i] = -implicit * above_[i] * f.inv_den[i];
            upper_prev = f.upper[i];
        }
        for (std::size_t i = 1; i < n_; ++i) f.lower2[i] = f.lower[i] * f.lower[i - 1];
        for (std::size_t i = 0; i + 1 < n_; ++i) f.upper2[i] = f.upper[i] * f.upper[i + 1];
        f.key = implicit;
        return f;
    }

    std::size_t n_;
    std::vector<double> below_, above_, out_; // generator
    std::vector<double> work_, pair_;
    std::array<Factor, 2> cache_;
};

/// Time steps, nondimensional, as multiples g(t) of the nominal step dt0:
/// * graded start, g = t/(kEarly dt0) >= kFloor: a delta initial condition,
///   or mass reaching the kink at v = 0 a time ~v0^2 after the start, varies
///   on the time scale t itself; constant steps would leave a Crank-Nicolson
///   error ~dt0^2/v0^2 (1e-5 for v0 = 0.1 with dt0 = 1e-3);
/// * g = 1 up to the relaxation time `unit`;
/// * g = sqrt(t/unit) while the drift carries a bump of width ~sqrt(t) from a
///   far v0 into the bulk (until t_grow): its time scale is its width;
/// * g proportional to t after t_grow: the solution relaxes exponentially and
///   the relative time resolution is what matters.
/// g is rounded down to a power of 2^(1/4) so that few distinct steps need
/// factorising.
struct Schedule {
    double dt0 = 0.0;
    double unit = 0.0;   // relaxation time of the stationary state
    double t_grow = 0.0; // unit + time to drift from v0 into the bulk
    static constexpr double kEarly = 50.0, kFloor = 0.01;

    double nominal(double t) const {
        double g = 1.0;
        if (t < kEarly * dt0) g = std::max(t / (kEarly * dt0), kFloor);
        else if (t > t_grow) g = std::sqrt(t_grow / unit) * t / t_grow;
        else if (t > unit) g = std::sqrt(t / unit);
        return dt0 * std::exp2(std::floor(4.0 * std::log2(g)) / 4.0);
    }
};

/// Evolves mu from t = 0 through the (nondimensional) times, in increasing
/// order, and calls observe(k, mu) at times[k]. Four backward-Euler steps at
/// the very start (Rannacher start-up: they damp the stiff modes that a
/// delta excites and Crank-Nicolson would only flip in sign), then
/// Crank-Nicolson with the schedule's steps, shortened to land on every
/// requested time.
template <class Observe>
void evolve(const Grid& g, std::vector<double> mu, const std::vector<double>& times, const Schedule& schedule,
            Observe observe) {
    std::vector<std::size_t> order(times.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return times[a] < times[b]; });
    Stepper stepper(g);
    const double start_up = 2.0 * Schedule::kFloor * schedule.dt0;
    double t = 0.0;
    for (const std::size_t k : order) {
        const double target = times[k];
        while (t < target) {
            const double remaining = target - t;
            const bool implicit = t < start_up;
            const double nominal = implicit ? 0.25 * start_up : schedule.nominal(t);
            const bool last = remaining <= nominal * (1.0 + 1e-9);
            stepper.step(mu, last ? remaining : nominal, implicit ? 1.0 : 0.5);
            t = last ? target : t + nominal;
        }
        observe(k, mu);
    }
}

/// Time for the drift alone to bring the velocity from v0 to the bulk of
/// the stationary density (potential <= 2), int dv/|a(v)| with
/// a = -(noise/2) phi'(v) = -phi'/2 the drift in nondimensional units. Until
/// then the solution is a moving bump, not a relaxing one, so the step must
/// not grow yet (pure dry friction from v0 = 50: t ~ 50).
double travel_time(const HayakawaDensity& d, double v0) {
    const double bulk = 2.0;
    if (d.potential(v0) <= bulk) return 0.0;
    const double dir = v0 > d.mode() ? 1.0 : -1.0;
    const double edge = reach(d, d.mode(), dir, bulk);
    const int n = 256;
    const double step = (v0 - edge) / n;
    double time = 0.0;
    for (int k = 0; k < n; ++k) {
        const double v = edge + (k + 0.5) * step, dv = 1e-6 * (1.0 + std::fabs(v));
        const double slope = (d.potential(v + dv) - d.potential(v - dv)) / (2.0 * dv);
        time += std::fabs(step) * 2.0 / std::fabs(slope);
    }
    return time;
}

/// The delta at v0 as (signed) cell weights: the quadratic Lagrange weights of
/// three neighbouring cells, so that sum w_i u(v_i) = u(v0) + O(h^3) for any
/// smooth u; in particular the discrete mean starts exactly at v0. (One cell
/// would shift every first moment by up to h/2, two cells leave an O(h^2)
/// error that depends on where v0 falls in its cell, which would spoil the
/// Richardson extrapolation.) u = E[V(t)|.] has a jump of its second
/// derivative at 0, where the drift jumps, so the three cells are taken on
/// the side of v0; v0 = 0 averages both sides.
std::vector<double> delta_at(const Grid& g, double v0) {
    const std::size_t n = g.size();
    std::vector<double> w(n, 0.0);
    auto one_side = [&](bool positive, double share) {
        // First cell of the side of v0 (the face at 0 separates the sides).
        const auto zero = static_cast<std::size_t>(
            std::clamp(std::round(-g.first_face / g.h), 0.0, static_cast<double>(n)));
        const std::size_t nearest = static_cast<std::size_t>(
            std::clamp(std::floor((v0 - g.first_face) / g.h), 0.0, static_cast<double>(n - 1)));
        std::size_t first = nearest == 0 ? 0 : nearest - 1;
        if (positive) first = std::max(first, zero);
        else if (zero >= 3) first = std::min(first, zero - 3);
        first = std::min(first, n - 3);
        const double* x = &g.mean_v[first];
        for (std::size_t k = 0; k < 3; ++k) {
            double l = 1.0;
            for (std::size_t j = 0; j < 3; ++j)
                if (j != k) l *= (v0 - x[j]) / (x[k] - x[j]);
            w[first + k] += share * l;
        }
    };
    if (v0 == 0.0) {
        one_side(true, 0.5);
        one_side(false, 0.5);
    } else {
        one_side(v0 > 0.0, 1.0);
    }
    return w;
}

double expectation(const Grid& g, const std::vector<double>& mu) {
    double s = 0.0;
    for (std::size_t i = 0; i < g.size(); ++i) s += g.mean_v[i] * mu[i];
    return s;
}

/// Density [nondimensional] at v from cell probabilities mu: the ratio
/// f = p/p_s (mu_i/m_i at the centres) interpolated quadratically through the
/// three nearest centres on the side of v (f is smooth on each side of 0 but
/// its second derivative jumps there), times the stationary density, every
/// factor referred to the local phi_i so that nothing overflows in the tails.
/// Linear interpolation would leave an error h^2 f''/8, 1e-4 of the peak for
/// a bump of width 0.2 on cells of 0.0075.
double reconstruct(const HayakawaDensity& d, const Grid& g, const std::vector<double>& mu, double v) {
    const std::size_t n = g.size();
    const double x = (v - g.first_face) / g.h;
    if (!(x >= 0.0) || x > static_cast<double>(n)) return 0.0;
    const auto zero = static_cast<std::size_t>(std::clamp(std::round(-g.first_face / g.h), 0.0, static_cast<double>(n)));
    const auto cell = std::min(static_cast<std::size_t>(x), n - 1);
    // Stencil: cell-1, cell, cell+1, moved inside the side of v and the grid.
    std::size_t first = cell == 0 ? 0 : cell - 1;
    if (v >= 0.0) first = std::max(first, zero);
    else if (zero >= 3) first = std::min(first, zero - 3);
    first = std::min(first, n - 3);
    const double phi = d.potential(v);
    double p = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t i = first + k;
        double l = 1.0;
        for (std::size_t j = first; j < first + 3; ++j)
            if (j != i) l *= (v - g.centre[j]) / (g.centre[i] - g.centre[j]);
        p += l * mu[i] * std::exp(-(phi - g.phi[i])) / g.spread[i];
    }
    return p;
}

void check_times(const std::vector<double>& times, bool allow_zero) {
    for (const double t : times) {
        if (!std::isfinite(t) || t < 0.0 || (!allow_zero && t == 0.0))
            throw InvalidParameter("time", std::string("times must be finite and ") + (allow_zero ? ">= 0" : "> 0") +
                                               " (s), got " + detail::format_number(t));
    }
}

void check_v0(double v0) {
    if (!std::isfinite(v0))
        throw InvalidParameter("v0", "v0 must be a finite number (m/s), got " + detail::format_number(v0));
}

ModelParams checked(const ModelParams& p, const FokkerPlanckSettings& s) {
    validate(p);
    if (!has_stationary_state(p))
        throw InvalidParameter("bias", "no stationary state: with relaxation inf, |bias| must be < friction");
    if (s.cells < 16)
        throw InvalidParameter("cells", "cells must be >= 16, got " + std::to_string(s.cells));
    if (!std::isfinite(s.half_width) || s.half_width < 0.0)
        throw InvalidParameter("half_width", "half_width must be a finite number >= 0 (m/s; 0 = automatic), got " +
                                                 detail::format_number(s.half_width));
    if (s.steps_per_unit_time < 1)
        throw InvalidParameter("steps_per_unit_time",
                               "steps_per_unit_time must be >= 1, got " + std::to_string(s.steps_per_unit_time));
    return to_nondimensional(p);
}

} // namespace

WhiteNoiseFokkerPlanck::WhiteNoiseFokkerPlanck(const ModelParams& p, const FokkerPlanckSettings& settings)
    : params_(p), settings_(settings), scales_(scales_of(p)), density_(checked(p, settings)) {
    const ModelParams nd = to_nondimensional(p);
    if (settings.half_width > 0.0) {
        const double w = settings.half_width / scales_.velocity;
        lo_ = density_.mean() - w;
        hi_ = density_.mean() + w;
    } else {
        lo_ = reach(density_, density_.mode(), -1.0, kRise);
        hi_ = reach(density_, density_.mode(), +1.0, kRise);
    }
    h_ = (hi_ - lo_) / settings.cells;
    unit_ = std::min(1.0, nd.relaxation); // nd.relaxation may be inf
    dt0_ = unit_ / settings.steps_per_unit_time;
    base_ = build_grid(density_, lo_, hi_, h_);
    if (settings.richardson) coarse_ = build_grid(density_, lo_, hi_, 2.0 * h_);
}

std::shared_ptr<const detail::FokkerPlanckGrid> WhiteNoiseFokkerPlanck::grid_for(double v0, bool coarse) const {
    // The chain started at v0 must not feel the zero-flux ends: reach where
    // the potential has risen by kRise beyond v0 (away from the mode), the
    // level the velocity exceeds with probability ~e^-kRise.
    double lo = lo_, hi = hi_;
    const double level = density_.potential(v0) + kRise;
    if (v0 >= density_.mode())
        hi = std::max(hi, reach(density_, v0, +1.0, level));
    else
        lo = std::min(lo, reach(density_, v0, -1.0, level));
    if (lo == lo_ && hi == hi_) return coarse ? coarse_ : base_;
    if ((hi - lo) / h_ > 100.0 * settings_.cells)
        throw InvalidParameter("v0", "v0 = " + detail::format_number(v0 * scales_.velocity) +
                                         " m/s is too far in the tail of the stationary density for the grid");
    return build_grid(density_, lo, hi, coarse ? 2.0 * h_ : h_);
}

template <class Solve>
auto WhiteNoiseFokkerPlanck::extrapolated(Solve solve) const {
    auto fine = solve(false);
    if (!settings_.richardson) return fine;
    const auto coarse = solve(true);
    // (4 E_h - E_2h)/3 removes the h^2 term of the spatial error.
    for (std::size_t k = 0; k < fine.size(); ++k) {
        if constexpr (std::is_same_v<decltype(fine), std::vector<double>>) {
            fine[k] = (4.0 * fine[k] - coarse[k]) / 3.0;
        } else {
            for (std::size_t j = 0; j < fine[k].size(); ++j) fine[k][j] = (4.0 * fine[k][j] - coarse[k][j]) / 3.0;
        }
    }
    return fine;
}

std::vector<double> WhiteNoiseFokkerPlanck::first_moment(double v0, const std::vector<double>& times) const {
    check_v0(v0);
    check_times(times, true);
    const double start = v0 / scales_.velocity;
    const Schedule schedule{dt0_, unit_, unit_ + travel_time(density_, start)};
    std::vector<double> nd_times(times.size());
    for (std::size_t k = 0; k < times.size(); ++k) nd_times[k] = times[k] / scales_.time;
    auto out = extrapolated([&](bool coarse) {
        const auto grid = grid_for(start, coarse);
        const Grid& g = *grid;
        std::vector<double> e(times.size());
        evolve(g, delta_at(g, start), nd_times, schedule,
               [&](std::size_t k, const std::vector<double>& m) { e[k] = expectation(g, m) * scales_.velocity; });
        return e;
    });
    for (std::size_t k = 0; k < times.size(); ++k)
        if (times[k] == 0.0) out[k] = v0; // exact by construction; avoid the rounding of the rescaling
    return out;
}

std::vector<double> WhiteNoiseFokkerPlanck::autocorrelation(const std::vector<double>& times) const {
    check_times(times, true);
    std::vector<double> nd_times(times.size());
    for (std::size_t k = 0; k < times.size(); ++k) nd_times[k] = times[k] / scales_.time;
    const double unit = scales_.velocity * scales_.velocity;
    return extrapolated([&](bool coarse) {
        const Grid& g = coarse ? *coarse_ : *base_;
        std::vector<double> q(g.size());
        for (std::size_t i = 0; i < g.size(); ++i) q[i] = g.mean_v[i] * g.mass[i];
        std::vector<double> c(times.size());
        evolve(g, std::move(q), nd_times, Schedule{dt0_, unit_, unit_},
               [&](std::size_t k, const std::vector<double>& m) { c[k] = expectation(g, m) * unit; });
        return c;
    });
}

namespace {

/// 2 Re sum_i m_i f_i phi_i with (i w - Q) phi = f, f = V_i - M0 on grid g
/// (nondimensional w), by the Thomas algorithm: the rows of i w - Q are
/// diagonally dominant (|i w + up + down| >= up + down), so no pivoting.
double chain_spectrum(const Grid& g, double w) {
    using C = std::complex<double>;
    const std::size_t n = g.size();
    const double total = std::accumulate(g.mass.begin(), g.mass.end(), 0.0);
    const double m0 = expectation(g, g.mass) / total; // the chain's own mean: f is orthogonal to constants
    std::vector<C> upper(n), rhs(n);
    C prev_upper = 0.0, prev_rhs = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const C diag(g.up[i] + g.down[i], w);
        const double lower = i > 0 ? -g.down[i] : 0.0;
        const C pivot = diag - lower * prev_upper;
        upper[i] = -g.up[i] / pivot;
        rhs[i] = ((g.mean_v[i] - m0) - lower * prev_rhs) / pivot;
        prev_upper = upper[i];
        prev_rhs = rhs[i];
    }
    double s = 0.0;
    C phi = 0.0;
    for (std::size_t k = n; k-- > 0;) {
        phi = rhs[k] - upper[k] * phi;
        s += g.mass[k] / total * (g.mean_v[k] - m0) * phi.real();
    }
    return 2.0 * s;
}

} // namespace

std::vector<double> WhiteNoiseFokkerPlanck::spectrum(const std::vector<double>& frequencies,
                                                     std::vector<double>& error) const {
    for (const double w : frequencies)
        if (!std::isfinite(w) || w < 0.0)
            throw InvalidParameter("frequencies", "frequencies must be finite and >= 0 (rad/s), got " +
                                                      detail::format_number(w));
    const double unit = scales_.velocity * scales_.velocity * scales_.time; // m^2/s
    const double d = white_noise_reference(params_).diffusivity;
    std::vector<double> out(frequencies.size());
    error.assign(frequencies.size(), 0.0);
    for (std::size_t k = 0; k < frequencies.size(); ++k) {
        if (frequencies[k] == 0.0) {
            out[k] = d; // Green-Kubo: the cell problem's D, in closed form
            continue;
        }
        const double w = frequencies[k] * scales_.time;
        const double fine = chain_spectrum(*base_, w);
        if (!settings_.richardson) {
            out[k] = fine * unit;
            continue;
        }
        const double coarse = chain_spectrum(*coarse_, w);
        out[k] = (4.0 * fine - coarse) / 3.0 * unit;
        error[k] = std::fabs(fine - coarse) / 3.0 * unit;
    }
    return out;
}

std::vector<std::vector<double>> WhiteNoiseFokkerPlanck::density(double v0, const std::vector<double>& times,
                                                                 const std::vector<double>& v) const {
    check_v0(v0);
    check_times(times, false);
    const double start = v0 / scales_.velocity;
    const Schedule schedule{dt0_, unit_, unit_ + travel_time(density_, start)};
    std::vector<double> nd_times(times.size());
    for (std::size_t k = 0; k < times.size(); ++k) nd_times[k] = times[k] / scales_.time;
    return extrapolated([&](bool coarse) {
        const auto grid = grid_for(start, coarse);
        const Grid& g = *grid;
        std::vector<std::vector<double>> out(times.size(), std::vector<double>(v.size()));
        evolve(g, delta_at(g, start), nd_times, schedule,
               [&](std::size_t k, const std::vector<double>& m) {
                   for (std::size_t j = 0; j < v.size(); ++j)
                       out[k][j] = reconstruct(density_, g, m, v[j] / scales_.velocity) / scales_.velocity;
               });
        return out;
    });
}

std::vector<double> WhiteNoiseFokkerPlanck::stationary_density(const std::vector<double>& v) const {
    std::vector<double> out(v.size());
    for (std::size_t j = 0; j < v.size(); ++j)
        out[j] = reconstruct(density_, *base_, base_->mass, v[j] / scales_.velocity) / scales_.velocity;
    return out;
}

double WhiteNoiseFokkerPlanck::cell_width() const { return h_ * scales_.velocity; }
double WhiteNoiseFokkerPlanck::lower_velocity() const { return lo_ * scales_.velocity; }
double WhiteNoiseFokkerPlanck::upper_velocity() const { return hi_ * scales_.velocity; }

} // namespace stickslip
