// SPDX-License-Identifier: BSD-3-Clause
// stickslip/stats/exact_sum.hpp -- an exact, order-free sum of doubles.
//
// Why: a floating-point sum depends on the order of its terms, so results used
// to be bitwise reproducible only because the per-block statistics were merged
// in one fixed order. ExactSum removes the order: every block still computes
// its own sums of doubles in a fixed order, but those block sums are added here
// *exactly*. An exact sum is a plain integer, so any order of additions, any
// split across threads, any MPI reduction tree and any checkpoint/resume give
// the same integer, the same canonical words and the same readout; rounding
// happens once, at the end (value(), value2(), long_value()).
//
// Representation (a fixed-point "superaccumulator", after Radford Neal's xsum
// small accumulator and Demmel & Nguyen's reproducible summation): every finite
// double is an integer multiple of 2^-1074 below 2^1024, so the sum is kept as
// one integer N in units of 2^-1074, in 67 chunks of 32 bits held in 64-bit
// limbs: chunk i has weight 2^(32 i - 1074); chunks 0..65 cover the 2098 bit
// positions of a double (2^-1074 .. 2^1023) and chunk 66 is headroom. Adding a
// double is one exponent extract, one 53-bit shift and three limb additions of
// pieces below 2^32 (a 53-bit significand at any bit offset straddles at most
// three chunks); no carries are propagated. The 31 spare bits of every limb
// absorb 2^31 - 1 such additions (carry_interval) before normalise() must
// propagate the carries (each chunk back to [0, 2^32), the sign in chunk 66);
// add() and merge() do that by themselves, so any number of additions is fine
// and the 66-step carry loop is amortised to nothing. (Xsum's two-piece split
// would save one limb addition but leave only 2^10 additions between carries.)
//
// Range: the limbs are unsigned and wrap, so N is exact modulo 2^2176 (the
// carry chain is exact; only the top limb wraps) and is read as a signed
// number in [-2^1101, 2^1101). A final total inside that range is therefore
// exact whatever the partial sums did on the way; leaving it needs more than
// 2^77 additions of DBL_MAX, far beyond any run, so there is no overflow test.
//
// Non-finite inputs are not added to N but remembered as flags (+inf, -inf,
// NaN), merged by OR, so they are order-free too. The readouts then give what
// IEEE addition gives: NaN if a NaN was added or both infinities were, else
// the infinity that was added. A finite total beyond the double range rounds
// to +-inf as IEEE rounding does (|N| >= 2^1024 - 2^970). An exact zero reads
// +0.0, even for a sum of -0.0 terms (IEEE would give -0.0 there; a sign of
// zero would depend on the inputs' order-free history, which N does not keep).
//
// Serialisation: to_words() writes `words` (35) 64-bit words, the normalised
// chunks packed two per word, chunk 66, then the flags. The form is canonical
// (equal sums give equal words), all-zero words are the empty sum, and
// merge_words() is a commutative, associative reduction of two such arrays:
// use it in an MPI user op on MPI_UINT64_T (count words) with MPI_Allreduce,
// or store the words in a checkpoint. The words are host-order integers; a
// file read on a machine of the other endianness needs byte swapping.
//
// Rounding: rounded(p) gives the sum correctly rounded (to nearest, ties to
// even) to p significant bits as an integer significand and a binary exponent;
// value() encodes p = 53 as a double (subnormal results are exact, because N
// has no bits below 2^-1074), long_value() p = digits of long double, value2()
// the double-double (hi, lo) = (round(N), round(N - hi)).
//
// Everything except long_value() is constexpr and STICKSLIP_HD: no allocation,
// no exceptions, fixed-size arrays (544 bytes). CUDA needs
// --expt-relaxed-constexpr for std::bit_cast and std::countl_zero. An ExactSum
// is a plain value, not atomic: give each thread its own and merge. The const
// members read a normalised copy, so concurrent readers are safe.
//
// BasicExactSum<MaxLoad> exists so that the tests can force frequent
// normalisation (small MaxLoad); use ExactSum. Words do not depend on MaxLoad.
#pragma once

/// \file
/// ExactSum: an exact, order-free sum of doubles, the basis of bitwise-
/// reproducible runs. The comment at the top of this header explains the
/// design.

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "stickslip/config.hpp"

namespace stickslip {

/// A sum rounded to p significant bits:
///   (-1)^negative (sig_hi 2^64 + sig_lo) 2^exponent,
/// with the significand in [2^(p-1), 2^p) for a nonzero finite sum; zero is
/// sig = 0, exponent = 0, negative = false. For the non-finite kinds the other
/// members are zero.
struct RoundedSum {
    /// What the sum is: finite, or, from the flags, +inf, -inf or NaN.
    enum class Kind : std::uint8_t { Finite, PlusInf, MinusInf, NaN };
    /// Finite, or the non-finite result the flags give.
    Kind kind = Kind::Finite;
    /// Sign of a nonzero finite sum.
    bool negative = false;
    /// @{
    /// The significand, sig_hi 2^64 + sig_lo, an integer below 2^127.
    std::uint64_t sig_hi = 0, sig_lo = 0;
    /// @}
    /// Binary exponent of the significand's last bit.
    int exponent = 0;
};

/// Exact sum of doubles; see the top of this header. MaxLoad bounds the
/// carry-free additions: every unnormalised chunk stays within
/// load * (2^32 - 1) of zero, which a 64-bit limb holds for load <= 2^31.
template <std::uint32_t MaxLoad = (std::uint32_t{1} << 31)>
class BasicExactSum {
    static_assert(MaxLoad >= 2 && MaxLoad <= (std::uint32_t{1} << 31),
                  "a limb holds at most 2^31 pieces below 2^32");

public:
    /// Bits per chunk of N: each 64-bit limb holds one 32-bit chunk, the
    /// spare 32 bits absorbing carries between normalisations.
    static constexpr int chunk_bits = 32;
    static constexpr int chunks = 67;         ///< 66 for 2^-1074 .. 2^1023, one of headroom
    static constexpr int unit_exponent = -1074; ///< N counts units of 2^unit_exponent
    static constexpr std::size_t words = 35;  ///< size of the serialised form
    /// Additions of doubles between two normalisations (automatic).
    static constexpr std::uint32_t carry_interval = MaxLoad - 1;

    /// @{
    /// Flag bits of the last word: which non-finite values were added
    /// (flag_plus_inf: +inf, flag_minus_inf: -inf, flag_nan: a NaN).
    static constexpr std::uint32_t flag_plus_inf = 1, flag_minus_inf = 2, flag_nan = 4;
    /// @}

    STICKSLIP_HD constexpr BasicExactSum() = default;
    /// The sum of the one term x (BasicExactSum() is the empty sum, 0).
    STICKSLIP_HD constexpr explicit BasicExactSum(double x) { add(x); }

    /// Adds x exactly (inf/NaN: sets a flag, see the top of the header).
    STICKSLIP_HD constexpr void add(double x) {
        const std::uint64_t b = std::bit_cast<std::uint64_t>(x);
        std::uint32_t e = static_cast<std::uint32_t>(b >> 52) & 0x7ffu;
        if (e == 0x7ffu) [[unlikely]] {
            add_non_finite(b);
            return;
        }
        if (load_ >= MaxLoad) [[unlikely]]
            normalise();
        ++load_;
        // Significand m and bit offset o of its lowest bit in units of 2^-1074;
        // a subnormal (e = 0) has offset 0 like the smallest normal binade.
        std::uint64_t m = b & ((std::uint64_t{1} << 52) - 1);
        m |= static_cast<std::uint64_t>(e != 0) << 52;
        e += static_cast<std::uint32_t>(e == 0);
        const std::uint32_t o = e - 1;
        const std::uint32_t i = o >> 5, s = o & 31;
        const std::uint64_t lo = m << s;             // bits 0..63 of m 2^s
        const std::uint64_t hi = (m >> 1) >> (63 - s); // bits 64..84 (no UB at s = 0)
        const std::uint64_t neg = std::uint64_t{0} - (b >> 63); // all ones if x < 0
        c_[i] += ((lo & 0xffffffffu) ^ neg) - neg;
        c_[i + 1] += ((lo >> 32) ^ neg) - neg;
        c_[i + 2] += (hi ^ neg) - neg;
    }
    /// Adds -x exactly (negation of a double is exact).
    STICKSLIP_HD constexpr void subtract(double x) { add(-x); }
    /// add(x).
    STICKSLIP_HD constexpr BasicExactSum& operator+=(double x) {
        add(x);
        return *this;
    }
    /// subtract(x).
    STICKSLIP_HD constexpr BasicExactSum& operator-=(double x) {
        add(-x);
        return *this;
    }

    /// Adds another sum exactly (threads, processes, blocks). Flags are OR-ed.
    STICKSLIP_HD constexpr void merge(const BasicExactSum& o) { combine(o, false); }
    /// Subtracts another sum exactly; its +inf counts as -inf and vice versa.
    STICKSLIP_HD constexpr void merge_negated(const BasicExactSum& o) { combine(o, true); }
    /// merge(o).
    STICKSLIP_HD constexpr BasicExactSum& operator+=(const BasicExactSum& o) {
        combine(o, false);
        return *this;
    }
    /// merge_negated(o).
    STICKSLIP_HD constexpr BasicExactSum& operator-=(const BasicExactSum& o) {
        combine(o, true);
        return *this;
    }
    /// N -> -N (and the infinity flags swap); exact, keeps the load.
    STICKSLIP_HD constexpr void negate() {
        for (auto& c : c_) c = std::uint64_t{0} - c;
        flags_ = swap_inf(flags_);
    }

    /// Propagates the carries: chunks 0..65 in [0, 2^32), chunk 66 signed
    /// (mod 2^64). Never needed for correctness (add and merge call it when the
    /// limbs are full, the readouts work on a normalised copy); it resets the
    /// carry-free budget.
    STICKSLIP_HD constexpr void normalise() {
        for (int i = 0; i + 1 < chunks; ++i) {
            // Two's-complement conversion and arithmetic shift are defined in
            // C++20; |c| < 2^63 by the load bound, so the carry is exact.
            const auto v = static_cast<std::int64_t>(c_[i]);
            c_[i] = c_[i] & 0xffffffffu;
            c_[i + 1] += static_cast<std::uint64_t>(v >> 32);
        }
        load_ = 1;
    }

    /// No inf or NaN was added: the readouts are the rounded finite sum.
    STICKSLIP_HD constexpr bool is_finite() const { return flags_ == 0; }
    /// The flag bits (flag_plus_inf | flag_minus_inf | flag_nan).
    STICKSLIP_HD constexpr std::uint32_t flags() const { return flags_; }
    /// Sign (-1, 0, +1) of the exact finite part N, ignoring the flags.
    STICKSLIP_HD constexpr int sign() const {
        BasicExactSum t = *this;
        t.normalise();
        if (static_cast<std::int64_t>(t.c_[chunks - 1]) < 0) return -1;
        for (const auto c : t.c_)
            if (c != 0) return 1;
        return 0;
    }

    /// The sum correctly rounded (to nearest, ties to even) to `bits`
    /// significant bits, 2 <= bits <= 127 (clamped). A finite sum never
    /// overflows here: its exponent is at most 1101 - bits.
    STICKSLIP_HD constexpr RoundedSum rounded(int bits) const {
        RoundedSum r;
        if (flags_ != 0) {
            r.kind = special_kind(flags_);
            return r;
        }
        const int p = bits < 2 ? 2 : (bits > 127 ? 127 : bits);
        Magnitude m = magnitude();
        int top = mag_words - 1;
        while (top >= 0 && m.w[top] == 0) --top;
        if (top < 0) return r; // exact zero
        r.negative = m.negative;
        const int t = 64 * top + 63 - std::countl_zero(m.w[top]); // leading bit
        if (t < p) {
            // Fewer than p bits: exact; shift up to a normalised significand.
            // N < 2^127 lives in words 0 and 1.
            const int up = p - 1 - t;
            r.sig_lo = m.w[0];
            r.sig_hi = m.w[1];
            shift_left(r.sig_hi, r.sig_lo, up);
            r.exponent = unit_exponent - up;
            return r;
        }
        int shift = t - p + 1; // >= 1: bits below 2^shift are rounded away
        r.sig_lo = bits_at(m, shift);
        r.sig_hi = p > 64 ? bits_at(m, shift + 64) : 0;
        if (p < 64)
            r.sig_lo &= (std::uint64_t{1} << p) - 1;
        else if (p > 64)
            r.sig_hi &= (std::uint64_t{1} << (p - 64)) - 1;
        const int rb = shift - 1; // position of the rounding bit
        const bool round_bit = (m.w[rb >> 6] >> (rb & 63)) & 1;
        bool sticky = (m.w[rb >> 6] & ((std::uint64_t{1} << (rb & 63)) - 1)) != 0;
        for (int k = 0; k < (rb >> 6) && !sticky; ++k) sticky = m.w[k] != 0;
        if (round_bit && (sticky || (r.sig_lo & 1))) {
            if (++r.sig_lo == 0) ++r.sig_hi;
            const std::uint64_t over = p < 64 ? r.sig_lo >> p : r.sig_hi >> (p - 64);
            if (over != 0) { // rounded up to 2^p: one binade up
                r.sig_hi = p - 1 >= 64 ? std::uint64_t{1} << (p - 65) : 0;
                r.sig_lo = p - 1 >= 64 ? 0 : std::uint64_t{1} << (p - 1);
                ++shift;
            }
        }
        r.exponent = unit_exponent + shift;
        return r;
    }

    /// The sum rounded to the nearest double (ties to even); +-inf beyond
    /// the double range; inf/NaN per the flags. An exact zero is +0.0.
    STICKSLIP_HD constexpr double value() const {
        const RoundedSum r = rounded(53);
        if (r.kind != RoundedSum::Kind::Finite) return special_double(r.kind);
        if (r.sig_lo == 0) return 0.0;
        const int lead = r.exponent + 52;
        std::uint64_t b;
        if (lead > 1023)
            b = std::uint64_t{0x7ff} << 52;
        else if (lead >= -1022) // the implicit bit of sig adds the last 1 to the biased exponent
            b = (static_cast<std::uint64_t>(lead + 1022) << 52) + r.sig_lo;
        else // subnormal: exact, sig is N shifted up
            b = r.sig_lo >> (unit_exponent - r.exponent);
        b |= static_cast<std::uint64_t>(r.negative) << 63;
        return std::bit_cast<double>(b);
    }

    /// Double-double readout: hi = value(), lo = round(N - hi) (both to
    /// nearest, ties to even), so |lo| <= ulp(hi)/2 and hi + lo carries ~106
    /// bits (fewer only where lo is subnormal). If hi is not finite (flags, or
    /// a finite total beyond the double range) lo = 0.
    STICKSLIP_HD constexpr void value2(double& hi, double& lo) const {
        hi = value();
        lo = 0.0;
        if ((std::bit_cast<std::uint64_t>(hi) >> 52 & 0x7ffu) == 0x7ffu) return; // inf or NaN
        BasicExactSum t = *this;
        t.add(-hi);
        lo = t.value();
    }

    /// The sum rounded to the nearest long double (ties to even, p =
    /// numeric_limits<long double>::digits: 64 on x86, 113 for binary128, 53
    /// where long double is double). Host only (std::ldexp).
    long double long_value() const {
        constexpr int p = std::numeric_limits<long double>::digits;
        static_assert(p <= 127, "long double wider than rounded() supports");
        const RoundedSum r = rounded(p);
        using L = std::numeric_limits<long double>;
        switch (r.kind) {
        case RoundedSum::Kind::PlusInf: return L::infinity();
        case RoundedSum::Kind::MinusInf: return -L::infinity();
        case RoundedSum::Kind::NaN: return L::quiet_NaN();
        case RoundedSum::Kind::Finite: break;
        }
        // Both parts and their sum are exact for a binary long double.
        long double v = std::ldexp(static_cast<long double>(r.sig_lo), r.exponent);
        if (r.sig_hi != 0) v += std::ldexp(static_cast<long double>(r.sig_hi), r.exponent + 64);
        return r.negative ? -v : v;
    }

    /// Writes the canonical form: words[k] = chunk 2k | chunk 2k+1 << 32 for
    /// k < 33 (normalised chunks), words[33] = chunk 66 (two's complement),
    /// words[34] = flags. Equal sums (and equal flags) give equal words.
    STICKSLIP_HD constexpr void to_words(std::uint64_t* out) const {
        BasicExactSum t = *this;
        t.normalise();
        for (int k = 0; k < 33; ++k) out[k] = t.c_[2 * k] | (t.c_[2 * k + 1] << 32);
        out[33] = t.c_[66];
        out[34] = t.flags_;
    }
    /// Reads words written by to_words (any MaxLoad). Unknown flag bits mean
    /// the words are not an ExactSum: the result then reads NaN.
    STICKSLIP_HD static constexpr BasicExactSum from_words(const std::uint64_t* in) {
        BasicExactSum r;
        for (int k = 0; k < 33; ++k) {
            r.c_[2 * k] = in[k] & 0xffffffffu;
            r.c_[2 * k + 1] = in[k] >> 32;
        }
        r.c_[66] = in[33];
        constexpr std::uint64_t known = flag_plus_inf | flag_minus_inf | flag_nan;
        r.flags_ = static_cast<std::uint32_t>(in[34] & known);
        if ((in[34] & ~known) != 0) r.flags_ |= flag_nan;
        r.load_ = 1;
        return r;
    }
    /// inout <- inout + in, both in word form: the body of an MPI user op.
    STICKSLIP_HD static constexpr void merge_words(const std::uint64_t* in, std::uint64_t* inout) {
        BasicExactSum a = from_words(inout);
        a.merge(from_words(in));
        a.to_words(inout);
    }

    /// Equal exact sums and equal flags (the words would be equal).
    STICKSLIP_HD friend constexpr bool operator==(const BasicExactSum& a, const BasicExactSum& b) {
        BasicExactSum x = a, y = b;
        x.normalise();
        y.normalise();
        if (x.flags_ != y.flags_) return false;
        for (int i = 0; i < chunks; ++i)
            if (x.c_[i] != y.c_[i]) return false;
        return true;
    }

private:
    static constexpr int mag_words = 34; // 66 chunks of 32 bits + the 64-bit top limb

    struct Magnitude {
        bool negative = false;
        std::uint64_t w[mag_words] = {};
    };

    // |N| as 34 little-endian 64-bit words, from a normalised copy.
    STICKSLIP_HD constexpr Magnitude magnitude() const {
        BasicExactSum t = *this;
        t.normalise();
        Magnitude m;
        for (int k = 0; k < 33; ++k) m.w[k] = t.c_[2 * k] | (t.c_[2 * k + 1] << 32);
        m.w[33] = t.c_[66];
        m.negative = static_cast<std::int64_t>(m.w[33]) < 0;
        if (m.negative) {
            std::uint64_t carry = 1;
            for (auto& w : m.w) {
                w = ~w + carry;
                carry = (carry != 0 && w == 0) ? 1 : 0;
            }
        }
        return m;
    }

    // 64 bits of m starting at bit pos >= 0 (zeros beyond the top).
    STICKSLIP_HD static constexpr std::uint64_t bits_at(const Magnitude& m, int pos) {
        const int k = pos >> 6, s = pos & 63;
        const std::uint64_t lo = k < mag_words ? m.w[k] >> s : 0;
        const std::uint64_t hi = (s != 0 && k + 1 < mag_words) ? m.w[k + 1] << (64 - s) : 0;
        return lo | hi;
    }

    STICKSLIP_HD static constexpr void shift_left(std::uint64_t& hi, std::uint64_t& lo, int n) {
        if (n == 0) return;
        if (n >= 64) {
            hi = lo << (n - 64);
            lo = 0;
        } else {
            hi = (hi << n) | (lo >> (64 - n));
            lo <<= n;
        }
    }

    STICKSLIP_HD static constexpr std::uint32_t swap_inf(std::uint32_t f) {
        return (f & flag_nan) | ((f & flag_plus_inf) << 1) | ((f & flag_minus_inf) >> 1);
    }

    STICKSLIP_HD static constexpr RoundedSum::Kind special_kind(std::uint32_t f) {
        constexpr std::uint32_t both = flag_plus_inf | flag_minus_inf;
        if ((f & flag_nan) || (f & both) == both) return RoundedSum::Kind::NaN;
        return (f & flag_plus_inf) ? RoundedSum::Kind::PlusInf : RoundedSum::Kind::MinusInf;
    }

    STICKSLIP_HD static constexpr double special_double(RoundedSum::Kind k) {
        if (k == RoundedSum::Kind::PlusInf) return std::numeric_limits<double>::infinity();
        if (k == RoundedSum::Kind::MinusInf) return -std::numeric_limits<double>::infinity();
        return std::numeric_limits<double>::quiet_NaN();
    }

    STICKSLIP_HD constexpr void add_non_finite(std::uint64_t b) {
        if ((b & ((std::uint64_t{1} << 52) - 1)) != 0)
            flags_ |= flag_nan;
        else
            flags_ |= (b >> 63) ? flag_minus_inf : flag_plus_inf;
    }

    STICKSLIP_HD constexpr void combine(const BasicExactSum& o, bool negated) {
        flags_ |= negated ? swap_inf(o.flags_) : o.flags_;
        const BasicExactSum* src = &o;
        BasicExactSum t;
        if (o.load_ > MaxLoad - load_) {
            normalise();
            if (o.load_ > MaxLoad - load_) {
                t = o;
                t.normalise();
                src = &t;
            }
        }
        if (negated)
            for (int i = 0; i < chunks; ++i) c_[i] -= src->c_[i];
        else
            for (int i = 0; i < chunks; ++i) c_[i] += src->c_[i];
        load_ += src->load_;
    }

    std::uint64_t c_[chunks] = {}; // chunk i: weight 2^(32 i - 1074), signed when unnormalised
    std::uint32_t load_ = 0;       // |chunk i| <= load_ (2^32 - 1) for i < 66; chunk 66 wraps
    std::uint32_t flags_ = 0;
};

/// The exact sum of doubles (normalisation every 2^31 - 1 additions).
using ExactSum = BasicExactSum<>;

} // namespace stickslip
