// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/noise.hpp -- the exact one-step law of the Ornstein-Uhlenbeck noise.
//
// The paper's X solves tau dX = -X dt + sqrt(2) dW (stationary variance 1/tau).
// Over a step h the pair (mean of X over the step, X at the end of the step) is
// exactly Gaussian, N(X0 m(h), Sigma(h)) (theory.md, section 5). Computing it
// exactly, rather than Euler-stepping X, is what lets the time step be chosen by
// the velocity dynamics alone; tau = 1e-5 s with h = 1e-4 s is a case the paper
// runs, so the coefficients must stay accurate for h/tau anywhere in 1e-8..1e8:
// the naive formula for Sigma11 loses every digit for small h/tau, so it is
// replaced there by its Taylor series.
#pragma once

/// \file
/// The exact one-step law of the Ornstein-Uhlenbeck noise X. The comment at the
/// top of this header explains the design.

#include <cmath>

#include "stickslip/config.hpp"

namespace stickslip {

/// Coefficients of one exact OU step, with Sigma factored as L L^T:
///   mean_of_step = mean_coef * X0 + l11 * z1
///   end_value    = end_coef  * X0 + l21 * z1 + l22 * z2,   z1, z2 ~ N(0, 1).
struct OUStep {
    double mean_coef; ///< m1 = tau/h (1 - e^{-h/tau})
    double end_coef;  ///< m2 = e^{-h/tau}
    /// @{
    /// Covariance Sigma(h) of (mean of X over the step, X at its end) [s^-1]:
    /// s11 = Var(mean), s12 = Cov(mean, end), s22 = Var(end).
    double s11, s12, s22; ///< covariance Sigma(h) [s^-1]
    /// @}
    /// @{
    /// Cholesky factor L of Sigma(h), L L^T = Sigma, lower triangular [s^-1/2]:
    /// the weights of the two independent standard normals z1, z2 (above).
    double l11, l21, l22; ///< its Cholesky factor [s^-1/2]
    /// @}
};

/// Sigma11 * tau as a function of r = h/tau:
/// (2r - 3 + 4e^{-r} - e^{-2r}) / r^2 = sum_{n>=3} (-1)^n (4 - 2^n) r^{n-2} / n!.
STICKSLIP_HD inline double ou_s11_scaled(double r) {
    if (r < 0.5) {
        // Alternating series; 25 terms give full double precision for r < 0.5.
        double sum = 0.0;
        double rn = r; // r^{n-2}
        double fact = 6.0;
        double pow2 = 8.0;
        for (int n = 3; n < 30; ++n) {
            sum += ((n % 2) ? -1.0 : 1.0) * (4.0 - pow2) * rn / fact;
            rn *= r;
            fact *= (n + 1);
            pow2 *= 2.0;
        }
        return sum;
    }
    const double em = std::expm1(-r);      // e^{-r} - 1
    const double em2 = std::expm1(-2 * r); // e^{-2r} - 1
    return (2 * r + 4 * em - em2) / (r * r);
}

/// Exact step law for correlation time tau > 0 [s] and step h > 0 [s].
STICKSLIP_HD inline OUStep ou_step(double tau, double h) {
    OUStep s{};
    const double r = h / tau;
    const double one_minus_e = -std::expm1(-r); // 1 - e^{-r}, accurate for small r
    s.mean_coef = one_minus_e / r;
    s.end_coef = std::exp(-r);
    s.s11 = ou_s11_scaled(r) / tau;
    s.s12 = one_minus_e * one_minus_e / h;
    s.s22 = -std::expm1(-2 * r) / tau;
    s.l11 = std::sqrt(s.s11);
    s.l21 = s.s12 / s.l11;
    // Schur complement; computed as S22 - S12^2/S11 it keeps ~14 digits at r = 1e-8.
    const double schur = s.s22 - s.l21 * s.l21;
    s.l22 = std::sqrt(schur > 0 ? schur : 0.0);
    return s;
}

} // namespace stickslip
