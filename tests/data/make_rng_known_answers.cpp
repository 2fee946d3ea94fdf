// Generator of rng_known_answers.json (run once; the file pins the streams).
// Not part of any build. From the repository root:
//   g++ -std=c++20 -O2 -Iinclude tests/data/make_rng_known_answers.cpp -o /tmp/kat \
//     && /tmp/kat > tests/data/rng_known_answers.json
// Regenerate only for a deliberate change of the random streams.
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "stickslip/random/rng.hpp"

using stickslip::CounterRng;
using stickslip::StreamPurpose;

static std::string hex64(double d) {
    std::uint64_t b;
    std::memcpy(&b, &d, 8);
    char s[32];
    std::snprintf(s, sizeof s, "0x%016" PRIx64, b);
    return s;
}
static std::string hex32(std::uint32_t w) {
    char s[16];
    std::snprintf(s, sizeof s, "0x%08x", w);
    return s;
}

int main() {
    const std::uint64_t seeds[] = {1ull, (1ull << 40) + 7, 0xfedcba9876543210ull};
    const std::pair<StreamPurpose, const char*> purposes[] = {{StreamPurpose::LongExcursion, "LongExcursion"},
                                                              {StreamPurpose::BruteForce, "BruteForce"}};
    const std::uint64_t indices[] = {0ull, 1ull, (1ull << 32) + 5, (1ull << 56) - 1};
    std::cout << "{\n \"description\": "
              << nlohmann::json(
                     "Known answers of stickslip::CounterRng (Philox4x32-10; key = seed, counter = {draw lo, draw hi, "
                     "index lo, index hi 24 bits | purpose << 24}). For each (seed, purpose, index): the first "
                     "128-bit block of a fresh stream, the first three normal2() pairs of a fresh stream (ziggurat, 256 "
                     "layers, rejected words resolved from the retry substream) and the "
                     "first three uniform2() pairs and the first three exponential_uniform() pairs (exponential ziggurat, "
                     "256 layers, the PDMP's draw) of a fresh stream. *_bits are the IEEE-754 bit patterns; the "
                     "numbers are the same values in shortest round-trip decimal.")
                     .dump()
              << ",\n \"generator\": \"tests/data/make_rng_known_answers.cpp, stickslip 0.1.0, g++ -O2, x86-64 "
                 "glibc\",\n \"cases\": [\n";
    bool first = true;
    for (auto seed : seeds)
        for (auto [purpose, name] : purposes)
            for (auto index : indices) {
                nlohmann::json block, normals, normal_bits, uniforms, uniform_bits, expos, expo_bits;
                {
                    CounterRng r(seed, purpose, index);
                    const auto b = r.next_block();
                    block = {hex32(b.v[0]), hex32(b.v[1]), hex32(b.v[2]), hex32(b.v[3])};
                }
                {
                    CounterRng r(seed, purpose, index);
                    for (int k = 0; k < 3; ++k) {
                        const auto z = r.normal2();
                        normals.push_back({z.x, z.y});
                        normal_bits.push_back({hex64(z.x), hex64(z.y)});
                    }
                }
                {
                    CounterRng r(seed, purpose, index);
                    for (int k = 0; k < 3; ++k) {
                        double a, b;
                        r.uniform2(a, b);
                        uniforms.push_back({a, b});
                        uniform_bits.push_back({hex64(a), hex64(b)});
                    }
                }
                {
                    CounterRng r(seed, purpose, index);
                    for (int k = 0; k < 3; ++k) {
                        double e, u;
                        r.exponential_uniform(e, u);
                        expos.push_back({e, u});
                        expo_bits.push_back({hex64(e), hex64(u)});
                    }
                }
                auto item = [](const char* key, const nlohmann::json& v, bool last = false) {
                    std::string s = "   \"" + std::string(key) + "\": " + v.dump(-1, ' ', false);
                    // nlohmann's compact dump has no spaces; add one after commas for readability.
                    std::string out;
                    for (char ch : s) {
                        out += ch;
                        if (ch == ',') out += ' ';
                    }
                    return out + (last ? "\n" : ",\n");
                };
                std::cout << (first ? "" : ",\n") << "  {\n"
                          << item("seed", seed) << item("purpose", name)
                          << item("purpose_value", static_cast<std::uint32_t>(purpose)) << item("index", index)
                          << item("block0", block) << item("normal2", normals) << item("normal2_bits", normal_bits)
                          << item("uniform2", uniforms) << item("uniform2_bits", uniform_bits)
                          << item("exponential_uniform", expos) << item("exponential_uniform_bits", expo_bits, true)
                          << "  }";
                first = false;
            }
    std::cout << "\n ]\n}\n";
}
