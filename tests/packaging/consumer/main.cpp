// SPDX-License-Identifier: BSD-3-Clause
// Uses an installed stickslip through find_package(stickslip): the
// nondimensional system (params.hpp), a closed form (analytic.hpp), a small
// long-excursion run on two threads (diffusivity.hpp, compiled library code),
// its JSON report, and the Philox stream (header-only, needs Random123).
#include <cmath>
#include <cstdio>

#include "stickslip/analytic.hpp"
#include "stickslip/config.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/params.hpp"
#include "stickslip/report.hpp"
#include "stickslip/random/rng.hpp"

int main() {
    stickslip::ModelParams p; // the paper's Fig. 2 case
    const stickslip::ModelParams nd = stickslip::to_nondimensional(p);

    stickslip::ModelParams dry;
    dry.relaxation = INFINITY;
    dry.bias = 0.0;
    const double d_dry = stickslip::dry_friction_diffusivity(dry); // white noise, no drag

    stickslip::DiffusivityRequest req;
    req.engine.engine = stickslip::Engine::Pdmp;
    req.excursions = 128;
    req.control.threads = 2;
    const stickslip::DiffusivityResult r = stickslip::compute_diffusivity(req);
    const bool json_ok = stickslip::to_json(r).find("\"diffusivity\"") != std::string::npos;

    stickslip::CounterRng a(1, stickslip::StreamPurpose::Test, 7), b(1, stickslip::StreamPurpose::Test, 7);
    const bool same = a.uniform() == b.uniform();

    std::printf("stickslip %s\n", STICKSLIP_VERSION_STRING);
    std::printf("nondimensional tau' = %.6g, relaxation' = %.6g, bias' = %.6g\n", nd.tau, nd.relaxation, nd.bias);
    std::printf("white-noise dry-friction D = %.6g m^2/s\n", d_dry);
    std::printf("pdmp D = %.6g m^2/s from %llu excursions%s\n", r.estimates.diffusivity.value,
                static_cast<unsigned long long>(r.estimates.excursions), json_ok ? ", json ok" : "");
    std::printf("philox %s\n", same ? "ok" : "MISMATCH");
    return same && json_ok && d_dry > 0 && r.estimates.diffusivity.value > 0 ? 0 : 1;
}
