#include "stickslip/runner.hpp"

#include <cmath>

#include "block_runner.hpp"

#include "stickslip/inclusion.hpp"
#include "stickslip/inclusion_lanes.hpp"
#include "stickslip/pdmp.hpp"
#include "stickslip/rng.hpp"
#include "stickslip/rng_batch.hpp"

namespace stickslip {

namespace {
struct NoExtra {};
} // namespace

RunTotals run_samples(std::uint64_t n, const RunControl& ctl,
                      const std::function<ExcursionOutcome(std::uint64_t)>& sample) {
    NoExtra none;
    return detail::run_blocks(
        n, ctl, [] { return NoExtra{}; }, [&](std::uint64_t k, NoExtra&) { return sample(k); },
        [](NoExtra&, const NoExtra&) {}, none);
}

RunTotals run_long_excursions(const ModelParams& p, const EngineSettings& s, std::uint64_t excursions,
                              const RunControl& ctl) {
    const std::uint64_t seed = ctl.seed;
    if (s.engine == Engine::Pdmp) {
        const PdmpConstants c = make_pdmp_constants(p, s);
        return run_samples(excursions, ctl, [&c, seed](std::uint64_t k) {
            BatchedUniformRng rng(seed, StreamPurpose::LongExcursion, k);
            return pdmp_long_excursion(c, rng);
        });
    }
    const InclusionConstants c = make_inclusion_constants(p, s);
    NoExtra none;
    return detail::run_blocks(
        excursions, ctl, [] { return NoExtra{}; },
        [&c, seed, cancel = ctl.cancel](std::uint64_t first, std::uint64_t count, ExcursionOutcome* out, NoExtra&) {
            return inclusion_long_excursions(c, seed, first, count, out, cancel);
        },
        [](NoExtra&, const NoExtra&) {}, none);
}

RunTotals run_bruteforce(const ModelParams& p, const EngineSettings& s, double horizon, double x0, double v0,
                         std::uint64_t trajectories, const RunControl& ctl) {
    if (!std::isfinite(horizon) || horizon <= 0)
        throw InvalidParameter("time", "time must be a finite number > 0 (s)");
    if (!std::isfinite(v0)) throw InvalidParameter("v0", "v0 must be a finite number (m/s)");
    const std::uint64_t seed = ctl.seed;
    if (s.engine == Engine::Pdmp) {
        const PdmpConstants c = make_pdmp_constants(p, s);
        return run_samples(trajectories, ctl, [&c, seed, horizon, x0, v0](std::uint64_t k) {
            BatchedUniformRng rng(seed, StreamPurpose::BruteForce, k);
            return pdmp_trajectory(c, x0, v0, horizon, rng);
        });
    }
    const InclusionConstants c = make_inclusion_constants(p, s);
    const double nsteps_real = std::nearbyint(horizon / s.dt);
    if (nsteps_real < 1 || nsteps_real > 1e13) // a stream holds 2^47 random blocks
        throw InvalidParameter("time", "time/dt must be between 1 and 1e13 steps");
    const auto nsteps = static_cast<std::uint64_t>(nsteps_real);
    return run_samples(trajectories, ctl, [&c, seed, x0, v0, nsteps](std::uint64_t k) {
        BatchedCounterRng rng(seed, StreamPurpose::BruteForce, k);
        return inclusion_trajectory(c, x0, v0, nsteps, rng);
    });
}

} // namespace stickslip
