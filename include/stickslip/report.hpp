// stickslip/report.hpp -- machine- and human-readable reports of results.
//
// The JSON schema is a contract that users script against (documented in
// README.md, section "JSON output"); the Python module's to_dict() is the same object. Infinite
// relaxation is written as the string "inf". Timing lives under "work" so that
// results can be compared with it removed.
#pragma once

#include <string>

#include "bruteforce.hpp"
#include "diffusivity.hpp"
#include "observables.hpp"
#include "sweep.hpp"
#include "white_noise.hpp"

namespace stickslip {

/// One JSON object (pretty-printed with `indent` spaces; -1 for one line).
std::string to_json(const DiffusivityResult& r, int indent = 2);
std::string to_json(const BruteForceResult& r, int indent = 2);

/// Small aligned table with units, physical and nondimensional.
std::string to_table(const DiffusivityResult& r);
std::string to_table(const BruteForceResult& r);

/// CSV: a header line and one row per value (no comment lines, so any CSV
/// reader takes it); warnings are not part of it (the CLI prints them on stderr).
std::string to_csv(const DiffusivityResult& r);
std::string to_csv(const BruteForceResult& r);

std::string to_json(const StationaryDensityResult& r, int indent = 2);
std::string to_table(const StationaryDensityResult& r);
std::string to_csv(const StationaryDensityResult& r); ///< one row per bin, then stuck/below/above rows

std::string to_json(const TransientResult& r, int indent = 2);
std::string to_table(const TransientResult& r);
std::string to_csv(const TransientResult& r); ///< one row per time (with density: per time and bin)

std::string to_json(const CorrelationResult& r, int indent = 2);
std::string to_table(const CorrelationResult& r);
std::string to_csv(const CorrelationResult& r); ///< one row per lag

std::string to_json(const TrajectoryResult& r, int indent = 2);
std::string to_table(const TrajectoryResult& r);
std::string to_csv(const TrajectoryResult& r); ///< path,t,x,mode,v,u

std::string to_json(const WhiteNoiseResult& r, int indent = 2);
std::string to_table(const WhiteNoiseResult& r);
std::string to_csv(const WhiteNoiseResult& r); ///< one row per time (or one row of stationary values)

std::string to_json(const SweepResult& r, int indent = 2);
std::string to_table(const SweepResult& r);
std::string to_csv(const SweepResult& r); ///< one row per (tau, noise) point

} // namespace stickslip
