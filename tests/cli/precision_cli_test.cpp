// SPDX-License-Identifier: BSD-3-Clause
// Precision on demand: `diffusivity --rel-precision` runs batches until the
// interval half-width of D is at most the target (or --max-excursions).
#include <gtest/gtest.h>

#include "cli_support.hpp"

namespace {

using namespace clitest;
using nlohmann::json;

const Args kBase{"diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "256", "--format", "json"};

TEST(CliPrecision, StopsWithHalfWidthWithinTarget) {
    // The plain estimator (the control variate reaches 8% with the first batch).
    const auto j = run_json(with(kBase, {"--rel-precision", "0.08", "--control-variate", "off"}));
    ASSERT_TRUE(j);
    const auto& d = (*j)["diffusivity"];
    const double value = d["value"].get<double>(), hi = d["ci"][1].get<double>();
    EXPECT_LE((hi - value) / value, 0.08);
    EXPECT_TRUE((*j)["precision"]["reached"].get<bool>());
    EXPECT_GE((*j)["precision"]["batches"].get<int>(), 2) << "256 excursions alone are not enough for 8%";
    EXPECT_NEAR((*j)["precision"]["relative_half_width"].get<double>(), (hi - value) / value, 1e-12);
    EXPECT_EQ((*j)["completed"].get<std::uint64_t>() % 64, 0u) << "batches are whole blocks";
}

TEST(CliPrecision, SameResultForAnyThreadCount) {
    const auto a = run_json(with(kBase, {"--rel-precision", "0.1", "--threads", "1"}));
    const auto b = run_json(with(kBase, {"--rel-precision", "0.1", "--threads", "2"}));
    ASSERT_TRUE(a && b);
    EXPECT_EQ(without_work(*a), without_work(*b));
}

TEST(CliPrecision, CapIsReportedNotHidden) {
    const auto j = run_json(with(kBase, {"--rel-precision", "0.001", "--max-excursions", "512"}));
    ASSERT_TRUE(j);
    EXPECT_FALSE((*j)["precision"]["reached"].get<bool>());
    EXPECT_EQ((*j)["completed"].get<std::uint64_t>() + (*j)["capped"].get<std::uint64_t>(), 512u);
    bool warned = false;
    for (const auto& w : (*j)["warnings"]) warned = warned || w.get<std::string>().find("not reached") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(CliPrecision, BadValuesExitTwo) {
    for (const Args& a : {with(kBase, {"--rel-precision", "-0.1"}), with(kBase, {"--rel-precision", "1"}),
                          with(kBase, {"--rel-precision", "0.1", "--max-excursions", "10"})}) {
        const Result r = run(a);
        EXPECT_EQ(r.code, 2) << describe(a) << "\n" << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
    }
}

TEST(CliPrecision, OffByDefault) {
    const auto j = run_json(kBase);
    ASSERT_TRUE(j);
    EXPECT_FALSE(j->contains("precision"));
    EXPECT_EQ((*j)["completed"].get<std::uint64_t>(), 256u);
}

} // namespace
