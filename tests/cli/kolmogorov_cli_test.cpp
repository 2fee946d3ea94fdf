// SPDX-License-Identifier: BSD-3-Clause
// --engine kolmogorov: diffusivity and density solved on grids, each value with
// its estimated discretisation error and no standard error; every command that
// samples paths, white noise and near-white noise refused in one line.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "cli_support.hpp"

namespace {

using namespace clitest;
using nlohmann::json;

// A loose precision: one round of grids, well under a second.
const Args kBase{"diffusivity", "--engine", "kolmogorov", "--rel-precision", "0.01", "--format", "json"};

TEST(CliKolmogorov, DiffusivityJsonHasValueAndErrorNoStderr) {
    const auto j = run_json(kBase);
    ASSERT_TRUE(j);
    EXPECT_EQ((*j)["engine"], "kolmogorov");
    for (const char* key : {"diffusivity", "mobility", "stuck_probability", "mean_duration"}) {
        const json& e = (*j)[key];
        ASSERT_TRUE(e.contains("value") && e.contains("error")) << key;
        EXPECT_FALSE(e.contains("stderr") || e.contains("ci")) << key;
        EXPECT_GT(e["error"].get<double>(), 0) << key;
        EXPECT_LT(e["error"].get<double>(), std::abs(e["value"].get<double>())) << key;
    }
    EXPECT_TRUE((*j)["precision"]["reached"].get<bool>());
    EXPECT_LE((*j)["precision"]["relative_error"].get<double>(), 0.01);
    // No excursion totals, step or seed for a solver.
    for (const char* key : {"completed", "capped", "engine_details"}) EXPECT_FALSE(j->contains(key)) << key;
    EXPECT_FALSE((*j)["params"].contains("dt") || (*j)["params"].contains("seed"));
}

TEST(CliKolmogorov, TableSaysDiscretisationAndCountsNoExcursions) {
    const Result r = run({"diffusivity", "--engine", "kolmogorov", "--rel-precision", "0.01"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("+- error (discretisation)"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("excursions"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("stderr"), std::string::npos) << r.out;
}

TEST(CliKolmogorov, BudgetBeforePrecisionIsANote) {
    // 1e-6 cannot be reached in the default time budget: the result comes with a note.
    const auto j = run_json({"diffusivity", "--engine", "kolmogorov", "--rel-precision", "1e-6", "--format", "json"});
    ASSERT_TRUE(j);
    EXPECT_FALSE((*j)["precision"]["reached"].get<bool>());
    bool noted = false;
    for (const auto& w : (*j)["warnings"]) noted = noted || w.get<std::string>().find("budget") != std::string::npos;
    EXPECT_TRUE(noted) << j->dump();
}

TEST(CliKolmogorov, RefusedWhereItCannotServeInOneLine) {
    const std::string checkpoint = temp_file("ckpt");
    const std::vector<std::pair<Args, std::string>> cases{
        {{"correlation", "--engine", "kolmogorov"}, "--engine inclusion or pdmp"},
        {{"moments", "--engine", "kolmogorov", "--times", "0.5"}, "--engine inclusion or pdmp"},
        {{"bruteforce", "--engine", "kolmogorov"}, "--engine inclusion or pdmp"},
        {{"trajectory", "--engine", "kolmogorov"}, "--engine inclusion or pdmp"},
        {{"sweep", "--engine", "kolmogorov", "--noise", "1,2"}, "diffusivity --engine kolmogorov"},
        {{"diffusivity", "--engine", "kolmogorov", "--tau", "0"}, "stickslip analytic"},
        {{"diffusivity", "--engine", "kolmogorov", "--tau", "0.01"}, "inclusion engine"},
        {{"density", "--engine", "kolmogorov", "--tau", "0"}, "stickslip analytic"},
        {{"diffusivity", "--engine", "kolmogorov", "--check-dt"}, "inclusion engine"},
        {{"diffusivity", "--engine", "kolmogorov", "--checkpoint", checkpoint}, "nothing to checkpoint"},
    };
    for (const auto& [args, advice] : cases) {
        const Result r = run(args);
        EXPECT_EQ(r.code, 2) << describe(args) << "\n" << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(advice), std::string::npos) << describe(args) << "\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
    EXPECT_EQ(std::ifstream(checkpoint, std::ios::ate).tellg(), 0) << "a refused run writes no checkpoint";
    std::remove(checkpoint.c_str());
}

} // namespace
