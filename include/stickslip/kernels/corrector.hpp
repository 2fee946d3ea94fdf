// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/corrector.hpp -- the martingale of a long excursion, for the
// control variate of D and M0 (theory.md, section 12).
//
// Why. Per excursion, (U - M0 t)^2 is extremely heavy-tailed, so the plain
// renewal-reward estimator of D needs millions of excursions for 0.3% and its
// intervals cover too rarely at a few thousand. With chi the solution of the
// Poisson equation L chi = -(v - M0), Ito's formula over an excursion (which
// starts and ends in the same state) gives exactly
//   U - M0 t = int chi_x(X, V) (sqrt(2)/tau) dW,
// a martingale of the noise. A kernel that sums g(X, V) times the noise's own
// innovation over every step, for any g fixed before the step, builds a
// martingale M of the simulated chain with E[M] = 0 and E[M^2 - Q] = 0 (Q its
// predictable quadratic variation) exactly, whatever g and whatever the step:
// C = M^2 - Q is then a control variate of known mean 0 for (U - M0 t)^2, and
// the closer g is to chi_x, the more variance it removes. Nothing is drawn
// differently: the plain estimates stay bitwise what they are without it.
//
// The innovation of a step from time 0 to a time T (T <= h, a stopping time
// where the step is cut short by an event) is xi = e^{T/tau} X_T - X_0, the
// OU process's exact martingale part (mean 0, variance (e^{2T/tau} - 1)/tau);
// for a whole step of the resolvent scheme, whose end is drawn as X_h =
// e^{-h/tau} X_0 + (l21 z1 + l22 z2), the drawn Gaussian term itself is used
// (the same martingale scaled by the constant e^{-h/tau}). White noise: the
// innovation is the Brownian increment of V, sqrt(noise h) z.
//
// g is a table (CorrectorTable), built once per run from a coarse solve of
// the Kolmogorov equations (coloured noise) or the one-dimensional closed form
// (white noise) by make_corrector (corrector.hpp at the top level); the
// kernels look it up once per step, bilinearly, with no branch on the engine.
#pragma once

/// \file
/// The corrector g(x, v) of the control variate as a table (POD, STICKSLIP_HD)
/// and the per-excursion martingale sums M and Q. The comment at the top of
/// this header explains the design.

#include "stickslip/config.hpp"

namespace stickslip {

/// g(x, v) ~ chi_x [m s^1/2] on uniform grids (a view: the arrays belong to the
/// Corrector that made it). Sliding states (v != 0) are looked up bilinearly
/// on nx x nv nodes (x-major: slide[i * nv + k] at x = x_first + i / inv_dx,
/// v = v_first + k / inv_dv), clamped at the table's edges; v == 0 exactly (the
/// object stuck) on a line of ns nodes in x. nx == 1: g depends on v alone
/// (white noise). Units: x [s^-1/2], v [m/s].
struct CorrectorTable {
    const double* slide = nullptr; ///< nx * nv values [m s^1/2] (white noise: [m / (m/s)] = [s])
    int nx = 0;                    ///< x nodes of the sliding table (1: no x dependence)
    int nv = 0;                    ///< v nodes of the sliding table (>= 2)
    double x_first = 0.0;          ///< x of node 0 [s^-1/2]
    double inv_dx = 0.0;           ///< 1 / x spacing [s^1/2]
    double v_first = 0.0;          ///< v of node 0 [m/s]
    double inv_dv = 0.0;           ///< 1 / v spacing [s/m]
    const double* stuck = nullptr; ///< ns values at v == 0 [m s^1/2] (nullptr: the sliding table at v = 0)
    int ns = 0;                    ///< nodes of the stuck line (>= 2 when stuck is set)
    double s_first = 0.0;          ///< x of stuck node 0 [s^-1/2]
    double inv_ds = 0.0;           ///< 1 / its spacing [s^1/2]

    /// g at the state (x [s^-1/2], v [m/s]).
    STICKSLIP_HD double operator()(double x, double v) const {
        if (v == 0.0 && stuck) return line(stuck, ns, (x - s_first) * inv_ds);
        const double pv = clamp((v - v_first) * inv_dv, nv);
        int k = static_cast<int>(pv);
        if (k > nv - 2) k = nv - 2;
        const double fv = pv - k;
        if (nx == 1) return slide[k] + fv * (slide[k + 1] - slide[k]);
        const double px = clamp((x - x_first) * inv_dx, nx);
        int i = static_cast<int>(px);
        if (i > nx - 2) i = nx - 2;
        const double fx = px - i;
        const double* r0 = slide + static_cast<long>(i) * nv + k;
        const double* r1 = r0 + nv;
        const double a = r0[0] + fv * (r0[1] - r0[0]);
        const double b = r1[0] + fv * (r1[1] - r1[0]);
        return a + fx * (b - a);
    }

private:
    /// p clamped to [0, n - 1] (NaN to 0).
    STICKSLIP_HD static double clamp(double p, int n) {
        const double hi = static_cast<double>(n - 1);
        return p > 0.0 ? (p < hi ? p : hi) : 0.0;
    }
    /// Linear interpolation on a line of n nodes at fractional position p.
    STICKSLIP_HD static double line(const double* y, int n, double p) {
        const double q = clamp(p, n);
        int i = static_cast<int>(q);
        if (i > n - 2) i = n - 2;
        return y[i] + (q - i) * (y[i + 1] - y[i]);
    }
};

/// No martingale: what the long-excursion kernels accumulate by default;
/// compiled away entirely, so the plain kernels are unchanged.
struct NoMartingale {
    /// Whether the kernel should accumulate (false: it skips the innovation).
    static constexpr bool active = false;
    /// Does nothing.
    STICKSLIP_HD void add(double /*x*/, double /*v*/, double /*xi*/, double /*var*/) {}
};

/// The martingale sums of one long excursion: M = sum g(X_n, V_n) xi_n [m] and
/// Q = sum g(X_n, V_n)^2 var_n [m^2], with xi_n the step's innovation and var_n
/// its variance (see the top of this header).
struct MartingaleSums {
    /// Whether the kernel should accumulate.
    static constexpr bool active = true;
    CorrectorTable g; ///< the corrector
    double m = 0.0;   ///< M so far [m]
    double q = 0.0;   ///< Q so far [m^2]
    /// Adds the step from the state (x [s^-1/2], v [m/s]) whose innovation is
    /// xi [s^-1/2] (white noise: [m/s]) with variance var (its square's unit).
    STICKSLIP_HD void add(double x, double v, double xi, double var) {
        const double gv = g(x, v);
        m += gv * xi;
        q += (gv * gv) * var;
    }
};

} // namespace stickslip
