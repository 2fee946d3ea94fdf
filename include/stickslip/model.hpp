// SPDX-License-Identifier: BSD-3-Clause
// stickslip/model.hpp -- the model resolved once: the parameters and the one
// drift law they define, passed as data to whatever runs.
//
// ModelParams is what a user types: numbers and, for a general drift law, its
// inputs (an expression, a table, a callable). Everything that runs needs the
// law those inputs define, and what follows from it: b(0), which places the
// static band (the noise thresholds x* and x-*), and the law's time scale,
// which bounds the steps. Making the law parses, reads, checks confinement and
// interpolates, so a run makes it once, in make_model, and hands the Model to
// the engines' constants, the step checks, the Kolmogorov solver and the
// corrector; a sweep makes one per point. A Model is valid by construction
// (make_model validates the parameters), so nothing that takes one validates
// the model again, and a table file rewritten after a run has started changes
// nothing in that run: the run holds the law, not the path.
//
// The functions that take ModelParams (the engines' constants builders, the
// thresholds of params.hpp) remain for callers that hold no Model; each makes
// one (make_drift_law keeps the last laws it made, so that costs little).
#pragma once

/// \file
/// The model resolved once (parameters and drift law). The comment at the top
/// of this header explains the design.

#include <memory>

#include "stickslip/drift_input.hpp"
#include "stickslip/drift_law.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

/// The parameters and the drift law they define, made once by make_model.
struct Model {
    /// The parameters as given (SI units), validated.
    ModelParams params;
    /// The law b(v) [m s^-2] that runs: the affine law -v/relaxation + bias
    /// when params gives no drift law, else its knots (drift_input.hpp).
    /// Shared, so that copies of a Model (a prepared engine's) are cheap and
    /// one law of 16 KiB serves them all, and models of one affine law (a
    /// sweep's points over noise and tau) share it too; never null in a Model
    /// that make_model made.
    std::shared_ptr<const DriftLaw> law;
    /// How `law` was made (source, range, knots, interpolation error, notes).
    DriftLawReport law_report;

    /// b(0) [m s^-2]: the bias for the affine law, the law's value at 0 else.
    double drift_at_zero() const;
    /// Upper noise threshold x* = (friction - b(0)) / sqrt(noise/2) [s^-1/2]:
    /// a stuck object starts up when the noise X exceeds it.
    double upper_threshold() const;
    /// Lower noise threshold x-* = (-friction - b(0)) / sqrt(noise/2) [s^-1/2].
    double lower_threshold() const;
    /// The drift law's own time scale [s]: relaxation for the affine law, 1/L
    /// for another (L its largest slope; +inf for a law without slope). What
    /// the automatic steps and the step checks compare a step with.
    double drift_time_scale() const;
};

/// Validates p (InvalidParameter naming the first bad setting, as
/// validate(p)) and makes its law once. Does not require a stationary state
/// (analytic's closed forms take a drifting object); see
/// require_stationary_state.
Model make_model(const ModelParams& p);

/// Throws InvalidParameter ("bias") when the model has no stationary state (a
/// drift law that makes it had one: make_drift_law refuses a law that does not
/// confine).
void require_stationary_state(const Model& m);

} // namespace stickslip
