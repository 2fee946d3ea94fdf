#include "format.hpp"
#include "run_checks.hpp"
#include "stickslip/diffusivity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stickslip/inclusion.hpp"
#include "stickslip/pdmp.hpp"

namespace stickslip {

namespace {

/// Below this many excursions the standard error of D is itself too noisy to
/// trust (U is heavy-tailed); the report says so.
constexpr std::uint64_t kFewExcursions = 5000;

} // namespace

ResolvedEngine resolve_engine(const ModelParams& p, const EngineSettings& s) {
    ResolvedEngine r;
    if (!p.white()) {
        r.upper_threshold = p.upper_threshold();
        r.lower_threshold = p.lower_threshold();
    }
    if (s.engine == Engine::Pdmp) {
        const PdmpConstants c = make_pdmp_constants(p, s);
        r.stop_rule = "exact";
        r.lattice_bound = c.n_max * c.delta;
        r.lattice_points = 2 * c.n_max + 1;
        r.truncated_mass = std::erfc(r.lattice_bound * std::sqrt(p.tau) / std::sqrt(2.0));
        r.jump_rate = c.rate;
    } else {
        const InclusionConstants c = make_inclusion_constants(p, s);
        if (c.white) {
            r.stop_rule = "velocity-levels";
            r.white_level = c.level;
        } else {
            r.stop_rule = to_string(c.rule);
        }
    }
    return r;
}

namespace {

void check_common(const ModelParams& p, const EngineSettings& s, double level) {
    // Building the engine's constants validates the model and both step settings.
    if (s.engine == Engine::Pdmp) make_pdmp_constants(p, s);
    else make_inclusion_constants(p, s);
    normal_quantile_two_sided(level); // validates level
}

} // namespace

namespace detail {

void finish_long_excursion_run(const ModelParams& p, const EngineSettings& s, const ResolvedEngine& resolved,
                               const RunTotals& totals, bool allow_capped, std::vector<std::string>& warnings) {
    const std::uint64_t done = totals.moments.count();
    if (totals.capped > 0) {
        const std::string msg = std::to_string(totals.capped) + " of " + std::to_string(totals.requested) +
                                " excursions hit the runaway guard of " + std::to_string(s.max_work_per_excursion) +
                                (s.engine == Engine::Pdmp ? " events" : " steps") +
                                " and were dropped: the estimates are biased towards short excursions";
        if (!allow_capped) throw CappedExcursions(msg + " (raise --max-steps, or pass --allow-capped)");
        warnings.push_back(msg);
    }
    if (done < 2) throw CappedExcursions("fewer than 2 excursions completed; nothing to estimate");
    if (s.engine == Engine::Pdmp && resolved.truncated_mass > 1e-9)
        warnings.push_back("the pdmp lattice is truncated at L = " + format_number(resolved.lattice_bound) +
                           " s^-1/2 (tau*grid*L < 2): stationary noise mass beyond +-L is " +
                           format_number(resolved.truncated_mass) + "; use a finer grid");
    if (done < kFewExcursions)
        warnings.push_back("only " + std::to_string(done) +
                           " excursions (fewer than 5000): U is heavy-tailed, so the standard errors are "
                           "themselves uncertain; use 10000 or more for reliable intervals");
    const ModelParams nd = to_nondimensional(p);
    if (s.engine == Engine::Pdmp && !p.white())
        warnings.push_back("pdmp mean_duration runs between the lattice points beyond the thresholds: it exceeds the "
                           "continuum E[t1] by a few % (about 12% at tau = 1 s, grid 0.125); halve --grid to see it "
                           "converge. D and M0 are not affected");
    if (p.white())
        warnings.push_back("white noise: mean_duration is the cycle time between the velocity levels +-" +
                           format_number(resolved.white_level) + " m/s, not a stick-slip excursion");
    else if (nd.tau < 0.1 || (s.engine == Engine::Inclusion && s.dt > 0.01 * p.tau))
        warnings.push_back("mean_duration depends on the discretisation and the stop rule when tau' < 0.1 or dt "
                           "is not << tau; report it with that caveat, not as a check");
}

void check_start(double x0, double v0) {
    if (!std::isfinite(v0)) throw InvalidParameter("v0", "v0 must be a finite number (m/s)");
    if (std::isinf(x0)) throw InvalidParameter("x0", "x0 must be a finite number (s^-1/2)");
}

} // namespace detail

void validate(const DiffusivityRequest& req) {
    check_common(req.params, req.engine, req.level);
    if (req.excursions < 2)
        throw InvalidParameter("excursions", "excursions must be >= 2 (got " + std::to_string(req.excursions) + ")");
    if (!std::isfinite(req.rel_precision) || req.rel_precision < 0 || req.rel_precision >= 1)
        throw InvalidParameter("rel-precision", "rel-precision must be in [0, 1) (0 = off), got " +
                                                    detail::format_number(req.rel_precision));
    if (req.rel_precision > 0 && req.max_excursions < req.excursions)
        throw InvalidParameter("max-excursions", "max-excursions must be >= excursions (got " +
                                                     std::to_string(req.max_excursions) + ")");
}

namespace {

std::uint64_t round_up_to_blocks(std::uint64_t n) { return (n + block_size - 1) / block_size * block_size; }

/// Precision on demand (DiffusivityRequest::rel_precision): batches of long
/// excursions at consecutive, block-aligned sample indices until the target.
RunTotals run_to_precision(const DiffusivityRequest& req, PrecisionOutcome& outcome) {
    RunTotals total;
    outcome.target = req.rel_precision;
    outcome.reached = false;
    outcome.batches = 0;
    std::uint64_t batch = std::min(round_up_to_blocks(req.excursions), req.max_excursions);
    std::uint64_t projected = batch;
    for (;;) {
        RunControl ctl = req.control;
        ctl.first_index = req.control.first_index + total.requested;
        if (req.control.progress) {
            ctl.progress = [&](const Progress& p) {
                BivariateMoments merged = total.moments;
                if (p.moments) merged.merge(*p.moments);
                Progress q{total.requested + p.done, projected, total.seconds + p.seconds, &merged};
                return req.control.progress(q);
            };
        }
        const RunTotals t = run_long_excursions(req.params, req.engine, batch, ctl);
        total.moments.merge(t.moments);
        total.requested += t.requested;
        total.capped += t.capped;
        total.work += t.work;
        total.seconds += t.seconds;
        total.threads = t.threads;
        ++outcome.batches;
        if (total.capped > 0 && !req.allow_capped) break; // reported by the caller
        std::uint64_t needed = batch;
        if (total.moments.count() >= 2) {
            const auto est = estimate_long_excursion(total.moments, req.level, req.estimator);
            const double d = est.diffusivity.value;
            outcome.relative_half_width = d > 0 ? (est.diffusivity.hi - d) / d : std::numeric_limits<double>::infinity();
            if (outcome.relative_half_width <= req.rel_precision) {
                outcome.reached = true;
                break;
            }
            // Half-width ~ 1/sqrt(N): N_needed = N (rel/target)^2, with 10% to spare.
            const double n = static_cast<double>(total.moments.count());
            const double ratio = outcome.relative_half_width / req.rel_precision;
            const double more = std::isfinite(ratio) ? n * (1.1 * ratio * ratio - 1.0) : 4.0 * n;
            needed = static_cast<std::uint64_t>(std::clamp(more, 1.0, 4.0 * static_cast<double>(total.requested)));
        }
        if (total.requested >= req.max_excursions) break;
        batch = std::min(round_up_to_blocks(std::max<std::uint64_t>(needed, block_size)),
                         req.max_excursions - total.requested);
        projected = total.requested + batch;
    }
    return total;
}

} // namespace

void validate(const BruteForceRequest& req) {
    check_common(req.params, req.engine, req.level);
    if (!std::isfinite(req.horizon) || req.horizon <= 0)
        throw InvalidParameter("time", "time must be a finite number > 0 (s), got " + detail::format_number(req.horizon));
    if (req.trajectories < 2)
        throw InvalidParameter("trajectories",
                               "trajectories must be >= 2 (got " + std::to_string(req.trajectories) + ")");
    detail::check_start(req.x0, req.v0);
    if (req.engine.engine == Engine::Inclusion && req.horizon / req.engine.dt < 1)
        throw InvalidParameter("time", "time must be at least one step dt");
}

DiffusivityResult compute_diffusivity(const DiffusivityRequest& req) {
    validate(req);
    DiffusivityResult out;
    out.request = req;
    out.resolved = resolve_engine(req.params, req.engine);
    if (req.rel_precision > 0) out.totals = run_to_precision(req, out.precision);
    else out.totals = run_long_excursions(req.params, req.engine, req.excursions, req.control);
    detail::finish_long_excursion_run(req.params, req.engine, out.resolved, out.totals, req.allow_capped,
                                      out.warnings);
    out.estimates = estimate_long_excursion(out.totals.moments, req.level, req.estimator);
    if (req.rel_precision > 0 && !out.precision.reached)
        out.warnings.push_back("precision target not reached: relative half-width " +
                               detail::format_number(out.precision.relative_half_width, 3) + " > " +
                               detail::format_number(req.rel_precision, 3) + " after " +
                               std::to_string(out.totals.requested) + " excursions (--max-excursions)");
    if (req.estimator == Estimator::Paper &&
        (out.estimates.mobility.lo > 0 || out.estimates.mobility.hi < 0))
        out.warnings.push_back("estimator 'paper' (eq. 12) is biased because the mobility is not 0; use 'renewal'");
    return out;
}

BruteForceResult compute_bruteforce(const BruteForceRequest& req) {
    validate(req);
    BruteForceResult out;
    out.request = req;
    out.resolved = resolve_engine(req.params, req.engine);
    out.resolved.stop_rule = "none"; // brute force needs no regeneration test
    double x0 = req.x0;
    if (std::isnan(x0)) {
        if (req.params.white()) x0 = 0.0;
        else if (req.engine.engine == Engine::Pdmp) {
            const PdmpConstants c = make_pdmp_constants(req.params, req.engine);
            x0 = (c.k_plus + 1) * c.delta;
        } else x0 = req.params.upper_threshold();
    }
    out.start_noise = x0;
    out.totals = run_bruteforce(req.params, req.engine, req.horizon, x0, req.v0, req.trajectories, req.control);
    // The inclusion engine simulates a whole number of steps: use the time it
    // actually simulated, and say so when it differs from the request.
    const double simulated = out.totals.moments.mean_y();
    if (std::fabs(simulated - req.horizon) > 1e-9 * req.horizon)
        out.warnings.push_back("time rounded to a whole number of steps: " + detail::format_number(simulated) + " s simulated");
    out.estimates = estimate_bruteforce(out.totals.moments, simulated, req.level);
    out.warnings.push_back("brute force estimates D_t = var U(t)/t, biased against D by O(1/t) (relative bias shrinks "
                           "like E[t1]/t); use `stickslip diffusivity` for an unbiased estimate");
    return out;
}

} // namespace stickslip
