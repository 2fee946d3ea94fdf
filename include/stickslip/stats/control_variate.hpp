// SPDX-License-Identifier: BSD-3-Clause
// stickslip/stats/control_variate.hpp -- the long-excursion estimators of D and
// M0 with a martingale control variate (theory.md, section 7).
//
// Why: per excursion (U - M0 t)^2 is extremely heavy-tailed, so the plain
// renewal-reward estimator of D (estimators.hpp) needs millions of excursions
// for a fraction of a percent, and its interval under-covers. Over an
// excursion U - M0 t is close to a martingale of the noise, M = sum g xi (plus
// Ito's second-order term, kernels/corrector.hpp), when the corrector g is
// good; M has E[M] = 0 and C = M^2 - Q (Q its compensator) has E[C] = 0
// exactly, whatever g. So
//   D_cv  = (sum (U - M0_hat t)^2 - beta  sum C) / sum t
//   M0_cv = (sum U - beta' sum M) / sum t
// estimate the same D and M0 for any beta, beta', and the coefficients that
// minimise the delta-method variance (taken from the same samples) remove most
// of it: what is left, (U - M0 t)^2 - C - D t, has a far lighter tail.
//
// Every statistic is E[P(U, t, M, C)] for a polynomial P of weighted degree at
// most 4, with C counting 2 (the variance of the influence function of D_cv is
// of that degree). So a run keeps the raw sums of every such monomial, 46 of
// them: each block of samples (one thread, index order) accumulates them in
// double-double arithmetic (stats/double_double.hpp, no fused multiply-add, so
// the same bits everywhere), and the blocks' sums are added into exact,
// order-free accumulators (ExactSum): any merge order, thread split, MPI
// reduction or checkpoint and resume gives the same bits, as for the plain
// sums (moment_sums.hpp). The estimates are computed from the exact sums once,
// in 50-digit arithmetic. Raw sums cancel on the way to centred quantities:
// with |mean U| / sd(U - M0 t) = r, the order-4 terms lose about 4 log10 r of
// the double-double's 32 digits, so r = 1e3 (strongly driven) keeps about 20,
// more than double precision.
#pragma once

/// \file
/// Long-excursion estimators of D and M0 with a martingale control variate,
/// from exact, mergeable sums. The comment at the top of this header explains
/// the design.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "stickslip/stats/double_double.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/stats/exact_sum.hpp"
#include "stickslip/stats/influence_tail.hpp"

namespace stickslip {

/// One block of long-excursion samples (U, t, M, C), added in index order by
/// one thread: the raw sums of every monomial U^a t^b M^e C^d with weighted
/// degree a + b + e + 2 d <= 4, in double-double arithmetic. Deterministic:
/// the same samples in the same order give the same bits on every machine.
class ControlVariateBlock {
public:
    ControlVariateBlock() = default;
    /// A block that also sums the shape of both influence functions
    /// (influence_tail.hpp) at `centres` (nullptr: not), which must outlive it.
    explicit ControlVariateBlock(const InfluenceCentres* centres) : centres_(centres) {}
    /// Number of monomials U^a t^b M^e C^d with a + b + e + 2 d <= 4, the
    /// constant 1 (the count) included.
    static constexpr int monomials = 46;

    /// Adds one excursion: displacement u [m], duration t [s], martingale sum
    /// m [m] (E[M] = 0) and c = M^2 - Q [m^2] (E[C] = 0), Q the compensator
    /// of M^2 (kernels/corrector.hpp).
    void add(double u, double t, double m, double c);
    /// Number of excursions added.
    std::uint64_t count() const { return n_; }
    /// The block's sum of monomial k (the order of ControlVariateSums; 0 is
    /// the count), as the double-double hi + lo, in the monomial's unit
    /// (m^(a+e+2d) s^b).
    detail::dd::DD sum(int k) const { return sums_[static_cast<std::size_t>(k)]; }
    /// The shape sums of the plain D's influence function and of D_cv's (empty
    /// without centres).
    const InfluenceTailBlock& plain_tail() const { return plain_tail_; }
    const InfluenceTailBlock& tail() const { return tail_; }

private:
    std::uint64_t n_ = 0;
    std::array<detail::dd::DD, monomials> sums_{}; ///< in the order of ControlVariateSums; 0 is the count
    const InfluenceCentres* centres_ = nullptr;
    InfluenceTailBlock plain_tail_, tail_;
};

/// The exact, order-free sums of every monomial of ControlVariateBlock over a
/// run: a BlockTotal (block_driver.hpp). Any order of add_block and merge,
/// any thread split, MPI reduction tree or checkpoint gives the same words.
class ControlVariateSums {
public:
    /// Adds the samples that `block` summarises: each of its double-double
    /// sums (hi and lo) into the exact accumulator of its monomial.
    void add_block(const ControlVariateBlock& block);
    /// Adds every sample of `other`, exactly.
    void merge(const ControlVariateSums& other);
    /// Serialised size in 64-bit words: monomials ExactSum's in turn, then
    /// the two influence functions' shape sums.
    std::size_t words() const { return ControlVariateBlock::monomials * ExactSum::words + 2 * InfluenceTailSums::words; }
    /// Writes the canonical form to out[0 .. words()): each monomial's
    /// ExactSum words, the count first. Equal sums give equal words.
    void to_words(std::uint64_t* out) const;
    /// Reads words written by to_words into this.
    void assign_words(const std::uint64_t* in);
    /// Number of excursions added.
    std::uint64_t count() const;
    /// The exact sum of monomial k (0 the count; the order is internal to
    /// control_variate.cpp, shared with ControlVariateBlock::sum).
    const ExactSum& sum(int k) const { return sums_[static_cast<std::size_t>(k)]; }
    /// The shape sums of the plain D's influence function and of D_cv's, over
    /// the blocks that had centres (ControlVariateBlock).
    const InfluenceTailSums& plain_tail() const { return plain_tail_; }
    const InfluenceTailSums& tail() const { return tail_; }

private:
    std::array<ExactSum, ControlVariateBlock::monomials> sums_{};
    InfluenceTailSums plain_tail_, tail_;
};

/// D and M0 with the control variate, and what it gained. See
/// estimate_control_variate for the formulas.
struct ControlVariateEstimates {
    /// D_cv [m^2/s], with the relative-error interval (make_relative_interval)
    /// as the plain D.
    Estimate diffusivity;
    /// M0_cv, the mean velocity [m/s], with the symmetric interval (make_interval).
    Estimate mobility;
    /// The coefficient on C in D_cv (dimensionless): E[phi C] / E[C^2], phi
    /// the plain D's influence function; 0 when every C is 0.
    double beta = 0.0;
    /// The coefficient on M in M0_cv (dimensionless): E[w M] / E[M^2],
    /// w = U - M0_hat t; 0 when every M is 0.
    double beta_mobility = 0.0;
    /// The plain D's delta-method variance over D_cv's, from the same samples
    /// (>= 1 up to sampling noise; 1 when both are 0, +inf when only D_cv's is).
    double variance_reduction = 1.0;
    /// The same ratio for M0 against the plain M0 = sum U / sum t.
    double variance_reduction_mobility = 1.0;
    /// Completed excursions N the estimates are from.
    std::uint64_t samples = 0;
};

/// The coefficients of the control variates (dimensionless): beta on C in
/// D's estimate, beta' on M in M0's (estimate_control_variate). Any values
/// keep the estimates unbiased; the run's interval is honest only when they do
/// not come from the excursions it corrects (docs/validation.md, "Why D's
/// interval under-covers without drag": fitted on the run itself, they follow
/// its few largest excursions and the interval covers 82-94% without drag).
struct ControlVariateCoefficients {
    double beta = 0.0;           ///< coefficient on C = M^2 - Q in D_cv
    double beta_mobility = 0.0;  ///< coefficient on M in M0_cv
};

/// The variance-minimising coefficients of a set of excursions (typically an
/// independent pilot run): beta = E[phi C] / E[C^2] and beta' = E[w M] /
/// E[M^2] in the notation of estimate_control_variate; 0 where every C (M)
/// is 0. InvalidParameter ("excursions") below 2 samples.
ControlVariateCoefficients fit_control_variate(const ControlVariateSums& s);

/// Where a run evaluates its influence functions (influence_tail.hpp): the
/// plain D's phi and, at `coefficients`, D_cv's psi, each centred at the
/// estimates of `s` (typically the pilot the coefficients were fitted on) and
/// scaled by its standard deviation there; nullopt when that is 0 or `s`
/// has fewer than 2 samples.
std::optional<InfluenceCentres> influence_centres(const ControlVariateSums& s,
                                                  const ControlVariateCoefficients& coefficients);

/// The control-variate estimates from the sums of (U [m], t [s], M [m],
/// C [m^2]) over N excursions, with intervals at `level` in (0, 1). With
/// E[.] the sample mean, tbar = E[t], M0_hat = sum U / sum t, w = U - M0_hat t,
/// D = sum w^2 / sum t and c = E[w t] / tbar:
///   phi = w^2 - D t - 2 c w              (the plain D's influence, times tbar)
///   beta = E[phi C] / E[C^2],  D_cv = (sum w^2 - beta sum C) / sum t
///   psi = w^2 - beta C - D_cv t - 2 c w, se(D_cv) = sqrt(E[psi^2] / (N - 1)) / tbar
///   beta' = E[w M] / E[M^2],   M0_cv = (sum U - beta' sum M) / sum t
///   se(M0_cv) = sqrt(E[(U - beta' M - M0_cv t)^2] / (N - 1)) / tbar
/// The plain variances, for the reductions, are E[phi^2] and E[w^2] in the
/// same form (as estimate_long_excursion). Computed in 50-digit arithmetic
/// from the exact sums. InvalidParameter ("excursions") below 2 samples,
/// ("level") for a level outside (0, 1).
ControlVariateEstimates estimate_control_variate(const ControlVariateSums& s, double level);

/// The same estimates with the coefficients given (an independent pilot's,
/// fit_control_variate): beta and beta' are `fixed`'s, the standard errors
/// those of psi and U - beta' M - M0_cv t at them, from `s` alone.
ControlVariateEstimates estimate_control_variate(const ControlVariateSums& s, double level,
                                                 const ControlVariateCoefficients& fixed);

} // namespace stickslip
