// SPDX-License-Identifier: BSD-3-Clause
// The Monte Carlo velocity spectrum (spectrum.hpp: the regenerative estimator
// over long excursions) against the Kolmogorov engine's complex resolvent
// solves on the Fig. 2 case, with two engines, and against the white-noise
// closed form; S(0) is the run's D; bitwise the same for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/spectrum.hpp"
#include "support.hpp"

namespace ss = stickslip;
using sstest::check;
using sstest::compare;

namespace {

const std::vector<double> kFrequencies{0.0, 0.1, 1.0, 10.0, 30.0}; // rad/s

ss::SpectrumRequest sampled(ss::Engine engine, std::uint64_t excursions, std::uint64_t seed) {
    ss::SpectrumRequest r; // the Fig. 2 case
    r.engine.engine = engine;
    r.excursions = excursions;
    r.control.seed = seed;
    r.frequencies = kFrequencies;
    return r;
}

/// The reference: the kolmogorov engine on the same case (its estimated errors
/// about 1e-4 relative, tests/unit/spectrum_test.cpp).
const ss::SpectrumResult& solved_fig2() {
    static const ss::SpectrumResult s = [] {
        ss::SpectrumRequest r;
        r.frequencies = kFrequencies;
        return ss::compute_spectrum(r);
    }();
    return s;
}

} // namespace

// The target is |MC - Kolmogorov| <= 3 se + 3% at 0.1, 1 and 10
// rad/s; this test asks more: 4 combined standard errors and no allowance, at
// 30 rad/s too. Measured at 100000 excursions (seeds 1, 2 with the event
// scheme, seed 1 with the PDMP): z between -0.6 and +1.9, the largest where
// the run's D itself was 1.6 se high (the low frequencies follow D).
TEST(SampledSpectrum, MatchesTheKolmogorovEngineOnFig2) {
    const ss::SpectrumResult& reference = solved_fig2();
    struct Case {
        ss::Engine engine;
        std::uint64_t excursions;
    };
    for (const Case c : {Case{ss::Engine::Inclusion, 20000}, Case{ss::Engine::Pdmp, 4000}}) {
        const ss::SpectrumResult mc = ss::compute_spectrum(sampled(c.engine, c.excursions, 2024));
        ASSERT_TRUE(mc.estimates.has_value());
        ASSERT_EQ(mc.spectrum.size(), kFrequencies.size());
        // Green-Kubo: S(0) is the run's own D, bit for bit.
        EXPECT_EQ(mc.spectrum[0].value, mc.estimates->diffusivity.value);
        for (std::size_t k = 1; k < kFrequencies.size(); ++k) {
            const ss::Estimate& s = mc.spectrum[k];
            const ss::Estimate& ref = reference.spectrum[k];
            EXPECT_GT(s.error, 0.0);
            EXPECT_TRUE(check(compare(s.value, s.error, ref.value, ref.error),
                              std::string(c.engine == ss::Engine::Pdmp ? "pdmp" : "inclusion") + " S(" +
                                  std::to_string(kFrequencies[k]) + " rad/s), Fig. 2"));
        }
    }
}

// White noise without drag: the closed form is exact. The resolvent scheme at
// dt = 1e-4 s carries a bias of D of about 0.39 sqrt(dt') = 0.4%
// (docs/validation.md, "Choosing the step"), allowed on top of 4 se (the
// standard errors here are 1-4%).
TEST(SampledSpectrum, MatchesTheWhiteNoiseClosedForm) {
    ss::SpectrumRequest r;
    r.params.friction = 1;
    r.params.noise = 1;
    r.params.tau = 0;
    r.params.relaxation = INFINITY;
    r.params.bias = 0.3;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4); // the inclusion engine
    r.excursions = 10000;
    r.control.seed = 99;
    r.frequencies = {0.1, 1.0, 10.0};
    const ss::SpectrumResult mc = ss::compute_spectrum(r);
    for (std::size_t k = 0; k < r.frequencies.size(); ++k) {
        const double exact = ss::dry_friction_spectrum(r.params, r.frequencies[k]);
        EXPECT_TRUE(check(compare(mc.spectrum[k].value, mc.spectrum[k].error, exact, 0.0, 0.004 * exact),
                          "white noise S(" + std::to_string(r.frequencies[k]) + " rad/s)"));
    }
}

// White noise with drag (the Fig. 2 law): the velocity's Fokker-Planck chain
// (within 1e-7 of the closed form without drag, tests/unit/spectrum_test.cpp)
// is the reference. The resolvent scheme at dt = 2e-5 s (dt' = 5.9e-5) carries
// a bias of D of about 0.39 sqrt(dt') = 0.3%, allowed on top of 4 se (1.2% at
// 1 rad/s, 0.7% at 10 and 30). Measured with seed 99: z -1.2, 0.0, -0.1.
TEST(SampledSpectrum, MatchesTheFokkerPlanckSpectrumWithDrag) {
    ss::SpectrumRequest r; // the Fig. 2 case with white noise
    r.params.tau = 0;
    r.frequencies = {1.0, 10.0, 30.0};
    const ss::SpectrumResult reference = ss::compute_spectrum(r);
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 2e-5); // the inclusion engine
    r.excursions = 50000;
    r.control.seed = 99;
    const ss::SpectrumResult mc = ss::compute_spectrum(r);
    for (std::size_t k = 0; k < r.frequencies.size(); ++k) {
        const ss::Estimate &s = mc.spectrum[k], &ref = reference.spectrum[k];
        EXPECT_TRUE(check(compare(s.value, s.error, ref.value, ref.error, 0.003 * ref.value),
                          "white noise with drag S(" + std::to_string(r.frequencies[k]) + " rad/s)"));
    }
}

TEST(SampledSpectrum, IsBitwiseTheSameForAnyThreadCount) {
    std::vector<std::vector<double>> runs;
    for (unsigned threads : {1u, 2u, 3u}) {
        ss::SpectrumRequest r = sampled(ss::Engine::Inclusion, 700, 5);
        r.control.threads = threads;
        const ss::SpectrumResult mc = ss::compute_spectrum(r);
        std::vector<double> bits;
        for (const ss::Estimate& e : mc.spectrum) {
            bits.push_back(e.value);
            bits.push_back(e.error);
        }
        runs.push_back(bits);
    }
    EXPECT_EQ(runs[0], runs[1]);
    EXPECT_EQ(runs[0], runs[2]);
}
