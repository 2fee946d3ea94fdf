// SPDX-License-Identifier: BSD-3-Clause
// stickslip/report.hpp -- machine- and human-readable reports of results.
//
// The JSON schema is a contract that users script against (documented in
// README.md, section "JSON output"); the Python module's to_dict() is the same object.
// Every output says what produced it: the JSON's "command" and "settings"
// (before "version" and "revision"), the CSV's '#' lines (report/common.hpp). Infinite
// relaxation is written as the string "inf". Timing lives under "work" so that
// results can be compared with it removed.
#pragma once

/// \file
/// JSON, table and CSV reports of every result. The comment at the top of this
/// header explains the design.

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/bruteforce.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/params.hpp"
#include "stickslip/result_fields.hpp"
#include "stickslip/stats/run_totals.hpp"
#include "stickslip/spectrum.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/white_noise.hpp"

namespace stickslip {

/// A report's results in the model's own units (the "nondimensional" block:
/// each value over its scale, Scales), after the parameters' nondimensional
/// values; each written when the report has it (a sweep point's tau, brute
/// force's horizon, the long excursions' E[t1], analytic's Var(V)).
struct NondimensionalValues {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    double tau = std::numeric_limits<double>::quiet_NaN();
    double time = std::numeric_limits<double>::quiet_NaN();
    double diffusivity = std::numeric_limits<double>::quiet_NaN();
    double mobility = std::numeric_limits<double>::quiet_NaN();
    double mean_duration = std::numeric_limits<double>::quiet_NaN();
    double variance = std::numeric_limits<double>::quiet_NaN();
    /// @}

    /// D [m^2/s], M0 [m/s] and E[t1] [s] (NaN: none) over the scales.
    static NondimensionalValues of(const Scales& sc, double diffusivity, double mobility, double mean_duration) {
        NondimensionalValues v;
        v.diffusivity = diffusivity / sc.diffusivity;
        v.mobility = mobility / sc.velocity;
        v.mean_duration = mean_duration / sc.time;
        return v;
    }

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = NondimensionalValues;
        visit(&S::tau, FieldInfo{"tau", "",
                                 "tau over the time scale (a sweep point's here; a run's is among its parameters')",
                                 FieldForm::WhenSet});
        visit(&S::time, FieldInfo{"time", "", "brute force's horizon over the time scale", FieldForm::WhenSet});
        visit(&S::diffusivity, FieldInfo{"diffusivity", "", "D over the diffusivity scale", FieldForm::WhenSet});
        visit(&S::mobility, FieldInfo{"mobility", "", "M0 over the velocity scale", FieldForm::WhenSet});
        visit(&S::mean_duration,
              FieldInfo{"mean_duration", "", "E[t1] over the time scale", FieldForm::WhenSet});
        visit(&S::variance,
              FieldInfo{"variance", "", "Var(V) over the velocity scale squared", FieldForm::WhenSet});
    }
};

/// The "work" block of a report: what the run cost. Filled by the report
/// writer from a run's totals (RunTotals), a solve's (KolmogorovResult) or a
/// sweep's; each report writes the fields it has (the count under its unit:
/// steps, events or grid states; the others left out or unset).
struct RunWork {
    /// The fields, each one's unit and meaning declared in fields() below.
    /// @{
    std::uint64_t steps = 0;
    std::uint64_t events = 0;
    std::uint64_t states = 0;
    double seconds = 0.0;
    std::uint64_t threads = 0;
    std::string threads_from;
    std::uint64_t resumed_samples = 0;
    double corrector_seconds = std::numeric_limits<double>::quiet_NaN();
    /// @}

    /// The count a report's unit names: "events" or "states", else steps.
    std::uint64_t& count_in(std::string_view unit) {
        return unit == "events" ? events : unit == "states" ? states : steps;
    }

    /// The fields, in report order (result_fields.hpp).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = RunWork;
        visit(&S::steps, FieldInfo{"steps", "", "time steps taken, all samples (the inclusion engine)",
                                   FieldForm::Optional});
        visit(&S::events, FieldInfo{"events", "", "events simulated, all samples (the pdmp engine)",
                                    FieldForm::Optional});
        visit(&S::states, FieldInfo{"states", "", "a sweep point's largest grid, in states (engine kolmogorov)",
                                    FieldForm::Optional});
        visit(&S::seconds, FieldInfo{"seconds", "s", "wall time; a resumed run counts only its own invocation"});
        visit(&S::threads, FieldInfo{"threads", "", "worker threads used", FieldForm::WhenSet});
        visit(&S::threads_from, FieldInfo{"threads_from", "", threads_from_help, FieldForm::WhenSet});
        visit(&S::resumed_samples, FieldInfo{"resumed_samples", "",
                                             "samples restored from a checkpoint (--resume) rather than computed",
                                             FieldForm::WhenSet});
        visit(&S::corrector_seconds,
              FieldInfo{"corrector_seconds", "s",
                        "wall time spent making the control variate's corrector (about 0 when the process had made "
                        "it for the same model already)",
                        FieldForm::WhenSet});
    }
};

/// Throws UntrustworthyResult when the JSON report `json` (what to_json
/// writes) holds a number that is not finite (written as null) outside its
/// "params" and "nondimensional" blocks and a sweep's fits (null where too
/// few points define them), naming the first such quantity by
/// its JSON path: no NaN or inf is ever reported as a result. The CLI checks
/// every result this way before writing it, in every format.
void check_finite_result(const std::string& json);

/// One JSON object (pretty-printed with `indent` spaces; -1 for one line).
std::string to_json(const DiffusivityResult& r, int indent = 2);
/// The brute-force result as one JSON object (as for DiffusivityResult).
std::string to_json(const BruteForceResult& r, int indent = 2);

/// Small aligned table with units, physical and nondimensional.
std::string to_table(const DiffusivityResult& r);
/// The brute-force result as a table with units, physical and nondimensional.
std::string to_table(const BruteForceResult& r);

/// CSV: '#' comment lines of provenance (version, revision, command, seed,
/// every setting as a config line), a header line and one row per value,
/// every number with all its digits (the shortest round-trip text); warnings
/// are not part of it (the CLI prints them on stderr).
std::string to_csv(const DiffusivityResult& r);
/// The brute-force result as CSV (as for DiffusivityResult).
std::string to_csv(const BruteForceResult& r);

/// The stationary density as one JSON object (`indent` as above).
std::string to_json(const DensityResult& r, int indent = 2);
/// The stationary density as a table: one row per bin, then P(V = 0), the
/// mass outside the range, the mean, the variance and D.
std::string to_table(const DensityResult& r);
std::string to_csv(const DensityResult& r); ///< one row per bin, then stuck/below/above rows

/// The transient statistics as one JSON object (`indent` as above).
std::string to_json(const MomentsResult& r, int indent = 2);
/// The transient statistics as a table, one row per time.
std::string to_table(const MomentsResult& r);
std::string to_csv(const MomentsResult& r); ///< one row per time (with density: per time and bin)

/// The autocorrelation as one JSON object (`indent` as above).
std::string to_json(const CorrelationResult& r, int indent = 2);
/// The autocorrelation as a table, one row per lag.
std::string to_table(const CorrelationResult& r);
std::string to_csv(const CorrelationResult& r); ///< one row per lag

/// The sample paths as one JSON object (`indent` as above).
std::string to_json(const TrajectoryResult& r, int indent = 2);
/// The sample paths as a table, one row per recorded point.
std::string to_table(const TrajectoryResult& r);
std::string to_csv(const TrajectoryResult& r); ///< path,t,x,mode,v,u

/// The white-noise references as one JSON object (`indent` as above).
std::string to_json(const WhiteNoiseResult& r, int indent = 2);
/// The white-noise references as a table: stationary values, then one row
/// per time.
std::string to_table(const WhiteNoiseResult& r);
std::string to_csv(const WhiteNoiseResult& r); ///< one row per time (or one row of stationary values)

/// The velocity spectrum as one JSON object (`indent` as above): the
/// solve's D, M0 (and for the Kolmogorov engine P(V = 0), E[t1], precision
/// and grids), then `frequency` and `spectrum` arrays.
std::string to_json(const SpectrumResult& r, int indent = 2);
/// The velocity spectrum as a table: the stationary values, then one row
/// per frequency.
std::string to_table(const SpectrumResult& r);
std::string to_csv(const SpectrumResult& r); ///< one row per frequency

/// The sweep as one JSON object (`indent` as above).
std::string to_json(const SweepResult& r, int indent = 2);
/// The sweep as a table, one row per point, then the exponents per tau.
std::string to_table(const SweepResult& r);
std::string to_csv(const SweepResult& r); ///< one row per (tau, noise) point

/// @name A run stopped before it had anything to estimate
/// What the command line writes when RunInterrupted is thrown by a run on the
/// block driver (a signal before its first block finished): the command, "result":
/// "no excursion completed" (or "only 1 ..."), the counts, "interrupted": true,
/// the warnings, the version; no estimate, so no number stands in for one.
/// `command` is the subcommand's name ("diffusivity").
/// @{
std::string to_json(const RunInterrupted& e, const char* command, const std::vector<std::string>& warnings,
                    int indent = 2);
std::string to_table(const RunInterrupted& e, const char* command, const std::vector<std::string>& warnings);
std::string to_csv(const RunInterrupted& e, const char* command); ///< a header and one row
/// @}

} // namespace stickslip
