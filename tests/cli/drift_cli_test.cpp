// SPDX-License-Identifier: BSD-3-Clause
// The drift law on the command line: --drift, --drift-params, --drift-table,
// --knots and --check-knots. Each bad input exits 2 with one line naming the
// flag and writes nothing; the JSON gives the law so that the run can be
// repeated; --print-config then --config reproduces the run bit for bit.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <string>

#include <sys/stat.h>

#include <thread>

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

// Issue 50, item 2: a table is read once per command, bounded, from a pipe
// too, its digest in the JSON and the checkpoint; a relative path in a config
// names a file beside the config.
TEST(CliDrift, ATableIsReadOnceAndRecorded) {
    const Scratch dir("table_once");
    const std::string law = "v,b\n-10,3\n0,0.342\n10,-3\n";
    const std::string table = dir / "law.csv";
    { std::ofstream(table) << law; }
    // A pipe: read more than once, it gave "got 0 rows".
    const std::string fifo = dir / "law.fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] { std::ofstream(fifo) << law; });
    const auto piped = run_json({"diffusivity", "--drift-table", fifo, "--excursions", "200", "--format", "json"});
    writer.join();
    ASSERT_TRUE(piped);
    const auto filed = run_json({"diffusivity", "--drift-table", table, "--excursions", "200", "--format", "json"});
    ASSERT_TRUE(filed);
    EXPECT_EQ((*piped)["params"]["drift_table_digest"], (*filed)["params"]["drift_table_digest"]);
    EXPECT_EQ((*piped)["diffusivity"], (*filed)["diffusivity"]);
    // Bounded before it fills memory (/dev/zero reached 1 GB in 3 s).
    const Result zero = run({"diffusivity", "--drift-table", "/dev/zero", "--excursions", "100"});
    EXPECT_EQ(zero.code, 2);
    EXPECT_NE(zero.err.find("larger than 16 MiB"), std::string::npos) << zero.err;
    // A config's relative path is the config's folder's.
    const std::string config = dir / "run.toml";
    { std::ofstream(config) << "drift-table = \"law.csv\"\nexcursions = 200\n"; }
    const auto configured = run_json({"diffusivity", "--config", config, "--format", "json"});
    ASSERT_TRUE(configured);
    EXPECT_EQ((*configured)["params"]["drift_table"], table);
    // A resume whose table changed is refused (it ran the other law, D 3.8 times off).
    const std::string ckpt = dir / "run.ckpt";
    ASSERT_EQ(run({"diffusivity", "--drift-table", table, "--excursions", "200", "--checkpoint", ckpt, "--quiet"}).code, 0);
    { std::ofstream(table) << "v,b\n-10,2\n0,0.1\n10,-2\n"; }
    const Result resumed = run({"diffusivity", "--drift-table", table, "--excursions", "200", "--resume", ckpt});
    EXPECT_EQ(resumed.code, 2) << resumed.err;
    EXPECT_NE(resumed.err.find("drift-table-digest"), std::string::npos) << resumed.err;
}

// Issue 50, item 2: a signal while a drift law's run is being prepared (the
// event scheme's pieces, a sweep's points: 2-4 s of work for this sweep) stops
// it there, exit 143 and a line saying so (it waited for the preparation to end).
TEST(CliDrift, ASignalWhilePreparingStopsAtOnce) {
    const Scratch dir("prep_stop");
    const pid_t pid = start({"sweep", "--drift", "3.5-0.01*v", "--tau", "0.1,0.2", "--excursions", "1e5"},
                            dir / "stdout", dir / "err.txt");
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    ASSERT_EQ(::kill(pid, SIGTERM), 0);
    // Measured: it stops 0.01 s after the signal; the line below proves where
    // it stopped without timing it (a loaded machine may be slow).
    const auto status = wait_for_exit(pid, 60);
    ASSERT_TRUE(status.has_value()) << "the preparation did not stop";
    ASSERT_TRUE(WIFEXITED(*status)) << "died by signal " << WTERMSIG(*status);
    EXPECT_EQ(WEXITSTATUS(*status), 143) << slurp(dir / "err.txt");
    EXPECT_NE(slurp(dir / "err.txt").find("while preparing"), std::string::npos) << slurp(dir / "err.txt");
}

// Issue 50, item 6: a stiff law's automatic step follows the noise and the
// friction, not the law's 1/L (it was 1.25e-7 s, 3.5 h; docs/validation.md,
// "Choosing the step": D the same at dt = 1e-3 s).
TEST(CliDrift, AStiffLawsAutomaticStepIsNotNeedlesslyFine) {
    const auto j = run_json({"diffusivity", "--drift", "-v*1e6", "--excursions", "200", "--format", "json"});
    ASSERT_TRUE(j);
    const double friction_time = 5.0 / (3.84 * 3.84);
    EXPECT_DOUBLE_EQ((*j)["params"]["dt"].get<double>(), friction_time / 256) << (*j)["params"];
    EXPECT_EQ((*j)["warnings"].dump().find("long run"), std::string::npos) << (*j)["warnings"];
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
    EXPECT_TRUE((*j)["knots_check"]["diffusivity"].contains("error"));
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
    EXPECT_GT((*white)["diffusivity"]["value"].get<double>(), 0.0);
    EXPECT_EQ((*white)["diffusivity"]["kind"], "solved"); // a quadrature, its error not estimated
}

} // namespace
