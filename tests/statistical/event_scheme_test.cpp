// The event scheme against references it did not produce: the PDMP engine on
// the paper's Fig. 4 case (D, M0 and the stuck fraction at a step 200 times
// the resolvent's default), and the mean exit time of the stuck noise against
// its quadrature. Tolerances: a few combined standard errors plus the
// allowances measured for this scheme (docs/validation.md, "The event scheme").
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stickslip/event_scheme.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/rng_batch.hpp"
#include "support.hpp"

namespace {

using namespace sstest;

ss::EngineSettings event(double dt) {
    ss::EngineSettings e;
    e.scheme = ss::Scheme::Event;
    e.dt = dt;
    return e;
}

TEST(EventSchemeStatistics, Fig4CaseAgreesWithPdmpAtACoarseStep) {
    ss::ModelParams p; // Fig. 2/4: tau 0.5, relaxation 0.067, bias 0.342
    ss::EngineSettings pdmp;
    pdmp.engine = ss::Engine::Pdmp;
    const auto a = run_le(p, event(2e-2), 60000, 2024);
    const auto b = run_le(p, pdmp, 60000, 2025);
    EXPECT_TRUE(check(compare(a.estimates.diffusivity.value, a.estimates.diffusivity.std_error,
                              b.estimates.diffusivity.value, b.estimates.diffusivity.std_error),
                      "D, event dt 2e-2 s vs pdmp grid 0.125"));
    EXPECT_TRUE(check(compare(a.estimates.mobility.value, a.estimates.mobility.std_error, b.estimates.mobility.value,
                              b.estimates.mobility.std_error),
                      "M0, event dt 2e-2 s vs pdmp grid 0.125"));
}

TEST(EventSchemeStatistics, StuckFractionAgreesWithPdmp) {
    auto stuck = [](const ss::EngineSettings& e, std::uint64_t seed) {
        ss::StationaryDensityRequest r;
        r.engine = e;
        r.excursions = 6000;
        r.bins.count = 4;
        r.sample_dt = 1e-3;
        r.control.seed = seed;
        return ss::compute_stationary_density(r).histogram.stuck;
    };
    ss::EngineSettings pdmp;
    pdmp.engine = ss::Engine::Pdmp;
    const auto a = stuck(event(1e-2), 1), b = stuck(pdmp, 2);
    // Allowance 0.005: the launch cascade resolved to h/64 (measured at
    // dt = 1e-2 s: 0.878 against the PDMP's 0.881 over 3000 excursions).
    EXPECT_TRUE(check(compare(a.value, a.std_error, b.value, b.std_error, 0.005, 3.0),
                      "P(V = 0), event dt 1e-2 s vs pdmp grid 0.125"));
}

TEST(EventSchemeStatistics, StuckNoiseExitsAtTheRightMeanTime) {
    // The stuck phase alone: X from 0 until it first leaves the band, against
    // the exact mean exit time of the OU process (Green's function quadrature).
    const ss::ModelParams p;
    const ss::EventConstants c = ss::make_event_constants(p, event(2e-2));
    const int n = 100000;
    double sum = 0, sum2 = 0;
    ss::NoPieceObserver none;
    for (int k = 0; k < n; ++k) {
        ss::BatchedCounterRng rng(7, ss::StreamPurpose::Test, static_cast<std::uint64_t>(k));
        ss::CounterRng ref(7, ss::StreamPurpose::Refinement, static_cast<std::uint64_t>(k));
        ss::EventWalk w = ss::event_walk_from(c, 0.0, 0.0);
        while (w.phase == 0) ss::event_step(c, w, 0, rng, ref, none);
        const double t = c.leaf * static_cast<double>(w.t);
        sum += t;
        sum2 += t * t;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    // Mean exit time from 0 of tau dX = -X dt + sqrt(2) dW from [x-*, x*]:
    // T(0) = int G(0, y) m(y) dy with scale density s(y) = e^{tau y^2/2}.
    const double tau = p.tau, xu = p.upper_threshold(), xd = p.lower_threshold();
    const int m = 400000;
    std::vector<double> y(m + 1), S(m + 1, 0.0);
    for (int i = 0; i <= m; ++i) y[i] = xd + (xu - xd) * i / m;
    auto scale = [&](double v) { return std::exp(tau * v * v / 2); };
    for (int i = 1; i <= m; ++i) S[i] = S[i - 1] + 0.5 * (scale(y[i]) + scale(y[i - 1])) * (y[i] - y[i - 1]);
    const double Sb = S[m];
    int i0 = 0;
    while (y[i0] < 0) ++i0;
    const double S0 = S[i0];
    double exact = 0;
    for (int i = 0; i < m; ++i) {
        const double ym = 0.5 * (y[i] + y[i + 1]), Sm = 0.5 * (S[i] + S[i + 1]);
        const double speed = tau * tau / scale(ym); // 2 / (sigma^2 s(y)), sigma^2 = 2 / tau^2
        const double G = ym < 0 ? Sm * (Sb - S0) / Sb : S0 * (Sb - Sm) / Sb;
        exact += G * speed * (y[i + 1] - y[i]);
    }
    // Allowance 0.4%: the straight-line boundary of the clock change at
    // step/tau = 0.04 (measured: -0.3% at dt = 1e-2 s, -0.9% at 0.1 s).
    EXPECT_TRUE(check(compare(mean, se, exact, 0.0, 0.004 * exact, 3.0), "mean exit time of the stuck noise"));
}

} // namespace
