// SPDX-License-Identifier: BSD-3-Clause
// The control variate's pilot (DiffusivityRequest::control_variate_pilot):
// a run's coefficients are those fitted on an independent pilot (its key
// pilot_seed(seed), the run's sample indices, the run's corrector), and its
// estimates are its own sums at them; pilot 0 fits them on the run itself.
#include <gtest/gtest.h>

#include <limits>

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

    q.control_variate_pilot = 0; // the coefficients fitted on the run: the same draws, another estimate
    const ss::DiffusivityResult fitted = ss::compute_diffusivity(q);
    EXPECT_EQ(fitted.control_variate->pilot_excursions, 0u);
    EXPECT_EQ(fitted.estimates.diffusivity.value,
              ss::estimate_control_variate(own.control_variate, 0.95).diffusivity.value);
    EXPECT_EQ(fitted.control_variate->plain_diffusivity.value, r.control_variate->plain_diffusivity.value);
    EXPECT_EQ(fitted.monte_carlo().totals.work, own.work);
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
