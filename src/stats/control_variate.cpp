// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/stats/control_variate.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "stickslip/errors.hpp"

namespace stickslip {

namespace {

using Big = boost::multiprecision::cpp_bin_float_50;
using detail::dd::DD;
constexpr int n_mono = ControlVariateBlock::monomials;
constexpr int max_degree = 4; // weighted: C counts 2

/// The monomials U^a t^b M^e C^d, a + b + e + 2 d <= 4, in order of weighted
/// degree, each (but the constant) with a parent of degree one or two less
/// and the variable (0 U, 1 t, 2 M, 3 C) that multiplies it: a block then
/// computes each monomial with one double-double by double product.
struct MonomialTable {
    std::array<std::array<int, 4>, n_mono> exponents{};
    std::array<int, n_mono> parent{}, variable{};
    int index[5][5][5][3];

    MonomialTable() {
        for (auto& a : index)
            for (auto& b : a)
                for (auto& e : b)
                    for (int& d : e) d = -1;
        int k = 0;
        for (int degree = 0; degree <= max_degree; ++degree)
            for (int d = degree / 2; d >= 0; --d)
                for (int a = degree - 2 * d; a >= 0; --a)
                    for (int b = degree - 2 * d - a; b >= 0; --b) {
                        const int e = degree - 2 * d - a - b;
                        exponents[k] = {a, b, e, d};
                        index[a][b][e][d] = k;
                        // Parent: remove one power of the first variable present.
                        std::array<int, 4> p = exponents[k];
                        int v = -1;
                        for (int j = 0; j < 4 && v < 0; ++j)
                            if (p[j] > 0) v = j;
                        if (v >= 0) {
                            --p[v];
                            parent[k] = index[p[0]][p[1]][p[2]][p[3]];
                        }
                        variable[k] = v;
                        ++k;
                    }
        if (k != n_mono) throw std::logic_error("ControlVariate: monomial count");
    }
    static int weighted_degree(const std::array<int, 4>& x) { return x[0] + x[1] + x[2] + 2 * x[3]; }
};

const MonomialTable& table() {
    static const MonomialTable t;
    return t;
}

Big big(const ExactSum& s) {
    double hi, lo;
    s.value2(hi, lo);
    return Big(hi) + Big(lo);
}

/// A polynomial in (U, t, M, C) of weighted degree <= 4, by its coefficients
/// on the monomials: products beyond degree 4 are a programming error.
struct Poly {
    std::array<Big, n_mono> c{};

    static Poly constant(const Big& v) {
        Poly p;
        p.c[0] = v;
        return p;
    }
    static Poly var(int j) {
        std::array<int, 4> x{0, 0, 0, 0};
        x[j] = 1;
        Poly p;
        p.c[table().index[x[0]][x[1]][x[2]][x[3]]] = 1;
        return p;
    }
    friend Poly operator-(Poly a, const Poly& b) {
        for (int k = 0; k < n_mono; ++k) a.c[k] -= b.c[k];
        return a;
    }
    friend Poly operator*(const Big& s, Poly a) {
        for (auto& x : a.c) x *= s;
        return a;
    }
    friend Poly operator*(const Poly& a, const Poly& b) {
        const MonomialTable& t = table();
        Poly r;
        for (int i = 0; i < n_mono; ++i) {
            if (a.c[i] == 0) continue;
            for (int j = 0; j < n_mono; ++j) {
                if (b.c[j] == 0) continue;
                std::array<int, 4> x;
                for (int v = 0; v < 4; ++v) x[v] = t.exponents[i][v] + t.exponents[j][v];
                if (MonomialTable::weighted_degree(x) > max_degree)
                    throw std::logic_error("ControlVariate: a product beyond weighted degree 4");
                r.c[t.index[x[0]][x[1]][x[2]][x[3]]] += a.c[i] * b.c[j];
            }
        }
        return r;
    }
};

/// Sample means of polynomials, from the exact monomial sums.
class Means {
public:
    explicit Means(const ControlVariateSums& s) {
        for (int k = 0; k < n_mono; ++k) mean_[k] = big(s.sum(k));
        const Big n = mean_[0];
        for (auto& m : mean_) m /= n;
    }
    /// E[P].
    Big operator()(const Poly& p) const {
        Big v = 0;
        for (int k = 0; k < n_mono; ++k) v += p.c[k] * mean_[k];
        return v;
    }
    /// E[P^2], 0 when it is below the rounding of the raw sums it cancels
    /// (about 1e-32 of each term; 1e-28 leaves a margin), never negative.
    Big square(const Poly& p) const {
        const Poly q = p * p;
        Big v = 0, scale = 0;
        for (int k = 0; k < n_mono; ++k) {
            const Big term = q.c[k] * mean_[k];
            v += term;
            scale += abs(term);
        }
        return v <= Big(1e-28) * scale ? Big(0) : v;
    }
    /// E[monomial k], raw.
    const Big& raw(int k) const { return mean_[k]; }

private:
    std::array<Big, n_mono> mean_{};
};

int monomial(int a, int b, int e, int d) { return table().index[a][b][e][d]; }

/// Plain variance over the control variate's, both >= 0: 1 when both are 0.
double ratio(const Big& plain, const Big& cv) {
    if (cv > 0) return static_cast<double>(plain / cv);
    return plain > 0 ? std::numeric_limits<double>::infinity() : 1.0;
}

} // namespace

void ControlVariateBlock::add(double u, double t, double m, double c) {
    const MonomialTable& tab = table();
    const double x[4] = {u, t, m, c};
    std::array<DD, n_mono> value;
    value[0] = DD{1.0, 0.0};
    for (int k = 1; k < n_mono; ++k) {
        value[k] = detail::dd::mul(value[tab.parent[k]], x[tab.variable[k]]);
        sums_[k] = detail::dd::add(sums_[k], value[k]);
    }
    sums_[0].hi += 1.0; // the count, exact below 2^53
    ++n_;
    if (centres_) {
        plain_tail_.add(centres_->plain(u, t, c));
        tail_.add(centres_->control_variate(u, t, c));
    }
}

void ControlVariateSums::add_block(const ControlVariateBlock& b) {
    if (b.count() == 0) return;
    sums_[0].add(static_cast<double>(b.count())); // exact: counts stay below 2^53
    for (int k = 1; k < n_mono; ++k) {
        const DD s = b.sum(k);
        sums_[k].add(s.hi);
        sums_[k].add(s.lo);
    }
    plain_tail_.add_block(b.plain_tail());
    tail_.add_block(b.tail());
}

void ControlVariateSums::merge(const ControlVariateSums& o) {
    for (int k = 0; k < n_mono; ++k) sums_[k].merge(o.sums_[k]);
    plain_tail_.merge(o.plain_tail_);
    tail_.merge(o.tail_);
}

void ControlVariateSums::to_words(std::uint64_t* out) const {
    for (int k = 0; k < n_mono; ++k) sums_[k].to_words(out + k * ExactSum::words);
    out += n_mono * ExactSum::words;
    plain_tail_.to_words(out);
    tail_.to_words(out + InfluenceTailSums::words);
}

void ControlVariateSums::assign_words(const std::uint64_t* in) {
    for (int k = 0; k < n_mono; ++k) sums_[k] = ExactSum::from_words(in + k * ExactSum::words);
    in += n_mono * ExactSum::words;
    plain_tail_.assign_words(in);
    tail_.assign_words(in + InfluenceTailSums::words);
}

std::uint64_t ControlVariateSums::count() const { return static_cast<std::uint64_t>(sums_[0].value()); }

namespace {

/// D's influence functions over a run's sums (times tbar, the notation of
/// estimate_control_variate): the centring that the estimates and the shape's
/// centres (influence_centres) share.
struct DiffusivityInfluence {
    Big tbar, m0, ew2, d, c;
    Poly T = Poly::var(1), C = Poly::var(3), w, w2, phi;

    explicit DiffusivityInfluence(const Means& E)
        : tbar(E.raw(monomial(0, 1, 0, 0))), m0(E.raw(monomial(1, 0, 0, 0)) / tbar) {
        w = Poly::var(0) - m0 * T; // E[w] = 0 exactly
        w2 = w * w;
        ew2 = E(w2);
        d = ew2 / tbar;
        c = E(w * T) / tbar;
        phi = w2 - d * T - Big(2) * c * w;
    }
    /// D_cv at the coefficient beta.
    Big d_cv(const Means& E, const Big& beta) const { return (ew2 - beta * E.raw(monomial(0, 0, 0, 1))) / tbar; }
    /// psi at beta and that D_cv.
    Poly psi(const Big& beta, const Big& d_cv) const { return w2 - beta * C - d_cv * T - Big(2) * c * w; }
};

/// The estimates with the coefficients fitted on `s` itself (no `fixed`) or
/// given.
ControlVariateEstimates estimate(const ControlVariateSums& s, double level, const ControlVariateCoefficients* fixed) {
    if (s.count() < 2) throw InvalidParameter("excursions", "at least 2 completed excursions are needed");
    normal_quantile_two_sided(level); // validates the level
    const Means E(s);
    const Big n = big(s.sum(0));
    const DiffusivityInfluence D(E);
    const Big& tbar = D.tbar;
    const Poly U = Poly::var(0), T = D.T, M = Poly::var(2), C = D.C;
    const Poly& w = D.w;
    const auto se = [&](const Big& var) { return static_cast<double>(sqrt(var / (n - 1)) / tbar); };

    ControlVariateEstimates r;
    r.samples = s.count();

    // D: the plain influence phi (times tbar), its regression on C.
    const Big ec2 = E.raw(monomial(0, 0, 0, 2));
    const Big beta = fixed ? Big(fixed->beta) : ec2 > 0 ? E(D.phi * C) / ec2 : Big(0);
    const Big d_cv = D.d_cv(E, beta);
    const Big var_phi = E.square(D.phi), var_psi = E.square(D.psi(beta, d_cv));
    r.beta = static_cast<double>(beta);
    r.diffusivity = make_relative_interval(static_cast<double>(d_cv), se(var_psi), level);
    r.variance_reduction = ratio(var_phi, var_psi);

    // M0: the plain influence w (times tbar), its regression on M.
    const Big em2 = E.raw(monomial(0, 0, 2, 0));
    const Big beta_m = fixed ? Big(fixed->beta_mobility) : em2 > 0 ? E(w * M) / em2 : Big(0);
    const Big m0_cv = (E.raw(monomial(1, 0, 0, 0)) - beta_m * E.raw(monomial(0, 0, 1, 0))) / tbar;
    const Poly chi = U - beta_m * M - m0_cv * T;
    const Big var_w = E.square(w), var_chi = E.square(chi);
    r.beta_mobility = static_cast<double>(beta_m);
    r.mobility = make_interval(static_cast<double>(m0_cv), se(var_chi), level);
    r.variance_reduction_mobility = ratio(var_w, var_chi);
    return r;
}

} // namespace

ControlVariateEstimates estimate_control_variate(const ControlVariateSums& s, double level) {
    return estimate(s, level, nullptr);
}

ControlVariateEstimates estimate_control_variate(const ControlVariateSums& s, double level,
                                                 const ControlVariateCoefficients& fixed) {
    return estimate(s, level, &fixed);
}

std::optional<InfluenceCentres> influence_centres(const ControlVariateSums& s,
                                                  const ControlVariateCoefficients& coefficients) {
    if (s.count() < 2) return std::nullopt;
    const Means E(s);
    const DiffusivityInfluence D(E);
    const Big beta = coefficients.beta;
    const Big d_cv = D.d_cv(E, beta);
    const Big var_phi = E.square(D.phi), var_psi = E.square(D.psi(beta, d_cv));
    if (!(var_phi > 0) || !(var_psi > 0)) return std::nullopt;
    InfluenceCentres r;
    r.plain = {static_cast<double>(D.m0), static_cast<double>(D.d), static_cast<double>(D.c), 0.0,
               static_cast<double>(sqrt(var_phi))};
    r.control_variate = {static_cast<double>(D.m0), static_cast<double>(d_cv), static_cast<double>(D.c),
                         coefficients.beta, static_cast<double>(sqrt(var_psi))};
    return r;
}

ControlVariateCoefficients fit_control_variate(const ControlVariateSums& s) {
    const ControlVariateEstimates e = estimate(s, 0.95, nullptr);
    return {e.beta, e.beta_mobility};
}

} // namespace stickslip
