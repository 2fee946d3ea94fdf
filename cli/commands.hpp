// SPDX-License-Identifier: BSD-3-Clause
// The subcommands of `stickslip` (commands.cpp): each registers its flags,
// generated from its request's settings, and returns what to run when it is
// the one chosen.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace stickslip::cli {

/// Exit codes: 0 ok, 1 unexpected failure (I/O, internal), 2 bad input,
/// 3 untrustworthy run (runaway excursions, estimates 0/0).
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitUntrustworthy = 3;

/// A registered subcommand and what to do when it is the one parsed: `run`
/// takes the command line (command_line()), which the reports record.
struct Action {
    CLI::App* app;
    std::function<void(const std::string& command)> run;
};

/// The command line as the reports record it: "stickslip" and the arguments
/// after the program's name (which may be a path of this machine), each
/// quoted for a POSIX shell where it needs it, so that it can be run again.
std::string command_line(int argc, char** argv);

std::vector<Action> register_all(CLI::App& app);

/// The conventions footer of every --help.
extern const char* const kConventions;

} // namespace stickslip::cli
