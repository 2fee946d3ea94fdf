// SPDX-License-Identifier: BSD-3-Clause
// The shared part of the libFuzzer targets of `stickslip` (fuzz_cli.cpp,
// fuzz_config.cpp): run an argument vector through the command without
// running a simulation, and check what it does.
//
// Each argument vector goes through two paths:
//
//  * the dry path, a replica of commands.cpp that builds the same CLI11 app
//    from the same pieces (SettingFlags, add_output_flags, the main app's
//    settings), parses, fills the request (apply(): defaults, the config file,
//    the command line), calls the library's validate(request) (which
//    --print-config needs too), writes --print-config, opens the --output target,
//    opens the checkpoint journal
//    (which reads --resume), and stops there: it predicts what
//    the real command will do without computing anything;
//  * the real path, stickslip::cli::run_command(), the very function main()
//    calls, run only when the dry path predicts that it stops before any
//    computation: a parse error, --help/--version, --print-config, or bad
//    input (refused by apply(), by the output check or by validate()). Its
//    stdout, stderr and exit code are captured and checked.
//
// What counts as a finding (abort(), so that libFuzzer keeps the input), on
// top of every AddressSanitizer / UndefinedBehaviorSanitizer report, leak,
// crash, hang (-timeout) and allocation over -malloc_limit_mb:
//
//  * an exception other than InvalidParameter out of apply() or validate()
//    (bad input must be exit 2 with one line naming the parameter, never
//    exit 1 "internal error");
//  * the real command disagreeing with the dry prediction: bad input that is
//    not exit 2 with nothing on stdout and exactly one "stickslip: error: "
//    line on stderr; --help that is not exit 0; --print-config whose output
//    differs from the dry path's (on stdout, or where --output says);
//  * --config naming a folder and read as an empty file instead of refused;
//  * a --print-config text that, read back with --config, is refused although
//    its request is valid, or prints a different text, or changes whether the
//    request is valid (the README's promise: --print-config then --config
//    reproduces a run exactly).
//
// File names never reach the file system as given: every --config, --resume,
// --output and --checkpoint value is replaced by a path in the sandbox (a
// private temporary folder; see neutralise()), so a fuzzed run reads and
// writes nothing else. The dry/real split is checked once at start-up:
// the replica must have the same subcommands with the same flags as
// register_all().
#pragma once

#include <string>
#include <vector>

namespace stickslip::fuzz {

/// LLVMFuzzerInitialize's work: makes the sandbox, checks the replica against
/// the real command, and asks libFuzzer for -close_fd_mask=3 (the command's
/// stdout and stderr then go to /dev/null, libFuzzer's and the sanitizers'
/// reports to the real stderr) unless a -close_fd_mask is given; with any
/// other mask than 3 the command's output is shown and not checked.
/// STICKSLIP_FUZZ_CHECK_DICT=FILE: check that FILE names every flag and
/// subcommand, and exit (0: it does).
void initialize(int* argc, char*** argv);

/// The sandbox's config file: what --config reads.
const std::string& config_path();
/// Writes `text` to config_path().
void write_config(const std::string& text);

/// The sandbox's resume file: what --resume reads (unless mapped otherwise).
void write_resume(const std::string& text);

/// Replaces the values of the flags that name files (also as --flag=X) by
/// sandbox paths:
///  * --config X: X ending in '/' becomes the sandbox folder, X starting with
///    "missing" a file that does not exist, any other config_path();
///  * --resume X: the same, but X starting with "checkpoint" becomes the
///    --checkpoint file, and any other the resume file (write_resume());
///  * --output X: empty stays empty (stdout), /dev/null, /dev/stdout,
///    /dev/stderr, /dev/fd/1 and /dev/fd/2 stay, X ending in '/' becomes the
///    sandbox folder, X containing "missing" a file in a folder that does not
///    exist, any other a file of the sandbox;
///  * --checkpoint X: as --output, but no device, and its own file, removed
///    before every input.
/// A value that looks like an option (-x, --x) is left alone: CLI11 would not
/// take it as one.
std::vector<std::string> neutralise(std::vector<std::string> args);

/// Runs `args` (args[0] is the program name) through the dry path, then the
/// real one when it computes nothing, and checks them (see above). Aborts on
/// a finding, after printing what it was on the real stderr.
void check(const std::vector<std::string>& args);

/// The names of the subcommands, in register_all() order.
const std::vector<std::string>& subcommands();
/// Those of them that take --resume (and --checkpoint).
const std::vector<std::string>& resumable_subcommands();
/// The sandbox's resume file (write_resume()).
const std::string& resume_path();

} // namespace stickslip::fuzz
