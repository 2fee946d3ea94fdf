// White-noise references by one-dimensional quadrature (MODEL.md section 7).
//
// The density is written q(v) = exp(-(phi(v) - phi_min)) with phi convex and
// piecewise quadratic (kink at v = 0), so it never overflows; the integration
// range is cut where q < e^-700. F(v) is integrated from whichever end is
// nearer in sign (F < 0 everywhere and vanishes at both ends), so F^2/q keeps
// its relative precision in the tails. Adaptive Gauss-Kronrod (61 points)
// with breakpoints at the kink and at the mode gives ~1e-13 relative accuracy.
#include "stickslip/analytic.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <vector>

namespace stickslip {

namespace {

using boost::math::quadrature::gauss_kronrod;
constexpr double kTol = 1e-14;
constexpr unsigned kDepth = 20;
constexpr double kCut = 700.0;

struct Hayakawa {
    double a2;  // 1/(Gamma tauL)  (0 without viscous drag)
    double cp;  // 2 (Delta - gbar)/Gamma, slope for v > 0
    double cm;  // 2 (Delta + gbar)/Gamma, slope magnitude for v < 0
    double v_min, phi_min, lo, hi;
    std::vector<double> breaks; // sorted: lo, (0), (v_min), hi

    double phi(double v) const { return a2 * v * v + (v >= 0 ? cp * v : -cm * v); }
    double q(double v) const { return std::exp(-(phi(v) - phi_min)); }

    explicit Hayakawa(const ModelParams& p) {
        a2 = p.inverse_relaxation() / p.noise;
        cp = 2.0 * (p.friction - p.bias) / p.noise;
        cm = 2.0 * (p.friction + p.bias) / p.noise;
        v_min = 0.0;
        if (cp < 0 && a2 > 0) v_min = -cp / (2 * a2);
        if (cm < 0 && a2 > 0) v_min = cm / (2 * a2);
        phi_min = phi(v_min);
        // Expand outwards until phi - phi_min exceeds the cut, then bisect.
        auto edge = [&](double dir) {
            double step = 1.0 / (std::fabs(cp) + std::fabs(cm) + std::sqrt(a2) + 1e-300);
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
        breaks = {lo, hi};
        if (0.0 > lo && 0.0 < hi) breaks.push_back(0.0);
        if (v_min != 0.0) breaks.push_back(v_min);
        std::sort(breaks.begin(), breaks.end());
    }

    template <class F>
    double integrate(F f, double a, double b) const {
        if (b <= a) return 0.0;
        double s = 0.0;
        double x0 = a;
        for (double br : breaks) {
            if (br <= x0) continue;
            if (br >= b) break;
            s += gauss_kronrod<double, 61>::integrate(f, x0, br, kDepth, kTol);
            x0 = br;
        }
        return s + gauss_kronrod<double, 61>::integrate(f, x0, b, kDepth, kTol);
    }
};

} // namespace

double hayakawa_potential(const ModelParams& p, double v) { return Hayakawa(p).phi(v); }

double hayakawa_density(const ModelParams& p, double v) {
    validate(p);
    if (!has_stationary_state(p))
        throw InvalidParameter("bias", "no stationary state: with relaxation inf, |bias| must be < friction");
    const Hayakawa h(p);
    const double z = h.integrate([&](double u) { return h.q(u); }, h.lo, h.hi);
    if (v < h.lo || v > h.hi) return 0.0;
    return h.q(v) / z;
}

WhiteNoiseReference white_noise_reference(const ModelParams& p) {
    validate(p);
    if (!has_stationary_state(p))
        throw InvalidParameter("bias", "no stationary state: with relaxation inf, |bias| must be < friction");
    const Hayakawa h(p);
    const double z = h.integrate([&](double u) { return h.q(u); }, h.lo, h.hi);
    const double m0 = h.integrate([&](double u) { return u * h.q(u); }, h.lo, h.hi) / z;
    const double var = h.integrate([&](double u) { return (u - m0) * (u - m0) * h.q(u); }, h.lo, h.hi) / z;
    auto flux = [&](double u) { return (u - m0) * h.q(u); };
    // F_q(v) = int_{lo}^{v} (u - M0) q du, from the nearer end to avoid cancellation.
    auto big_f = [&](double v) {
        if (v <= m0) return h.integrate(flux, h.lo, v);
        return -h.integrate(flux, v, h.hi);
    };
    auto integrand = [&](double v) {
        const double f = big_f(v);
        return f * (f / h.q(v));
    };
    // m0 is where F turns; add it as a breakpoint of the outer integral.
    Hayakawa outer = h;
    if (m0 > h.lo && m0 < h.hi) {
        outer.breaks.push_back(m0);
        std::sort(outer.breaks.begin(), outer.breaks.end());
    }
    const double d = 4.0 / p.noise * outer.integrate(integrand, h.lo, h.hi) / z;
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

} // namespace stickslip
