// SPDX-License-Identifier: BSD-3-Clause
// The drift law's exact properties: Lipschitz constant, potential, confinement,
// scaling and coarsening (drift_law.hpp says why the law is piecewise affine).
#include "stickslip/drift_law.hpp"

#include <algorithm>
#include <cmath>

#include "stickslip/errors.hpp"

namespace stickslip {

DriftLaw affine_drift_law(double relaxation, double bias) {
    DriftLaw b;
    b.kind = DriftLaw::Kind::Affine;
    b.slope = std::isinf(relaxation) ? -0.0 : -(1.0 / relaxation);
    b.intercept = bias;
    return b;
}

double lipschitz_constant(const DriftLaw& b) {
    double l = 0.0;
    for (int j = 0; j < b.pieces(); ++j) l = std::max(l, std::fabs(b.piece_slope(j)));
    return l;
}

namespace {

/// int_a^c of piece j's line (a <= c, both within the piece).
double piece_integral(const DriftLaw& b, int j, double a, double c) {
    const double s = b.piece_slope(j), k = b.piece_intercept(j);
    return 0.5 * s * (c * c - a * a) + k * (c - a);
}

} // namespace

double drift_potential(const DriftLaw& b, double v) {
    // Sum the exact integral of each piece's line between 0 and v, from the
    // piece at 0 outward.
    if (b.affine()) return 0.5 * b.slope * v * v + b.intercept * v;
    double sum = 0.0;
    if (v >= 0) {
        for (int j = b.piece(0.0); j <= b.piece(v); ++j) {
            const double a = std::max(0.0, b.piece_lower(j)), c = std::min(v, b.piece_upper(j));
            if (c > a) sum += piece_integral(b, j, a, c);
        }
        return sum;
    }
    for (int j = b.piece(0.0); j >= b.piece(v); --j) {
        const double a = std::max(v, b.piece_lower(j)), c = std::min(0.0, b.piece_upper(j));
        if (c > a) sum += piece_integral(b, j, a, c);
    }
    return -sum;
}

DriftPotential::DriftPotential(const DriftLaw& b) : law_(b) {
    if (b.affine()) return;
    zero_piece_ = b.piece(0.0);
    before_.assign(static_cast<std::size_t>(b.pieces()), 0.0);
    // The same sums, in the same order, as drift_potential's loops stopped
    // before piece j.
    double sum = 0.0;
    for (int j = zero_piece_; j < b.pieces(); ++j) {
        before_[static_cast<std::size_t>(j)] = sum;
        const double a = std::max(0.0, b.piece_lower(j)), c = b.piece_upper(j);
        if (c > a && std::isfinite(c)) sum += piece_integral(b, j, a, c);
    }
    sum = 0.0;
    for (int j = zero_piece_; j >= 0; --j) {
        if (j < zero_piece_) before_[static_cast<std::size_t>(j)] = sum;
        const double a = b.piece_lower(j), c = std::min(0.0, b.piece_upper(j));
        if (c > a && std::isfinite(a)) sum += piece_integral(b, j, a, c);
    }
}

double DriftPotential::operator()(double v) const {
    const DriftLaw& b = law_;
    if (b.affine()) return 0.5 * b.slope * v * v + b.intercept * v;
    // piece() rounds: v just below a knot may be given the piece above it,
    // whose term drift_potential's loop skips (and the reverse for v < 0).
    int j = b.piece(v);
    if (v >= 0) {
        while (j > zero_piece_ && v < b.piece_lower(j)) --j;
        double sum = before_[static_cast<std::size_t>(j)];
        const double a = std::max(0.0, b.piece_lower(j)), c = std::min(v, b.piece_upper(j));
        if (c > a) sum += piece_integral(b, j, a, c);
        return sum;
    }
    while (j < zero_piece_ && v > b.piece_upper(j)) ++j;
    double sum = j == zero_piece_ ? 0.0 : before_[static_cast<std::size_t>(j)];
    const double a = std::max(v, b.piece_lower(j)), c = std::min(0.0, b.piece_upper(j));
    if (c > a) sum += piece_integral(b, j, a, c);
    return -sum;
}

bool confines(const DriftLaw& b, double friction) {
    const int last = b.pieces() - 1;
    const double s_hi = b.piece_slope(last), s_lo = b.piece_slope(0);
    const bool up = s_hi < 0 || (s_hi == 0 && b.piece_intercept(last) - friction < 0);
    const bool down = s_lo < 0 || (s_lo == 0 && b.piece_intercept(0) + friction > 0);
    return up && down;
}

DriftLaw scaled_drift_law(const DriftLaw& b, double velocity_unit, double acceleration_unit) {
    DriftLaw s = b;
    if (b.affine()) {
        s.slope = b.slope * velocity_unit / acceleration_unit;
        s.intercept = b.intercept / acceleration_unit;
        return s;
    }
    s.first = b.first / velocity_unit;
    s.spacing = b.spacing / velocity_unit;
    s.inv_spacing = 1.0 / s.spacing;
    for (int k = 0; k < b.knots; ++k) s.values[k] = b.values[k] / acceleration_unit;
    return s;
}

DriftLaw coarsened_drift_law(const DriftLaw& b) {
    if (b.affine() || b.knots < 3) return b;
    DriftLaw c = b;
    c.knots = (b.knots + 1) / 2;
    c.spacing = 2.0 * b.spacing;
    c.inv_spacing = 1.0 / c.spacing;
    for (int k = 0; k < c.knots; ++k) c.values[k] = b.values[2 * k];
    for (int k = c.knots; k < DriftLaw::max_knots; ++k) c.values[k] = 0.0;
    return c;
}

int zero_knot(const DriftLaw& b) {
    const long k = std::lround(-b.first * b.inv_spacing);
    if (b.kind != DriftLaw::Kind::Knots || k < 1 || k > b.knots - 2 || b.knot(static_cast<int>(k)) != 0.0)
        throw InvalidParameter("knots", "the drift law's knots must include v = 0"); // make_drift_law's invariant
    return static_cast<int>(k);
}

} // namespace stickslip
