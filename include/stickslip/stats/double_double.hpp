// SPDX-License-Identifier: BSD-3-Clause
// stickslip/stats/double_double.hpp -- the one double-double arithmetic.
//
// An unevaluated sum hi + lo of two doubles carries about 106 significant
// bits. The project needs it in three places: the portable exp/log of the
// kernels (random/portable_math.hpp, host and device alike), the exact
// moments of a run's sums (stats/moment_sums.hpp) and the mode of the
// white-noise density (analytic.hpp). The error-free transformations here use
// no fused multiply-add (Dekker's product with Veltkamp's split), so the bits
// are the same on every machine, CPU and GPU, whatever the compiler contracts
// (the build has -ffp-contract=off besides).
#pragma once

/// \file
/// Double-double numbers and their error-free transformations. The comment at
/// the top of this header explains the design.

#include "stickslip/config.hpp"

namespace stickslip::detail::dd {

/// An unevaluated sum hi + lo with |lo| <= ulp(hi) / 2 (0 by default).
struct DD {
    double hi = 0, lo = 0; ///< the leading part and the rounding error below it
};

/// s + e = a + b exactly (Knuth).
STICKSLIP_HD inline DD two_sum(double a, double b) {
    const double s = a + b;
    const double bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

/// s + e = a + b exactly, for |a| >= |b| or a == 0 (Dekker).
STICKSLIP_HD inline DD fast_two_sum(double a, double b) {
    const double s = a + b;
    return {s, b - (s - a)};
}

/// a = hi + lo with hi and lo of 26 significant bits (Veltkamp; |a| < 2^995).
STICKSLIP_HD inline DD split(double a) {
    const double c = 134217729.0 * a; // 2^27 + 1
    const double hi = c - (c - a);
    return {hi, a - hi};
}

/// p + e = a * b exactly, without a fused multiply-add (Dekker).
STICKSLIP_HD inline DD two_prod(double a, double b) {
    const double p = a * b;
    const DD x = split(a), y = split(b);
    const double e = ((x.hi * y.hi - p) + x.hi * y.lo + x.lo * y.hi) + x.lo * y.lo;
    return {p, e};
}

STICKSLIP_HD inline DD add(DD a, DD b) {
    DD s = two_sum(a.hi, b.hi);
    const DD t = two_sum(a.lo, b.lo);
    s.lo += t.hi;
    s = fast_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return fast_two_sum(s.hi, s.lo);
}

STICKSLIP_HD inline DD add(DD a, double b) {
    DD s = two_sum(a.hi, b);
    s.lo += a.lo;
    return fast_two_sum(s.hi, s.lo);
}

STICKSLIP_HD inline DD mul(DD a, DD b) {
    DD p = two_prod(a.hi, b.hi);
    p.lo += a.hi * b.lo + a.lo * b.hi;
    return fast_two_sum(p.hi, p.lo);
}

STICKSLIP_HD inline DD mul(DD a, double b) {
    DD p = two_prod(a.hi, b);
    p.lo += a.lo * b;
    return fast_two_sum(p.hi, p.lo);
}

/// a / b, three quotient digits.
STICKSLIP_HD inline DD div(DD a, DD b) {
    const double q1 = a.hi / b.hi;
    DD r = add(a, mul(b, -q1));
    const double q2 = r.hi / b.hi;
    r = add(r, mul(b, -q2));
    const double q3 = r.hi / b.hi;
    return add(fast_two_sum(q1, q2), q3);
}

} // namespace stickslip::detail::dd
