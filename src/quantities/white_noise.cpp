// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/white_noise.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/format.hpp"
#include "stickslip/drift_law_quadrature.hpp"
#include "stickslip/fokker_planck.hpp"

namespace stickslip {

namespace {
/// The Fokker-Planck grid's relative accuracy at its default resolution, as
/// measured (fokker_planck.hpp): what a result reports as its discretisation error.
constexpr double fokker_planck_accuracy = 1e-6;
} // namespace

bool is_pure_dry_friction(const ModelParams& p) {
    return !p.has_drift_law() && std::isinf(p.relaxation) && p.bias == 0.0;
}

void validate(const WhiteNoiseRequest& req) {
    ModelParams p = req.params;
    p.tau = 0.0;
    validate(p);
    if (!has_stationary_state(p))
        throw InvalidParameter("bias", "no stationary state: with relaxation inf, |bias| must be < friction");
    if (!std::isfinite(req.v0)) throw InvalidParameter("v0", "v0 must be a finite number (m/s)");
    if (req.times.size() > 100000) throw InvalidParameter("times", "at most 100000 times");
    if (req.velocities.size() > 1000000) throw InvalidParameter("velocities", "at most 1000000 velocities");
    if (req.times.size() * req.velocities.size() > 10000000)
        throw InvalidParameter("velocities", "at most 1e7 (time, velocity) pairs");
    for (double v : req.velocities)
        if (!std::isfinite(v))
            throw InvalidParameter("velocities", "velocities must be finite (m/s), got " + detail::format_number(v));
    for (double t : req.times)
        if (!std::isfinite(t) || t < 0)
            throw InvalidParameter("times", "times must be finite and >= 0 (s), got " + detail::format_number(t));
}

WhiteNoiseResult compute_white_noise(const WhiteNoiseRequest& req) {
    validate(req);
    WhiteNoiseResult out;
    out.request = req;
    out.request.params.tau = 0.0;
    const ModelParams& p = out.request.params;
    if (p.has_static_band())
        out.warnings.push_back(white_noise_static_friction_note());
    if (p.has_drift_law()) {
        // Any law: the stationary quantities by quadrature; the transient
        // Fokker-Planck solver is written for the affine law.
        if (!req.times.empty())
            throw InvalidParameter("times", "transient references (--times) are computed for the affine law only "
                                            "(--relaxation, --bias); for this drift law use `stickslip moments` "
                                            "or `correlation` with --tau 0");
        const DriftLawWhiteNoise law(p);
        out.reference = law.reference();
        out.details = GridDetails{"quadrature of the drift law's interpolant (drift_law_quadrature.hpp)"};
        for (double v : req.velocities) out.stationary_density.push_back(law.density(v));
        return out;
    }
    out.reference = white_noise_reference(p);
    // The stationary references are closed forms; the transient ones too for
    // pure dry friction, else the Fokker-Planck grid.
    out.details = GridDetails{"closed form"};
    if (!req.velocities.empty()) {
        const HayakawaDensity density(p);
        for (double v : req.velocities) out.stationary_density.push_back(density(v));
    }
    if (req.times.empty()) return out;
    out.times = req.times;
    std::vector<double> positive; // times with a transition density (t > 0)
    for (double t : req.times)
        if (t > 0) positive.push_back(t);
    std::vector<std::vector<double>> rows;
    if (is_pure_dry_friction(p)) {
        out.grid().solver = "closed form (Touchette, Van der Straeten and Just 2010, eqs. 2.10, 2.11 and 2.13)";
        for (double t : req.times) {
            out.first_moment.push_back(exact_estimate(dry_friction_first_moment(p, t, req.v0)));
            out.autocorrelation.push_back(exact_estimate(dry_friction_autocorrelation(p, t)));
        }
        if (!req.velocities.empty())
            for (double t : positive) {
                std::vector<double> row;
                for (double v : req.velocities) row.push_back(dry_friction_propagator(p, v, t, req.v0));
                rows.push_back(std::move(row));
            }
    } else {
        const WhiteNoiseFokkerPlanck fp(p);
        GridDetails& g = out.grid();
        g.solver = "fokker-planck (finite volumes, see fokker_planck.hpp)";
        g.lower = fp.lower_velocity();
        g.upper = fp.upper_velocity();
        g.cells = static_cast<std::uint64_t>(std::llround((g.upper - g.lower) / fp.cell_width()));
        // Measured against the closed forms of pure dry friction at the
        // default resolution (fokker_planck.hpp): first moment within 5e-7,
        // autocorrelation 2e-8, density 1e-6 of its peak for t' >= 0.5.
        g.discretisation_error = fokker_planck_accuracy;
        // Each value with the grid's relative discretisation error (a solved value).
        for (double m : fp.first_moment(req.v0, req.times))
            out.first_moment.push_back(solved_estimate(m, g.discretisation_error * std::abs(m)));
        for (double c : fp.autocorrelation(req.times))
            out.autocorrelation.push_back(solved_estimate(c, g.discretisation_error * std::abs(c)));
        if (!req.velocities.empty() && !positive.empty()) rows = fp.density(req.v0, positive, req.velocities);
    }
    if (!req.velocities.empty()) {
        std::size_t k = 0;
        for (double t : req.times) out.transient_density.push_back(t > 0 ? rows[k++] : std::vector<double>{});
    }
    return out;
}

} // namespace stickslip
