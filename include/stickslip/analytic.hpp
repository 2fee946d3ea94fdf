// stickslip/analytic.hpp -- exact white-noise references (MODEL.md sections 7, 9).
//
// For white noise (tau = 0) the velocity is a one-dimensional diffusion
// dV = (b(V) - Delta sgn V) dt + sqrt(Gamma) dW whose stationary density is
// Hayakawa's, p(v) ~ exp(-v^2/(Gamma tauL) - 2 Delta |v|/Gamma + 2 gbar v/Gamma),
// and whose mobility and diffusivity follow from one-dimensional quadrature:
//   M0 = int v p dv,  F(v) = int_{-inf}^v (u - M0) p(u) du,  D = (4/Gamma) int F^2/p dv.
// These are the references for every white-noise-limit test. All in SI units.
#pragma once

#include "params.hpp"

namespace stickslip {

/// Exact white-noise stationary quantities for the drift and friction of p
/// (p.tau is ignored). Throws InvalidParameter when no stationary state exists.
struct WhiteNoiseReference {
    double mobility;    ///< M0 [m/s]
    double diffusivity; ///< D [m^2/s]
    double variance;    ///< stationary Var(V) [m^2/s^2]
};
WhiteNoiseReference white_noise_reference(const ModelParams& p);

/// Unnormalised log of Hayakawa's density, -log p(v) + const [dimensionless].
double hayakawa_potential(const ModelParams& p, double v);

/// Normalised Hayakawa stationary density p(v) [s/m].
double hayakawa_density(const ModelParams& p, double v);

/// Closed forms for pure dry friction with a constant force (no viscous drag),
/// |bias| < friction; g = bias/friction. SI units.
double dry_friction_mobility(const ModelParams& p);    ///< (Gamma/Delta) g/(1-g^2)
double dry_friction_diffusivity(const ModelParams& p); ///< Gamma^3/Delta^4 (5g^4+22g^2+5)/(4(1-g^2)^4)

} // namespace stickslip
