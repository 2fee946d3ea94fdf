// SPDX-License-Identifier: BSD-3-Clause
// Writes the long excursions of one run, one record per excursion, for the
// diagnosis of D's interval (docs/validation.md, "Why D's interval
// under-covers without drag"): five doubles (U [m], t [s], M [m], C [m^2],
// capped 0/1), raw little-endian, in index order. The inclusion engine's
// resolvent scheme (or the event scheme) with the martingale of the run's
// corrector, exactly as `stickslip diffusivity --scheme resolvent` runs them (the same seed gives
// the same excursions: its D is this file's).
//
// Built against a build tree (it reaches the driver's engine visitor, which is
// not public):
//   c++ -O2 -DNDEBUG -std=c++20 -Ibuild/generated -Isrc -Iinclude -isystem /usr/include/eigen3 \
//       -ffp-contract=off scripts/validation/influence/excursion_dump.cpp -o excursion_dump \
//       build/libstickslip.a -lmuparser -ltomlplusplus -lpthread
// Usage: excursion_dump TAU BIAS RELAXATION N SEED OUT [DT [FRICTION [NOISE]]]
//   (SI units; DT 1e-2, FRICTION 1, NOISE 1 by default; N rounded up to 4096s;
//   DT "event": the event scheme at its automatic step instead, coloured noise)
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "driver/visit_engine.hpp"
#include "stickslip/corrector.hpp"
#include "stickslip/run.hpp"

int main(int argc, char** argv) {
    using namespace stickslip;
    if (argc < 7) {
        std::fprintf(stderr, "usage: excursion_dump TAU BIAS RELAXATION N SEED OUT [DT [FRICTION [NOISE]]]\n");
        return 2;
    }
    RunSettings r;
    r.params.tau = std::atof(argv[1]);
    r.params.bias = std::atof(argv[2]);
    r.params.relaxation = std::atof(argv[3]);
    const std::uint64_t n = std::strtoull(argv[4], nullptr, 10);
    const std::uint64_t seed = std::strtoull(argv[5], nullptr, 10);
    const bool event = argc > 7 && std::string(argv[7]) == "event";
    r.engine.dt = argc > 7 && !event ? std::atof(argv[7]) : 1e-2;
    r.engine.dt_auto = event;
    r.engine.scheme = event ? Scheme::Event : Scheme::Resolvent;
    r.params.friction = argc > 8 ? std::atof(argv[8]) : 1.0;
    r.params.noise = argc > 9 ? std::atof(argv[9]) : 1.0;
    const PreparedEngine e = prepare(r);
    const auto g = make_corrector(e.model);
    std::FILE* f = std::fopen(argv[6], "wb");
    if (!f) return 1;
    std::vector<ExcursionOutcome> out(4096);
    for (std::uint64_t first = 0; first < n; first += out.size()) {
        detail::visit_engine(e, [&](const auto& engine) {
            if constexpr (requires { engine.long_excursions_with(seed, first, out.size(), out.data(), nullptr, g->table); })
                engine.long_excursions_with(seed, first, out.size(), out.data(), nullptr, g->table);
            else
                std::abort(); // both schemes have the martingale kernel (the event scheme: coloured noise)
        });
        for (const ExcursionOutcome& o : out) {
            const double row[5] = {o.displacement, o.duration, o.martingale,
                                   o.martingale * o.martingale - o.martingale_qv, o.capped ? 1.0 : 0.0};
            std::fwrite(row, sizeof row, 1, f);
        }
    }
    return std::fclose(f) == 0 ? 0 : 1;
}
