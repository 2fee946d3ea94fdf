// SPDX-License-Identifier: BSD-3-Clause
// A run as a file: --print-config writes every setting of a subcommand (its
// effective values, defaults included, with units), and --config of that
// output reproduces the run bit for bit; flags override the file; bad files
// are refused with exit 2 and one line naming the key.
#include "cli_support.hpp"

#include <fstream>

namespace {

using namespace clitest;

std::string write_file(const std::string& text) {
    const std::string path = temp_file("config");
    std::ofstream(path) << text;
    return path;
}

json strip(json j) {
    j.erase("work");
    j.erase("revision");
    j.erase("command"); // the flags or --config FILE: the settings must be the same
    if (j.contains("settings")) j["settings"].erase("threads");
    if (j.contains("points"))
        for (auto& p : j["points"]) p.erase("work");
    return j;
}

/// The run as given on the command line, and the same run from the file
/// --print-config wrote for it: the JSON (less timing) must be identical.
void expect_reproduced(const Args& args) {
    Args print = args;
    print.push_back("--print-config");
    const Result printed = run(print);
    ASSERT_EQ(printed.code, 0) << describe(print) << "\n" << printed.err;
    EXPECT_NE(printed.out.find(" = "), std::string::npos) << printed.out;
    const std::string path = write_file(printed.out);
    Args direct = args, from_file{args[0], "--config", path};
    for (auto* a : {&direct, &from_file}) a->insert(a->end(), {"--format", "json", "--quiet"});
    const auto a = run_json(direct), b = run_json(from_file);
    ASSERT_TRUE(a && b) << describe(args);
    EXPECT_EQ(strip(*a), strip(*b)) << describe(args) << "\nconfig:\n" << printed.out;
    std::remove(path.c_str());
}

TEST(CliConfig, PrintConfigThenConfigReproducesEverySubcommand) {
    expect_reproduced({"diffusivity", "--excursions", "128", "--scheme", "resolvent", "--dt", "2e-3", "--seed", "7", "--estimator", "paper",
                       "--relaxation", "inf", "--bias", "0.5", "--level", "0.9"});
    expect_reproduced({"diffusivity", "--engine", "pdmp", "--excursions", "64", "--grid", "0.25", "--rel-precision",
                       "0.3", "--max-excursions", "1000"});
    expect_reproduced({"bruteforce", "--time", "1.5", "--trajectories", "64", "--scheme", "resolvent", "--dt", "1e-3", "--x0", "0.25"});
    expect_reproduced({"density", "--excursions", "64", "--scheme", "resolvent", "--dt", "2e-3", "--bins", "7", "--range=-0.5,0.75"});
    expect_reproduced({"correlation", "--excursions", "64", "--scheme", "resolvent", "--dt", "2e-3", "--lags", "3", "--max-lag", "0.2"});
    expect_reproduced({"moments", "--trajectories", "64", "--scheme", "resolvent", "--dt", "1e-3", "--times", "0.1:1:3", "--density",
                       "--v0", "0.3"});
    expect_reproduced({"trajectory", "--scheme", "resolvent", "--dt", "1e-2", "--index", "1", "--every", "0.5"});
    expect_reproduced({"analytic", "--friction", "2", "--relaxation", "0.5", "--times", "0.1,1", "--velocities=-1:1:3"});
    expect_reproduced({"sweep", "--noise", "2,4", "--tau", "0,0.5", "--excursions", "64", "--scheme", "resolvent", "--dt", "1e-2",
                       "--allow-capped"});
}

TEST(CliConfig, FlagsOverrideTheFileAndDefaultsFillTheRest) {
    const std::string path =
        write_file("excursions = 64\nscheme = \"resolvent\"\ndt = 2e-3\nseed = 3  # a comment\nengine = \"inclusion\"\n");
    const auto a = run_json({"diffusivity", "--config", path, "--seed", "4", "--format", "json", "--quiet"});
    const auto b = run_json({"diffusivity", "--excursions", "64", "--scheme", "resolvent", "--dt", "2e-3", "--seed", "4", "--format", "json",
                             "--quiet"});
    ASSERT_TRUE(a && b);
    EXPECT_EQ(strip(*a), strip(*b));
    EXPECT_EQ((*a)["params"]["seed"], 4) << "the command line wins over the file";
    std::remove(path.c_str());
}

TEST(CliConfig, PrintConfigStatesUnitsAndEverySetting) {
    const Result r = run({"diffusivity", "--print-config"});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* s : {"friction = 3.84", "[m s^-2]", "noise = 5", "dt = \"auto\"", "scheme = \"auto\"", "[s]", "max-steps = 200000000",
                          "engine = \"inclusion\"", "allow-capped = false", "excursions = 10000", "seed = 1"})
        EXPECT_NE(r.out.find(s), std::string::npos) << "lacks " << s << ":\n" << r.out;
}

struct BadConfig {
    std::string text;  ///< file contents ("" with missing = true: no file at all)
    bool missing;
    std::string names; ///< must appear in the error line
};

class CliBadConfig : public ::testing::TestWithParam<BadConfig> {};

TEST_P(CliBadConfig, ExitsTwoWithOneLineNamingTheKey) {
    const std::string path = GetParam().missing ? "/nonexistent/dir/run.toml" : write_file(GetParam().text);
    const Result r = run({"diffusivity", "--config", path, "--excursions", "64", "--scheme", "resolvent", "--dt", "1e-3"});
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(GetParam().names), std::string::npos) << r.err;
    if (!GetParam().missing) std::remove(path.c_str());
}

TEST(CliConfig, AFolderIsRefusedNotReadAsAnEmptyFile) { // found by tests/fuzz/ (fuzz_cli)
    const Result r = run({"diffusivity", "--config", ::testing::TempDir(), "--excursions", "64", "--scheme", "resolvent", "--dt", "1e-3"});
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("cannot read"), std::string::npos) << r.err;
}

INSTANTIATE_TEST_SUITE_P(All, CliBadConfig,
                         ::testing::Values(BadConfig{"frictoin = 3\n", false, "frictoin"},
                                           BadConfig{"grid = fast\n", false, "--grid"},
                                           BadConfig{"level = 2\n", false, "--level"},
                                           BadConfig{"engine = \"gpu\"\n", false, "--engine"},
                                           BadConfig{"[diffusivity]\ndt = 1e-3\n", false, "section"},
                                           BadConfig{"", true, "cannot read"}));

} // namespace
