// stickslip/fokker_planck.hpp -- numerical transient law of the white-noise
// velocity diffusion, for any drift b (MODEL.md sections 1, 2, 7).
//
// The white-noise limit of the model (p.tau is ignored) is the diffusion
//   dV = (b(V) - Delta sgn V) dt + sqrt(Gamma) dW,   b(v) = -v/tauL + gbar,
// whose density obeys the Fokker-Planck equation
//   dp/dt = -d/dv[(b(v) - Delta sgn v) p] + (Gamma/2) d^2p/dv^2.
// Closed forms exist only for pure dry friction (analytic.hpp, Touchette et
// al.); this solver is their independent numerical check and the way to get
// E[V(t)|v0], <V(t)V(0)> and p(v,t|v0) when b has drag or a bias.
//
// Method (all internally in the nondimensional variables of MODEL.md section 3):
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
// * Time: Crank-Nicolson (tridiagonal solves), started with backward-Euler
//   half steps over the first two nominal steps (Rannacher start-up) to damp
//   the stiff modes a delta initial condition excites. The nominal step is
//   T/steps_per_unit_time, T = min(Gamma/Delta^2, tauL); beyond t = T it grows
//   like t/steps_per_unit_time (the solution relaxes exponentially, so the
//   relative time resolution is what matters). Steps are shortened to land
//   exactly on every requested time.
// * Observables: E[g(V)] = sum_i g_i mu_i with mu_i the cell probability and
//   g_i the mean of g over cell i under p_s, so stationary means are exact.
//   The density between cell centres is f interpolated linearly times p_s(v),
//   exact at the kink and in the stationary state.
// Accuracy, defaults, pure dry friction (nondimensional): first moment and
// autocorrelation within about 2e-6 of the closed forms (errors O(h^2 + dt^2)).
#pragma once

#include <memory>
#include <vector>

#include "analytic.hpp"
#include "params.hpp"

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
    /// Nominal time steps per time unit min(noise/friction^2, relaxation) (>= 1).
    int steps_per_unit_time = 1000;
    /// Richardson extrapolation in the cell width: every result is
    /// (4 R(h) - R(2h))/3 from a second run on cells of width 2h, which
    /// removes the O(h^2) spatial error for 50% more work.
    bool richardson = true;
};

/// Fokker-Planck solver for the white-noise velocity of p (any drift b; p.tau
/// is ignored). Built once per parameter set (a few milliseconds); every query
/// runs its own time integration and is independent of the others (the class
/// is immutable and may be shared between threads). All arguments and results
/// in SI units. Times need not be sorted; results come in the order asked.
/// Throws InvalidParameter when p is invalid or has no stationary state
/// ("bias"), when a time is negative or not finite ("time"), when v0 is not
/// finite ("v0"), or when v0 is so far out that the grid would need more than
/// 100 times settings.cells cells ("v0").
class WhiteNoiseFokkerPlanck {
public:
    explicit WhiteNoiseFokkerPlanck(const ModelParams& p, const FokkerPlanckSettings& settings = {});

    /// E[V(t) | V(0) = v0] [m/s] at each time t >= 0 [s] (t = 0 gives v0);
    /// v0 [m/s]. The initial delta is split between the two nearest cells so
    /// that the discrete mean is exactly v0.
    std::vector<double> first_moment(double v0, const std::vector<double>& times) const;

    /// Stationary autocorrelation <V(t) V(0)> [m^2/s^2] (not the covariance:
    /// it tends to M0^2) at each lag t >= 0 [s]. Computed as
    /// int v q(v, t) dv where q evolves from q(v, 0) = v p_s(v), a signed
    /// initial condition. t = 0 gives the discrete <V^2>, which is below the
    /// exact one by the within-cell variance, about h^2/12.
    std::vector<double> autocorrelation(const std::vector<double>& times) const;

    /// Transition density p(v, t | v0) [s/m]: one row per time t > 0 [s]
    /// (t = 0, a delta function, is rejected), one column per velocity
    /// v [m/s]; 0 outside the computational interval. Resolving the density
    /// itself needs t >> h^2/noise.
    std::vector<std::vector<double>> density(double v0, const std::vector<double>& times,
                                             const std::vector<double>& v) const;

    /// Stationary density of the discrete chain, reconstructed like density()
    /// [s/m] at velocities v [m/s]; equal to Hayakawa's inside the interval.
    std::vector<double> stationary_density(const std::vector<double>& v) const;

    /// Cell width h [m/s] and the automatic (or chosen) interval [m/s].
    double cell_width() const;
    double lower_velocity() const;
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
