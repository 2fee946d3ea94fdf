// SPDX-License-Identifier: BSD-3-Clause
// stickslip/fokker_planck.hpp -- numerical transient law of the white-noise
// velocity diffusion, for any drift b (theory.md, sections 1, 2 and 8).
//
// The white-noise limit of the model (p.tau is ignored) is the diffusion
//   dV = (b(V) - Delta sgn V) dt + sqrt(Gamma) dW,   b(v) = -v/tauL + gbar,
// whose density obeys the Fokker-Planck equation
//   dp/dt = -d/dv[(b(v) - Delta sgn v) p] + (Gamma/2) d^2p/dv^2.
// Closed forms exist only for pure dry friction (analytic.hpp, Touchette et
// al.); this solver is their independent numerical check and the way to get
// E[V(t)|v0], <V(t)V(0)> and p(v,t|v0) when b has drag or a bias.
//
// Method (all internally in the nondimensional variables of theory.md, section 3):
// * Space: finite volumes of equal width h on a truncated interval, with a cell
//   face at v = 0 so the kink of the drift lies on a face, zero-flux ends.
//   The flux between neighbouring cells is exponentially fitted: writing
//   p = f p_s with p_s Hayakawa's stationary density, the exact flux is
//   J = -(Gamma/2) p_s df/dv, and the conductance between the centres v_i,
//   v_{i+1} is (Gamma/2) / int_{v_i}^{v_{i+1}} dv/p_s(v) (the Scharfetter-
//   Gummel / Chang-Cooper flux, which it equals where log p_s is linear, e.g.
//   for pure dry friction away from 0), integrated exactly across the kink.
//   Cell masses use the exact cell probabilities of p_s. The result is a
//   reversible Markov chain on the cells whose stationary law is exactly the
//   cell probabilities of Hayakawa's density (detailed balance holds by
//   construction): it is positive, mass is conserved, and t -> inf recovers
//   M0 and Var(V) of white_noise_reference to quadrature accuracy.
// * Richardson extrapolation in h (default): every result is combined with a
//   second run on cells of width 2h as (4 R(h) - R(2h))/3, removing the
//   O(h^2) error. The initial delta at v0 is spread over three cells with
//   quadratic Lagrange weights (on the side of v0) so that the O(h^2) error
//   does not depend on where v0 falls in its cell.
// * Time: Crank-Nicolson (tridiagonal solves), after four backward-Euler
//   start-up steps (Rannacher) that damp the stiff modes a delta excites.
//   Steps are graded: ~t/50 at early times (down to 1/100 of the nominal
//   step), the nominal step T/steps_per_unit_time with T = min(Gamma/Delta^2,
//   tauL) up to t = T, growing like sqrt(t) while the drift carries a bump
//   from a far v0 into the bulk, then like t (the solution relaxes
//   exponentially, so relative time resolution is what matters). Steps are
//   shortened to land exactly on every requested time; times need not be
//   sorted and cost no more than the largest one.
// * Observables: E[g(V)] = sum_i g_i mu_i with mu_i the cell probability and
//   g_i the mean of g over cell i under p_s, so stationary means are exact.
//   The density is f = mu_i/m_i interpolated quadratically between centres
//   (on the side of 0 of v) times p_s(v): exact at the kink and in the
//   stationary state.
// Accuracy with the defaults, pure dry friction, nondimensional, against the
// closed forms: first moment within 5e-7 (7e-8 from v0 = 1) for v0 in
// [-2, 50] and t up to 60; autocorrelation within 2e-8; Green-Kubo
// 2 int C = 5/4 to 2e-7 relative; density within 1e-6 for t >= 0.5 (2e-5 of
// the peak at t = 0.05, where the bump is 30 cells wide). Cost: ~70 ms for
// E[V(t)|1] at ten times up to t' = 5 (about 6000 cells, 4000 steps). What
// remains is mostly the O(dt^2) time error: doubling steps_per_unit_time
// divides it by about 4.
#pragma once

/// \file
/// A Fokker-Planck solver for the white-noise velocity with any drift:
/// E[V(t)|v0], <V(t)V(0)>, p(v,t|v0). The comment at the top of this header
/// explains the design.

#include <memory>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

namespace detail {
struct FokkerPlanckGrid; // cells, transition rates and masses (fokker_planck.cpp)
}

/// Resolution of WhiteNoiseFokkerPlanck. Invalid values throw InvalidParameter
/// named after the field.
struct FokkerPlanckSettings {
    /// Number of cells (>= 16) across the velocity interval below; the cell
    /// width h follows and is kept when the interval must be widened.
    int cells = 4000;
    /// Half-width of the velocity interval [m/s] (> 0), centred on the
    /// stationary mean M0. 0 (default): automatic, the interval where Hayakawa's
    /// density exceeds e^-30 times its maximum. Whatever is chosen, the
    /// interval is widened (same h) to include v0 and the range the velocity
    /// can reach from it, where the stationary potential rises by 30 beyond v0.
    double half_width = 0.0;
    /// Nominal time steps per time unit T = min(noise/friction^2, relaxation)
    /// (>= 1); the steps are graded around it (see the file comment).
    int steps_per_unit_time = 1000;
    /// Richardson extrapolation in the cell width: every result is
    /// (4 R(h) - R(2h))/3 from a second run on cells of width 2h, which
    /// removes the O(h^2) spatial error for 50% more work.
    bool richardson = true;
};

/// Fokker-Planck solver for the white-noise velocity of p (any drift b; p.tau
/// is ignored). Built once per parameter set (about 10 ms); every query runs
/// its own time integration and is independent of the others (the class is
/// immutable and may be shared between threads). Cells are uniform: without
/// drag and with |bias| close to friction the interval is long on the side the
/// bias pushes (potential slope 2(friction - |bias|)/noise) and the steep side
/// is resolved by few cells; raise `cells` there. All arguments and results
/// in SI units. Times need not be sorted; results come in the order asked.
/// Throws InvalidParameter when p is invalid or has no stationary state
/// ("bias"), when a time is negative or not finite ("time"), when v0 is not
/// finite ("v0"), or when v0 is so far out that the grid would need more than
/// 100 times settings.cells cells ("v0").
class WhiteNoiseFokkerPlanck {
public:
    /// Builds the cells, rates and masses for p (SI units; p.tau ignored) at
    /// the given resolution, and for Richardson extrapolation the coarse
    /// grid too. Throws InvalidParameter as described above.
    explicit WhiteNoiseFokkerPlanck(const ModelParams& p, const FokkerPlanckSettings& settings = {});

    /// E[V(t) | V(0) = v0] [m/s] at each time t >= 0 [s] (t = 0 gives v0);
    /// v0 [m/s]. The initial delta is split between the two nearest cells so
    /// that the discrete mean is exactly v0.
    std::vector<double> first_moment(double v0, const std::vector<double>& times) const;

    /// Stationary autocorrelation <V(t) V(0)> [m^2/s^2] (not the covariance:
    /// it tends to M0^2) at each lag t >= 0 [s]. Computed as
    /// int v q(v, t) dv where q evolves from q(v, 0) = v p_s(v), a signed
    /// initial condition. t = 0 gives <V^2> = Var + M0^2 (without Richardson
    /// extrapolation, less the within-cell variance h^2/12).
    std::vector<double> autocorrelation(const std::vector<double>& times) const;

    /// Two-sided velocity spectrum S(w) = int over all t of C(t) e^{-i w t} dt
    /// [m^2/s], C the stationary autocovariance of V, at each angular
    /// frequency w >= 0 [rad/s] (S(0) = D, white_noise_reference's, exact),
    /// with its estimated error [m^2/s] in `error` (same order). No time
    /// integration: per frequency and grid one complex tridiagonal solve of
    /// the chain's resolvent, (i w - Q) phi = V - M0, and S = 2 Re sum_i m_i
    /// (V_i - M0) phi_i; Richardson-extrapolated like every result, the error
    /// |S(h) - S(2h)|/3 (what the extrapolation removed: an upper estimate).
    /// Throws InvalidParameter ("frequencies") for a negative or non-finite w.
    std::vector<double> spectrum(const std::vector<double>& frequencies, std::vector<double>& error) const;

    /// Transition density p(v, t | v0) [s/m]: one row per time t > 0 [s]
    /// (t = 0, a delta function, is rejected), one column per velocity
    /// v [m/s]; 0 outside the computational interval. Resolving the density
    /// itself needs t >> h^2/noise. Where it is below ~1e-8 of its peak the
    /// relative accuracy is lost to numerical diffusion (values may even be
    /// tiny and negative); compare histograms in absolute terms.
    std::vector<std::vector<double>> density(double v0, const std::vector<double>& times,
                                             const std::vector<double>& v) const;

    /// Stationary density of the discrete chain, reconstructed like density()
    /// [s/m] at velocities v [m/s]; equal to Hayakawa's inside the interval.
    std::vector<double> stationary_density(const std::vector<double>& v) const;

    /// Cell width h [m/s] and the automatic (or chosen) interval [m/s].
    double cell_width() const;
    /// Lower end of the velocity interval [m/s], before any widening for a
    /// query's v0 (FokkerPlanckSettings::half_width).
    double lower_velocity() const;
    /// Upper end of the velocity interval [m/s], before any widening for a
    /// query's v0.
    double upper_velocity() const;

private:
    std::shared_ptr<const detail::FokkerPlanckGrid> grid_for(double v0_nd, bool coarse) const;
    template <class Solve>
    auto extrapolated(Solve solve) const;

    ModelParams params_;
    FokkerPlanckSettings settings_;
    Scales scales_;
    HayakawaDensity density_; // of the nondimensional twin
    double lo_ = 0, hi_ = 0, h_ = 0; // interval and cell width, nondimensional
    double unit_ = 0, dt0_ = 0;      // time unit and nominal time step, nondimensional
    std::shared_ptr<const detail::FokkerPlanckGrid> base_, coarse_; // cell width h and 2h
};

} // namespace stickslip
