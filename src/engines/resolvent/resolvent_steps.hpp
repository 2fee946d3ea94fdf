// SPDX-License-Identifier: BSD-3-Clause
// Internal: the resolvent scheme's step laws, measured (docs/validation.md,
// "Step checks" and "Choosing the step"): its bias of D in friction times
// T_f = noise/friction^2 (like +0.35 dt' for coloured noise, -0.39 sqrt(dt')
// for white and near-white noise, tau' < 0.3), the step --dt auto takes from
// it, and the checks of a step before a run. Kept with the scheme, so that the
// driver's checks (driver/step_check.hpp) ask the engine, not the reverse.
#pragma once

#include <string>
#include <vector>

#include "stickslip/model.hpp"

namespace stickslip::detail {

/// The predicted relative bias of D of the resolvent scheme at step dt [s] on
/// model p: > 0 when D comes out too high.
double resolvent_bias(const ModelParams& p, double dt);

/// The resolvent step [s] whose predicted relative bias of D is `bias` (> 0),
/// from the law above.
double resolvent_step_for_bias(const ModelParams& p, double bias);

/// The step [s] --dt auto chooses for the resolvent scheme on model p: the
/// bias law's step for 0.1% of D, and at most relaxation/100
/// (stickslip::auto_time_step, run.hpp).
double resolvent_auto_step(const Model& m);

/// The resolvent scheme's step dt [s] on model p against its measured bias
/// law: InvalidParameter ("dt") beyond 20% predicted bias of D or a step
/// longer than the friction time, a note beyond 2% or half a relaxation time.
void check_resolvent_step(const Model& m, double dt, std::vector<std::string>& notes);

} // namespace stickslip::detail
