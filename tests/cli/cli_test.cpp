// SPDX-License-Identifier: BSD-3-Clause
// End-to-end tests of the `stickslip` command: they run the built binary
// (STICKSLIP_CLI_PATH) in a child process with stdin from /dev/null and stdout
// and stderr captured in temporary files, and check the documented contract:
//   * exit codes: 0 ok, 2 bad input (nothing on stdout, exactly one line on
//     stderr naming the parameter), 3 untrustworthy run (capped excursions);
//   * the JSON schema of `diffusivity` and `bruteforce`;
//   * bitwise reproducibility: the same JSON (less "work") for any --threads.
// Every run uses small, fast settings; the whole suite takes a few seconds.
#include <gtest/gtest.h>

#include <regex>

#include "cli_support.hpp"
#include "stickslip/config.hpp" // STICKSLIP_VERSION_STRING

namespace {

using namespace clitest;
using nlohmann::json;

const Args kPdmp{"diffusivity", "--engine", "pdmp", "--excursions", "300", "--format", "json"};
const Args kInclusion{"diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "200", "--format", "json"};

void expect_number(const json& j, const std::string& key, const std::string& where) {
    ASSERT_TRUE(j.contains(key)) << where << " lacks \"" << key << "\":\n" << j.dump(2);
    EXPECT_TRUE(j[key].is_number()) << where << "." << key << " is not a number: " << j[key];
}

void expect_estimate(const json& j, const std::string& key, bool with_ci) {
    ASSERT_TRUE(j.contains(key)) << "no \"" << key << "\"";
    const json& e = j[key];
    expect_number(e, "value", key);
    expect_number(e, "error", key);
    EXPECT_GT(e["error"].get<double>(), 0.0) << key;
    EXPECT_EQ(e.at("kind"), "sampled") << key;
    if (!with_ci) return;
    ASSERT_TRUE(e.contains("ci")) << key;
    ASSERT_TRUE(e["ci"].is_array()) << key;
    ASSERT_EQ(e["ci"].size(), 2u) << key;
    expect_number(e, "level", key);
    EXPECT_DOUBLE_EQ(e["level"].get<double>(), 0.95) << key;
    const double v = e["value"], lo = e["ci"][0], hi = e["ci"][1];
    EXPECT_LT(lo, v) << key;
    EXPECT_LT(v, hi) << key;
    const double qse = 1.959963984540054 * e["error"].get<double>();
    if (key == "diffusivity") {
        // D (and brute force D_t): the relative-error interval v / (1 -+ q se / v),
        // positive and longer above (make_relative_interval).
        EXPECT_GT(lo, 0.0) << key;
        EXPECT_NEAR(lo, v / (1 + qse / v), 1e-12 * v) << key;
        EXPECT_NEAR(hi, v / (1 - qse / v), 1e-12 * hi) << key;
        EXPECT_GT(hi - v, v - lo) << key;
        return;
    }
    // A symmetric normal interval: half-width = 1.959964 * standard error.
    EXPECT_NEAR((hi - lo) / 2, qse, 1e-9 * std::fabs(hi - lo)) << key;
}

/// The documented schema of `diffusivity --format json`.
void expect_diffusivity_schema(const json& j, bool pdmp) {
    const std::string step = pdmp ? "grid" : "dt", other = pdmp ? "dt" : "grid";
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j.value("engine", ""), pdmp ? "pdmp" : "inclusion");
    EXPECT_EQ(j.value("estimator", ""), "renewal");
    ASSERT_TRUE(j.contains("stop_rule"));
    EXPECT_EQ(j["stop_rule"], pdmp ? "exact" : "bridge"); // dt 1e-3 <= tau/10 = 0.05: auto picks bridge

    ASSERT_TRUE(j.contains("params"));
    const json& p = j["params"];
    for (const char* k : {"friction", "noise", "tau", "relaxation", "bias", "seed", "excursions"})
        expect_number(p, k, "params");
    expect_number(p, step, "params");
    EXPECT_FALSE(p.contains(other)) << "params." << other << " only belongs to the other engine";
    EXPECT_DOUBLE_EQ(p["friction"].get<double>(), 3.84);
    EXPECT_DOUBLE_EQ(p["noise"].get<double>(), 5.0);
    EXPECT_DOUBLE_EQ(p["tau"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(p["relaxation"].get<double>(), 0.067);
    EXPECT_DOUBLE_EQ(p["bias"].get<double>(), 0.342);
    EXPECT_EQ(p["seed"].get<std::uint64_t>(), 1u);
    EXPECT_EQ(p["excursions"].get<std::uint64_t>(), pdmp ? 300u : 200u);

    ASSERT_TRUE(j.contains("nondimensional"));
    const json& nd = j["nondimensional"];
    for (const char* k : {"tau", "relaxation", "bias", "time_unit", "length_unit"}) expect_number(nd, k, "nondimensional");
    expect_number(nd, step, "nondimensional");
    const double time_unit = 5.0 / (3.84 * 3.84), length_unit = 25.0 / (3.84 * 3.84 * 3.84);
    EXPECT_NEAR(nd["time_unit"].get<double>(), time_unit, 1e-12 * time_unit);
    EXPECT_NEAR(nd["length_unit"].get<double>(), length_unit, 1e-12 * length_unit);
    EXPECT_NEAR(nd["tau"].get<double>(), 0.5 / time_unit, 1e-12);
    EXPECT_NEAR(nd["bias"].get<double>(), 0.342 / 3.84, 1e-12);
    if (!pdmp) {
        EXPECT_NEAR(nd["dt"].get<double>(), 1e-3 / time_unit, 1e-15);
    }
    if (nd.contains("diffusivity") && nd.contains("diffusivity_unit")) {
        const double d = j["diffusivity"]["value"];
        EXPECT_NEAR(nd["diffusivity"].get<double>() * nd["diffusivity_unit"].get<double>(), d, 1e-12 * std::fabs(d));
    }

    expect_estimate(j, "diffusivity", true);
    expect_estimate(j, "mobility", true);
    expect_estimate(j, "mean_duration", false);
    EXPECT_GT(j["diffusivity"]["value"].get<double>(), 0.0);
    EXPECT_GT(j["mean_duration"]["value"].get<double>(), 0.0);

    ASSERT_TRUE(j.contains("work"));
    const json& w = j["work"];
    expect_number(w, pdmp ? "events" : "steps", "work");
    expect_number(w, "seconds", "work");
    expect_number(w, "threads", "work");
    EXPECT_GT(w[pdmp ? "events" : "steps"].get<double>(), 0.0);
    EXPECT_GE(w["threads"].get<int>(), 1);
}

// --- help, version ------------------------------------------------------------

TEST(CliHelp, TopLevelHelpExitsZeroAndStatesUnits) {
    const Result r = run({"--help"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("diffusivity"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("bruteforce"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("SI units"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Nondimensional units"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Exit codes"), std::string::npos) << r.out;
}

TEST(CliHelp, SubcommandHelpListsFlagsWithUnits) {
    const Result d = run({"diffusivity", "--help"});
    EXPECT_EQ(d.code, 0) << d.err;
    for (const char* s : {"--friction", "m s^-2", "--noise", "m^2 s^-3", "--tau", "--relaxation", "--bias", "--engine",
                          "--scheme", "resolvent", "--dt", "--grid", "s^-1/2", "--excursions", "--estimator", "--seed", "--threads", "--format",
                          "--allow-capped"})
        EXPECT_NE(d.out.find(s), std::string::npos) << "diffusivity --help lacks " << s;
    const Result b = run({"bruteforce", "--help"});
    EXPECT_EQ(b.code, 0) << b.err;
    for (const char* s : {"--time", "--trajectories", "--x0", "--v0", "m s^-2"})
        EXPECT_NE(b.out.find(s), std::string::npos) << "bruteforce --help lacks " << s;
}

TEST(CliHelp, VersionMatchesLibrary) {
    const Result r = run({"--version"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find(STICKSLIP_VERSION_STRING), std::string::npos) << r.out;
}

// --version names the source revision as well, the same one the JSON reports
// carry, or "unknown" for a build from outside a git checkout (whose reports
// have no "revision"): a result and the binary that made it can be matched.
TEST(CliHelp, VersionNamesTheRevision) {
    const Result r = run({"--version"});
    ASSERT_EQ(r.code, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_match(r.out, m, std::regex(R"(stickslip (\S+) \(git ([0-9a-f]{12}(-dirty)?|unknown)\)\n)")))
        << r.out;
    EXPECT_EQ(m[1].str(), STICKSLIP_VERSION_STRING);
    const auto j = run_json(kPdmp);
    ASSERT_TRUE(j);
    EXPECT_EQ(m[2].str(), j->contains("revision") ? (*j)["revision"].get<std::string>() : "unknown");
}

// --- diffusivity: output ------------------------------------------------------

TEST(CliDiffusivity, PdmpJsonSchema) {
    const auto j = run_json(kPdmp);
    ASSERT_TRUE(j);
    expect_diffusivity_schema(*j, true);
}

TEST(CliDiffusivity, InclusionJsonSchema) {
    const auto j = run_json(kInclusion);
    ASSERT_TRUE(j);
    expect_diffusivity_schema(*j, false);
    EXPECT_EQ((*j)["version"], STICKSLIP_VERSION_STRING);
}

TEST(CliDiffusivity, TableIsTheDefaultFormat) {
    const Args args{"diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "200"};
    const Result r = run(args);
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* s : {"diffusivity D", "mobility M0", "E[t1]", "95% interval", "m^2/s", "nondim"})
        EXPECT_NE(r.out.find(s), std::string::npos) << "table lacks " << s << ":\n" << r.out;
    EXPECT_FALSE(json::accept(r.out)) << "the table is not JSON";
}

TEST(CliDiffusivity, InfiniteRelaxationIsTheStringInf) {
    for (const Args& base : {kPdmp, kInclusion}) {
        const auto j = run_json(with(base, {"--relaxation", "inf"}));
        ASSERT_TRUE(j);
        EXPECT_EQ((*j)["params"]["relaxation"], "inf");
        EXPECT_EQ((*j)["nondimensional"]["relaxation"], "inf");
        EXPECT_TRUE((*j)["diffusivity"]["value"].is_number());
    }
}

TEST(CliDiffusivity, WhiteNoiseRuns) {
    const auto j = run_json(with(kInclusion, {"--tau", "0"}));
    ASSERT_TRUE(j);
    EXPECT_EQ((*j)["params"]["tau"].get<double>(), 0.0);
    EXPECT_EQ((*j)["stop_rule"], "velocity-levels");
    EXPECT_GT((*j)["diffusivity"]["value"].get<double>(), 0.0);
}

TEST(CliDiffusivity, PaperEstimatorIsNamedAndChangesOnlyD) {
    // The paper's estimator has no control variate: the renewal one without it too.
    const auto renewal = run_json(with(kInclusion, {"--control-variate", "off"}));
    const auto paper = run_json(with(kInclusion, {"--estimator", "paper"}));
    ASSERT_TRUE(renewal && paper);
    EXPECT_EQ((*paper)["estimator"], "paper");
    EXPECT_EQ((*renewal)["estimator"], "renewal");
    // Same seed, same excursions: only the D formula differs (M0 != 0 here).
    EXPECT_EQ((*paper)["mobility"], (*renewal)["mobility"]);
    EXPECT_EQ((*paper)["mean_duration"], (*renewal)["mean_duration"]);
    EXPECT_NE((*paper)["diffusivity"]["value"], (*renewal)["diffusivity"]["value"]);
}

TEST(CliDiffusivity, LevelSetsTheIntervals) {
    const auto a = run_json(kPdmp);
    const auto b = run_json(with(kPdmp, {"--level", "0.9"}));
    ASSERT_TRUE(a && b);
    EXPECT_DOUBLE_EQ((*b)["diffusivity"]["level"].get<double>(), 0.9);
    EXPECT_EQ((*a)["diffusivity"]["value"], (*b)["diffusivity"]["value"]);
    const auto width = [](const json& j) { return j["diffusivity"]["ci"][1].get<double>() - j["diffusivity"]["ci"][0].get<double>(); };
    EXPECT_LT(width(*b), width(*a));
}

// --- reproducibility ----------------------------------------------------------

class CliThreads : public ::testing::TestWithParam<Args> {};

TEST_P(CliThreads, SameJsonForAnyThreadCount) {
    const Args base = GetParam();
    const auto one = run_json(with(base, {"--threads", "1"}));
    ASSERT_TRUE(one);
    EXPECT_EQ((*one)["work"]["threads"].get<int>(), 1);
    for (const char* n : {"2", "3"}) {
        const auto many = run_json(with(base, {"--threads", n}));
        ASSERT_TRUE(many);
        EXPECT_EQ((*many)["work"]["threads"].get<int>(), std::atoi(n));
        // Bitwise: the serialised text, not just the parsed values.
        EXPECT_EQ(without_work(*one).dump(), without_work(*many).dump()) << describe(base) << " --threads " << n;
    }
}

TEST_P(CliThreads, DifferentSeedsDiffer) {
    const Args base = GetParam();
    const auto a = run_json(with(base, {"--seed", "1"}));
    const auto b = run_json(with(base, {"--seed", "2"}));
    ASSERT_TRUE(a && b);
    EXPECT_EQ((*b)["params"]["seed"].get<std::uint64_t>(), 2u);
    EXPECT_NE((*a)["diffusivity"]["value"], (*b)["diffusivity"]["value"]);
    EXPECT_NE((*a)["mobility"]["value"], (*b)["mobility"]["value"]);
}

TEST_P(CliThreads, SameSeedSameResultAcrossRuns) {
    const auto a = run_json(with(GetParam(), {"--seed", "12345678901234"}));
    const auto b = run_json(with(GetParam(), {"--seed", "12345678901234"}));
    ASSERT_TRUE(a && b);
    EXPECT_EQ(without_work(*a).dump(), without_work(*b).dump());
}

std::string engine_case_name(const ::testing::TestParamInfo<Args>& info) {
    static const char* const names[] = {"DiffusivityPdmp", "DiffusivityInclusion", "DiffusivityWhite",
                                        "BruteforcePdmp", "BruteforceInclusion"};
    return names[info.index];
}

INSTANTIATE_TEST_SUITE_P(
    Engines, CliThreads,
    ::testing::Values(kPdmp, kInclusion, with(kInclusion, {"--tau", "0"}),
                      Args{"bruteforce", "--engine", "pdmp", "--time", "1", "--trajectories", "200", "--format", "json"},
                      Args{"bruteforce", "--scheme", "resolvent", "--dt", "1e-3", "--time", "1", "--trajectories", "200", "--format", "json"}),
    engine_case_name);

// --- bruteforce -----------------------------------------------------------------

TEST(CliBruteforce, JsonSchema) {
    for (const bool pdmp : {false, true}) {
        const Args args = pdmp ? Args{"bruteforce", "--engine", "pdmp", "--time", "2", "--trajectories", "200",
                                      "--format", "json"}
                               : Args{"bruteforce", "--scheme", "resolvent", "--dt", "1e-3", "--time", "2", "--trajectories", "200",
                                      "--format", "json"};
        const auto j = run_json(args);
        ASSERT_TRUE(j);
        EXPECT_EQ((*j)["engine"], pdmp ? "pdmp" : "inclusion");
        EXPECT_EQ((*j)["estimator"], "bruteforce");
        ASSERT_TRUE(j->contains("params"));
        const json& p = (*j)["params"];
        for (const char* k : {"friction", "noise", "tau", "relaxation", "bias", "seed", "time", "trajectories"})
            expect_number(p, k, "params");
        expect_number(p, pdmp ? "grid" : "dt", "params");
        EXPECT_DOUBLE_EQ(p["time"].get<double>(), 2.0);
        EXPECT_EQ(p["trajectories"].get<std::uint64_t>(), 200u);
        ASSERT_TRUE(j->contains("nondimensional"));
        for (const char* k : {"tau", "relaxation", "bias", "time_unit", "length_unit"})
            expect_number((*j)["nondimensional"], k, "nondimensional");
        expect_estimate(*j, "diffusivity", true);
        expect_estimate(*j, "mobility", true);
        ASSERT_TRUE(j->contains("work"));
        expect_number((*j)["work"], pdmp ? "events" : "steps", "work");
        expect_number((*j)["work"], "seconds", "work");
        expect_number((*j)["work"], "threads", "work");
    }
}

// --- bad input: exit 2, nothing on stdout, one line on stderr naming it -----------

struct BadInput {
    Args args;
    std::string names; ///< must appear in the error line
};

void PrintTo(const BadInput& b, std::ostream* os) { *os << describe(b.args); }

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, ExitsTwoWithOneLineNamingTheParameter) {
    const Args args = fast(GetParam().args);
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << describe(args) << "\nstderr: " << r.err;
    EXPECT_EQ(r.out, "") << describe(args);
    EXPECT_EQ(count_lines(r.err), 1) << describe(args) << "\nstderr: " << r.err;
    EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << describe(args);
    EXPECT_NE(r.err.find(GetParam().names), std::string::npos)
        << describe(args) << ": the error should name " << GetParam().names << "\nstderr: " << r.err;
}

const BadInput kBadInputs[] = {
    {{"diffusivity", "--friction", "0"}, "friction"},
    {{"diffusivity", "--friction", "-1"}, "friction"},
    {{"diffusivity", "--friction", "inf"}, "friction"},
    {{"diffusivity", "--noise", "0"}, "noise"},
    {{"diffusivity", "--tau", "-1"}, "tau"},
    {{"diffusivity", "--relaxation", "0"}, "relaxation"},
    {{"diffusivity", "--relaxation", "nan"}, "relaxation"},
    {{"diffusivity", "--bias", "nan"}, "bias"},
    // Static friction below the friction, NaN, negative, with a drift law (issue 46).
    {{"diffusivity", "--static-friction", "3"}, "--static-friction: static-friction must be a finite number >= friction"},
    {{"diffusivity", "--static-friction", "nan"}, "--static-friction: static-friction must be a number, got NaN"},
    {{"diffusivity", "--static-friction", "-1"}, "--static-friction"},
    {{"diffusivity", "--static-friction", "inf"}, "--static-friction"},
    {{"density", "--drift", "0.3 - v", "--static-friction", "1"}, "--static-friction"},
    {{"diffusivity", "--scheme", "resolvent", "--dt", "0"}, "dt"},
    {{"diffusivity", "--scheme", "resolvent", "--dt", "-1e-4"}, "dt"},
    {{"diffusivity", "--scheme", "resolvent", "--dt", "1e-3x"}, "dt"},
    {{"diffusivity", "--engine", "pdmp", "--grid", "0"}, "grid"},
    {{"diffusivity", "--engine", "pdmp", "--tau", "0"}, "tau"},
    {{"diffusivity", "--engine", "pdmp", "--grid", "2"}, "grid"}, // tau*grid*L < 2 impossible
    {{"diffusivity", "--engine", "pdmp", "--lattice-bound", "-1"}, "lattice-bound"},
    // Shorter than one grid step: it blamed --grid ("grid = 0.125 gives 1 lattice points").
    {{"diffusivity", "--engine", "pdmp", "--lattice-bound", "0.1"}, "--lattice-bound: lattice-bound L = 0.1"},
    // The event scheme far beyond its measured reach: at 200 tau (the Fig. 2 case)
    // D was 100 times too large and M0 of the wrong sign, with exit 0.
    {{"diffusivity", "--dt", "100"}, "--dt: dt = 100 s is 200 correlation times of the noise"},
    {{"density", "--scheme", "event", "--dt", "5"}, "10 correlation times"},
    // White noise at 15 relaxation times: D 76% low, exit 0.
    {{"diffusivity", "--tau", "0", "--scheme", "event", "--dt", "1"}, "--dt: dt = 1 s is 14.9 relaxation times"},
    {{"diffusivity", "--friction", "1", "--noise", "1", "--tau", "0", "--relaxation", "inf", "--scheme", "event",
      "--dt", "3"},
     "3 friction times"},
    {{"diffusivity", "--excursions", "1"}, "excursions"},
    {{"diffusivity", "--excursions", "abc"}, "excursions"},
    {{"diffusivity", "--excursions", "2.5"}, "excursions"},
    {{"diffusivity", "--level", "1.5"}, "level"},
    {{"diffusivity", "--level", "0"}, "level"},
    {{"diffusivity", "--format", "xml"}, "format"},
    {{"diffusivity", "--engine", "foo"}, "engine"},
    {{"diffusivity", "--estimator", "foo"}, "estimator"},
    {{"diffusivity", "--stop-rule", "foo"}, "stop-rule"},
    {{"diffusivity", "--seed", "-1"}, "seed"},
    {{"diffusivity", "--threads", "-1"}, "threads"},
    {{"diffusivity", "--max-steps", "0"}, "max-steps"},
    {{"diffusivity", "--no-such-flag"}, "--no-such-flag"},
    {{"diffusivity", "--friction"}, "friction"}, // missing value
    {{"diffusivity", "--relaxation", "inf", "--bias", "3.84"}, "bias"},
    {{"diffusivity", "--relaxation", "inf", "--bias", "-5"}, "bias"},
    {{"diffusivity", "--engine", "pdmp", "--relaxation", "inf", "--bias", "4"}, "bias"},
    {{"bruteforce", "--time", "0"}, "time"},
    {{"bruteforce", "--time", "-1"}, "time"},
    {{"bruteforce", "--trajectories", "1"}, "trajectories"},
    {{"bruteforce", "--trajectories", "abc"}, "trajectories"},
    {{"bruteforce", "--x0", "nan"}, "x0"},
    {{"bruteforce", "--engine", "pdmp", "--tau", "0"}, "tau"},
    {{"bruteforce", "--friction", "0"}, "friction"},
    {{}, "subcommand"},
    {{"nonsense"}, "unknown subcommand 'nonsense'; one of: diffusivity,"},
    // Found trying extreme input as a new user would (each used to end
    // otherwise: exit 1 with a Boost overflow, a message naming --noise with
    // "-nan", hexadecimal accepted, "--every" blamed, D = nan with exit 0 ...).
    {{"diffusivity", "--level", "0.9999999999999999"}, "--level: level must be strictly between 0 and 1"},
    {{"diffusivity", "--friction", "1e308"}, "--friction: friction = 1e+308 m s^-2"},
    {{"diffusivity", "--noise", "1e-300"}, "--noise: friction = 3.84"},
    {{"diffusivity", "--friction", "0x10"}, "--friction: friction must be a number, got '0x10'"},
    {{"diffusivity", "--excursions", "0x10"}, "--excursions"},
    {{"diffusivity", "--excursions", "1e300"}, "--excursions"},
    {{"diffusivity", "--seed", "18446744073709551616"}, "--seed"},
    {{"trajectory", "--max-points", "0"}, "--max-points: max-points must be at least 2"},
    {{"diffusivity", "--excursion", "200"}, "--excursion; did you mean --excursions?"},
    {{"sweep", "--noises=1,2"}, "did you mean --noise?"},
};

std::string bad_input_name(const ::testing::TestParamInfo<BadInput>& info) {
    std::string name = std::to_string(info.index);
    for (const auto& a : info.param.args)
        for (char c : a) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    if (info.param.args.empty()) name += "no_arguments";
    return name;
}

INSTANTIATE_TEST_SUITE_P(All, CliBadInput, ::testing::ValuesIn(kBadInputs), bad_input_name);

// --- runaway guard: exit 3 ------------------------------------------------------

TEST(CliCapped, GuardHitIsAnErrorByDefault) {
    // 4000 steps of 1e-3 s lie above the lower bound of the mean excursion
    // (3.4 s, so the run is not refused up front) and below E[t1] = 8.1 s:
    // 154 of the 200 excursions hit the guard (seed 1).
    const Args args{"diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "200", "--max-steps", "4000"};
    const Result r = run(args);
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("runaway guard"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--max-steps"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--allow-capped"), std::string::npos) << r.err;
}

TEST(CliCapped, AllowCappedStillFailsWhenFewerThanTwoComplete) {
    // White noise: no lower bound of the excursion's length is known up
    // front, so the run starts, and 10 steps of 1e-3 s end none of them.
    const Args args{"diffusivity", "--friction", "1", "--noise", "1", "--tau", "0", "--relaxation", "inf",
                    "--bias", "0", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "200", "--max-steps", "10", "--allow-capped"};
    const Result r = run(args);
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("fewer than 2"), std::string::npos) << r.err;
}

TEST(CliCapped, RunsWhoseExcursionsCannotEndAreRefusedUpFront) {
    // The noise must cross the static band before an excursion ends: at least
    // 3.4 s on average in the Fig. 2 case, far beyond 10 steps or events.
    for (const Args& args : {Args{"diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "200", "--max-steps", "10",
                                  "--allow-capped"},
                             Args{"diffusivity", "--engine", "pdmp", "--excursions", "200", "--max-steps", "10",
                                  "--allow-capped", "--format", "json"},
                             Args{"diffusivity", "--friction", "1", "--noise", "1", "--tau", "1e12", "--relaxation",
                                  "inf", "--bias", "0"},
                             Args{"density", "--friction", "16"}, Args{"correlation", "--friction", "16"}}) {
        const Result r = run(args);
        EXPECT_EQ(r.code, 2) << describe(args) << "\n" << r.err;
        EXPECT_EQ(r.out, "") << describe(args);
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("--max-steps"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("standard deviations"), std::string::npos) << r.err;
    }
}

TEST(CliUntrustworthy, NearWhiteNoiseAtATinyStepIsRefusedNotNaN) {
    // tau' = 1e-8 at dt = 1e-10: the discrete chain's excursions all ended
    // within their first step, so D was 0/0 (it printed "nan"); the chain
    // itself, resolved, has excursions of hours (the near-white law of
    // E[t1], docs/validation.md, "Step checks"). Either way no number may
    // come out: the run is refused before any work, naming --tau, or (were
    // the prediction to let it through) ends with exit 3 saying why.
    const auto refused_or_untrustworthy = [](const Result& r, const std::string& what) {
        EXPECT_TRUE(r.code == 2 || r.code == 3) << what << "\n" << r.err;
        EXPECT_EQ(r.out, "") << what;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        if (r.code == 2) {
            EXPECT_NE(r.err.find("--tau: this run would take"), std::string::npos) << r.err;
        }
        if (r.code == 3) {
            EXPECT_NE(r.err.find("first step"), std::string::npos) << r.err;
        }
        EXPECT_EQ(r.err.find("nan"), std::string::npos) << r.err;
    };
    for (const char* cmd : {"diffusivity", "density", "correlation"}) {
        Args args{cmd, "--friction", "1", "--noise", "1", "--tau", "1e-8", "--relaxation", "inf",
                  "--bias", "0", "--scheme", "resolvent", "--dt", "1e-10", "--excursions", "200"};
        if (std::string(cmd) == "correlation") args.insert(args.end(), {"--max-lag", "1e-8"});
        refused_or_untrustworthy(run(args), describe(args));
    }
    const Result sweep = run({"sweep", "--friction", "1", "--noise", "1", "--tau", "1e-8", "--relaxation", "inf",
                              "--bias", "0", "--scheme", "resolvent", "--dt", "1e-10", "--excursions", "200"});
    refused_or_untrustworthy(sweep, "sweep");
    EXPECT_NE(sweep.err.find("at noise 1, tau 1e-08"), std::string::npos) << sweep.err;
}

TEST(CliNumbers, SubnormalsAndFullSeedsAreNumbersLikeAnyOther) {
    // 5e-324 is the smallest double (strtod flags it ERANGE, and it was
    // refused as "not a number"); seeds are read exactly up to 2^64 - 1.
    const Result tiny = run({"diffusivity", "--bias", "5e-324", "--scheme", "resolvent", "--dt", "1e-2", "--excursions", "64", "--format",
                             "json", "--quiet"});
    EXPECT_EQ(tiny.code, 0) << tiny.err;
    EXPECT_EQ(nlohmann::json::parse(tiny.out)["params"]["bias"].get<double>(), 5e-324);
    const Result seed = run({"diffusivity", "--seed", "18446744073709551615", "--scheme", "resolvent", "--dt", "1e-2", "--excursions", "64",
                             "--format", "json", "--quiet"});
    ASSERT_EQ(seed.code, 0) << seed.err;
    EXPECT_EQ(nlohmann::json::parse(seed.out)["params"]["seed"].get<std::uint64_t>(), 18446744073709551615ull);
    const Result near = run({"diffusivity", "--seed", "9007199254740993", "--scheme", "resolvent", "--dt", "1e-2", "--excursions", "64",
                             "--format", "json", "--quiet"});
    ASSERT_EQ(near.code, 0) << near.err;
    EXPECT_EQ(nlohmann::json::parse(near.out)["params"]["seed"].get<std::uint64_t>(), 9007199254740993ull); // not rounded
}

TEST(CliHelp, HelpWinsOverAMisspeltSubcommand) { // found by tests/fuzz/ (fuzz_cli)
    const Result r = run({"densitypaper", "--help"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("Subcommands:"), std::string::npos) << r.out;
}

TEST(CliWarnings, TwoTrajectoriesSayTheirIntervalIsNotAnInterval) {
    const Result r = run({"bruteforce", "--trajectories", "2", "--time", "1", "--scheme", "resolvent", "--dt", "1e-2"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("only 2 trajectories"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("0 by construction"), std::string::npos) << r.out;
}

// --- --check-dt ------------------------------------------------------------------

TEST(CliCheckDt, DetectsTheResolventBiasOfWhiteNoiseAtACoarseStep) {
    // White noise, dt' = 0.1: D is biased by about -12% at dt and -17% at
    // 2 dt (docs/validation.md, "Step checks"), a difference of about 6% of D;
    // with 2e5 excursions per run its standard error is about 1.5% (seed 1:
    // -6.8% +- 1.7%, z = -3.9).
    const Result r = run({"diffusivity", "--friction", "1", "--noise", "1", "--tau", "0", "--relaxation", "inf",
                          "--bias", "0", "--scheme", "resolvent", "--dt", "0.1", "--excursions", "200000",
                          "--check-dt", "--format", "json",
                          "--quiet"});
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    const json& c = j.at("discretisation");
    EXPECT_EQ(c.at("dt").get<double>(), 0.1);
    EXPECT_EQ(c.at("check_dt").get<double>(), 0.2);
    EXPECT_EQ(c.at("excursions").get<std::uint64_t>(), 200000u);
    const double diff = c.at("diffusivity").at("value").get<double>();
    const double se = c.at("diffusivity").at("error").get<double>();
    EXPECT_LT(diff / se, -3.0) << "D(2 dt) - D(dt) = " << diff << " +- " << se << ", z = " << diff / se;
    bool warned = false;
    for (const auto& w : j.at("warnings")) warned = warned || w.get<std::string>().find("bias is visible") != std::string::npos;
    EXPECT_TRUE(warned) << j.at("warnings").dump();
}

TEST(CliCheckDt, EventSchemeShowsNoBiasAndTheTableSaysSo) {
    const Args args{"diffusivity", "--scheme", "event", "--dt", "0.03", "--excursions", "20000", "--check-dt"};
    const Result r = run(args);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("check at 2 dt = 0.06 s (20000 excursions): D(2 dt) - D(dt) = "), std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("bias is visible"), std::string::npos) << r.out; // seed 1: z = 1.1 (D), -1.0 (M0)
    const Result csv = run(with(args, {"--format", "csv"}));
    ASSERT_EQ(csv.code, 0) << csv.err;
    // The check's block, each column named by its JSON path (discretisation.check_dt, ...).
    EXPECT_NE(csv.out.find(",discretisation_dt,discretisation_check_dt,discretisation_excursions,"
                           "discretisation_steps,discretisation_diffusivity,discretisation_diffusivity_error,"),
              std::string::npos)
        << csv.out;
}

TEST(CliStepNotes, AStepNearTheRelaxationTimeGetsItsOwnNote) {
    // Fig. 2 case, dt = 0.06 s = 0.9 relaxation times: measured D -5%, where
    // the friction-time law alone says +6% (docs/validation.md, "Step checks").
    const Result r = run({"diffusivity", "--scheme", "resolvent", "--dt", "0.06", "--excursions", "2000"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("0.9 relaxation times: the explicit drift step's own error"), std::string::npos) << r.out;
    const Result fine = run({"diffusivity", "--scheme", "resolvent", "--dt", "0.03", "--excursions", "2000"});
    ASSERT_EQ(fine.code, 0) << fine.err;
    EXPECT_EQ(fine.out.find("relaxation times"), std::string::npos) << fine.out;
}

TEST(CliStepNotes, AnEventStepBeyondItsValidatedReachGetsANote) {
    // docs/validation.md, "The event scheme at coarse steps": coloured noise is
    // flat to dt = tau, white noise to relaxation/4 and half the friction time.
    const Result coloured = run({"diffusivity", "--dt", "2", "--excursions", "2000"}); // 4 tau
    ASSERT_EQ(coloured.code, 0) << coloured.err;
    EXPECT_NE(coloured.out.find("dt = 2 s is 4 correlation times of the noise"), std::string::npos) << coloured.out;
    const Result at_tau = run({"diffusivity", "--dt", "0.5", "--excursions", "2000"});
    ASSERT_EQ(at_tau.code, 0) << at_tau.err;
    EXPECT_EQ(at_tau.out.find("correlation times"), std::string::npos) << at_tau.out;
    const Args white{"diffusivity", "--friction", "1", "--noise", "1", "--tau", "0", "--relaxation", "inf",
                     "--scheme", "event", "--excursions", "2000"};
    const Result coarse = run(with(white, {"--dt", "1.5"}));
    ASSERT_EQ(coarse.code, 0) << coarse.err;
    EXPECT_NE(coarse.out.find("dt = 1.5 s is 1.5 friction times"), std::string::npos) << coarse.out;
    const Result fine = run(with(white, {"--dt", "0.5"}));
    ASSERT_EQ(fine.code, 0) << fine.err;
    EXPECT_EQ(fine.out.find("friction times"), std::string::npos) << fine.out;
    // Below the finest validated step (dt/tau = 1e-5): a note, not a refusal.
    const Result finest = run({"diffusivity", "--scheme", "event", "--dt", "2e-6", "--excursions", "20"});
    ASSERT_EQ(finest.code, 0) << finest.err;
    EXPECT_NE(finest.out.find("4e-06 correlation times of the noise: finer than the event scheme's validated steps"),
              std::string::npos)
        << finest.out;
    const Result drag = run({"diffusivity", "--tau", "0", "--scheme", "event", "--dt", "0.05", "--excursions", "2000"});
    ASSERT_EQ(drag.code, 0) << drag.err;
    EXPECT_NE(drag.out.find("0.746 relaxation times"), std::string::npos) << drag.out;
}

TEST(CliAutoStep, TheJsonSaysTheStepWasChosenAndWhichOne) {
    // Fig. 2 case: the event scheme's automatic step is relaxation/8 = 0.008375 s.
    const Result r = run({"diffusivity", "--scheme", "event", "--dt", "auto", "--excursions", "200", "--check-dt",
                          "--format", "json", "--quiet"});
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j.at("params").at("dt").get<double>(), 0.008375);
    EXPECT_TRUE(j.at("params").at("dt_auto").get<bool>());
    EXPECT_EQ(j.at("discretisation").at("check_dt").get<double>(), 2 * 0.008375); // twice the chosen step
    const Result table = run({"diffusivity", "--scheme", "resolvent", "--dt", "auto", "--excursions", "200"});
    ASSERT_EQ(table.code, 0) << table.err;
    EXPECT_NE(table.out.find("dt 0.00067 s (auto), resolvent scheme"), std::string::npos) << table.out;
    // The defaults: the event scheme at its automatic step.
    const Result defaults = run({"diffusivity", "--excursions", "200", "--format", "json", "--quiet"});
    ASSERT_EQ(defaults.code, 0) << defaults.err;
    const json d = json::parse(defaults.out);
    EXPECT_EQ(d.at("params").at("dt").get<double>(), 0.008375);
    EXPECT_TRUE(d.at("params").at("dt_auto").get<bool>());
    EXPECT_EQ(d.at("engine_details").at("scheme"), "event");
    const Result given = run({"diffusivity", "--scheme", "resolvent", "--dt", "0.001", "--excursions", "200", "--format", "json"});
    ASSERT_EQ(given.code, 0) << given.err;
    EXPECT_FALSE(json::parse(given.out).at("params").contains("dt_auto"));
}

TEST(CliAutoStep, PrintConfigKeepsAutoAndABadValueNamesBothForms) {
    Scratch dir("auto_step");
    const Result printed = run({"diffusivity", "--scheme", "resolvent", "--dt", "auto", "--print-config"});
    ASSERT_EQ(printed.code, 0) << printed.err;
    EXPECT_NE(printed.out.find("dt = \"auto\""), std::string::npos) << printed.out;
    const std::string config = dir.path + "/run.toml";
    std::ofstream(config) << printed.out;
    const Result reread = run({"diffusivity", "--config", config, "--excursions", "200", "--format", "json"});
    ASSERT_EQ(reread.code, 0) << reread.err;
    EXPECT_TRUE(json::parse(reread.out).at("params").at("dt_auto").get<bool>());
    const Result bad = run({"diffusivity", "--scheme", "resolvent", "--dt", "automatic"});
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("dt must be a number or auto, got 'automatic'"), std::string::npos) << bad.err;
}

TEST(CliAutoStep, ASweepChoosesAStepPerPoint) {
    const Result r = run({"sweep", "--scheme", "event", "--dt", "auto", "--noise", "0.25,1", "--tau", "0.5",
                          "--friction", "1", "--relaxation", "inf", "--bias", "0", "--excursions", "100",
                          "--format", "json", "--quiet"});
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_FALSE(j.at("params").contains("dt"));
    const json& pts = j.at("points");
    ASSERT_EQ(pts.size(), 2u);
    // min(tau/16 = 0.03125 s, T_f/16 = noise/16 s): 0.015625 and 0.03125 s.
    EXPECT_EQ(pts[0].at("dt").get<double>(), 0.25 / 16);
    EXPECT_EQ(pts[1].at("dt").get<double>(), 0.5 / 16);
    const Result table = run({"sweep", "--scheme", "event", "--dt", "auto", "--noise", "0.25,1", "--tau", "0.5",
                              "--friction", "1", "--relaxation", "inf", "--bias", "0", "--excursions", "100"});
    ASSERT_EQ(table.code, 0) << table.err;
    EXPECT_NE(table.out.find("dt auto, per point"), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("dt 0.015625 s"), std::string::npos) << table.out;
}

TEST(CliCheckDt, RefusedWhereItCannotRun) {
    const Result pdmp = run({"diffusivity", "--engine", "pdmp", "--check-dt"});
    EXPECT_EQ(pdmp.code, 2) << pdmp.err;
    EXPECT_NE(pdmp.err.find("--check-dt"), std::string::npos) << pdmp.err;
    // 2 dt = 0.08 s would be longer than the relaxation time 0.067 s.
    const Result coarse = run({"diffusivity", "--scheme", "resolvent", "--dt", "0.04", "--check-dt"});
    EXPECT_EQ(coarse.code, 2) << coarse.err;
    EXPECT_NE(coarse.err.find("--check-dt: twice the step cannot be run: --dt"), std::string::npos) << coarse.err;
}

TEST(CliUntrustworthy, OverflowingInputsAreRefusedUpFront) {
    for (const Args& args : {Args{"moments", "--v0", "1e200"}, Args{"density", "--range=-1e308,1e308"},
                             Args{"density", "--range=1,1.0000000000000002"}}) {
        const Result r = run(args);
        EXPECT_EQ(r.code, 2) << describe(args) << "\n" << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_EQ(r.err.find("nan"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("double precision"), std::string::npos) << r.err;
    }
}

TEST(CliCapped, SomeCappedIsErrorUnlessAllowed) {
    // With 3000 events per excursion a good part, but not all, of the PDMP
    // excursions of the Fig. 2 case hit the guard (deterministic for seed 1).
    const Args base{"diffusivity", "--engine", "pdmp", "--excursions", "300", "--max-steps", "3000", "--format", "json"};
    const Result refused = run(base);
    EXPECT_EQ(refused.code, 3) << refused.err;
    EXPECT_EQ(refused.out, "");
    EXPECT_EQ(count_lines(refused.err), 1) << refused.err;
    EXPECT_NE(refused.err.find("runaway guard"), std::string::npos) << refused.err;

    const auto j = run_json(with(base, {"--allow-capped"}));
    ASSERT_TRUE(j);
    const auto capped = (*j)["capped"].get<std::uint64_t>(), completed = (*j)["completed"].get<std::uint64_t>();
    EXPECT_GT(capped, 0u);
    EXPECT_GE(completed, 2u);
    EXPECT_EQ(capped + completed, 300u);
    bool warned = false;
    for (const auto& w : (*j)["warnings"]) warned = warned || w.get<std::string>().find("runaway guard") != std::string::npos;
    EXPECT_TRUE(warned) << (*j)["warnings"].dump();
}

} // namespace
