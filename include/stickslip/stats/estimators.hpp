// SPDX-License-Identifier: BSD-3-Clause
// stickslip/stats/estimators.hpp -- renewal-reward estimators with delta-method
// confidence intervals (theory.md, section 7).
//
// From N i.i.d. long excursions with displacements U_k [m] and durations t_k [s]:
//   M0_hat = sum U / sum t                      (mobility, eq. 8)
//   D_hat  = sum (U - M0_hat t)^2 / sum t       (renewal-reward CLT)
//   E[t1]  = mean t
// D_hat is the limit of var(U(t))/t for any mean velocity. The paper's eq. (12),
// Var(U)/E[t], is wrong whenever M0 != 0; it is kept as Estimator::Paper for
// reproducing the paper's numbers only.
//
// Every statistic needs only the bivariate centred moments of (U, t) up to
// order four. Within a block of samples they are accumulated in
// BivariateMoments, which merges two samples with the exact formulas (Pebay
// 2008, arbitrary-order update); a run then adds its blocks into exact,
// order-free sums (ExactBivariateSums, moment_sums.hpp), so the result is
// bitwise the same whatever the thread count or process split. Centred
// moments do not suffer the catastrophic cancellation of raw power sums, so
// N = 1e9 keeps its digits.
#pragma once

/// \file
/// Renewal-reward estimators of D, M0 and E[t1], mergeable moments and delta-
/// method intervals. The comment at the top of this header explains the design.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "stickslip/result_fields.hpp"
#include "stickslip/setting.hpp"

namespace stickslip {

/// Exact, mergeable centred moments of a bivariate sample (x, y) up to total
/// order 4: n, the means, and M(p,q) = sum (x - xbar)^p (y - ybar)^q.
class BivariateMoments {
public:
    /// Highest total order p + q kept: the fourth moments give the standard
    /// errors of the second-order statistics (D, var U).
    static constexpr int max_order = 4;

    /// Adds one sample (x, y): in a run, x = displacement U [m] and
    /// y = duration t [s] of one excursion or trajectory.
    void add(double x, double y);
    /// Adds every sample of `other`: the moments of the union, by Pebay's
    /// update. Exact in exact arithmetic; in floating point the last bits
    /// depend on the order of the merges (ExactBivariateSums has no order).
    void merge(const BivariateMoments& other);

    /// Number of samples n.
    std::uint64_t count() const { return n_; }
    /// Mean of x (0 for an empty sample).
    double mean_x() const { return mean_x_; }
    /// Mean of y (0 for an empty sample).
    double mean_y() const { return mean_y_; }
    /// Sum of (x - mean_x)^p (y - mean_y)^q over the sample, p + q <= 4.
    double central_sum(int p, int q) const { return m_[p][q]; }
    /// central_sum(p, q) / n.
    double central_moment(int p, int q) const;

    /// The complete state as raw_size doubles (n, the means, every central
    /// sum), for sending between processes; from_raw restores it exactly.
    static constexpr int raw_size = 3 + (max_order + 1) * (max_order + 1);
    /// Writes the state to out[0 .. raw_size): n (as a double, exact below
    /// 2^53), mean x, mean y, then M(p, q) for p, q = 0 .. 4, p-major (the
    /// entries with p + q > 4 are zero).
    void to_raw(double* out) const;
    /// The moments whose state to_raw wrote to in[0 .. raw_size).
    static BivariateMoments from_raw(const double* in);

private:
    std::uint64_t n_ = 0;
    double mean_x_ = 0.0, mean_y_ = 0.0;
    std::array<std::array<double, max_order + 1>, max_order + 1> m_{};
};

/// Which estimator of D a long-excursion run reports.
enum class Estimator {
    RenewalReward, ///< sum (U - M0 t)^2 / sum t: correct for any M0 (default)
    Paper,         ///< the paper's eq. (12), Var(U)/E[t]: biased when M0 != 0
};
std::string to_string(Estimator e);      ///< "renewal" | "paper"
/// The estimator named s, "renewal" | "paper"; InvalidParameter("estimator")
/// otherwise.
Estimator parse_estimator(const std::string& s);
// Its text form as a setting (setting.hpp).

/// @name Text form of the estimator as a setting
/// @{

/// As for the other setting types (setting.hpp): to_string's names, read by
/// parse_estimator; the form is "renewal|paper".
std::string format_setting(Estimator e);
void parse_setting(const SettingInfo& info, const std::string& text, Estimator& out);
const char* setting_form(const Estimator&);
/// @}

/// How an estimate was made, which says what its error means.
enum class EstimateKind {
    /// By Monte Carlo: error is the standard error (delta method), [lo, hi]
    /// an interval at `level`.
    Sampled,
    /// By a solver (the Kolmogorov engine's grids, a quadrature): error is an
    /// estimated discretisation error (absolute; NaN when the solver has none);
    /// no interval (lo, hi, level NaN), as a solver has no sampling distribution.
    Solved,
    /// By a closed form: error 0, no interval.
    Exact,
};

/// "sampled", "solved", "exact": the JSON's and Python's names.
const char* to_string(EstimateKind kind);

/// A value with its uncertainty and the kind that says what the uncertainty
/// is: every estimate of every method (Monte Carlo, the solvers, the closed
/// forms) is one, so that the reports and Python treat them alike.
struct Estimate {
    /// The point estimate, in the quantity's unit (the field that holds the
    /// Estimate names it).
    double value = 0.0;
    /// Its uncertainty, in the same unit: the standard error when sampled,
    /// the estimated discretisation error when solved, 0 when exact.
    double error = 0.0;
    /// @{
    /// The interval [lo, hi] at `level` (sampled only): make_interval
    /// (symmetric) or, for D and D_t, make_relative_interval (asymmetric,
    /// never negative; hi may be +inf). Same unit as value.
    double lo = 0.0, hi = 0.0;
    /// @}
    /// Nominal coverage of [lo, hi], in (0, 1).
    double level = 0.95;
    /// What `error` means (and whether there is an interval).
    EstimateKind kind = EstimateKind::Sampled;
};

/// A solver's value with its estimated discretisation error (absolute; NaN:
/// not estimated), kind Solved, no interval.
Estimate solved_estimate(double value, double error);
/// A closed form's value: error 0, kind Exact, no interval.
Estimate exact_estimate(double value);

/// The relative upper half-width (hi - value) / value [1] of an estimate of a
/// positive quantity: what --rel-precision and the notes on a run's precision
/// compare; +inf where value <= 0 (no relative precision).
inline double relative_upper_half_width(const Estimate& e) {
    return e.value > 0 ? (e.hi - e.value) / e.value : std::numeric_limits<double>::infinity();
}

/// Sampled Estimate with the normal interval value -+ q_{(1+level)/2} * std_error.
Estimate make_interval(double value, double std_error, double level);

/// Estimate of a positive scale quantity (D, D_t) with the interval of its
/// relative error: with r = std_error / value and q = q_{(1+level)/2}, the set
/// of D with |value - D| <= q r D, i.e.
///   [value / (1 + q r), value / (1 - q r)]        (hi = +inf when q r >= 1).
/// This is the normal interval with the standard error taken at the candidate
/// D rather than at the estimate (the standard error of a scale estimate is
/// proportional to the scale, r estimating the constant), as Wilson's score
/// interval does for a proportion; equivalently the delta-method normal
/// interval of 1/D, mapped back. It is never negative, longer above the
/// estimate than below (a right-skewed estimate whose standard error grows
/// with it is mostly too low when it misses), and needs only (value,
/// std_error), so it keeps the mergeability and bitwise reproducibility of the
/// moments. Coverage: docs/validation.md, "Interval coverage". A value that is
/// not > 0 gets the normal interval with lo clamped at 0.
Estimate make_relative_interval(double value, double std_error, double level);

/// Mergeable centred sums for ratio estimators R_j = E[y_j] / E[t] from i.i.d.
/// samples (y, t), y a vector of `dim` path functionals of one excursion (time
/// spent in a velocity bin, integral of V(s)V(s+r) ds, ...) and t its duration.
/// This is the renewal-reward form of a stationary average, exact in the limit
/// of many excursions with no burn-in. With t = 1 for every sample, R_j is a
/// plain mean. Chan's pairwise update, in the order of the samples. The
/// covariance of y_j with y_k is kept for j == k and for every k among
/// `columns` (needed for functions of several ratios, cost dim per column per
/// sample); `full_covariance` keeps every pair.
class RatioMoments {
public:
    RatioMoments() = default;
    /// Empty moments of `dim` ratios, keeping every covariance pair when
    /// full_covariance (cost dim^2 per sample), else the variances only.
    RatioMoments(std::size_t dim, bool full_covariance);
    /// Keeps the variances and the covariances with the ratios in `columns`.
    RatioMoments(std::size_t dim, std::vector<std::size_t> columns);

    /// Adds one sample: y[0 .. dim) the path functionals of one excursion
    /// and t its duration [s] (1 for a plain mean).
    void add(const double* y, double t);
    /// Adds every sample of `other` (same dim and columns): Chan's pairwise
    /// update, exact in exact arithmetic, order-dependent in the last bits.
    void merge(const RatioMoments& other);

    /// Number of ratios (the length of each sample's y).
    std::size_t dim() const { return dim_; }
    /// Number of samples n.
    std::uint64_t count() const { return n_; }
    /// Mean of the denominators t: E[t] estimated [s].
    double mean_denominator() const { return mean_t_; }
    /// Mean of the numerator y_j over the samples.
    double mean(std::size_t j) const { return mean_y_[j]; }
    /// R_j = mean(y_j) / mean(t).
    double ratio(std::size_t j) const { return mean_y_[j] / mean_t_; }
    /// Delta-method covariance of R_j and R_k:
    /// cov(y_j - R_j t, y_k - R_k t) / (n E[t]^2), sample covariance with n - 1.
    /// j != k needs k (or j) among the columns.
    double ratio_covariance(std::size_t j, std::size_t k) const;
    /// R_j with its standard error and interval.
    Estimate estimate(std::size_t j, double level) const;
    /// One term g_j dF/dR_j of a gradient: the ratio index and the derivative.
    struct GradientTerm {
        /// The ratio j of the term.
        std::size_t index;
        /// dF/dR_j at the estimates.
        double derivative;
    };
    /// Delta-method variance of a smooth function F of the ratios whose
    /// gradient at (R_0, R_1, ...) has the given nonzero terms:
    /// sum_a sum_b g_a g_b cov(R_a, R_b), clamped at 0 (pairs need a column).
    double delta_variance(std::initializer_list<GradientTerm> gradient) const;

    /// The centred sums themselves, for exact merging (moment_sums.hpp):
    /// sum (t - mean t)^2, sum (y_j - mean y_j)(t - mean t), and
    /// sum (y_j - mean y_j)(y_k - mean y_k) for k == j or k a column.
    double central_tt() const { return m_tt_; }
    /// sum (y_j - mean y_j)(t - mean t).
    double central_yt(std::size_t j) const { return m_yt_[j]; }
    /// sum (y_j - mean y_j)(y_k - mean y_k); needs k == j or k (or j) a column.
    double central_yy(std::size_t j, std::size_t k) const { return cyy(j, k); }
    /// The ratios whose covariance with every other ratio is kept.
    const std::vector<std::size_t>& columns() const { return columns_; }
    /// The moments with the given count, means and centred sums (the layout
    /// of the accessors above; `yy` holds dim variances, then dim covariances
    /// per column).
    static RatioMoments from_central(std::size_t dim, std::vector<std::size_t> columns, std::uint64_t n, double mean_t,
                                     double m_tt, std::vector<double> mean_y, std::vector<double> m_yt,
                                     std::vector<double> yy);

private:
    double& cyy(std::size_t j, std::size_t k);
    double cyy(std::size_t j, std::size_t k) const;

    std::size_t dim_ = 0;
    std::vector<std::size_t> columns_;  ///< the ratios whose covariance with every other is kept
    std::vector<std::size_t> column_of_; ///< index into columns_ + 1, or 0 (per ratio)
    std::uint64_t n_ = 0;
    double mean_t_ = 0.0, m_tt_ = 0.0;
    std::vector<double> mean_y_, m_yt_;
    std::vector<double> m_yy_; ///< dim variances, then dim covariances per column
};

/// D, M0 and E[t1] from the moments of (U, t) over long excursions. D has the
/// relative-error interval (make_relative_interval): D_hat is right-skewed and
/// its standard error grows with it, so the symmetric interval misses mostly
/// below and can go negative. M0 and E[t1] keep the symmetric interval.
struct LongExcursionEstimates {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    Estimate diffusivity;
    Estimate mobility;
    Estimate mean_duration;
    std::uint64_t excursions = 0;
    Estimator estimator = Estimator::RenewalReward;
    /// @}

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = LongExcursionEstimates;
        visit(&S::diffusivity, FieldInfo{"diffusivity", "m^2/s", "D, the effective diffusivity"});
        visit(&S::mobility, FieldInfo{"mobility", "m/s", "M0, the mean velocity"});
        visit(&S::mean_duration,
              FieldInfo{"mean_duration", "s", "E[t1], the mean duration of a long excursion", FieldForm::NoInterval});
        visit(&S::excursions,
              FieldInfo{"completed", "", "completed long excursions the estimates are from (capped ones excluded)"});
        visit(&S::estimator, FieldInfo{"estimator", "", "the estimator D was computed with; reported in the head",
                                       FieldForm::NotInBlock});
    }
};

/// Two-sided standard-normal quantile q_{(1+level)/2}; level in (0, 1).
double normal_quantile_two_sided(double level);

/// Estimates from moments where x = U [m], y = t [s]. Needs count() >= 2.
LongExcursionEstimates estimate_long_excursion(const BivariateMoments& ut, double level,
                                               Estimator estimator = Estimator::RenewalReward);

/// Brute-force estimates (eq. 13) from the moments of U(t) at a fixed horizon t:
/// D_t = var U(t) / t with the standard error of the sample variance and its
/// relative-error interval (make_relative_interval), and M0_t = mean U(t) / t
/// with the symmetric one.
struct BruteForceEstimates {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    Estimate diffusivity;
    Estimate mobility;
    std::uint64_t trajectories = 0;
    double horizon = 0.0;
    /// @}

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = BruteForceEstimates;
        visit(&S::diffusivity,
              FieldInfo{"diffusivity", "m^2/s", "D_t = var U(t)/t, biased against D by O(1/t)"});
        visit(&S::mobility, FieldInfo{"mobility", "m/s", "the mean of U(t)/t"});
        visit(&S::trajectories, FieldInfo{"trajectories", "", "trajectories the estimates are from; reported in "
                                                               "the params", FieldForm::NotInBlock});
        visit(&S::horizon, FieldInfo{"time", "s", "the horizon t; reported in the params", FieldForm::NotInBlock});
    }
};
/// Brute-force estimates from the moments of (U(t), .) over the
/// trajectories (x = U(horizon) [m]; y unused) at horizon t [s]: D_t from the
/// unbiased sample variance, its standard error from the fourth moment.
/// InvalidParameter ("trajectories") for fewer than 2, ("level") for a level
/// outside (0, 1).
BruteForceEstimates estimate_bruteforce(const BivariateMoments& u_only, double horizon, double level);

} // namespace stickslip
