// SPDX-License-Identifier: BSD-3-Clause
// stickslip/analytic.hpp -- exact white-noise references (theory.md, section 8).
//
// For white noise (tau = 0) the velocity is a one-dimensional diffusion
// dV = (b(V) - Delta sgn V) dt + sqrt(Gamma) dW whose stationary density is
// Hayakawa's, p(v) ~ exp(-v^2/(Gamma tauL) - 2 Delta |v|/Gamma + 2 gbar v/Gamma),
// and whose mobility and diffusivity follow from one-dimensional quadrature:
//   M0 = int v p dv,  F(v) = int_{-inf}^v (u - M0) p(u) du,  D = (4/Gamma) int F^2/p dv.
// For pure dry friction (no viscous drag, no bias) the transient law is known in
// closed form too (Touchette, Van der Straeten and Just 2010). These are the
// references for every white-noise-limit test. All in SI units; p.tau is ignored
// throughout (the references are those of the white-noise limit).
//
// Noise convention (theory.md, section 2): the white-noise limit has intensity
// Gamma = p.noise, i.e. the Fokker-Planck diffusion coefficient is Gamma/2.
#pragma once

/// \file
/// Exact white-noise references: Hayakawa's stationary density, M0, D and
/// Var(V) by quadrature, and Touchette's transient closed forms for pure dry
/// friction. The comment at the top of this header explains the design.

#include "stickslip/drift_law_quadrature.hpp" // WhiteNoiseReference
#include "stickslip/params.hpp"

namespace stickslip {

/// Exact white-noise stationary quantities for the drift and friction of p
/// (p.tau is ignored), to a few units of double rounding for every valid p:
/// closed forms without drag, the viscous values (D = relaxation^2 noise,
/// Var = noise relaxation/2, M0 = the mode) once the mode is more than ~9
/// standard deviations from the kink, otherwise quadratures that never cancel
/// (analytic.cpp). Throws InvalidParameter when no stationary state exists
/// ("bias"), or when a result is outside what a double holds to 12 digits
/// (beyond 1.8e308, or deep among the denormals): "relaxation" with drag,
/// "bias" without (as |bias| -> friction) and for M0 or a mode out of range.
WhiteNoiseReference white_noise_reference(const ModelParams& p);

/// Hayakawa's stationary velocity density for white noise, normalised once.
///
/// p(v) = exp(-phi(v)) / Z with phi(v) = v^2/(Gamma tauL) + 2 Delta |v|/Gamma
/// - 2 gbar v/Gamma shifted so that min phi = 0; phi is convex and piecewise
/// quadratic with a kink at v = 0. Build it once and evaluate it many times:
/// the constructor does the quadratures (well under a millisecond), the calls
/// are a few flops. phi is evaluated without cancellation (a2 (v - mode)^2 with
/// a double-double mode on the mode's side), so density, potential and
/// probabilities are exact to rounding however far the mode is from 0 in
/// standard deviations. p.tau is ignored. Throws InvalidParameter (like every
/// function here: "friction", "noise", ... from validate(), "bias" when no
/// stationary state exists, i.e. relaxation = inf and |bias| >= friction, or
/// when the mean or mode is out of the range of double; like
/// white_noise_reference when the variance is).
class HayakawaDensity {
public:
    /// Normalises the density of p (SI units; p.tau ignored): the
    /// quadratures, once. Throws InvalidParameter as described above.
    explicit HayakawaDensity(const ModelParams& p);

    /// Normalised density p(v) [s/m] at velocity v [m/s]; 0 for |v| = inf.
    double operator()(double v) const;
    /// P(a <= V <= b) [1] for a <= b [m/s] (either may be infinite); for a > b
    /// it is -P(b <= V <= a). Computed by Gauss-Legendre panels split at the
    /// kink and the mode, so each panel integrates an analytic function and the
    /// result is exact to rounding: use it to compare histogram bins, where the
    /// density at the bin centre would be off by O(width^2).
    double probability(double a, double b) const;
    /// Stationary mean E[V] = M0 [m/s].
    double mean() const { return mean_; }
    /// Stationary variance Var(V) [m^2/s^2].
    double variance() const { return variance_; }
    /// phi(v) = -log(p(v)/p(mode)) >= 0 [1]: the potential, 0 at the mode.
    double potential(double v) const;
    /// The most probable velocity [m/s] (0 unless |bias| > friction with drag),
    /// rounded to double: where |mode| >> sd that double may sit a fraction of
    /// sd off the exact mode, and potential(mode()) is then not 0.
    double mode() const { return mode_; }

private:
    // phi(v) = a2 v^2 + kp v (v >= 0), a2 v^2 + km |v| (v < 0), shifted to min 0
    // and evaluated without cancellation (analytic.cpp): a2 (v - mode)^2 on the
    // side of the mode, kink + a2 v^2 + k |v| on the other.
    long double a2_ = 0, kp_ = 0, km_ = 0; // [s^2/m^2], [s/m], [s/m]
    long double kink_ = 0;                 // phi(0)
    int side_ = 0;                         // sign of the mode (0: the mode is v = 0)
    double mode_ = 0, mode_lo_ = 0;        // the mode as a double-double mode_ + mode_lo_ [m/s]
    double inv_z_ = 0, mean_ = 0, variance_ = 0;
};

/// Unnormalised log of Hayakawa's density, -log p(v) + const [dimensionless]
/// (the constant makes its minimum 0, as HayakawaDensity::potential).
double hayakawa_potential(const ModelParams& p, double v);

/// Normalised Hayakawa stationary density p(v) [s/m]. Convenience wrapper of
/// HayakawaDensity that keeps the last parameters' normalisation per thread, so
/// that repeated calls with the same parameters do not redo the quadrature.
double hayakawa_density(const ModelParams& p, double v);

/// Closed forms for pure dry friction with a constant force (no viscous drag),
/// |bias| < friction; g = bias/friction. SI units; evaluated with
/// 1 - g^2 = (friction - bias)(friction + bias)/friction^2, so they keep their
/// digits as |bias| -> friction. Not validated (see white_noise_reference).
/// White-noise mobility M0 [m/s] without drag: closed form in g.
double dry_friction_mobility(const ModelParams& p);    ///< (Gamma/Delta) g/(1-g^2)
/// White-noise diffusivity D [m^2/s] without drag: closed form in g
/// (5/4 Gamma^3/Delta^4 at g = 0).
double dry_friction_diffusivity(const ModelParams& p); ///< Gamma^3/Delta^4 (5g^4+22g^2+5)/(4(1-g^2)^4)
/// White-noise two-sided velocity spectrum S(w) = int C(t) e^{-i w t} dt over
/// all t [m^2/s] without drag, at the angular frequency w >= 0 [rad/s]:
/// S(0) = dry_friction_diffusivity. The resolvent equation (i w - L) phi =
/// V - M0, L = (bias - Delta sgn v) d/dv + (Gamma/2) d^2/dv^2, has constant
/// coefficients on each half line, so phi is a line plus one decaying
/// exponential on each, joined C^1 at v = 0, and S = 2 Re E[(V - M0) phi]
/// against the two-exponential stationary density (theory.md, section on the
/// spectrum). Evaluated in extended precision; the terms of order 1/w'^2
/// cancel, so the relative rounding error is about 1e-19/w'^2 (w' = w
/// Gamma/Delta^2). Not validated (see white_noise_reference).
double dry_friction_spectrum(const ModelParams& p, double w);

// ---- Pure dry friction, transient (Touchette, Van der Straeten, Just 2010) ----
//
// dV = -Delta sgn(V) dt + sqrt(Gamma) dW: relaxation must be inf and bias 0
// (InvalidParameter "relaxation" or "bias" otherwise; p.tau is ignored). Their
// formulas (2.10), (2.11), (2.13) are written in x = 2v', s = 2t'; here they are
// restated in the nondimensional variables (theory.md, section 3) v' = v Delta/Gamma,
// t' = t Delta^2/Gamma (section 9) and returned in SI. Evaluated in extended
// precision with scaled complementary error functions, so they neither
// overflow (e^{2|v0|} Phi(-...) is never formed) nor lose the small values
// at large t to cancellation. Time arguments must be finite ("time"),
// velocities finite ("v0", "v").

/// Transition density p(v, t | v0) [s/m] of V(t) = v [m/s] given V(0) = v0
/// [m/s], for t > 0 [s] (t = 0 is a delta function: rejected).
double dry_friction_propagator(const ModelParams& p, double v, double t, double v0);

/// First moment E[V(t) | V(0) = v0] [m/s] for t >= 0 [s] (v0 at t = 0).
double dry_friction_first_moment(const ModelParams& p, double t, double v0);

/// Stationary autocorrelation <V(t) V(0)> [m^2/s^2] at lag t [s]; even in t
/// (|t| is used). It equals the covariance, since the stationary mean is 0:
/// C(0) = Var(V) = Gamma^2/(2 Delta^2) and 2 int_0^inf C = D = 5 Gamma^3/(4 Delta^4).
double dry_friction_autocorrelation(const ModelParams& p, double t);

/// Diffusivity of a purely viscous object, D = relaxation^2 * noise [m^2/s]:
/// the Delta -> 0 limit of white_noise_reference (an Ornstein-Uhlenbeck
/// velocity with relaxation time tauL, whose integral diffuses with
/// tauL^2 Gamma whatever the bias). Friction, bias and tau are not used; noise
/// must be finite and > 0 ("noise") and relaxation finite and > 0
/// ("relaxation": with neither drag nor friction nothing is stationary).
double viscous_diffusivity(const ModelParams& p);

} // namespace stickslip
