// SPDX-License-Identifier: BSD-3-Clause
// The closed forms behind the step checks (src/driver/step_check.hpp): the mean
// first-passage time of the OU noise, against its small- and large-threshold
// expansions, and the bound on an excursion's length in the Fig. 2 case.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "driver/step_check.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/params.hpp"
#include "stickslip/run.hpp"

namespace stickslip::detail {
namespace {

// T(h) = tau sqrt(2 pi) int_0^h e^{u^2/2} Phi(u) du.
// Small h: e^{u^2/2} Phi(u) = 1/2 + u/sqrt(2 pi) + u^2/4 + O(u^3).
TEST(OuFirstPassage, SmallThresholdSeries) {
    const double tau = 0.5, h = 0.01;
    const double s = std::sqrt(2 * std::numbers::pi);
    const double series = tau * s * (h / 2 + h * h / (2 * s) + h * h * h / 12);
    EXPECT_NEAR(ou_first_passage_time(h, tau) / series, 1.0, 3e-7); // next term: 0.07 h^3
}

// Large h: int_0^h e^{u^2/2} Phi(u) du = e^{h^2/2}/h (1 + 1/h^2 + 3/h^4 + ...)
// up to Phi(u) - 1 = O(e^{-u^2/2}/u), negligible at h = 8.
TEST(OuFirstPassage, LargeThresholdAsymptotics) {
    const double tau = 2.0, h = 8.0;
    const double asym = tau * std::sqrt(2 * std::numbers::pi) * std::exp(h * h / 2) / h *
                        (1 + 1 / (h * h) + 3 / std::pow(h, 4) + 15 / std::pow(h, 6));
    EXPECT_NEAR(ou_first_passage_time(h, tau) / asym, 1.0, 2e-4); // next term 105/h^8 = 6e-6
}

TEST(OuFirstPassage, EdgesAndMonotone) {
    EXPECT_EQ(ou_first_passage_time(0.0, 1.0), 0.0);
    EXPECT_TRUE(std::isinf(ou_first_passage_time(38.0, 1.0)));
    double last = 0.0;
    for (double h = 0.5; h < 36; h += 0.5) {
        const double t = ou_first_passage_time(h, 1.0);
        EXPECT_GT(t, last) << "h = " << h;
        EXPECT_TRUE(std::isfinite(t)) << "h = " << h;
        last = t;
    }
}

// Fig. 2 case: the bound (3.4 s) lies below the measured E[t1] = 8.04 s
// (docs/validation.md, sec. 2), as a lower bound must, and within a factor 3.
TEST(ExcursionBound, BelowTheMeasuredMeanDurationOfFig2) {
    const ModelParams p; // the paper's Fig. 2 case
    const double bound = excursion_duration_lower_bound(make_model(p));
    EXPECT_GT(bound, 8.04 / 3);
    EXPECT_LT(bound, 8.04);
    EXPECT_EQ(excursion_duration_lower_bound(make_model(ModelParams{1, 1, 0, INFINITY, 0})), 0.0); // white noise
}

// A sweep point at noise 1 (Fig. 2 otherwise) needs at least 1.1e7 steps per
// excursion (measured E[t1] = 3374 s, 3.4e7 steps): 5000 excursions are a
// long run worth a note, 64 are not.
TEST(CostNote, SaysALongRunIsLongBeforeItStarts) {
    DiffusivityRequest req;
    req.engine = fixed_step_settings(Scheme::Resolvent, 1e-4);
    req.params.noise = 1.0;
    const PreparedEngine e = prepare(req);
    std::vector<std::string> notes;
    note_cost(e, 5000, RunControl{}, notes);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("a long run: predicted about"), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("--checkpoint"), std::string::npos) << notes[0];
    notes.clear();
    note_cost(e, 64, RunControl{}, notes);
    EXPECT_TRUE(notes.empty());
}

TEST(AutoStep, FollowsTheMeasuredLawsAndTheTimeScales) {
    // Fig. 2 case: T_f = noise/friction^2 = 0.339 s, relaxation 0.067 s, tau 0.5 s.
    const ModelParams fig2;
    // Resolvent: the coloured law gives 0.001/0.35 T_f = 9.7e-4 s; relaxation/100 = 6.7e-4 s wins.
    EXPECT_DOUBLE_EQ(auto_time_step(fig2, Scheme::Resolvent), 0.01 * fig2.relaxation);
    // Event: min(tau/16 = 0.031, relaxation/8 = 0.008375, T_f/16 = 0.021).
    EXPECT_DOUBLE_EQ(auto_time_step(fig2, Scheme::Event), fig2.relaxation / 8);
    ModelParams dry; // pure dry friction, friction = noise = 1 (T_f = 1 s)
    dry.friction = 1;
    dry.noise = 1;
    dry.relaxation = INFINITY;
    dry.bias = 0;
    dry.tau = 0;
    const double white = auto_time_step(dry, Scheme::Resolvent); // (0.001/0.39)^2 s
    EXPECT_NEAR(white, 6.5746e-6, 1e-9);
    EXPECT_NEAR(std::fabs(resolvent_bias(dry, white)), 1e-3, 1e-12); // the law's 0.1%
    EXPECT_DOUBLE_EQ(auto_time_step(dry, Scheme::Event), 1.0 / 16); // white: T_f/16
    dry.relaxation = 0.2;
    EXPECT_DOUBLE_EQ(auto_time_step(dry, Scheme::Event), 0.2 / 16); // white with drag: relaxation/16
    dry.relaxation = INFINITY;
    dry.tau = 0.1;
    EXPECT_DOUBLE_EQ(auto_time_step(dry, Scheme::Event), 0.1 / 16);
    dry.tau = 1; // tau' = 1: the coloured law, 0.001/0.35 T_f
    EXPECT_NEAR(resolvent_bias(dry, auto_time_step(dry, Scheme::Resolvent)), 1e-3, 1e-15);
    EXPECT_DOUBLE_EQ(auto_time_step(dry, Scheme::Event), 1.0 / 16);
    // It scales with the model: twice the noise, twice T_f.
    dry.noise = 2;
    dry.tau = 100;
    EXPECT_DOUBLE_EQ(auto_time_step(dry, Scheme::Event), 2.0 / 16);
    dry.friction = -1;
    EXPECT_THROW(auto_time_step(dry, Scheme::Event), InvalidParameter);
}

TEST(AutoStep, ResolvedOnlyWhenAskedAndForTheInclusionEngine) {
    const ModelParams fig2;
    EngineSettings s = fixed_step_settings(Scheme::Resolvent, 1e-4);
    EXPECT_EQ(resolve_engine_settings(fig2, s).dt, 1e-4); // a given step is kept
    s.dt_auto = true;
    s.scheme = Scheme::Event;
    const EngineSettings r = resolve_engine_settings(fig2, s);
    EXPECT_DOUBLE_EQ(r.dt, fig2.relaxation / 8);
    EXPECT_TRUE(r.dt_auto); // so that reports can say so
    EXPECT_EQ(resolve_engine_settings(fig2, r).dt, r.dt); // idempotent
    EXPECT_EQ(prepare_engine(fig2, s).settings.dt, r.dt);
    s.engine = Engine::Pdmp; // no time step to choose
    EXPECT_EQ(resolve_engine_settings(fig2, s).dt, 1e-4);
}

TEST(Defaults, TheEventSchemeAtItsAutomaticStepWhereverItServes) {
    const ModelParams fig2;
    const EngineSettings d; // the defaults: scheme auto, dt auto
    EXPECT_EQ(d.scheme, Scheme::Auto);
    EXPECT_TRUE(d.dt_auto);
    const EngineSettings r = resolve_engine_settings(fig2, d);
    EXPECT_EQ(r.scheme, Scheme::Event);
    EXPECT_DOUBLE_EQ(r.dt, auto_time_step(fig2, Scheme::Event));
    EXPECT_EQ(resolve_engine_settings(fig2, d, PathUse::GridSamples).scheme, Scheme::Event);
    ModelParams white = fig2;
    white.tau = 0;
    // The event scheme cannot sample white-noise paths on a grid: density and
    // correlation get the resolvent at its own automatic step.
    EXPECT_EQ(resolve_engine_settings(white, d).scheme, Scheme::Event);
    const EngineSettings grid = resolve_engine_settings(white, d, PathUse::GridSamples);
    EXPECT_EQ(grid.scheme, Scheme::Resolvent);
    EXPECT_DOUBLE_EQ(grid.dt, auto_time_step(white, Scheme::Resolvent));
    // A scheme given is kept, auto or not; resolving twice changes nothing.
    EngineSettings given = d;
    given.scheme = Scheme::Event;
    EXPECT_EQ(resolve_engine_settings(white, given, PathUse::GridSamples).scheme, Scheme::Event);
    EXPECT_EQ(resolve_engine_settings(white, grid).scheme, Scheme::Resolvent);
    // Near-white coloured noise: the resolvent's white-noise step is the longer.
    ModelParams near_white = fig2;
    near_white.tau = 1e-5 * scales_of(fig2).time;
    EXPECT_GT(auto_time_step(near_white, Scheme::Resolvent), auto_time_step(near_white, Scheme::Event));
    EXPECT_EQ(resolve_engine_settings(near_white, d).scheme, Scheme::Resolvent);
    near_white.tau = 1e-3 * scales_of(fig2).time;
    EXPECT_EQ(resolve_engine_settings(near_white, d).scheme, Scheme::Event);
    EngineSettings pdmp = d;
    pdmp.engine = Engine::Pdmp;
    EXPECT_EQ(resolve_engine_settings(fig2, pdmp).scheme, Scheme::Auto);
    EXPECT_EQ(to_string(Scheme::Auto), "auto");
    EXPECT_EQ(parse_scheme("auto"), Scheme::Auto);
}

// A run at an automatic step whose interval is narrower than the 0.3% to
// which the step's bias was checked says so; at a chosen step, at a wider
// interval, or with the PDMP (no step), it says nothing.
TEST(PrecisionNote, SaysWhenTheIntervalIsNarrowerThanTheStepsCheck) {
    DiffusivityRequest req; // the defaults: the event scheme at --dt auto
    const PreparedEngine e = prepare(req);
    std::vector<std::string> notes;
    note_precision_beyond_step(e, true, 0.0008, notes);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0].rfind(precision_note_start, 0), 0u) << notes[0]; // how a sweep finds it
    EXPECT_NE(notes[0].find("0.08%, is below the 0.3%"), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("--check-dt"), std::string::npos) << notes[0];
    EXPECT_NE(sweep_precision_note(3, 0.0012).find("at 3 points D's relative half-width (the narrowest 0.12%) is below"),
              std::string::npos);
    notes.clear();
    note_precision_beyond_step(e, false, 0.0008, notes); // --dt given
    note_precision_beyond_step(e, true, 0.004, notes);   // wider than the check
    EXPECT_TRUE(notes.empty());
    DiffusivityRequest pdmp;
    pdmp.engine.engine = Engine::Pdmp;
    note_precision_beyond_step(prepare(pdmp), true, 0.0008, notes);
    EXPECT_TRUE(notes.empty());
}

} // namespace
} // namespace stickslip::detail
