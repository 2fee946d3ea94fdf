// SPDX-License-Identifier: BSD-3-Clause
// Exact step and midpoint-bridge laws within one phase (phase_law.hpp).
//
// References, all independent of the library's path sums of divided differences:
//  * the moment ODEs dM/dt = A M, dg/dt = A g + e_c, dS/dt = A S + S A^T + B B^T
//    from 0, integrated in 50 significant digits (Boost.Multiprecision) by the
//    Taylor method (order adaptive, up to 200, each entry converged to 1e-45
//    relative) with a fixed step dt = h / 2^k, max rate * dt <= 1/8. The ODE is
//    linear and autonomous, so its one-step map is the same affine map at every
//    step and the 2^k steps are composed by k squarings of it (an identity in
//    exact arithmetic; 2^k steps for the price of k: h/tau = 1e8 needs 2^30);
//  * the bridge: the joint Gaussian of (Z_{h/2}, Z_h) given Z_0 built from two
//    reference half steps (mean M1 Z0 + g1 c and M1^2 Z0 + (M1 g1 + g1) c;
//    covariance blocks S1, S1 M1^T, M1 S1 M1^T + S1), conditioned by the
//    textbook formula (Gauss-Jordan inverse) in 100 digits;
//  * closed forms in 100 digits: the white law with and without drag, the OU
//    marginal of the coloured law, the textbook OU bridge.
// Tolerances are relative, per entry, on every entry that is not below the
// double underflow range (those must come out below it too). Some bridge
// entries vanish identically (e.g. Cov(V, U) given both ends); the reference
// finds them as sums cancelling below 1e-30 of their terms, and the library's
// value must be below that too (it returns an exact 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "stickslip/kernels/phase_law.hpp"

namespace ss = stickslip;

namespace {

using Big = boost::multiprecision::cpp_bin_float_50;
using Huge = boost::multiprecision::cpp_bin_float_100;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTau = 0.01;        // [s]
constexpr double kAmplitude = 0.92;  // [m s^-3/2], sqrt(noise/2) for noise 1.69
constexpr double kNoise = 1.3;       // [m^2 s^-3] (white)
constexpr double kSameAsTau = -1.0;  // marker in the drag list: tauL = tau

// ---------------------------------------------------------------- reference

// dZ = (A Z + e c) dt + noise with covariance rate Q.
template <class T, int N>
struct System {
    T a[N][N]{};
    T e[N]{};
    T q[N][N]{};
};

template <class T, int N>
struct Moments {
    T m[N][N]{};
    T g[N]{};
    T s[N][N]{};
};

template <class T>
T tabs(const T& x) {
    return x < 0 ? T(-x) : x;
}

// Taylor method for the moment ODEs from the zero state over dt, then 2^k steps.
template <class T, int N>
Moments<T, N> integrate(const System<T, N>& sys, const T& h) {
    T rate = 0;
    for (int i = 0; i < N; ++i) rate = std::max(rate, tabs(sys.a[i][i]));
    T dt = h;
    int k = 0;
    while (rate * dt > T(1) / 8) {
        dt /= 2;
        ++k;
    }
    Moments<T, N> st;
    T mt[N][N]{}, gt[N]{}, st_[N][N]{};
    for (int i = 0; i < N; ++i) {
        mt[i][i] = 1;
        st.m[i][i] = 1;
        gt[i] = sys.e[i] * dt;
        st.g[i] = gt[i];
        for (int j = 0; j < N; ++j) {
            st_[i][j] = sys.q[i][j] * dt;
            st.s[i][j] = st_[i][j];
        }
    }
    const T tol = T(1e-45);
    for (int n = 1; n < 200; ++n) {
        T nm[N][N]{}, ng[N]{}, ns[N][N]{};
        for (int i = 0; i < N; ++i) {
            for (int j = 0; j < N; ++j)
                for (int l = 0; l < N; ++l) {
                    nm[i][j] += sys.a[i][l] * mt[l][j];
                    ns[i][j] += sys.a[i][l] * st_[l][j] + st_[i][l] * sys.a[j][l];
                }
            for (int l = 0; l < N; ++l) ng[i] += sys.a[i][l] * gt[l];
        }
        bool converged = n > 2 * N + 2;
        for (int i = 0; i < N; ++i) {
            ng[i] *= dt / (n + 1);
            gt[i] = ng[i];
            st.g[i] += gt[i];
            if (tabs(gt[i]) > tol * tabs(st.g[i])) converged = false;
            for (int j = 0; j < N; ++j) {
                nm[i][j] *= dt / n;
                ns[i][j] *= dt / (n + 1);
                mt[i][j] = nm[i][j];
                st_[i][j] = ns[i][j];
                st.m[i][j] += mt[i][j];
                st.s[i][j] += st_[i][j];
                if (tabs(mt[i][j]) > tol * tabs(st.m[i][j]) || tabs(st_[i][j]) > tol * tabs(st.s[i][j]))
                    converged = false;
            }
        }
        if (converged) break;
    }
    for (int step = 0; step < k; ++step) {
        Moments<T, N> nx;
        for (int i = 0; i < N; ++i) {
            nx.g[i] = st.g[i];
            for (int j = 0; j < N; ++j) {
                for (int l = 0; l < N; ++l) nx.m[i][j] += st.m[i][l] * st.m[l][j];
                nx.g[i] += st.m[i][j] * st.g[j];
            }
        }
        T ms[N][N]{};
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j)
                for (int l = 0; l < N; ++l) ms[i][j] += st.m[i][l] * st.s[l][j];
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) {
                nx.s[i][j] = st.s[i][j];
                for (int l = 0; l < N; ++l) nx.s[i][j] += ms[i][l] * st.m[j][l];
            }
        st = nx;
    }
    return st;
}

template <class T>
System<T, 3> colored_system(double tau, double relaxation, double amplitude) {
    System<T, 3> s;
    const T alpha = T(1) / T(tau);
    s.a[0][0] = -alpha;
    s.a[1][0] = T(amplitude);
    s.a[1][1] = std::isinf(relaxation) ? T(0) : T(-(T(1) / T(relaxation)));
    s.a[2][1] = 1;
    s.e[1] = 1;
    s.q[0][0] = 2 * alpha * alpha;
    return s;
}

template <class T>
System<T, 2> white_system(double relaxation, double noise) {
    System<T, 2> s;
    s.a[0][0] = std::isinf(relaxation) ? T(0) : T(-(T(1) / T(relaxation)));
    s.a[1][0] = 1;
    s.e[0] = 1;
    s.q[0][0] = T(noise);
    return s;
}

template <class T, int N>
struct Bridge {
    T p[N][N]{}, q[N][N]{}, r[N]{}, c[N][N]{};
    // Sum of the magnitudes of the terms of each entry: an entry below 1e-30 of
    // it is an exact cancellation (a zero of the exact bridge), not a value.
    T ps[N][N]{}, qs[N][N]{}, rs[N]{}, cs[N][N]{};
    bool scaled = false;
};

// Gauss-Jordan inverse with partial pivoting.
template <class T, int N>
void invert(const T (&a)[N][N], T (&inv)[N][N]) {
    T w[N][2 * N];
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            w[i][j] = a[i][j];
            w[i][N + j] = i == j ? T(1) : T(0);
        }
    for (int col = 0; col < N; ++col) {
        int piv = col;
        for (int i = col + 1; i < N; ++i)
            if (tabs(w[i][col]) > tabs(w[piv][col])) piv = i;
        for (int j = 0; j < 2 * N; ++j) std::swap(w[col][j], w[piv][j]);
        const T d = w[col][col];
        for (int j = 0; j < 2 * N; ++j) w[col][j] /= d;
        for (int i = 0; i < N; ++i) {
            if (i == col) continue;
            const T f = w[i][col];
            for (int j = 0; j < 2 * N; ++j) w[i][j] -= f * w[col][j];
        }
    }
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) inv[i][j] = w[i][N + j];
}

// Condition the joint law of (Z_{h/2}, Z_h) | Z_0 built from two half steps.
template <class T, int N>
Bridge<T, N> reference_bridge(const System<T, N>& sys, const T& h) {
    const Moments<T, N> half = integrate(sys, T(h / 2));
    T mh[N][N]{}, gh[N]{}, cross[N][N]{}, sh[N][N]{}, shi[N][N]{}, k[N][N]{};
    for (int i = 0; i < N; ++i) {
        gh[i] = half.g[i];
        for (int j = 0; j < N; ++j) {
            gh[i] += half.m[i][j] * half.g[j];
            for (int l = 0; l < N; ++l) {
                mh[i][j] += half.m[i][l] * half.m[l][j];
                cross[i][j] += half.s[i][l] * half.m[j][l]; // Cov(Z_{h/2}, Z_h) = S1 M1^T
            }
        }
    }
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            sh[i][j] = half.s[i][j];
            for (int l = 0; l < N; ++l) sh[i][j] += half.m[i][l] * cross[l][j];
        }
    invert(sh, shi);
    Bridge<T, N> b;
    b.scaled = true;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j)
            for (int l = 0; l < N; ++l) {
                k[i][j] += cross[i][l] * shi[l][j];
                b.qs[i][j] += tabs(T(cross[i][l] * shi[l][j]));
            }
    for (int i = 0; i < N; ++i) {
        b.r[i] = half.g[i];
        b.rs[i] = tabs(half.g[i]);
        for (int l = 0; l < N; ++l) {
            b.r[i] -= k[i][l] * gh[l];
            b.rs[i] += b.qs[i][l] * tabs(gh[l]); // K's terms, not |K|
        }
        for (int j = 0; j < N; ++j) {
            b.q[i][j] = k[i][j];
            b.p[i][j] = half.m[i][j];
            b.ps[i][j] = tabs(half.m[i][j]);
            b.c[i][j] = half.s[i][j];
            b.cs[i][j] = tabs(half.s[i][j]);
            for (int l = 0; l < N; ++l) {
                b.p[i][j] -= k[i][l] * mh[l][j];
                b.ps[i][j] += b.qs[i][l] * tabs(mh[l][j]);
                b.c[i][j] -= k[i][l] * cross[j][l];
                b.cs[i][j] += b.qs[i][l] * tabs(cross[j][l]);
            }
        }
    }
    return b;
}

// ---------------------------------------------------------------- comparison

// Relative error of a double against a high-precision reference. Exact zeros must
// be exact; references below the normal double range must come out below it.
template <class T>
double rel_err(double x, const T& ref) {
    if (!std::isfinite(x)) return kInf;
    if (ref == 0) return x == 0 ? 0.0 : kInf;
    if (tabs(ref) < T(1e-290)) return std::fabs(x) < 1e-280 ? 0.0 : kInf;
    return static_cast<double>(tabs(T(T(x) - ref) / ref));
}

struct Worst {
    double err = 0;
    std::string where;
    int zeros = 0; // bridge entries found to vanish identically
    void note(double e, const std::string& w) {
        if (!(e <= err)) { // NaN counts as worst
            err = e;
            where = w;
        }
    }
};

std::string fmt(double x) {
    std::ostringstream os;
    os.precision(3);
    os << x;
    return os.str();
}

std::string describe(double r, double rho) {
    return "h/tau=" + fmt(r) + " h/tauL=" + (rho == kSameAsTau ? std::string("h/tau") : fmt(rho));
}

double relaxation_for(double h, double rho) {
    if (rho == 0) return kInf;
    if (rho == kSameAsTau) return kTau;
    return h / rho;
}

template <int N, class T, class Law>
void compare_law(const Law& law, const Moments<T, N>& ref, const std::string& what, Worst& worst) {
    for (int i = 0; i < N; ++i) {
        worst.note(rel_err(law.g[i], ref.g[i]), what + " g[" + std::to_string(i) + "]");
        for (int j = 0; j < N; ++j) {
            // Appended piece by piece: GCC 12 warns (-Wrestrict, a false
            // positive, its bug 105651) on "literal" + std::string&& here.
            std::string ij = "[";
            ij += std::to_string(i);
            ij += "][";
            ij += std::to_string(j);
            ij += "]";
            worst.note(rel_err(law.m[i][j], ref.m[i][j]), what + " m" + ij);
            worst.note(rel_err(law.cov[i][j], ref.s[i][j]), what + " cov" + ij);
        }
    }
}

// skip_zeros: entries whose reference is exactly 0 are checked elsewhere (a
// closed form's zero is reached only to rounding by a computed bridge).
// Entries the reference finds to cancel exactly (below 1e-30 of their terms)
// must come out below 1e-30 of those terms (the library sets them to 0).
constexpr double kCancelled = 1e-30;

template <int N, class T, class Br>
void compare_bridge(const Br& b, const Bridge<T, N>& ref, const std::string& what, Worst& worst,
                    bool skip_zeros = false) {
    auto note = [&](double x, const T& y, const T& scale, const std::string& name) {
        if (skip_zeros && y == 0) return;
        if (ref.scaled && tabs(y) <= T(kCancelled) * scale) {
            ++worst.zeros;
            worst.note(T(tabs(T(x))) <= T(kCancelled) * scale ? 0.0 : kInf, what + " " + name + " (zero)");
            return;
        }
        worst.note(rel_err(x, y), what + " " + name);
    };
    for (int i = 0; i < N; ++i) {
        note(b.r[i], ref.r[i], ref.rs[i], "r[" + std::to_string(i) + "]");
        for (int j = 0; j < N; ++j) {
            // Appended piece by piece: GCC 12 warns (-Wrestrict, a false
            // positive, its bug 105651) on "literal" + std::string&& here.
            std::string ij = "[";
            ij += std::to_string(i);
            ij += "][";
            ij += std::to_string(j);
            ij += "]";
            note(b.p[i][j], ref.p[i][j], ref.ps[i][j], "p" + ij);
            note(b.q[i][j], ref.q[i][j], ref.qs[i][j], "q" + ij);
            note(b.cov[i][j], ref.c[i][j], ref.cs[i][j], "cov" + ij);
        }
    }
}

// Largest |chol chol^T - cov| / sqrt(cov_ii cov_jj), and the checks that chol is
// lower triangular with a non-negative diagonal.
template <int N, class Law>
double chol_residual(const Law& law) {
    double worst = 0;
    for (int i = 0; i < N; ++i) {
        if (!(law.chol[i][i] >= 0)) return kInf;
        for (int j = i + 1; j < N; ++j)
            if (law.chol[i][j] != 0) return kInf;
    }
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            long double s = 0;
            for (int k = 0; k < N; ++k) s += static_cast<long double>(law.chol[i][k]) * law.chol[j][k];
            const long double scale = std::sqrt(static_cast<long double>(law.cov[i][i]) * law.cov[j][j]);
            if (scale == 0) {
                if (s != 0 || law.cov[i][j] != 0) return kInf;
                continue;
            }
            worst = std::max(worst, static_cast<double>(std::fabs(s - law.cov[i][j]) / scale));
        }
    return worst;
}

template <class Law>
bool all_finite(const Law& law) {
    const double* p = reinterpret_cast<const double*>(&law);
    for (std::size_t i = 0; i < sizeof(Law) / sizeof(double); ++i)
        if (!std::isfinite(p[i])) return false;
    return true;
}

void report(const char* test, const Worst& w, double tol) {
    std::printf("[phase_law] %-44s worst rel. error %.2e (tolerance %.0e) at %s\n", test, w.err, tol, w.where.c_str());
}

const std::vector<double> kRatios = {1e-20, 1e-15, 1e-12, 1e-8, 1e-6, 1e-3, 0.1, 0.5, 1, 2, 10, 1e3, 1e5, 1e8, 1e12};
const std::vector<double> kDrags = {0, 1e-12, 1e-8, 1e-3, 1, 1e3, 1e8, 1e12, kSameAsTau}; // h/tauL; 0: tauL = inf

// ---------------------------------------------------------------- laws

TEST(PhaseLaw, ColoredLawMatchesMomentOde) {
    constexpr double tol = 1e-12;
    Worst worst, chol;
    for (double r : kRatios)
        for (double rho : kDrags) {
            const double h = r * kTau;
            const double relax = relaxation_for(h, rho);
            const auto law = ss::colored_slide_law(kTau, relax, kAmplitude, h);
            const auto ref = integrate(colored_system<Big>(kTau, relax, kAmplitude), Big(h));
            compare_law<3>(law, ref, describe(r, rho), worst);
            chol.note(chol_residual<3>(law), describe(r, rho));
            EXPECT_EQ(law.h, h);
        }
    report("coloured law vs moment ODE", worst, tol);
    report("coloured law: chol chol^T - cov (scaled)", chol, 1e-14);
    EXPECT_LE(worst.err, tol) << worst.where;
    EXPECT_LE(chol.err, 1e-14) << chol.where;
}

TEST(PhaseLaw, WhiteLawMatchesMomentOdeAndClosedForm) {
    constexpr double tol = 1e-12;
    Worst worst, closed, chol;
    const std::vector<double> drags = {0, 1e-15, 1e-12, 1e-8, 1e-6, 1e-3, 0.1, 0.5, 1, 2, 10, 1e3, 1e5, 1e8};
    for (double h : {1e-12, 1e-4, 1.0, 1e4})
        for (double rho : drags) {
            const double relax = rho == 0 ? kInf : h / rho;
            const auto law = ss::white_slide_law(relax, kNoise, h);
            const std::string what = "h=" + fmt(h) + " h/tauL=" + fmt(rho);
            compare_law<2>(law, integrate(white_system<Big>(relax, kNoise), Big(h)), what, worst);
            chol.note(chol_residual<2>(law), what);
            // Closed forms, 100 digits (they cancel for small h/tauL: kept where 100 digits suffice).
            Moments<Huge, 2> cf;
            const Huge hh = h, G = kNoise;
            if (rho == 0) {
                cf.m[0][0] = 1;
                cf.m[1][0] = hh;
                cf.m[1][1] = 1;
                cf.g[0] = hh;
                cf.g[1] = hh * hh / 2;
                cf.s[0][0] = G * hh;
                cf.s[1][0] = cf.s[0][1] = G * hh * hh / 2;
                cf.s[1][1] = G * hh * hh * hh / 3;
            } else if (rho >= 1e-12) {
                const Huge b = Huge(1) / Huge(relax), e = exp(-b * hh), e2 = exp(-2 * b * hh);
                cf.m[0][0] = e;
                cf.m[1][0] = (1 - e) / b;
                cf.m[1][1] = 1;
                cf.g[0] = (1 - e) / b;
                cf.g[1] = (b * hh - (1 - e)) / (b * b);
                cf.s[0][0] = G * (1 - e2) / (2 * b);
                cf.s[1][0] = cf.s[0][1] = G * (1 - e) * (1 - e) / (2 * b * b);
                cf.s[1][1] = G / (b * b) * (hh - 2 * (1 - e) / b + (1 - e2) / (2 * b));
            } else {
                continue;
            }
            compare_law<2>(law, cf, what, closed);
        }
    report("white law vs moment ODE", worst, tol);
    report("white law vs closed form", closed, tol);
    report("white law: chol chol^T - cov (scaled)", chol, 1e-14);
    EXPECT_LE(worst.err, tol) << worst.where;
    EXPECT_LE(closed.err, tol) << closed.where;
    EXPECT_LE(chol.err, 1e-14) << chol.where;
}

// While stuck, X alone is OU: the X block of the sliding law is its law.
TEST(PhaseLaw, StuckOuMarginalMatchesClosedForm) {
    Worst worst;
    for (double r : kRatios)
        for (double rho : {0.0, 1.0}) {
            const double h = r * kTau;
            const auto law = ss::colored_slide_law(kTau, relaxation_for(h, rho), kAmplitude, h);
            const Huge x = Huge(h) / Huge(kTau);
            worst.note(rel_err(law.m[0][0], Huge(exp(-x))), describe(r, rho) + " m[0][0]");
            worst.note(rel_err(law.cov[0][0], Huge(-expm1(Huge(-2 * x)) / Huge(kTau))), describe(r, rho) + " cov[0][0]");
        }
    report("OU marginal vs closed form", worst, 1e-14);
    EXPECT_LE(worst.err, 1e-14) << worst.where;
}

// ---------------------------------------------------------------- switch points

// Distinct positive differences between the scaled rates the laws combine: the
// series/recursion switch happens where h times one of them crosses the spread.
std::vector<double> rate_gaps(double alpha, double beta) {
    const double pts[] = {0, alpha, beta, 2 * alpha, alpha + beta, 2 * beta};
    std::vector<double> gaps;
    for (double u : pts)
        for (double v : pts)
            if (u - v > 1e-12 * std::max(u, v)) gaps.push_back(u - v);
    std::sort(gaps.begin(), gaps.end());
    gaps.erase(std::unique(gaps.begin(), gaps.end(), [](double a, double b) { return std::fabs(a - b) <= 1e-12 * b; }),
               gaps.end());
    return gaps;
}

template <int N, class Law>
double law_jump(const Law& a, const Law& b) {
    double worst = 0;
    auto rel = [](double x, double y) { return x == y ? 0.0 : std::fabs(x - y) / std::max(std::fabs(x), std::fabs(y)); };
    for (int i = 0; i < N; ++i) {
        worst = std::max(worst, rel(a.g[i], b.g[i]));
        for (int j = 0; j < N; ++j) worst = std::max({worst, rel(a.m[i][j], b.m[i][j]), rel(a.cov[i][j], b.cov[i][j])});
    }
    return worst;
}

template <int N, class Br>
double bridge_jump(const Br& a, const Br& b) {
    double worst = 0;
    auto rel = [](double x, double y) { return x == y ? 0.0 : std::fabs(x - y) / std::max(std::fabs(x), std::fabs(y)); };
    for (int i = 0; i < N; ++i) {
        worst = std::max(worst, rel(a.r[i], b.r[i]));
        for (int j = 0; j < N; ++j)
            worst = std::max({worst, rel(a.p[i][j], b.p[i][j]), rel(a.q[i][j], b.q[i][j]), rel(a.cov[i][j], b.cov[i][j])});
    }
    return worst;
}

TEST(PhaseLaw, NoJumpAcrossSeriesSwitch) {
    // h (1 -+ 1e-14): the true relative change is below ~1e-13 (entries go like h^5 at most).
    constexpr double tol = 1e-12, eps = 1e-14;
    const double spread = ss::detail::phase_law_series_spread;
    Worst law_w, bridge_w, white_w;
    for (double ratio : {0.0, 1.0 / 3.0, 1.0, 1.0 + 1e-9, 5.0}) { // tau/tauL
        const double alpha = 1 / kTau, beta = ratio / kTau;
        const double relax = ratio == 0 ? kInf : kTau / ratio;
        for (double gap : rate_gaps(alpha, beta)) {
            const double h0 = spread / gap;
            const std::string what = "tau/tauL=" + fmt(ratio) + " h/tau=" + fmt(h0 / kTau);
            const auto lo = ss::colored_slide_law(kTau, relax, kAmplitude, h0 * (1 - eps));
            const auto hi = ss::colored_slide_law(kTau, relax, kAmplitude, h0 * (1 + eps));
            law_w.note(law_jump<3>(lo, hi), what);
            // The bridge combines half steps: its switch is at h/2 = h0.
            const auto blo = ss::colored_slide_bridge(kTau, relax, kAmplitude, 2 * h0 * (1 - eps));
            const auto bhi = ss::colored_slide_bridge(kTau, relax, kAmplitude, 2 * h0 * (1 + eps));
            bridge_w.note(bridge_jump<3>(blo, bhi), what);
        }
        if (ratio != 0)
            for (double gap : {beta, 2 * beta}) {
                const double h0 = spread / gap;
                const std::string what = "white h/tauL=" + fmt(h0 * beta);
                white_w.note(law_jump<2>(ss::white_slide_law(relax, kNoise, h0 * (1 - eps)),
                                         ss::white_slide_law(relax, kNoise, h0 * (1 + eps))),
                             what);
                white_w.note(bridge_jump<2>(ss::white_slide_bridge(relax, kNoise, 2 * h0 * (1 - eps)),
                                            ss::white_slide_bridge(relax, kNoise, 2 * h0 * (1 + eps))),
                             what + " (bridge)");
            }
    }
    report("coloured law: jump across series switch", law_w, tol);
    report("coloured bridge: jump across series switch", bridge_w, tol);
    report("white law and bridge: jump across switch", white_w, tol);
    EXPECT_LE(law_w.err, tol) << law_w.where;
    EXPECT_LE(bridge_w.err, tol) << bridge_w.where;
    EXPECT_LE(white_w.err, tol) << white_w.where;
}

TEST(PhaseLaw, NearlyConfluentRatesAreSmooth) {
    // tauL = tau (1 +- 1e-9): exact against the reference, and within the
    // first-order change of tauL = tau: |d log(entry) / d log tauL| <= 5 + 2 h/tauL.
    constexpr double tol = 1e-12;
    Worst ref_w, near_w;
    for (double r : kRatios) {
        const double h = r * kTau;
        const auto same = ss::colored_slide_law(kTau, kTau, kAmplitude, h);
        for (double d : {-1e-9, 1e-9}) {
            const double relax = kTau * (1 + d);
            const auto law = ss::colored_slide_law(kTau, relax, kAmplitude, h);
            const std::string what = "h/tau=" + fmt(r) + " tauL/tau-1=" + fmt(d);
            compare_law<3>(law, integrate(colored_system<Big>(kTau, relax, kAmplitude), Big(h)), what, ref_w);
            const double allowed = 1e-9 * (5 + 2 * r);
            near_w.note(law_jump<3>(law, same) / allowed, what);
        }
    }
    report("tauL = tau (1 +- 1e-9) vs moment ODE", ref_w, tol);
    std::printf("[phase_law] tauL = tau (1 +- 1e-9) vs tauL = tau: worst change / allowed %.2f at %s\n", near_w.err,
                near_w.where.c_str());
    EXPECT_LE(ref_w.err, tol) << ref_w.where;
    EXPECT_LE(near_w.err, 1.0) << near_w.where;
}

// ---------------------------------------------------------------- consistency

TEST(PhaseLaw, TwoHalfStepsMakeOneStep) {
    // Both sides are rounded doubles; 1e-16 measured with an x86 long double,
    // 1e-14 where long double is a double.
    constexpr double tol = 5e-14;
    Worst worst;
    for (double r : kRatios)
        for (double rho : kDrags) {
            const double h = r * kTau;
            const double relax = relaxation_for(h, rho);
            const auto half = ss::colored_slide_law(kTau, relax, kAmplitude, h / 2);
            const auto full = ss::colored_slide_law(kTau, relax, kAmplitude, h);
            Moments<long double, 3> comp;
            for (int i = 0; i < 3; ++i) {
                comp.g[i] = half.g[i];
                for (int j = 0; j < 3; ++j) {
                    comp.g[i] += static_cast<long double>(half.m[i][j]) * half.g[j];
                    for (int l = 0; l < 3; ++l) comp.m[i][j] += static_cast<long double>(half.m[i][l]) * half.m[l][j];
                }
            }
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) {
                    comp.s[i][j] = half.cov[i][j];
                    for (int k = 0; k < 3; ++k)
                        for (int l = 0; l < 3; ++l)
                            comp.s[i][j] += static_cast<long double>(half.m[i][k]) * half.cov[k][l] * half.m[j][l];
                }
            compare_law<3>(full, comp, describe(r, rho), worst);
        }
    report("law(h) vs law(h/2) composed twice", worst, tol);
    EXPECT_LE(worst.err, tol) << worst.where;
}

// ---------------------------------------------------------------- bridges

TEST(PhaseLaw, ColoredBridgeMatchesConditionedJointLaw) {
    constexpr double tol = 1e-12;
    Worst worst, chol;
    const std::vector<double> ratios = {1e-15, 1e-12, 1e-9, 1e-6, 1e-3, 0.1, 1, 10, 1e3, 1e5, 1e8};
    for (double r : ratios)
        for (double rho : kDrags) {
            const double h = r * kTau;
            const double relax = relaxation_for(h, rho);
            const auto b = ss::colored_slide_bridge(kTau, relax, kAmplitude, h);
            const auto ref = reference_bridge(colored_system<Huge>(kTau, relax, kAmplitude), Huge(h));
            compare_bridge<3>(b, ref, describe(r, rho), worst);
            chol.note(chol_residual<3>(b), describe(r, rho));
            EXPECT_EQ(b.h, h);
        }
    report("coloured bridge vs conditioned joint law", worst, tol);
    std::printf("[phase_law] (%d entries found to vanish identically; checked to be below 1e-30 of their terms)\n",
                worst.zeros);
    report("coloured bridge: chol chol^T - cov (scaled)", chol, 1e-14);
    EXPECT_LE(worst.err, tol) << worst.where;
    EXPECT_LE(chol.err, 1e-14) << chol.where;
}

TEST(PhaseLaw, WhiteBridgeMatchesConditionedJointLaw) {
    constexpr double tol = 1e-12;
    Worst worst, chol;
    for (double h : {1e-12, 1e-4, 1.0})
        for (double rho : {0.0, 1e-15, 1e-12, 1e-6, 1e-3, 0.5, 1.0, 10.0, 1e3, 1e8}) {
            const double relax = rho == 0 ? kInf : h / rho;
            const auto b = ss::white_slide_bridge(relax, kNoise, h);
            const auto ref = reference_bridge(white_system<Huge>(relax, kNoise), Huge(h));
            const std::string what = "h=" + fmt(h) + " h/tauL=" + fmt(rho);
            compare_bridge<2>(b, ref, what, worst);
            chol.note(chol_residual<2>(b), what);
        }
    // Without drag V is a Brownian motion with drift and U its integral; the
    // midpoint bridge then has the closed form (worked out symbolically)
    //   q = [[-1/4, 3/(2h)], [-h/8, 1/2]], p = [[-1/4, -3/(2h)], [h/8, 1/2]], r = 0,
    //   cov = noise h [[1/16, 0], [0, h^2/192]].
    Worst closed;
    for (double h : {1e-9, 0.37, 250.0}) {
        const auto b = ss::white_slide_bridge(kInf, kNoise, h);
        const Huge hh = h, G = kNoise;
        Bridge<Huge, 2> cf;
        cf.q[0][0] = Huge(-1) / 4;
        cf.q[0][1] = 3 / (2 * hh);
        cf.q[1][0] = -hh / 8;
        cf.q[1][1] = Huge(1) / 2;
        cf.p[0][0] = Huge(-1) / 4;
        cf.p[0][1] = -3 / (2 * hh);
        cf.p[1][0] = hh / 8;
        cf.p[1][1] = Huge(1) / 2;
        cf.c[0][0] = G * hh / 16;
        cf.c[1][1] = G * hh * hh * hh / 192;
        compare_bridge<2>(b, cf, "h=" + fmt(h), closed, true);
        EXPECT_LE(std::fabs(b.r[0]), 1e-15 * h);
        EXPECT_LE(std::fabs(b.r[1]), 1e-15 * h * h);
        EXPECT_LE(std::fabs(b.cov[1][0]), 1e-14 * std::sqrt(b.cov[0][0] * b.cov[1][1]));
    }
    report("white bridge without drag vs closed form", closed, 1e-13);
    EXPECT_LE(closed.err, 1e-13) << closed.where;
    report("white bridge vs conditioned joint law", worst, tol);
    std::printf("[phase_law] (%d entries found to vanish identically; checked to be below 1e-30 of their terms)\n",
                worst.zeros);
    report("white bridge: chol chol^T - cov (scaled)", chol, 1e-14);
    EXPECT_LE(worst.err, tol) << worst.where;
    EXPECT_LE(chol.err, 1e-14) << chol.where;
}

TEST(PhaseLaw, OuBridgeMatchesTextbook) {
    // X_s | X_0, X_h for dX = -X/tau dt + sqrt(2)/tau dW at s = h/2:
    // p = q = sinh(h/2tau) / sinh(h/tau), var = (2/tau) sinh(h/2tau)^2 / sinh(h/tau).
    // p ~ e^{-h/2tau} amplifies the rounding of h/tau by h/2tau (500 here): 1e-13
    // leaves room for a platform whose long double is a double.
    constexpr double tol = 1e-13;
    Worst worst;
    for (double r : {1e-15, 1e-12, 1e-8, 1e-4, 0.1, 0.5, 1.0, 2.0, 10.0, 100.0, 1e3, 1e5, 1e8}) {
        const double h = r * kTau;
        const auto b = ss::ou_bridge(kTau, h);
        const Huge x = Huge(h) / Huge(kTau), t = Huge(kTau);
        const Huge s1 = sinh(x / 2), s2 = sinh(x);
        const Huge p = s1 / s2, var = 2 / t * s1 * s1 / s2;
        worst.note(rel_err(b.p, p), "h/tau=" + fmt(r) + " p");
        worst.note(rel_err(b.q, p), "h/tau=" + fmt(r) + " q");
        worst.note(rel_err(b.sd, Huge(sqrt(var))), "h/tau=" + fmt(r) + " sd");
    }
    report("OU bridge vs textbook", worst, tol);
    EXPECT_LE(worst.err, tol) << worst.where;
}

// ---------------------------------------------------------------- robustness

TEST(PhaseLaw, FiniteEverywhereAndCholReproducesCov) {
    Worst chol;
    int bad = 0;
    std::vector<double> ratios, drags = {0.0};
    for (int e = -16; e <= 9; ++e) ratios.push_back(std::pow(10.0, e));
    for (int e = -16; e <= 9; ++e) drags.push_back(std::pow(10.0, e));
    for (double r : ratios)
        for (double rho : drags) {
            const double h = r * kTau, relax = rho == 0 ? kInf : h / rho;
            const std::string what = describe(r, rho);
            const auto law = ss::colored_slide_law(kTau, relax, kAmplitude, h);
            const auto white = ss::white_slide_law(relax, kNoise, h);
            bad += !all_finite(law) + !all_finite(white);
            for (int i = 0; i < 3; ++i) bad += !(law.cov[i][i] >= 0);
            chol.note(chol_residual<3>(law), what);
            chol.note(chol_residual<2>(white), what + " white");
            const auto ou = ss::ou_bridge(kTau, h);
            bad += !(std::isfinite(ou.p) && std::isfinite(ou.sd));
        }
    for (std::size_t a = 0; a < ratios.size(); a += 3)
        for (std::size_t c = 0; c < drags.size(); c += 3) {
            const double h = ratios[a] * kTau, relax = drags[c] == 0 ? kInf : h / drags[c];
            const auto b = ss::colored_slide_bridge(kTau, relax, kAmplitude, h);
            const auto w = ss::white_slide_bridge(relax, kNoise, h);
            bad += !all_finite(b) + !all_finite(w);
            chol.note(chol_residual<3>(b), describe(ratios[a], drags[c]) + " bridge");
            chol.note(chol_residual<2>(w), describe(ratios[a], drags[c]) + " white bridge");
        }
    report("all inputs: chol chol^T - cov (scaled)", chol, 1e-14);
    EXPECT_EQ(bad, 0);
    EXPECT_LE(chol.err, 1e-14) << chol.where;
}

TEST(PhaseLaw, RejectsInvalidArguments) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (double bad : {0.0, -1.0, nan, kInf}) {
        EXPECT_THROW(ss::colored_slide_law(bad, 1.0, 1.0, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::colored_slide_law(1.0, 1.0, bad, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::colored_slide_law(1.0, 1.0, 1.0, bad), std::invalid_argument);
        EXPECT_THROW(ss::colored_slide_bridge(bad, 1.0, 1.0, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::colored_slide_bridge(1.0, 1.0, bad, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::colored_slide_bridge(1.0, 1.0, 1.0, bad), std::invalid_argument);
        EXPECT_THROW(ss::white_slide_law(1.0, bad, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::white_slide_law(1.0, 1.0, bad), std::invalid_argument);
        EXPECT_THROW(ss::white_slide_bridge(1.0, bad, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::white_slide_bridge(1.0, 1.0, bad), std::invalid_argument);
        EXPECT_THROW(ss::ou_bridge(bad, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::ou_bridge(1.0, bad), std::invalid_argument);
    }
    for (double bad : {0.0, -1.0, nan, -kInf}) {
        EXPECT_THROW(ss::colored_slide_law(1.0, bad, 1.0, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::colored_slide_bridge(1.0, bad, 1.0, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::white_slide_law(bad, 1.0, 0.1), std::invalid_argument);
        EXPECT_THROW(ss::white_slide_bridge(bad, 1.0, 0.1), std::invalid_argument);
    }
    EXPECT_NO_THROW(ss::colored_slide_law(1.0, kInf, 1.0, 0.1));
    EXPECT_NO_THROW(ss::white_slide_bridge(kInf, 1.0, 0.1));
}

TEST(PhaseLaw, ApplyComputesTheAffineMapInPlace) {
    const auto law = ss::colored_slide_law(kTau, 0.03, kAmplitude, 0.004);
    const double z0[3] = {1.5, -0.2, 3.0}, n[3] = {0.3, -1.1, 0.7}, c = -2.5;
    double expect[3];
    for (int i = 0; i < 3; ++i) {
        expect[i] = law.g[i] * c;
        for (int j = 0; j < 3; ++j) expect[i] += law.m[i][j] * z0[j] + law.chol[i][j] * n[j];
    }
    double z[3] = {z0[0], z0[1], z0[2]};
    ss::apply(law, z, c, n, z); // in place
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(z[i], expect[i], 1e-14 * (1 + std::fabs(expect[i])));

    const auto b = ss::colored_slide_bridge(kTau, 0.03, kAmplitude, 0.004);
    const double zh[3] = {0.4, 0.1, 3.001};
    for (int i = 0; i < 3; ++i) {
        expect[i] = b.r[i] * c;
        for (int j = 0; j < 3; ++j) expect[i] += b.p[i][j] * z0[j] + b.q[i][j] * zh[j] + b.chol[i][j] * n[j];
    }
    double out[3];
    ss::apply(b, z0, zh, c, n, out);
    // Same terms in another order: equal up to rounding of the largest term.
    for (int i = 0; i < 3; ++i) {
        double terms = std::fabs(b.r[i] * c);
        for (int j = 0; j < 3; ++j)
            terms += std::fabs(b.p[i][j] * z0[j]) + std::fabs(b.q[i][j] * zh[j]) + std::fabs(b.chol[i][j] * n[j]);
        EXPECT_NEAR(out[i], expect[i], 1e-15 * terms);
    }

    const auto ou = ss::ou_bridge(kTau, 0.004);
    EXPECT_DOUBLE_EQ(ss::apply(ou, 1.0, 2.0, 0.5), ou.p * 1.0 + ou.q * 2.0 + ou.sd * 0.5);
}

// Cheap Monte Carlo: two half steps drawn with apply(); the bridge residual
// Z_{h/2} - (p Z_0 + q Z_h + r c) must have mean 0, covariance cov, and no
// correlation with Z_h; Z_h itself must follow law(h).
TEST(PhaseLaw, MonteCarloHalfStepsAgreeWithLawAndBridge) {
    const double h = kTau, relax = 0.7 * kTau, c = -1.3;
    const auto half = ss::colored_slide_law(kTau, relax, kAmplitude, h / 2);
    const auto full = ss::colored_slide_law(kTau, relax, kAmplitude, h);
    const auto br = ss::colored_slide_bridge(kTau, relax, kAmplitude, h);
    const double z0[3] = {4.0, 0.05, 0.0};
    std::mt19937_64 gen(20240611);
    std::normal_distribution<double> normal;
    constexpr int n = 100000;
    double sum_res[3] = {}, sum_rr[3][3] = {}, sum_rz[3][3] = {}, sum_z[3] = {}, sum_zz[3][3] = {};
    double mean_h[3];
    const double no_noise[3] = {0, 0, 0};
    ss::apply(full, z0, c, no_noise, mean_h);
    for (int k = 0; k < n; ++k) {
        double nz[3], mid[3], end[3], res[3];
        for (double& v : nz) v = normal(gen);
        ss::apply(half, z0, c, nz, mid);
        for (double& v : nz) v = normal(gen);
        ss::apply(half, mid, c, nz, end);
        ss::apply(br, z0, end, c, no_noise, res);
        for (int i = 0; i < 3; ++i) {
            res[i] = mid[i] - res[i];
            end[i] -= mean_h[i];
        }
        for (int i = 0; i < 3; ++i) {
            sum_res[i] += res[i];
            sum_z[i] += end[i];
            for (int j = 0; j < 3; ++j) {
                sum_rr[i][j] += res[i] * res[j];
                sum_rz[i][j] += res[i] * end[j];
                sum_zz[i][j] += end[i] * end[j];
            }
        }
    }
    // Standardised deviations (z-scores); 5 sigma.
    for (int i = 0; i < 3; ++i) {
        EXPECT_LT(std::fabs(sum_res[i] / n) / std::sqrt(br.cov[i][i] / n), 5.0) << i;
        EXPECT_LT(std::fabs(sum_z[i] / n) / std::sqrt(full.cov[i][i] / n), 5.0) << i;
        for (int j = 0; j < 3; ++j) {
            const double cij = br.cov[i][j], sij = full.cov[i][j];
            const double se_c = std::sqrt((br.cov[i][i] * br.cov[j][j] + cij * cij) / n);
            const double se_s = std::sqrt((full.cov[i][i] * full.cov[j][j] + sij * sij) / n);
            const double se_x = std::sqrt(br.cov[i][i] * full.cov[j][j] / n);
            EXPECT_LT(std::fabs(sum_rr[i][j] / n - cij) / se_c, 5.0) << i << j;
            EXPECT_LT(std::fabs(sum_zz[i][j] / n - sij) / se_s, 5.0) << i << j;
            EXPECT_LT(std::fabs(sum_rz[i][j] / n) / se_x, 5.0) << i << j;
        }
    }
}

// A piece of a drift law (the event scheme with --drift): V's rate is the
// piece's slope, of either sign; the reference systems take relaxation
// -1/slope (a negative relaxation is a growth rate). Bridges with slope h in
// [-64, 0.5] are computed in long double, beyond in 50 digits: both sides of
// both switches are in the list. The bridges' tolerance is 5e-12: long double
// leaves 1.2e-12 (measured) in Cov(X, V) where |slope h| = 1e-3, an entry
// that nearly cancels there (its error is 1e-19 of its terms); the laws keep
// 1e-12.
TEST(PhaseLaw, PieceLawsAndBridgesMatchTheReferences) {
    constexpr double tol = 1e-12, bridge_tol = 5e-12;
    Worst law_worst, bridge_worst, chol;
    const std::vector<double> ratios = {1e-12, 1e-6, 1e-3, 0.1, 1, 10, 1e3};
    const std::vector<double> rates = {-1e3, -65, -63, -10, -1, -1e-3, 0, 1e-3, 0.49, 0.51, 1, 3, 10}; // slope h
    for (double r : ratios)
        for (double rate : rates) {
            const double h = r * kTau;
            const double slope = rate / h;
            const double relax = rate == 0 ? kInf : -1.0 / slope;
            const std::string where = "h/tau=" + fmt(r) + " slope h=" + fmt(rate);
            const auto law = ss::colored_piece_law(kTau, slope, kAmplitude, h);
            compare_law<3>(law, integrate(colored_system<Big>(kTau, relax, kAmplitude), Big(h)), where, law_worst);
            chol.note(chol_residual<3>(law), where);
            const auto b = ss::colored_piece_bridge(kTau, slope, kAmplitude, h);
            compare_bridge<3>(b, reference_bridge(colored_system<Huge>(kTau, relax, kAmplitude), Huge(h)), where,
                              bridge_worst);
            chol.note(chol_residual<3>(b), where);
        }
    report("piece law vs moment ODE", law_worst, tol);
    report("piece bridge vs conditioned joint law", bridge_worst, bridge_tol);
    EXPECT_LE(law_worst.err, tol) << law_worst.where;
    EXPECT_LE(bridge_worst.err, bridge_tol) << bridge_worst.where;
    EXPECT_LE(chol.err, 1e-13) << chol.where;
    EXPECT_THROW(ss::colored_piece_law(kTau, kInf, kAmplitude, 0.1), std::invalid_argument);
    EXPECT_THROW(ss::colored_piece_bridge(kTau, std::nan(""), kAmplitude, 0.1), std::invalid_argument);
    EXPECT_THROW(ss::colored_piece_bridge(kTau, 1.0, kAmplitude, 0.0), std::invalid_argument);
}

TEST(PhaseLaw, ConstructionIsCheap) {
    const auto t0 = std::chrono::steady_clock::now();
    double sink = 0;
    for (int k = 0; k < 200; ++k) sink += ss::colored_slide_law(kTau, 0.02, kAmplitude, 1e-3 * (1 + k)).cov[2][2];
    const auto t1 = std::chrono::steady_clock::now();
    for (int k = 0; k < 20; ++k) sink += ss::colored_slide_bridge(kTau, 0.02, kAmplitude, 1e-3 * (1 + k)).cov[2][2];
    const auto t2 = std::chrono::steady_clock::now();
    const double law_us = std::chrono::duration<double, std::micro>(t1 - t0).count() / 200;
    const double bridge_us = std::chrono::duration<double, std::micro>(t2 - t1).count() / 20;
    std::printf("[phase_law] construction: law %.1f us, bridge %.1f us\n", law_us, bridge_us);
    EXPECT_GT(sink, 0);
    EXPECT_LT(bridge_us, 20000); // generous: "called once per run and per refinement depth"
}

} // namespace
