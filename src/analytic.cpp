// White-noise references by one-dimensional quadrature (MODEL.md section 7).
//
// The density is written q(v) = exp(-(phi(v) - phi_min)) with phi convex and
// piecewise quadratic (kink at v = 0), so it never overflows; the range is cut
// where q < e^-700. Integrals use composite 20-point Gauss-Legendre panels on
// segments split at the kink, the mode and M0 (the integrand is analytic on
// each panel, so every panel is exact to rounding). F(v) = int (u - M0) q du is
// accumulated from the left end for v <= M0 and from the right end (with a
// minus sign) for v > M0: F < 0 everywhere and vanishes at both ends, so this
// keeps its relative precision in the tails, where F^2/q is evaluated.
#include "stickslip/analytic.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <vector>

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

double hayakawa_potential(const ModelParams& p, double v) {
    check(p);
    return Hayakawa(p).phi(v);
}

double hayakawa_density(const ModelParams& p, double v) {
    check(p);
    const Hayakawa h(p);
    if (v < h.lo || v > h.hi) return 0.0;
    const double z = h.integrate([&](double u) { return h.q(u); });
    return h.q(v) / z;
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

} // namespace stickslip
