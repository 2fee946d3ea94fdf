// White-noise references (MODEL.md sections 7 and 9).
//
// Stationary part. The density is written q(v) = exp(-(phi(v) - phi_min)) with
// phi convex and piecewise quadratic (kink at v = 0), so it never overflows;
// the range is cut where q < e^-700. Integrals use composite 20-point
// Gauss-Legendre panels on segments split at the kink, the mode and M0 (the
// integrand is analytic on each panel, so every panel is exact to rounding).
// F(v) = int (u - M0) q du is accumulated from the left end for v <= M0 and
// from the right end (with a minus sign) for v > M0: F < 0 everywhere and
// vanishes at both ends, so this keeps its relative precision in the tails,
// where F^2/q is evaluated.
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

#include <algorithm>
#include <array>
#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <optional>
#include <vector>

#include "format.hpp"

namespace stickslip {

namespace {

using Rule = boost::math::quadrature::gauss<double, 20>;
constexpr double kCut = 700.0;
constexpr int kPanels = 400; // per segment

struct Hayakawa {
    double a2;  // 1/(Gamma tauL)  (0 without viscous drag)
    double cp;  // 2 (Delta - gbar)/Gamma, slope for v > 0
    double cm;  // 2 (Delta + gbar)/Gamma, slope magnitude for v < 0
    double v_min = 0, phi_min = 0, lo = 0, hi = 0;

    double phi(double v) const { return a2 * v * v + (v >= 0 ? cp * v : -cm * v); }
    double q(double v) const { return std::exp(-(phi(v) - phi_min)); }

    explicit Hayakawa(const ModelParams& p) {
        a2 = p.inverse_relaxation() / p.noise;
        cp = 2.0 * (p.friction - p.bias) / p.noise;
        cm = 2.0 * (p.friction + p.bias) / p.noise;
        if (cp < 0 && a2 > 0) v_min = -cp / (2 * a2);
        if (cm < 0 && a2 > 0) v_min = cm / (2 * a2);
        phi_min = phi(v_min);
        auto edge = [&](double dir) { // expand until phi - phi_min > kCut, then bisect
            double step = 1.0 / (std::fabs(cp) + std::fabs(cm) + std::sqrt(a2));
            double inner = v_min, outer = v_min + dir * step;
            while (phi(outer) - phi_min < kCut) {
                inner = outer;
                step *= 2;
                outer = v_min + dir * step;
            }
            for (int k = 0; k < 200; ++k) {
                const double mid = 0.5 * (inner + outer);
                (phi(mid) - phi_min < kCut ? inner : outer) = mid;
            }
            return outer;
        };
        lo = edge(-1.0);
        hi = edge(+1.0);
    }

    std::vector<double> breaks(double extra) const {
        std::vector<double> b{lo, hi};
        for (double x : {0.0, v_min, extra})
            if (x > lo && x < hi) b.push_back(x);
        std::sort(b.begin(), b.end());
        b.erase(std::unique(b.begin(), b.end()), b.end());
        return b;
    }

    /// Panel edges: kPanels equal panels per segment between breaks.
    std::vector<double> edges(double extra) const {
        const auto b = breaks(extra);
        std::vector<double> e;
        for (std::size_t s = 0; s + 1 < b.size(); ++s)
            for (int k = 0; k < kPanels; ++k) e.push_back(b[s] + (b[s + 1] - b[s]) * k / kPanels);
        e.push_back(b.back());
        return e;
    }

    template <class F>
    static double panel(F f, double a, double b) {
        return Rule::integrate(f, a, b);
    }

    template <class F>
    double integrate(F f, double extra = 0.0) const {
        const auto e = edges(extra);
        double s = 0.0;
        for (std::size_t k = 0; k + 1 < e.size(); ++k) s += panel(f, e[k], e[k + 1]);
        return s;
    }
};

void check(const ModelParams& p) {
    validate(p);
    if (!has_stationary_state(p))
        throw InvalidParameter("bias", "no stationary state: with relaxation inf, |bias| must be < friction");
}

} // namespace

// ---- Hayakawa density ----------------------------------------------------------

// Gauss-Legendre nodes and weights covering [a, b] (clipped to the support),
// with panels split at the kink and the mode and small enough that phi changes
// by at most ~1 across each: exp(-phi) is then a mildly varying analytic
// function on every panel and 20 points integrate it to rounding, in the
// bulk and deep in the tails alike.
template <class Visit>
void HayakawaDensity::visit_nodes(double a, double b, Visit&& visit) const {
    a = std::max(a, lo_);
    b = std::min(b, hi_);
    if (!(a < b)) return;
    std::array<double, 4> cuts{a, 0.0, mode_, b};
    std::sort(cuts.begin() + 1, cuts.begin() + 3);
    const auto& x = Rule::abscissa();
    const auto& w = Rule::weights();
    double left = a;
    for (std::size_t k = 1; k < cuts.size(); ++k) {
        const double right = cuts[k];
        if (right <= left || right > b) continue;
        // phi is convex: its minimum on [left, right] is at the mode clamped into it.
        const double m = std::clamp(mode_, left, right);
        const double variation = potential(left) + potential(right) - 2.0 * potential(m);
        const int panels = static_cast<int>(std::min(std::ceil(variation), 1e5)) + 1;
        const double width = (right - left) / panels;
        for (int j = 0; j < panels; ++j) {
            const double c = left + (j + 0.5) * width, r = 0.5 * width;
            for (std::size_t i = 0; i < x.size(); ++i) {
                visit(c - r * x[i], r * w[i]);
                visit(c + r * x[i], r * w[i]);
            }
        }
        left = right;
    }
}

HayakawaDensity::HayakawaDensity(const ModelParams& p) {
    check(p);
    const Hayakawa h(p);
    a2_ = h.a2;
    cp_ = h.cp;
    cm_ = h.cm;
    mode_ = h.v_min;
    phi_min_ = h.phi_min;
    lo_ = h.lo;
    hi_ = h.hi;
    double z = 0.0, first = 0.0;
    visit_nodes(lo_, hi_, [&](double v, double w) {
        const double q = std::exp(-potential(v));
        z += w * q;
        first += w * v * q;
    });
    inv_z_ = 1.0 / z;
    mean_ = first / z;
    // Centred second pass: E[V^2] - M0^2 would cancel when |M0| >> sd.
    double second = 0.0;
    visit_nodes(lo_, hi_, [&](double v, double w) { second += w * (v - mean_) * (v - mean_) * std::exp(-potential(v)); });
    variance_ = second / z;
}

double HayakawaDensity::potential(double v) const {
    return a2_ * v * v + (v >= 0 ? cp_ * v : -cm_ * v) - phi_min_;
}

double HayakawaDensity::operator()(double v) const {
    if (std::isinf(v)) return 0.0;
    return std::exp(-potential(v)) * inv_z_;
}

double HayakawaDensity::probability(double a, double b) const {
    if (std::isnan(a) || std::isnan(b)) throw InvalidParameter("v", "probability(a, b): a and b must not be NaN");
    if (a > b) return -probability(b, a);
    double s = 0.0;
    visit_nodes(a, b, [&](double v, double w) { s += w * std::exp(-potential(v)); });
    return s * inv_z_;
}

double hayakawa_potential(const ModelParams& p, double v) {
    check(p);
    return Hayakawa(p).phi(v);
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
    check(p);
    const Hayakawa h(p);
    const double z = h.integrate([&](double u) { return h.q(u); });
    const double m0 = h.integrate([&](double u) { return u * h.q(u); }) / z;
    const double var = h.integrate([&](double u) { return (u - m0) * (u - m0) * h.q(u); }, m0) / z;

    // F at the panel edges, from the nearer end; then F^2/q panel by panel.
    const auto e = h.edges(m0);
    auto flux = [&](double u) { return (u - m0) * h.q(u); };
    const std::size_t n = e.size();
    std::vector<double> f_edge(n, 0.0);
    for (std::size_t k = 1; k < n && e[k] <= m0; ++k) f_edge[k] = f_edge[k - 1] + Hayakawa::panel(flux, e[k - 1], e[k]);
    for (std::size_t k = n - 1; k-- > 0 && e[k] >= m0;) f_edge[k] = f_edge[k + 1] - Hayakawa::panel(flux, e[k], e[k + 1]);
    double integral = 0.0;
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const double a = e[k], b = e[k + 1];
        const bool left = b <= m0;
        auto big_f = [&](double v) {
            return left ? f_edge[k] + Hayakawa::panel(flux, a, v) : f_edge[k + 1] - Hayakawa::panel(flux, v, b);
        };
        integral += Hayakawa::panel([&](double v) {
            const double f = big_f(v);
            return f * (f / h.q(v));
        }, a, b);
    }
    const double d = 4.0 / p.noise * integral / z;
    return {m0, d, var};
}

double dry_friction_mobility(const ModelParams& p) {
    const double g = p.bias / p.friction;
    return p.noise / p.friction * g / (1 - g * g);
}

double dry_friction_diffusivity(const ModelParams& p) {
    const double g = p.bias / p.friction, g2 = g * g;
    const double s = scales_of(p).diffusivity;
    return s * (5 * g2 * g2 + 22 * g2 + 5) / (4 * std::pow(1 - g2, 4));
}

// ---- Pure dry friction, transient ---------------------------------------------

namespace {

using Real = long double;
namespace bmc = boost::math::constants;

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

// Nondimensional closed forms (Delta = Gamma = 1), MODEL.md section 9.

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
