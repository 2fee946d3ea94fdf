// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/stats/influence_tail.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>

namespace stickslip {

namespace {

using Big = boost::multiprecision::cpp_bin_float_50;

/// The bin of |x|: 0 below 2^-influence_low_octaves, else 1 + 2 (octave
/// above that) + (upper half of the octave), the last bin open above. frexp
/// and a comparison with the double nearest sqrt(2)/2 are exact, so every
/// machine bins alike.
int bin_of(double x) {
    const double a = std::fabs(x);
    if (!(a >= std::ldexp(1.0, -influence_low_octaves))) return std::isnan(a) ? influence_bins - 1 : 0;
    if (!std::isfinite(a)) return influence_bins - 1;
    int e = 0;
    const double m = std::frexp(a, &e); // a = m 2^e, m in [0.5, 1): the octave is e - 1
    const int j = 1 + 2 * (e - 1 + influence_low_octaves) + (m >= 0.70710678118654752440 ? 1 : 0);
    return j < influence_bins ? j : influence_bins - 1;
}

Big big(const ExactSum& s) {
    double hi, lo;
    s.value2(hi, lo);
    return Big(hi) + Big(lo);
}

} // namespace

void InfluenceTailBlock::add(double x) {
    detail::dd::DD p{x, 0.0};
    powers_[0] = detail::dd::add(powers_[0], p);
    for (std::size_t k = 1; k < 4; ++k) {
        p = detail::dd::mul(p, x);
        powers_[k] = detail::dd::add(powers_[k], p);
    }
    ++bins_[static_cast<std::size_t>(bin_of(x))];
    ++n_;
}

void InfluenceTailSums::add_block(const InfluenceTailBlock& b) {
    if (b.count() == 0) return;
    count_.add(static_cast<double>(b.count())); // exact: counts stay below 2^53
    for (int k = 1; k <= 4; ++k) {
        powers_[static_cast<std::size_t>(k - 1)].add(b.power(k).hi);
        powers_[static_cast<std::size_t>(k - 1)].add(b.power(k).lo);
    }
    for (int j = 0; j < influence_bins; ++j)
        if (b.bin(j)) bins_[static_cast<std::size_t>(j)].add(static_cast<double>(b.bin(j)));
}

void InfluenceTailSums::merge(const InfluenceTailSums& o) {
    count_.merge(o.count_);
    for (std::size_t k = 0; k < powers_.size(); ++k) powers_[k].merge(o.powers_[k]);
    for (std::size_t j = 0; j < bins_.size(); ++j) bins_[j].merge(o.bins_[j]);
}

void InfluenceTailSums::to_words(std::uint64_t* out) const {
    count_.to_words(out);
    out += ExactSum::words;
    for (const ExactSum& s : powers_) {
        s.to_words(out);
        out += ExactSum::words;
    }
    for (const ExactSum& s : bins_) {
        s.to_words(out);
        out += ExactSum::words;
    }
}

void InfluenceTailSums::assign_words(const std::uint64_t* in) {
    count_ = ExactSum::from_words(in);
    in += ExactSum::words;
    for (ExactSum& s : powers_) {
        s = ExactSum::from_words(in);
        in += ExactSum::words;
    }
    for (ExactSum& s : bins_) {
        s = ExactSum::from_words(in);
        in += ExactSum::words;
    }
}

std::uint64_t InfluenceTailSums::count() const { return static_cast<std::uint64_t>(count_.value()); }

InfluenceShape InfluenceTailSums::shape() const {
    InfluenceShape r;
    const std::uint64_t n = count();
    if (n < 4) return r;
    for (const ExactSum& s : powers_)
        if (!std::isfinite(s.value())) return r;
    const Big bn = Big(static_cast<double>(n));
    const Big m1 = big(powers_[0]) / bn, m2 = big(powers_[1]) / bn, m3 = big(powers_[2]) / bn,
              m4 = big(powers_[3]) / bn;
    const Big var = m2 - m1 * m1;
    if (!(var > 0)) return r;
    const Big c3 = m3 - 3 * m1 * m2 + 2 * m1 * m1 * m1;
    const Big c4 = m4 - 4 * m1 * m3 + 6 * m1 * m1 * m2 - 3 * m1 * m1 * m1 * m1;
    r.samples = n;
    r.skewness = static_cast<double>(c3 / (var * sqrt(var)));
    r.excess_kurtosis = static_cast<double>(c4 / (var * var) - 3);

    // Hill, binned: the highest bin edge (from 1 up) with at least k terms above.
    const double k = std::max(10.0, std::sqrt(static_cast<double>(n)));
    double above = 0.0;
    int start = 0;
    for (int j = influence_bins - 1; j >= 1; --j) {
        above += bins_[static_cast<std::size_t>(j)].value();
        if (above >= k) {
            start = j;
            break;
        }
    }
    if (start == 0) {
        r.tail_index = std::nan("");
        return r;
    }
    double offsets = 0.0; // sum of (bin - start) over the terms above
    for (int j = start + 1; j < influence_bins; ++j) offsets += (j - start) * bins_[static_cast<std::size_t>(j)].value();
    // Every term in the starting bin (mean offset 0) would give alpha = inf:
    // half a term's offset bounds it.
    const double mean_offset = std::max(offsets, 0.5) / above;
    r.tail_index = 2.0 * std::log2(1.0 + 1.0 / mean_offset);
    r.tail_terms = static_cast<std::uint64_t>(above);
    return r;
}

} // namespace stickslip
