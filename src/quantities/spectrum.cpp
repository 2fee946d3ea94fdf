// SPDX-License-Identifier: BSD-3-Clause
// The velocity power spectrum (`spectrum`; spectrum.hpp explains the methods).
#include "stickslip/spectrum.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>

#include "core/format.hpp"
#include "driver/block_driver.hpp"
#include "driver/result_checks.hpp"
#include "driver/step_check.hpp"
#include "driver/visit_engine.hpp"
#include "quantities/path_sampling.hpp"
#include "quantities/solved.hpp"
#include "stickslip/analytic.hpp"
#include "stickslip/fokker_planck.hpp"
#include "stickslip/prepared_engine.hpp"
#include "stickslip/stats/moment_sums.hpp"
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

/// InvalidParameter ("frequencies") unless each is finite and >= 0, at most
/// kolmogorov_max_frequencies of them (whatever the engine: one limit).
void validate_frequencies(const SpectrumRequest& req) {
    KolmogorovSettings frequencies_only;
    frequencies_only.frequencies = req.frequencies;
    validate(frequencies_only);
}

/// The work of one frequency at one sample of the path (a complex rotation
/// and two complex multiply-adds), in steps of the engine, for the run's
/// predicted duration (detail::predict_run), on the basis of correlation's
/// kLagProductCost (10.9 ns a step): measured on the Fig. 2 case (event
/// scheme, 100000 excursions, 1.7e8 samples, one thread) 19.3, 20.5 and
/// 27.7 s with 1, 5 and 20 frequencies, so 2.6 ns a frequency and sample.
constexpr double kFrequencySampleCost = 0.25;

constexpr double kPi = 3.14159265358979323846;

detail::PathSampling path_sampling(const SpectrumRequest& req, std::size_t frequencies) {
    return {.interval = detail::extra_sampling(req.engine, req.sample_dt),
            .per_sample = kFrequencySampleCost * static_cast<double>(frequencies)};
}

/// Every check of a Monte Carlo spectrum (those of `correlation`'s sampled
/// paths), before any work; returns the prepared engine.
PreparedEngine prepare_sampled(const SpectrumRequest& req_in) {
    const SpectrumRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
    PreparedEngine engine = prepare(static_cast<const RunSettings&>(req));
    validate(static_cast<const ExcursionSettings&>(req));
    if (req.rel_precision != 0)
        throw InvalidParameter("rel-precision", "rel-precision chooses the kolmogorov engine's grids; a Monte Carlo "
                                                "spectrum runs --excursions: drop --rel-precision");
    detail::check_event_sampling(req);
    // Above the sampling grid's Nyquist frequency pi/dt the grid sees an
    // alias of w, not w.
    const double dt = detail::sampling_interval(req.engine, req.sample_dt);
    for (double w : resolved_frequencies(req))
        if (!(w * dt <= kPi))
            throw InvalidParameter("frequencies", "w = " + detail::format_number(w) + " rad/s is above the Nyquist "
                                                  "frequency pi/dt = " + detail::format_number(kPi / dt) +
                                                  " rad/s of the path's sampling interval " +
                                                  detail::format_number(dt) + " s; lower --sample-dt (pdmp, "
                                                  "--scheme event) or --dt, or use the kolmogorov engine");
    detail::check_excursions_can_end(engine, detail::extra_sampling(req.engine, req.sample_dt));
    detail::check_run_duration(engine, req.excursions, req.control,
                               path_sampling(req, resolved_frequencies(req).size()));
    return engine;
}

// One excursion's path functionals at one frequency w, in the layout of its
// RatioMoments (the first two shared by every frequency): the time integrals
// of V and of 1 over the cycle, then G = int V e^{-iwt}, H = int e^{-iwt}
// (real, imaginary), |G|^2, Re(G conj(H)), |H|^2, conj(G) e^{-iw t1},
// conj(H) e^{-iw t1} and 1 - e^{-iw t1}. Every time from the cycle's start.
enum Component : std::size_t {
    kU, kN, kGre, kGim, kHre, kHim, kGG, kGH, kHH, kAGre, kAGim, kAHre, kAHim, kCre, kCim, kComponents
};

/// S(w) from the renewal-reward ratios R of one frequency's components
/// (spectrum.hpp): with M0 = R_U / R_N, F = G - M0 H,
///   S = R_|F|^2 + 2 Re(R_A R_B / R_C), R_A = R_AG - M0 R_AH, R_B = R_G - M0 R_H,
/// R_C the ratio of 1 - e^{-iw t1} (E[t1] cancels), its standard error by
/// the delta method over the 15 ratios.
Estimate regenerative_spectrum(const RatioMoments& m, double level) {
    using C = std::complex<double>;
    auto r = [&m](std::size_t j) { return m.ratio(j); };
    auto rc = [&m](std::size_t re) { return C(m.ratio(re), m.ratio(re + 1)); };
    const double m0 = r(kU) / r(kN);
    const C g = rc(kGre), h = rc(kHre), ag = rc(kAGre), ah = rc(kAHre), c = rc(kCre);
    const C a = ag - m0 * ah, b = g - m0 * h, p = a * b / c;
    const double value = r(kGG) - 2 * m0 * r(kGH) + m0 * m0 * r(kHH) + 2 * p.real();
    // dP = alpha_a dA + alpha_b dB - (P / C) dC; a real component x with
    // dP = beta dx contributes 2 Re(beta) to dS.
    const C alpha_a = b / c, alpha_b = a / c, alpha_c = -p / c;
    const double d_m0 = -2 * r(kGH) + 2 * m0 * r(kHH) + 2 * (alpha_a * -ah + alpha_b * -h).real();
    std::vector<double> grad(kComponents, 0.0);
    grad[kU] = d_m0 / r(kN);
    grad[kN] = -d_m0 * m0 / r(kN);
    grad[kGG] = 1.0;
    grad[kGH] = -2 * m0;
    grad[kHH] = m0 * m0;
    auto complex_terms = [&grad](std::size_t re, C beta) {
        grad[re] += 2 * beta.real();
        grad[re + 1] += -2 * beta.imag(); // d/d(imaginary part): beta * i
    };
    complex_terms(kAGre, alpha_a);
    complex_terms(kAHre, -m0 * alpha_a);
    complex_terms(kGre, alpha_b);
    complex_terms(kHre, -m0 * alpha_b);
    complex_terms(kCre, alpha_c);
    double variance = 0.0;
    for (std::size_t j = 0; j < kComponents; ++j)
        for (std::size_t k = 0; k < kComponents; ++k) variance += grad[j] * grad[k] * m.ratio_covariance(j, k);
    return make_interval(value, std::sqrt(std::fmax(variance, 0.0)), level);
}

/// The Monte Carlo spectrum of `engine`'s long excursions (spectrum.hpp).
template <class Engine>
void sample_spectrum(const Engine& engine, const SpectrumRequest& req, const PreparedEngine& prepared,
                     SpectrumResult& out) {
    using C = std::complex<double>;
    const double dt = detail::sampling_interval(req.engine, req.sample_dt);
    const bool at_steps = samples_at_steps(req.engine); // then sample m is at m dt, else at phase + m dt
    const std::vector<double>& w = out.frequencies;
    const std::size_t nf = w.size();
    const std::uint64_t seed = req.control.seed;
    std::vector<C> rotation(nf);
    for (std::size_t f = 0; f < nf; ++f) rotation[f] = std::polar(1.0, -w[f] * dt);
    // One RatioMoments per frequency (its covariances are all the delta
    // method needs), as one block of the driver.
    struct Block {
        std::vector<RatioMoments> per_frequency;
    };
    struct Total {
        std::vector<ExactRatioSums> per_frequency;
        void add_block(const Block& b) {
            for (std::size_t f = 0; f < per_frequency.size(); ++f) per_frequency[f].add_block(b.per_frequency[f]);
        }
        void merge(const Total& o) {
            for (std::size_t f = 0; f < per_frequency.size(); ++f) per_frequency[f].merge(o.per_frequency[f]);
        }
        std::size_t words() const { return per_frequency.empty() ? 0 : per_frequency.size() * per_frequency[0].words(); }
        void to_words(std::uint64_t* out) const {
            for (const ExactRatioSums& s : per_frequency) out += (s.to_words(out), s.words());
        }
        void assign_words(const std::uint64_t* in) {
            for (ExactRatioSums& s : per_frequency) in += (s.assign_words(in), s.words());
        }
    };
    auto make = [nf] { return Block{std::vector<RatioMoments>(nf, RatioMoments(kComponents, true))}; };
    const std::vector<std::size_t> columns = RatioMoments(kComponents, true).columns();
    Total exact{std::vector<ExactRatioSums>(nf, ExactRatioSums(kComponents, columns))};
    // Per-excursion sums of one path; the phases e^{-iw t} advance by a
    // rotation per sample, recomputed from the time every kRephase samples
    // so that rounding cannot accumulate over a long excursion.
    constexpr std::uint64_t kRephase = 1024;
    struct PathSums {
        std::vector<C> g, h, phase;
        double u = 0.0;
        std::uint64_t n = 0;
    };
    out.monte_carlo().totals = detail::run_blocks<Block>(
        req.excursions, req.control, make,
        [&](std::uint64_t k, Block& acc) {
            thread_local PathSums s;
            s.g.assign(nf, C{});
            s.h.assign(nf, C{});
            s.phase.assign(nf, C{});
            s.u = 0.0;
            s.n = 0;
            const double t0 = at_steps ? 0.0 : detail::sampling_phase(seed, k, dt);
            const ExcursionOutcome o = detail::sampled_excursion(engine, seed, k, dt, t0, [&](double v) {
                if (s.n % kRephase == 0) {
                    const double t = t0 + static_cast<double>(s.n) * dt;
                    for (std::size_t f = 0; f < nf; ++f) s.phase[f] = std::polar(1.0, -w[f] * t);
                }
                for (std::size_t f = 0; f < nf; ++f) {
                    s.g[f] += v * s.phase[f];
                    s.h[f] += s.phase[f];
                    s.phase[f] *= rotation[f];
                }
                s.u += v;
                ++s.n;
            });
            // An excursion shorter than its grid phase has no sample: it still
            // counts, with its duration (the ratios' denominators).
            if (o.capped) return o;
            double y[kComponents];
            y[kU] = s.u * dt;
            y[kN] = static_cast<double>(s.n) * dt;
            for (std::size_t f = 0; f < nf; ++f) {
                const C g = s.g[f] * dt, h = s.h[f] * dt, end = std::polar(1.0, -w[f] * o.duration);
                const C ag = std::conj(g) * end, ah = std::conj(h) * end, c = 1.0 - end;
                y[kGre] = g.real(), y[kGim] = g.imag(), y[kHre] = h.real(), y[kHim] = h.imag();
                y[kGG] = std::norm(g), y[kGH] = (g * std::conj(h)).real(), y[kHH] = std::norm(h);
                y[kAGre] = ag.real(), y[kAGim] = ag.imag(), y[kAHre] = ah.real(), y[kAHim] = ah.imag();
                y[kCre] = c.real(), y[kCim] = c.imag();
                acc.per_frequency[f].add(y, o.duration);
            }
            return o;
        },
        exact);
    detail::finish_long_excursion_run(prepared, out.monte_carlo().totals, req.allow_capped, out.warnings);
    out.estimates = estimate_long_excursion(out.monte_carlo().totals.moments, req.level);
    detail::check_finite(*out.estimates);
    for (std::size_t f = 0; f < nf; ++f) {
        // S(0) is D itself: the run's estimate of it (the same excursions and
        // their exact displacements; the plain estimator, as correlation's D).
        const Estimate e = w[f] == 0 ? out.estimates->diffusivity
                                     : regenerative_spectrum(exact.per_frequency[f].moments(), req.level);
        if (!std::isfinite(e.value) || !std::isfinite(e.error))
            throw std::runtime_error("the Monte Carlo spectrum at w = " + detail::format_number(w[f]) +
                                     " rad/s is not finite; run more --excursions");
        out.spectrum.push_back(e);
    }
    detail::add_sampling_note(engine.sampling_note(dt), out.warnings);
}

} // namespace

void validate(const SpectrumRequest& req) {
    validate_frequencies(req);
    if (samples(req.engine)) {
        prepare_sampled(req);
        return;
    }
    detail::refuse_sampling_settings(req);
    if (!std::isfinite(req.rel_precision) || req.rel_precision < 0 || req.rel_precision >= 1)
        throw InvalidParameter("rel-precision", "rel-precision must be in [0, 1) (0: the solver's default), got " +
                                                    detail::format_number(req.rel_precision));
    if (req.params.tau == 0) {
        validate(req.engine);
        validate(req.params);
        if (req.params.has_drift_law())
            throw InvalidParameter("tau", "with white noise (tau 0) the spectrum is solved for the affine law only "
                                          "(--relaxation, --bias: closed form or Fokker-Planck); for a drift law give "
                                          "tau > 0 (below tau' = 1e-6 the kolmogorov engine gives the white-noise "
                                          "limit), or sample it with --engine inclusion");
        if (!has_stationary_state(req.params))
            throw InvalidParameter("bias", "no stationary state: with relaxation inf, |bias| must be < friction");
        return;
    }
    detail::validate_solved(req, req.rel_precision, resolved_frequencies(req));
}

SpectrumResult compute_spectrum(const SpectrumRequest& req_in) {
    SpectrumResult out;
    out.request = req_in;
    out.request.frequencies = resolved_frequencies(req_in);
    out.frequencies = out.request.frequencies;
    if (samples(req_in.engine)) { // the method, chosen once
        validate_frequencies(req_in);
        const SpectrumRequest req = with_resolved_engine(req_in, PathUse::GridSamples);
        const PreparedEngine prepared = prepare_sampled(req);
        out.request = req;
        out.request.frequencies = out.frequencies;
        out.monte_carlo().engine = prepared.resolved;
        const std::vector<std::string> notes = detail::start_notes(prepared, req.excursions, req.control,
                                                                   path_sampling(req, out.frequencies.size()));
        detail::visit_engine(prepared, [&](const auto& engine) { sample_spectrum(engine, req, prepared, out); });
        out.warnings.insert(out.warnings.begin(), notes.begin(), notes.end());
        return out;
    }
    const SpectrumRequest& req = req_in;
    validate(req);
    const ModelParams& p = req.params;
    if (closed_form(p)) {
        if (p.has_static_band()) out.warnings.push_back(white_noise_static_friction_note());
        out.reference = white_noise_reference(p);
        for (double w : out.frequencies) out.spectrum.push_back(exact_estimate(dry_friction_spectrum(p, w)));
        out.details = GridDetails{"closed form (white noise without drag: the resolvent on each half line)"};
        return out;
    }
    if (p.tau == 0) { // white noise with drag: the velocity's Fokker-Planck chain
        if (p.has_static_band()) out.warnings.push_back(white_noise_static_friction_note());
        out.reference = white_noise_reference(p);
        const WhiteNoiseFokkerPlanck fp(p);
        std::vector<double> error;
        const std::vector<double> values = fp.spectrum(out.frequencies, error);
        // One kind for the series: solved (S(0) = D is the closed form's, its error 0).
        for (std::size_t k = 0; k < values.size(); ++k) out.spectrum.push_back(solved_estimate(values[k], error[k]));
        GridDetails g{"fokker-planck (the resolvent of the velocity's finite-volume chain, see fokker_planck.hpp)"};
        g.lower = fp.lower_velocity();
        g.upper = fp.upper_velocity();
        g.cells = static_cast<std::uint64_t>(std::llround((g.upper - g.lower) / fp.cell_width()));
        out.details = g;
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
