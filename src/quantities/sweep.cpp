// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/sweep.hpp"
#include "stickslip/prepared_engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "core/format.hpp"
#include "driver/result_checks.hpp"
#include "driver/step_check.hpp"
#include "stickslip/analytic.hpp"
#include "stickslip/drift_input.hpp"

namespace stickslip {

namespace {

/// "a, b, c".
std::string join(const std::vector<std::string>& items, const char* separator) {
    std::string s;
    for (const auto& x : items) s += (s.empty() ? "" : separator) + x;
    return s;
}

/// "noise N, tau T", or with --vary "NAME X, noise N, tau T": which point of
/// a sweep (its progress line, and where a point failed).
std::string point_text(const SweepRequest& req, double varied, double noise, double tau) {
    return (req.vary.empty() ? std::string() : req.vary + " " + detail::format_number(varied) + ", ") + "noise " +
           detail::format_number(noise) + ", tau " + detail::format_number(tau);
}

/// " [at noise N, tau T]": where in a sweep a point failed.
std::string at_point(const SweepRequest& req, double varied, double noise, double tau) {
    return " [at " + point_text(req, varied, noise, tau) + "]";
}

constexpr std::size_t kMaxPoints = 1u << 16; // sweep_index_stride * kMaxPoints = 2^56 sample indices

DiffusivityRequest point_request(const SweepRequest& req, double varied, double noise, double tau, std::size_t k) {
    DiffusivityRequest d;
    static_cast<RunSettings&>(d) = req;
    static_cast<ExcursionSettings&>(d) = req;
    d.params.noise = noise;
    d.params.tau = tau;
    if (req.vary == vary_static_friction) d.params.static_friction = varied;
    else if (!req.vary.empty()) d.params.drift_params = drift_params_with(d.params.drift_params, req.vary, varied);
    d.estimator = req.estimator;
    d.control_variate = req.control_variate;
    d.control_variate_pilot = req.control_variate_pilot;
    d.rel_precision = req.rel_precision;
    d.control.first_index = req.control.first_index + k * sweep_index_stride;
    return d;
}

std::vector<double> sorted_unique(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

/// The sorted grid of a sweep and its points' prepared engines (tau-major).
struct PreparedSweep {
    std::vector<double> noises, taus;
    /// The swept drift constant's values, or one NaN without --vary.
    std::vector<double> varied;
    std::vector<PreparedEngine> engines;
    /// With a drift law, how each point's law was made (tau-major as the
    /// points), for the sweep's one note on it: made here, before any point
    /// runs, so that a table file changed during the run cannot lose results.
    std::vector<DriftLawReport> laws;
    /// Points whose engine is prepared again when it runs: the event scheme's
    /// laws per piece of a knots drift law (10 MB and 0.25 s for 1024 pieces)
    /// are checked here and dropped, not kept for every point (a 1000-point
    /// sweep would hold 10 GB).
    std::vector<bool> again;
};

/// Every check of a sweep, once: the grid, then every point as a diffusivity
/// run (the first bad point is named).
PreparedSweep prepare_sweep(const SweepRequest& req) {
    const bool solved = !samples(req.engine);
    if (!solved && req.rel_precision != 0)
        throw InvalidParameter("rel-precision", "a Monte Carlo sweep has no precision mode: --rel-precision is the "
                                                "Kolmogorov engine's target error of D (--engine kolmogorov); set "
                                                "--excursions per point instead");
    if (req.noises.empty()) throw InvalidParameter("noise", "the sweep needs at least one noise value");
    if (req.taus.empty()) throw InvalidParameter("tau", "the sweep needs at least one tau value");
    if (req.vary.empty() && !req.vary_values.empty())
        throw InvalidParameter("vary-values", "--vary-values needs --vary NAME, the constant of --drift they are for");
    if (!req.vary.empty() && req.vary != vary_static_friction) {
        if (req.params.drift.empty())
            throw InvalidParameter("vary", "--vary sweeps a named constant of a --drift expression, or "
                                           "static-friction; there is no --drift for \"" + req.vary + "\"");
        const auto names = drift_expression_constants(req.params.drift);
        if (std::find(names.begin(), names.end(), req.vary) == names.end())
            throw InvalidParameter("vary", "\"" + req.vary + "\" is not a constant of the --drift expression \"" +
                                               req.params.drift + "\"" +
                                               (names.empty() ? std::string(", which has none")
                                                              : " (its constants: " + join(names, ", ") + ")"));
    }
    if (req.vary == vary_static_friction && !std::isnan(req.params.static_friction))
        throw InvalidParameter("static-friction", "--vary static-friction sweeps the static friction: give its "
                                                  "values in --vary-values, not --static-friction");
    if (!req.vary.empty()) {
        if (req.vary_values.empty())
            throw InvalidParameter("vary-values", "--vary " + req.vary + " needs at least one value in --vary-values");
        for (double x : req.vary_values)
            if (!std::isfinite(x))
                throw InvalidParameter("vary-values", "the values of " + req.vary + " must be finite, got " +
                                                          detail::format_number(x));
    }
    const std::size_t values = req.vary_values.empty() ? 1 : req.vary_values.size();
    if (req.noises.size() * req.taus.size() * values > kMaxPoints) {
        // The longest list is the one to shorten (the limit was blamed on
        // --noise whichever made it).
        const char* longest = req.noises.size() >= req.taus.size() ? "noise" : "tau";
        if (values > std::max(req.noises.size(), req.taus.size())) longest = "vary-values";
        throw InvalidParameter(longest, "at most 65536 sweep points (noises x taus" +
                                            std::string(req.vary.empty() ? "" : " x vary-values") + ": " +
                                            std::to_string(req.noises.size()) + " x " +
                                            std::to_string(req.taus.size()) +
                                            (req.vary.empty() ? std::string() : " x " + std::to_string(values)) +
                                            "); --" + longest + " has the most values");
    }
    if (req.excursions > sweep_index_stride) throw InvalidParameter("excursions", "at most 2^40 excursions per point");
    if (req.control.first_index != 0) throw InvalidParameter("first-index", "a sweep starts at sample index 0");
    for (double g : req.noises)
        if (std::isnan(g)) throw InvalidParameter("noise", "noise must be a number, got NaN");
    for (double t : req.taus)
        if (std::isnan(t)) throw InvalidParameter("tau", "tau must be a number, got NaN");
    PreparedSweep out{sorted_unique(req.noises), sorted_unique(req.taus),
                      req.vary.empty() ? std::vector<double>{std::numeric_limits<double>::quiet_NaN()}
                                       : sorted_unique(req.vary_values),
                      {}, {}, {}};
    std::size_t k = 0;
    for (double c : out.varied)
        for (double t : out.taus)
            for (double g : out.noises) {
                // Preparing 65536 points of a knots law takes hours: a
                // signal is obeyed between them (and within one, while its
                // laws are built).
                if (req.control.stop && req.control.stop->load()) throw RunInterrupted();
                try {
                    // A solved point has no engine to prepare: its checks are the solver's.
                    const DiffusivityRequest point = point_request(req, c, g, t, k++);
                    if (solved) {
                        validate(point);
                        if (point.params.has_drift_law()) out.laws.push_back(make_model(point.params).law_report);
                    } else {
                        PreparedEngine& e = out.engines.emplace_back(prepare(point));
                        if (point.params.has_drift_law()) out.laws.push_back(e.model.law_report);
                        out.again.push_back(e.release_storage()); // keep the checks' outcome, not the laws
                    }
                } catch (const InvalidParameter& e) {
                    throw InvalidParameter(e.parameter(), std::string(e.what()) + " (at " + point_text(req, c, g, t) + ")");
                }
            }
    return out;
}

/// The least-squares fit y = sum_k beta_k f_k(x) with weights 1/sigma^2:
/// the coefficients, their standard errors and chi^2 (normal equations,
/// solved by Gaussian elimination: at most three terms).
struct LinearFit {
    std::vector<double> beta, se;
    double chi2 = 0;
};
LinearFit least_squares(const std::vector<std::vector<double>>& f, const std::vector<double>& y,
                        const std::vector<double>& sigma) {
    const std::size_t m = f.size(), n = y.size();
    std::vector<std::vector<double>> a(m, std::vector<double>(m, 0.0)), inv(m, std::vector<double>(m, 0.0));
    std::vector<double> b(m, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        const double w = 1.0 / (sigma[i] * sigma[i]);
        for (std::size_t j = 0; j < m; ++j) {
            b[j] += w * f[j][i] * y[i];
            for (std::size_t k = 0; k < m; ++k) a[j][k] += w * f[j][i] * f[k][i];
        }
    }
    for (std::size_t j = 0; j < m; ++j) inv[j][j] = 1.0;
    for (std::size_t c = 0; c < m; ++c) { // Gauss-Jordan with partial pivoting
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < m; ++r)
            if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
        std::swap(a[c], a[pivot]);
        std::swap(inv[c], inv[pivot]);
        std::swap(b[c], b[pivot]);
        const double d = a[c][c];
        for (std::size_t k = 0; k < m; ++k) a[c][k] /= d, inv[c][k] /= d;
        b[c] /= d;
        for (std::size_t r = 0; r < m; ++r) {
            if (r == c) continue;
            const double factor = a[r][c];
            for (std::size_t k = 0; k < m; ++k) a[r][k] -= factor * a[c][k], inv[r][k] -= factor * inv[c][k];
            b[r] -= factor * b[c];
        }
    }
    LinearFit fit{b, std::vector<double>(m), 0.0};
    for (std::size_t j = 0; j < m; ++j) fit.se[j] = std::sqrt(inv[j][j]);
    for (std::size_t i = 0; i < n; ++i) {
        double model = 0;
        for (std::size_t j = 0; j < m; ++j) model += b[j] * f[j][i];
        fit.chi2 += (y[i] - model) * (y[i] - model) / (sigma[i] * sigma[i]);
    }
    return fit;
}

/// Each point's D over its white-noise value, and per noise (and value)
/// the approach to white noise (SweepWhiteLimit in sweep.hpp).
void add_white_limits(SweepResult& out) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double level = out.request.level;
    const bool solved = out.solved();
    auto spread = [&](double value, double error) {
        return solved ? Estimate{value, error, nan, nan, level, EstimateKind::Solved} : make_interval(value, error, level);
    };
    std::vector<bool> done(out.points.size(), false);
    for (std::size_t first = 0; first < out.points.size(); ++first) {
        if (done[first]) continue;
        const SweepPoint& head = out.points[first];
        std::vector<std::size_t> group; // this noise and value, increasing tau
        for (std::size_t i = first; i < out.points.size(); ++i) {
            const SweepPoint& p = out.points[i];
            const bool same_value = std::isnan(head.varied) ? std::isnan(p.varied) : p.varied == head.varied;
            if (p.noise == head.noise && same_value) group.push_back(i), done[i] = true;
        }
        ModelParams white = point_request(out.request, head.varied, head.noise, 0.0, 0).params;
        const double d_white = white_noise_reference(white).diffusivity;
        const double time_unit = scales_of(white).time;
        std::vector<double> tau_prime, delta, sigma;
        for (std::size_t i : group) {
            SweepPoint& p = out.points[i];
            const double d = p.diffusivity().value, e = p.diffusivity().error;
            p.white_ratio = spread(d / d_white, e / d_white);
            if (p.tau > 0) {
                tau_prime.push_back(p.tau / time_unit);
                delta.push_back(1.0 - d / d_white);
                sigma.push_back(e / d_white);
            }
        }
        if (tau_prime.size() < 2) continue;
        SweepWhiteLimit w;
        w.noise = head.noise;
        w.varied = head.varied;
        w.white_diffusivity = d_white;
        // Where delta crosses 1%, between neighbouring taus.
        for (std::size_t k = 0; k + 1 < tau_prime.size(); ++k)
            if (delta[k] > 0 && delta[k] <= 0.01 && delta[k + 1] > 0.01) {
                const double f = std::log(0.01 / delta[k]) / std::log(delta[k + 1] / delta[k]);
                w.tau_within_percent = time_unit * std::exp(std::log(tau_prime[k]) + f * std::log(tau_prime[k + 1] / tau_prime[k]));
                break;
            }
        std::vector<double> x, logs, log_sigma, ys, ss;
        std::vector<std::vector<double>> terms(3);
        for (std::size_t k = 0; k < tau_prime.size(); ++k) {
            if (!(delta[k] > 3 * sigma[k]) || delta[k] > 0.1) continue;
            x.push_back(std::log(tau_prime[k]));
            logs.push_back(std::log(delta[k]));
            log_sigma.push_back(sigma[k] / delta[k]);
            ys.push_back(delta[k]);
            ss.push_back(sigma[k]);
            terms[0].push_back(std::sqrt(tau_prime[k]));
            terms[1].push_back(tau_prime[k]);
            terms[2].push_back(tau_prime[k] * std::sqrt(tau_prime[k]));
        }
        w.points = static_cast<int>(x.size());
        w.exponent = w.coefficient = w.half_order = w.first_order = w.three_half_order = spread(nan, nan);
        w.chi2_per_dof = nan;
        if (x.size() >= 2) {
            const LinearFit power = least_squares({std::vector<double>(x.size(), 1.0), x}, logs, log_sigma);
            w.exponent = spread(power.beta[1], power.se[1]);
            const double c1 = std::exp(power.beta[0]);
            w.coefficient = spread(c1, c1 * power.se[0]);
            if (x.size() >= 3) w.chi2_per_dof = power.chi2 / static_cast<double>(x.size() - 2);
        }
        if (x.size() >= 4) {
            const LinearFit expansion = least_squares(terms, ys, ss);
            w.half_order = spread(expansion.beta[0], expansion.se[0]);
            w.first_order = spread(expansion.beta[1], expansion.se[1]);
            w.three_half_order = spread(expansion.beta[2], expansion.se[2]);
        }
        out.white_limits.push_back(w);
    }
}

} // namespace

void validate(const SweepRequest& req) { prepare_sweep(req); }

SweepResult compute_sweep(const SweepRequest& req) {
    const PreparedSweep prepared = prepare_sweep(req);
    SweepResult out;
    out.request = req;
    out.request.noises = prepared.noises;
    out.request.taus = prepared.taus;
    if (!req.vary.empty()) out.request.vary_values = prepared.varied;
    // With --dt auto each point has its own step (SweepPoint::dt), none the sweep's.
    if (out.request.engine.dt_auto && has_time_step(out.request.engine))
        out.request.engine.dt = std::numeric_limits<double>::quiet_NaN();
    const auto& noises = out.request.noises;
    const auto& taus = out.request.taus;
    const auto start = std::chrono::steady_clock::now();
    const std::size_t total = noises.size() * taus.size() * prepared.varied.size();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::size_t k = 0;
    // A solved sweep reports whole points to control.progress (sweep.hpp):
    // before each point and after the last.
    auto solved_progress = [&](std::size_t done) {
        if (!req.control.progress) return;
        Progress pr;
        pr.done = done;
        pr.total = total;
        pr.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!req.control.progress(pr)) throw RunCancelled();
    };
    for (double varied : prepared.varied) {
        for (double tau : taus) {
            if (out.interrupted) break;
            const std::size_t first = out.points.size();
            for (double noise : noises) {
                DiffusivityRequest d = point_request(out.request, varied, noise, tau, k);
                d.control.progress =
                    req.point_progress ? req.point_progress(k, total, point_text(req, varied, noise, tau)) : nullptr;
                DiffusivityResult r;
                try {
                    if (out.solved()) {
                        // A stop ends a solved sweep between points, as below.
                        if (req.control.stop && req.control.stop->load()) throw RunInterrupted();
                        solved_progress(k);
                        r = compute_diffusivity(d);
                    } else {
                        r = prepared.again[k] ? compute_diffusivity(d, prepare(d))
                                              : compute_diffusivity(d, prepared.engines[k]);
                    }
                } catch (const CappedExcursions& e) {
                    throw CappedExcursions(std::string(e.what()) + at_point(req, varied, noise, tau));
                } catch (const UntrustworthyResult& e) {
                    throw UntrustworthyResult(std::string(e.what()) + at_point(req, varied, noise, tau));
                } catch (const RunInterrupted&) {
                    if (out.points.empty()) throw;
                    out.interrupted = true; // stopped before this point had a result
                    break;
                }
                SweepPoint p;
                p.noise = noise;
                p.tau = tau;
                p.varied = varied;
                p.warnings = r.warnings;
                if (r.solution) {
                    p.work = grid_span(*r.solution).largest_states;
                    p.seconds = r.solution->seconds;
                    const bool stopped = r.solution->interrupted; // its rounds finished so far
                    p.precision_reached = r.solution->converged;
                    p.solution = std::move(r.solution);
                    out.points.push_back(std::move(p));
                    ++k;
                    if (stopped) {
                        out.interrupted = true;
                        break;
                    }
                    continue;
                }
                out.resumed += r.monte_carlo().totals.resumed;
                p.estimates = r.estimates;
                p.stop_rule = r.monte_carlo().engine.stop_rule;
                p.dt = r.request.engine.dt;
                p.scheme = r.request.engine.scheme;
                p.work = r.monte_carlo().totals.work;
                p.seconds = r.monte_carlo().totals.seconds;
                out.points.push_back(p);
                ++k;
                if (r.monte_carlo().totals.interrupted) {
                    out.interrupted = true;
                    break;
                }
            }
            // Local slopes from the neighbours; errors from the independent
            // standard errors, or for solved points from the discretisation
            // errors (propagated alike, though they are not random: a bound's
            // scale, not a sampling distribution, so no interval).
            const std::size_t n = out.points.size() - first; // all the noises, unless interrupted
            auto d_value = [&](std::size_t i) { return out.points[first + i].diffusivity().value; };
            auto logd = [&](std::size_t i) { return std::log(d_value(i)); };
            auto sig = [&](std::size_t i) { return out.points[first + i].diffusivity().error / d_value(i); };
            auto spread = [&](double value, double error) {
                return out.solved() ? Estimate{value, error, nan, nan, req.level, EstimateKind::Solved}
                                   : make_interval(value, error, req.level);
            };
            for (std::size_t i = 0; i < n; ++i) {
                if (n < 2) {
                    out.points[first + i].slope = spread(nan, nan);
                    continue;
                }
                const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? n - 1 : i + 1;
                const double dx = std::log(noises[b]) - std::log(noises[a]);
                const double s = (logd(b) - logd(a)) / dx;
                const double se = std::hypot(sig(a), sig(b)) / dx;
                out.points[first + i].slope = spread(s, se);
            }
            if (n >= 2) {
                // Weighted least squares of log D on log Gamma.
                double sw = 0, sx = 0, sy = 0;
                for (std::size_t i = 0; i < n; ++i) {
                    const double w = 1 / (sig(i) * sig(i));
                    sw += w;
                    sx += w * std::log(noises[i]);
                    sy += w * logd(i);
                }
                const double xb = sx / sw, yb = sy / sw;
                double sxx = 0, sxy = 0;
                for (std::size_t i = 0; i < n; ++i) {
                    const double w = 1 / (sig(i) * sig(i)), x = std::log(noises[i]) - xb;
                    sxx += w * x * x;
                    sxy += w * x * (logd(i) - yb);
                }
                const double alpha = sxy / sxx;
                double chi2 = 0;
                for (std::size_t i = 0; i < n; ++i) {
                    const double r = (logd(i) - yb - alpha * (std::log(noises[i]) - xb)) / sig(i);
                    chi2 += r * r;
                }
                SweepExponent e;
                e.tau = tau;
                e.varied = varied;
                e.exponent = spread(alpha, std::sqrt(1 / sxx));
                e.points = static_cast<int>(n);
                e.chi2_per_dof = n > 2 ? chi2 / static_cast<double>(n - 2) : nan;
                out.exponents.push_back(e);
            }
        }
    }
    add_white_limits(out);
    if (out.solved() && !out.interrupted) solved_progress(out.points.size());
    if (out.interrupted)
        out.warnings.push_back("interrupted: " + std::to_string(out.points.size()) + " of " + std::to_string(total) +
                               " points have a result (the last from a prefix of its excursions)");
    // Every point has its own knots (the range follows noise and the law):
    // one note for all of them instead of one per point.
    std::optional<DriftLawReport> laws;
    std::string law_suffix;
    for (std::size_t i = 0; i < out.points.size() && i < prepared.laws.size(); ++i) {
        const SweepPoint& p = out.points[i];
        const DriftLawReport& law = prepared.laws[i];
        if (!laws) {
            laws = law;
            const std::string head = drift_law_note(law);
            for (const auto& w : p.warnings)
                if (w.rfind(head, 0) == 0) law_suffix = w.substr(head.size());
        }
        laws->lower = std::min(laws->lower, law.lower);
        laws->upper = std::max(laws->upper, law.upper);
        laws->interpolation_error = std::max(laws->interpolation_error, law.interpolation_error);
    }
    if (laws)
        out.warnings.push_back("drift law (" + laws->source + ") " + laws->text + ": interpolated on " +
                               std::to_string(laws->knots) + " knots over each point's own range (within [" +
                               detail::format_number(laws->lower, 4) + ", " + detail::format_number(laws->upper, 4) +
                               "] m/s), off by at most " + detail::format_number(laws->interpolation_error, 2) +
                               " m s^-2" + law_suffix);
    std::size_t narrow_points = 0; // points whose interval is narrower than the automatic step's check
    double narrowest = 1.0;
    std::size_t flagged_points = 0; // points whose interval of D is flagged
    for (const auto& p : out.points)
        for (const auto& w : p.warnings) {
            if (w.starts_with(detail::precision_note_start)) {
                ++narrow_points;
                narrowest = std::min(narrowest, relative_upper_half_width(p.estimates.diffusivity));
            } else if (w.starts_with(detail::interval_flag_note_start)) {
                ++flagged_points;
            } else if (std::find(out.warnings.begin(), out.warnings.end(), w) == out.warnings.end() &&
                       w.rfind("only ", 0) != 0 && w.rfind("drift law (", 0) != 0)
                out.warnings.push_back(w);
        }
    if (narrow_points > 0) out.warnings.push_back(detail::sweep_precision_note(narrow_points, narrowest));
    if (flagged_points > 0)
        out.warnings.push_back(detail::sweep_interval_flag_note(flagged_points, out.points.size(), interval_flag_tail_index));
    if (req.excursions < 5000 && !out.solved())
        out.warnings.push_back("fewer than 5000 excursions per point: the standard errors (and so the slope errors) "
                               "are themselves uncertain");
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace stickslip
