// SPDX-License-Identifier: BSD-3-Clause
// Construction of the event scheme's per-run constants: the exact laws of a
// step and of its midpoint at every refinement depth.
#include "stickslip/kernels/event_scheme.hpp"

#include <cmath>

#include "core/format.hpp"
#include "stickslip/model.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/kernels/resolvent.hpp"

namespace stickslip {

namespace {

/// The laws of every piece of the knots law b and every depth (steps h / 2^d).
/// A set `stop` ends it (RunInterrupted) between pieces: a 2049-knot law of a
/// wide range takes seconds, and a signal is to be obeyed within one.
std::vector<EventDriftPiece> drift_pieces(const DriftLaw& b, const ModelParams& p, double h, double amp,
                                          const std::atomic<bool>* stop) {
    std::vector<EventDriftPiece> out(static_cast<std::size_t>(b.pieces()));
    for (int j = 0; j < b.pieces(); ++j) {
        if (stop && stop->load(std::memory_order_relaxed)) throw RunInterrupted();
        EventDriftPiece& q = out[static_cast<std::size_t>(j)];
        const double slope = b.piece_slope(j);
        q.inv_relaxation = -slope;
        q.intercept = b.piece_intercept(j);
        q.lower = b.piece_lower(j);
        q.upper = b.piece_upper(j);
        for (int d = 0; d <= event_depth; ++d) {
            const double len = std::ldexp(h, -d);
            q.lv[d].slide = colored_piece_law(p.tau, slope, amp, len);
            q.lv[d].mid = colored_piece_bridge(p.tau, slope, amp, len);
            q.lv[d].v_mid_sd = std::sqrt(q.lv[d].mid.cov[1][1]);
        }
    }
    return out;
}

} // namespace

EventConstants make_event_constants(const ModelParams& p, const EngineSettings& s,
                                    std::shared_ptr<const std::vector<EventDriftPiece>>* pieces,
                                    const std::atomic<bool>* stop) {
    return make_event_constants(make_model(p), s, pieces, stop);
}

EventConstants make_event_constants(const Model& m, const EngineSettings& s,
                                    std::shared_ptr<const std::vector<EventDriftPiece>>* pieces,
                                    const std::atomic<bool>* stop) {
    const ModelParams& p = m.params;
    validate(s);
    require_stationary_state(m);
    if (p.has_drift_law() && p.white())
        throw InvalidParameter("scheme", "the white-noise event scheme takes the affine drift law only (--relaxation, "
                                         "--bias); with --drift or --drift-table use --scheme resolvent");
    if (p.has_drift_law() && !pieces)
        throw InvalidParameter("scheme", "the event scheme's laws of a knots drift law need a place to live "
                                         "(make_event_constants without `pieces`)");
    EventConstants c{};
    c.h = s.dt;
    c.leaf = std::ldexp(s.dt, -event_depth);
    c.amp = p.force_amplitude();
    c.bias = p.bias;
    c.friction = p.friction;
    c.inv_relaxation = p.inverse_relaxation();
    c.relaxation = p.relaxation;
    c.noise = p.noise;
    c.max_work = s.max_work_per_excursion;
    c.white = p.white();
    if (c.white) {
        c.level = s.white_level > 0 ? s.white_level : white_level_default(m);
        double r = c.level * c.level / (36.0 * p.noise);
        if (std::isfinite(p.relaxation)) r = std::fmin(r, p.relaxation / 16.0);
        const double leaves = std::floor(r / c.leaf);
        c.leave_zero_leaves = leaves < 1.0 ? 1 : (leaves >= std::ldexp(1.0, event_depth) ? std::uint64_t{1} << event_depth
                                                                                        : static_cast<std::uint64_t>(leaves));
    } else {
        c.x_up = m.upper_threshold();
        c.x_down = m.lower_threshold();
    }
    // The laws reject what they cannot compute (tiny or huge ratios); say it with the flag's name.
    try {
        for (int d = 0; d <= event_depth; ++d) {
            EventLevel& L = c.lv[d];
            L.leaves = std::uint64_t{1} << (event_depth - d);
            L.len = std::ldexp(s.dt, -d);
            if (c.white) {
                L.wslide = white_slide_law(p.relaxation, p.noise, L.len);
                L.wmid = white_slide_bridge(p.relaxation, p.noise, L.len);
                const double k = p.inverse_relaxation();
                L.v_grow = k == 0.0 ? 1.0 : std::exp(L.len * k);
                L.v_u_len = k == 0.0 ? L.len : 0.5 * std::expm1(2.0 * L.len * k) / k;
                L.v_touch_rate = 2.0 * L.v_grow / (p.noise * L.v_u_len);
            } else {
                L.slide = colored_slide_law(p.tau, p.relaxation, c.amp, L.len);
                L.mid = colored_slide_bridge(p.tau, p.relaxation, c.amp, L.len);
                L.v_mid_sd = std::sqrt(L.mid.cov[1][1]);
                const OUStep ou = ou_step(p.tau, L.len);
                L.x_keep = ou.end_coef;
                L.x_sd = std::sqrt(ou.s22);
                L.x_mid = ou_bridge(p.tau, L.len);
                L.x_grow = std::exp(L.len / p.tau);
                L.x_u_len = 0.5 * p.tau * std::expm1(2.0 * L.len / p.tau);
                L.x_var_rate = 2.0 / (p.tau * p.tau);
                L.x_tau = p.tau;
            }
        }
        if (p.has_drift_law()) {
            // b(0) sets the static band (c.bias, as the thresholds); the
            // slope and intercept of each piece replace the affine law's.
            const DriftLaw& b = *m.law;
            auto table = std::make_shared<const std::vector<EventDriftPiece>>(drift_pieces(b, p, s.dt, c.amp, stop));
            c.bias = b(0.0);
            c.inv_relaxation = 0.0;
            c.relaxation = HUGE_VAL;
            c.pieces = table->data();
            c.piece_count = b.pieces();
            c.zero_piece = zero_knot(b); // the piece above the knot at 0
            c.knot_first = b.first;
            c.knot_inv_spacing = b.inv_spacing;
            *pieces = std::move(table);
        }
    } catch (const InvalidParameter&) {
        throw;
    } catch (const std::invalid_argument& e) {
        throw InvalidParameter("dt", "dt = " + detail::format_number(s.dt) +
                                         " s is outside the range the event scheme's laws can be computed for (" +
                                         e.what() + ")");
    }
    return c;
}

} // namespace stickslip
