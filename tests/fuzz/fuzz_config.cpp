// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the config file (--config FILE), the one file the
// program reads.
//
// The input is the file. When its first line is the header --print-config
// writes ("# stickslip NAME: ..."), it is read by subcommand NAME, otherwise
// by the subcommand that the input's size picks (size modulo 8, in
// register_all() order); twice, as `NAME --config FILE --print-config` and as
// `NAME --config FILE`, through the dry path and, when that computes nothing,
// the real command (harness.hpp lists what is checked).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "harness.hpp"

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
    stickslip::fuzz::initialize(argc, argv);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace stickslip::fuzz;
    if (size > 16384) return 0;
    const std::string text(reinterpret_cast<const char*>(data), size);
    write_config(text);
    const std::vector<std::string>& all = subcommands();
    std::string command = all[size % all.size()];
    const std::string header = "# stickslip ";
    const std::size_t colon = text.find(':');
    if (text.compare(0, header.size(), header) == 0 && colon != std::string::npos && colon > header.size()) {
        const std::string name = text.substr(header.size(), colon - header.size());
        for (const auto& c : all)
            if (c == name) command = c;
    }
    check({"stickslip", command, "--config", config_path(), "--print-config"});
    check({"stickslip", command, "--config", config_path()});
    return 0;
}
