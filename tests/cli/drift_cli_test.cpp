// SPDX-License-Identifier: BSD-3-Clause
// The drift law on the command line: --drift, --drift-params, --drift-table,
// --knots and --check-knots. Each bad input exits 2 with one line naming the
// flag and writes nothing; the JSON gives the law so that the run can be
// repeated; --print-config then --config reproduces the run bit for bit.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace clitest;

const Args kFast{"diffusivity", "--friction", "1", "--noise", "1", "--tau", "1", "--engine", "pdmp", "--grid", "0.2",
                 "--excursions", "2000", "--threads", "2", "--format", "json"};

Args with(Args a, const Args& more) {
    a.insert(a.end(), more.begin(), more.end());
    return a;
}

void expect_refused(const Args& args, const std::string& flag, const std::string& needle) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << describe(args) << "\nstderr: " << r.err;
    EXPECT_EQ(r.out, "") << describe(args);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(args) << ": " << r.err;
    EXPECT_NE(r.err.find(flag + ":"), std::string::npos) << describe(args) << ": " << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << describe(args) << ": expected '" << needle << "' in " << r.err;
}

std::string table_file(const std::string& text) {
    const std::string path = temp_file("drift_table");
    std::ofstream(path) << text;
    return path;
}

TEST(CliDrift, BadLawsAreRefusedWithOneLine) {
    expect_refused(with(kFast, {"--drift", "sin("}), "--drift", "cannot read");
    expect_refused(with(kFast, {"--drift", "x*v - v"}), "--drift", "names 'x'");
    expect_refused(with(kFast, {"--drift", "1/v"}), "--drift", "not finite");
    expect_refused(with(kFast, {"--drift", "v"}), "--drift", "does not confine");
    expect_refused(with(kFast, {"--drift", "a*v - v^3", "--drift-params", "a"}), "--drift-params", "NAME=NUM");
    expect_refused(with(kFast, {"--drift", "-v", "--knots", "8"}), "--knots", "odd");
    expect_refused(with(kFast, {"--drift", "-v", "--bias", "0.1"}), "--bias", "cannot be combined with --drift");
    expect_refused(with(kFast, {"--drift", "-v", "--relaxation", "2"}), "--relaxation", "cannot be combined");
    expect_refused({"diffusivity", "--drift", "-v", "--tau", "0", "--scheme", "event", "--excursions", "100"},
                   "--scheme", "white-noise event scheme takes the affine drift law only");
    expect_refused(with(kFast, {"--check-knots"}), "--check-knots", "needs a drift law");
    const std::string unsorted = table_file("v,b\n1,0\n-1,1\n");
    expect_refused(with(kFast, {"--drift-table", unsorted}), "--drift-table", "unsorted");
    const std::string dup = table_file("-1,1\n-1,2\n1,0\n");
    expect_refused(with(kFast, {"--drift-table", dup}), "--drift-table", "duplicate");
    const std::string nan = table_file("-1,nan\n1,0\n");
    expect_refused(with(kFast, {"--drift-table", nan}), "--drift-table", "finite");
    const std::string one = table_file("-1,1\n");
    expect_refused(with(kFast, {"--drift-table", one}), "--drift-table", "at least two rows");
    expect_refused(with(kFast, {"--drift-table", "/nonexistent/law.csv"}), "--drift-table", "cannot read");
    // Issue 50, item 5: drift input without surprises.
    expect_refused(with(kFast, {"--drift", ""}), "--drift", "is empty"); // ran the Fig. 2 law
    expect_refused(with(kFast, {"--drift-table", ""}), "--drift-table", "is empty");
    expect_refused(with(kFast, {"--drift", "a*v", "--drift-params", "a=-1,a=-2"}), "--drift-params", "given twice");
    expect_refused(with(kFast, {"--drift-params", "a=1"}), "--drift-params", "there is none");
    expect_refused(with(kFast, {"--knots", "65"}), "--knots", "there is none");
    expect_refused(with(kFast, {"--drift", "v=3"}), "--drift", "assigns");
    expect_refused(with(kFast, {"--drift", "-v,2*v"}), "--drift", "list of expressions");
    expect_refused(with(kFast, {"--drift-table", "/tmp"}), "--drift-table", "is a directory");
    const std::string hex = table_file("v,b\n-0x10,3\n0,0\n0x10,-3\n");
    expect_refused(with(kFast, {"--drift-table", hex}), "--drift-table", "is not two numbers");
    expect_refused({"diffusivity", "--tau", "5e-324", "--excursions", "100"}, "--tau", "white to double precision");
    expect_refused({"sweep", "--noise", "1:10:3", "--tau", "1:2:30000"}, "--tau", "has the most values");
    // Comparisons and functions of several arguments still read.
    EXPECT_EQ(run(with(kFast, {"--drift", "(v<=1)*(-v) + (v>1)*(-2*v)"})).code, 0);
    EXPECT_EQ(run(with(kFast, {"--drift", "min(-v, 1-v)"})).code, 0);
    for (const auto& f : {unsorted, dup, nan, one, hex}) std::remove(f.c_str());
}

TEST(CliDrift, JsonGivesTheLawAndTheRunRepeatsFromIt) {
    const Args args = with(kFast, {"--drift", "a*v - 0.5*v^3", "--drift-params", "a=0.8", "--check-knots"});
    const auto j = run_json(args);
    ASSERT_TRUE(j);
    const auto& p = (*j)["params"];
    EXPECT_EQ(p["drift"], "a*v - 0.5*v^3");
    EXPECT_EQ(p["drift_params"], "a=0.8");
    EXPECT_EQ(p["knots"], 1025);
    EXPECT_FALSE(p.contains("relaxation")) << "the affine law's settings are not the run's";
    EXPECT_FALSE(p.contains("bias"));
    EXPECT_EQ((*j)["knots_check"]["check_knots"], 513);
    EXPECT_TRUE((*j)["knots_check"]["diffusivity"].contains("stderr"));
    // --print-config, then --config: the same numbers.
    const Result printed = run(with(args, {"--print-config"}));
    ASSERT_EQ(printed.code, 0) << printed.err;
    const std::string config = temp_file("drift_config");
    std::ofstream(config) << printed.out;
    const auto again = run_json({"diffusivity", "--config", config, "--format", "json"});
    ASSERT_TRUE(again);
    EXPECT_EQ((*again)["diffusivity"], (*j)["diffusivity"]);
    EXPECT_EQ((*again)["mobility"], (*j)["mobility"]);
    std::remove(config.c_str());
}

TEST(CliDrift, EveryCommandTakesALaw) {
    const Args model{"--friction", "1", "--noise", "1", "--tau", "1", "--drift", "0.2 - v*abs(v)", "--format", "json"};
    for (const Args& cmd : {Args{"density", "--excursions", "500"}, Args{"correlation", "--excursions", "500"},
                            Args{"moments", "--trajectories", "64", "--times", "0.5,1"},
                            Args{"trajectory", "--time", "1"},
                            Args{"bruteforce", "--trajectories", "64", "--time", "5"}}) {
        const Args args = with(cmd, model);
        const Result r = run(args);
        EXPECT_EQ(r.code, 0) << describe(args) << "\nstderr: " << r.err;
        EXPECT_EQ(r.out.find("nan"), std::string::npos) << describe(args);
    }
    const auto white = run_json({"analytic", "--drift", "0.2 - v*abs(v)", "--format", "json"});
    ASSERT_TRUE(white);
    EXPECT_GT((*white)["diffusivity"].get<double>(), 0.0);
}

} // namespace
