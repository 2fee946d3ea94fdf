// SPDX-License-Identifier: BSD-3-Clause
// The control variate's pilot (DiffusivityRequest::control_variate_pilot):
// a run's coefficients are those fitted on an independent pilot (its key
// pilot_seed(seed), the run's sample indices, the run's corrector), and its
// estimates are its own sums at them; pilot 0 fits them on the run itself.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "stickslip/corrector.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/sample_runs.hpp"
#include "stickslip/stats/control_variate.hpp"

namespace ss = stickslip;

namespace {

ss::DiffusivityRequest coloured_bias(std::uint64_t excursions) {
    ss::DiffusivityRequest q;
    q.params = ss::ModelParams{.friction = 1, .noise = 1, .tau = 0.1,
                               .relaxation = std::numeric_limits<double>::infinity(), .bias = 0.3};
    q.engine = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-2);
    q.excursions = excursions;
    q.control.seed = 9;
    q.control.threads = 2;
    return q;
}

TEST(ControlVariatePilot, TheRunsCoefficientsAreItsPilotsAndItsEstimatesItsOwnSums) {
    ss::DiffusivityRequest q = coloured_bias(500);
    const ss::DiffusivityResult r = ss::compute_diffusivity(q);
    ASSERT_TRUE(r.control_variate.has_value());
    EXPECT_EQ(r.control_variate->pilot_excursions, 2000u) << "at most 4 times the run's 500";

    const ss::PreparedEngine engine = ss::prepare(q);
    const auto corrector = ss::make_corrector(engine.model);
    ss::RunControl pilot_control = q.control;
    pilot_control.seed = ss::pilot_seed(q.control.seed);
    const ss::RunTotals pilot = ss::run_long_excursions(engine, 2000, pilot_control, corrector->table);
    const ss::RunTotals own = ss::run_long_excursions(engine, 500, q.control, corrector->table);
    const ss::ControlVariateEstimates expected =
        ss::estimate_control_variate(own.control_variate, 0.95, ss::fit_control_variate(pilot.control_variate));
    EXPECT_EQ(r.estimates.diffusivity.value, expected.diffusivity.value);
    EXPECT_EQ(r.estimates.diffusivity.error, expected.diffusivity.error);
    EXPECT_EQ(r.estimates.mobility.value, expected.mobility.value);
    EXPECT_EQ(r.control_variate->beta, expected.beta);
    EXPECT_EQ(r.monte_carlo().totals.work, own.work + pilot.work) << "the pilot's cost is the run's";

    // The shape of D's influence functions: measured on the pilot, at the
    // run's estimates and its own fitted beta.
    const auto centres = ss::influence_centres(own.control_variate, ss::fit_control_variate(own.control_variate));
    ASSERT_TRUE(centres.has_value());
    const ss::RunTotals shaped = ss::run_long_excursions(engine, 2000, pilot_control, corrector->table, &*centres);
    EXPECT_EQ(shaped.control_variate.sum(1).value(), pilot.control_variate.sum(1).value()) << "the sums are unchanged";
    const ss::InfluenceShape shape = shaped.control_variate.tail().shape();
    ASSERT_EQ(shape.samples, 2000u);
    EXPECT_EQ(r.control_variate->shape_excursions, 2000u);
    EXPECT_EQ(r.control_variate->skewness, shape.skewness);
    EXPECT_EQ(r.control_variate->excess_kurtosis, shape.excess_kurtosis);
    EXPECT_EQ(r.control_variate->tail_index, shape.tail_index);
    EXPECT_EQ(r.control_variate->tail_terms, shape.tail_terms);
    EXPECT_EQ(r.control_variate->plain_tail_index, shaped.control_variate.plain_tail().shape().tail_index);
    // Coloured noise with a bias and no drag: a heavy tail, so the interval is
    // flagged, and the note says so in place of the one on few excursions.
    EXPECT_LT(shape.tail_index, ss::interval_flag_tail_index);
    EXPECT_TRUE(r.control_variate->flagged);
    bool flag_note = false, few_note = false;
    for (const std::string& w : r.warnings) {
        flag_note |= w.rfind("D's interval may cover well below its level", 0) == 0;
        few_note |= w.find("fewer than 5000") != std::string::npos;
    }
    EXPECT_TRUE(flag_note);
    EXPECT_FALSE(few_note) << "the run's own diagnosis replaces the general note";
    q.control.threads = 1; // every field bit for bit on one thread
    const ss::DiffusivityResult one = ss::compute_diffusivity(q);
    EXPECT_EQ(one.control_variate->tail_index, r.control_variate->tail_index);
    EXPECT_EQ(one.control_variate->excess_kurtosis, r.control_variate->excess_kurtosis);
    EXPECT_EQ(one.control_variate->plain_skewness, r.control_variate->plain_skewness);
    q.control.threads = 2;

    q.control_variate_pilot = 0; // the coefficients fitted on the run: the same draws, another estimate
    const ss::DiffusivityResult fitted = ss::compute_diffusivity(q);
    EXPECT_EQ(fitted.control_variate->pilot_excursions, 0u);
    EXPECT_EQ(fitted.estimates.diffusivity.value,
              ss::estimate_control_variate(own.control_variate, 0.95).diffusivity.value);
    EXPECT_EQ(fitted.control_variate->plain_diffusivity.value, r.control_variate->plain_diffusivity.value);
    EXPECT_EQ(fitted.monte_carlo().totals.work, own.work);
    EXPECT_TRUE(std::isnan(fitted.control_variate->tail_index)) << "no pilot, no centre";
    EXPECT_FALSE(fitted.control_variate->flagged);
}

TEST(ControlVariatePilot, APilotOfOneOrBeyondItsIndicesIsRefused) {
    ss::DiffusivityRequest q = coloured_bias(64);
    q.control_variate_pilot = 1;
    EXPECT_THROW(ss::validate(q), ss::InvalidParameter);
    q.control_variate_pilot = ss::max_control_variate_pilot + 1;
    EXPECT_THROW(ss::validate(q), ss::InvalidParameter);
}

TEST(ControlVariatePilot, ThePilotsKeyIsABijectionOfTheSeed) {
    EXPECT_NE(ss::pilot_seed(0), ss::pilot_seed(1));
    EXPECT_NE(ss::pilot_seed(1), 1u);
    static_assert(ss::pilot_seed(1) == ss::pilot_seed(1)); // constexpr: the key is part of the format
}

} // namespace
