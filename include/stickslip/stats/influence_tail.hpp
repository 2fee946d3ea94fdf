// SPDX-License-Identifier: BSD-3-Clause
// stickslip/stats/influence_tail.hpp -- the shape of an interval's influence
// function, from mergeable sums: its skewness, its excess kurtosis and the
// index of its tail.
//
// Why: an interval D -+ 1.96 se is a normal approximation of the mean of the
// influence function psi over the excursions (control_variate.hpp). Without
// drag psi has a power-law tail, P(|psi| > x) ~ x^-alpha with alpha between
// about 2 and 3.5 (docs/validation.md, "Why D's interval under-covers without
// drag"): a variance, but no fourth moment, so the run's own standard error
// is itself a heavy-tailed estimate and the interval's coverage converges to
// its level only slowly. A run says so itself when it measures alpha.
//
// How: psi depends on D and M0, which a run knows only at its end, so it is
// evaluated at a centre fixed before the run (InfluenceCentre: the
// independent pilot's estimates and coefficients, whose error shifts psi by a
// term of the order of the pilot's standard error, negligible in its tail).
// Each excursion's x = psi / scale (scale: the pilot's standard deviation of
// psi) goes into the sums of x, x^2, x^3, x^4 (double-double per block, exact
// over the run: the skewness and kurtosis about the run's own mean) and into
// a histogram of |x| with two bins per octave from 2^-8 to 2^40 (counts,
// exact).
// Bins are chosen by frexp and exact comparisons, never by a logarithm, so
// every machine bins alike. Hill's estimator of alpha from the k largest
// terms becomes, with binned data, the maximum-likelihood estimate of a
// Pareto tail above a bin edge: the bin offsets above the edge are then
// geometric with ratio 2^(-alpha/2), so alpha = 2 log2(1 + 1/mean offset).
// Everything is a sum: any thread split, MPI reduction or resume gives the
// same bits.
#pragma once

/// \file
/// The shape (skewness, kurtosis, tail index) of an influence function, from
/// exact mergeable sums. The comment at the top of this header explains the
/// design.

#include <array>
#include <cstddef>
#include <cstdint>

#include "stickslip/stats/double_double.hpp"
#include "stickslip/stats/exact_sum.hpp"

namespace stickslip {

/// Where an influence function psi = w^2 - beta C - d t - 2 c w, w = U - m0 t,
/// is evaluated during a run (control_variate.hpp's psi; beta = 0 gives the
/// plain D's phi), and its scale. Units: U [m], t [s], C [m^2].
struct InfluenceCentre {
    double m0 = 0.0;    ///< mean velocity [m/s]
    double d = 0.0;     ///< D [m^2/s]
    double c = 0.0;     ///< E[w t] / E[t] [m]
    double beta = 0.0;  ///< coefficient of C (dimensionless)
    double scale = 1.0; ///< the standard deviation of psi [m^2], > 0: the histogram's unit

    /// psi / scale of one excursion (dimensionless).
    double operator()(double u, double t, double c2) const {
        const double w = u - m0 * t;
        return (w * w - beta * c2 - d * t - 2.0 * c * w) / scale;
    }
};

/// The centres of the plain D's influence function and the control
/// variate's, both from one pilot (influence_centres in control_variate.hpp).
struct InfluenceCentres {
    InfluenceCentre plain;
    InfluenceCentre control_variate;
};

/// The bins of |psi| / scale: bin 0 below 2^-influence_low_octaves, then two
/// per octave up to 2^influence_high_octaves, the last open above.
inline constexpr int influence_low_octaves = 8;
inline constexpr int influence_high_octaves = 40;
inline constexpr int influence_bins = 1 + 2 * (influence_low_octaves + influence_high_octaves);

/// One block's sums of x = psi / scale, in index order (one thread).
class InfluenceTailBlock {
public:
    /// Adds one excursion's x (finite; a non-finite x is counted in the last bin
    /// and makes the moments non-finite, which the shape then omits).
    void add(double x);
    std::uint64_t count() const { return n_; }
    /// sum of x^k, k = 1..4, as a double-double.
    detail::dd::DD power(int k) const { return powers_[static_cast<std::size_t>(k - 1)]; }
    std::uint64_t bin(int j) const { return bins_[static_cast<std::size_t>(j)]; }

private:
    std::uint64_t n_ = 0;
    std::array<detail::dd::DD, 4> powers_{};
    std::array<std::uint64_t, influence_bins> bins_{};
};

/// The skewness, excess kurtosis and tail index of x over a run.
struct InfluenceShape {
    std::uint64_t samples = 0;    ///< excursions summed
    double skewness = 0.0;        ///< E[(x - mean)^3] / var^1.5
    double excess_kurtosis = 0.0; ///< E[(x - mean)^4] / var^2 - 3
    /// Hill's (binned) estimate of alpha in P(|psi| > x) ~ x^-alpha, from the
    /// tail_terms largest terms (alpha < 4: no fourth moment; < 2: no
    /// variance); NaN when fewer than 10 terms exceed 2^-8 scale.
    double tail_index = 0.0;
    std::uint64_t tail_terms = 0; ///< terms above the bin edge the estimate starts at
};

/// The exact sums of InfluenceTailBlock over a run: a part of a BlockTotal
/// (words for MPI and checkpoints).
class InfluenceTailSums {
public:
    static constexpr std::size_t words = (1 + 4 + influence_bins) * ExactSum::words;
    void add_block(const InfluenceTailBlock& b);
    void merge(const InfluenceTailSums& o);
    void to_words(std::uint64_t* out) const;
    void assign_words(const std::uint64_t* in);
    std::uint64_t count() const;
    /// The shape from the sums; samples = 0 (and the rest 0) when fewer than 4
    /// excursions were summed or a moment is not finite. Hill's k is
    /// max(10, sqrt(N)): the tail starts at the highest bin edge with at
    /// least k terms above it.
    InfluenceShape shape() const;

private:
    ExactSum count_;
    std::array<ExactSum, 4> powers_{};
    std::array<ExactSum, influence_bins> bins_{};
};

} // namespace stickslip
