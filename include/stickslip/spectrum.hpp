// SPDX-License-Identifier: BSD-3-Clause
// stickslip/spectrum.hpp -- the velocity power spectrum (`stickslip
// spectrum`): S(w) = int over all t of C(t) e^{-i w t} dt, C the stationary
// autocovariance of V, the two-sided convention in which S(0) = D
// (Green-Kubo with the project's D = lim Var U(t)/t).
//
// Two methods. The Kolmogorov engine's generator L gives S(w) = 2 Re <V -
// M0, (i w - L)^{-1} (V - M0)> exactly on each grid: one complex sparse solve
// per frequency, extrapolated over the grids like D (kolmogorov.hpp). With
// white noise and no drag (relaxation inf, the affine law) the resolvent
// equation is solved in closed form on each half line (analytic.hpp:
// dry_friction_spectrum), and the command gives that exact reference; with
// white noise and drag, the velocity's Fokker-Planck chain gives it by one
// complex tridiagonal solve per frequency (fokker_planck.hpp).
//
// Monte Carlo (--engine inclusion or pdmp) needs no window and no lag grid:
// the long excursions are i.i.d. cycles of a regenerative process, so the
// periodogram of the whole path splits into each cycle's own transform F =
// int (V - M0) e^{-iwt} dt over the cycle and the cross terms between cycles,
// which sum to a geometric series in phi = E[e^{-iw t1}]:
//   S(w) = (E|F|^2 + 2 Re(E[conj(F) e^{-iw t1}] E[F] / (1 - phi))) / E[t1],
// every expectation a renewal-reward ratio of exact sums (mergeable, bitwise
// for any split), the error by the delta method. The path is seen on the
// sampling grid of `correlation` (a random phase per excursion), so F is a
// Riemann sum: the estimate is that of the sampled path, S(w) plus the
// aliased tail sum_{k != 0} S(w + 2 pi k / dt), negligible for w dt << 1
// (docs/theory.md, section 14). S(0) is the run's D.
#pragma once

/// \file
/// The stationary velocity power spectrum S(w), S(0) = D. The comment at the
/// top of this header explains the design.

#include <optional>
#include <string>
#include <vector>

#include "stickslip/analytic.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/method.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/result_fields.hpp"
#include "stickslip/run.hpp"
#include "stickslip/stats/estimators.hpp"

namespace stickslip {

/// A spectrum request (`stickslip spectrum`): the model, the engine (the
/// kolmogorov engine, its default here; inclusion or pdmp sample long
/// excursions), the angular frequencies and, for Monte Carlo, the excursions.
struct SpectrumRequest : RunSettings, ExcursionSettings {
    static constexpr const char* command = "spectrum"; ///< the CLI subcommand, and a checkpoint's name for it
    static constexpr bool resumable = true; ///< Monte Carlo runs through the block driver: checkpoints, graceful stop
    SpectrumRequest() { engine.engine = Engine::Kolmogorov; }
    /// Angular frequencies w [rad/s], each finite and >= 0, at most
    /// kolmogorov_max_frequencies; empty: 0 and 0.01, 0.1, 1, 10, 100 over the
    /// time unit noise/friction^2.
    std::vector<double> frequencies;
    /// The target estimated relative error of D for the grids
    /// (KolmogorovSettings::rel_precision; 0: that setting's default). The
    /// spectrum is solved on the grids D's target chooses, with its own
    /// estimated errors. The kolmogorov engine only: Monte Carlo runs
    /// --excursions.
    double rel_precision = 0.0;
    /// Monte Carlo: the sampling interval of the path [s] (sample_dt_info); 0 uses engine.dt.
    double sample_dt = 0.0;
};

/// The request's settings: RunSettings', ExcursionSettings', --frequencies,
/// --rel-precision and --sample-dt. The kolmogorov engine refuses the
/// sampling ones given a value (detail::refuse_sampling_settings).
template <class Visitor>
void visit_settings(SpectrumRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), v);
    visit_settings(static_cast<ExcursionSettings&>(r), v);
    v(NumberList{r.frequencies},
      SettingInfo{"frequencies", "rad/s",
                  "angular frequencies w >= 0, comma-separated or lo:hi:n (log-spaced); default: 0 and 0.01, 0.1, 1, "
                  "10, 100 over the time unit noise/friction^2. kolmogorov: each w > 0 costs a complex sparse LU per "
                  "grid (seconds to tens of seconds); Monte Carlo: a few operations per sample of the path"});
    v(r.rel_precision, SettingInfo{"rel-precision", "",
                                   "kolmogorov engine: target estimated relative error of D, which chooses the grids "
                                   "(0: the solver's default, 0.001); each S(w) carries its own estimated error"});
    v(r.sample_dt, sample_dt_info);
}

/// What compute_spectrum returns; report.hpp writes it. Its details
/// (MethodResult) are a GridDetails (the Kolmogorov solver's grids, the
/// closed form of white noise without drag, or the Fokker-Planck chain of
/// white noise with drag) or the Monte Carlo run's.
struct SpectrumResult : MethodResult {
    /// The request, with the frequencies resolved (the default set filled in).
    SpectrumRequest request;
    /// The series, declared in fields() below.
    /// @{
    std::vector<double> frequencies;
    std::vector<Estimate> spectrum;
    /// @}
    /// The Kolmogorov solve (empty for white noise and Monte Carlo): D, M0, P(V = 0),
    /// E[t1] of the same grids, their precision and the grids.
    std::optional<KolmogorovResult> solution;
    /// The white-noise references (tau 0, closed form or Fokker-Planck): M0, D, Var(V).
    std::optional<WhiteNoiseReference> reference;
    /// Monte Carlo only: D, M0 and E[t1] of the same excursions.
    std::optional<LongExcursionEstimates> estimates;
    /// Notes for the user, one sentence each (the solver's remarks, the law).
    std::vector<std::string> warnings;

    /// The series, in report order (result_fields.hpp): each value with its
    /// estimated discretisation error (exact for the closed form), or with
    /// its standard error and interval (Monte Carlo).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = SpectrumResult;
        visit(&S::frequencies, FieldInfo{"frequency", "rad/s", "the angular frequencies w (the request's)", FieldForm::Axis});
        visit(&S::spectrum, FieldInfo{"spectrum", "m^2/s",
                                      "S(w) = int C(t) exp(-i w t) dt over all t, C the stationary autocovariance of "
                                      "V (S(0) = D)"});
    }
};

/// Every check of the request, before any work (InvalidParameter naming the
/// setting): the model, the frequencies, then the kolmogorov engine's own
/// checks (white noise with the affine law only; no sampling setting given) or the
/// Monte Carlo run's (those of `correlation`'s sampled paths).
void validate(const SpectrumRequest& req);
/// Validates the request and solves or samples the spectrum.
SpectrumResult compute_spectrum(const SpectrumRequest& req);

} // namespace stickslip
