// SPDX-License-Identifier: BSD-3-Clause
// White-noise references for any drift law (drift_law_quadrature.hpp says how).
#include "stickslip/drift_law_quadrature.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/quadrature/gauss.hpp>

#include "stickslip/drift_input.hpp"
#include "stickslip/errors.hpp"

namespace stickslip {
namespace {

using Rule = boost::math::quadrature::gauss<double, 10>;

/// Gauss-Legendre nodes and weights on [a, b]: f(node, weight) for each node.
template <class F>
void nodes(double a, double b, F&& f) {
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    const auto& x = Rule::abscissa();
    const auto& w = Rule::weights();
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x[i] == 0.0) {
            f(mid, half * w[i]);
            continue;
        }
        f(mid - half * x[i], half * w[i]);
        f(mid + half * x[i], half * w[i]);
    }
}

constexpr double kPanelRise = 0.5; // most Phi changes across one panel
constexpr double kDomainDrop = 60; // Phi below its maximum where the domain ends

} // namespace

double DriftLawWhiteNoise::phi(double v) const {
    return 2.0 / noise_ * (potential_(v) - friction_ * std::fabs(v)) - phi_max_;
}

template <class F>
double DriftLawWhiteNoise::integrate(double a, double b, F&& f) const {
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < cuts_.size(); ++k) {
        const double lo = std::max(a, cuts_[k]), hi = std::min(b, cuts_[k + 1]);
        if (!(hi > lo)) continue;
        nodes(lo, hi, [&](double v, double w) { sum += w * f(v); });
    }
    return sum;
}

DriftLawWhiteNoise::DriftLawWhiteNoise(const ModelParams& given) {
    ModelParams p = given;
    p.tau = 0.0;
    validate(p);
    law_ = make_drift_law(p);
    potential_ = DriftPotential(law_);
    friction_ = p.friction;
    noise_ = p.noise;
    build();
}

DriftLawWhiteNoise::DriftLawWhiteNoise(const DriftLaw& law, double friction, double noise)
    : law_(law), potential_(law_), friction_(friction), noise_(noise) {
    build();
}

double DriftLawWhiteNoise::lower_end(double drop) const {
    // From the outer break outwards while Phi is above -drop; where it is far
    // below there already (a table over a wide range), inwards over the knots
    // to the outermost one still within a margin of -drop, keeping the next.
    const double margin = 5;
    double v = breaks_.front();
    if (phi(v) < -drop - margin) {
        std::size_t k = 0;
        while (k + 1 < breaks_.size() && phi(breaks_[k + 1]) < -drop - margin) ++k;
        return breaks_[k];
    }
    for (double step = noise_ / friction_ / 64; phi(v) > -drop; step *= 1.25) v -= step;
    return v;
}

double DriftLawWhiteNoise::upper_end(double drop) const {
    const double margin = 5;
    double v = breaks_.back();
    if (phi(v) < -drop - margin) {
        std::size_t k = breaks_.size() - 1;
        while (k > 0 && phi(breaks_[k - 1]) < -drop - margin) --k;
        return breaks_[k];
    }
    for (double step = noise_ / friction_ / 64; phi(v) > -drop; step *= 1.25) v += step;
    return v;
}

void DriftLawWhiteNoise::build() {
    // The points where the net force b - friction sgn v changes: the knots
    // (and 0) bound pieces on which Phi is one quadratic.
    std::vector<double> breaks{0.0};
    if (!law_.affine())
        for (int k = 0; k < law_.knots; ++k) breaks.push_back(law_.knot(k));
    breaks_ = breaks;
    std::sort(breaks_.begin(), breaks_.end());
    const double unit = noise_ / friction_;
    // Phi's maximum: at a break or where a piece's net force vanishes.
    phi_max_ = 0.0;
    double best = -HUGE_VAL;
    auto consider = [&](double v) {
        if (std::isfinite(v)) best = std::max(best, phi(v));
    };
    for (double v : breaks) consider(v);
    for (int j = 0; j < law_.pieces(); ++j) {
        const double s = law_.piece_slope(j), c = law_.piece_intercept(j);
        if (s == 0.0) continue;
        for (int sign : {-1, 1}) {
            const double v = -(c - sign * friction_) / s;
            if (v * sign > 0 && v >= law_.piece_lower(j) && v <= law_.piece_upper(j)) consider(v);
        }
    }
    phi_max_ = best;
    // The domain: out from the outer breaks until Phi has fallen kDomainDrop.
    lo_ = *std::min_element(breaks.begin(), breaks.end());
    hi_ = *std::max_element(breaks.begin(), breaks.end());
    for (double step = unit; phi(lo_) > -kDomainDrop; step *= 2) lo_ -= step;
    for (double step = unit; phi(hi_) > -kDomainDrop; step *= 2) hi_ += step;
    breaks.push_back(lo_);
    breaks.push_back(hi_);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    // Panels: within each piece, short enough that Phi rises at most kPanelRise
    // (|Phi'| is largest at a piece's ends: it is linear within it).
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
        const double a = breaks[k], b = breaks[k + 1];
        if (b <= lo_ || a >= hi_) continue;
        const double mid = 0.5 * (a + b);
        const double sgn = mid > 0 ? 1.0 : -1.0;
        auto slope = [&](double v) { return std::fabs(2.0 / noise_ * (law_(v) - sgn * friction_)); };
        const double g = std::max(slope(a), slope(b));
        const int n = static_cast<int>(std::min(1e6, std::ceil(g * (b - a) / kPanelRise))) + 1;
        for (int i = 0; i < n; ++i) cuts_.push_back(a + (b - a) * i / n);
    }
    cuts_.push_back(hi_);

    auto weight = [&](double v) { return std::exp(phi(v)); };
    const double z = integrate(lo_, hi_, weight);
    inv_z_ = 1.0 / z;
    double m0 = integrate(lo_, hi_, [&](double v) { return v * weight(v); }) * inv_z_;
    // The quadrature is good to about 1e-12 of the velocity's spread: a mean
    // below that (an odd law's, 0 by symmetry) is reported as 0, not as
    // rounding noise such as 3e-17.
    const double spread = std::sqrt(integrate(lo_, hi_, [&](double v) { return v * v * weight(v); }) * inv_z_);
    if (std::fabs(m0) < 1e-12 * spread) m0 = 0.0;
    const double var = integrate(lo_, hi_, [&](double v) { return (v - m0) * (v - m0) * weight(v); }) * inv_z_;
    // F from the nearer tail: left partial sums below M0, right ones above.
    const std::size_t panels = cuts_.size() - 1;
    std::vector<double> left(panels + 1, 0.0), right(panels + 1, 0.0);
    auto flux = [&](double u) { return (u - m0) * weight(u) * inv_z_; };
    for (std::size_t k = 0; k < panels; ++k) {
        double s = 0.0;
        nodes(cuts_[k], cuts_[k + 1], [&](double u, double w) { s += w * flux(u); });
        left[k + 1] = left[k] + s;
    }
    for (std::size_t k = panels; k-- > 0;) {
        double s = 0.0;
        nodes(cuts_[k], cuts_[k + 1], [&](double u, double w) { s += w * flux(u); });
        right[k] = right[k + 1] + s;
    }
    double d = 0.0;
    for (std::size_t k = 0; k < panels; ++k) {
        const double a = cuts_[k], b = cuts_[k + 1];
        nodes(a, b, [&](double v, double w) {
            double f = 0.0;
            if (v < m0) {
                f = left[k];
                nodes(a, v, [&](double u, double wu) { f += wu * flux(u); });
            } else {
                f = -right[k + 1];
                nodes(v, b, [&](double u, double wu) { f -= wu * flux(u); });
            }
            const double pv = weight(v) * inv_z_;
            if (pv > 0) d += w * f * f / pv;
        });
    }
    reference_.mobility = m0;
    reference_.variance = var;
    reference_.diffusivity = 4.0 / noise_ * d;
    if (!std::isfinite(reference_.diffusivity) || !std::isfinite(m0) || !std::isfinite(var))
        throw InvalidParameter("drift", "the white-noise quadrature of this law leaves double precision's range; "
                                        "rescale the units towards friction = noise = 1");
}

double DriftLawWhiteNoise::density(double v) const { return std::exp(phi(v)) * inv_z_; }

double DriftLawWhiteNoise::commute_time(double a, double b) const {
    if (!(b > a)) return 0.0;
    if (a < lo_ || b > hi_) return INFINITY;
    return 2.0 / noise_ * integrate(a, b, [&](double v) { return 1.0 / density(v); });
}

double DriftLawWhiteNoise::probability(double a, double b) const {
    if (!(b > a)) return 0.0;
    return std::clamp(integrate(std::max(a, lo_), std::min(b, hi_), [&](double v) { return density(v); }), 0.0, 1.0);
}

} // namespace stickslip
