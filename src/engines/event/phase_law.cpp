// SPDX-License-Identifier: BSD-3-Clause
// Exact Gaussian step and midpoint-bridge laws within one phase (phase_law.hpp).
//
// Method, and why. The naive closed forms are sums of exponentials in the rates
// 1/tau, 1/tauL and 0 with O(1) terms whose sum is O(h^5) (Var U) for small h,
// and they have removable singularities at tauL = tau and tauL = inf; a case
// split per regime would need a dozen series, each with its own switch point.
// Instead we use the structure of A: it is lower bidiagonal with diagonal
// (-1/tau, -1/tauL, 0) (non-positive for the affine law; a piece of a drift
// law puts its slope, of either sign, in place of -1/tauL) and non-negative
// sub-diagonal (a, 1). For such
// a matrix every entry of e^{Ar} is a sum over the paths of its graph of
// (product of the couplings on the path) x (divided difference of exp over the
// diagonal entries visited), and so is every entry of the Kronecker square
// e^{(A (+) A) r} = e^{Ar} (x) e^{Ar}, whose graph is again acyclic. Hence
//   M_ij = w_j..w_{i-1} h^{i-j} E[h lam_j, ..., h lam_i],
//   g_i  = w_1..w_{i-1} h^i E[h lam_1, ..., h lam_i, 0]               (c drives V),
//   S_ij = b^2 (w..)(w..) h^{i+j+1} sum_{paths (0,0)->(i,j)} E[h (lam_p + lam_q) along the path, 0],
// (0-based indices; the extra point 0 is the integral over r), where
// E[z_1..z_n] is the divided difference of exp. Every term is positive, so
// nothing cancels between terms and the relative accuracy of every entry is
// that of the divided differences, for any h, tau, tauL: the confluent cases
// (tauL = tau, tauL = inf, h -> 0) need no special formula at all.
//
// The divided differences of exp (ExpDividedDifference) are computed stably:
// the points are sorted; a cluster spreading by at most
// detail::phase_law_series_spread = 1 is summed as the Taylor series
//   E[z_1..z_n] = e^{z_1} sum_{m >= 0} h_m(z - z_1) / (m + n - 1)!
// (h_m the complete homogeneous symmetric polynomials, |z - z_1| <= 1, so at
// most a factor e^2 of cancellation inside it); a wider set by the recursion
// (E[z_1..z_{n-1}] - E[z_2..z_n]) / (z_1 - z_n) between two positive numbers
// whose ratio is at least about e^{1/(n-1)} there, i.e. a loss of a few bits
// per level at worst (n <= 6 here). The laws are computed in long double
// (64-bit significand on x86: three spare digits for those bits) and rounded:
// measured 1e-16 relative against the moment ODEs in 50 digits; 1e-14 where
// long double is a double.
//
// The bridges condition the joint Gaussian of (Z_{h/2}, Z_h) given Z_0, and the
// covariance conditioned on can be nearly singular even after scaling: with
// h >> tauL the velocity is slaved to the noise, and the smallest eigenvalue
// of the correlation matrix of Z_h is about tauL/(2h) (2.5e-9 at h/tauL = 1e8),
// so conditioning amplifies the rounding of its inputs by h/tauL: in long
// double about 1e-10 would be left there, and less beyond. The bridges are
// therefore computed from the same path sums evaluated in 50 significant
// digits (Boost.Multiprecision), and the conditioning is done in variables
// scaled by the square root of the diagonal of S(h) (X ~ h^1/2, V ~ h^3/2,
// U ~ h^5/2 for small h), so that the matrices solved are correlation
// matrices whatever the magnitude of h. Entries that vanish identically come
// out as exact zeros (see snap). 0.2 to 0.6 ms per bridge (a law: a few
// microseconds), called once per refinement depth.
#include "stickslip/kernels/phase_law.hpp"

#include <algorithm>
#include <bit>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "stickslip/number_text.hpp"

namespace stickslip {
namespace {

using Wide = long double;
using Big = boost::multiprecision::cpp_bin_float_50;

// Divided difference of exp over n <= K points given with their exponentials.
template <class T, int K>
class ExpDividedDifference {
public:
    ExpDividedDifference(const T* z, const T* ez, int n) : n_(n) {
        for (int i = 0; i < n; ++i) {
            z_[i] = z[i];
            ez_[i] = ez[i];
            for (int j = 0; j < n; ++j) known_[i][j] = false;
        }
        // Descending order: contiguous ranges are then the clusters.
        for (int i = 1; i < n; ++i)
            for (int j = i; j > 0 && z_[j - 1] < z_[j]; --j) {
                std::swap(z_[j - 1], z_[j]);
                std::swap(ez_[j - 1], ez_[j]);
            }
    }

    T value() { return eval(0, n_ - 1); }

private:
    T eval(int i, int j) {
        if (known_[i][j]) return memo_[i][j];
        T v;
        if (i == j)
            v = ez_[i];
        else if (z_[i] - z_[j] <= T(detail::phase_law_series_spread))
            v = series(i, j);
        else
            v = (eval(i, j - 1) - eval(i + 1, j)) / (z_[i] - z_[j]);
        known_[i][j] = true;
        memo_[i][j] = v;
        return v;
    }

    // e^{z_i} sum_m h_m(y) / (m + n - 1)!, y_l = z_{i+l} - z_i in [-s, 0], s <= 1.
    T series(int i, int j) const {
        const int n = j - i + 1;
        T y[K];
        T hm[K]; // hm[l] = h_m(y_0, ..., y_l)
        for (int l = 0; l < n; ++l) {
            y[l] = z_[i + l] - z_[i];
            hm[l] = T(1);
        }
        const T spread = z_[i] - z_[j];
        T coef = T(1);
        for (int l = 2; l < n; ++l) coef /= l; // 1/(n-1)!
        T sum = coef;
        // |h_m(y)| / (m+n-1)! <= s^m / (m! (n-1)!) while the sum is >= e^{-s} / (n-1)!:
        // stop once s^m / m! is below the working precision.
        const T eps = std::numeric_limits<T>::epsilon() / 16;
        T bound = T(1);
        for (int m = 1; m < 400; ++m) {
            T prev = T(0); // h_m of no variables, m >= 1
            for (int l = 0; l < n; ++l) {
                hm[l] = prev + y[l] * hm[l];
                prev = hm[l];
            }
            coef /= (m + n - 1);
            sum += coef * hm[n - 1];
            bound = bound * spread / m;
            if (bound < eps) break;
        }
        return ez_[i] * sum;
    }

    int n_;
    T z_[K];
    T ez_[K];
    T memo_[K][K];
    bool known_[K][K];
};

// dZ = (A Z + c e_input) dt + sqrt(b2) e_noisy dW with A lower bidiagonal:
// A[i][i] = lam[i] (<= 0 but for a drift law's piece that pushes V away),
// A[i+1][i] = w[i] >= 0.
template <class T, int N>
struct Chain {
    T lam[N];
    T w[N]; // w[N-1] unused
    int input;
    int noisy;
    T b2;
};

template <class T, int N>
struct Moments {
    T m[N][N];
    T g[N];
    T s[N][N];
};

template <class T, int N>
Moments<T, N> moments(const Chain<T, N>& ch, const T& h) {
    using std::exp;
    constexpr int K = 2 * N; // longest path of A (+) A plus the integration point
    Moments<T, N> out{};
    T z1[N], e1[N], z2[N][N], e2[N][N];
    for (int p = 0; p < N; ++p) {
        z1[p] = h * ch.lam[p];
        e1[p] = exp(z1[p]);
    }
    for (int p = 0; p < N; ++p)
        for (int q = 0; q < N; ++q) {
            z2[p][q] = z1[p] + z1[q];
            e2[p][q] = e1[p] * e1[q]; // one rounding; exp is the costly part in 50 digits
        }
    auto couplings = [&](int from, int to) { // w_from ... w_{to-1}
        T c = T(1);
        for (int l = from; l < to; ++l) c *= ch.w[l];
        return c;
    };
    auto power = [&](int n) {
        T c = T(1);
        for (int l = 0; l < n; ++l) c *= h;
        return c;
    };
    T z[K], ez[K];
    // M = e^{Ah}.
    for (int i = 0; i < N; ++i)
        for (int j = 0; j <= i; ++j) {
            for (int l = j; l <= i; ++l) {
                z[l - j] = z1[l];
                ez[l - j] = e1[l];
            }
            ExpDividedDifference<T, K> dd(z, ez, i - j + 1);
            out.m[i][j] = couplings(j, i) * power(i - j) * dd.value();
        }
    // g = int_0^h e^{Ar} e_input dr.
    for (int i = ch.input; i < N; ++i) {
        int n = 0;
        for (int l = ch.input; l <= i; ++l, ++n) {
            z[n] = z1[l];
            ez[n] = e1[l];
        }
        z[n] = T(0);
        ez[n] = T(1);
        ExpDividedDifference<T, K> dd(z, ez, n + 1);
        out.g[i] = couplings(ch.input, i) * power(n) * dd.value();
    }
    // S_ij = b2 int_0^h [e^{Ar}]_{ik} [e^{Ar}]_{jk} dr, k = noisy: paths of A (+) A.
    const int k = ch.noisy;
    for (int i = k; i < N; ++i)
        for (int j = k; j <= i; ++j) {
            const int up = i - k, right = j - k, moves = up + right;
            T sum = T(0);
            for (unsigned mask = 0; mask < (1u << moves); ++mask) {
                if (std::popcount(mask) != up) continue;
                int p = k, q = k, n = 0;
                z[n] = z2[p][q];
                ez[n++] = e2[p][q];
                for (int step = 0; step < moves; ++step) {
                    if (mask & (1u << step))
                        ++p;
                    else
                        ++q;
                    z[n] = z2[p][q];
                    ez[n++] = e2[p][q];
                }
                z[n] = T(0);
                ez[n++] = T(1);
                ExpDividedDifference<T, K> dd(z, ez, n);
                sum += dd.value();
            }
            out.s[i][j] = ch.b2 * couplings(k, i) * couplings(k, j) * power(moves + 1) * sum;
            out.s[j][i] = out.s[i][j];
        }
    return out;
}

// Lower Cholesky factor; a pivot at or below rounding level (rank loss, or a
// zero variance) gives a zero column instead of a NaN.
template <class T, int N>
void cholesky(const T (&a)[N][N], T (&l)[N][N]) {
    using std::sqrt;
    const T tol = 16 * std::numeric_limits<T>::epsilon();
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) l[i][j] = T(0);
    for (int j = 0; j < N; ++j) {
        T d = a[j][j];
        for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
        if (!(d > tol * a[j][j])) continue; // column stays zero
        l[j][j] = sqrt(d);
        for (int i = j + 1; i < N; ++i) {
            T s = a[i][j];
            for (int k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
            l[i][j] = s / l[j][j];
        }
    }
}

template <class T, int N>
struct Bridge {
    T p[N][N], q[N][N], r[N], c[N][N];
    T cscale[N][N]; // magnitude of the terms of c (scaled), for snap
};

template <class T>
T magnitude(const T& x) {
    return x < 0 ? T(-x) : x;
}

// x is a sum of terms of total magnitude `scale`; a remainder below 1e-36 of
// that (far below double resolution, far above the 1e-50 of the working
// precision times any conditioning met here) is an exact cancellation. In
// long double (a piece's bridge with slope h in [-64, 0.5], colored_piece_bridge)
// the rounding left by a cancellation is up to about 64 eps of the scale, so
// there the line is 1000 eps (1.1e-16 with x86's 64-bit significand, 2.2e-13
// where long double is a double): what it zeroes is at or below a double's
// resolution of the sum.
template <class T>
T snap(const T& x, const T& scale) {
    const T line = std::is_same_v<T, Wide> ? T(1000) * std::numeric_limits<Wide>::epsilon() : T(1e-36);
    return magnitude(x) <= line * scale ? T(0) : x;
}

// Midpoint bridge from two half steps, conditioned in scaled variables.
template <class T, int N>
Bridge<T, N> midpoint_bridge(const Chain<T, N>& ch, const T& h) {
    using std::sqrt;
    const Moments<T, N> half = moments(ch, T(h / 2));
    const auto& m1 = half.m;
    const auto& s1 = half.s;
    const auto& g1 = half.g;
    // The whole step as the composition of the two halves: the joint law.
    T mh[N][N]{}, gh[N]{}, ms1[N][N]{}, sh[N][N]{};
    for (int i = 0; i < N; ++i) {
        gh[i] = g1[i];
        for (int j = 0; j < N; ++j) {
            for (int k = 0; k < N; ++k) {
                mh[i][j] += m1[i][k] * m1[k][j];
                ms1[i][j] += m1[i][k] * s1[k][j]; // M1 S1 = Cov(Z_h, Z_{h/2})
            }
            gh[i] += m1[i][j] * g1[j];
        }
    }
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            sh[i][j] = s1[i][j];
            for (int k = 0; k < N; ++k) sh[i][j] += ms1[i][k] * m1[j][k];
        }
    T d[N];
    for (int i = 0; i < N; ++i) d[i] = sqrt(sh[i][i]);
    // Scaled: hat(Y)_ij = Y_ij / (d_i d_j) for covariances, Y_ij d_j / d_i for maps.
    T shs[N][N], l[N][N], inv[N][N], xs[N][N], m1s[N][N], mhs[N][N];
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            shs[i][j] = sh[i][j] / (d[i] * d[j]);
            xs[i][j] = ms1[i][j] / (d[i] * d[j]); // hat(M1 S1) = hat(Cov(Z_h, Z_{h/2}))
            m1s[i][j] = m1[i][j] * d[j] / d[i];
            mhs[i][j] = mh[i][j] * d[j] / d[i];
        }
    // hat(Sh)^{-1}, by Cholesky solves of the unit vectors (a correlation matrix).
    cholesky(shs, l);
    for (int col = 0; col < N; ++col) {
        T b[N];
        for (int i = 0; i < N; ++i) b[i] = i == col ? T(1) : T(0);
        for (int i = 0; i < N; ++i) {
            for (int k = 0; k < i; ++k) b[i] -= l[i][k] * b[k];
            b[i] = l[i][i] > 0 ? T(b[i] / l[i][i]) : T(0); // rank loss: no information there
        }
        for (int i = N - 1; i >= 0; --i) {
            for (int k = i + 1; k < N; ++k) b[i] -= l[k][i] * b[k];
            b[i] = l[i][i] > 0 ? T(b[i] / l[i][i]) : T(0);
        }
        for (int i = 0; i < N; ++i) inv[i][col] = b[i];
    }
    // Gain hat(K) = hat(S1 M1^T) hat(Sh)^{-1}; Q = K, P = M1 - K Mh, r = g1 - K gh,
    // C = S1 - K (M1 S1). Each entry is a sum whose terms' magnitudes are tracked:
    // some entries vanish identically (coloured: Cov(V, U) and the V entry of r
    // for every drag, Cov(X, V) and the weight of U_0 on X without drag; white:
    // Cov(V, U) and r) and would otherwise come out as rounding residue ~1e-50
    // of their terms, with a sign that flips from one h to the next; they are
    // set to an exact 0 instead.
    T k[N][N], ks[N][N];
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            k[i][j] = T(0);
            ks[i][j] = T(0);
            for (int t = 0; t < N; ++t) {
                k[i][j] += xs[t][i] * inv[t][j];
                ks[i][j] += magnitude(xs[t][i]) * magnitude(inv[t][j]);
            }
            k[i][j] = snap(k[i][j], ks[i][j]);
        }
    // The terms' magnitudes propagate through K by ks, not by |K|.
    Bridge<T, N> out{};
    for (int i = 0; i < N; ++i) {
        T rs = g1[i] / d[i], rm = magnitude(rs);
        for (int t = 0; t < N; ++t) {
            rs -= k[i][t] * (gh[t] / d[t]);
            rm += ks[i][t] * magnitude(gh[t] / d[t]);
        }
        out.r[i] = snap(rs, rm) * d[i];
        for (int j = 0; j < N; ++j) {
            out.q[i][j] = k[i][j] * d[i] / d[j];
            T ps = m1s[i][j], pm = magnitude(ps);
            T cs = s1[i][j] / (d[i] * d[j]), cm = magnitude(cs);
            for (int t = 0; t < N; ++t) {
                ps -= k[i][t] * mhs[t][j];
                pm += ks[i][t] * magnitude(mhs[t][j]);
                cs -= k[i][t] * xs[t][j];
                cm += ks[i][t] * magnitude(xs[t][j]);
            }
            out.p[i][j] = snap(ps, pm) * d[i] / d[j];
            out.c[i][j] = cs;
            out.cscale[i][j] = cm;
        }
    }
    for (int i = 0; i < N; ++i)
        for (int j = 0; j <= i; ++j) {
            const T sym = snap(T((out.c[i][j] + out.c[j][i]) / 2), std::max(out.cscale[i][j], out.cscale[j][i]));
            out.c[i][j] = sym * d[i] * d[j];
            out.c[j][i] = out.c[i][j];
        }
    return out;
}

template <class T>
Chain<T, 3> colored_chain(double tau, double relaxation, double amplitude) {
    Chain<T, 3> ch{};
    const T alpha = T(1) / T(tau);
    ch.lam[0] = -alpha;
    ch.lam[1] = std::isinf(relaxation) ? T(0) : -(T(1) / T(relaxation));
    ch.lam[2] = T(0);
    ch.w[0] = T(amplitude);
    ch.w[1] = T(1);
    ch.input = 1;
    ch.noisy = 0;
    ch.b2 = 2 * alpha * alpha; // (sqrt(2)/tau)^2
    return ch;
}

// The chain of a piece of a drift law: V's own rate is the piece's slope
// db/dv, of either sign (a positive slope makes the diagonal entry positive;
// every path sum is still a sum of positive terms, since the divided
// differences of exp are positive at any real points).
template <class T>
Chain<T, 3> colored_piece_chain(double tau, double slope, double amplitude) {
    Chain<T, 3> ch = colored_chain<T>(tau, HUGE_VAL, amplitude);
    ch.lam[1] = T(slope);
    return ch;
}

template <class T>
Chain<T, 2> white_chain(double relaxation, double noise) {
    Chain<T, 2> ch{};
    ch.lam[0] = std::isinf(relaxation) ? T(0) : -(T(1) / T(relaxation));
    ch.lam[1] = T(0);
    ch.w[0] = T(1);
    ch.input = 0;
    ch.noisy = 0;
    ch.b2 = T(noise);
    return ch;
}

/// -slope h up to which a piece that pulls V back has its bridge in long double.
constexpr double kPieceBridgeLongDouble = 64.0;
/// slope h up to which a piece that pushes V away has its bridge in long double.
constexpr double kPieceBridgeLongDoubleGrowth = 0.5;

void require_positive(double x, const char* name) {
    if (!(std::isfinite(x) && x > 0))
        throw std::invalid_argument(std::string("phase law: ") + name + " must be positive and finite, got " +
                                    number_text::general(x));
}

void require_slope(double x) {
    if (!std::isfinite(x))
        throw std::invalid_argument("phase law: a piece's slope must be finite, got " + number_text::general(x));
}

void require_relaxation(double x) {
    if (!(x > 0)) // NaN fails too; +inf (no drag) passes
        throw std::invalid_argument("phase law: relaxation must be positive or +inf, got " + number_text::general(x));
}

template <class T, int N>
void round_matrix(const T (&a)[N][N], double (&out)[N][N]) {
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) out[i][j] = static_cast<double>(a[i][j]);
}

template <class T, int N>
void round_vector(const T (&a)[N], double (&out)[N]) {
    for (int i = 0; i < N; ++i) out[i] = static_cast<double>(a[i]);
}

template <class Law, class T, int N>
void fill_law(const Moments<T, N>& mo, double h, Law& law) {
    T l[N][N];
    cholesky(mo.s, l);
    round_matrix(mo.m, law.m);
    round_vector(mo.g, law.g);
    round_matrix(mo.s, law.cov);
    round_matrix(l, law.chol);
    law.h = h;
}

template <class Out, class T, int N>
void fill_bridge(const Bridge<T, N>& b, double h, Out& out) {
    T l[N][N];
    cholesky(b.c, l);
    round_matrix(b.p, out.p);
    round_matrix(b.q, out.q);
    round_vector(b.r, out.r);
    round_matrix(b.c, out.cov);
    round_matrix(l, out.chol);
    out.h = h;
}

} // namespace

namespace {

void require_colored(double tau, double amplitude, double h) {
    require_positive(tau, "tau");
    require_positive(amplitude, "amplitude");
    require_positive(h, "h");
}

ColoredSlideLaw colored_law(const Chain<Wide, 3>& ch, double h) {
    ColoredSlideLaw law{};
    fill_law(moments(ch, Wide(h)), h, law);
    return law;
}

template <class T>
ColoredSlideBridge colored_bridge(const Chain<T, 3>& ch, double h) {
    ColoredSlideBridge out{};
    fill_bridge(midpoint_bridge(ch, T(h)), h, out);
    return out;
}

} // namespace

ColoredSlideLaw colored_slide_law(double tau, double relaxation, double amplitude, double h) {
    require_colored(tau, amplitude, h);
    require_relaxation(relaxation);
    return colored_law(colored_chain<Wide>(tau, relaxation, amplitude), h);
}

WhiteSlideLaw white_slide_law(double relaxation, double noise, double h) {
    require_relaxation(relaxation);
    require_positive(noise, "noise");
    require_positive(h, "h");
    WhiteSlideLaw law{};
    fill_law(moments(white_chain<Wide>(relaxation, noise), Wide(h)), h, law);
    return law;
}

ColoredSlideBridge colored_slide_bridge(double tau, double relaxation, double amplitude, double h) {
    require_colored(tau, amplitude, h);
    require_relaxation(relaxation);
    return colored_bridge(colored_chain<Big>(tau, relaxation, amplitude), h);
}

ColoredSlideLaw colored_piece_law(double tau, double slope, double amplitude, double h) {
    require_colored(tau, amplitude, h);
    require_slope(slope);
    return colored_law(colored_piece_chain<Wide>(tau, slope, amplitude), h);
}

ColoredSlideBridge colored_piece_bridge(double tau, double slope, double amplitude, double h) {
    require_colored(tau, amplitude, h);
    require_slope(slope);
    // The conditioning amplifies rounding by about |slope| h where the piece
    // pulls V back (see the top) and by about e^{2 slope h} where it pushes
    // V away: long double, at a fortieth of the 50-digit cost (a law of a
    // thousand pieces pays it 17 times per piece), is used for slope h in
    // [-64, 0.5], where it was measured against a 100-digit reference
    // (tests/unit/phase_law_test.cpp): 1.2e-12 relative at worst, in Cov(X, V),
    // an entry that nearly cancels where |slope h| is small (its error is
    // 1e-19 of its terms); 1e-14 or better elsewhere. At slope h = 10, long
    // double would leave 4e-8.
    const double rate = slope * h;
    if (rate >= -kPieceBridgeLongDouble && rate <= kPieceBridgeLongDoubleGrowth)
        return colored_bridge(colored_piece_chain<Wide>(tau, slope, amplitude), h);
    return colored_bridge(colored_piece_chain<Big>(tau, slope, amplitude), h);
}

WhiteSlideBridge white_slide_bridge(double relaxation, double noise, double h) {
    require_relaxation(relaxation);
    require_positive(noise, "noise");
    require_positive(h, "h");
    WhiteSlideBridge out{};
    fill_bridge(midpoint_bridge(white_chain<Big>(relaxation, noise), Big(h)), h, out);
    return out;
}

OUBridge ou_bridge(double tau, double h) {
    require_positive(tau, "tau");
    require_positive(h, "h");
    // p = q = sinh(x)/sinh(2x) = e^{-x} / (1 + e^{-2x}), var = tanh(x)/tau, x = h/(2 tau):
    // in this form nothing overflows for large x nor cancels for small x. Long
    // double because e^{-x} amplifies the rounding of h/tau by x (up to ~700).
    const Wide x = Wide(h) / Wide(tau) / 2;
    const Wide e = std::exp(-x);
    const Wide e2 = std::exp(-2 * x);
    OUBridge b{};
    b.p = static_cast<double>(e / (1 + e2));
    b.q = b.p;
    b.sd = static_cast<double>(std::sqrt(-std::expm1(-2 * x) / (1 + e2) / Wide(tau)));
    return b;
}

} // namespace stickslip
