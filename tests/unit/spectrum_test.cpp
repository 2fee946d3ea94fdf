// SPDX-License-Identifier: BSD-3-Clause
// The velocity spectrum (spectrum.hpp): the white-noise closed form against an
// independent derivation and its limits, the Kolmogorov engine's two
// discretisations against each other, and its near-white limit against the
// closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/fokker_planck.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/spectrum.hpp"
#include "model_cases.hpp"

namespace ss = stickslip;

namespace {

/// Pure dry friction (friction = noise = 1) with a bias.
ss::ModelParams dry(double bias, double tau = 0.0) {
    ss::ModelParams p = ss::test::pure_dry_friction(tau);
    p.bias = bias;
    return p;
}

/// Without bias the resolvent is odd in v and the spectrum reduces to one
/// half line: S(w) = (2 Delta k / w^2) Re[1/k^2 - 1/(k - r)^2], k = 2 Delta /
/// Gamma, r = (Delta - sqrt(Delta^2 + 2 i w Gamma)) / Gamma (derived apart from
/// the general form, which joins the two half lines C^1 at v = 0).
double symmetric_spectrum(double delta, double gamma, double w) {
    const std::complex<double> iw(0, w);
    const double k = 2 * delta / gamma;
    const std::complex<double> r = (delta - std::sqrt(delta * delta + 2.0 * gamma * iw)) / gamma;
    return 2 * delta * k / (w * w) * (1 / (k * k) - 1.0 / ((k - r) * (k - r))).real();
}

} // namespace

TEST(DryFrictionSpectrum, SymmetricCaseMatchesItsOwnDerivation) {
    for (double w : {0.03, 0.3, 1.0, 3.0, 30.0}) {
        ss::ModelParams p = dry(0.0);
        p.friction = 1.7;
        p.noise = 2.3;
        const double expected = symmetric_spectrum(1.7, 2.3, w);
        EXPECT_NEAR(ss::dry_friction_spectrum(p, w) / expected, 1.0, 1e-12) << "w = " << w;
    }
}

TEST(DryFrictionSpectrum, TendsToDAtZeroAndToTheDiffusiveLawAtLargeFrequencies) {
    for (double bias : {0.0, 0.3, -0.6}) {
        const ss::ModelParams p = dry(bias);
        const double d = ss::dry_friction_diffusivity(p);
        EXPECT_EQ(ss::dry_friction_spectrum(p, 0.0), d);
        // Green-Kubo, continuously: the O(w^2) term is of order D w'^2.
        EXPECT_NEAR(ss::dry_friction_spectrum(p, 1e-3) / d, 1.0, 1e-4) << "bias " << bias;
        // V diffuses on short times: S ~ noise / w^2.
        EXPECT_NEAR(ss::dry_friction_spectrum(p, 1e3) * 1e6 / p.noise, 1.0, 1e-2) << "bias " << bias;
        // Decreasing in w.
        double last = d;
        for (double w : {0.01, 0.1, 1.0, 10.0}) {
            const double s = ss::dry_friction_spectrum(p, w);
            EXPECT_LT(s, last) << "bias " << bias << ", w " << w;
            last = s;
        }
    }
}

/// Two independent discretisations (the upwind chain, and the near-white
/// noise chain with DG in v) give the same spectrum on the Fig. 2 case within
/// their estimated errors (measured: within 0.25 of the combined errors at
/// 0.1 to 30 rad/s), and S(0) is D, the same solve.
TEST(KolmogorovSpectrum, ChainAndNearWhiteAgreeOnFig2) {
    const ss::ModelParams p; // Fig. 2
    const std::vector<double> w{0.0, 0.1, 1.0, 10.0, 30.0};
    std::vector<ss::KolmogorovResult> r;
    for (auto d : {ss::KolmogorovDiscretisation::Chain, ss::KolmogorovDiscretisation::NearWhite}) {
        ss::KolmogorovSettings s;
        s.discretisation = d;
        s.frequencies = w;
        r.push_back(ss::solve_kolmogorov(p, s));
        ASSERT_EQ(r.back().spectrum.size(), w.size());
        EXPECT_EQ(r.back().spectrum[0].value, r.back().diffusivity.value);
    }
    for (std::size_t k = 1; k < w.size(); ++k) {
        const ss::Estimate &a = r[0].spectrum[k], &b = r[1].spectrum[k];
        const double combined = a.error + b.error;
        EXPECT_LE(std::abs(a.value - b.value), combined)
            << "w = " << w[k] << ": chain " << a.value << " +- " << a.error << ", near-white " << b.value << " +- "
            << b.error << ": " << std::abs(a.value - b.value) / combined << " combined errors apart";
        EXPECT_LT(b.value, r[1].spectrum[k - 1].value) << "S decreasing at w = " << w[k];
    }
}

/// The near-white limit: at tau' = 1e-4 the Kolmogorov engine's spectrum is
/// the white-noise closed form's (an independent reference: no grid) within
/// its estimated error plus the colour's own share, measured at most 0.9e-4
/// relative at 0 to 10 (D's at tau' = 1e-4: 0.7e-4); allowed 3e-4.
TEST(KolmogorovSpectrum, NearWhiteLimitIsTheClosedForm) {
    const ss::ModelParams p = dry(0.3, 1e-4);
    ss::KolmogorovSettings s;
    s.frequencies = {0.0, 0.1, 1.0, 10.0};
    const ss::KolmogorovResult r = ss::solve_kolmogorov(p, s);
    ASSERT_EQ(r.spectrum.size(), s.frequencies.size());
    for (std::size_t k = 0; k < s.frequencies.size(); ++k) {
        const double exact = ss::dry_friction_spectrum(p, s.frequencies[k]);
        const ss::Estimate& e = r.spectrum[k];
        EXPECT_LE(std::abs(e.value - exact), e.error + 3e-4 * exact)
            << "w = " << s.frequencies[k] << ": " << e.value << " +- " << e.error << " against " << exact
            << " (relative " << (e.value - exact) / exact << ")";
    }
}

TEST(SpectrumRequest, RefusesWhatItCannotSolve) {
    auto refused = [](ss::SpectrumRequest r, const char* setting) {
        try {
            ss::validate(r);
            ADD_FAILURE() << "not refused: " << setting;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), setting) << e.what();
        }
    };
    ss::SpectrumRequest r;
    r.control.seed = 7; // a sampling setting: the kolmogorov engine samples nothing
    refused(r, "seed");
    r = {};
    r.engine.engine = ss::Engine::Pdmp;
    r.rel_precision = 0.01; // the grids' target: Monte Carlo runs --excursions
    refused(r, "rel-precision");
    r = {};
    r.params.tau = 0; // white noise with a drift law: no solver of it
    r.params.drift = "-v/0.067 + 0.342";
    refused(r, "tau");
    r = {};
    r.frequencies = {1.0, -1.0};
    refused(r, "frequencies");
    r.frequencies = {NAN};
    refused(r, "frequencies");
    // White noise without drag: the closed form, exact.
    ss::SpectrumRequest white;
    white.params = dry(0.2);
    white.frequencies = {0.0, 1.0};
    const ss::SpectrumResult out = ss::compute_spectrum(white);
    ASSERT_EQ(out.spectrum.size(), 2u);
    EXPECT_EQ(out.spectrum[0].value, ss::dry_friction_diffusivity(white.params));
    EXPECT_EQ(out.spectrum[1].error, 0.0);
}

/// An independent reference for the closed form: the cosine transform of
/// Touchette, Van der Straeten and Just's closed-form autocorrelation C(t)
/// (dry_friction_autocorrelation), S(w) = 2 int_0^inf C(t) cos(w t) dt, by
/// Simpson's rule on [0, 40] time units (C has fallen below 1e-12 of C(0)
/// there); and the sum rule (1/pi) int_0^inf S dw = C(0) = Var(V).
TEST(DryFrictionSpectrum, IsTheCosineTransformOfTheClosedFormAutocorrelation) {
    const ss::ModelParams p = dry(0.0);
    const double t_end = 40.0;
    const int n = 40000; // even
    const double h = t_end / n;
    for (double w : {0.0, 0.2, 1.0, 4.0}) {
        double sum = 0;
        for (int k = 0; k <= n; ++k) {
            const double t = k * h, weight = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
            sum += weight * ss::dry_friction_autocorrelation(p, t) * std::cos(w * t);
        }
        const double transform = 2.0 * sum * h / 3.0;
        EXPECT_NEAR(ss::dry_friction_spectrum(p, w) / transform, 1.0, 1e-6) << "w = " << w;
    }
    // Sum rule: int_0^W S dw by Simpson on a log grid, plus the tail Gamma/W.
    const double big_w = 1e4;
    double integral = 0;
    const int m = 20000;
    const double lo = std::log(1e-6), step = (std::log(big_w) - lo) / m;
    for (int k = 0; k <= m; ++k) {
        const double u = std::exp(lo + k * step), weight = (k == 0 || k == m) ? 1.0 : (k % 2 ? 4.0 : 2.0);
        integral += weight * ss::dry_friction_spectrum(p, u) * u; // dw = w du
    }
    integral = integral * step / 3.0 + 1e-6 * ss::dry_friction_diffusivity(p) + p.noise / big_w;
    EXPECT_NEAR(integral / M_PI / ss::white_noise_reference(p).variance, 1.0, 1e-5);
}

// White noise with drag: the velocity's Fokker-Planck chain (fokker_planck.hpp),
// one complex tridiagonal solve per frequency and grid. Without drag it must be
// the closed form: measured within 2e-8 relative from 0.01 to 100 rad/s, with
// an estimated error (what Richardson removed) near 1e-5 relative, an upper
// estimate by three orders of magnitude.
TEST(FokkerPlanckSpectrum, IsTheClosedFormWithoutDrag) {
    for (double bias : {0.0, 0.3, -0.6}) {
        const ss::ModelParams p = dry(bias);
        const ss::WhiteNoiseFokkerPlanck fp(p);
        const std::vector<double> w{0.0, 0.01, 0.1, 1.0, 10.0, 100.0};
        std::vector<double> error;
        const std::vector<double> s = fp.spectrum(w, error);
        for (std::size_t k = 0; k < w.size(); ++k) {
            const double exact = ss::dry_friction_spectrum(p, w[k]);
            EXPECT_NEAR(s[k] / exact, 1.0, 1e-7) << "bias " << bias << ", w = " << w[k];
            EXPECT_LE(std::abs(s[k] - exact), error[k] + 1e-12 * exact) << "bias " << bias << ", w = " << w[k];
        }
    }
}

// With drag (the Fig. 2 law) the Kolmogorov engine's near-white discretisation
// at tau' = 1e-5 is an independent solver of a neighbouring model: its
// spectrum differs from the white one by the colour's own share, measured
// -3.2e-5, -2.8e-5 and -1.8e-5 relative at 1, 10 and 30 rad/s (proportional
// to tau': -3.2e-4 at 1e-4, -3.6e-6 at 1e-6, within the estimated errors
// there). Allowed: both estimated errors + 5e-5 relative.
TEST(FokkerPlanckSpectrum, IsTheNearWhiteLimitWithDrag) {
    ss::SpectrumRequest white; // the Fig. 2 case with white noise
    white.params.tau = 0;
    white.frequencies = {1.0, 10.0};
    const ss::SpectrumResult fp = ss::compute_spectrum(white);
    ASSERT_EQ(fp.grid().solver.rfind("fokker-planck", 0), 0u) << fp.grid().solver;
    ss::SpectrumRequest near = white;
    near.params.tau = 1e-5 * ss::scales_of(near.params).time;
    near.rel_precision = 0.01;
    const ss::SpectrumResult k = ss::compute_spectrum(near);
    for (std::size_t j = 0; j < white.frequencies.size(); ++j) {
        const ss::Estimate &a = fp.spectrum[j], &b = k.spectrum[j];
        EXPECT_LE(std::abs(a.value - b.value), a.error + b.error + 5e-5 * a.value)
            << "w = " << white.frequencies[j] << ": Fokker-Planck " << a.value << " +- " << a.error
            << ", kolmogorov at tau' = 1e-5 " << b.value << " +- " << b.error << " (relative "
            << (b.value - a.value) / a.value << ")";
    }
}
