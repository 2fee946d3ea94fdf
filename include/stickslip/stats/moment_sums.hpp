// SPDX-License-Identifier: BSD-3-Clause
// stickslip/stats/moment_sums.hpp -- the statistics of a run as exact, order-free
// sums.
//
// Why: a run is cut into blocks of 64 samples (sample_runs.hpp, stats/run_totals.hpp). Each block's
// statistics are computed by one thread in a fixed order, so they are the
// same bits whoever computes them; merging blocks with floating-point
// arithmetic, though, depends on the order of the merges, and results used to
// be bitwise reproducible only because blocks were merged in index order --
// which made threads wait for each other, made every process gather every
// block's record, and made a checkpoint hard to resume exactly. Here each
// block's statistics become contributions to *raw* sums (sum x^p y^q, sum y_j
// t, ...) added into exact accumulators (exact_sum.hpp): any order, any
// thread split, any MPI reduction tree and any checkpoint and resume give the
// same sums, and the centred moments the estimators use are computed from
// them once, at the end, in 50-digit arithmetic.
//
// Accuracy: a block's centred moments and means are turned into raw-sum
// contributions in double-double arithmetic (error-free products and sums,
// no fused multiply-add, so the same bits everywhere): each contribution is
// correct to about 1e-32 of the largest term, n mean^p, so after the
// cancellation of the final centring the centred moment of order p keeps
// about 32 - p log10(|mean| / sd) digits: full double precision for
// |mean|/sd up to 1e4 at order 4 (1e8 at order 2), far beyond the strongly
// driven cases (U ~ M0 t).
#pragma once

/// \file
/// A run's statistics as exact, order-free sums (blocks merged in any order
/// give the same bits). The comment at the top of this header explains the
/// design.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "stickslip/stats/estimators.hpp"
#include "stickslip/stats/exact_sum.hpp"

namespace stickslip {

/// The raw sums sum x^p y^q (p + q <= 4) and the count of a bivariate sample,
/// exactly: the order-free form of BivariateMoments.
class ExactBivariateSums {
public:
    static constexpr int terms = 14; ///< (p, q) with 1 <= p + q <= 4
    /// Serialised size in 64-bit words (see ExactSum).
    static constexpr std::size_t words = (terms + 1) * ExactSum::words;

    /// Adds the sample that `block` summarises (any sample; typically one block).
    void add_block(const BivariateMoments& block);
    /// Adds every sample of `other`, exactly: in any order, the same sums.
    void merge(const ExactBivariateSums& other);
    /// Number of samples added.
    std::uint64_t count() const;
    /// The centred moments of everything added, each rounded once.
    BivariateMoments moments() const;

    /// Writes the canonical form to out[0 .. words): each sum's ExactSum
    /// words, the count last. Equal sums give equal words; words of two runs
    /// merge with ExactSum::merge_words, sum by sum.
    void to_words(std::uint64_t* out) const;
    /// The sums whose words to_words wrote to in[0 .. words).
    static ExactBivariateSums from_words(const std::uint64_t* in);

private:
    ExactSum sum_[terms]; ///< in the order of detail::bivariate_term
    ExactSum n_;
};

/// The raw sums of RatioMoments (count, sum t, sum t^2, sum y_j, sum y_j t,
/// sum y_j y_k for k == j or k a column), exactly.
class ExactRatioSums {
public:
    ExactRatioSums() = default;
    /// Empty sums for `dim` ratios keeping the covariances with `columns`
    /// (the shape of the RatioMoments blocks to be added).
    ExactRatioSums(std::size_t dim, std::vector<std::size_t> columns);

    /// Adds the sample that `block` summarises; its shape must match.
    void add_block(const RatioMoments& block);
    /// Adds every sample of `other` (same shape), exactly.
    void merge(const ExactRatioSums& other);
    /// The centred moments of everything added, each rounded once.
    RatioMoments moments() const;

    /// Serialised size in 64-bit words.
    std::size_t words() const { return sums_.size() * ExactSum::words; }
    /// Writes the canonical form to out[0 .. words()): each sum's ExactSum
    /// words in turn.
    void to_words(std::uint64_t* out) const;
    /// Reads words written by to_words into this (same shape).
    void assign_words(const std::uint64_t* in);

private:
    std::size_t dim_ = 0;
    std::vector<std::size_t> columns_;
    // [n, sum t, sum t^2, sum y_j (dim), sum y_j t (dim), sum y_j^2 (dim), then
    // sum y_j y_k (dim) per column]
    std::vector<ExactSum> sums_;
};

} // namespace stickslip
