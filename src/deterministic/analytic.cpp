// SPDX-License-Identifier: BSD-3-Clause
// White-noise references (theory.md, section 8).
//
// Stationary part. Hayakawa's potential phi(v) = A v^2 + k+ v (v >= 0),
// A v^2 + k- |v| (v < 0), A = 1/(Gamma tauL), k+- = 2 (Delta -+ gbar)/Gamma, is
// convex and piecewise quadratic with a kink at 0. It is never evaluated as that
// sum, which cancels catastrophically when the drift overwhelms friction (the
// mode tauL (gbar - Delta) = 1e8 puts two terms of 1e16 against a difference of
// order 1): on the side of the mode it is A (v - mode)^2, with v - mode formed
// from a double-double mode, and on the other side kink + A v^2 + k |v|, a sum of
// positive terms (kink = A mode^2 = phi(0)). Everything is in long double.
//
// The line is cut into "segments", each running away from its least-potential
// point (the mode or the kink) over a coordinate u >= 0 on which
// phi = phi0 + A u^2 + k u: two for a mode at the kink, three (kink side, mode to
// kink, mode outwards) otherwise. Quadratures are composite 20-point
// Gauss-Legendre on each segment, in u, with as many equal panels as phi rises
// (about 1 per panel), up to phi = 80 (mass beyond < e^-80) for moments and up to
// 745 (where exp(-phi) underflows double) for probabilities: every panel then
// integrates an analytic, mildly varying function in the local scale, whatever
// the ratio of the Gaussian and exponential scales, and close to the mode the
// nodes are offsets from it, so no digit is lost to |mode| >> sd.
//
// Moments, by regime:
//  * no drag (relaxation = inf, |gbar| < Delta): the closed forms of theory.md
//    section 8, written with K+- = Delta -+ gbar (exact when |gbar| -> Delta):
//    M0 = Gamma gbar/(K+ K-), Var = Gamma^2 (Delta^2 + gbar^2)/(2 (K+ K-)^2),
//    D = Gamma^3 (5 gbar^4 + 22 gbar^2 Delta^2 + 5 Delta^4)/(4 (K+ K-)^4);
//  * mode so far from the kink that phi(0) >= 80: the density is the
//    Ornstein-Uhlenbeck Gaussian to e^-80, so M0 = mode, Var = Gamma tauL/2 and
//    D = tauL^2 Gamma (relative corrections below 1e-30);
//  * otherwise quadrature of integrands that never change sign:
//      M0 = int_0^inf y (q(y) - q(-y)) dy / Z, the pairs v = +-y folded so that
//           the cancellation of the two half-lines (M0 -> 0 as gbar -> 0) is
//           done analytically: q(-y)/q(y) = exp(-4 |gbar| y/Gamma), and the
//           integrand is y q_dominant(y) (1 - exp(-4 |gbar| y/Gamma)) by expm1;
//      Var = int (v - M0)^2 q / Z;
//      D = (4/Gamma) int F^2/q / Z, F(v) = -int_{-inf}^v (M0 - u) q du for v <= M0
//           and -int_v^inf (u - M0) q du for v >= M0 (panels split at M0), each
//           a sum of positive terms accumulated from the nearer end, and inside
//           a panel completed by a 10-point rule from the panel's outer edge.
// All three are exact to a few units of double rounding (checked against
// 50-digit references in tests/unit/white_noise_quadrature_test.cpp). A result
// that no double holds to 12 digits (beyond 1.8e308, or below ~5e-312) is
// refused with InvalidParameter, never returned as inf, 0 or a digitless denormal.
//
// Transient part (pure dry friction). Touchette et al.'s closed forms combine
// exponentials that overflow (e^{2|v0|}) with normal tails that underflow, and
// at large t they are differences of nearly equal terms. Every exp * erfc pair
// is therefore merged into exp(exponent) * erfcx(x) with the exponent
// simplified by hand (it is then <= 0), and the sums are done in long double
// (64-bit mantissa on x86-64), which absorbs the remaining cancellation; for
// t' > 100 the autocorrelation switches to its asymptotic series, where the
// closed form would lose more than six digits.
#include "stickslip/analytic.hpp"
#include "stickslip/drift_law_quadrature.hpp"

#include <algorithm>
#include <array>
#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <cfloat>
#include <cmath>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "core/format.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/stats/double_double.hpp"

namespace stickslip {

namespace {

using Real = long double;
namespace bmc = boost::math::constants;

constexpr Real kMomentCut = 80;   // potential rise bounding the moment integrals (mass beyond < e^-80)
constexpr Real kSupportCut = 745; // beyond it exp(-phi) < 5e-324: the density is 0 in double
constexpr Real kFarMode = 80;     // phi(0) from which the density is the viscous Gaussian to e^-80

// ---- Double-double numbers: the mode, exact to ~2^-104 --------------------------

// The one double-double arithmetic (stats/double_double.hpp).
using Exact = detail::dd::DD;
using detail::dd::two_sum;

/// t (x.hi + x.lo), to ~2^-104 relative.
Exact times(double t, Exact x) { return detail::dd::mul(x, t); }

Real value(Exact x) { return static_cast<Real>(x.hi) + x.lo; }

/// v - x, to the 64 bits of Real whatever |v| and |x| are.
Real minus(double v, Exact x) { return (static_cast<Real>(v) - x.hi) - x.lo; }

std::string text(Real x) { return number_text::general(static_cast<long double>(x), 6); }

void check(const ModelParams& p) {
    validate(p);
    if (!has_stationary_state(p))
        throw InvalidParameter("bias", "no stationary state: with relaxation inf, |bias| must be < friction");
}

/// x as a double, or InvalidParameter(parameter) when no double holds it to
/// 1e-12: beyond 1.8e308 (it would print as inf) or so deep among the
/// denormals (below ~5e-312) that its digits are gone.
double representable(Real x, const char* parameter, const char* what, const char* unit, const char* why) {
    const double d = static_cast<double>(x);
    if (std::isfinite(d) && std::fabs(static_cast<Real>(d) - x) <= 1e-12L * std::fabs(x)) return d;
    throw InvalidParameter(parameter, std::string("the white-noise ") + what + " would be " + text(x) + " " + unit +
                                          ", which double cannot hold (beyond 1.8e308, or too far below 2.2e-308 "
                                          "to keep 12 digits): " + why);
}

// ---- Hayakawa's potential -------------------------------------------------------

/// phi(v) - min phi for the drift and friction of p, evaluated without
/// cancellation (see the top of the file).
struct Shape {
    Real a2 = 0;         // A = 1/(Gamma tauL) [s^2/m^2]; 0 without drag
    Real kp = 0, km = 0; // 2 (Delta - gbar)/Gamma, 2 (Delta + gbar)/Gamma [s/m]
    int side = 0;        // sign of the mode; 0: the mode is the kink v = 0
    Exact mode;          // tauL (gbar - side Delta) [m/s] (0 when side = 0)
    Real kink = 0;       // phi(0) = A mode^2

    Shape() = default;
    Shape(Real a2_, Real kp_, Real km_, int side_, Exact mode_, Real kink_)
        : a2(a2_), kp(kp_), km(km_), side(side_), mode(mode_), kink(kink_) {}

    explicit Shape(const ModelParams& p) {
        const Real gamma = p.noise, delta = p.friction, g = p.bias;
        kp = 2 * (delta - g) / gamma;
        km = 2 * (delta + g) / gamma;
        if (std::isinf(p.relaxation)) return; // no drag: |bias| < friction, so kp, km > 0
        a2 = 1 / (gamma * static_cast<Real>(p.relaxation));
        if (std::fabs(p.bias) > p.friction) {
            side = p.bias > 0 ? 1 : -1;
            mode = times(p.relaxation, two_sum(p.bias, -side * p.friction));
            if (!std::isfinite(mode.hi) || !std::isfinite(mode.lo))
                throw InvalidParameter("bias", "the most probable velocity relaxation * (|bias| - friction) = " +
                                                   text(static_cast<Real>(p.relaxation) * (std::fabs(g) - delta)) +
                                                   " m/s is beyond the range of double");
            const Real m = value(mode);
            kink = a2 * m * m;
        }
    }

    Real potential(double v) const {
        if (v == 0) return kink;
        const int s = v > 0 ? 1 : -1;
        if (s == side) {
            const Real d = minus(v, mode);
            return a2 * d * d;
        }
        const Real u = std::fabs(static_cast<Real>(v));
        return kink + (a2 * u + (s > 0 ? kp : km)) * u;
    }
};

// ---- Segments and their quadrature ------------------------------------------------

/// v = anchor + dir u for u in [0, length], on which phi = phi0 + a2 u^2 + k u.
struct Segment {
    Exact anchor;
    int dir = 1;
    Real phi0 = 0, a2 = 0, k = 0;
    Real length = INFINITY;

    Real phi(Real u) const { return phi0 + (a2 * u + k) * u; }
    /// The u in [0, length] where phi reaches level (length if it never does).
    Real reach(Real level) const {
        if (level <= phi0) return 0;
        const Real d = level - phi0;
        return std::min(length, 2 * d / (k + std::sqrt(k * k + 4 * a2 * d)));
    }
};

/// The segments in the order of v.
std::vector<Segment> segments_of(const Shape& s) {
    if (s.side == 0) return {Segment{{}, -1, 0, s.a2, s.km}, Segment{{}, +1, 0, s.a2, s.kp}};
    const Segment kink_side{{}, -s.side, s.kink, s.a2, s.side > 0 ? s.km : s.kp};
    const Segment toward{s.mode, -s.side, 0, s.a2, 0, std::fabs(value(s.mode))};
    const Segment outward{s.mode, s.side, 0, s.a2, 0};
    if (s.side > 0) return {kink_side, toward, outward};
    return {outward, toward, kink_side};
}

using Outer = boost::math::quadrature::gauss<Real, 20>;
using Inner = boost::math::quadrature::gauss<Real, 10>;

/// Gauss rule R on [a, a + h]: visit(x, weight) at its nodes.
template <class R, class Visit>
void nodes(Real a, Real h, Visit&& visit) {
    const auto& x = R::abscissa();
    const auto& w = R::weights();
    const Real r = h / 2, c = a + r;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x[i] == 0) {
            visit(c, r * w[i]);
            continue;
        }
        visit(c - r * x[i], r * w[i]);
        visit(c + r * x[i], r * w[i]);
    }
}

template <class R, class F>
Real rule(F&& f, Real a, Real h) {
    Real s = 0;
    nodes<R>(a, h, [&](Real x, Real w) { s += w * f(x); });
    return s;
}

/// Equal panels on [u0, u1] over which phi (monotone there) rises by `rise`.
int panels_for(Real rise) { return static_cast<int>(std::min<Real>(std::ceil(std::fabs(rise)), 1e5)) + 1; }

/// int_{u0}^{u1} f(u) du on a segment, f ~ exp(-phi) times a slowly varying factor.
template <class F>
Real integrate(const Segment& s, Real u0, Real u1, F&& f) {
    if (!(u1 > u0)) return 0;
    const int n = panels_for(s.phi(u1) - s.phi(u0));
    const Real h = (u1 - u0) / n;
    Real sum = 0;
    for (int j = 0; j < n; ++j) sum += rule<Outer>(f, u0 + j * h, h);
    return sum;
}

/// Z = int exp(-phi) dv [m/s].
Real normalisation(const std::vector<Segment>& segs) {
    Real z = 0;
    for (const Segment& s : segs) z += integrate(s, 0, s.reach(kMomentCut), [&](Real u) { return std::exp(-s.phi(u)); });
    return z;
}

/// int v exp(-phi) dv with v and -v paired (near-mode regime, drag present).
Real paired_first_moment(const Shape& sh, Real gamma, Real g) {
    if (g == 0) return 0;
    const int dom = g > 0 ? 1 : -1; // the heavier side
    const Real kappa = 4 * std::fabs(g) / gamma;
    const bool gauss = sh.side == dom; // the mode is on it
    const Real m = gauss ? std::fabs(value(sh.mode)) : 0, k = dom > 0 ? sh.kp : sh.km;
    auto psi = [&](Real y) { return gauss ? sh.a2 * (y - m) * (y - m) : (sh.a2 * y + k) * y; };
    const Real end = gauss ? m + std::sqrt(kMomentCut / sh.a2)
                           : 2 * kMomentCut / (k + std::sqrt(k * k + 4 * sh.a2 * kMomentCut));
    const Real layer = 40 / kappa; // where exp(-kappa y) < 5e-18
    std::vector<Real> cuts{0, end};
    if (m > 0 && m < end) cuts.push_back(m);
    if (layer < end) cuts.push_back(layer);
    std::sort(cuts.begin(), cuts.end());
    auto f = [&](Real y) { return -y * std::exp(-psi(y)) * std::expm1(-kappa * y); };
    Real sum = 0;
    for (std::size_t j = 0; j + 1 < cuts.size(); ++j) {
        const Real a = cuts[j], b = cuts[j + 1];
        if (!(b > a)) continue;
        const int n = panels_for(psi(b) - psi(a) + (a < layer ? kappa * (b - a) : 0));
        const Real h = (b - a) / n;
        for (int i = 0; i < n; ++i) sum += rule<Outer>(f, a + i * h, h);
    }
    return dom * sum;
}

/// int (v - m0)^2 exp(-phi) dv.
Real centred_second_moment(const std::vector<Segment>& segs, Real m0) {
    Real sum = 0;
    for (const Segment& s : segs) {
        const Real w0 = value(s.anchor) - m0;
        sum += integrate(s, 0, s.reach(kMomentCut), [&](Real u) {
            const Real d = w0 + s.dir * u;
            return d * d * std::exp(-s.phi(u));
        });
    }
    return sum;
}

/// int F^2 exp(phi) dv, F(v) = int_{-inf}^v (u - m0) exp(-phi(u)) du.
Real flux_square_integral(const std::vector<Segment>& segs, Real m0) {
    struct Panel {
        const Segment* s;
        Real u;     // u at the panel's lower-v end
        Real width; // in u (and in v)
        Real w;     // v - m0 at the lower-v end
    };
    std::vector<Panel> panels; // in the order of v, none straddling m0
    for (const Segment& s : segs) {
        const Real end = s.reach(kMomentCut);
        if (!(end > 0)) continue;
        const int n = panels_for(s.phi(end) - s.phi(0));
        std::vector<Real> cuts;
        for (int j = 0; j <= n; ++j) cuts.push_back(j == n ? end : end * j / n);
        const Real w0 = value(s.anchor) - m0, at_m0 = -s.dir * w0; // u where v = m0
        if (at_m0 > 0 && at_m0 < end) cuts.insert(std::upper_bound(cuts.begin(), cuts.end(), at_m0), at_m0);
        const std::size_t count = cuts.size() - 1;
        for (std::size_t j = 0; j < count; ++j) {
            const std::size_t k = s.dir > 0 ? j : count - 1 - j;
            const Real lower = s.dir > 0 ? cuts[k] : cuts[k + 1];
            panels.push_back({&s, lower, cuts[k + 1] - cuts[k], w0 + s.dir * lower});
        }
    }
    // v = lower end + t for t in [0, width]; u = p.u + dir t.
    auto q = [](const Panel& p, Real t) { return std::exp(-p.s->phi(p.u + p.s->dir * t)); };
    Real sum = 0;
    std::size_t split = 0; // panels [0, split) lie below m0
    while (split < panels.size() && panels[split].w + panels[split].width / 2 < 0) ++split;
    Real f_edge = 0; // F at the current panel's lower end, from -inf
    for (std::size_t j = 0; j < split; ++j) {
        const Panel& p = panels[j];
        auto g = [&](Real t) { return -(p.w + t) * q(p, t); }; // (m0 - v) q >= 0
        nodes<Outer>(0, p.width, [&](Real t, Real weight) {
            const Real f = f_edge - rule<Inner>(g, 0, t);
            sum += weight * f * f / q(p, t);
        });
        f_edge -= rule<Outer>(g, 0, p.width);
    }
    f_edge = 0; // F at the current panel's upper end, from +inf
    for (std::size_t j = panels.size(); j-- > split;) {
        const Panel& p = panels[j];
        auto g = [&](Real t) { return (p.w + t) * q(p, t); }; // (v - m0) q >= 0
        nodes<Outer>(0, p.width, [&](Real t, Real weight) {
            const Real f = f_edge - rule<Inner>(g, t, p.width - t);
            sum += weight * f * f / q(p, t);
        });
        f_edge -= rule<Outer>(g, 0, p.width);
    }
    return sum;
}

struct Moments {
    Real z = 0;    // int exp(-phi) dv [m/s]
    Real mean = 0; // M0 [m/s]
    Real var = 0;  // [m^2/s^2]
    Real d = 0;    // D [m^2/s] (when asked for)
};

Moments moments_of(const ModelParams& p, const Shape& sh, const std::vector<Segment>& segs, bool diffusivity) {
    Moments r;
    r.z = normalisation(segs);
    const Real gamma = p.noise, delta = p.friction, g = p.bias;
    if (sh.a2 == 0) { // no drag: closed forms
        const Real kk = (delta - g) * (delta + g), g2 = g * g, d2 = delta * delta;
        r.mean = gamma * g / kk;
        r.var = gamma * gamma * (d2 + g2) / (2 * kk * kk);
        r.d = gamma * gamma * gamma * (5 * g2 * g2 + 22 * g2 * d2 + 5 * d2 * d2) / (4 * kk * kk * kk * kk);
        return r;
    }
    const Real tl = p.relaxation;
    if (sh.kink >= kFarMode) { // the viscous Gaussian around the mode
        r.mean = value(sh.mode);
        r.var = gamma * tl / 2;
        r.d = tl * tl * gamma;
        return r;
    }
    r.mean = paired_first_moment(sh, gamma, g) / r.z;
    r.var = centred_second_moment(segs, r.mean) / r.z;
    if (diffusivity) r.d = 4 / gamma * flux_square_integral(segs, r.mean) / r.z;
    return r;
}

/// The parameter to blame for a variance or diffusivity out of range: the
/// relaxation time with drag (Var <= noise relaxation/2, D <= relaxation^2 noise,
/// approached when the drift overwhelms friction), the bias without (the
/// closed forms diverge as |bias| -> friction; validate() keeps their
/// bias-free scales in range).
const char* culprit(const ModelParams& p) { return std::isinf(p.relaxation) ? "bias" : "relaxation"; }

const char* mobility_why(const ModelParams& p) {
    return std::isinf(p.relaxation) ? "M0 = noise bias/(friction^2 - bias^2): bias is too small, or |bias| too close to "
                                      "friction"
                                    : "M0 is about relaxation * bias (relaxation * (|bias| - friction) once the drift "
                                      "overwhelms friction): bias or relaxation is out of range";
}

const char* variance_why(const ModelParams& p) {
    return std::isinf(p.relaxation) ? "Var = (noise/friction)^2 (1 + g^2)/(2 (1 - g^2)^2), g = bias/friction, grows "
                                      "without bound as |bias| -> friction"
                                    : "with drag Var <= noise * relaxation/2, its value without friction and when the "
                                      "drift overwhelms friction: relaxation is out of range";
}

} // namespace

// ---- Hayakawa density ----------------------------------------------------------

HayakawaDensity::HayakawaDensity(const ModelParams& p) {
    if (p.has_drift_law())
        throw InvalidParameter("drift", "Hayakawa's closed-form density is the affine law's; for a drift law use "
                                        "DriftLawWhiteNoise (drift_law_quadrature.hpp), `analytic --velocities`, or "
                                        "stickslip.analytic.hayakawa_density / white_noise_reference");
    check(p);
    const Shape sh(p);
    a2_ = sh.a2;
    kp_ = sh.kp;
    km_ = sh.km;
    kink_ = sh.kink;
    side_ = sh.side;
    mode_ = sh.mode.hi;
    mode_lo_ = sh.mode.lo;
    const Moments m = moments_of(p, sh, segments_of(sh), false);
    inv_z_ = representable(1 / m.z, culprit(p), "density peak 1/Z", "s/m", variance_why(p));
    mean_ = representable(m.mean, "bias", "mean velocity M0", "m/s", mobility_why(p));
    variance_ = representable(m.var, culprit(p), "variance Var(V)", "m^2/s^2", variance_why(p));
}

double HayakawaDensity::potential(double v) const {
    return static_cast<double>(Shape(a2_, kp_, km_, side_, {mode_, mode_lo_}, kink_).potential(v));
}

double HayakawaDensity::operator()(double v) const {
    if (std::isinf(v)) return 0.0;
    return static_cast<double>(std::exp(-Shape(a2_, kp_, km_, side_, {mode_, mode_lo_}, kink_).potential(v)) * inv_z_);
}

double HayakawaDensity::probability(double a, double b) const {
    if (std::isnan(a) || std::isnan(b)) throw InvalidParameter("v", "probability(a, b): a and b must not be NaN");
    if (a > b) return -probability(b, a);
    const Shape sh(a2_, kp_, km_, side_, {mode_, mode_lo_}, kink_);
    Real sum = 0;
    for (const Segment& s : segments_of(sh)) {
        const Real ua = s.dir * minus(a, s.anchor), ub = s.dir * minus(b, s.anchor);
        const Real lo = std::max<Real>(std::min(ua, ub), 0), hi = std::min(std::max(ua, ub), s.reach(kSupportCut));
        if (hi > lo) sum += integrate(s, lo, hi, [&](Real u) { return std::exp(-s.phi(u)); });
    }
    return static_cast<double>(sum * inv_z_);
}

double hayakawa_potential(const ModelParams& p, double v) {
    check(p);
    return static_cast<double>(Shape(p).potential(v));
}

double hayakawa_density(const ModelParams& p, double v) {
    check(p);
    // One density per thread, rebuilt only when the parameters that shape it
    // change (tau does not): callers evaluate it on grids, point by point.
    struct Cache {
        double friction = 0, noise = 0, relaxation = 0, bias = 0;
        std::optional<HayakawaDensity> density;
    };
    thread_local Cache cache;
    if (!cache.density || cache.friction != p.friction || cache.noise != p.noise ||
        cache.relaxation != p.relaxation || cache.bias != p.bias) {
        cache.density.emplace(p);
        cache.friction = p.friction;
        cache.noise = p.noise;
        cache.relaxation = p.relaxation;
        cache.bias = p.bias;
    }
    return (*cache.density)(v);
}

WhiteNoiseReference white_noise_reference(const ModelParams& p) {
    if (p.has_drift_law()) return DriftLawWhiteNoise(p).reference(); // any law: drift_law_quadrature.hpp
    check(p);
    const Shape sh(p);
    const Moments m = moments_of(p, sh, segments_of(sh), true);
    WhiteNoiseReference r{};
    r.mobility = representable(m.mean, "bias", "mobility M0", "m/s", mobility_why(p));
    r.diffusivity = representable(m.d, culprit(p), "diffusivity D", "m^2/s",
                                  std::isinf(p.relaxation)
                                      ? "D = (noise^3/friction^4) (5g^4 + 22g^2 + 5)/(4 (1 - g^2)^4), g = bias/friction, "
                                        "grows without bound as |bias| -> friction"
                                      : "with drag D <= relaxation^2 * noise, its value without friction and when the "
                                        "drift overwhelms friction: relaxation is out of range");
    r.variance = representable(m.var, culprit(p), "variance Var(V)", "m^2/s^2", variance_why(p));
    return r;
}

double dry_friction_mobility(const ModelParams& p) {
    const Real delta = p.friction, g = p.bias;
    return static_cast<double>(static_cast<Real>(p.noise) * g / ((delta - g) * (delta + g)));
}

double dry_friction_diffusivity(const ModelParams& p) {
    const Real gamma = p.noise, delta = p.friction, g = p.bias, g2 = g * g, d2 = delta * delta;
    const Real kk = (delta - g) * (delta + g);
    return static_cast<double>(gamma * gamma * gamma * (5 * g2 * g2 + 22 * g2 * d2 + 5 * d2 * d2) /
                               (4 * kk * kk * kk * kk));
}

double dry_friction_spectrum(const ModelParams& p, double w) {
    if (w == 0) return dry_friction_diffusivity(p);
    using C = std::complex<Real>;
    const Real gamma = p.noise, delta = p.friction, b = p.bias;
    const Real c_pos = b - delta, c_neg = b + delta;                  // the drift on v > 0 and v < 0
    const Real k_pos = 2 * (delta - b) / gamma, k_neg = 2 * (delta + b) / gamma; // density e^{-k+ v}, e^{k- v}
    const Real a = 1 / (1 / k_pos + 1 / k_neg);                     // its value at v = 0
    const Real m0 = a * (1 / (k_pos * k_pos) - 1 / (k_neg * k_neg));
    const C iw(0, static_cast<Real>(w));
    const C alpha = Real(1) / iw;
    const C beta_pos = (c_pos * alpha - m0) / iw, beta_neg = (c_neg * alpha - m0) / iw;
    // The decaying roots of (Gamma/2) r^2 + c r - i w = 0 on each side.
    const C r_pos = (-c_pos - std::sqrt(c_pos * c_pos + Real(2) * gamma * iw)) / gamma;
    const C r_neg = (-c_neg + std::sqrt(c_neg * c_neg + Real(2) * gamma * iw)) / gamma;
    // phi continuous and C^1 at 0.
    const C c_plus = (beta_neg - beta_pos) * r_neg / (r_neg - r_pos);
    const C c_minus = (beta_neg - beta_pos) * r_pos / (r_neg - r_pos);
    // int_0^inf (v - M0)(alpha v + beta) e^{-k v} dv, and the exponential's share.
    auto line = [&](Real k, C beta, Real sign) {
        return alpha * (Real(2) / (k * k * k)) + sign * (beta - m0 * alpha) / (k * k) - m0 * beta / k;
    };
    const C pos = line(k_pos, beta_pos, 1) + c_plus * (Real(1) / ((k_pos - r_pos) * (k_pos - r_pos)) - m0 / (k_pos - r_pos));
    const C neg = line(k_neg, beta_neg, -1) - c_minus * (Real(1) / ((k_neg + r_neg) * (k_neg + r_neg)) + m0 / (k_neg + r_neg));
    return static_cast<double>(2 * a * (pos + neg).real());
}

// ---- Pure dry friction, transient ---------------------------------------------

namespace {

/// erfcx(x) = e^{x^2} erfc(x) for x >= 0: bounded by 1, so products with
/// e^{-x^2}-sized factors can be formed without under- or overflow.
Real erfcx(Real x) {
    if (x < 30) {
        // e^{x^2} from the exact square: x*x rounds by up to x^2 * eps, which
        // e^{x^2} would turn into a relative error of 900 eps at x = 30.
        const Real x2 = x * x, x2_err = std::fma(x, x, -x2);
        return std::exp(x2) * std::exp(x2_err) * boost::math::erfc(x);
    }
    // Asymptotic series 1/(x sqrt(pi)) sum (-1)^k (2k-1)!!/(2x^2)^k: at x >= 30
    // its terms fall below 1e-21 of the sum within ten terms.
    const Real u = 1 / (2 * x * x);
    Real term = 1, sum = 1;
    for (int k = 1; k < 40 && std::fabs(term) > 1e-22L; ++k) {
        term *= -(2 * k - 1) * u;
        sum += term;
    }
    return sum * bmc::one_div_root_pi<Real>() / x;
}

/// Standard normal CDF.
Real normal_cdf(Real x) { return boost::math::erfc(-x / bmc::root_two<Real>()) / 2; }

void require_pure_dry(const ModelParams& p) {
    validate(p);
    if (!std::isinf(p.relaxation))
        throw InvalidParameter("relaxation", "the closed forms of Touchette et al. hold without viscous drag only "
                                             "(relaxation = inf), got relaxation = " +
                                                 detail::format_number(p.relaxation));
    if (p.bias != 0.0)
        throw InvalidParameter("bias", "the closed forms of Touchette et al. hold without bias only (bias = 0), got " +
                                           detail::format_number(p.bias));
}

void require_finite(const char* name, double x, const char* unit) {
    if (!std::isfinite(x))
        throw InvalidParameter(name, std::string(name) + " must be a finite number (" + unit + "), got " +
                                         detail::format_number(x));
}

// Nondimensional closed forms (Delta = Gamma = 1), theory.md, section 8.

Real propagator_nd(Real v, Real t, Real v0) {
    const Real av = std::fabs(v), a0 = std::fabs(v0);
    // Its exponent is <= -(|v| - |v0| + t)^2/(2t) <= 0: no overflow.
    const Real gauss = std::exp(-(v - v0) * (v - v0) / (2 * t) - (av - a0) - t / 2) / std::sqrt(2 * bmc::pi<Real>() * t);
    const Real z = (av + a0 - t) / std::sqrt(2 * t);
    const Real reflected = z <= 0 ? std::exp(-2 * av) * boost::math::erfc(z) / 2
                                  : std::exp(-2 * av - z * z) * erfcx(z) / 2;
    return gauss + reflected;
}

Real first_moment_nd(Real t, Real v0) {
    if (t == 0 || v0 == 0) return v0; // v0 = 0: by symmetry
    const Real a = std::fabs(v0), s = std::sqrt(t);
    // e^{2a} Phi(-(a+t)/s) = e^{-(a-t)^2/(2t)} erfcx((a+t)/(s sqrt 2)) / 2.
    const Real decay = std::exp(-(a - t) * (a - t) / (2 * t));
    const Real plus = (a + t) * erfcx((a + t) / (s * bmc::root_two<Real>()));
    Real e;
    if (a >= t) {
        e = (a - t) * normal_cdf((a - t) / s) + decay * plus / 2;
    } else {
        // Both terms carry the same Gaussian factor; keep it outside the
        // difference so that it can underflow only with the result.
        const Real minus = (t - a) * erfcx((t - a) / (s * bmc::root_two<Real>()));
        e = decay * (plus - minus) / 2;
    }
    return std::copysign(e, v0);
}

// Above this lag the closed form of C loses more than ~t^4/48 * eps: use the series.
constexpr Real kAutocorrelationSeriesFrom = 100;

Real autocorrelation_nd(Real t) {
    if (t < kAutocorrelationSeriesFrom) {
        // Phibar(sqrt t) = e^{-t/2} erfcx(sqrt(t/2)) / 2.
        const Real poly = 1 - t + t * t + t * t * t / 3;
        const Real tail = std::sqrt(t / (2 * bmc::pi<Real>())) * (1 - 2 * t / 3 - t * t / 3);
        return std::exp(-t / 2) * (poly * erfcx(std::sqrt(t / 2)) / 2 + tail);
    }
    // Inserting erfcx(x) ~ (x sqrt pi)^-1 sum_k c_k (2x^2)^-k, c_k = (-1)^k (2k-1)!!,
    // the powers t^3 ... t^0 cancel exactly and
    //   C(t) = e^{-t/2} (2 pi t)^{-1/2} sum_{n>=1} c_n P(n) t^{-n},
    //   P(n) = 1 + (2n+1) + (2n+1)(2n+3) - (2n+1)(2n+3)(2n+5)/3   (c_1 P(1) = 16).
    // Asymptotic: summed up to its smallest term, which at t >= 100 is < 1e-20.
    Real scaled_c = 1, sum = 0, previous = INFINITY;
    for (int n = 1; n < 400; ++n) {
        scaled_c *= -(2 * n - 1) / t; // c_n t^{-n}
        const Real m = 2 * n + 1;
        const Real term = scaled_c * (1 + m + m * (m + 2) - m * (m + 2) * (m + 4) / 3);
        if (std::fabs(term) >= previous) break;
        sum += term;
        previous = std::fabs(term);
        if (previous < 1e-21L * std::fabs(sum)) break;
    }
    return std::exp(-t / 2) / std::sqrt(2 * bmc::pi<Real>() * t) * sum;
}

} // namespace

double dry_friction_propagator(const ModelParams& p, double v, double t, double v0) {
    require_pure_dry(p);
    require_finite("v", v, "m/s");
    require_finite("v0", v0, "m/s");
    require_finite("time", t, "s");
    if (t <= 0)
        throw InvalidParameter("time", "the propagator needs t > 0 (s; at t = 0 it is a delta function), got " +
                                           detail::format_number(t));
    const Scales s = scales_of(p);
    const Real nd = propagator_nd(static_cast<Real>(v) / s.velocity, static_cast<Real>(t) / s.time,
                                  static_cast<Real>(v0) / s.velocity);
    return static_cast<double>(nd / s.velocity);
}

double dry_friction_first_moment(const ModelParams& p, double t, double v0) {
    require_pure_dry(p);
    require_finite("v0", v0, "m/s");
    require_finite("time", t, "s");
    if (t < 0) throw InvalidParameter("time", "the first moment needs t >= 0 (s), got " + detail::format_number(t));
    const Scales s = scales_of(p);
    const Real nd = first_moment_nd(static_cast<Real>(t) / s.time, static_cast<Real>(v0) / s.velocity);
    return static_cast<double>(nd * s.velocity);
}

double dry_friction_autocorrelation(const ModelParams& p, double t) {
    require_pure_dry(p);
    require_finite("time", t, "s");
    const Scales s = scales_of(p);
    const Real nd = autocorrelation_nd(std::fabs(static_cast<Real>(t)) / s.time);
    return static_cast<double>(nd * s.velocity * s.velocity);
}

double viscous_diffusivity(const ModelParams& p) {
    if (!std::isfinite(p.noise) || p.noise <= 0)
        throw InvalidParameter("noise", "noise must be a finite number > 0 (m^2 s^-3), got " +
                                            detail::format_number(p.noise));
    if (!std::isfinite(p.relaxation) || p.relaxation <= 0)
        throw InvalidParameter("relaxation", "the viscous diffusivity needs a finite relaxation > 0 (s), got " +
                                                 detail::format_number(p.relaxation));
    return p.relaxation * p.relaxation * p.noise;
}

} // namespace stickslip
