// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/kernels/event_lanes.hpp"

#include <optional>

#include "random/lane_streams.hpp"
#include "stickslip/kernels/resolvent_lanes.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "core/x86_levels.hpp"

namespace stickslip {

namespace {

constexpr int L = lane_count;
constexpr int B = detail::rng_batch_size;

/// The draw's numbers as one step of event_colored_step sees them: its normal
/// pair and its side draw (from the lane's buffer where it was filled).
struct LaneStepRng {
    double z1, z2;
    bool side_filled;
    double side_normal, side_uniform;
    const CounterRng::Philox::key_type* key;
    std::uint32_t c2, c3;
    std::uint64_t j;
    NormalPair normal2() const { return {z1, z2}; }
    NormalPair side_draw() const {
        return side_filled ? NormalPair{side_normal, side_uniform} : CounterRng::side_draw_of(*key, c2, c3, j);
    }
};

/// The few constants of a whole step that the vector step reads (level 0).
struct QuietStepConstants {
    double x_up, x_down, x_keep, x_sd, x_grow, spread; // stuck
    double amp, inv_relaxation, len, v_mid_sd, bias, friction;
    double m[3][3], g[3], chol[3][3]; // sliding law
    std::int64_t leaves, max_work;
};

QuietStepConstants quiet_constants(const EventConstants& c) {
    const EventLevel& L0 = c.lv[0];
    QuietStepConstants q{};
    q.x_up = c.x_up;
    q.x_down = c.x_down;
    q.x_keep = L0.x_keep;
    q.x_sd = L0.x_sd;
    q.x_grow = L0.x_grow;
    q.spread = L0.x_var_rate * L0.x_u_len;
    q.amp = c.amp;
    q.inv_relaxation = c.inv_relaxation;
    q.len = L0.len;
    q.v_mid_sd = L0.v_mid_sd;
    q.bias = c.bias;
    q.friction = c.friction;
    for (int i = 0; i < 3; ++i) {
        q.g[i] = L0.slide.g[i];
        for (int k = 0; k < 3; ++k) {
            q.m[i][k] = L0.slide.m[i][k];
            q.chol[i][k] = L0.slide.chol[i][k];
        }
    }
    q.leaves = static_cast<std::int64_t>(L0.leaves);
    q.max_work = static_cast<std::int64_t>(c.max_work);
    return q;
}

/// Eight walks, structure of arrays, and their draws by (half, step, lane).
struct LaneGroup {
    alignas(64) double x[L];
    alignas(64) double v[L];
    alignas(64) double u[L];
    alignas(64) double phase[L];            ///< 0 stuck, +1 / -1 sliding
    alignas(64) std::int64_t t[L];          ///< [leaves]
    alignas(64) std::int64_t steps[L];      ///< (signed: AVX2 compares signed 64-bit integers only)
    alignas(64) std::int64_t midpoints[L];
    alignas(64) std::int64_t attention[L];  ///< 1: the lane's step is left to the scalar kernel
    alignas(64) double mart[L];             ///< the martingale M so far (with a corrector) [m]
    alignas(64) double mart_qv[L];          ///< its Q so far [m^2]
    alignas(64) double corrector[L];        ///< g at the start of the step
    alignas(64) double slope[L];            ///< its slope there
    alignas(64) double z[2][B][L];
    alignas(64) double side[2][B][L];       ///< side normal and uniform, where side_filled
    bool side_filled[L];
    int dir[L];
    bool launched[L];
    std::uint64_t launch[L], first_half[L];
    std::uint64_t slot[L];
    std::uint64_t base[L]; ///< draw number of buffer position 0 (mod 2^64)
    std::uint32_t c2[L], c3[L];
    bool active[L];
};

/// Martingale: NoMartingale (the plain kernel) or MartingaleSums (the sums of
/// the corrector in it, kernels/corrector.hpp), accumulated per lane exactly
/// as event_step_with does, so the outcomes' M and Q are bitwise
/// event_long_excursion_with's too.
template <class Martingale>
class LaneRunner {
public:
    LaneRunner(const EventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
               ExcursionOutcome* out, const std::atomic<bool>* cancel, const Martingale& mart = Martingale{})
        : c_(c), q_(quiet_constants(c)), seed_(seed), key_(CounterRng::make_key(seed)), first_(first), out_(out),
          dealer_(count, cancel), mart_(mart) {}

    bool run() {
        int live = 0;
        for (int l = 0; l < L; ++l) live += load(l, 0) ? 1 : 0;
        while (live > 0) {
            for (int p = 0; p < B && live > 0; ++p) {
                bool sliding = false;
                for (int l = 0; l < L; ++l) // a sliding lane's plain step needs its side normal
                    if (g_.active[l] && g_.phase[l] != 0.0) {
                        sliding = true;
                        if (!g_.side_filled[l]) fill_side(l, p);
                    }
                // (Where every lane is stuck, as in most steps at small dt, the
                // sliding update is not computed.)
                if (!(sliding ? vector_step<true>(p) : vector_step<false>(p))) continue;
                for (int l = 0; l < L; ++l)
                    if (g_.attention[l] && g_.active[l] && !scalar_step(l, p)) --live;
            }
            for (int l = 0; l < L; ++l)
                if (g_.active[l]) {
                    g_.base[l] += B;
                    refill(l, 0);
                }
        }
        return !dealer_.cancelled();
    }

private:
    /// Normals of lane l for draws base .. base+B-1, from buffer position `from` on.
    void refill(int l, int from) {
        detail::refill_lane_normals(g_, key_, l, from);
        g_.side_filled[l] = false;
    }

    /// Side draws of lane l for its buffered draws, from position `from` on.
    void fill_side(int l, int from) {
        double side[2][B];
        detail::fill_side_draws(key_, g_.c2[l], g_.c3[l], g_.base[l], side, from);
        for (int h = 0; h < 2; ++h)
            for (int i = from; i < B; ++i) g_.side[h][i][l] = side[h][i];
        g_.side_filled[l] = true;
    }

    EventWalk walk_of(int l) const {
        EventWalk w;
        w.x = g_.x[l];
        w.v = g_.v[l];
        w.u = g_.u[l];
        w.t = static_cast<std::uint64_t>(g_.t[l]);
        w.phase = g_.phase[l] > 0.0 ? +1 : (g_.phase[l] < 0.0 ? -1 : 0);
        w.dir = g_.dir[l];
        w.launched = g_.launched[l];
        w.launch = g_.launch[l];
        w.first = g_.first_half[l];
        w.steps = static_cast<std::uint64_t>(g_.steps[l]);
        w.midpoints = static_cast<std::uint64_t>(g_.midpoints[l]);
        return w;
    }

    void store(int l, const EventWalk& w) {
        g_.x[l] = w.x;
        g_.v[l] = w.v;
        g_.u[l] = w.u;
        g_.t[l] = static_cast<std::int64_t>(w.t);
        g_.phase[l] = static_cast<double>(w.phase);
        g_.dir[l] = w.dir;
        g_.launched[l] = w.launched;
        g_.launch[l] = w.launch;
        g_.first_half[l] = w.first;
        g_.steps[l] = static_cast<std::int64_t>(w.steps);
        g_.midpoints[l] = static_cast<std::int64_t>(w.midpoints);
    }

    /// Gives lane l the next excursion, its draw 0 at buffer position `phase`.
    bool load(int l, int phase) {
        g_.active[l] = dealer_.next(g_.slot[l]);
        g_.attention[l] = 0;
        if (!g_.active[l]) {
            park(l);
            return false;
        }
        ref_[l].emplace(seed_, StreamPurpose::Refinement, first_ + g_.slot[l]);
        EventWalk w;
        event_start_half(c_, w, +1);
        store(l, w);
        g_.mart[l] = 0.0;
        g_.mart_qv[l] = 0.0;
        detail::start_lane_stream(g_, key_, l, first_ + g_.slot[l], phase);
        g_.side_filled[l] = false; // (a new stream: nothing of it is filled)
        return true;
    }

    /// An idle lane: it keeps stepping on zero normals, stuck at X = 0, but
    /// run() skips inactive lanes, so it only computes values nobody reads.
    void park(int l) {
        store(l, EventWalk{});
        g_.mart[l] = 0.0;
        g_.mart_qv[l] = 0.0;
        g_.side_filled[l] = true; // (never needs a side draw)
        for (int h = 0; h < 2; ++h)
            for (int i = 0; i < B; ++i) g_.z[h][i][l] = g_.side[h][i][l] = 0.0;
    }

    /// Step p of every lane where the step is quiet; marks the others in
    /// g_.attention. Returns whether any lane was marked. The updates are
    /// event_colored_step's own (apply, the stuck X step) and the tests
    /// sufficient conditions of its decisions (stuck_step_is_quiet,
    /// slide_step_is_quiet), so the applied lanes get its bits.
    template <bool AnySliding>
    bool vector_step(int p) {
        // A local copy: the stores to g_ below cannot alias it, so the
        // constants stay in registers and the loop vectorises.
        const QuietStepConstants q = q_;
        if constexpr (Martingale::active) {
            // g at the steps' starts, one lane at a time: a loop of its own,
            // so that the step's loop below still vectorises.
            const CorrectorTable g = mart_.g;
            for (int l = 0; l < L; ++l) g_.corrector[l] = g.value_and_slope(g_.x[l], g_.v[l], g_.slope[l]);
        }
        ColoredSlideLaw law{};
        for (int i = 0; i < 3; ++i) {
            law.g[i] = q.g[i];
            for (int k = 0; k < 3; ++k) {
                law.m[i][k] = q.m[i][k];
                law.chol[i][k] = q.chol[i][k];
            }
        }
#if !defined(__clang__) // GCC's no-dependence hint; clang vectorizes this loop without it
#pragma GCC ivdep
#endif
        for (int l = 0; l < L; ++l) {
            const double z1 = g_.z[0][p][l], z2 = g_.z[1][p][l], z3 = g_.side[0][p][l];
            const double x0 = g_.x[l], v0 = g_.v[l], u0 = g_.u[l], s = g_.phase[l];
            // stuck
            const double xs = q.x_keep * x0 + q.x_sd * z1;
            const bool stuck_quiet = detail::stuck_step_is_quiet(q.x_up, q.x_down, q.x_grow, q.spread, x0, xs);
            // sliding in direction s
            double xb = x0, vb = v0, ub = u0;
            bool slide_quiet = false;
            if constexpr (AnySliding) {
                const double cs = q.bias - s * q.friction;
                apply(law, x0, v0, 0.0, cs, z1, z2, z3, xb, vb, ub); // U from the step's start, as there
                slide_quiet =
                    detail::slide_step_is_quiet(q.amp, q.inv_relaxation, q.len, q.v_mid_sd, x0, v0, xb, vb, s, cs);
            }
            const double floor = 0.0; // as event_colored_step: nothing was reflected
            const bool stuck = s == 0.0;
            std::int64_t flag = g_.steps[l] + g_.midpoints[l] >= q.max_work ? 1 : 0;
            flag |= (stuck ? stuck_quiet : slide_quiet) ? 0 : 1;
            g_.attention[l] = flag;
            const double xn = stuck ? xs : xb, vn = stuck ? v0 : vb - s * floor, un = stuck ? u0 : u0 + (ub + floor);
            g_.x[l] = flag ? x0 : xn;
            g_.v[l] = flag ? v0 : vn;
            g_.u[l] = flag ? u0 : un;
            g_.t[l] += flag ? 0 : q.leaves;
            g_.steps[l] += 1 - flag;
            if constexpr (Martingale::active) { // a whole step: event_step_with's growth and variance
                const double xi = q.x_grow * xn - x0;
                double dm, dq;
                MartingaleSums::increments(g_.corrector[l], g_.slope[l], xi, q.spread, dm, dq);
                g_.mart[l] = flag ? g_.mart[l] : g_.mart[l] + dm;
                g_.mart_qv[l] = flag ? g_.mart_qv[l] : g_.mart_qv[l] + dq;
            }
        }
        std::int64_t any = 0; // (a reduction inside the loop above keeps it from vectorising)
        for (int l = 0; l < L; ++l) any |= g_.attention[l];
        return any != 0;
    }

    /// Step p of lane l by the one-excursion kernel itself. Returns false when
    /// the lane has no excursion left to run.
    bool scalar_step(int l, int p) {
        EventWalk w = walk_of(l);
        LaneStepRng rng{g_.z[0][p][l], g_.z[1][p][l], g_.side_filled[l], g_.side[0][p][l], g_.side[1][p][l],
                        &key_, g_.c2[l], g_.c3[l], g_.base[l] + static_cast<std::uint64_t>(p)};
        EventStatus st;
        if constexpr (Martingale::active) {
            Martingale mart = mart_;
            mart.m = g_.mart[l];
            mart.q = g_.mart_qv[l];
            st = event_step_with(c_, w, rng, *ref_[l], mart);
            g_.mart[l] = mart.m;
            g_.mart_qv[l] = mart.q;
        } else {
            NoPieceObserver none;
            st = event_colored_step(c_, w, 0, rng, *ref_[l], none);
        }
        store(l, w);
        if (st == EventStatus::Running) return true;
        if (st == EventStatus::HalfDone && w.dir > 0) {
            w.first = w.t;
            event_start_half(c_, w, -1);
            store(l, w);
            return true;
        }
        ExcursionOutcome& o = out_[g_.slot[l]];
        o = event_walk_outcome(c_, w, st == EventStatus::Capped);
        if constexpr (Martingale::active) {
            o.martingale = g_.mart[l];
            o.martingale_qv = g_.mart_qv[l];
        }
        return load(l, p + 1);
    }

    const EventConstants& c_;
    const QuietStepConstants q_;
    const std::uint64_t seed_;
    const CounterRng::Philox::key_type key_;
    const std::uint64_t first_;
    ExcursionOutcome* const out_;
    detail::LaneDealer dealer_;
    const Martingale mart_; ///< the corrector (its sums unused: each lane keeps its own)
    LaneGroup g_{};
    std::optional<BatchedCounterRng> ref_[L]; ///< each lane's refinement stream
};

// One source, compiled per x86-64 level (x86_levels.hpp); the runner is
// inlined into each clone.
STICKSLIP_X86_CLONES_FLATTEN
bool run_lanes(const EventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
               ExcursionOutcome* out, const std::atomic<bool>* cancel) {
    return LaneRunner<NoMartingale>(c, seed, first, count, out, cancel).run();
}

STICKSLIP_X86_CLONES_FLATTEN
bool run_lanes_with(const EventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                    ExcursionOutcome* out, const std::atomic<bool>* cancel, const CorrectorTable& g) {
    return LaneRunner<MartingaleSums>(c, seed, first, count, out, cancel, MartingaleSums{g}).run();
}

bool one_at_a_time(const EventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                   ExcursionOutcome* out, const std::atomic<bool>* cancel) {
    for (std::uint64_t i = 0; i < count; ++i) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return false;
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, first + i);
        BatchedCounterRng ref(seed, StreamPurpose::Refinement, first + i);
        out[i] = event_long_excursion(c, rng, ref);
    }
    return true;
}

bool one_at_a_time_with(const EventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                        ExcursionOutcome* out, const std::atomic<bool>* cancel, const CorrectorTable& g) {
    for (std::uint64_t i = 0; i < count; ++i) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return false;
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, first + i);
        BatchedCounterRng ref(seed, StreamPurpose::Refinement, first + i);
        out[i] = event_long_excursion_with(c, rng, ref, g);
    }
    return true;
}

/// Whether the lanes run: where they are vectorised and the step is short
/// enough for most steps to be quiet.
bool lanes_pay(const EventConstants& c) {
    // With drag, many steps longer than relaxation/16 are not quiet, and a
    // lane whose step is not pays for the vector step too: on the Fig. 2 case,
    // 22% of the steps fail a quiet test at relaxation/16 (3.3% refine), 63%
    // at relaxation/4 (8.5% refine; most are stuck steps whose bridge
    // exponent is below 50, which the scalar kernel settles without a
    // refinement). Measured (Fig. 2 case, 2048 excursions, time one at a time / in
    // lanes): 1.25, 1.19, 1.04 at dt = 3e-4, 1e-3, relaxation/16; 0.93, 0.89
    // at relaxation/8 (the automatic step), relaxation/4. Without drag the
    // lanes win at every step measured (1.55, 1.19, 1.05 at tau/100, tau/10,
    // tau/2).
    return resolvent_lanes_vectorised() && c.h <= c.relaxation / 16.0;
}

} // namespace

bool event_long_excursions_with(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                std::uint64_t count, ExcursionOutcome* out, const std::atomic<bool>* cancel,
                                const CorrectorTable& g) {
    if (!lanes_pay(c)) return one_at_a_time_with(c, seed, first, count, out, cancel, g);
    return detail::event_long_excursions_in_lanes_with(c, seed, first, count, out, cancel, g);
}

bool event_long_excursions(const EventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                           ExcursionOutcome* out, const std::atomic<bool>* cancel) {
    if (!lanes_pay(c)) return one_at_a_time(c, seed, first, count, out, cancel);
    return detail::event_long_excursions_in_lanes(c, seed, first, count, out, cancel);
}

bool detail::event_long_excursions_in_lanes(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                            std::uint64_t count, ExcursionOutcome* out,
                                            const std::atomic<bool>* cancel) {
    // (The lanes slide on the affine law; a knots law's steps run one at a time.)
    if (c.white || c.pieces) return one_at_a_time(c, seed, first, count, out, cancel);
    return run_lanes(c, seed, first, count, out, cancel);
}

bool detail::event_long_excursions_in_lanes_with(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                                 std::uint64_t count, ExcursionOutcome* out,
                                                 const std::atomic<bool>* cancel, const CorrectorTable& g) {
    if (c.white || c.pieces) return one_at_a_time_with(c, seed, first, count, out, cancel, g);
    return run_lanes_with(c, seed, first, count, out, cancel, g);
}

} // namespace stickslip
