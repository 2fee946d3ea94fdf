// SPDX-License-Identifier: BSD-3-Clause
// --engine kolmogorov: diffusivity, density and sweep solved on grids, each value with
// its estimated discretisation error and no standard error; every tau' > 0 down
// to the white-noise limit; every command that samples paths and white noise
// refused in one line.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <thread>

#include "cli_support.hpp"

namespace {

using namespace clitest;
using nlohmann::json;

// A loose precision: one round of grids, well under a second.
const Args kBase{"diffusivity", "--engine", "kolmogorov", "--rel-precision", "0.01", "--format", "json"};

TEST(CliKolmogorov, DiffusivityJsonHasValueAndErrorOfKindSolved) {
    const auto j = run_json(kBase);
    ASSERT_TRUE(j);
    EXPECT_EQ((*j)["engine"], "kolmogorov");
    for (const char* key : {"diffusivity", "mobility", "stuck_probability", "mean_duration"}) {
        const json& e = (*j)[key];
        ASSERT_TRUE(e.contains("value") && e.contains("error")) << key;
        EXPECT_FALSE(e.contains("stderr") || e.contains("ci")) << key;
        EXPECT_EQ(e["kind"], "solved") << key;
        EXPECT_GT(e["error"].get<double>(), 0) << key;
        EXPECT_LT(e["error"].get<double>(), std::abs(e["value"].get<double>())) << key;
    }
    EXPECT_TRUE((*j)["precision"]["reached"].get<bool>());
    EXPECT_LE((*j)["precision"]["relative_error"].get<double>(), 0.01);
    // No excursion totals, step or seed for a solver; its details name it.
    for (const char* key : {"completed", "capped", "method", "grid"}) EXPECT_FALSE(j->contains(key)) << key;
    EXPECT_EQ((*j)["engine_details"]["method"], "kolmogorov");
    EXPECT_FALSE((*j)["params"].contains("dt") || (*j)["params"].contains("seed"));
}

TEST(CliKolmogorov, EveryTauDownToTheWhiteNoiseLimit) {
    // Near-white noise (tau' = 0.01, 1e-5) was refused below 0.05; now its own
    // discretisation solves it, and below tau' = 1e-6 the white-noise values
    // come with a bound and a note.
    for (const char* tau : {"0.01", "1e-5"}) {
        const auto j = run_json(with(with(kBase, {"--tau", tau}), {"--friction", "1", "--noise", "1", "--relaxation",
                                                                    "inf", "--bias", "0"}));
        ASSERT_TRUE(j) << tau;
        const json& method = (*j)["engine_details"]["method"];
        EXPECT_NE(method.get<std::string>().find("near-white"), std::string::npos) << method;
        const double d = (*j)["diffusivity"]["value"], error = (*j)["diffusivity"]["error"];
        EXPECT_GT(d, 1.2) << tau; // between D(tau' = 0.1) = 1.06 and the white 1.25
        EXPECT_LT(d, 1.25) << tau;
        EXPECT_LT(error, 0.01 * d) << tau;
    }
    const auto white = run_json(with(with(kBase, {"--tau", "1e-9"}), {"--friction", "1", "--noise", "1", "--relaxation",
                                                                       "inf", "--bias", "0"}));
    ASSERT_TRUE(white);
    EXPECT_EQ((*white)["diffusivity"]["value"].get<double>(), 1.25);
    const std::string notes = (*white)["warnings"].dump();
    EXPECT_NE(notes.find("white-noise values"), std::string::npos) << notes;
    // A sweep over tau answers how white is white enough: D over white noise's
    // D at every point, the fitted departure and where it crosses 1%.
    const auto sweep = run_json(with({"sweep", "--engine", "kolmogorov", "--noise", "1", "--tau", "1e-4,1e-3,1e-2,3e-2",
                                      "--rel-precision", "0.01", "--format", "json"},
                                     {"--friction", "1", "--relaxation", "inf", "--bias", "0"}));
    ASSERT_TRUE(sweep);
    for (const json& p : (*sweep)["points"]) {
        EXPECT_LT(p["white_ratio"]["value"].get<double>(), 1.0) << p;
        EXPECT_GT(p["white_ratio"]["value"].get<double>(), 0.9) << p;
    }
    const json& limit = (*sweep)["white_limits"][0];
    EXPECT_NEAR(limit["exponent"]["value"].get<double>(), 1.0, 0.1) << limit;
    EXPECT_NEAR(limit["half_order"]["value"].get<double>(), 0.0, 0.05) << limit;
    EXPECT_GT(limit["tau_within_percent"].get<double>(), 1e-3) << limit;  // measured 0.0076 s
    // The density's mean and variance of V, at the paths Monte Carlo uses.
    const auto density = run_json({"density", "--engine", "kolmogorov", "--tau", "0.001", "--format", "json"});
    ASSERT_TRUE(density);
    EXPECT_NEAR((*density)["variance"]["value"].get<double>(), 0.1005, 0.002) << *density; // white: 0.1035
    EXPECT_EQ((*density)["mean"]["value"], (*density)["mobility"]["value"]);
    EXPECT_LT(limit["tau_within_percent"].get<double>(), 1e-2) << limit;
}

// Issue 50: the Monte Carlo engines' settings would change nothing here, so a
// value other than their default is refused in one line naming the flag.
TEST(CliKolmogorov, SettingsOfTheMonteCarloEnginesAreRefused) {
    const std::vector<Args> cases{{"--estimator", "paper"}, {"--excursions", "100"}, {"--seed", "3"},
                                  {"--dt", "0.01"},         {"--scheme", "event"},   {"--control-variate", "off"},
                                  {"--max-steps", "1000"},  {"--level", "0.9"},      {"--grid", "0.2"}};
    for (const Args& extra : cases) {
        Args args{"diffusivity", "--engine", "kolmogorov"};
        args.insert(args.end(), extra.begin(), extra.end());
        const Result r = run(args);
        EXPECT_EQ(r.code, 2) << describe(args) << "\n" << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("stickslip: error: " + extra[0] + ":", 0), 0u) << r.err;
        EXPECT_NE(r.err.find("samples nothing"), std::string::npos) << r.err;
        EXPECT_TRUE(r.out.empty());
    }
    const Result density = run({"density", "--engine", "kolmogorov", "--bins", "10"});
    EXPECT_EQ(density.code, 2) << density.err;
    EXPECT_EQ(density.err.rfind("stickslip: error: --bins:", 0), 0u) << density.err;
    // Its own settings run.
    EXPECT_EQ(run(with(kBase, {"--threads", "1"})).code, 0);
}

// Issue 50: models whose rarer phase (sliding, or sticking) the grids cannot
// resolve are refused before any work, in one line naming the setting (they
// ran 10-70 s and up to 24 GB, then failed with a message about samples, or
// an LU's).
TEST(CliKolmogorov, ModelsBeyondTheGridsAreRefusedAtOnce) {
    const std::vector<std::pair<Args, std::string>> cases{
        {{"--tau", "1e3"}, "--tau"},        {{"--friction", "100"}, "--friction"}, {{"--bias", "100"}, "--bias"},
        {{"--tau", "1e6"}, "--tau"},        {{"--noise", "1e-3"}, "--noise"},      {{"--bias", "1e6"}, "--bias"},
        {{"--tau", "1e300"}, "--tau"}};
    for (const auto& [extra, flag] : cases) {
        Args args{"diffusivity", "--engine", "kolmogorov"};
        args.insert(args.end(), extra.begin(), extra.end());
        const Result r = run(args);
        EXPECT_EQ(r.code, 2) << describe(args) << "\n" << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("stickslip: error: " + flag + ":", 0), 0u) << r.err;
        EXPECT_NE(r.err.find("static band with probability"), std::string::npos) << r.err;
    }
}

// Issue 50: a weakly confining law (no drag and a bias near the friction;
// drag too weak to stop the slips within the chain's range) was solved on a
// cut velocity range with a tiny claimed error (D 466 and 352, M0 4.24 and
// 3.78). Monte Carlo (docs/validation.md, "The Kolmogorov engine's domain"):
// D 4721 +- 85 (inclusion) and 4631 +- 108 (PDMP), M0 5.862 +- 0.008 for the
// first (the engine: 4591.6, 5.8484); D 950 +- 6 (956 +- 8 plain), M0 4.3237
// +- 0.0026 for the second (the engine: 963.5, 4.32827).
TEST(CliKolmogorov, WeaklyConfinedLawsAreSolvedOnTheRangeTheyNeed) {
    const auto bias = run_json({"diffusivity", "--engine", "kolmogorov", "--relaxation", "inf", "--bias", "3.5",
                                "--rel-precision", "0.01", "--format", "json"});
    ASSERT_TRUE(bias);
    EXPECT_NEAR((*bias)["mobility"]["value"].get<double>(), 5.85, 0.05) << *bias;
    EXPECT_NEAR((*bias)["diffusivity"]["value"].get<double>(), 4590, 200) << *bias;
    const json& grid = (*bias)["engine_details"]["grid"];
    EXPECT_GT(grid["v_upper"].get<double>(), 100.0) << grid;
    const auto drift = run_json({"diffusivity", "--engine", "kolmogorov", "--drift", "3.5 - 0.01*v", "--rel-precision",
                                 "0.01", "--format", "json"});
    ASSERT_TRUE(drift);
    EXPECT_NEAR((*drift)["diffusivity"]["value"].get<double>(), 960, 100) << *drift;
    // The chain was chosen (drag) and turned down for its range: a note says so.
    EXPECT_NE((*drift)["warnings"].dump().find("the upwind chain's velocity range held"), std::string::npos)
        << (*drift)["warnings"];
}

// Issue 50: under a memory limit the solve is refused in one line before its
// factorisation (it aborted inside Eigen with "double free or corruption").
TEST(CliKolmogorov, AMemoryLimitIsOneLineNotACrash) {
    const std::string out_path = temp_file("out"), err_path = temp_file("err");
    const pid_t pid = ::fork();
    if (pid == 0) {
        struct rlimit limit {};
        limit.rlim_cur = limit.rlim_max = 160000ul * 1024ul;
        ::setrlimit(RLIMIT_AS, &limit);
        const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(out, STDOUT_FILENO);
        ::dup2(err, STDERR_FILENO);
        const char* argv[] = {STICKSLIP_CLI_PATH, "diffusivity", "--engine", "kolmogorov", nullptr};
        ::execv(argv[0], const_cast<char* const*>(argv));
        ::_exit(127);
    }
    const auto status = wait_for_exit(pid, 60);
    ASSERT_TRUE(status.has_value());
    const std::string err = slurp(err_path);
    std::remove(out_path.c_str());
    std::remove(err_path.c_str());
    ASSERT_TRUE(WIFEXITED(*status)) << "died by signal " << WTERMSIG(*status) << ": " << err;
    EXPECT_EQ(WEXITSTATUS(*status), 1) << err;
    EXPECT_EQ(count_lines(err), 1) << err;
    EXPECT_NE(err.find("out of memory"), std::string::npos) << err;
}

// Issue 50: SIGTERM stops a solve between its rounds of grids with the result
// so far, marked interrupted, and exit 143 (it ran to the end, unmarked).
TEST(CliKolmogorov, ASignalStopsTheSolveWithTheResultSoFar) {
    const Scratch dir("kstop");
    const pid_t pid = start({"diffusivity", "--engine", "kolmogorov", "--friction", "1", "--noise", "1", "--relaxation",
                             "inf", "--bias", "0", "--tau", "0.01", "--rel-precision", "1e-7", "--format", "json",
                             "--output", dir / "out.json"},
                            dir / "stdout", dir / "err.txt");
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(2500)); // the first round has finished
    ASSERT_EQ(::kill(pid, SIGTERM), 0);
    const auto status = wait_for_exit(pid, 30);
    ASSERT_TRUE(status.has_value()) << "the solve did not stop";
    ASSERT_TRUE(WIFEXITED(*status)) << "died by signal " << WTERMSIG(*status);
    EXPECT_EQ(WEXITSTATUS(*status), 143) << slurp(dir / "err.txt");
    const json j = json::parse(slurp(dir / "out.json"));
    EXPECT_TRUE(j.value("interrupted", false)) << j.dump(1);
    EXPECT_NE(j["warnings"].dump().find("interrupted: the estimates are those of the rounds"), std::string::npos);
    EXPECT_GT(j["diffusivity"]["value"].get<double>(), 1.2);
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

// A solved sweep: every point is the diffusivity the solver gives there, bit
// for bit, with errors and no standard errors; slopes from neighbours.
TEST(CliKolmogorov, SweepPointsAreTheSolversDiffusivities) {
    const auto j = run_json({"sweep", "--engine", "kolmogorov", "--noise", "2,4,8", "--tau", "0.5",
                             "--rel-precision", "0.01", "--format", "json"});
    ASSERT_TRUE(j);
    EXPECT_EQ((*j)["engine_details"]["method"], "kolmogorov");
    const json& points = (*j)["points"];
    ASSERT_EQ(points.size(), 3u);
    const char* noises[] = {"2", "4", "8"};
    for (std::size_t k = 0; k < 3; ++k) {
        const json& p = points[k];
        const auto one = run_json({"diffusivity", "--engine", "kolmogorov", "--noise", noises[k], "--tau", "0.5",
                                   "--rel-precision", "0.01", "--format", "json"});
        ASSERT_TRUE(one);
        for (const char* key : {"diffusivity", "mobility", "stuck_probability", "mean_duration"}) {
            EXPECT_EQ(p[key], (*one)[key]) << key << " at noise " << p["noise"];
            EXPECT_FALSE(p[key].contains("stderr")) << key;
        }
    }
    const double d2 = points[0]["diffusivity"]["value"], d8 = points[2]["diffusivity"]["value"];
    EXPECT_DOUBLE_EQ(points[1]["slope"]["value"].get<double>(), std::log(d8 / d2) / std::log(4.0));
    EXPECT_GT(points[1]["slope"]["error"].get<double>(), 0.0);
    EXPECT_EQ((*j)["exponents"].size(), 1u);

    const Result table = run({"sweep", "--engine", "kolmogorov", "--noise", "2,4", "--tau", "0.5", "--rel-precision",
                              "0.01"});
    ASSERT_EQ(table.code, 0) << table.err;
    EXPECT_NE(table.out.find("discretisation errors, not standard errors"), std::string::npos) << table.out;
    EXPECT_EQ(table.out.find("excursions"), std::string::npos) << table.out;
}

TEST(CliKolmogorov, RefusedWhereItCannotServeInOneLine) {
    const std::string checkpoint = temp_file("ckpt");
    const std::vector<std::pair<Args, std::string>> cases{
        {{"correlation", "--engine", "kolmogorov"}, "--engine inclusion or pdmp"},
        {{"moments", "--engine", "kolmogorov", "--times", "0.5"}, "--engine inclusion or pdmp"},
        {{"bruteforce", "--engine", "kolmogorov"}, "--engine inclusion or pdmp"},
        {{"trajectory", "--engine", "kolmogorov"}, "--engine inclusion or pdmp"},
        {{"sweep", "--engine", "kolmogorov", "--noise", "1,2", "--tau", "0"}, "stickslip analytic"},
        {{"sweep", "--noise", "1,2", "--rel-precision", "0.01"}, "--engine kolmogorov"},
        {{"sweep", "--engine", "kolmogorov", "--noise", "1,2", "--checkpoint", checkpoint}, "nothing to checkpoint"},
        {{"diffusivity", "--engine", "kolmogorov", "--tau", "0"}, "stickslip analytic"},
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
