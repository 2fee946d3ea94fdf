// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/sample_runs.hpp"

#include <cmath>
#include <concepts>
#include <type_traits>

#include "driver/block_driver.hpp"
#include "driver/result_checks.hpp"

#include "driver/visit_engine.hpp"
#include "stickslip/prepared_engine.hpp"

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
    // Blocks of excursions (in SIMD lanes where the engine vectorises them).
    return detail::visit_engine(e, [&](const auto& engine) {
        detail::NoTotal none;
        return detail::run_blocks<detail::NoBlock>(
            excursions, ctl, [] { return detail::NoBlock{}; },
            [&engine, seed, cancel = ctl.cancel](std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                                                 detail::NoBlock&) {
                return engine.long_excursions(seed, first, count, out, cancel);
            },
            none);
    });
}

namespace {
/// Whether an engine adapter has the martingale kernel.
template <class Engine>
concept HasMartingale = requires(const Engine& e, ExcursionOutcome* out, const CorrectorTable& g) {
    { e.long_excursions_with(0, 0, 0, out, nullptr, g) } -> std::same_as<bool>;
};
} // namespace

bool engine_has_martingale(const PreparedEngine& e, std::string* why) {
    return detail::visit_engine(e, [&](const auto& engine) {
        if constexpr (HasMartingale<std::decay_t<decltype(engine)>>) {
            // An adapter may lack it for some constants (no_martingale says why).
            if constexpr (requires { engine.no_martingale(); }) {
                if (const char* reason = engine.no_martingale()) {
                    if (why) *why = reason;
                    return false;
                }
            }
            return true;
        } else {
            if (why) *why = "this engine has no martingale kernel";
            return false;
        }
    });
}

RunTotals run_long_excursions(const PreparedEngine& e, std::uint64_t excursions, const RunControl& ctl,
                              const CorrectorTable& g, const InfluenceCentres* centres) {
    if (!engine_has_martingale(e)) throw std::logic_error("run_long_excursions: this engine has no martingale");
    const std::uint64_t seed = ctl.seed;
    return detail::visit_engine(e, [&](const auto& engine) {
        ControlVariateSums total;
        RunTotals t;
        if constexpr (HasMartingale<std::decay_t<decltype(engine)>>) {
            t = detail::run_blocks<ControlVariateBlock>(
                excursions, ctl, [centres] { return ControlVariateBlock{centres}; },
                [&engine, &g, seed, cancel = ctl.cancel](std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                                                          ControlVariateBlock& block) {
                    if (!engine.long_excursions_with(seed, first, count, out, cancel, g)) return false;
                    for (std::uint64_t i = 0; i < count; ++i) // in index order, as the driver adds (U, t)
                        if (!out[i].capped)
                            block.add(out[i].displacement, out[i].duration, out[i].martingale,
                                      out[i].martingale * out[i].martingale - out[i].martingale_qv);
                    return true;
                },
                total);
        }
        t.control_variate = std::move(total);
        return t;
    });
}

RunTotals run_long_excursions(const ModelParams& p, const EngineSettings& s, std::uint64_t excursions,
                              const RunControl& ctl) {
    check_run_control(ctl);
    return run_long_excursions(prepare_engine(p, s), excursions, ctl);
}

RunTotals run_bruteforce(const PreparedEngine& e, double horizon, double x0, double v0, std::uint64_t trajectories,
                         const RunControl& ctl) {
    const std::uint64_t seed = ctl.seed;
    return detail::visit_engine(e, [&](const auto& engine) {
        return run_samples(trajectories, ctl, [&engine, seed, horizon, x0, v0](std::uint64_t k) {
            return engine.trajectory(seed, k, x0, v0, horizon);
        });
    });
}

RunTotals run_bruteforce(const ModelParams& p, const EngineSettings& s, double horizon, double x0, double v0,
                         std::uint64_t trajectories, const RunControl& ctl) {
    if (!std::isfinite(horizon) || horizon <= 0)
        throw InvalidParameter("time", "time must be a finite number > 0 (s)");
    detail::check_start(p, x0, v0);
    check_run_control(ctl);
    const PreparedEngine e = prepare_engine(p, s); // e.settings: --dt auto resolved
    if (has_time_step(s)) bruteforce_steps(horizon, e.settings.dt);
    return run_bruteforce(e, horizon, x0, v0, trajectories, ctl);
}

} // namespace stickslip
