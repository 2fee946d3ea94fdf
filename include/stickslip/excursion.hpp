// stickslip/excursion.hpp -- engine settings and the outcome of one long excursion.
//
// A long excursion (MODEL.md section 6) is a +HLE followed by a -HLE, each
// started exactly at its threshold state. Excursions are i.i.d. and are the
// units of the renewal-reward estimators in estimators.hpp. This header holds
// the types shared by both engines; the samplers live in inclusion.hpp and
// pdmp.hpp.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "config.hpp"

namespace stickslip {

enum class Engine { Inclusion, Pdmp };

/// How a time-stepping HLE detects its end (MODEL.md section 6).
///  * Bridge ("rule Q"): stuck at the start of the step and the noise path
///    reaches the opposite threshold during it (endpoint beyond it, or a
///    Brownian-bridge crossing). Flat in dt; the right rule when dt << tau.
///  * Stuck ("rule P"): the object was genuinely stuck during the previous step
///    and the step's force leaves the band the other way. Converges like
///    sqrt(dt/tau); used when dt is not small against tau.
///  * Auto: Bridge when dt <= auto_bridge_ratio * tau, else Stuck.
/// The paper's literal test ("rule A") is biased and deliberately absent.
enum class StopRule { Auto, Bridge, Stuck };

/// dt/tau at or below which StopRule::Auto selects the bridge rule.
inline constexpr double auto_bridge_ratio = 0.1;

std::string to_string(Engine e);
std::string to_string(StopRule r);
Engine parse_engine(const std::string& s);     ///< "inclusion" | "pdmp"
StopRule parse_stop_rule(const std::string& s); ///< "auto" | "bridge" | "stuck"

/// Numerical settings of the engines, SI units.
struct EngineSettings {
    Engine engine = Engine::Inclusion;
    double dt = 1e-4;        ///< time step h of the inclusion engine [s]
    double grid = 0.125;     ///< lattice step delta of the PDMP noise [s^-1/2]
    /// Half-width L of the PDMP lattice [s^-1/2]; 0 chooses it (see pdmp.hpp).
    double lattice_bound = 0.0;
    StopRule stop_rule = StopRule::Auto;
    /// White noise only: the regeneration velocity levels +-c [m/s]; 0 chooses
    /// c = white_level_default(params).
    double white_level = 0.0;
    /// Runaway guard: most steps (inclusion) or events (PDMP) in one long
    /// excursion. An excursion that reaches it is dropped and counted as capped.
    std::uint64_t max_work_per_excursion = 200'000'000;
};

/// Throws InvalidParameter for a non-positive or non-finite dt or grid, a
/// negative lattice bound or white level, or a zero work cap. Both step
/// settings are checked whatever the engine.
void validate(const EngineSettings& s);

/// Outcome of one long excursion (or one brute-force trajectory).
struct ExcursionOutcome {
    double displacement = 0.0; ///< U [m]
    double duration = 0.0;     ///< t [s]
    std::uint64_t work = 0;    ///< steps or events used
    bool capped = false;       ///< hit max_work_per_excursion; U, t meaningless
    double first_half = 0.0;   ///< long excursions: duration of the +HLE [s]
};

} // namespace stickslip
