// SPDX-License-Identifier: BSD-3-Clause
// stickslip/errors.hpp -- what the library throws, in one place.
//
// Every failure a user can meet is one of four kinds, and each front end maps
// a kind to one behaviour: bad input (InvalidParameter: exit status 2, Python
// ValueError subclass), a run that finished but cannot be believed
// (UntrustworthyResult, CappedExcursions: exit status 3), a run cancelled
// (RunCancelled: nothing returned) and a run stopped before it had anything to
// report (RunInterrupted). Kept apart from the requests so that the driver and
// the kernels' callers can throw them without including every request.
#pragma once

/// \file
/// The exceptions of the library. The comment at the top of this header
/// explains the design.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

namespace stickslip {

/// Thrown for invalid input. `parameter()` is the name of the offending
/// parameter as spelled on the command line (e.g. "friction", "dt").
class InvalidParameter : public std::invalid_argument {
public:
    /// `parameter`: the setting's name ("friction"); `message`: the whole
    /// sentence a user reads (what()), which front ends prefix with --parameter.
    InvalidParameter(std::string parameter, const std::string& message)
        : std::invalid_argument(message), parameter_(std::move(parameter)) {}
    /// The offending setting's name, as SettingInfo::name spells it.
    const std::string& parameter() const noexcept { return parameter_; }

private:
    std::string parameter_;
};

/// Thrown when a run was cancelled: RunControl::progress returned false or
/// RunControl::cancel was set. Nothing of the run is returned (compare
/// RunControl::stop, which returns what is done).
struct RunCancelled : std::runtime_error {
    RunCancelled() : std::runtime_error("run cancelled") {}
};

/// Thrown when a run was stopped (RunControl::stop) before it had anything to
/// report (fewer than two samples, or during a pilot run). The checkpoint, if
/// any, still holds the run's state; the command line writes a report that
/// says no estimate exists (to_json(const RunInterrupted&...), report.hpp).
struct RunInterrupted : std::runtime_error {
    /// Stopped before the run proper (preparing it, a pilot run): nothing counted.
    RunInterrupted() : std::runtime_error("stopped before the run had any result (while preparing it)") {}
    /// Stopped with `completed` of `requested` samples done (fewer than 2);
    /// `samples` names them ("excursions", "trajectories").
    RunInterrupted(std::uint64_t done, std::uint64_t asked, std::string what)
        : std::runtime_error(text(done, asked, what)), completed(done), requested(asked), samples(std::move(what)) {}
    std::uint64_t completed = 0; ///< samples completed before the stop (0 or 1)
    std::uint64_t requested = 0; ///< samples asked for (0: unknown, a pilot run)
    std::string samples = "excursions"; ///< what the samples are: "excursions" or "trajectories"

private:
    static std::string text(std::uint64_t done, std::uint64_t asked, const std::string& what) {
        const std::string singular = what.substr(0, what.size() - 1);
        return (done == 0 ? "no " + singular + " completed" : "only 1 " + singular + " completed") +
               " before the stop (" + std::to_string(done) + " of " + std::to_string(asked) + " " + what +
               "): no estimate";
    }
};

/// Thrown when a run finished but its numbers cannot be believed: every
/// excursion ended within its first step (the estimates would be 0/0), or an
/// estimate is not a finite number. The message says why and what to change.
/// The command exits with status 3 on it; Python raises
/// UntrustworthyResultError.
struct UntrustworthyResult : std::runtime_error {
    /// `m`: the message for the user.
    explicit UntrustworthyResult(const std::string& m) : std::runtime_error(m) {}
};

/// Thrown when excursions hit the runaway guard and the request does not
/// allow it, or fewer than 2 completed: an untrustworthy result of one kind.
struct CappedExcursions : UntrustworthyResult {
    /// `m`: the message for the user (how many were capped, what to do).
    explicit CappedExcursions(const std::string& m) : UntrustworthyResult(m) {}
};

} // namespace stickslip
