// SPDX-License-Identifier: BSD-3-Clause
// The `stickslip` command: a thin layer over the library. It parses flags,
// reports progress on a terminal, prints or writes the result, and maps errors
// to exit codes: 2 bad input (one line on stderr, nothing on stdout), 3 a run
// that cannot be trusted (capped excursions), 1 anything else (I/O), 128 +
// the signal for a run stopped by SIGINT (130) or SIGTERM (143), whose result
// so far has been written.
#include "app.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "distributed.hpp"
#include "interrupt.hpp"
#include "output.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/version.hpp"

namespace stickslip::cli {

namespace {

/// Prints the one error line (first process only) and returns the exit code.
int report(int code, const std::string& line) {
    if (is_root()) std::fprintf(stderr, "stickslip: %s\n", line.c_str());
    return code;
}

/// Levenshtein distance of a and b (short strings: flag names).
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

/// "; did you mean --excursions?" for the first --flag on the command line
/// that the chosen subcommand does not have, when one of its flags is within
/// two edits of it; else "".
std::string flag_suggestion(CLI::App& app, int argc, char** argv) {
    const std::vector<CLI::App*> chosen = app.get_subcommands();
    CLI::App* sub = chosen.empty() ? &app : chosen.front();
    std::vector<std::string> names;
    for (const CLI::Option* o : sub->get_options())
        for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    for (const CLI::Option* o : app.get_options())
        for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    for (int k = 1; k < argc; ++k) {
        std::string given(argv[k]);
        if (given.rfind("--", 0) != 0 || given.size() < 4) continue;
        given = given.substr(0, given.find('='));
        if (std::find(names.begin(), names.end(), given) != names.end()) continue;
        std::string best;
        std::size_t best_distance = 3;
        for (const std::string& n : names)
            if (const std::size_t d = edit_distance(given, n); d < best_distance) {
                best = n;
                best_distance = d;
            }
        return best.empty() ? std::string() : "; did you mean " + best + "?";
    }
    return "";
}

} // namespace

int run_command(int argc, char** argv) {
    CLI::App app{"stickslip: diffusivity, mobility and velocity statistics of an object with dry friction under "
                 "white or colored\nnoise, by the unbiased long-excursion estimators (exact piecewise-deterministic "
                 "Markov process\n(PDMP) or differential-inclusion engine), with exact white-noise references."};
    app.footer(kConventions);
    app.require_subcommand(1);
    app.set_version_flag("--version", stickslip::version_line());
    const auto actions = register_all(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return is_root() ? app.exit(e) : 0;
    } catch (const CLI::CallForAllHelp& e) {
        return is_root() ? app.exit(e) : 0;
    } catch (const CLI::CallForVersion& e) {
        return is_root() ? app.exit(e) : 0;
    } catch (const CLI::ParseError& e) {
        // CLI11 answers a misspelt subcommand with "A subcommand is required".
        if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
            std::string names;
            for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
                names += (names.empty() ? "" : ", ") + sub->get_name();
            return report(kExitBadInput, "error: unknown subcommand '" + printable_text(argv[1]) + "'; one of: " +
                                             names + " (see --help)");
        }
        std::string msg = e.what();
        for (auto& ch : msg)
            if (ch == '\n') ch = ' ';
        return report(kExitBadInput,
                      "error: " + printable_text(msg) + flag_suggestion(app, argc, argv) + " (see --help)");
    }

    // Bad input and capped runs are found by every process alike (validation
    // comes before any work, the capped check after the gather), so each
    // process exits with the same code; anything else on one process of a
    // distributed run ends them all.
    const StopOnSignals stop_on_signals; // before the clean-up handlers (interrupt.hpp)
    const CleanupOnSignals cleanup_on_signals;
    try {
        for (const auto& a : actions)
            if (a.app->parsed()) a.run(command_line(argc, argv));
    } catch (const stickslip::RunInterrupted& e) {
        return report(exit_code_of_signal(StopOnSignals::signal()), std::string("interrupted: ") + e.what());
    } catch (const stickslip::InvalidParameter& e) {
        return report(kExitBadInput, "error: --" + e.parameter() + ": " + e.what());
    } catch (const stickslip::UntrustworthyResult& e) { // capped excursions, 0/0, non-finite estimates
        return report(kExitUntrustworthy, std::string("ERROR: ") + e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "stickslip: error: %s\n", e.what());
        if (distributed()) abort_distribution(1);
        return 1;
    }
    // Stopped by a signal: the result so far has been written (marked "interrupted").
    if (StopOnSignals::signal()) return exit_code_of_signal(StopOnSignals::signal());
    return 0;
}

} // namespace stickslip::cli
