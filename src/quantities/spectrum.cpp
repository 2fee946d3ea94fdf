// SPDX-License-Identifier: BSD-3-Clause
// The velocity power spectrum (`spectrum`; spectrum.hpp explains the methods).
#include "stickslip/spectrum.hpp"

#include <cmath>
#include <stdexcept>

#include "core/format.hpp"
#include "quantities/solved.hpp"
#include "stickslip/analytic.hpp"
#include "stickslip/white_noise.hpp"

namespace stickslip {

namespace {

/// The white-noise case the closed form covers: the affine law without drag.
bool closed_form(const ModelParams& p) { return p.tau == 0 && !p.has_drift_law() && std::isinf(p.relaxation); }

/// The request's frequencies, or the default set (spectrum.hpp) in rad/s.
std::vector<double> resolved_frequencies(const SpectrumRequest& req) {
    if (!req.frequencies.empty()) return req.frequencies;
    const double unit = 1.0 / scales_of(req.params).time;
    std::vector<double> out{0.0};
    for (int k = -2; k <= 2; ++k) out.push_back(unit * std::pow(10.0, k));
    return out;
}

} // namespace

void validate(const SpectrumRequest& req) {
    if (samples(req.engine))
        throw InvalidParameter("engine", "the spectrum is solved by the kolmogorov engine (the default of `spectrum`) "
                                         "or, for white noise without drag, in closed form; no Monte Carlo estimator "
                                         "of it is built: drop --engine " + format_setting(req.engine.engine));
    if (!std::isfinite(req.rel_precision) || req.rel_precision < 0 || req.rel_precision >= 1)
        throw InvalidParameter("rel-precision", "rel-precision must be in [0, 1) (0: the solver's default), got " +
                                                    detail::format_number(req.rel_precision));
    KolmogorovSettings frequencies_only;
    frequencies_only.frequencies = req.frequencies;
    validate(frequencies_only);
    if (req.params.tau == 0) {
        validate(req.engine);
        validate(req.params);
        if (!closed_form(req.params))
            throw InvalidParameter("tau", "with white noise (tau 0) the spectrum is known in closed form without drag "
                                          "only (--relaxation inf, no --drift); give tau > 0: the kolmogorov engine "
                                          "takes every tau > 0, and below tau' = 1e-6 gives the white-noise limit");
        if (!has_stationary_state(req.params))
            throw InvalidParameter("bias", "no stationary state: with relaxation inf, |bias| must be < friction");
        return;
    }
    detail::validate_solved(req, req.rel_precision, resolved_frequencies(req));
}

SpectrumResult compute_spectrum(const SpectrumRequest& req) {
    validate(req);
    SpectrumResult out;
    out.request = req;
    out.request.frequencies = resolved_frequencies(req);
    out.frequencies = out.request.frequencies;
    const ModelParams& p = req.params;
    if (closed_form(p)) {
        if (p.has_static_band()) out.warnings.push_back(white_noise_static_friction_note());
        out.reference = white_noise_reference(p);
        for (double w : out.frequencies) out.spectrum.push_back(exact_estimate(dry_friction_spectrum(p, w)));
        out.details = GridDetails{"closed form (white noise without drag: the resolvent on each half line)"};
        return out;
    }
    out.solution = detail::solve(req, req.rel_precision, out.warnings, out.frequencies);
    out.details = out.solution->details;
    out.spectrum = out.solution->spectrum;
    if (out.spectrum.size() != out.frequencies.size())
        throw std::runtime_error("the Kolmogorov engine was stopped before the spectrum was solved");
    return out;
}

} // namespace stickslip
