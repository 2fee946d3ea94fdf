// SPDX-License-Identifier: BSD-3-Clause
// stickslip/drift_law.hpp -- the drift law b(v): affine, or piecewise affine on
// uniform knots.
//
// The paper's system is dV/dt + dphi(V) contains b(V) + force, with b any
// Lipschitz function; its numerical section, and the `--relaxation`/`--bias`
// flags, take b affine. A user's law (an expression, a table, a Python
// callable) reaches the engines as the piecewise-affine interpolant of b on
// uniform knots, built once per run (make_drift_law, drift_input.hpp), for
// three reasons:
//  * a kernel may not call back into a parser or a std::function (GPU, SIMD,
//    checkpoints): this struct is plain data of a bounded size;
//  * within a piece the dynamics is as linear as with the affine law, so the
//    exact engines stay exact (the PDMP's flow, landing and displacement are
//    closed form per piece; a knot crossing is one more event);
//  * the interpolation error is O(h^2 b'') for a smooth law and O(h) at a kink,
//    and measurable like a time step's: run again with knots twice as far
//    apart (--check-knots).
// Uniform knots make the piece of v one multiply and a clamp (O(1), no search).
// Outside the knots the law is continued by its outer pieces, so the range is
// chosen to hold every velocity a run reaches (drift_input.cpp says how).
//
// The affine law keeps its own exact form (slope -1/relaxation, intercept
// bias): every number computed with it is bitwise what it was before this
// type existed.
#pragma once

#include <vector>

/// \file
/// The drift law b(v) [m s^-2] of velocity v [m/s]: affine, or piecewise affine
/// on uniform knots. The comment at the top of this header explains the design.

#include <cmath>

#include "stickslip/config.hpp"

namespace stickslip {

/// b(v) in SI units (v in m/s, b in m s^-2). Plain data (trivially copyable,
/// fixed size), usable in kernels.
struct DriftLaw {
    /// Most knots a law may have (so the struct has a fixed size, 16 KiB of values).
    static constexpr int max_knots = 2049;

    /// Affine: b = slope v + intercept. Knots: the interpolant of values[] on
    /// v_k = first + k spacing, k = 0..knots-1, continued by the outer pieces.
    enum class Kind { Affine, Knots };

    Kind kind = Kind::Affine; ///< which form
    double slope = 0.0;       ///< affine: db/dv [s^-1] (-1/relaxation)
    double intercept = 0.0;   ///< affine: b(0) [m s^-2] (bias)
    int knots = 0;            ///< knots: their count, 2..max_knots
    double first = 0.0;       ///< knots: v_0 [m/s]
    double spacing = 0.0;     ///< knots: v_{k+1} - v_k [m/s], > 0
    double inv_spacing = 0.0; ///< knots: 1/spacing [s/m]
    double values[max_knots] = {}; ///< knots: b(v_k) [m s^-2]

    /// True for the affine law.
    STICKSLIP_HD bool affine() const { return kind == Kind::Affine; }
    /// Number of affine pieces: 1 (affine) or knots - 1.
    STICKSLIP_HD int pieces() const { return kind == Kind::Affine ? 1 : knots - 1; }

    /// The piece that holds v: 0..pieces()-1; v below the first knot is in
    /// piece 0, above the last in the last piece (the outer pieces continue).
    /// At a knot v_k (k inside) the piece above it, k.
    STICKSLIP_HD int piece(double v) const {
        if (kind == Kind::Affine) return 0;
        const double r = (v - first) * inv_spacing;
        if (!(r > 0.0)) return 0; // also NaN
        const double last = static_cast<double>(knots - 2);
        return r >= last ? knots - 2 : static_cast<int>(r);
    }
    /// Slope of piece j [s^-1].
    STICKSLIP_HD double piece_slope(int j) const {
        return kind == Kind::Affine ? slope : (values[j + 1] - values[j]) * inv_spacing;
    }
    /// Intercept of piece j's line at v = 0 [m s^-2]: b = piece_slope(j) v + piece_intercept(j) on the piece.
    STICKSLIP_HD double piece_intercept(int j) const {
        if (kind == Kind::Affine) return intercept;
        return values[j] - piece_slope(j) * knot(j);
    }
    /// Knot k [m/s] (knots only).
    STICKSLIP_HD double knot(int k) const { return first + spacing * static_cast<double>(k); }
    /// Lower end of piece j [m/s]; -inf for piece 0 (it continues).
    STICKSLIP_HD double piece_lower(int j) const { return j == 0 ? -HUGE_VAL : knot(j); }
    /// Upper end of piece j [m/s]; +inf for the last piece.
    STICKSLIP_HD double piece_upper(int j) const { return j >= pieces() - 1 ? HUGE_VAL : knot(j + 1); }

    /// b(v) [m s^-2]. The affine law computes -v/relaxation + bias as before
    /// (v * slope + intercept; the product's sign does not change its bits).
    STICKSLIP_HD double operator()(double v) const {
        if (kind == Kind::Affine) return v * slope + intercept;
        const int j = piece(v);
        return values[j] + (v - knot(j)) * piece_slope(j);
    }
};

/// The index k of the knot at v = 0 of a knots law (make_drift_law puts one
/// there, so that V reaching 0 is a knot: the exact engines' landing), with
/// 1 <= k <= knots - 2. Throws InvalidParameter("knots") where there is none.
int zero_knot(const DriftLaw& b);

/// The affine law b(v) = -v/relaxation + bias (relaxation may be +inf: no drag).
DriftLaw affine_drift_law(double relaxation, double bias);

/// Largest |b'| over the pieces [s^-1]: the law's Lipschitz constant (an
/// explicit step of length h is stable for h L < 1).
double lipschitz_constant(const DriftLaw& b);

/// int_0^v b(u) du [m^2 s^-3]: piecewise quadratic, exact. The pieces are
/// summed from v = 0 outward, so that DriftPotential gives the same bits.
double drift_potential(const DriftLaw& b, double v);

/// drift_potential(b, v), bit for bit, in O(1) a call after O(knots) set-up:
/// the white-noise quadratures evaluate it millions of times (a sweep's
/// white-noise reference for a 1025-knot law took 5 s at O(knots) a call).
class DriftPotential {
public:
    /// Sums the whole pieces once (O(knots)); keeps a copy of the law.
    explicit DriftPotential(const DriftLaw& b);
    /// int_0^v b(u) du [m^2 s^-3].
    double operator()(double v) const;

private:
    DriftLaw law_;
    int zero_piece_ = 0;          ///< law_.piece(0)
    std::vector<double> before_; ///< per piece: the sum over the whole pieces between 0 and it
};

/// Whether a stationary state can exist with friction Delta [m s^-2]: the law
/// pulls back beyond the knots, b(v) - Delta < 0 for all large v and
/// b(v) + Delta > 0 for all large negative v (outer slopes < 0, or = 0 with
/// the outer value inside (-Delta, Delta)).
bool confines(const DriftLaw& b, double friction);

/// The law in the nondimensional system: v' = v/velocity_unit, b' = b/acceleration_unit.
DriftLaw scaled_drift_law(const DriftLaw& b, double velocity_unit, double acceleration_unit);

/// The knots' law with every second knot dropped, keeping the knot at v = 0
/// (spacing doubled), for a caller that holds only the knots. (--check-knots
/// instead samples the law itself again on (knots + 1)/2 knots over the same
/// range: make_drift_law.) An affine law is returned unchanged.
DriftLaw coarsened_drift_law(const DriftLaw& b);

} // namespace stickslip
