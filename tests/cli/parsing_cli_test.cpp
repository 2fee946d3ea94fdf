// SPDX-License-Identifier: BSD-3-Clause
// How the command reads what it is given: boolean flags with a value, numbers
// (decimal only, on every flag), config files that are not plain text, and
// the messages for values that used to be blamed on the wrong flag or
// described wrongly. Each case here was once accepted, or answered with a
// misleading or garbled line.
#include "cli_support.hpp"

#include <fstream>
#include <sys/stat.h>

namespace {

using namespace clitest;

/// The run of CliCapped (cli_test.cpp) at a third of its size: most
/// excursions hit the guard, so it exits 3 unless --allow-capped is on.
Args capped_run(const std::string& allow) {
    Args a{"diffusivity", "--scheme", "resolvent", "--dt", "1e-3", "--excursions", "64", "--max-steps", "4000",
           "--format", "json", "--quiet"};
    if (!allow.empty()) a.push_back(allow);
    return a;
}

/// Every byte printable ASCII, and one line: a message quotes no raw bytes.
void expect_one_clean_line(const Result& r, const Args& args) {
    EXPECT_EQ(count_lines(r.err), 1) << describe(args) << "\nstderr: " << r.err;
    for (const char c : r.err) {
        const auto u = static_cast<unsigned char>(c);
        EXPECT_TRUE((u >= 0x20 && u < 0x7f) || c == '\n')
            << describe(args) << ": raw byte " << static_cast<int>(u) << " in the message";
    }
}

/// Expects exit 2, nothing on stdout, one clean line containing `what`.
void expect_refused(const Args& args, const std::string& what) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << describe(args) << "\nstderr: " << r.err;
    EXPECT_EQ(r.out, "") << describe(args);
    expect_one_clean_line(r, args);
    EXPECT_NE(r.err.find(what), std::string::npos) << describe(args) << "\nexpected: " << what << "\nstderr: " << r.err;
}

std::string write_bytes(const std::string& bytes) {
    const std::string path = temp_file("parsing");
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// --- boolean flags -----------------------------------------------------------------

TEST(CliParsing, BooleanFlagsTakeFalseForms) {
    // --allow-capped=false (or 0, no, off) used to turn the option on: a
    // biased result with exit 0 where the user had asked for the error.
    for (const std::string off : {"--allow-capped=false", "--allow-capped=0", "--allow-capped=no",
                                  "--allow-capped=off", "--allow-capped=False"}) {
        const Result r = run(capped_run(off));
        EXPECT_EQ(r.code, 3) << off << "\nstderr: " << r.err;
        EXPECT_EQ(r.out, "") << off;
    }
    for (const std::string on : {"--allow-capped", "--allow-capped=true", "--allow-capped=1", "--allow-capped=yes"}) {
        const Result r = run(capped_run(on));
        EXPECT_EQ(r.code, 0) << on << "\nstderr: " << r.err;
    }
    EXPECT_EQ(run(capped_run("")).code, 3);
}

TEST(CliParsing, BooleanFlagsRefuseOtherValues) {
    expect_refused(capped_run("--allow-capped=maybe"),
                   "--allow-capped: allow-capped must be true or false (also 1/0, yes/no, on/off), got 'maybe'");
    expect_refused(capped_run("--allow-capped=2"), "--allow-capped: allow-capped must be true or false");
    expect_refused({"analytic", "--quiet=maybe"}, "--quiet: quiet must be true or false");
    expect_refused({"analytic", "--print-config=maybe"}, "--print-config: print-config must be true or false");
    expect_refused({"moments", "--trajectories", "64", "--dt", "1e-3", "--density=sometimes"},
                   "--density: density must be true or false");
}

TEST(CliParsing, OtherBooleanFlagsReadTheirValue) {
    // --print-config=false runs the command; --quiet=false is a valid flag.
    const auto j = run_json({"analytic", "--print-config=false", "--quiet=false", "--format", "json"});
    ASSERT_TRUE(j);
    EXPECT_TRUE(j->contains("diffusivity"));
    const Result printed = run({"analytic", "--print-config=yes"});
    EXPECT_EQ(printed.code, 0) << printed.err;
    EXPECT_NE(printed.out.find("friction = "), std::string::npos) << printed.out;
    // A moments run without --density=0 has no density.
    auto m = run_json({"moments", "--scheme", "resolvent", "--trajectories", "64", "--dt", "1e-3", "--times",
                             "0.1", "--density=0", "--format", "json"});
    ASSERT_TRUE(m);
    auto with = run_json({"moments", "--scheme", "resolvent", "--trajectories", "64", "--dt", "1e-3", "--times",
                                "0.1", "--density=1", "--format", "json"});
    ASSERT_TRUE(with);
    EXPECT_EQ((*m)["settings"]["density"], false);
    EXPECT_EQ((*with)["settings"]["density"], true);
    m->erase("settings"); // the results: without a density, no "density" anywhere
    with->erase("settings");
    EXPECT_EQ(m->dump().find("\"density\""), std::string::npos) << m->dump();
    EXPECT_NE(with->dump().find("\"density\""), std::string::npos) << with->dump();
}

// --- numbers ---------------------------------------------------------------------------

TEST(CliParsing, HexadecimalIsRefusedOnEveryFlag) {
    // The settings refused 0x10, but --checkpoint-every (read by CLI11) took it as 16.
    expect_refused({"diffusivity", "--excursions", "64", "--checkpoint-every", "0x10"},
                   "--checkpoint-every: checkpoint-every must be a number, got '0x10'");
    expect_refused({"diffusivity", "--excursions", "64", "--checkpoint-every", "1e400"}, "--checkpoint-every");
    expect_refused({"diffusivity", "--excursions", "64", "--checkpoint-every", "0"}, "--checkpoint-every");
    expect_refused({"diffusivity", "--dt", "0x1p-10"}, "--dt");
    expect_refused({"diffusivity", "--seed", "0x10"}, "--seed");
    const Result ok = run({"diffusivity", "--excursions", "64", "--checkpoint-every", "1.5e1", "--print-config"});
    EXPECT_EQ(ok.code, 0) << ok.err;
}

TEST(CliParsing, TinyRelaxationIsBlamedOnRelaxation) {
    // 5e-324 is a double (subnormal); its inverse is not, and the automatic
    // step came out as 0, which was reported as "--dt: dt must be > 0".
    expect_refused({"diffusivity", "--relaxation", "5e-324"},
                   "--relaxation: relaxation must be at least 2.2250738585072014e-308 s");
    expect_refused({"diffusivity", "--relaxation", "1e-310", "--scheme", "resolvent"}, "--relaxation");
    expect_refused({"analytic", "--relaxation", "5e-324"}, "--relaxation");
}

TEST(CliParsing, ControlBytesInValuesAreEscaped) {
    expect_refused({"diffusivity", "--dt", "1\x1b[31m"}, "--dt: dt must be a number or auto, got '1\\x1b[31m'");
    expect_refused({"diffusivity", "--seed", "7\xff"}, "got '7\\xff'");
    expect_refused({"diff\x01usivity"}, "unknown subcommand 'diff\\x01usivity'");
}

// --- config files that are not plain text --------------------------------------------

TEST(CliParsing, ConfigFileWithByteOrderMarkIsNamed) {
    const std::string path = write_bytes("\xEF\xBB\xBF" "excursions = 64\n");
    expect_refused({"diffusivity", "--config", path}, "--config: '" + path + "' starts with a byte-order mark (BOM)");
    std::remove(path.c_str());
}

TEST(CliParsing, ConfigFileWithADuplicateKeyIsRefused) {
    // The second line used to win silently.
    const std::string path = write_bytes("excursions = 64\ndt = 1e-3\nexcursions = 128\n");
    expect_refused({"diffusivity", "--config", path},
                   "--config: '" + path + "': setting 'excursions' is given more than once; keep one line for it (line 3");
    std::remove(path.c_str());
    const std::string spelt = write_bytes("max-steps = 1000000\nmax_steps = 2000000\n");
    expect_refused({"diffusivity", "--config", spelt}, "setting 'max-steps' is given more than once");
    std::remove(spelt.c_str());
}

TEST(CliParsing, ConfigFileWithANulIsRefused) {
    static const char bytes[] = "excursions = 64\ndt\0 = 1e-3\n";
    const std::string path = write_bytes(std::string(bytes, sizeof bytes - 1));
    expect_refused({"diffusivity", "--config", path},
                   "--config: '" + path + "' contains a NUL byte (line 2, column 3): not a text settings file");
    std::remove(path.c_str());
}

TEST(CliParsing, ConfigFileOfBinaryGarbageIsRefusedWithoutEchoingIt) {
    std::string garbage = "\x7f" "ELF\x02\x01\x01";
    for (int k = 0; k < 200; ++k) garbage += static_cast<char>((k * 37 + 11) & 0xff);
    const std::string path = write_bytes(garbage);
    expect_refused({"diffusivity", "--config", path}, "--config: '" + path + "' is not a text settings file");
    std::remove(path.c_str());
    const std::string latin1 = write_bytes("excursions = 64 # r\xE9sum\xE9\n");
    expect_refused({"diffusivity", "--config", latin1}, "invalid UTF-8 at line 1, column 20");
    std::remove(latin1.c_str());
    // UTF-8 is text: a comment in any language is fine.
    const std::string utf8 = write_bytes("excursions = 64 # r\xC3\xA9sum\xC3\xA9\ndt = 1e-3\n");
    const Result r = run({"diffusivity", "--config", utf8, "--print-config"});
    EXPECT_EQ(r.code, 0) << r.err;
    std::remove(utf8.c_str());
}

// Issue 50, item 7: the hand-written reader took a '#' inside a quoted value
// for a comment, so --print-config then --config failed for a table path
// with a '#'; quotes and backslashes were written unescaped. toml++ reads the
// file now: what --print-config writes reads back to the same run, numbers
// to the same bits.
TEST(CliParsing, PrintConfigThenConfigIsTheSameRun) {
    const Scratch dir("config_round_trip");
    const std::string table = dir / "law #1 \"b\\v\".csv";
    { std::ofstream(table) << "v,b\n-10,3\n0,0.342\n10,-3\n"; }
    const Args settings{"diffusivity", "--drift-table", table, "--friction", "3.8400000000000003",
                        "--tau", "0.30000000000000004", "--seed", "18446744073709551615", "--excursions", "300"};
    Args print = settings;
    for (const char* a : {"--print-config", "--output"}) print.push_back(a);
    print.push_back(dir / "run.toml");
    const Result printed = run(print);
    ASSERT_EQ(printed.code, 0) << printed.err;
    Args direct = settings;
    for (const char* a : {"--format", "json", "--quiet"}) direct.push_back(a);
    const auto expected = run_json(direct);
    const auto configured = run_json({"diffusivity", "--config", dir / "run.toml", "--format", "json", "--quiet"});
    ASSERT_TRUE(expected && configured);
    EXPECT_EQ((*configured)["params"], (*expected)["params"]);
    EXPECT_EQ((*configured)["diffusivity"], (*expected)["diffusivity"]);
}

TEST(CliParsing, ConfigFileThatIsNotTomlIsRefusedWithItsPlace) {
    // An unquoted text value was taken as text by the old reader.
    const std::string bare = write_bytes("excursions = 64\ndrift = -v\n");
    expect_refused({"diffusivity", "--config", bare}, "is not TOML: ");
    expect_refused({"diffusivity", "--config", bare}, "(line 2, column 9); write `key = value` lines, text quoted");
    std::remove(bare.c_str());
    const std::string section = write_bytes("[run]\nnoise = 1\n");
    expect_refused({"diffusivity", "--config", section}, "sections ([run], line 1) are not read");
    std::remove(section.c_str());
    const std::string date = write_bytes("noise = 1979-05-27\n");
    expect_refused({"diffusivity", "--config", date}, "setting 'noise' (line 1) takes a number, a quoted text");
    std::remove(date.c_str());
    const std::string bad = write_bytes("excursions = 64\ntau = \"x\"\n");
    expect_refused({"diffusivity", "--config", bad}, "--tau: tau must be a number, got 'x' (in '" + bad + "', line 2)");
    std::remove(bad.c_str());
    // Bounded before it fills memory.
    expect_refused({"diffusivity", "--config", "/dev/zero"}, "'/dev/zero' is larger than 1 MiB");
}

// --- --resume and --print-config ---------------------------------------------------------

TEST(CliParsing, ResumeFromADirectorySaysSo) {
    const Scratch dir("resume_dir");
    expect_refused({"diffusivity", "--excursions", "64", "--resume", dir.path},
                   "--resume: cannot resume from '" + dir.path + "': it is a directory");
    const Result r = run({"diffusivity", "--excursions", "64", "--resume", dir.path});
    EXPECT_EQ(r.err.find("empty"), std::string::npos) << r.err;
}

TEST(CliParsing, PrintConfigValidatesTheSettings) {
    // It printed friction = -1 with exit 0: a config file that could never run.
    expect_refused({"diffusivity", "--friction", "-1", "--print-config"}, "--friction");
    expect_refused({"diffusivity", "--excursions", "1", "--print-config"}, "--excursions");
    expect_refused({"diffusivity", "--checkpoint-every", "-1", "--print-config"}, "--checkpoint-every");
    expect_refused({"density", "--bins", "0", "--print-config"}, "--bins");
    expect_refused({"analytic", "--print-config", "--format", "xml"}, "--format");
}

TEST(CliParsing, PrintConfigHonoursOutput) {
    const Scratch dir("print_config");
    const std::string file = dir / "run.toml";
    const Result r = run({"diffusivity", "--excursions", "128", "--print-config", "--output", file});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, "") << "the config went to stdout instead of --output";
    const std::string text = slurp(file);
    EXPECT_NE(text.find("excursions = 128"), std::string::npos) << text;
    // And that file runs.
    const auto j = run_json({"diffusivity", "--config", file, "--scheme", "resolvent", "--dt", "2e-3", "--format",
                             "json", "--quiet"});
    ASSERT_TRUE(j);
    EXPECT_EQ((*j)["params"]["excursions"], 128) << j->dump();
    expect_refused({"diffusivity", "--print-config", "--output", dir.path}, "--output");
}

// --- settings a run does not use are checked all the same ------------------------------

TEST(CliParsing, UnusedSettingsAreCheckedAsUsedOnes) {
    // --range was checked without --density, --bins was not; --index was
    // checked with --paths, --time not without.
    expect_refused({"moments", "--trajectories", "64", "--dt", "1e-3", "--bins", "0"}, "--bins");
    expect_refused({"moments", "--trajectories", "64", "--dt", "1e-3", "--range=1,0"}, "--range");
    expect_refused({"trajectory", "--dt", "1e-2", "--time", "-1"}, "--time");
    expect_refused({"trajectory", "--dt", "1e-2", "--paths", "2", "--index", "-1"}, "--index");
}

} // namespace
