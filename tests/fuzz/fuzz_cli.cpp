// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the command line of every subcommand.
//
// The input is an argument vector, one argument per line (the program name
// comes first, implicitly): e.g. "diffusivity\n--friction\n-1\n". A line
// "@config" or "@resume" ends the arguments and starts the text of the file
// that --config or --resume reads, up to the next such line or the end (see
// neutralise() in harness.hpp for how the values of --config, --resume,
// --output and --checkpoint are mapped into the sandbox). Each vector goes
// through the dry path (parse, fill the request, --print-config, the output
// and checkpoint checks, validate) and, when that computes nothing, the real
// command; harness.hpp lists what is checked.
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
    if (size > 8192) return 0;
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> args{"stickslip"};
    std::string config, resume;
    std::string* file = nullptr; // the file whose text the lines are, once past the arguments
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t nl = text.find('\n', at);
        const std::string line = text.substr(at, nl == std::string::npos ? std::string::npos : nl - at);
        at = nl == std::string::npos ? text.size() : nl + 1;
        if (line == "@config" || line == "@resume") {
            file = line == "@config" ? &config : &resume;
            continue;
        }
        if (file) {
            *file += line;
            if (nl != std::string::npos) *file += '\n';
            continue;
        }
        args.push_back(line);
        if (args.size() > 65) return 0; // a command line, not a file
    }
    stickslip::fuzz::write_config(config);
    stickslip::fuzz::write_resume(resume);
    stickslip::fuzz::check(stickslip::fuzz::neutralise(args));
    return 0;
}
