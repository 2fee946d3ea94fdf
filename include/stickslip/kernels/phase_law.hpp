// SPDX-License-Identifier: BSD-3-Clause
// stickslip/kernels/phase_law.hpp -- exact Gaussian laws of one step, and of its midpoint
// bridge, within one phase (theory.md, section 10: within a phase the dynamics is linear).
//
// While the object slides in direction s (V != 0) the state Z = (X, V, U) solves
// the linear SDE
//     dX = -X/tau dt + (sqrt(2)/tau) dW        (the paper's X, variance 1/tau)
//     dV = (a X - V/tauL + c) dt               (c = bias - s friction, constant)
//     dU = V dt
// i.e. dZ = (A Z + c e_V) dt + B dW with A = [[-1/tau, 0, 0], [a, -1/tauL, 0],
// [0, 1, 0]] and B = e_X sqrt(2)/tau. Over a step h the state is therefore
// exactly Gaussian: Z_h = M(h) Z_0 + g(h) c + N(0, S(h)), with M = e^{Ah},
// g = int_0^h e^{Ar} e_V dr and S = int_0^h e^{Ar} B B^T e^{A^T r} dr. With white
// noise (tau = 0) the same holds for (V, U) with dV = (c - V/tauL) dt +
// sqrt(noise) dW. While stuck, X alone is OU (noise.hpp) and U does not move.
//
// The bridges are the laws of the state at the midpoint h/2 of a step given both
// ends, which is what the event scheme's dichotomic search draws.
//
// Units: X [s^-1/2], V [m s^-1], U [m], amplitude a = sqrt(noise/2)
// [m s^-3/2], c [m s^-2], noise [m^2 s^-3], tau, relaxation and h [s]. Index 0
// is X, 1 is V, 2 is U for the coloured laws; 0 is V, 1 is U for the white ones.
//
// The construction functions (src/engines/event/phase_law.cpp) are meant to be called once per
// run and per refinement depth (a law takes microseconds, a bridge under a
// millisecond). Every entry is correct to the rounding of a double (measured
// 1e-16 relative) for h/tau and h/tauL anywhere in 1e-20 .. 1e12, tauL = tau
// and tauL = inf included; bridge entries that vanish identically (e.g.
// Cov(V, U) given both ends) are exact zeros. Applying a law is a handful of
// multiply-adds (STICKSLIP_HD, no allocation, no exceptions).
#pragma once

/// \file
/// Exact Gaussian laws of one step, and of its midpoint bridge, within one
/// phase of the motion. The comment at the top of this header explains the
/// design.

#include "stickslip/config.hpp"

namespace stickslip {

/// Exact law of the sliding state (X, V, U) over a step h with coloured noise:
///   Z_h = m Z_0 + g c + chol n,   n ~ N(0, I_3).
struct ColoredSlideLaw {
    double m[3][3];    ///< M(h) = e^{Ah}; lower triangular (m[i][j] = 0 for j > i)
    double g[3];       ///< response to c: (0, [s], [s^2]); g[0] = 0
    double cov[3][3];  ///< S(h), symmetric, units of Z_i Z_j
    double chol[3][3]; ///< lower factor, chol chol^T = cov (upper part zero, clamped at rank loss)
    double h;          ///< step [s]
};

/// Exact law of the sliding state (V, U) over a step h with white noise:
///   Z_h = m Z_0 + g c + chol n,   n ~ N(0, I_2).
struct WhiteSlideLaw {
    double m[2][2];    ///< [[e^{-h/tauL}, 0], [tauL (1 - e^{-h/tauL}), 1]]
    double g[2];       ///< response to c: ([s], [s^2])
    double cov[2][2];  ///< S(h), symmetric
    double chol[2][2]; ///< lower factor, chol chol^T = cov
    double h;          ///< step [s]
};

/// Midpoint bridge of the coloured sliding state over a step [0, h]: the law of
/// Z_{h/2} given Z_0 and Z_h (both in the same sliding phase, same c):
///   Z_{h/2} = p Z_0 + q Z_h + r c + chol n,   n ~ N(0, I_3).
struct ColoredSlideBridge {
    double p[3][3];    ///< weight of Z_0 (units of Z_i / Z_j)
    double q[3][3];    ///< weight of Z_h
    double r[3];       ///< response to c (units of Z_i per m s^-2); r[0] != 0: V_h tells about X
    double cov[3][3];  ///< conditional covariance
    double chol[3][3]; ///< lower factor, chol chol^T = cov
    double h;          ///< length of the whole step [s] (the bridge is at h/2)
};

/// Midpoint bridge of the white-noise sliding state (V, U) over a step [0, h].
struct WhiteSlideBridge {
    double p[2][2];    ///< weight of Z_0
    double q[2][2];    ///< weight of Z_h
    double r[2];       ///< response to c
    double cov[2][2];  ///< conditional covariance
    double chol[2][2]; ///< lower factor, chol chol^T = cov
    double h;          ///< length of the whole step [s]
};

/// Midpoint bridge of the OU noise alone (the stuck phase):
///   X_{h/2} = p X_0 + q X_h + sd n,  p = q = sinh(h/2tau)/sinh(h/tau), sd^2 = tanh(h/2tau)/tau.
struct OUBridge {
    double p;  ///< weight of X_0
    double q;  ///< weight of X_h (equal to p: the OU bridge is time-symmetric)
    double sd; ///< conditional standard deviation [s^-1/2]
};

/// Law of (X, V, U) over h for tau > 0 [s], relaxation tauL in (0, +inf] [s]
/// (+inf: no drag), amplitude a > 0 [m s^-3/2] and h > 0 [s].
/// Throws std::invalid_argument for non-positive or non-finite tau, amplitude or
/// h, and for NaN or non-positive relaxation.
ColoredSlideLaw colored_slide_law(double tau, double relaxation, double amplitude, double h);

/// Law of (X, V, U) over h within one piece of a piecewise-affine drift law
/// (drift_law.hpp): V's own rate is the piece's slope db/dv [s^-1], of either
/// sign (colored_slide_law is the case slope = -1/relaxation). Throws
/// std::invalid_argument for non-positive or non-finite tau, amplitude or h,
/// and for a non-finite slope.
ColoredSlideLaw colored_piece_law(double tau, double slope, double amplitude, double h);

/// Bridge of (X, V, U) at the midpoint of a step of length h within one piece
/// (arguments as for colored_piece_law). Computed in long double where slope
/// h is in [-64, 0.5] (measured: 1.2e-12 relative at worst, in an entry that
/// nearly cancels, 1e-14 elsewhere), in 50 digits beyond, as
/// colored_slide_bridge (0.2 to 0.6 ms; long double is 40 times faster).
ColoredSlideBridge colored_piece_bridge(double tau, double slope, double amplitude, double h);

/// Law of (V, U) over h with white noise of intensity noise > 0 [m^2 s^-3].
WhiteSlideLaw white_slide_law(double relaxation, double noise, double h);

/// Bridge of (X, V, U) at the midpoint of a step of length h (arguments as for
/// colored_slide_law).
ColoredSlideBridge colored_slide_bridge(double tau, double relaxation, double amplitude, double h);

/// Bridge of (V, U) at the midpoint of a step of length h (as white_slide_law).
WhiteSlideBridge white_slide_bridge(double relaxation, double noise, double h);

/// OU bridge at the midpoint of a step of length h > 0 for tau > 0.
OUBridge ou_bridge(double tau, double h);

/// (x_out, v_out, u_out) = m (x, v, u) + g c + chol (n0, n1, n2): the sliding
/// step from (X, V, U) with constant c and the normals n0, n1, n2.
STICKSLIP_HD inline void apply(const ColoredSlideLaw& law, double x, double v, double u, double c, double n0,
                               double n1, double n2, double& x_out, double& v_out, double& u_out) {
    // Written out (the sums in the order of the lower-triangular rows, from
    // 0.0) on scalars, so that the SIMD lanes of event_lanes.cpp vectorise it.
    const auto& m = law.m;
    const auto& l = law.chol;
    const double r0 = 0.0 + m[0][0] * x + law.g[0] * c + l[0][0] * n0;
    const double r1 = 0.0 + m[1][0] * x + m[1][1] * v + law.g[1] * c + l[1][0] * n0 + l[1][1] * n1;
    const double r2 = 0.0 + m[2][0] * x + m[2][1] * v + m[2][2] * u + law.g[2] * c + l[2][0] * n0 + l[2][1] * n1 +
                      l[2][2] * n2;
    x_out = r0;
    v_out = r1;
    u_out = r2;
}

/// out = m z0 + g c + chol n, z0 = (X, V, U). out may alias z0.
STICKSLIP_HD inline void apply(const ColoredSlideLaw& law, const double z0[3], double c, const double n[3],
                               double out[3]) {
    apply(law, z0[0], z0[1], z0[2], c, n[0], n[1], n[2], out[0], out[1], out[2]);
}

/// out = m z0 + g c + chol n. out may alias z0.
STICKSLIP_HD inline void apply(const WhiteSlideLaw& law, const double z0[2], double c, const double n[2],
                               double out[2]) {
    double res[2];
    for (int i = 0; i < 2; ++i) {
        double s = 0.0;
        for (int j = 0; j <= i; ++j) s += law.m[i][j] * z0[j];
        s += law.g[i] * c;
        for (int j = 0; j <= i; ++j) s += law.chol[i][j] * n[j];
        res[i] = s;
    }
    for (int i = 0; i < 2; ++i) out[i] = res[i];
}

/// Midpoint state: out = p z0 + q zh + r c + chol n. out may alias z0 or zh.
STICKSLIP_HD inline void apply(const ColoredSlideBridge& b, const double z0[3], const double zh[3], double c,
                               const double n[3], double out[3]) {
    double res[3];
    for (int i = 0; i < 3; ++i) {
        double s = 0.0;
        for (int j = 0; j < 3; ++j) s += b.p[i][j] * z0[j];
        for (int j = 0; j < 3; ++j) s += b.q[i][j] * zh[j];
        s += b.r[i] * c;
        for (int j = 0; j <= i; ++j) s += b.chol[i][j] * n[j];
        res[i] = s;
    }
    for (int i = 0; i < 3; ++i) out[i] = res[i];
}

/// Midpoint state: out = p z0 + q zh + r c + chol n. out may alias z0 or zh.
STICKSLIP_HD inline void apply(const WhiteSlideBridge& b, const double z0[2], const double zh[2], double c,
                               const double n[2], double out[2]) {
    double res[2];
    for (int i = 0; i < 2; ++i) {
        double s = 0.0;
        for (int j = 0; j < 2; ++j) s += b.p[i][j] * z0[j];
        for (int j = 0; j < 2; ++j) s += b.q[i][j] * zh[j];
        s += b.r[i] * c;
        for (int j = 0; j <= i; ++j) s += b.chol[i][j] * n[j];
        res[i] = s;
    }
    for (int i = 0; i < 2; ++i) out[i] = res[i];
}

/// Midpoint OU state: p x0 + q xh + sd n.
STICKSLIP_HD inline double apply(const OUBridge& b, double x0, double xh, double n) {
    return b.p * x0 + b.q * xh + b.sd * n;
}

namespace detail {
/// The construction switches from a Taylor series to the divided-difference
/// recursion when a cluster of scaled rates (h times sums of 1/tau, 1/tauL, 0)
/// spreads wider than this. Exposed so that the tests can probe both sides.
inline constexpr double phase_law_series_spread = 1.0;
} // namespace detail

} // namespace stickslip
