// SPDX-License-Identifier: BSD-3-Clause
// The `stickslip` command. Its logic is run_command() (run.cpp), so that the
// fuzz targets (tests/fuzz/) can call it in-process; main() only brackets it
// with the process split.
#include "distributed.hpp"
#include "app.hpp"

namespace cli = stickslip::cli;

int main(int argc, char** argv) {
    // MPI starts here, before parsing, only when launched by an MPI launcher.
    cli::start_distribution(argc, argv);
    const int code = cli::run_command(argc, argv);
    cli::stop_distribution();
    return code;
}
