// Registration of the `stickslip` subcommands (commands.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

#include "common.hpp"

namespace stickslip::cli {

/// A registered subcommand and what to do when it is the one parsed.
struct Action {
    CLI::App* app;
    std::function<void()> run;
};

std::vector<Action> register_all(CLI::App& app);

} // namespace stickslip::cli
