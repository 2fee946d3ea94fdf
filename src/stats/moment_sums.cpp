// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/stats/moment_sums.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <stdexcept>

#include "stickslip/stats/double_double.hpp"

namespace stickslip {

namespace {

using Big = boost::multiprecision::cpp_bin_float_50;

// Double-double arithmetic (stats/double_double.hpp): error-free
// transformations without fused multiply-add, so the bits are the same on
// every machine.
using detail::dd::DD;
using detail::dd::mul;
using detail::dd::two_prod;

void add(ExactSum& s, const DD& x) {
    s.add(x.hi);
    s.add(x.lo);
}

Big big(const ExactSum& s) {
    double hi, lo;
    s.value2(hi, lo);
    return Big(hi) + Big(lo);
}

/// A centred sum computed as a difference of raw ones, with the scale of its
/// terms: below 1e-28 of it, it is the double-double rounding of the blocks'
/// contributions (about 1e-32 of it), not information, and is 0 (a sample of
/// equal values has no spread).
double centred(const Big& value, const Big& scale) {
    return abs(value) <= Big(1e-28) * scale ? 0.0 : static_cast<double>(value);
}

constexpr double binom[5][5] = {
    {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};

/// Index of the raw sum x^p y^q (1 <= p + q <= 4) in ExactBivariateSums.
int term(int p, int q) {
    static const auto table = [] {
        std::array<std::array<int, 5>, 5> t{};
        int k = 0;
        for (int order = 1; order <= 4; ++order)
            for (int i = order; i >= 0; --i) t[i][order - i] = k++;
        return t;
    }();
    return table[p][q];
}

} // namespace

// ---- bivariate -------------------------------------------------------------------

void ExactBivariateSums::add_block(const BivariateMoments& b) {
    const std::uint64_t n = b.count();
    if (n == 0) return;
    n_.add(static_cast<double>(n)); // exact: counts stay below 2^53
    // Raw sum S_pq = sum_{i<=p, j<=q} C(p,i) C(q,j) M_ij mx^(p-i) my^(q-j),
    // with M_00 = n and M_10 = M_01 = 0.
    DD px[5], py[5];
    px[0] = py[0] = DD{1.0, 0.0};
    for (int k = 1; k <= 4; ++k) {
        px[k] = mul(px[k - 1], b.mean_x());
        py[k] = mul(py[k - 1], b.mean_y());
    }
    const double nd = static_cast<double>(n);
    for (int p = 0; p <= 4; ++p)
        for (int q = 0; p + q <= 4; ++q) {
            if (p + q == 0) continue;
            ExactSum& s = sum_[term(p, q)];
            for (int i = 0; i <= p; ++i)
                for (int j = 0; j <= q; ++j) {
                    if (i + j == 1) continue; // centred first moments vanish
                    const double m = i + j == 0 ? nd : b.central_sum(i, j);
                    if (m == 0.0) continue;
                    add(s, mul(mul(mul(px[p - i], py[q - j]), m), binom[p][i] * binom[q][j]));
                }
        }
}

void ExactBivariateSums::merge(const ExactBivariateSums& o) {
    for (int k = 0; k < terms; ++k) sum_[k].merge(o.sum_[k]);
    n_.merge(o.n_);
}

std::uint64_t ExactBivariateSums::count() const { return static_cast<std::uint64_t>(n_.value()); }

BivariateMoments ExactBivariateSums::moments() const {
    double raw[BivariateMoments::raw_size] = {};
    const std::uint64_t n = count();
    if (n == 0) return BivariateMoments{};
    const Big N(static_cast<double>(n));
    Big S[5][5];
    for (int p = 0; p <= 4; ++p)
        for (int q = 0; p + q <= 4; ++q) S[p][q] = p + q == 0 ? N : big(sum_[term(p, q)]);
    const Big mx = S[1][0] / N, my = S[0][1] / N;
    Big ax[5], ay[5]; // (-mx)^k, (-my)^k
    ax[0] = ay[0] = 1;
    for (int k = 1; k <= 4; ++k) {
        ax[k] = ax[k - 1] * -mx;
        ay[k] = ay[k - 1] * -my;
    }
    raw[0] = static_cast<double>(n);
    raw[1] = static_cast<double>(mx);
    raw[2] = static_cast<double>(my);
    for (int p = 0; p <= 4; ++p)
        for (int q = 0; p + q <= 4; ++q) {
            if (p + q < 2) continue;
            Big m = 0, scale = 0;
            for (int i = 0; i <= p; ++i)
                for (int j = 0; j <= q; ++j) {
                    const Big t = binom[p][i] * binom[q][j] * S[i][j] * ax[p - i] * ay[q - j];
                    m += t;
                    scale += abs(t);
                }
            raw[3 + p * (BivariateMoments::max_order + 1) + q] = centred(m, scale);
        }
    return BivariateMoments::from_raw(raw);
}

void ExactBivariateSums::to_words(std::uint64_t* out) const {
    for (int k = 0; k < terms; ++k) sum_[k].to_words(out + k * ExactSum::words);
    n_.to_words(out + terms * ExactSum::words);
}

ExactBivariateSums ExactBivariateSums::from_words(const std::uint64_t* in) {
    ExactBivariateSums s;
    for (int k = 0; k < terms; ++k) s.sum_[k] = ExactSum::from_words(in + k * ExactSum::words);
    s.n_ = ExactSum::from_words(in + terms * ExactSum::words);
    return s;
}

// ---- ratios -------------------------------------------------------------------------

ExactRatioSums::ExactRatioSums(std::size_t dim, std::vector<std::size_t> columns)
    : dim_(dim), columns_(std::move(columns)), sums_(3 + dim * (3 + columns_.size())) {}

void ExactRatioSums::add_block(const RatioMoments& b) {
    if (b.count() == 0) return;
    if (b.dim() != dim_ || b.columns() != columns_) throw std::logic_error("ExactRatioSums: shapes differ");
    const double n = static_cast<double>(b.count());
    const double mt = b.mean_denominator();
    sums_[0].add(n);
    const DD st = two_prod(n, mt);
    add(sums_[1], st);
    sums_[2].add(b.central_tt());
    add(sums_[2], mul(st, mt));
    const std::size_t y0 = 3, yt0 = 3 + dim_, yy0 = 3 + 2 * dim_;
    for (std::size_t j = 0; j < dim_; ++j) {
        const DD sy = two_prod(n, b.mean(j));
        add(sums_[y0 + j], sy);
        sums_[yt0 + j].add(b.central_yt(j));
        add(sums_[yt0 + j], mul(sy, mt));
        sums_[yy0 + j].add(b.central_yy(j, j));
        add(sums_[yy0 + j], mul(sy, b.mean(j)));
        for (std::size_t c = 0; c < columns_.size(); ++c) {
            ExactSum& s = sums_[yy0 + dim_ * (c + 1) + j];
            s.add(b.central_yy(j, columns_[c]));
            add(s, mul(sy, b.mean(columns_[c])));
        }
    }
}

void ExactRatioSums::merge(const ExactRatioSums& o) {
    if (o.sums_.size() != sums_.size() || o.columns_ != columns_) throw std::logic_error("ExactRatioSums: shapes differ");
    for (std::size_t k = 0; k < sums_.size(); ++k) sums_[k].merge(o.sums_[k]);
}

RatioMoments ExactRatioSums::moments() const {
    const auto n = static_cast<std::uint64_t>(sums_[0].value());
    if (n == 0) return RatioMoments(dim_, columns_);
    const Big N(static_cast<double>(n)), St = big(sums_[1]);
    const std::size_t y0 = 3, yt0 = 3 + dim_, yy0 = 3 + 2 * dim_;
    std::vector<Big> Sy(dim_);
    for (std::size_t j = 0; j < dim_; ++j) Sy[j] = big(sums_[y0 + j]);
    std::vector<double> mean_y(dim_), m_yt(dim_), yy(dim_ * (1 + columns_.size()));
    for (std::size_t j = 0; j < dim_; ++j) {
        mean_y[j] = static_cast<double>(Sy[j] / N);
        auto diff = [](const Big& a, const Big& b) { return centred(a - b, abs(a) + abs(b)); };
        m_yt[j] = diff(big(sums_[yt0 + j]), Sy[j] * St / N);
        yy[j] = diff(big(sums_[yy0 + j]), Sy[j] * Sy[j] / N);
        for (std::size_t c = 0; c < columns_.size(); ++c)
            yy[dim_ * (c + 1) + j] = diff(big(sums_[yy0 + dim_ * (c + 1) + j]), Sy[j] * Sy[columns_[c]] / N);
    }
    const Big Stt = big(sums_[2]), tt = St * St / N;
    return RatioMoments::from_central(dim_, columns_, n, static_cast<double>(St / N),
                                      centred(Stt - tt, abs(Stt) + abs(tt)), std::move(mean_y), std::move(m_yt),
                                      std::move(yy));
}

void ExactRatioSums::to_words(std::uint64_t* out) const {
    for (std::size_t k = 0; k < sums_.size(); ++k) sums_[k].to_words(out + k * ExactSum::words);
}

void ExactRatioSums::assign_words(const std::uint64_t* in) {
    for (std::size_t k = 0; k < sums_.size(); ++k) sums_[k] = ExactSum::from_words(in + k * ExactSum::words);
}

} // namespace stickslip
