// SPDX-License-Identifier: BSD-3-Clause
// stickslip/random/portable_math.hpp -- exp, log and log1p of the project's own, so
// that a CUDA device computes the kernels' transcendental functions to the
// same bits as the CPU.
//
// Why: the kernels are one code for the CPU and a GPU (STICKSLIP_HD), and
// their +, -, *, /, sqrt are IEEE operations, correctly rounded on both sides
// (the CPU build uses -ffp-contract=off, the CUDA build -fmad=false, and the
// default -prec-div=true -prec-sqrt=true -ftz=false). Their exp, log and
// log1p are not: the CPU's come from glibc (about 0.52 ulp, and a run-time
// choice between an FMA and a non-FMA variant), a device's from CUDA's math
// library (up to 1 ulp), and the two disagree in the last bit for a fraction
// of arguments. Where the kernels *use* such a value (the ziggurat's tail
// takes log of a uniform; the event scheme's first passage time takes log1p),
// a last-bit difference changes the path; where they only compare it with a
// uniform (exp in the ziggurat's wedge, the Brownian-bridge test), a
// difference matters only when the uniform falls between the two values.
//
// What: portable_exp, portable_log and portable_log1p evaluate the function
// in double-double arithmetic (about 100 correct bits) with nothing but IEEE
// +, -, *, / and exact bit operations, and round once: the correctly rounded
// result, except for arguments whose value lies within ~2^-100 relative of a
// rounding boundary (hard cases, probability ~2^-45 per argument). The same
// bits on every IEEE machine, host or device, whatever libm is installed. They
// are slow (a few hundred flops): the kernels call them only on rare paths.
//
// How the kernels use them (kernel_log, kernel_log1p, kernel_below_exp):
//  * on the host, by default, the kernels keep calling std::log, std::log1p
//    and std::exp, exactly as before, so no CPU result changes by a bit;
//  * on a device (__CUDA_ARCH__), kernel_log and kernel_log1p are
//    portable_log and portable_log1p, and kernel_below_exp(y, a) = (y <
//    exp(a)) is decided with CUDA's fast exp unless y lies within a few ulps
//    of it, where portable_exp decides: the correctly rounded exp's decision;
//  * on the host of a build with STICKSLIP_PORTABLE_MATH=1 (the CMake option),
//    as on the device (with glibc's exp as the fast one).
// glibc is correctly rounded on most arguments, not all: on the kernels'
// arguments (uniforms for the tail's log, the bridge's and the wedge's
// exponents) glibc 2.36 differs from the correctly rounded value on about 8e-4
// of them for log and exp, 5e-2 for log1p (and its FMA and non-FMA variants,
// chosen at run time by the CPU, differ from each other on 1e-4 .. 6e-4). So
// by default the device equals the CPU except where such an argument changes
// a path (the tail's log is a value; a comparison differs only if the uniform
// falls exactly on the misrounded value); with STICKSLIP_PORTABLE_MATH the CPU
// computes what the device computes, bit for bit (docs/gpu.md). The host
// tests (tests/gpu_host, label gpu-host) check the functions against 60-digit
// references and the device's decision rule.
//
// Domain: portable_log, x > 0 (and the IEEE special values); portable_log1p,
// y > -1 (same); portable_exp, correctly rounded for a in [-708, 709.78],
// whose results are normal numbers (below -708 the result is subnormal and
// rounded twice).
#pragma once

/// \file
/// exp, log and log1p in double-double arithmetic: the same bits on the CPU
/// and on a CUDA device. The comment at the top of this header explains the
/// design.

#include <cmath>
#include <cstdint>
#include <cstring>

#include "stickslip/config.hpp"
#include "stickslip/stats/double_double.hpp"

/// Keeps a function out of line: the portable functions are on rare paths,
/// and inlined they would crowd the hot loops that call them (registers on a
/// device, code size on the host).
#if defined(__CUDACC__)
#define STICKSLIP_PM_NOINLINE __noinline__
#elif defined(__GNUC__)
#define STICKSLIP_PM_NOINLINE __attribute__((noinline))
#else
#define STICKSLIP_PM_NOINLINE
#endif

namespace stickslip {

namespace detail::pm {

using namespace detail::dd; // the one double-double arithmetic (stats/double_double.hpp)

/// The bits of a double.
STICKSLIP_HD inline std::uint64_t bits_of(double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

/// The double with bits u.
STICKSLIP_HD inline double from_bits(std::uint64_t u) {
    double x;
    std::memcpy(&x, &u, sizeof x);
    return x;
}

/// 2^n for n in [-1074, 1023], exactly (subnormal below -1022).
STICKSLIP_HD inline double pow2(int n) {
    if (n >= -1022) return from_bits(static_cast<std::uint64_t>(n + 1023) << 52);
    return from_bits(std::uint64_t{1} << (n + 1074));
}

/// ln 2 = ln2_hi + ln2_lo + O(2^-110).
inline constexpr double ln2_hi = 0x1.62e42fefa39efp-1, ln2_lo = 0x1.abc9e3b39803fp-56;

/// log(x) for x = hi + lo, hi in [2^-1022, 2^1022], to about 2^-100 relative
/// (|result| >= 2^-1000 or x within 2^-53 of 1).
STICKSLIP_HD inline DD dd_log(DD x) {
    // x = 2^e m with m in [sqrt(1/2), sqrt(2)), exactly.
    const std::uint64_t b = bits_of(x.hi);
    int e = static_cast<int>((b >> 52) & 0x7ff) - 1023;
    double mh = from_bits((b & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1023} << 52)); // in [1, 2)
    if (mh > 0x1.6a09e667f3bcdp+0) {
        mh *= 0.5;
        ++e;
    }
    const double ml = x.lo * pow2(-e);
    // log(m) = 2 atanh(s), s = (m - 1) / (m + 1), |s| < 0.1716. (mh - 1 is exact.)
    const DD s = div(two_sum(mh - 1.0, ml), add(DD{mh, ml}, 1.0));
    const DD s2 = mul(s, s);
    // P(s2) = sum_k s2^k / (2k + 1): terms k >= 11 (below 2^-55 of the sum)
    // in double, k <= 10 in double-double; k <= 21 reaches 2^-110.
    const double t = s2.hi;
    double q = 0x1.7d05f417d05f4p-6; // 1/43
    q = q * t + 0x1.8f9c18f9c18fap-6;  // 1/41
    q = q * t + 0x1.a41a41a41a41ap-6;  // 1/39
    q = q * t + 0x1.bacf914c1bad0p-6;  // 1/37
    q = q * t + 0x1.d41d41d41d41dp-6;  // 1/35
    q = q * t + 0x1.f07c1f07c1f08p-6;  // 1/33
    q = q * t + 0x1.0842108421084p-5;  // 1/31
    q = q * t + 0x1.1a7b9611a7b96p-5;  // 1/29
    q = q * t + 0x1.2f684bda12f68p-5;  // 1/27
    q = q * t + 0x1.47ae147ae147bp-5;  // 1/25
    q = q * t + 0x1.642c8590b2164p-5;  // 1/23
    constexpr DD inv_odd[10] = {
        {0x1.5555555555555p-2, 0x1.5555555555555p-56},  {0x1.999999999999ap-3, -0x1.999999999999ap-57},
        {0x1.2492492492492p-3, 0x1.2492492492492p-57},  {0x1.c71c71c71c71cp-4, 0x1.c71c71c71c71cp-58},
        {0x1.745d1745d1746p-4, -0x1.745d1745d1746p-59}, {0x1.3b13b13b13b14p-4, -0x1.3b13b13b13b14p-58},
        {0x1.1111111111111p-4, 0x1.1111111111111p-60},  {0x1.e1e1e1e1e1e1ep-5, 0x1.e1e1e1e1e1e1ep-61},
        {0x1.af286bca1af28p-5, 0x1.af286bca1af28p-59},  {0x1.8618618618618p-5, 0x1.8618618618618p-59},
    }; // 1/3, 1/5, ..., 1/21
    DD p{q, 0.0};
    for (int k = 9; k >= 0; --k) p = add(mul(p, s2), inv_odd[k]);
    p = add(mul(p, s2), 1.0);
    const DD log_m = mul(DD{2.0 * s.hi, 2.0 * s.lo}, p);
    if (e == 0) return log_m;
    const double ed = static_cast<double>(e);
    DD e_ln2 = two_prod(ed, ln2_hi);
    e_ln2 = add(e_ln2, ed * ln2_lo);
    return add(e_ln2, log_m);
}

} // namespace detail::pm

/// log(x), correctly rounded but for hard cases; the same bits on host and
/// device (no libm). IEEE special values as std::log.
STICKSLIP_HD STICKSLIP_PM_NOINLINE inline double portable_log(double x) {
    using namespace detail::pm;
    if (!(x > 0.0)) return x == 0.0 ? -HUGE_VAL : (x - x) / (x - x); // -inf; NaN for x < 0 or NaN
    if (x > 0x1.fffffffffffffp+1023) return x;                       // +inf
    if (x < 0x1p-1022) { // subnormal: scale into the normal range
        const DD r = add(dd_log(DD{x * 0x1p54, 0.0}), two_prod(-54.0, ln2_hi));
        return add(r, -54.0 * ln2_lo).hi;
    }
    if (x >= 0x1p1022) {
        const DD r = add(dd_log(DD{x * 0.5, 0.0}), DD{ln2_hi, ln2_lo});
        return r.hi;
    }
    return dd_log(DD{x, 0.0}).hi;
}

/// log(1 + y), correctly rounded but for hard cases; the same bits on host
/// and device (no libm). IEEE special values as std::log1p.
STICKSLIP_HD STICKSLIP_PM_NOINLINE inline double portable_log1p(double y) {
    using namespace detail::pm;
    if (y == 0.0 || y != y) return y;          // +-0, NaN
    if (!(y > -1.0)) return y == -1.0 ? -HUGE_VAL : (y - y) / (y - y);
    if (y > 0x1.fffffffffffffp+1023) return y; // +inf
    if (y >= 0x1p1000) return portable_log(y) ; // 1 + y rounds to y, log(1 + 1/y) < 2^-1000
    return dd_log(two_sum(1.0, y)).hi;
}

/// exp(a), correctly rounded but for hard cases for a in [-708, 709.78]
/// (normal results); the same bits on host and device (no libm).
STICKSLIP_HD STICKSLIP_PM_NOINLINE inline double portable_exp(double a) {
    using namespace detail::pm;
    if (a != a) return a;
    if (a > 0x1.62e42fefa39efp+9) return HUGE_VAL; // 709.78...: overflows
    if (a < -0x1.74910d52d3052p+9) return 0.0;    // -745.13...: below half the least subnormal
    // a = k ln2 + r, |r| <= ln2/2 (+ rounding), r in double-double.
    const double kd = std::floor(a * 0x1.71547652b82fep+0 + 0.5);
    const DD kh = two_prod(kd, ln2_hi);
    DD r = two_sum(a, -kh.hi);
    r.lo -= kh.lo;
    r.lo -= kd * ln2_lo;
    r = fast_two_sum(r.hi, r.lo);
    // exp(r) = (1 + q)^256 with q = expm1(r / 256): Taylor to r^10, then 8 squarings.
    const DD x{r.hi * 0x1p-8, r.lo * 0x1p-8};
    double t = 0x1.27e4fb7789f5cp-22;        // 1/10!
    t = t * x.hi + 0x1.71de3a556c734p-19;     // 1/9!
    t = t * x.hi + 0x1.a01a01a01a01ap-16;     // 1/8!
    t = t * x.hi + 0x1.a01a01a01a01ap-13;     // 1/7!
    t = t * x.hi + 0x1.6c16c16c16c17p-10;     // 1/6!
    DD q{t, 0.0};
    q = add(mul(q, x), DD{0x1.1111111111111p-7, 0x1.1111111111111p-63}); // 1/5!
    q = add(mul(q, x), DD{0x1.5555555555555p-5, 0x1.5555555555555p-59}); // 1/4!
    q = add(mul(q, x), DD{0x1.5555555555555p-3, 0x1.5555555555555p-57}); // 1/3!
    q = add(mul(q, x), 0.5);
    q = add(mul(q, x), 1.0);
    q = mul(q, x);
    for (int i = 0; i < 8; ++i) q = add(mul(q, q), DD{2.0 * q.hi, 2.0 * q.lo}); // (1+q)^2 = 1 + 2q + q^2
    const double m = add(q, 1.0).hi; // rounded once
    int k = static_cast<int>(kd);
    if (k > 1023) return m * 2.0 * pow2(k - 1);
    if (k < -1022) return m * pow2(k + 600) * 0x1p-600; // subnormal result: rounded twice
    return m * pow2(k);
}

/// exp(a) - 1, correctly rounded but for hard cases for a <= 709.78; the
/// same bits on every machine (no libm: glibc's expm1 is chosen at run time
/// among variants that differ in the last bit). For the grid solvers, whose
/// every number would follow it; not used in kernels.
STICKSLIP_HD STICKSLIP_PM_NOINLINE inline double portable_expm1(double a) {
    using namespace detail::pm;
    if (a != a || a == 0.0) return a;
    if (a > 0x1.62e42fefa39efp+9) return HUGE_VAL;
    if (a < -40.0) return -1.0; // exp(a) < 2^-57: -1 to the last bit
    // As portable_exp: a = k ln2 + r, exp(r) = 1 + q in double-double.
    const double kd = std::floor(a * 0x1.71547652b82fep+0 + 0.5);
    const DD kh = two_prod(kd, ln2_hi);
    DD r = two_sum(a, -kh.hi);
    r.lo -= kh.lo;
    r.lo -= kd * ln2_lo;
    r = fast_two_sum(r.hi, r.lo);
    const DD x{r.hi * 0x1p-8, r.lo * 0x1p-8};
    double t = 0x1.27e4fb7789f5cp-22;
    t = t * x.hi + 0x1.71de3a556c734p-19;
    t = t * x.hi + 0x1.a01a01a01a01ap-16;
    t = t * x.hi + 0x1.a01a01a01a01ap-13;
    t = t * x.hi + 0x1.6c16c16c16c17p-10;
    DD q{t, 0.0};
    q = add(mul(q, x), DD{0x1.1111111111111p-7, 0x1.1111111111111p-63});
    q = add(mul(q, x), DD{0x1.5555555555555p-5, 0x1.5555555555555p-59});
    q = add(mul(q, x), DD{0x1.5555555555555p-3, 0x1.5555555555555p-57});
    q = add(mul(q, x), 0.5);
    q = add(mul(q, x), 1.0);
    q = mul(q, x);
    for (int i = 0; i < 8; ++i) q = add(mul(q, q), DD{2.0 * q.hi, 2.0 * q.lo});
    // exp(a) - 1 = 2^k (1 + q) - 1, in double-double (2^k scales exactly).
    const int k = static_cast<int>(kd);
    if (k == 0) return q.hi + q.lo;
    const DD m = add(q, 1.0);
    const double scale = k > 1023 ? 2.0 * pow2(k - 1) : pow2(k);
    return add(DD{m.hi * scale, m.lo * scale}, -1.0).hi;
}

/// x^y for x > 0 (normal), within about 1 ulp and the same bits on every
/// machine, unlike glibc's pow: y log x in double-double, then exp of its
/// high part times 1 + its low part.
STICKSLIP_HD inline double portable_pow(double x, double y) {
    using namespace detail::pm;
    if (y == 0.0 || x == 1.0) return 1.0;
    if (!(x > 0.0)) return x == 0.0 ? (y > 0 ? 0.0 : HUGE_VAL) : (x - x) / (x - x);
    const DD t = mul(dd_log(DD{x, 0.0}), y);
    return portable_exp(t.hi) * (1.0 + t.lo);
}

namespace detail {

/// Whether y < exp(a), given p, an approximation of exp(a) within 2 ulps
/// (a normal number): decided by p where y is clearly apart from it, else by
/// portable_exp. The result is y < portable_exp(a) whenever that is the
/// correctly rounded exp(a). Host and device; the device's kernel_below_exp.
STICKSLIP_HD inline bool below_exp_given(double y, double a, double p) {
    const double margin = p * 0x1p-49; // at least 8 ulps of p
    if (y < p - margin) return true;
    if (y > p + margin) return false;
    return y < portable_exp(a);
}

} // namespace detail

/// Whether the kernels use the portable functions on this side: always in
/// device code; on the host only in a build with STICKSLIP_PORTABLE_MATH=1
/// (CMake option of that name, off by default: the host then calls glibc).
#if defined(__CUDA_ARCH__) || (defined(STICKSLIP_PORTABLE_MATH) && STICKSLIP_PORTABLE_MATH)
#define STICKSLIP_KERNEL_MATH_PORTABLE 1
#else
#define STICKSLIP_KERNEL_MATH_PORTABLE 0
#endif

/// log(x) as the kernels take it: std::log on the host (the CPU's results are
/// glibc's), portable_log on a CUDA device (and on the host with
/// STICKSLIP_PORTABLE_MATH).
STICKSLIP_HD inline double kernel_log(double x) {
#if STICKSLIP_KERNEL_MATH_PORTABLE
    return portable_log(x);
#else
    return std::log(x);
#endif
}

/// log1p(y) as the kernels take it: std::log1p on the host, portable_log1p on
/// a CUDA device (and on the host with STICKSLIP_PORTABLE_MATH).
STICKSLIP_HD inline double kernel_log1p(double y) {
#if STICKSLIP_KERNEL_MATH_PORTABLE
    return portable_log1p(y);
#else
    return std::log1p(y);
#endif
}

/// y < exp(a) as the kernels decide it: y < std::exp(a) on the host; on a
/// CUDA device (and on the host with STICKSLIP_PORTABLE_MATH) with the fast
/// exp of that side -- CUDA's, at most 1 ulp off (CUDA Math API), or glibc's
/// -- and portable_exp where y lies within a few ulps of it
/// (detail::below_exp_given), so that the decision is the correctly rounded
/// exp's on both. For exp(a) normal (a >= -708).
STICKSLIP_HD inline bool kernel_below_exp(double y, double a) {
#if defined(__CUDA_ARCH__)
    return detail::below_exp_given(y, a, ::exp(a));
#elif STICKSLIP_KERNEL_MATH_PORTABLE
    return detail::below_exp_given(y, a, std::exp(a));
#else
    return y < std::exp(a);
#endif
}

} // namespace stickslip
