// SPDX-License-Identifier: BSD-3-Clause
// stickslip/drift_law_quadrature.hpp -- white-noise references for any drift law.
//
// With white noise, dV = (b(V) - friction sgn V) dt + sqrt(noise) dW is a
// one-dimensional diffusion (theory.md, "Any drift law"): its stationary density
// is p = exp(Phi)/Z with Phi(v) = (2/noise) int_0^v (b(u) - friction sgn u) du,
// M0 = int v p, and the Poisson equation gives
//     D = (4/noise) int F(v)^2 / p(v) dv,   F(v) = int_{-inf}^v (u - M0) p(u) du.
// For the run's law (the interpolant on knots, drift_input.hpp) Phi is exactly
// piecewise quadratic, so each piece is integrated by Gauss-Legendre panels
// short enough that Phi changes by at most 1/2 across one: the quadrature
// error is then far below 1e-10 relative. F is accumulated from the nearer
// tail (F(+inf) = 0), so F^2/p keeps its digits where p is tiny; the domain
// ends where Phi has fallen 60 below its maximum (mass beyond < 1e-26).
// For the affine law this reproduces white_noise_reference (analytic.hpp) to
// 1e-9 (tests/unit/drift_law_test.cpp), which is what that function uses.
#pragma once

/// \file
/// White-noise stationary density, M0, D and Var(V) for any drift law, by
/// exact-exponent quadrature. The comment at the top of this header explains
/// the design.

#include <vector>

#include "stickslip/drift_law.hpp"
#include "stickslip/params.hpp"
#include "stickslip/result_fields.hpp"

namespace stickslip {

/// The exact white-noise stationary quantities of one parameter set: what
/// every white-noise-limit check compares against (white_noise_reference,
/// analytic.hpp; DriftLawWhiteNoise::reference).
struct WhiteNoiseReference {
    double mobility;    ///< M0 [m/s]
    double diffusivity; ///< D [m^2/s]
    double variance;    ///< stationary Var(V) [m^2/s^2]

    /// The fields, in report order (result_fields.hpp): each a reference of
    /// the report's model (exact for the affine law, solved for a quadrature).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using W = WhiteNoiseReference;
        visit(&W::mobility, FieldInfo{"mobility", "m/s", "M0 with white noise", FieldForm::Reference});
        visit(&W::diffusivity, FieldInfo{"diffusivity", "m^2/s", "D with white noise", FieldForm::Reference});
        visit(&W::variance, FieldInfo{"variance", "m^2/s^2", "the stationary Var(V) with white noise",
                                      FieldForm::Reference});
    }
};

/// The white-noise stationary law of p's drift law (p.tau is ignored), built
/// once (a few milliseconds), then evaluated.
class DriftLawWhiteNoise {
public:
    /// Throws InvalidParameter as make_drift_law does (no stationary state, bad law).
    explicit DriftLawWhiteNoise(const ModelParams& p);
    /// The same for a law already made (make_drift_law), with the friction
    /// [m s^-2] and noise [m^2 s^-3] it runs with: a caller that holds the
    /// run's law does not make it again (a table file is read once per run).
    DriftLawWhiteNoise(const DriftLaw& law, double friction, double noise);
    /// The velocities [m/s] below and above which Phi has fallen by `drop`
    /// (> 0) below its maximum: the stationary density there is e^-drop of
    /// its peak. Within the quadrature's own domain for drop <= 60.
    double lower_end(double drop) const;
    double upper_end(double drop) const; ///< see lower_end
    /// Stationary density p(v) [s/m].
    double density(double v) const;
    /// P(a < V < b) [1].
    double probability(double a, double b) const;
    /// The mean time [s] for V to go from velocity a to b > a [m/s] and back:
    /// (2/noise) int_a^b dv/p(v), the commute-time identity of a diffusion (the
    /// scale measure of [a, b] times the whole speed measure). With a = -c,
    /// b = c it is E[t1] of the white-noise runs' excursions (velocity levels
    /// +-c, theory.md section 6): the run-time prediction uses it. Infinite
    /// where [a, b] reaches past where the density has fallen e^-60 from its peak.
    double commute_time(double a, double b) const;
    /// M0, D and Var(V) (SI).
    const WhiteNoiseReference& reference() const { return reference_; }
    /// The law integrated (SI).
    const DriftLaw& law() const { return law_; }

private:
    void build(); // from law_, friction_ and noise_
    double phi(double v) const; // Phi(v) - Phi_max [1]
    template <class F>
    double integrate(double a, double b, F&& f) const;
    DriftLaw law_;
    DriftPotential potential_{law_}; // int_0^v b, O(1) a call
    double friction_ = 0, noise_ = 0, phi_max_ = 0, inv_z_ = 0, lo_ = 0, hi_ = 0;
    std::vector<double> cuts_; // panel ends, increasing, from lo_ to hi_
    std::vector<double> breaks_; // 0 and the knots: where Phi changes its quadratic
    WhiteNoiseReference reference_{};
};

} // namespace stickslip
