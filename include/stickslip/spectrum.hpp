// SPDX-License-Identifier: BSD-3-Clause
// stickslip/spectrum.hpp -- the velocity power spectrum (`stickslip
// spectrum`): S(w) = int over all t of C(t) e^{-i w t} dt, C the stationary
// autocovariance of V, the two-sided convention in which S(0) = D
// (Green-Kubo with the project's D = lim Var U(t)/t).
//
// Why no sampling. C(t) decays on every time scale of the model at once (the
// noise's tau, the relaxation, the slips), so a spectrum from sampled paths
// pays for a window and a resolution before its variance. The Kolmogorov
// engine's generator L gives S(w) = 2 Re <V - M0, (i w - L)^{-1} (V - M0)>
// exactly on each grid: one complex sparse solve per frequency, extrapolated
// over the grids like D (kolmogorov.hpp). With white noise and no drag
// (relaxation inf, the affine law) the resolvent equation is solved in
// closed form on each half line (analytic.hpp: white_noise_spectrum), and the
// command gives that exact reference.
//
// Monte Carlo is not built: the sampling engines are refused with a line that
// says so.
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
#include "stickslip/result_fields.hpp"
#include "stickslip/run.hpp"
#include "stickslip/stats/estimators.hpp"

namespace stickslip {

/// A spectrum request (`stickslip spectrum`): the model, the engine (the
/// kolmogorov engine, its default here) and the angular frequencies.
struct SpectrumRequest : RunSettings {
    static constexpr const char* command = "spectrum"; ///< the CLI subcommand
    SpectrumRequest() { engine.engine = Engine::Kolmogorov; }
    /// Angular frequencies w [rad/s], each finite and >= 0, at most
    /// kolmogorov_max_frequencies; empty: 0 and 0.01, 0.1, 1, 10, 100 over the
    /// time unit noise/friction^2.
    std::vector<double> frequencies;
    /// The target estimated relative error of D for the grids
    /// (KolmogorovSettings::rel_precision; 0: that setting's default). The
    /// spectrum is solved on the grids D's target chooses, with its own
    /// estimated errors.
    double rel_precision = 0.0;
};

/// The request's settings: RunSettings' less those only sampling uses (a
/// solve has no step, lattice, seed or interval level), then --frequencies
/// and --rel-precision.
template <class Visitor>
void visit_settings(SpectrumRequest& r, Visitor&& v) {
    visit_settings(static_cast<RunSettings&>(r), skip_settings(v, {"scheme", "dt", "grid", "lattice-bound", "stop-rule",
                                                                   "white-level", "max-steps", "seed", "level"}));
    v(NumberList{r.frequencies},
      SettingInfo{"frequencies", "rad/s",
                  "angular frequencies w >= 0, comma-separated or lo:hi:n (log-spaced); default: 0 and 0.01, 0.1, 1, "
                  "10, 100 over the time unit noise/friction^2. Each w > 0 costs a complex sparse LU per grid "
                  "(seconds to tens of seconds)"});
    v(r.rel_precision, SettingInfo{"rel-precision", "",
                                   "target estimated relative error of D, which chooses the grids (0: the solver's "
                                   "default, 0.001); each S(w) carries its own estimated error"});
}

/// What compute_spectrum returns; report.hpp writes it. Its details
/// (MethodResult) are a GridDetails: the Kolmogorov solver's grids, or the
/// closed form (white noise without drag).
struct SpectrumResult : MethodResult {
    /// The request, with the frequencies resolved (the default set filled in).
    SpectrumRequest request;
    /// The series, declared in fields() below.
    /// @{
    std::vector<double> frequencies;
    std::vector<Estimate> spectrum;
    /// @}
    /// The Kolmogorov solve (empty for the closed form): D, M0, P(V = 0),
    /// E[t1] of the same grids, their precision and the grids.
    std::optional<KolmogorovResult> solution;
    /// The white-noise references (the closed form only): M0, D, Var(V).
    std::optional<WhiteNoiseReference> reference;
    /// Notes for the user, one sentence each (the solver's remarks, the law).
    std::vector<std::string> warnings;

    /// The series, in report order (result_fields.hpp): each value with its
    /// estimated discretisation error (exact for the closed form).
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = SpectrumResult;
        visit(&S::frequencies, FieldInfo{"frequency", "rad/s", "the angular frequencies w (the request's)", FieldForm::Axis});
        visit(&S::spectrum, FieldInfo{"spectrum", "m^2/s",
                                      "S(w) = int C(t) exp(-i w t) dt over all t, C the stationary autocovariance of "
                                      "V (S(0) = D)"});
    }
};

/// Every check of the request, before any work (InvalidParameter naming the
/// setting): the model, the engine (a sampling engine is refused: Monte Carlo
/// is not built for the spectrum), the frequencies, and the Kolmogorov
/// engine's own checks (white noise only without drag).
void validate(const SpectrumRequest& req);
/// Validates the request and solves the spectrum.
SpectrumResult compute_spectrum(const SpectrumRequest& req);

} // namespace stickslip
