// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/stats/estimators.hpp"

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/format.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

namespace {
constexpr double binom[5][5] = {
    {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
}

void BivariateMoments::add(double x, double y) {
    BivariateMoments one;
    one.n_ = 1;
    one.mean_x_ = x;
    one.mean_y_ = y;
    merge(one);
}

void BivariateMoments::to_raw(double* out) const {
    out[0] = static_cast<double>(n_); // exact below 2^53 samples
    out[1] = mean_x_;
    out[2] = mean_y_;
    for (int p = 0; p <= max_order; ++p)
        for (int q = 0; q <= max_order; ++q) out[3 + p * (max_order + 1) + q] = m_[p][q];
}

BivariateMoments BivariateMoments::from_raw(const double* in) {
    BivariateMoments m;
    m.n_ = static_cast<std::uint64_t>(in[0]);
    m.mean_x_ = in[1];
    m.mean_y_ = in[2];
    for (int p = 0; p <= max_order; ++p)
        for (int q = 0; q <= max_order; ++q) m.m_[p][q] = in[3 + p * (max_order + 1) + q];
    return m;
}

void BivariateMoments::merge(const BivariateMoments& b) {
    if (b.n_ == 0) return;
    if (n_ == 0) {
        *this = b;
        return;
    }
    const double na = static_cast<double>(n_), nb = static_cast<double>(b.n_);
    const double n = na + nb;
    const double dx = b.mean_x_ - mean_x_, dy = b.mean_y_ - mean_y_;
    // Old moments with M(0,0) = count and M(1,0) = M(0,1) = 0, so that the
    // general binomial update (Pebay 2008) needs no special cases.
    auto ma = m_, mb = b.m_;
    ma[0][0] = na;
    mb[0][0] = nb;
    ma[1][0] = ma[0][1] = mb[1][0] = mb[0][1] = 0.0;
    const double fa = -nb / n, fb = na / n; // shifts of each part's mean to the new mean, per unit d
    double pa_x[5], pa_y[5], pb_x[5], pb_y[5];
    pa_x[0] = pa_y[0] = pb_x[0] = pb_y[0] = 1.0;
    for (int k = 1; k <= max_order; ++k) {
        pa_x[k] = pa_x[k - 1] * fa * dx;
        pa_y[k] = pa_y[k - 1] * fa * dy;
        pb_x[k] = pb_x[k - 1] * fb * dx;
        pb_y[k] = pb_y[k - 1] * fb * dy;
    }
    for (int p = 0; p <= max_order; ++p)
        for (int q = 0; p + q <= max_order; ++q) {
            if (p + q < 2) continue;
            double s = 0.0;
            for (int i = 0; i <= p; ++i)
                for (int j = 0; j <= q; ++j) {
                    const double c = binom[p][i] * binom[q][j];
                    s += c * (pa_x[i] * pa_y[j] * ma[p - i][q - j] + pb_x[i] * pb_y[j] * mb[p - i][q - j]);
                }
            m_[p][q] = s;
        }
    mean_x_ += dx * nb / n;
    mean_y_ += dy * nb / n;
    n_ += b.n_;
}

double BivariateMoments::central_moment(int p, int q) const {
    return n_ == 0 ? 0.0 : m_[p][q] / static_cast<double>(n_);
}

std::string to_string(Estimator e) { return e == Estimator::Paper ? "paper" : "renewal"; }

Estimator parse_estimator(const std::string& s) {
    if (s == "renewal") return Estimator::RenewalReward;
    if (s == "paper") return Estimator::Paper;
    throw InvalidParameter("estimator", "estimator must be 'renewal' (default, correct for any mobility) or 'paper' "
                                        "(eq. 12, biased when the mobility is not 0), got '" + s + "'");
}

std::string format_setting(Estimator e) { return to_string(e); }
void parse_setting(const SettingInfo&, const std::string& text, Estimator& out) { out = parse_estimator(text); }
const char* setting_form(const Estimator&) { return "renewal|paper"; }

double normal_quantile_two_sided(double level) {
    // 0.5 (1 + level) rounds to 1 for level above 1 - 1.1e-16, where the
    // quantile is infinite: such a level is refused, not an overflow.
    if (!(level > 0.0 && level < 1.0) || !(0.5 * (1.0 + level) < 1.0))
        throw InvalidParameter("level", "level must be strictly between 0 and 1, and at most 0.9999999999999998 "
                                        "(double precision); got " + detail::format_number(level, 17));
    return boost::math::quantile(boost::math::normal_distribution<double>(), 0.5 * (1.0 + level));
}

const char* to_string(EstimateKind kind) {
    switch (kind) {
    case EstimateKind::Sampled: return "sampled";
    case EstimateKind::Solved: return "solved";
    case EstimateKind::Exact: return "exact";
    }
    return "?";
}

Estimate solved_estimate(double value, double error) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return Estimate{value, error, nan, nan, nan, EstimateKind::Solved};
}

Estimate exact_estimate(double value) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return Estimate{value, 0.0, nan, nan, nan, EstimateKind::Exact};
}

Estimate make_interval(double value, double std_error, double level) {
    const double q = normal_quantile_two_sided(level);
    Estimate e;
    e.value = value;
    e.error = std_error;
    e.lo = value - q * std_error;
    e.hi = value + q * std_error;
    e.level = level;
    return e;
}

namespace {
std::vector<std::size_t> all_of(std::size_t dim, bool full) {
    std::vector<std::size_t> c;
    if (full)
        for (std::size_t k = 0; k < dim; ++k) c.push_back(k);
    return c;
}
} // namespace

Estimate make_relative_interval(double value, double std_error, double level) {
    if (!(value > 0.0)) { // 0 or NaN (a D_hat is never negative)
        Estimate e = make_interval(value, std_error, level);
        if (e.lo < 0.0) e.lo = 0.0;
        return e;
    }
    const double q = normal_quantile_two_sided(level);
    Estimate e;
    e.value = value;
    e.error = std_error;
    e.level = level;
    const double h = q * std_error / value; // relative half-width q r
    if (std::isnan(h)) {
        e.lo = e.hi = h;
    } else {
        e.lo = value / (1.0 + h);
        e.hi = h < 1.0 ? value / (1.0 - h) : std::numeric_limits<double>::infinity();
    }
    return e;
}

RatioMoments::RatioMoments(std::size_t dim, bool full_covariance) : RatioMoments(dim, all_of(dim, full_covariance)) {}

RatioMoments::RatioMoments(std::size_t dim, std::vector<std::size_t> columns)
    : dim_(dim), columns_(std::move(columns)), column_of_(dim, 0), mean_y_(dim, 0.0), m_yt_(dim, 0.0),
      m_yy_(dim * (1 + columns_.size()), 0.0) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
        if (columns_[c] >= dim) throw std::logic_error("RatioMoments: column out of range");
        column_of_[columns_[c]] = c + 1;
    }
}

double& RatioMoments::cyy(std::size_t j, std::size_t k) {
    if (j == k) return m_yy_[j];
    if (column_of_[k]) return m_yy_[dim_ * column_of_[k] + j];
    if (column_of_[j]) return m_yy_[dim_ * column_of_[j] + k];
    throw std::logic_error("RatioMoments: the covariance of these two ratios is not kept");
}

double RatioMoments::cyy(std::size_t j, std::size_t k) const { return const_cast<RatioMoments*>(this)->cyy(j, k); }

RatioMoments RatioMoments::from_central(std::size_t dim, std::vector<std::size_t> columns, std::uint64_t n,
                                        double mean_t, double m_tt, std::vector<double> mean_y,
                                        std::vector<double> m_yt, std::vector<double> yy) {
    RatioMoments r(dim, std::move(columns));
    if (mean_y.size() != dim || m_yt.size() != dim || yy.size() != r.m_yy_.size())
        throw std::logic_error("RatioMoments::from_central: sizes differ");
    r.n_ = n;
    r.mean_t_ = mean_t;
    r.m_tt_ = m_tt;
    r.mean_y_ = std::move(mean_y);
    r.m_yt_ = std::move(m_yt);
    r.m_yy_ = std::move(yy);
    return r;
}

void RatioMoments::add(const double* y, double t) {
    // Chan's update with a one-point sample: M += d_j d_k (n-1)/n with d = x - old mean.
    ++n_;
    const double n = static_cast<double>(n_);
    const double dt = t - mean_t_;
    const double f = (n - 1.0) / n;
    mean_t_ += dt / n;
    m_tt_ += dt * dt * f;
    thread_local std::vector<double> d;
    d.resize(dim_);
    for (std::size_t j = 0; j < dim_; ++j) {
        d[j] = y[j] - mean_y_[j];
        mean_y_[j] += d[j] / n;
        m_yt_[j] += d[j] * dt * f;
    }
    for (std::size_t j = 0; j < dim_; ++j) m_yy_[j] += d[j] * d[j] * f;
    for (std::size_t c = 0; c < columns_.size(); ++c) {
        const double dk = d[columns_[c]] * f;
        double* col = &m_yy_[dim_ * (c + 1)];
        for (std::size_t j = 0; j < dim_; ++j) col[j] += d[j] * dk;
    }
}

void RatioMoments::merge(const RatioMoments& o) {
    if (o.n_ == 0) return;
    if (n_ == 0) {
        *this = o;
        return;
    }
    if (o.dim_ != dim_ || o.columns_ != columns_) throw std::logic_error("RatioMoments::merge: shapes differ");
    const double na = static_cast<double>(n_), nb = static_cast<double>(o.n_), n = na + nb;
    const double f = na * nb / n;
    const double dt = o.mean_t_ - mean_t_;
    std::vector<double> d(dim_);
    for (std::size_t j = 0; j < dim_; ++j) d[j] = o.mean_y_[j] - mean_y_[j];
    for (std::size_t j = 0; j < dim_; ++j) {
        m_yy_[j] += o.m_yy_[j] + d[j] * d[j] * f;
        for (std::size_t c = 0; c < columns_.size(); ++c)
            m_yy_[dim_ * (c + 1) + j] += o.m_yy_[dim_ * (c + 1) + j] + d[j] * d[columns_[c]] * f;
        m_yt_[j] += o.m_yt_[j] + d[j] * dt * f;
        mean_y_[j] += d[j] * nb / n;
    }
    m_tt_ += o.m_tt_ + dt * dt * f;
    mean_t_ += dt * nb / n;
    n_ += o.n_;
}

double RatioMoments::ratio_covariance(std::size_t j, std::size_t k) const {
    if (n_ < 2) return std::numeric_limits<double>::quiet_NaN();
    const double rj = ratio(j), rk = ratio(k), n = static_cast<double>(n_);
    const double c = cyy(j, k) - rj * m_yt_[k] - rk * m_yt_[j] + rj * rk * m_tt_;
    return c / (n - 1.0) / n / (mean_t_ * mean_t_);
}

Estimate RatioMoments::estimate(std::size_t j, double level) const {
    return make_interval(ratio(j), std::sqrt(std::fmax(ratio_covariance(j, j), 0.0)), level);
}

double RatioMoments::delta_variance(std::initializer_list<GradientTerm> gradient) const {
    double v = 0.0;
    for (const GradientTerm& a : gradient)
        for (const GradientTerm& b : gradient) v += a.derivative * b.derivative * ratio_covariance(a.index, b.index);
    return std::fmax(v, 0.0);
}

namespace {
/// The standard error sqrt(var_influence / (n - 1)) of an average of n influence values.
double influence_se(double var_influence, double n) { return std::sqrt(std::fmax(var_influence, 0.0) / (n - 1.0)); }
/// Symmetric interval (M0, E[t1]: their coverage is nominal, docs/validation.md).
Estimate make_estimate(double value, double var_influence, double n, double level) {
    return make_interval(value, influence_se(var_influence, n), level);
}
/// Relative-error interval, never negative (D, D_t: right-skewed).
Estimate make_scale_estimate(double value, double var_influence, double n, double level) {
    return make_relative_interval(value, influence_se(var_influence, n), level);
}
} // namespace

LongExcursionEstimates estimate_long_excursion(const BivariateMoments& ut, double level, Estimator estimator) {
    if (ut.count() < 2) throw InvalidParameter("excursions", "at least 2 completed excursions are needed");
    normal_quantile_two_sided(level); // validates the level
    const double n = static_cast<double>(ut.count());
    const double tbar = ut.mean_y();
    const double m0 = ut.mean_x() / tbar;
    auto mu = [&](int i, int j) { return ut.central_moment(i, j); };
    // E[w^k t~^l] with w = U - M0 t = u~ - M0 t~ (w has sample mean exactly 0).
    auto ew = [&](int k, int l) {
        double s = 0.0, pw = 1.0;
        for (int i = k; i >= 0; --i) { // term C(k,i) u~^i (-M0 t~)^{k-i}
            s += binom[k][i] * pw * mu(i, k - i + l);
            pw *= -m0;
        }
        return s;
    };
    LongExcursionEstimates r;
    r.excursions = ut.count();
    r.estimator = estimator;
    const double s2 = ew(2, 0);
    r.mobility = make_estimate(m0, s2 / (tbar * tbar), n, level);
    r.mean_duration = make_estimate(tbar, mu(0, 2), n, level);
    if (estimator == Estimator::RenewalReward) {
        // Influence function (theory.md, section 7): ((w^2 - D t) - 2 c w) / E[t].
        const double d = s2 / tbar;
        const double c = ew(1, 1) / tbar;
        const double var_g = (ew(4, 0) - s2 * s2) + d * d * mu(0, 2) + 4 * c * c * s2 - 2 * d * ew(2, 1) -
                             4 * c * ew(3, 0) + 4 * c * d * ew(1, 1);
        r.diffusivity = make_scale_estimate(d, var_g / (tbar * tbar), n, level);
    } else {
        const double d = mu(2, 0) / tbar;
        const double var_g = (mu(4, 0) - mu(2, 0) * mu(2, 0)) + d * d * mu(0, 2) - 2 * d * mu(2, 1);
        r.diffusivity = make_scale_estimate(d, var_g / (tbar * tbar), n, level);
    }
    return r;
}

BruteForceEstimates estimate_bruteforce(const BivariateMoments& u, double horizon, double level) {
    if (u.count() < 2) throw InvalidParameter("trajectories", "at least 2 trajectories are needed");
    normal_quantile_two_sided(level); // validates the level
    const double n = static_cast<double>(u.count());
    const double m2 = u.central_moment(2, 0), m4 = u.central_moment(4, 0);
    BruteForceEstimates r;
    r.trajectories = u.count();
    r.horizon = horizon;
    // Unbiased sample variance; its standard error from the fourth moment.
    const double var = m2 * n / (n - 1.0);
    r.diffusivity = make_scale_estimate(var / horizon, (m4 - m2 * m2) / (horizon * horizon), n, level);
    r.mobility = make_estimate(u.mean_x() / horizon, m2 / (horizon * horizon), n, level);
    return r;
}

} // namespace stickslip
