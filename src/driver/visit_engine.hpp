// SPDX-License-Identifier: BSD-3-Clause
// Internal: the engine switch, written once.
//
// A prepared engine holds one engine's constants (a std::variant,
// prepared_engine.hpp). visit_engine hands the caller that engine's adapter,
// whose static interface is the same for every engine (EngineAdapter below):
// the caller's code is a generic lambda, compiled once per engine, and the
// choice is made once per run, never per step or per sample. So the kernels
// stay non-virtual and vectorised, and what is specific to an engine (its
// streams, its clock, how it continues a path, what its report notes) lives
// in its adapter, in its own folder, not in the quantities.
//
// Adding an engine: its constants as an alternative of EngineConstants, an
// adapter with this interface in src/engines/<engine>/, and one engine_of
// overload below (ARCHITECTURE.md, "Add an engine").
#pragma once

#include <atomic>
#include <concepts>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "engines/event/event_engine.hpp"
#include "engines/path_point.hpp"
#include "engines/pdmp/pdmp_engine.hpp"
#include "engines/resolvent/resolvent_engine.hpp"
#include "stickslip/prepared_engine.hpp"

namespace stickslip::detail {

/// What every engine adapter offers (engines/<engine>/<engine>_engine.hpp):
///  * work_unit ("steps" | "events"), clock() (its time quantum [s], 0 for
///    continuous time), default_start_noise(params) [s^-1/2],
///    sampling_note(dt) (what a report says of its grid sampling; "" none);
///  * long_excursions(seed, first, count, out, cancel): a block of long
///    excursions, streams (seed, LongExcursion, index);
///  * trajectory(seed, k, x0, v0, horizon): a brute-force trajectory;
///  * sampled_excursion(seed, k, dt, phase, on_v, more), excursion_path(seed,
///    index, every, f), regeneration_point(outcome), clock_times(times,
///    warnings), path_at_times(seed, k, start_x, v0, times, record),
///    path_on_grid(seed, k, x0, v0, every, npoints, f, warnings): its paths,
///    for density, correlation, moments and trajectory.
template <class E>
concept EngineAdapter = requires(const E& e, std::uint64_t n, double t, ExcursionOutcome* out,
                                 const std::atomic<bool>* cancel, const Model& m,
                                 std::vector<std::string>& warnings) {
    { E::work_unit } -> std::convertible_to<const char*>;
    { E::work_per_second } -> std::convertible_to<double>;
    { E::resolution_setting } -> std::convertible_to<const char*>;
    { E::resolution_chosen(EngineSettings{}) } -> std::same_as<bool>;
    { e.clock() } -> std::same_as<double>;
    { e.default_start_noise(m) } -> std::same_as<double>;
    { e.check_step(m, warnings) };
    { E::sampling_note(t) } -> std::same_as<std::string>;
    { e.long_excursions(n, n, n, out, cancel) } -> std::same_as<bool>;
    { e.trajectory(n, n, t, t, t) } -> std::same_as<ExcursionOutcome>;
    { e.clock_times(std::vector<double>{}, warnings) } -> std::same_as<std::vector<double>>;
    { e.regeneration_point(ExcursionOutcome{}) } -> std::same_as<PathPoint>;
};

inline ResolventEngine engine_of(const ResolventConstants& c) { return ResolventEngine(c); }
inline EventEngine engine_of(const EventConstants& c) { return EventEngine(c); }
inline PdmpEngine engine_of(const PdmpConstants& c) { return PdmpEngine(c); }

static_assert(EngineAdapter<ResolventEngine> && EngineAdapter<EventEngine> && EngineAdapter<PdmpEngine>);

/// f(adapter) for the engine e holds; every alternative's f must return the
/// same type. The adapter refers to e's constants: e must outlive it.
template <class F>
decltype(auto) visit_engine(const PreparedEngine& e, F&& f) {
    return std::visit([&f](const auto& c) -> decltype(auto) { return f(engine_of(c)); }, e.constants);
}

} // namespace stickslip::detail
