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

double drift_potential(const DriftLaw& b, double v) {
    // Sum the exact integral of each piece's line between 0 and v.
    if (b.affine()) return 0.5 * b.slope * v * v + b.intercept * v;
    const double lo = std::min(0.0, v), hi = std::max(0.0, v);
    double sum = 0.0;
    for (int j = b.piece(lo); j <= b.piece(hi); ++j) {
        const double a = std::max(lo, b.piece_lower(j)), c = std::min(hi, b.piece_upper(j));
        if (!(c > a)) continue;
        const double s = b.piece_slope(j), k = b.piece_intercept(j);
        sum += 0.5 * s * (c * c - a * a) + k * (c - a);
    }
    return v >= 0 ? sum : -sum;
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
