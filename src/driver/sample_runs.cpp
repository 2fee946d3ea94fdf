// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/runner.hpp"

#include <cmath>

#include "driver/block_driver.hpp"
#include "driver/result_checks.hpp"

#include "stickslip/kernels/event_lanes.hpp"
#include "stickslip/kernels/resolvent.hpp"
#include "stickslip/kernels/resolvent_lanes.hpp"
#include "stickslip/kernels/pdmp.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "stickslip/run.hpp"

namespace stickslip {

void check_run_control(const RunControl& ctl) {
    if (ctl.threads > 4096) throw InvalidParameter("threads", "threads must be between 0 and 4096");
}

RunTotals run_samples(std::uint64_t n, const RunControl& ctl,
                      const std::function<ExcursionOutcome(std::uint64_t)>& sample) {
    check_run_control(ctl);
    detail::NoTotal none;
    return detail::run_blocks<detail::NoBlock>(
        n, ctl, [] { return detail::NoBlock{}; }, [&](std::uint64_t k, detail::NoBlock&) { return sample(k); }, none);
}

RunTotals run_long_excursions(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl) {
    const std::uint64_t seed = ctl.seed;
    if (e.settings.engine == Engine::Pdmp) {
        const PdmpConstants& c = e.pdmp;
        return run_samples(excursions, ctl, [&c, seed](std::uint64_t k) {
            BatchedUniformRng rng(seed, StreamPurpose::LongExcursion, k);
            return pdmp_long_excursion(c, rng);
        });
    }
    // Both inclusion schemes run blocks of excursions (in SIMD lanes where vectorised).
    const auto in_blocks = [&](auto&& kernel) {
        detail::NoTotal none;
        return detail::run_blocks<detail::NoBlock>(
            excursions, ctl, [] { return detail::NoBlock{}; },
            [&kernel, seed, cancel = ctl.cancel](std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                                                 detail::NoBlock&) { return kernel(seed, first, count, out, cancel); },
            none);
    };
    if (e.settings.scheme == Scheme::Event) {
        const EventConstants& c = e.event;
        return in_blocks([&c](auto... a) { return event_long_excursions(c, a...); });
    }
    const InclusionConstants& c = e.inclusion;
    return in_blocks([&c](auto... a) { return inclusion_long_excursions(c, a...); });
}

RunTotals run_long_excursions(const ModelParams& p, const EngineSettings& s, std::uint64_t excursions,
                              const RunControl& ctl) {
    check_run_control(ctl);
    return run_long_excursions(prepare_engine(p, s), excursions, ctl);
}

std::uint64_t bruteforce_steps(double horizon, double dt) {
    if (!(horizon / dt >= 1)) throw InvalidParameter("time", "time must be at least one step dt");
    const double nsteps = std::nearbyint(horizon / dt);
    if (nsteps > 1e13) // a stream holds 2^47 random blocks
        throw InvalidParameter("time", "time/dt must be between 1 and 1e13 steps");
    return static_cast<std::uint64_t>(nsteps);
}

RunTotals run_bruteforce(const PreparedEngine& e, double horizon, double x0, double v0, std::uint64_t trajectories,
                         const RunControl& ctl) {
    const std::uint64_t seed = ctl.seed;
    if (e.settings.engine == Engine::Pdmp) {
        const PdmpConstants& c = e.pdmp;
        return run_samples(trajectories, ctl, [&c, seed, horizon, x0, v0](std::uint64_t k) {
            BatchedUniformRng rng(seed, StreamPurpose::BruteForce, k);
            return pdmp_trajectory(c, x0, v0, horizon, rng);
        });
    }
    if (e.settings.scheme == Scheme::Event) {
        const EventConstants& c = e.event;
        const auto at = static_cast<std::uint64_t>(std::llround(horizon / c.leaf));
        return run_samples(trajectories, ctl, [&c, seed, x0, v0, at](std::uint64_t k) {
            BatchedCounterRng rng(seed, StreamPurpose::BruteForce, k);
            BatchedCounterRng ref(seed, StreamPurpose::Refinement, k);
            EventWalk w = event_walk_from(c, x0, v0);
            NoPieceObserver none;
            ExcursionOutcome o;
            o.capped = event_advance_to(c, w, at, rng, ref, none) == EventStatus::Capped;
            o.displacement = w.u;
            o.duration = c.leaf * static_cast<double>(w.t);
            o.work = w.steps + w.midpoints;
            return o;
        });
    }
    const InclusionConstants& c = e.inclusion;
    const std::uint64_t nsteps = bruteforce_steps(horizon, c.h);
    return run_samples(trajectories, ctl, [&c, seed, x0, v0, nsteps](std::uint64_t k) {
        BatchedCounterRng rng(seed, StreamPurpose::BruteForce, k);
        return inclusion_trajectory(c, x0, v0, nsteps, rng);
    });
}

RunTotals run_bruteforce(const ModelParams& p, const EngineSettings& s, double horizon, double x0, double v0,
                         std::uint64_t trajectories, const RunControl& ctl) {
    if (!std::isfinite(horizon) || horizon <= 0)
        throw InvalidParameter("time", "time must be a finite number > 0 (s)");
    detail::check_start(p, x0, v0);
    check_run_control(ctl);
    const PreparedEngine e = prepare_engine(p, s); // e.settings: --dt auto resolved
    if (s.engine == Engine::Inclusion) bruteforce_steps(horizon, e.settings.dt);
    return run_bruteforce(e, horizon, x0, v0, trajectories, ctl);
}

} // namespace stickslip
