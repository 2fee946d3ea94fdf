#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "stickslip/params.hpp"

namespace ss = stickslip;

TEST(Params, NondimensionalRoundTrip) {
    ss::ModelParams p; // Fig. 2 case
    const ss::ModelParams nd = ss::to_nondimensional(p);
    EXPECT_DOUBLE_EQ(nd.friction, 1.0);
    EXPECT_DOUBLE_EQ(nd.noise, 1.0);
    const double tau0 = p.noise / (p.friction * p.friction);
    EXPECT_DOUBLE_EQ(nd.tau, p.tau / tau0);
    EXPECT_DOUBLE_EQ(nd.relaxation, p.relaxation / tau0);
    EXPECT_DOUBLE_EQ(nd.bias, p.bias / p.friction);
    const ss::ModelParams back = ss::from_nondimensional(nd, p.friction, p.noise);
    EXPECT_NEAR(back.tau, p.tau, 1e-15);
    EXPECT_NEAR(back.relaxation, p.relaxation, 1e-15);
    EXPECT_NEAR(back.bias, p.bias, 1e-15);
}

TEST(Params, InfiniteRelaxationSurvivesScaling) {
    ss::ModelParams p;
    p.relaxation = std::numeric_limits<double>::infinity();
    EXPECT_TRUE(std::isinf(ss::to_nondimensional(p).relaxation));
    EXPECT_EQ(p.inverse_relaxation(), 0.0);
}

TEST(Params, ValidationNamesTheParameter) {
    auto expect_bad = [](ss::ModelParams p, const char* name) {
        try {
            ss::validate(p);
            ADD_FAILURE() << "no error for " << name;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), name) << e.what();
        }
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    ss::ModelParams p;
    p.friction = 0; expect_bad(p, "friction");
    p = {}; p.friction = -1; expect_bad(p, "friction");
    p = {}; p.friction = nan; expect_bad(p, "friction");
    p = {}; p.noise = 0; expect_bad(p, "noise");
    p = {}; p.noise = inf; expect_bad(p, "noise");
    p = {}; p.tau = -0.1; expect_bad(p, "tau");
    p = {}; p.tau = inf; expect_bad(p, "tau");
    p = {}; p.relaxation = 0; expect_bad(p, "relaxation");
    p = {}; p.relaxation = nan; expect_bad(p, "relaxation");
    p = {}; p.bias = nan; expect_bad(p, "bias");
    p = {}; p.relaxation = inf; p.tau = 0; EXPECT_NO_THROW(ss::validate(p));
}
