// The `stickslip` command: a thin layer over the library. It parses flags,
// reports progress on a terminal, prints or writes the result, and maps errors
// to exit codes: 2 bad input (one line on stderr, nothing on stdout), 3 a run
// that cannot be trusted (capped excursions), 1 anything else (I/O).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "stickslip/config.hpp"

namespace cli = stickslip::cli;

int main(int argc, char** argv) {
    CLI::App app{"stickslip: diffusivity, mobility and velocity statistics of an object with dry friction under "
                 "white or colored\nnoise, by the unbiased long-excursion estimators (exact PDMP or "
                 "differential-inclusion engine),\nwith exact white-noise references."};
    app.footer(cli::kConventions);
    app.require_subcommand(1);
    app.set_version_flag("--version", STICKSLIP_VERSION_STRING);
    const auto actions = cli::register_all(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::string msg = e.what();
        for (auto& ch : msg)
            if (ch == '\n') ch = ' ';
        std::fprintf(stderr, "stickslip: error: %s (see --help)\n", msg.c_str());
        return cli::kExitBadInput;
    }

    try {
        for (const auto& a : actions)
            if (a.app->parsed()) a.run();
    } catch (const stickslip::InvalidParameter& e) {
        std::fprintf(stderr, "stickslip: error: --%s: %s\n", e.parameter().c_str(), e.what());
        return cli::kExitBadInput;
    } catch (const stickslip::CappedExcursions& e) {
        std::fprintf(stderr, "stickslip: ERROR: %s\n", e.what());
        return cli::kExitCapped;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "stickslip: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
