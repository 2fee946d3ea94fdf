// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the checkpoint file that --resume FILE reads.
//
// The input is the file. It is read by the resumable subcommand it names
// ("command": "NAME", as checkpoints spell it) or else by the one that the
// input's size picks (size modulo their number, in register_all() order), as
// `NAME --resume FILE`: through the dry path, which opens the checkpoint
// journal and so reads and checks the file, and, when that computes nothing
// (the file is refused), the real command (harness.hpp lists what is checked).
//
// A checksum covers a checkpoint, so nearly every mutation would stop there.
// Inputs of even size that are JSON objects with a "checksum" have it put
// right first (FNV-1a of the compact JSON without it, as src/driver/checkpoint.cpp
// computes it), so that the checks behind it are fuzzed too; inputs of odd
// size are read as they are.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness.hpp"

namespace {

std::string with_checksum_put_right(const std::string& text) {
    auto j = nlohmann::ordered_json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("checksum")) return text;
    j.erase("checksum");
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : j.dump()) {
        h ^= c;
        h *= 0x100000001b3ull;
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    j["checksum"] = hex;
    return j.dump(1) + "\n";
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
    stickslip::fuzz::initialize(argc, argv);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace stickslip::fuzz;
    if (size > 65536) return 0;
    const std::vector<std::string>& all = resumable_subcommands();
    if (all.empty()) return 0;
    std::string text(reinterpret_cast<const char*>(data), size);
    std::string command = all[size % all.size()];
    for (const auto& c : all)
        if (text.find("\"command\": \"" + c + "\"") != std::string::npos ||
            text.find("\"command\":\"" + c + "\"") != std::string::npos)
            command = c;
    if (size % 2 == 0) text = with_checksum_put_right(text);
    write_resume(text);
    check({"stickslip", command, "--resume", resume_path()});
    return 0;
}
