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
// martingale M of the simulated chain with E[M] = 0 and E[M^2 - Q] = 0 (Q the
// sum of the steps' conditional variances g^2 var) exactly, whatever g and
// whatever the step:
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
// The second-order term. g fixed at a step's start misses how chi_x changes
// along the step; Ito's formula for chi over a step also has the term
// (1/2) chi_xx ((dX)^2 - its mean), the larger part of what a first-order
// sum leaves at coarse steps (most steps of the Fig. 2 case are stuck, where
// X alone moves). Each step therefore adds c (xi^2 - var) with c = g_x / 2,
// the table's slope in x (white noise: in v), also fixed before the step: its
// mean is 0 by optional stopping, so M stays an exact martingale. Q adds each
// increment's square less g^2 (xi^2 - var), a term of mean 0, so that
// E[M^2 - Q] = 0 holds for any step, cut short or not, Gaussian or not (as
// for the first-order term, the event scheme's event times rounded to a leaf
// make it hold to far below any standard error; theory.md, section 12). Q is
// then no longer positive on every excursion. Measured: the Fig. 2 factor at
// dt = 0.01675 s 19x -> 34x, the driven case 62x -> 150x (docs/validation.md).
// Beyond the table's edges the value is clamped flat but the slope is the
// edge cell's: any c fixed before the step keeps M a martingale.
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
        double slope;
        return value_and_slope(x, v, slope);
    }

    /// g at the state (x [s^-1/2], v [m/s]), and in `slope` its derivative
    /// in x [m s] (white noise, nx == 1: in v [s^2/m]) on the
    /// cell or stuck-line segment of the state: the interpolation's own slope.
    STICKSLIP_HD double value_and_slope(double x, double v, double& slope) const {
        if (v == 0.0 && stuck) {
            const double q = clamp((x - s_first) * inv_ds, ns);
            int i = static_cast<int>(q);
            if (i > ns - 2) i = ns - 2;
            const double rise = stuck[i + 1] - stuck[i];
            slope = rise * inv_ds;
            return stuck[i] + (q - i) * rise;
        }
        const double pv = clamp((v - v_first) * inv_dv, nv);
        int k = static_cast<int>(pv);
        if (k > nv - 2) k = nv - 2;
        const double fv = pv - k;
        if (nx == 1) {
            const double rise = slide[k + 1] - slide[k];
            slope = rise * inv_dv;
            return slide[k] + fv * rise;
        }
        const double px = clamp((x - x_first) * inv_dx, nx);
        int i = static_cast<int>(px);
        if (i > nx - 2) i = nx - 2;
        const double fx = px - i;
        const double* r0 = slide + static_cast<long>(i) * nv + k;
        const double* r1 = r0 + nv;
        const double a = r0[0] + fv * (r0[1] - r0[0]);
        const double b = r1[0] + fv * (r1[1] - r1[0]);
        slope = (b - a) * inv_dx;
        return a + fx * (b - a);
    }

private:
    /// p clamped to [0, n - 1] (NaN to 0).
    STICKSLIP_HD static double clamp(double p, int n) {
        const double hi = static_cast<double>(n - 1);
        return p > 0.0 ? (p < hi ? p : hi) : 0.0;
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

/// The martingale sums of one long excursion: M = sum (g_n xi_n + c_n (xi_n^2 -
/// var_n)) [m] and Q = sum (g_n^2 var_n + its second-order part) [m^2], with
/// g_n = g(X_n, V_n), c_n half its slope, xi_n the step's innovation and var_n
/// its variance (see the top of this header).
struct MartingaleSums {
    /// Whether the kernel should accumulate.
    static constexpr bool active = true;
    CorrectorTable g; ///< the corrector
    double m = 0.0;   ///< M so far [m]
    double q = 0.0;   ///< Q so far [m^2]

    /// One step's increments of M and Q, from g [m s^1/2] and its slope at
    /// the step's start, the innovation xi and its variance var: one
    /// definition, for add() and for the SIMD lanes, which must get its bits.
    STICKSLIP_HD static void increments(double gv, double slope, double xi, double var, double& dm, double& dq) {
        const double c = 0.5 * slope;       // (1/2) chi_xx: Ito's second-order term
        const double centred = xi * xi - var; // mean 0 given the step's start
        const double second = c * centred;
        dm = gv * xi + second;
        // dm^2 - g^2 (xi^2 - var), written without the cancellation.
        dq = (gv * gv) * var + second * (2.0 * (gv * xi) + second);
    }

    /// Adds the step from the state (x [s^-1/2], v [m/s]) whose innovation is
    /// xi [s^-1/2] (white noise: [m/s]) with variance var (its square's unit).
    STICKSLIP_HD void add(double x, double v, double xi, double var) {
        double slope;
        const double gv = g.value_and_slope(x, v, slope);
        double dm, dq;
        increments(gv, slope, xi, var, dm, dq);
        m += dm;
        q += dq;
    }
};

} // namespace stickslip
