// SPDX-License-Identifier: BSD-3-Clause
// End-to-end tests of the velocity-statistics subcommands (density, moments,
// correlation, trajectory, analytic, sweep) and the output contract every
// subcommand shares: --format table|json|csv and --output FILE written
// atomically (nothing left behind on failure). The JSON fields that users
// script against (README, "JSON output") are checked here.
#include <gtest/gtest.h>

#include <dirent.h>
#include <sys/stat.h>

#include "cli_support.hpp"

namespace {

using namespace clitest;
using nlohmann::json;

const Args kDry{"--friction", "1", "--noise", "1", "--relaxation", "inf", "--bias", "0"};

Args cmd(std::initializer_list<std::string> head, const Args& tail = {}) {
    Args a(head);
    a.insert(a.end(), tail.begin(), tail.end());
    return a;
}

// --- the fixed contracts ------------------------------------------------------------

TEST(CliAnalytic, ContractWithTimes) {
    const auto j = run_json(cmd({"analytic", "--v0", "1", "--times", "0.05,0.125,0.25,0.5,1,2.5", "--format", "json"}, kDry));
    ASSERT_TRUE(j);
    // Closed forms: estimates of kind "exact" at the paths every engine uses.
    for (const char* k : {"mobility", "diffusivity", "variance"}) {
        ASSERT_TRUE((*j)[k]["value"].is_number()) << k;
        EXPECT_EQ((*j)[k]["error"], 0.0) << k;
        EXPECT_EQ((*j)[k]["kind"], "exact") << k;
    }
    EXPECT_NEAR((*j)["diffusivity"]["value"].get<double>(), 1.25, 1e-10);
    EXPECT_NEAR((*j)["variance"]["value"].get<double>(), 0.5, 1e-10);
    EXPECT_NEAR((*j)["mobility"]["value"].get<double>(), 0.0, 1e-12);
    const double table_i[] = {0.950000, 0.875248, 0.757249, 0.567963, 0.336204, 0.090194};
    ASSERT_EQ((*j)["first_moment"].size(), 6u);
    ASSERT_EQ((*j)["autocorrelation"].size(), 6u);
    for (int k = 0; k < 6; ++k) EXPECT_NEAR((*j)["first_moment"][k]["value"].get<double>(), table_i[k], 1e-6);
    EXPECT_NEAR((*j)["autocorrelation"][3]["value"].get<double>(), 0.3179579, 1e-6);
    EXPECT_EQ((*j)["autocorrelation"][3]["lag"].get<double>(), 0.5);
}

TEST(CliAnalytic, StationaryOnlyWithoutTimesAndPhysicalUnits) {
    // Physical units: D = 5/4 noise^3/friction^4.
    const auto j = run_json({"analytic", "--friction", "2", "--noise", "3", "--relaxation", "inf", "--bias", "0",
                             "--format", "json"});
    ASSERT_TRUE(j);
    EXPECT_NEAR((*j)["diffusivity"]["value"].get<double>(), 1.25 * 27 / 16, 1e-9);
    EXPECT_EQ((*j)["diffusivity"]["kind"], "exact");
    EXPECT_FALSE(j->contains("first_moment"));
    // The paper's b: Fokker-Planck for the transient part; first moment starts at v0.
    const auto b = run_json({"analytic", "--v0", "0.2", "--times", "0,0.1", "--format", "json"});
    ASSERT_TRUE(b);
    EXPECT_NEAR((*b)["first_moment"][0]["value"].get<double>(), 0.2, 1e-12);
    EXPECT_EQ((*b)["first_moment"][0]["time"].get<double>(), 0.0);
    EXPECT_NE((*b)["engine_details"]["method"].get<std::string>().find("fokker-planck"), std::string::npos);
}

TEST(CliMoments, ContractFirstMomentRows) {
    const auto j = run_json(cmd({"moments", "--v0", "1", "--times", "0.5,1", "--trajectories", "500", "--tau", "0.001",
                                 "--scheme", "resolvent", "--dt", "1e-3", "--format", "json"},
                                kDry));
    ASSERT_TRUE(j);
    ASSERT_EQ((*j)["first_moment"].size(), 2u);
    for (const auto& row : (*j)["first_moment"]) {
        ASSERT_TRUE(row["time"].is_number());
        ASSERT_TRUE(row["value"].is_number());
        ASSERT_TRUE(row["error"].is_number());
        EXPECT_GT(row["error"].get<double>(), 0.0);
    }
    EXPECT_DOUBLE_EQ((*j)["first_moment"][0]["time"].get<double>(), 0.5);
    EXPECT_NEAR((*j)["first_moment"][0]["value"].get<double>(), 0.568, 0.1);
    EXPECT_EQ((*j)["params"]["x0"], "stationary");
}

TEST(CliMoments, DensityHistogramsPerTime) {
    const auto j = run_json(cmd({"moments", "--times", "0.5", "--trajectories", "300", "--tau", "0.01", "--scheme", "resolvent", "--dt", "1e-3",
                                 "--density", "--bins", "10", "--format", "json"},
                                kDry));
    ASSERT_TRUE(j);
    ASSERT_EQ((*j)["density"].size(), 1u);
    EXPECT_EQ((*j)["density"][0]["bins"].size(), 10u);
    EXPECT_TRUE((*j)["density"][0]["stuck_probability"]["value"].is_number());
}

// --- every subcommand: json runs, csv has a header and rows, table is default -------

struct Case {
    Args args;
    std::string first_csv_column;
};

const Case kCases[] = {
    {{"density", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "100", "--bins", "8"}, "kind"},
    {{"correlation", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "100", "--max-lag", "0.2", "--lags", "4"}, "lag"},
    {{"moments", "--scheme", "resolvent", "--dt", "1e-3", "--trajectories", "100", "--times", "0.1,0.2"}, "time"},
    {{"trajectory", "--scheme", "resolvent", "--dt", "1e-3"}, "path"},
    {{"trajectory", "--engine", "pdmp", "--paths", "2", "--time", "0.5"}, "path"},
    {{"analytic", "--times", "0.1"}, "mobility"},
    {{"sweep", "--scheme", "resolvent", "--dt", "1e-3", "--noise", "4,6", "--tau", "0.5", "--excursions", "50", "--allow-capped"}, "tau"},
    {{"diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "100"}, "engine"},
    {{"bruteforce", "--scheme", "resolvent", "--dt", "1e-3", "--time", "1", "--trajectories", "50"}, "engine"},
};

class CliEverySubcommand : public ::testing::TestWithParam<Case> {};

TEST_P(CliEverySubcommand, JsonCsvAndTable) {
    const Args& a = GetParam().args;
    Args j = a;
    j.insert(j.end(), {"--format", "json"});
    const auto parsed = run_json(j);
    ASSERT_TRUE(parsed);
    EXPECT_TRUE(parsed->contains("version")) << describe(j);

    Args c = a;
    c.insert(c.end(), {"--format", "csv"});
    const Result run_csv = run(c);
    ASSERT_EQ(run_csv.code, 0) << describe(c) << "\n" << run_csv.err;
    // The '#' lines of provenance first: the command line and every setting.
    EXPECT_EQ(run_csv.out.rfind("# stickslip ", 0), 0u) << run_csv.out;
    EXPECT_NE(run_csv.out.find("\n# command: stickslip "), std::string::npos) << run_csv.out;
    std::string csv;
    {
        std::istringstream all(run_csv.out);
        for (std::string line; std::getline(all, line);)
            if (line.rfind('#', 0) != 0) csv += line + "\n";
    }
    ASSERT_GE(count_lines(csv), 2) << describe(c);
    EXPECT_EQ(csv.substr(0, csv.find(',')), GetParam().first_csv_column) << describe(c);
    const std::string header = csv.substr(0, csv.find('\n'));
    const auto commas = std::count(header.begin(), header.end(), ',');
    std::istringstream lines(csv);
    std::string line;
    while (std::getline(lines, line)) EXPECT_EQ(std::count(line.begin(), line.end(), ','), commas) << line;
    EXPECT_EQ(csv.find("nan"), std::string::npos) << "no NaN printed as a result:\n" << csv;

    const Result table = run(a);
    EXPECT_EQ(table.code, 0) << describe(a) << "\n" << table.err;
    EXPECT_NE(table.out.find("stickslip"), std::string::npos) << table.out;
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    std::string name = std::to_string(info.index) + "_" + info.param.args[0];
    return name;
}

INSTANTIATE_TEST_SUITE_P(All, CliEverySubcommand, ::testing::ValuesIn(kCases), case_name);

TEST(CliObservables, SameJsonForAnyThreadCount) {
    for (const Args& a : {Args{"density", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "300", "--bins", "8", "--format", "json"},
                          Args{"correlation", "--engine", "pdmp", "--excursions", "300", "--max-lag", "0.2", "--lags",
                               "4", "--format", "json"},
                          Args{"moments", "--scheme", "resolvent", "--dt", "1e-3", "--trajectories", "300", "--times", "0.1", "--format",
                               "json"}}) {
        Args one = a, two = a;
        one.insert(one.end(), {"--threads", "1"});
        two.insert(two.end(), {"--threads", "2"});
        const auto j1 = run_json(one), j2 = run_json(two);
        ASSERT_TRUE(j1 && j2);
        EXPECT_EQ(without_work(*j1), without_work(*j2)) << describe(a);
    }
}

// --- --output: atomic, nothing half-written --------------------------------------------

std::string temp_dir() { return make_dir("out"); }

TEST(CliOutput, WritesTheFileAndNothingOnStdout) {
    const std::string dir = temp_dir(), file = dir + "/d.json";
    const Result r = run({"analytic", "--format", "json", "--output", file});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(json::accept(slurp(file))) << "valid JSON";
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{"d.json"}) << "no temporary file left";
    std::remove(file.c_str());
    ::rmdir(dir.c_str());
}

TEST(CliOutput, FailedRunLeavesNothingAndKeepsAnOldFile) {
    const std::string dir = temp_dir(), file = dir + "/old.csv";
    { std::ofstream(file) << "previous contents\n"; }
    // Bad input after the output was opened: exit 2, old file untouched, no temporary.
    const Result r = run({"density", "--bins", "0", "--output", file, "--format", "csv"});
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_EQ(slurp(file), "previous contents\n");
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{"old.csv"});
    // Capped run (exit 3): same.
    const Result capped = run({"diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "100", "--max-steps", "4000", "--output",
                               file});
    EXPECT_EQ(capped.code, 3) << capped.err;
    EXPECT_EQ(slurp(file), "previous contents\n");
    EXPECT_EQ(list_dir(dir), std::vector<std::string>{"old.csv"});
    std::remove(file.c_str());
    ::rmdir(dir.c_str());
}

TEST(CliOutput, UnwritablePathIsBadInputBeforeAnyWork) {
    const Result r = run({"diffusivity", "--excursions", "1e9", "--output", "/nonexistent-dir/x.json"});
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--output"), std::string::npos) << r.err;
}

// --- bad input: exit 2, one line naming the flag -------------------------------------------

struct Bad {
    Args args;
    std::string names;
};

class CliObservablesBadInput : public ::testing::TestWithParam<Bad> {};

TEST_P(CliObservablesBadInput, ExitsTwoWithOneLineNamingTheParameter) {
    const Result r = run(GetParam().args);
    EXPECT_EQ(r.code, 2) << describe(GetParam().args) << "\n" << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(GetParam().names), std::string::npos) << r.err;
}

const Bad kBad[] = {
    {{"density", "--bins", "0"}, "bins"},
    {{"density", "--range", "1,0"}, "range"},
    {{"density", "--range", "1"}, "range"},
    {{"density", "--engine", "pdmp", "--sample-dt", "-1"}, "sample-dt"},
    {{"correlation", "--lags", "0"}, "lags"},
    {{"correlation", "--max-lag", "-1"}, "max-lag"},
    {{"moments", "--times", "1,-1"}, "times"},
    {{"moments", "--times", "a"}, "times"},
    {{"moments", "--times", "1,"}, "times"},
    {{"moments", "--trajectories", "1"}, "trajectories"},
    {{"moments", "--v0", "inf"}, "v0"},
    {{"trajectory", "--paths", "2", "--time", "0"}, "time"},
    {{"trajectory", "--every", "-1"}, "every"},
    {{"analytic", "--relaxation", "inf", "--bias", "5"}, "bias"},
    {{"analytic", "--times", "-1"}, "times"},
    {{"analytic", "--friction", "0"}, "friction"},
    {{"sweep", "--noise", "0:10:3"}, "noise"},
    {{"sweep", "--noise", "1:10"}, "noise"},
    {{"sweep", "--tau", "-1"}, "tau"},
    {{"density", "--format", "xml"}, "format"},
};

INSTANTIATE_TEST_SUITE_P(All, CliObservablesBadInput, ::testing::ValuesIn(kBad),
                         [](const ::testing::TestParamInfo<Bad>& bad) {
                             std::string n = std::to_string(bad.index) + "_" + bad.param.args[0];
                             return n;
                         });

TEST(CliObservablesHelp, EverySubcommandDocumentsUnits) {
    for (const char* sub : {"density", "moments", "correlation", "trajectory", "analytic", "sweep"}) {
        const Result r = run({sub, "--help"});
        EXPECT_EQ(r.code, 0) << sub;
        for (const char* needle : {"--format", "--output", "[m/s]"})
            EXPECT_NE(r.out.find(needle), std::string::npos) << sub << " --help lacks " << needle;
    }
}

} // namespace
