// SPDX-License-Identifier: BSD-3-Clause
#include "driver/step_check.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>

#include "core/format.hpp"
#include "stickslip/drift_law_quadrature.hpp"
#include "stickslip/stats/run_totals.hpp"
#include "stickslip/threads.hpp"
#include "engines/event/event_steps.hpp"
#include "engines/resolvent/resolvent_steps.hpp"
#include "driver/visit_engine.hpp"

namespace stickslip::detail {

namespace {

constexpr double kNoteSeconds = 60.0; ///< a run predicted to last longer says so before it starts
/// Predicted E[t1] over the OU first-passage bound: measured 1.2 to 2.6 for
/// coloured noise (the bound is 2-3x short).
constexpr double kBoundFactor = 3.0;





/// Two significant digits, written out below a million ("600 steps", "100
/// min", not "6e+02"), in exponent form above.
std::string rounded(double x) {
    if (std::abs(x) >= 10 && std::abs(x) < 1e6) {
        const double unit = std::pow(10.0, std::floor(std::log10(std::abs(x))) - 1);
        return format_number(std::round(x / unit) * unit, 7);
    }
    return format_number(x, 2);
}

/// Phi(u) e^{u^2/2}, without overflow for the u used here (u <= 37).
double integrand(double u) { return 0.5 * std::erfc(-u / std::sqrt(2.0)) * std::exp(0.5 * u * u); }

std::string duration_text(double seconds) {
    if (!std::isfinite(seconds)) return "forever";
    if (seconds < 120) return rounded(seconds) + " s";
    if (seconds < 7200) return rounded(seconds / 60) + " min";
    if (seconds < 2 * 86400) return rounded(seconds / 3600) + " h";
    if (seconds < 2 * 3.156e7) return rounded(seconds / 86400) + " days";
    return rounded(seconds / 3.156e7) + " years";
}

} // namespace

double ou_first_passage_time(double h, double tau) {
    if (!(h > 0)) return 0.0;
    if (h > 37.0) return std::numeric_limits<double>::infinity();
    // Simpson's rule on a grid fine enough for the steep end: the integrand
    // grows like e^{u^2/2}, so 64 h^2 intervals, at least 256.
    const int n = 2 * static_cast<int>(std::ceil(std::max(128.0, 32.0 * h * h)));
    const double step = h / n;
    double sum = integrand(0.0) + integrand(h);
    for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * integrand(k * step);
    return tau * std::sqrt(2.0 * std::numbers::pi) * sum * step / 3.0;
}

double excursion_duration_lower_bound(const Model& m) {
    const ModelParams& p = m.params;
    if (p.white()) return 0.0;
    const double sd = 1.0 / std::sqrt(p.tau); // of the stationary noise X [s^-1/2]
    const double up = std::fabs(m.upper_threshold()) / sd, down = std::fabs(m.lower_threshold()) / sd;
    return 0.5 * (ou_first_passage_time(up, p.tau) + ou_first_passage_time(down, p.tau));
}

double excursion_work_lower_bound(const PreparedEngine& e, double sample_dt) {
    const double t = excursion_duration_lower_bound(e.model);
    // A sample costs about what a step or an event does (the velocity is
    // interpolated and binned), so it counts as one: `density --sample-dt
    // 5e-324` sampled every 5e-324 s and ran for ever.
    const double samples = sample_dt > 0 ? t / sample_dt : 0.0;
    return visit_engine(e, [t](const auto& engine) { return engine.work_for(t); }) + samples;
}







void check_step(const PreparedEngine& e, std::vector<std::string>& notes) {
    visit_engine(e, [&](const auto& engine) { engine.check_step(e.model, notes); });
}

namespace {
/// Why a narrow interval at an automatic step deserves a note (one text for
/// a run and a sweep).
const std::string beyond_step_reason =
    "below the 0.3% to which the automatic steps' bias of D was checked (docs/validation.md, \"Choosing the "
    "step\"; measured more closely, the event scheme's on the Fig. 2 case is +0.06% +- 0.05%), and the interval "
    "does not include the step's bias";
} // namespace

void note_precision_beyond_step(const PreparedEngine& e, bool dt_auto, double relative_half_width,
                                std::vector<std::string>& notes) {
    if (!dt_auto || !(relative_half_width < auto_step_checked_to)) return;
    const bool stepped =
        visit_engine(e, [](const auto& engine) { return std::string_view(engine.resolution_setting) == "dt"; });
    if (!stepped) return;
    notes.push_back(std::string(precision_note_start) + format_number(100 * relative_half_width, 3) + "%, is " +
                    beyond_step_reason + ": --check-dt shows the step's effect (D at twice the step), or a smaller "
                                         "--dt");
}

std::string sweep_precision_note(std::size_t points, double narrowest) {
    return "at " + std::to_string(points) + (points == 1 ? " point" : " points") +
           " D's relative half-width (the narrowest " + format_number(100 * narrowest, 3) + "%) is " +
           beyond_step_reason + ": a run of such a point with --check-dt shows the step's effect";
}

void check_excursions_can_end(const PreparedEngine& e, double sample_dt) {
    const ModelParams& p = e.model.params;
    const EngineSettings& s = e.settings;
    const double work = excursion_work_lower_bound(e, sample_dt);
    const double t = excursion_duration_lower_bound(e.model);
    if (sample_dt > 0 && work >= static_cast<double>(s.max_work_per_excursion) && t / sample_dt >= 0.5 * work)
        throw InvalidParameter("sample-dt", "sampling every " + format_number(sample_dt) + " s, an excursion of at "
                                            "least " + duration_text(t) + " on average takes " +
                                            (std::isfinite(t / sample_dt) ? "about " + rounded(t / sample_dt)
                                                                          : std::string("unboundedly many")) +
                                            " samples, more than --max-steps (" +
                                            std::to_string(s.max_work_per_excursion) +
                                            ") allows: the run could not finish; use a --sample-dt of at least " +
                                            rounded(2 * t / static_cast<double>(s.max_work_per_excursion)) +
                                            " s (0: the engine's step)");
    if (work >= static_cast<double>(s.max_work_per_excursion)) {
        const double sd = p.white() ? 0.0 : std::sqrt(p.tau);
        const double h = std::max(std::fabs(e.model.upper_threshold()), std::fabs(e.model.lower_threshold())) * sd;
        const char* unit = work_unit(s);
        const std::string takes =
            std::isfinite(work) ? "which takes at least " + duration_text(excursion_duration_lower_bound(e.model)) +
                                      " on average, about " + rounded(work) + " " + unit + " per excursion"
                                : std::string("which practically never happens");
        throw InvalidParameter("max-steps", "excursions would mostly hit --max-steps (" +
                                                std::to_string(s.max_work_per_excursion) + " " + unit +
                                                "): to end, an excursion's noise must cross the static band, reaching " +
                                                rounded(h) + " standard deviations, " + takes +
                                                "; raise --max-steps (at most 1.8e13), use a coarser --dt or the pdmp "
                                                "engine, or choose a model whose thresholds are nearer the noise "
                                                "(friction, bias, tau)");
    }
}

RunPrediction predict_run(const PreparedEngine& e, std::uint64_t samples, const RunControl& ctl,
                          const PathSampling& sampling) {
    const ModelParams& p = e.model.params;
    const EngineSettings& s = e.settings;
    RunPrediction r;
    const double friction_time = p.noise / (p.friction * p.friction);
    r.excursion_seconds = std::max(kBoundFactor * excursion_duration_lower_bound(e.model), friction_time);
    // Near-white coloured noise: an excursion ends stuck with the noise past
    // the opposite threshold, which gets rarer as tau' falls; measured (Fig. 2
    // model, --dt auto) 1.67 friction times at tau' = 0.003 and 383 at 3e-6.
    if (!p.white()) {
        const double tau_nd = to_nondimensional(p).tau;
        r.excursion_seconds = std::max(r.excursion_seconds, 1.67 * friction_time * std::pow(tau_nd / 0.003, -0.79));
    } else if (e.resolved.white_level > 0) {
        // White noise: E[t1] exactly, the commute time between the levels -c
        // and +c (the pure dry friction's 2.028 friction times at c' = 0.35
        // against 2.030 +- 0.005 measured). A law that rarely brings V back
        // to 0 (--tau 0 --drift '10-v': 7500 s, 3e9 resolvent steps an
        // excursion) was predicted at one friction time and started unnoted.
        const double c = e.resolved.white_level;
        r.excursion_seconds = DriftLawWhiteNoise(p).commute_time(-c, c);
    }
    const double t = r.excursion_seconds + sampling.continued;
    const double steps = visit_engine(e, [t](const auto& engine) { return engine.work_for(t); });
    // The samples' own work: a unit each beyond the steps (every interval),
    // and per_sample more each, wherever they are taken (at the steps when
    // there is no interval).
    const double every_interval = sampling.interval > 0 ? t / sampling.interval : 0.0;
    const double sampled = every_interval + sampling.per_sample * (sampling.interval > 0 ? every_interval : steps);
    r.work = steps + sampled;
    // The engine's own rate (a sample every sample_dt costs about a step).
    const double rate = visit_engine(e, [](const auto& engine) { return engine.work_per_second; });
    const unsigned wanted = ctl.threads ? ctl.threads : default_threads().threads;
    const std::uint64_t blocks = (samples + block_size - 1) / block_size;
    r.threads = static_cast<unsigned>(std::clamp<std::uint64_t>(blocks, 1, std::max(wanted, 1u)));
    r.seconds = r.work * static_cast<double>(samples) / rate / r.threads;
    // What makes it long: the samples, a single excursion's cost, or their number.
    const ModelParams model_defaults;
    const char* resolution = visit_engine(e, [](const auto& engine) { return engine.resolution_setting; });
    const bool resolution_chosen = visit_engine(e, [&s](const auto& engine) { return engine.resolution_chosen(s); });
    // The samples are to blame only when the steps alone would not be long.
    const bool long_without_samples = steps * static_cast<double>(samples) / rate / r.threads > hopeless_seconds;
    if (sampled > steps && !long_without_samples) r.cause = sampling.interval > 0 ? "sample-dt" : "lags";
    else if (r.work / rate < 1.0 && samples > 1000) r.cause = "excursions";
    else if (resolution_chosen || p.white()) r.cause = resolution; // (white noise: tau = 0 is the model)
    else if (p.tau != model_defaults.tau) r.cause = "tau";
    else if (p.friction != model_defaults.friction) r.cause = "friction";
    else if (p.noise != model_defaults.noise) r.cause = "noise";
    else r.cause = resolution;
    return r;
}

void check_run_duration(const PreparedEngine& e, std::uint64_t samples, const RunControl& ctl,
                        const PathSampling& sampling) {
    const RunPrediction r = predict_run(e, samples, ctl, sampling);
    if (!(r.seconds > hopeless_seconds)) return;
    // Long only by the number asked for (each excursion is short): not
    // hopeless. A signal stops it at any time with the result so far, and a
    // checkpoint extends it; note_cost says how long it will take.
    if (r.cause == "excursions") return;
    throw InvalidParameter(r.cause, "this run would take about " + duration_text(r.seconds) + " on " +
                                        std::to_string(r.threads) + (r.threads == 1 ? " thread" : " threads") +
                                        " (predicted: " + std::to_string(samples) + " excursions of about " +
                                        rounded(r.work) + " " + work_unit(e.settings) + " each, E[t1] ~ " +
                                        duration_text(r.excursion_seconds) +
                                        "), more than two days: refused; change --" + r.cause +
                                        ", or run fewer --excursions (with --checkpoint, and --resume to extend)");
}

void note_cost(const PreparedEngine& e, std::uint64_t samples, const RunControl& ctl,
               std::vector<std::string>& notes, const PathSampling& sampling) {
    const RunPrediction r = predict_run(e, samples, ctl, sampling);
    if (!(r.seconds >= kNoteSeconds)) return;
    notes.push_back("a long run: predicted about " + duration_text(r.seconds) + " on " + std::to_string(r.threads) +
                    (r.threads == 1 ? " thread" : " threads") + " (" + std::to_string(samples) +
                    " excursions of about " + rounded(r.work) + " " + work_unit(e.settings) +
                    " each; the prediction is good to a factor of 3); --checkpoint FILE keeps it safe");
    if (r.seconds >= long_run_seconds && ctl.long_run) ctl.long_run(notes.back());
}

} // namespace stickslip::detail
