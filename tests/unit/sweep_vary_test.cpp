// SPDX-License-Identifier: BSD-3-Clause
// A sweep over a named constant of the drift expression (--vary): its points
// are value-major, each one bit for bit the diffusivity run with that value in
// --drift-params on the point's own sample indices, the exponents are fitted
// per value and tau, and every misuse is refused by the setting's name.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "stickslip/drift_input.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/report.hpp"
#include "stickslip/sweep.hpp"

namespace ss = stickslip;

namespace {

ss::SweepRequest varied_sweep() {
    ss::SweepRequest r;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-3);
    // std::string temporaries: assigning the literals directly trips a GCC 12
    // -Wrestrict false positive when this function is inlined.
    r.params.drift = std::string("-v/0.067 + c");
    r.params.drift_params = std::string("c=9"); // a placeholder, replaced at every point
    r.vary = std::string("c");
    r.vary_values = {0.342, 0.1};
    r.noises = {4, 2};
    r.taus = {0.5};
    r.excursions = 64;
    r.control.seed = 3;
    return r;
}

/// varied_sweep() without --vary: its law with the bias fixed at 0.342.
ss::SweepRequest unvaried_sweep() {
    ss::SweepRequest r = varied_sweep();
    r.params.drift = std::string("-v/0.067 + 0.342");
    r.params.drift_params.clear();
    r.vary.clear();
    r.vary_values.clear();
    return r;
}

void expect_refused(const ss::SweepRequest& r, const std::string& setting, const std::string& words) {
    try {
        ss::validate(r);
        ADD_FAILURE() << "expected InvalidParameter(" << setting << ")";
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), setting) << e.what();
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
}

/// Point k of sweep r is, bit for bit, the diffusivity run of `model` (with
/// the point's noise and tau) on the point's own sample indices.
void expect_point_is_its_run(const ss::SweepRequest& r, const ss::SweepPoint& p, std::size_t k,
                             ss::ModelParams model) {
    ss::DiffusivityRequest d;
    d.engine = r.engine;
    d.params = std::move(model);
    d.params.noise = p.noise;
    d.params.tau = p.tau;
    d.excursions = r.excursions;
    d.control.seed = r.control.seed;
    d.control.first_index = k * ss::sweep_index_stride;
    d.control_variate = r.control_variate;
    d.control_variate_pilot = r.control_variate_pilot;
    const ss::DiffusivityResult one = ss::compute_diffusivity(d);
    EXPECT_EQ(p.estimates.diffusivity.value, one.estimates.diffusivity.value) << k;
    EXPECT_EQ(p.estimates.mobility.value, one.estimates.mobility.value) << k;
}

TEST(SweepVary, PointsAreValueMajorAndEachIsItsDiffusivityRun) {
    const ss::SweepRequest r = varied_sweep();
    const ss::SweepResult res = ss::compute_sweep(r);
    ASSERT_TRUE(res.varies());
    ASSERT_EQ(res.points.size(), 4u);
    EXPECT_EQ(res.request.vary_values, (std::vector<double>{0.1, 0.342})); // sorted
    EXPECT_EQ(res.request.params.drift_params, "c=9"); // kept (the Params a user gave), replaced per point
    EXPECT_EQ(ss::drift_params_with(" c=9, d=2 ", "c", 0.1), "d=2,c=0.1");
    EXPECT_EQ(ss::drift_params_without("c=9,d", "c"), "d"); // kept for the parser to refuse
    const double expected_varied[] = {0.1, 0.1, 0.342, 0.342};
    const double expected_noise[] = {2, 4, 2, 4};
    for (std::size_t k = 0; k < 4; ++k) {
        const ss::SweepPoint& p = res.points[k];
        EXPECT_EQ(p.varied, expected_varied[k]) << k;
        EXPECT_EQ(p.noise, expected_noise[k]) << k;
        ss::ModelParams model;
        model.drift = r.params.drift;
        model.drift_params = "c=" + std::string(k < 2 ? "0.1" : "0.342");
        expect_point_is_its_run(r, p, k, model);
    }
    // The bias c moves M0 with it: the two values are different models.
    EXPECT_GT(res.points[2].estimates.mobility.value, res.points[0].estimates.mobility.value);
    ASSERT_EQ(res.exponents.size(), 2u);
    EXPECT_EQ(res.exponents[0].varied, 0.1);
    EXPECT_EQ(res.exponents[1].varied, 0.342);
    EXPECT_NEAR(res.exponents[1].exponent.value, res.points[3].slope.value, 1e-9); // two noises: the secant
    // The reports name the constant and give every point's value.
    const std::string table = ss::to_table(res), csv = ss::to_csv(res), json = ss::to_json(res);
    EXPECT_NE(table.find("c swept over 0.1, 0.342"), std::string::npos) << table;
    EXPECT_EQ(table.find("c=9"), std::string::npos) << table; // the placeholder is not shown
    EXPECT_NE(csv.find("\nvaried,tau,noise,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("\n0.342,0.5,4,"), std::string::npos) << csv;
    EXPECT_NE(json.find("\"vary\": \"c\""), std::string::npos);
    EXPECT_NE(json.find("\"varied\": 0.342"), std::string::npos);
}

TEST(SweepVary, WithoutItNothingChanges) {
    ss::SweepRequest r = unvaried_sweep();
    const ss::SweepResult res = ss::compute_sweep(r);
    ASSERT_FALSE(res.varies());
    ASSERT_EQ(res.points.size(), 2u);
    EXPECT_TRUE(std::isnan(res.points[0].varied));
    EXPECT_EQ(ss::to_csv(res).find("varied"), std::string::npos);
}

// --control-variate and --control-variate-pilot reach every point: each is
// still its own diffusivity run with those settings, and they change D.
TEST(Sweep, ControlVariateSettingsReachEveryPoint) {
    ss::SweepRequest r = unvaried_sweep();
    std::vector<double> d;
    for (auto [mode, pilot] : {std::pair{ss::ControlVariateMode::Auto, ss::default_control_variate_pilot},
                               std::pair{ss::ControlVariateMode::Auto, std::uint64_t{0}},
                               std::pair{ss::ControlVariateMode::Off, ss::default_control_variate_pilot}}) {
        r.control_variate = mode;
        r.control_variate_pilot = pilot;
        const ss::SweepResult res = ss::compute_sweep(r);
        ASSERT_EQ(res.points.size(), 2u);
        ss::ModelParams model;
        model.drift = r.params.drift;
        for (std::size_t k = 0; k < 2; ++k) expect_point_is_its_run(r, res.points[k], k, model);
        d.push_back(res.points[0].estimates.diffusivity.value);
    }
    EXPECT_NE(d[0], d[1]);
    EXPECT_NE(d[0], d[2]);
}

TEST(SweepVary, StaticFrictionIsAnAxis) {
    // --vary static-friction: each point is the diffusivity run with that
    // static friction (issue 46), bit for bit, on its own sample indices.
    ss::SweepRequest r;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-3);
    r.vary = std::string(ss::vary_static_friction);
    r.vary_values = {5.76, 3.84};
    r.noises = {5};
    r.taus = {0.5};
    r.excursions = 64;
    r.control.seed = 5;
    const ss::SweepResult res = ss::compute_sweep(r);
    ASSERT_EQ(res.points.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
        const ss::SweepPoint& p = res.points[k];
        EXPECT_EQ(p.varied, k == 0 ? 3.84 : 5.76);
        ss::ModelParams model;
        model.static_friction = p.varied;
        expect_point_is_its_run(r, p, k, model);
    }
    EXPECT_NE(ss::to_table(res).find("static-friction swept over 3.84, 5.76"), std::string::npos) << ss::to_table(res);
    // A value below the friction is refused, naming the point; so is
    // --static-friction beside the axis that sweeps it.
    r.vary_values = {3.0};
    try {
        ss::validate(r);
        ADD_FAILURE() << "static friction 3 < friction 3.84 accepted";
    } catch (const ss::InvalidParameter& e) {
        EXPECT_EQ(e.parameter(), "static-friction") << e.what();
    }
    r.vary_values = {5.76};
    r.params.static_friction = 4.0;
    expect_refused(r, "static-friction", "give its values in --vary-values");
}

TEST(SweepVary, MisuseIsRefusedByName) {
    ss::SweepRequest r = varied_sweep();
    r.params.drift.clear();
    expect_refused(r, "vary", "there is no --drift for \"c\"");
    r = varied_sweep();
    r.vary = "d";
    expect_refused(r, "vary", "\"d\" is not a constant of the --drift expression");
    r = varied_sweep();
    r.vary_values.clear();
    expect_refused(r, "vary-values", "needs at least one value");
    r = varied_sweep();
    r.vary.clear();
    expect_refused(r, "vary-values", "needs --vary NAME");
    r = varied_sweep();
    r.vary_values = {0.2, std::nan("")};
    expect_refused(r, "vary-values", "finite");
    // A value at which the law no longer confines: named with its point.
    r = varied_sweep();
    r.params.drift = "c*v";
    r.vary_values = {-1, 1};
    expect_refused(r, "drift", "at c 1,");
}

TEST(DriftExpressionConstants, NamesButV) {
    EXPECT_EQ(ss::drift_expression_constants("a*v - c*v^3"), (std::vector<std::string>{"a", "c"}));
    EXPECT_TRUE(ss::drift_expression_constants("-v/0.067 + 0.342").empty());
    EXPECT_THROW(ss::drift_expression_constants("-v/"), ss::InvalidParameter);
}

} // namespace

// Guards the sweep's notes: the points whose interval of D is flagged (the
// pilot's tail index of D's influence function, diffusivity.hpp) are counted
// in one note, not one note per point with its own numbers.
TEST(SweepVary, FlaggedIntervalsAreOneNote) {
    ss::SweepRequest r;
    r.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-2);
    r.params.relaxation = std::numeric_limits<double>::infinity(); // no drag: heavy tails
    r.params.bias = 0.3;
    r.noises = {1, 2, 3};
    r.taus = {0.1};
    r.excursions = 128;
    r.control.seed = 3;
    const ss::SweepResult res = ss::compute_sweep(r);
    std::size_t flagged = 0;
    for (const auto& p : res.points)
        for (const auto& w : p.warnings) flagged += w.rfind("D's interval may cover well below its level", 0) == 0;
    ASSERT_GT(flagged, 0u) << "coloured noise with a bias and no drag, 128 excursions: flagged";
    std::size_t notes = 0;
    for (const auto& w : res.warnings) {
        EXPECT_NE(w.rfind("D's interval may cover", 0), 0u) << "a point's own note in the sweep's: " << w;
        if (w.find("points D's interval may cover well below its level") != std::string::npos) {
            ++notes;
            EXPECT_EQ(w.rfind("at " + std::to_string(flagged) + " of 3 points", 0), 0u) << w;
        }
    }
    EXPECT_EQ(notes, 1u);
}
