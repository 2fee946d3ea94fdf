// SPDX-License-Identifier: BSD-3-Clause
// The event scheme's step laws (event_steps.hpp): the automatic step and the
// checks of a step against the scheme's measured reach.
#include "engines/event/event_steps.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "core/format.hpp"
#include "stickslip/model.hpp"
#include "stickslip/errors.hpp"

namespace stickslip::detail {

namespace {

/// Event scheme: dt = min(tau / 16, relaxation / 8, T_f / 16). No bias was
/// seen (1e6 excursions, 0.3% standard errors) up to 0.12 tau, 0.9 relaxation
/// and 0.18 T_f on the Fig. 2 case, and E[t1], M0 flat to 1% up to dt = tau
/// at tau' = 0.1. With the control variate's precision the drag's share was
/// measured (docs/validation.md, "Choosing the step"): D +0.18% +- 0.05% at
/// relaxation/4 against the Kolmogorov engine (the main job), +0.04% +- 0.06%
/// at dt = 0.008 s (1e6 excursions) and +0.06% +- 0.05% at relaxation/8 (the
/// main job since), so relaxation/8 keeps the bias below the 0.1% that --dt
/// auto aims at. (The "no bias seen" above is at 0.3% resolution.)
constexpr double kAutoEventTau = 1.0 / 16, kAutoEventRelaxation = 1.0 / 8, kAutoEventFriction = 1.0 / 16;
/// ... but never finer for the drag than min(tau, T_f)/256: with a drag much
/// faster than the noise V follows the force, and the coloured event scheme
/// integrates the affine pieces exactly; measured (docs/validation.md,
/// "Choosing the step", "A drag much faster than the noise"; 1e5 excursions
/// with the control variate, 0.16% standard errors): at relaxation tau/100
/// D within 0.27% (z <= 1.6) of the Kolmogorov engine at relaxation/8, 0.4
/// and 1.6 relaxation times; at tau/10^4, within 0.3% (z = -1.3) from 10 to
/// 160 relaxation times; --drift '-v*1e6' (dt = 1e-3 s, 2000 relaxation
/// times) within 0.8% of dt = 5e-6 s (z = 0.3).
constexpr double kAutoEventDragFloor = 1.0 / 256;
/// White noise, event scheme: dt = min(T_f / 16, relaxation / 16). Measured
/// (1e6 excursions, docs/validation.md): no bias of D or M0 up to dt = T_f/8
/// without drag; with relaxation 0.2 T_f, D and M0 +0.08% at relaxation/20,
/// -0.35% and -0.9% (z = -1.3, -1.8) at relaxation/8, D -0.7% (z = -2.6) at
/// relaxation/4.
constexpr double kAutoEventWhiteRelaxation = 1.0 / 16;

// The event scheme's measured reach (docs/validation.md, "The event scheme at
// coarse steps"; 1e5 excursions per point against the automatic step, the
// PDMP or the exact quadrature):
//  * coloured noise: flat to dt = tau (E[t1] +1.7% at tau' = 0.1); beyond,
//    E[t1] +3.7% at 3 tau and +25% at 10 tau (tau' = 0.1), M0 -2% at 6 tau
//    and -33% at 20 tau (Fig. 2 case), D 100 times too large at 200 tau;
//    the drag and the friction time set no limit of their own (Fig. 2: D
//    within 1% at 45 relaxation times, 9 friction times);
//  * white noise: D within 1% up to relaxation/4 (-2% at relaxation/2, -6%
//    at 1, -10% at 2, -76% at 15) and M0 to T_f/2 (-1.1%; -2% at T_f, -3.6%
//    at 2 T_f, no drag).
constexpr double kEventTauNote = 1.0, kEventTauRefuse = 8.0;
// The finest steps its tables validate (docs/validation.md, "The event scheme
// at fine steps"): dt/tau = 1e-5 (coloured), 1e-5 friction times (white).
// Finer steps are not known to be wrong, only not shown right: a note.
constexpr double kEventFinestValidated = 1e-5;
constexpr double kEventWhiteRelaxationNote = 0.25, kEventWhiteRelaxationRefuse = 2.0;
constexpr double kEventWhiteFrictionNote = 0.5, kEventWhiteFrictionRefuse = 2.0;

std::string rounded(double x) { return format_number(x, 2); }

} // namespace

double event_auto_step(const Model& m) {
    const ModelParams& p = m.params;
    const Scales sc = scales_of(p);
    double dt = kAutoEventFriction * sc.time;
    if (!p.white()) dt = std::fmin(dt, kAutoEventTau * p.tau);
    // A drift law's own time 1/L (L its Lipschitz constant) in place of the relaxation.
    const double relaxation = m.drift_time_scale();
    if (!std::isfinite(relaxation)) return dt;
    if (p.white()) return std::fmin(dt, kAutoEventWhiteRelaxation * relaxation);
    // Coloured noise: the drag's limit stops at the noise's and the
    // friction's own times over 256 (a stiff law, --drift '-v*1e6', got
    // 1.25e-7 s, 2.5e-7 tau, for 3.5 h where 1e-3 s gives the same D).
    return std::fmin(dt, std::fmax(kAutoEventRelaxation * relaxation, kAutoEventDragFloor * std::fmin(p.tau, sc.time)));
}

void check_event_step(const Model& m, double dt, std::vector<std::string>& notes) {
    const ModelParams& p = m.params;
    const Scales sc = scales_of(p);
    const std::string at = "dt = " + format_number(dt) + " s is ";
    const std::string where = " (measured: docs/validation.md, \"The event scheme at coarse steps\")";
    std::string refuse, note, cure;
    if (!p.white()) {
        const double r = dt / p.tau;
        cure = "use --dt " + rounded(p.tau) + " or smaller (--dt auto: " + rounded(event_auto_step(m)) +
               "), or --engine pdmp";
        const std::string what = at + format_number(r, 3) + " correlation times of the noise (tau = " + format_number(p.tau) + " s)";
        if (r > kEventTauRefuse)
            refuse = what + ": the event scheme's stuck phases and launches are not resolved there (M0 -33% at 20 tau, "
                            "D 100 times too large at 200 tau)";
        else if (r > kEventTauNote)
            note = what + ": beyond the event scheme's validated steps (dt <= tau); E[t1] +3.7% at 3 tau, M0 -2% at "
                          "6 tau";
    } else {
        const double rl = std::isfinite(p.relaxation) ? dt / p.relaxation : 0.0, rf = dt / sc.time;
        const double fine = std::fmin(kEventWhiteFrictionNote * sc.time,
                                      std::isfinite(p.relaxation) ? kEventWhiteRelaxationNote * p.relaxation : HUGE_VAL);
        cure = "use --dt " + rounded(fine) + " or smaller (--dt auto: " + rounded(event_auto_step(m)) + ")";
        const std::string in_relaxation = at + format_number(rl, 3) + " relaxation times (" + format_number(p.relaxation) + " s)";
        const std::string in_friction =
            at + format_number(rf, 3) + " friction times (noise/friction^2 = " + format_number(sc.time) + " s)";
        if (rl > kEventWhiteRelaxationRefuse)
            refuse = in_relaxation + ": the white-noise event scheme's D is 10% low at 2 and 76% low at 15";
        else if (rf > kEventWhiteFrictionRefuse)
            refuse = in_friction + ": beyond the white-noise event scheme's measured steps (M0 -3.6% at 2)";
        else if (rl > kEventWhiteRelaxationNote)
            note = in_relaxation + ": the white-noise event scheme's D is about -2% at 0.5 and -6% at 1";
        else if (rf > kEventWhiteFrictionNote)
            note = in_friction + ": the white-noise event scheme's M0 is about -1% at 0.5 and -2% at 1";
    }
    const double finest = p.white() ? dt / sc.time : dt / p.tau;
    if (refuse.empty() && note.empty() && finest < kEventFinestValidated)
        notes.push_back(at + format_number(finest, 3) + (p.white() ? " friction times" : " correlation times of the noise") +
                        ": finer than the event scheme's validated steps (down to 1e-5; docs/validation.md, \"The "
                        "event scheme at fine steps\"), so not shown right there; a coarser --dt is as accurate and "
                        "cheaper");
    if (!refuse.empty()) throw InvalidParameter("dt", refuse + where + "; " + cure);
    if (!note.empty()) notes.push_back(note + where + "; " + cure);
}

} // namespace stickslip::detail
