// SPDX-License-Identifier: BSD-3-Clause
// stickslip/white_noise.hpp -- every exact white-noise reference for one
// parameter set, in one call (what `stickslip analytic` prints).
//
// Stationary mobility, diffusivity and variance come from the quadrature of
// analytic.hpp for any b(v). Transient quantities at given times, the first
// moment E[V(t) | v0] and the stationary autocorrelation <V(t) V(0)>, use the
// closed forms of Touchette, Van der Straeten and Just (2010) for pure dry
// friction (relaxation inf, bias 0), and otherwise the Fokker-Planck solver of
// fokker_planck.hpp; `method` names which one was used. The same goes for the
// transition density p(v, t | v0) at given velocities (Touchette's (2.10)).
#pragma once

/// \file
/// Every exact white-noise reference for one parameter set in one call
/// (`stickslip analytic`). The comment at the top of this header explains the
/// design.

#include <string>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/method.hpp"
#include "stickslip/params.hpp"
#include "stickslip/result_fields.hpp"
#include "stickslip/stats/estimators.hpp"

namespace stickslip {

/// The exact white-noise references for one parameter set (`stickslip
/// analytic`): no simulation, so no seed, engine or run control.
struct WhiteNoiseRequest {
    static constexpr const char* command = "analytic"; ///< the CLI subcommand, and a checkpoint's name for it
    ModelParams params;        ///< tau is ignored (white noise)
    double v0 = 0.0;           ///< initial velocity of the first moment [m/s]
    std::vector<double> times; ///< t >= 0 [s]; empty: stationary values only
    /// Velocities [m/s] at which to evaluate the stationary (Hayakawa) density
    /// and, for every time t > 0, the transition density p(v, t | v0).
    std::vector<double> velocities;
    /// What asked for the references (the command line, a Python call), as
    /// RunSettings::command_line; not a setting.
    std::string command_line;
};

/// The request's settings: the model's without --tau, then --v0, --times
/// and --velocities.
template <class Visitor>
void visit_settings(WhiteNoiseRequest& r, Visitor&& v) {
    visit_settings(r.params, skip_settings(v, {"tau"}));
    v(r.v0, SettingInfo{"v0", "m/s", "initial velocity of the first moment"});
    v(NumberList{r.times}, SettingInfo{"times", "s", "times t >= 0, comma-separated or lo:hi:n (log-spaced)"});
    v(NumberList{r.velocities, true},
      SettingInfo{"velocities", "m/s",
                  "velocities v, comma-separated or lo:hi:n (n evenly spaced): adds the stationary density p(v) and, "
                  "with --times, the transition density p(v, t | v0) (json)"});
}

/// What compute_white_noise returns; report.hpp writes it.
/// Its details (MethodResult) are a GridDetails: the closed forms, or the
/// Fokker-Planck grid of the transient quantities with its cells, domain and
/// measured accuracy.
struct WhiteNoiseResult : MethodResult {
    /// The request, with params.tau set to 0.
    WhiteNoiseRequest request;
    WhiteNoiseReference reference;       ///< M0 [m/s], D [m^2/s], Var(V) [m^2/s^2]
    /// The series' times and their values, declared in fields() below.
    /// @{
    std::vector<double> times;
    std::vector<Estimate> first_moment;
    std::vector<Estimate> autocorrelation;
    /// @}
    std::vector<double> stationary_density; ///< Hayakawa p(v) [s/m] at request.velocities
    /// p(v, t | v0) [s/m]: one row per time (t = 0 rows are empty: a delta
    /// function), one column per velocity.
    std::vector<std::vector<double>> transient_density;
    /// Notes for the user, one sentence each, reported like every result's;
    /// compute_white_noise currently adds none (exact references).
    std::vector<std::string> warnings;

    /// The series (with times), in report order (result_fields.hpp): each
    /// value exact for a closed form, solved (the grid's relative
    /// discretisation error times the value) for the Fokker-Planck grid, at
    /// the paths of the sampled series (moments' first_moment, correlation's
    /// autocorrelation, keyed "lag").
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = WhiteNoiseResult;
        visit(&S::times, FieldInfo{"time", "s", "the times of the series (the request's)", FieldForm::Axis});
        visit(&S::first_moment, FieldInfo{"first_moment", "m/s", "E[V(t) | V(0) = v0] with white noise"});
        visit(&S::autocorrelation, FieldInfo{"autocorrelation", "m^2/s^2",
                                             "<V(t) V(0)> in the stationary state with white noise (at lag t)",
                                             FieldForm::Value, "lag"});
    }
};

/// True for pure dry friction (relaxation inf, bias 0): closed forms exist.
bool is_pure_dry_friction(const ModelParams& p);

/// Every check of the request (InvalidParameter on the first problem): the
/// model (tau aside) with a stationary state, a finite v0, at most 100000
/// times, each finite and >= 0, at most 1e6 velocities, each finite, and at
/// most 1e7 (time, velocity) pairs.
void validate(const WhiteNoiseRequest& req);
/// Validates the request and computes every reference it asks for.
WhiteNoiseResult compute_white_noise(const WhiteNoiseRequest& req);

} // namespace stickslip
