// SPDX-License-Identifier: BSD-3-Clause
// Internal: the event scheme's step laws, measured (docs/validation.md, "The
// event scheme at coarse steps" and "... at fine steps"): the step --dt auto
// takes and the checks of a step against the scheme's validated reach. Kept
// with the scheme, so that the driver's checks (driver/step_check.hpp) ask the
// engine, not the reverse.
#pragma once

#include <string>
#include <vector>

#include "stickslip/model.hpp"

namespace stickslip::detail {

/// The step [s] --dt auto chooses for the event scheme on model p:
/// min(tau, 4 relaxation, T_f)/16 (coloured), min(T_f, relaxation)/16 (white).
double event_auto_step(const Model& m);

/// The event scheme's step dt [s] on model p against its measured reach
/// (docs/validation.md, "The event scheme at coarse steps" and "... at fine
/// steps"): InvalidParameter ("dt") far beyond it, a note beyond it.
void check_event_step(const Model& m, double dt, std::vector<std::string>& notes);

} // namespace stickslip::detail
