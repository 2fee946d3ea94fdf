// SPDX-License-Identifier: BSD-3-Clause
// The event scheme at every step a user may choose, against schemes and
// engines it does not share code with. Its tables once stopped at dt/tau =
// 0.03, and below dt of about 1e-3 friction times it was wrong by 26% to
// 1e5-fold (the midpoint bridge weighed an absolute displacement whose
// rounding swamped what it tells; docs/validation.md, "The event scheme at
// fine steps"). These tests sweep the step over five decades down to dt/tau =
// 1e-5, and draw random models and steps from a documented box.
//
// What is compared: the transient statistics E[V(t)], E[V(t)^2] and P(V(t) =
// 0) from a fixed start (the `moments` command's), at two times of order tau:
// they exercise launches, landings and sticking like a long excursion, at a
// cost that does not grow with the excursion's length, so the finest steps
// stay affordable (1e5 steps per path at dt/tau = 1e-5). Tolerances: 4
// combined standard errors (Bonferroni over the comparisons of a test: at
// most about 40, so a false alarm has probability below 0.3%) plus the
// allowances named at each test, measured where said.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "stickslip/observables.hpp"
#include "support.hpp"

namespace {

using namespace sstest;

ss::MomentsResult transient(const ss::ModelParams& p, const ss::EngineSettings& e, double v0,
                              std::vector<double> times, std::uint64_t paths, std::uint64_t seed) {
    ss::MomentsRequest r;
    r.params = p;
    r.engine = e;
    r.v0 = v0;
    r.times = std::move(times);
    r.trajectories = paths;
    r.control.seed = seed;
    return ss::compute_moments(r);
}

ss::EngineSettings scheme(ss::Scheme s, double dt) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.scheme = s;
    e.dt = dt;
    return e;
}

/// Compares every moment of a against b at every time; returns the number of failures.
int compare_moments(const ss::MomentsResult& a, const ss::MomentsResult& b, const std::string& what,
                    double stuck_allowance) {
    int failures = 0;
    for (std::size_t i = 0; i < a.time.size(); ++i) {
        const std::string at = what + ", t = " + std::to_string(a.time[i]) + " s";
        failures += !check(compare(a.first_moment[i].value, a.first_moment[i].error, b.first_moment[i].value,
                                   b.first_moment[i].error),
                           "E[V(t)], " + at);
        failures += !check(compare(a.second_moment[i].value, a.second_moment[i].error, b.second_moment[i].value,
                                   b.second_moment[i].error),
                           "E[V(t)^2], " + at);
        failures += !check(compare(a.stuck[i].value, a.stuck[i].error, b.stuck[i].value, b.stuck[i].error,
                                   stuck_allowance),
                           "P(V(t) = 0), " + at);
    }
    return failures;
}

TEST(EventSchemeFineSteps, TransientMomentsAgreeWithTheResolventFromDtOverTauOneDownTo1e5) {
    // Dry friction with a bias (friction = noise = 1, tau' = 1, bias 0.3, no
    // drag), from V = 0.5 with X drawn from its stationary law; the reference
    // is the resolvent scheme at dt/tau = 1e-4. Allowance 0.01 on P(V = 0):
    // the resolvent's stuck fraction has an O(dt) part (one step at V = 0 per
    // landing); measured here at t = 1 s: 0.6365 +- 0.0076 against the event
    // scheme's 0.640 +- 0.0076 at dt/tau = 1e-5 (both 4000 paths, bias 0).
    ss::ModelParams p;
    p.friction = 1;
    p.noise = 1;
    p.tau = 1;
    p.relaxation = INFINITY;
    p.bias = 0.3;
    const std::vector<double> times{0.25, 1.0};
    const auto ref = transient(p, scheme(ss::Scheme::Resolvent, 1e-4), 0.5, times, 16000, 101);
    struct Step {
        double ratio;
        std::uint64_t paths;
    };
    int failures = 0;
    for (const Step& s : {Step{1.0, 8000}, Step{1e-1, 8000}, Step{1e-2, 8000}, Step{1e-3, 4000}, Step{1e-4, 2000},
                          Step{1e-5, 1000}}) {
        const auto ev = transient(p, scheme(ss::Scheme::Event, s.ratio * p.tau), 0.5, times, s.paths,
                                  200 + static_cast<std::uint64_t>(-std::log10(s.ratio)));
        std::ostringstream what;
        what << "event at dt/tau = " << s.ratio << " vs resolvent at 1e-4";
        failures += compare_moments(ev, ref, what.str(), 0.01);
    }
    EXPECT_EQ(failures, 0);
}

TEST(EventSchemeFineSteps, RandomModelsAndStepsAgreeWithTheResolventAndThePdmp) {
    // Models drawn from a box (friction = noise = 1, the nondimensional form,
    // which loses no generality): tau' log-uniform in [0.05, 2]; relaxation
    // infinite or log-uniform in [0.2, 5]; bias uniform in [-0.5, 0.5];
    // v0 uniform in [-1, 1]; the event scheme's dt/tau log-uniform in [1e-5,
    // 1e-1]; times tau/4 and tau. References: the resolvent scheme at dt/tau =
    // 1e-3 and the PDMP at grid 0.0625 / sqrt(tau') (lattice steps of 1/16
    // of X's standard deviation). Allowances on P(V = 0): 0.015 against the
    // resolvent (its O(dt) part, as above, larger at dt/tau = 1e-3) and 0.01
    // against the PDMP (its lattice moves the stuck band's edges by up to half
    // a step). Fixed seeds: the same six models every run.
    std::mt19937_64 gen(20261202);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, unit(gen)); };
    int failures = 0;
    for (int k = 0; k < 6; ++k) {
        ss::ModelParams p;
        p.friction = 1;
        p.noise = 1;
        p.tau = log_uniform(0.05, 2.0);
        p.relaxation = unit(gen) < 0.5 ? INFINITY : log_uniform(0.2, 5.0);
        p.bias = -0.5 + unit(gen);
        const double v0 = -1.0 + 2.0 * unit(gen);
        const double ratio = log_uniform(1e-5, 1e-1);
        const std::vector<double> times{p.tau / 4, p.tau};
        const std::uint64_t paths = ratio < 1e-4 ? 1500 : 4000;
        std::ostringstream model;
        model << "tau " << p.tau << ", relaxation " << p.relaxation << ", bias " << p.bias << ", v0 " << v0
              << ", event dt/tau " << ratio;
        const auto ev = transient(p, scheme(ss::Scheme::Event, ratio * p.tau), v0, times, paths, 300 + k);
        const auto rs = transient(p, scheme(ss::Scheme::Resolvent, 1e-3 * p.tau), v0, times, 8000, 400 + k);
        ss::EngineSettings pdmp = scheme(ss::Scheme::Resolvent, 1e-4);
        pdmp.engine = ss::Engine::Pdmp;
        pdmp.grid = 0.0625 / std::sqrt(p.tau);
        const auto pd = transient(p, pdmp, v0, times, 8000, 500 + k);
        failures += compare_moments(ev, rs, model.str() + " vs resolvent at dt/tau 1e-3", 0.015);
        failures += compare_moments(ev, pd, model.str() + " vs pdmp", 0.01);
    }
    EXPECT_EQ(failures, 0);
}

} // namespace
