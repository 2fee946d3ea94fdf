// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/kernels/resolvent_lanes.hpp"

#include "random/lane_streams.hpp"
#include "stickslip/random/rng.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "core/x86_levels.hpp"

namespace stickslip {

namespace {

constexpr int L = lane_count;
constexpr int B = detail::rng_batch_size;

/// The draw's numbers as one step of resolvent_walk_step_as sees them: its
/// normal pair and, if the bridge test asks, its side uniform.
struct LaneStepRng {
    double z1, z2;
    const CounterRng::Philox::key_type* key;
    std::uint32_t c2, c3;
    std::uint64_t j;
    NormalPair normal2() const { return {z1, z2}; }
    double side_uniform() const { return CounterRng::side_uniform_of(*key, c2, c3, j); }
};

/// Eight walks, structure of arrays, and their normals by (half, step, lane).
struct LaneGroup {
    alignas(64) double x[L];
    alignas(64) double v[L];
    alignas(64) double vsum[L];
    alignas(64) double target[L];  ///< the half's stopping level of X
    alignas(64) double dir[L];     ///< +1 or -1
    alignas(64) std::int64_t steps[L];      ///< (signed: AVX2 compares signed 64-bit integers only)
    alignas(64) std::int64_t prev_stuck[L]; ///< rule P: 1 or 0
    alignas(64) std::int64_t attention[L];  ///< 1: the lane's step is left to the scalar kernel
    alignas(64) double mart[L];             ///< the martingale M so far (with a corrector) [m]
    alignas(64) double mart_qv[L];          ///< its Q so far [m^2]
    alignas(64) double corrector[L];        ///< g at the start of the step
    alignas(64) double slope[L];            ///< its slope there
    alignas(64) double z[2][B][L];
    std::uint64_t first_half[L];
    std::uint64_t slot[L];
    std::uint64_t base[L]; ///< draw number of buffer position 0 (mod 2^64)
    std::uint32_t c2[L], c3[L];
    bool active[L];
};

/// Martingale: NoMartingale (the plain kernel) or MartingaleSums (the sums of
/// the corrector in it, kernels/corrector.hpp), accumulated per lane exactly
/// as resolvent_walk_step_as does, so the outcomes' M and Q are bitwise
/// resolvent_long_excursion_with's too.
template <StepKind K, class Martingale>
class LaneRunner {
public:
    LaneRunner(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
               ExcursionOutcome* out, const std::atomic<bool>* cancel, const Martingale& mart = Martingale{})
        : c_(c), key_(CounterRng::make_key(seed)), first_(first), out_(out), dealer_(count, cancel), mart_(mart) {}

    bool run() {
        int live = 0;
        for (int l = 0; l < L; ++l) live += load(l, 0) ? 1 : 0;
        while (live > 0) {
            for (int p = 0; p < B && live > 0; ++p) {
                if (!vector_step(p)) continue;
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
    void refill(int l, int from) { detail::refill_lane_normals(g_, key_, l, from); }

    void start_half(int l, int dir) {
        ResolventWalk w;
        resolvent_walk_start_half(c_, w, dir);
        g_.x[l] = w.x;
        g_.v[l] = w.v;
        g_.dir[l] = dir;
        g_.target[l] = dir > 0 ? c_.x_down : c_.x_up;
        g_.prev_stuck[l] = 0;
    }

    /// Gives lane l the next excursion, its draw 0 at buffer position `phase`.
    bool load(int l, int phase) {
        g_.active[l] = dealer_.next(g_.slot[l]);
        g_.attention[l] = 0;
        if (!g_.active[l]) {
            park(l);
            return false;
        }
        g_.vsum[l] = 0.0;
        g_.mart[l] = 0.0;
        g_.mart_qv[l] = 0.0;
        g_.steps[l] = 0;
        g_.first_half[l] = 0;
        start_half(l, +1);
        detail::start_lane_stream(g_, key_, l, first_ + g_.slot[l], phase);
        return true;
    }

    /// An idle lane: it keeps stepping on zero normals and may even be flagged
    /// later (stuck, or at the cap), but run() skips inactive lanes, so it only
    /// computes values nobody reads.
    void park(int l) {
        g_.x[l] = 0.0;
        g_.v[l] = 1.0;
        g_.vsum[l] = 0.0;
        g_.mart[l] = 0.0;
        g_.mart_qv[l] = 0.0;
        g_.steps[l] = 0;
        g_.prev_stuck[l] = 0;
        g_.dir[l] = 1.0;
        g_.target[l] = c_.x_down;
        for (int h = 0; h < 2; ++h)
            for (int i = 0; i < B; ++i) g_.z[h][i][l] = 0.0;
    }

    /// Step p of every lane where the outcome is the plain step; marks the
    /// others in g_.attention. Returns whether any lane was marked. The step is
    /// resolvent_colored_step and soft_threshold themselves, so the applied
    /// lanes get the one-excursion kernel's bits.
    bool vector_step(int p) {
        // A local copy: the stores to g_ below cannot alias it, so the
        // constants stay in registers and the loop vectorises.
        const ResolventConstants c = c_;
        const double band = c.h_friction, xd = c.x_down, xu = c.x_up, rate = c.bridge_rate;
        const auto cap = static_cast<std::int64_t>(c.max_steps);
        if constexpr (Martingale::active) {
            // g at the steps' starts, one lane at a time: a loop of its own,
            // so that the step's loop below still vectorises (GCC does not
            // if-convert the table lookup, and its gathers, emulated for
            // generic tuning, made it no faster: measured in bench/).
            const CorrectorTable g = mart_.g;
            for (int l = 0; l < L; ++l) g_.corrector[l] = g.value_and_slope(g_.x[l], g_.v[l], g_.slope[l]);
        }
        std::int64_t any = 0;
#if !defined(__clang__) // GCC's no-dependence hint; clang vectorizes this loop without it
#pragma GCC ivdep
#endif
        for (int l = 0; l < L; ++l) {
            const double z1 = g_.z[0][p][l], z2 = g_.z[1][p][l];
            const double x0 = g_.x[l], v0 = g_.v[l];
            double xn, f;
            resolvent_colored_step_affine(c, x0, v0, z1, z2, xn, f); // lanes run the affine law only
            const double vn = soft_threshold(f, band);
            const std::int64_t stuck = v0 == 0.0 ? 1 : 0;
            std::int64_t flag = g_.steps[l] >= cap ? 1 : 0;
            if constexpr (K == StepKind::ColoredBridge) {
                const double t = g_.target[l];
                const std::int64_t inband = (x0 >= xd ? 1 : 0) & (x0 <= xu ? 1 : 0);
                const std::int64_t crossed = g_.dir[l] * (xn - t) <= 0.0 ? 1 : 0;
                const double e = (x0 - t) * (xn - t) * rate;
                const std::int64_t maybe = e > bridge_exponent_cutoff ? 0 : 1; // also NaN
                flag |= stuck & inband & (crossed | maybe);
            } else {
                const std::int64_t pos = g_.dir[l] > 0.0 ? 1 : 0;
                const std::int64_t leaves = (pos & (f < -band ? 1 : 0)) | ((1 - pos) & (f > band ? 1 : 0));
                flag |= stuck & g_.prev_stuck[l] & leaves;
                const std::int64_t stays = vn == 0.0 ? 1 : 0;
                g_.prev_stuck[l] = flag ? g_.prev_stuck[l] : (stuck & stays);
            }
            g_.attention[l] = flag;
            any |= flag;
            g_.x[l] = flag ? x0 : xn;
            g_.v[l] = flag ? v0 : vn;
            g_.vsum[l] = flag ? g_.vsum[l] : g_.vsum[l] + v0;
            g_.steps[l] += 1 - flag;
            if constexpr (Martingale::active) { // X's exact innovation, as resolvent_walk_step_as
                const double xi = c.ou.l21 * z1 + c.ou.l22 * z2;
                double dm, dq;
                MartingaleSums::increments(g_.corrector[l], g_.slope[l], xi, c.ou.s22, dm, dq);
                g_.mart[l] = flag ? g_.mart[l] : g_.mart[l] + dm;
                g_.mart_qv[l] = flag ? g_.mart_qv[l] : g_.mart_qv[l] + dq;
            }
        }
        return any != 0;
    }

    /// Step p of lane l by the one-excursion kernel itself. Returns false when
    /// the lane has no excursion left to run.
    bool scalar_step(int l, int p) {
        ResolventWalk w;
        w.x = g_.x[l];
        w.v = g_.v[l];
        w.vsum = g_.vsum[l];
        w.steps = static_cast<std::uint64_t>(g_.steps[l]);
        w.first = g_.first_half[l];
        w.dir = g_.dir[l] > 0.0 ? +1 : -1;
        w.prev_stuck = g_.prev_stuck[l] != 0;
        LaneStepRng rng{g_.z[0][p][l], g_.z[1][p][l], &key_, g_.c2[l], g_.c3[l],
                        g_.base[l] + static_cast<std::uint64_t>(p)};
        NoPathObserver none;
        Martingale mart = mart_;
        if constexpr (Martingale::active) {
            mart.m = g_.mart[l];
            mart.q = g_.mart_qv[l];
        }
        const WalkStatus st = resolvent_walk_step_as<K>(c_, w, rng, none, mart);
        if constexpr (Martingale::active) {
            g_.mart[l] = mart.m;
            g_.mart_qv[l] = mart.q;
        }
        g_.x[l] = w.x;
        g_.v[l] = w.v;
        g_.vsum[l] = w.vsum;
        g_.steps[l] = static_cast<std::int64_t>(w.steps);
        g_.prev_stuck[l] = w.prev_stuck ? 1 : 0;
        if (st == WalkStatus::Running) return true;
        if (st == WalkStatus::HalfDone && w.dir > 0) {
            g_.first_half[l] = w.steps;
            start_half(l, -1);
            return true;
        }
        ExcursionOutcome& o = out_[g_.slot[l]];
        o = resolvent_walk_outcome(c_, w, st == WalkStatus::Capped);
        if constexpr (Martingale::active) {
            o.martingale = mart.m;
            o.martingale_qv = mart.q;
        }
        return load(l, p + 1);
    }

    const ResolventConstants& c_;
    const CounterRng::Philox::key_type key_;
    const std::uint64_t first_;
    ExcursionOutcome* const out_;
    detail::LaneDealer dealer_;
    const Martingale mart_; ///< the corrector (its sums unused: each lane keeps its own)
    LaneGroup g_{};
};

// One source, compiled per x86-64 level (x86_levels.hpp); the runner is
// inlined into each clone.

STICKSLIP_X86_CLONES_FLATTEN
bool run_lanes_bridge(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                      ExcursionOutcome* out, const std::atomic<bool>* cancel) {
    return LaneRunner<StepKind::ColoredBridge, NoMartingale>(c, seed, first, count, out, cancel).run();
}

STICKSLIP_X86_CLONES_FLATTEN
bool run_lanes_stuck(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                     ExcursionOutcome* out, const std::atomic<bool>* cancel) {
    return LaneRunner<StepKind::ColoredStuck, NoMartingale>(c, seed, first, count, out, cancel).run();
}

STICKSLIP_X86_CLONES_FLATTEN
bool run_lanes_bridge_with(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                           ExcursionOutcome* out, const std::atomic<bool>* cancel, const CorrectorTable& g) {
    return LaneRunner<StepKind::ColoredBridge, MartingaleSums>(c, seed, first, count, out, cancel, MartingaleSums{g})
        .run();
}

STICKSLIP_X86_CLONES_FLATTEN
bool run_lanes_stuck_with(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                          ExcursionOutcome* out, const std::atomic<bool>* cancel, const CorrectorTable& g) {
    return LaneRunner<StepKind::ColoredStuck, MartingaleSums>(c, seed, first, count, out, cancel, MartingaleSums{g})
        .run();
}

bool one_at_a_time(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                   ExcursionOutcome* out, const std::atomic<bool>* cancel) {
    for (std::uint64_t i = 0; i < count; ++i) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return false;
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, first + i);
        out[i] = resolvent_long_excursion(c, rng);
    }
    return true;
}

bool one_at_a_time_with(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                        ExcursionOutcome* out, const std::atomic<bool>* cancel, const CorrectorTable& g) {
    for (std::uint64_t i = 0; i < count; ++i) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return false;
        BatchedCounterRng rng(seed, StreamPurpose::LongExcursion, first + i);
        out[i] = resolvent_long_excursion_with(c, rng, g);
    }
    return true;
}

} // namespace

bool resolvent_long_excursions_with(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first,
                                    std::uint64_t count, ExcursionOutcome* out, const std::atomic<bool>* cancel,
                                    const CorrectorTable& g) {
    if (!resolvent_lanes_vectorised()) return one_at_a_time_with(c, seed, first, count, out, cancel, g);
    return detail::resolvent_long_excursions_in_lanes_with(c, seed, first, count, out, cancel, g);
}

bool resolvent_long_excursions(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first,
                               std::uint64_t count, ExcursionOutcome* out, const std::atomic<bool>* cancel) {
    if (!resolvent_lanes_vectorised()) return one_at_a_time(c, seed, first, count, out, cancel);
    return detail::resolvent_long_excursions_in_lanes(c, seed, first, count, out, cancel);
}

bool detail::resolvent_long_excursions_in_lanes(const ResolventConstants& c, std::uint64_t seed,
                                                std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                                                const std::atomic<bool>* cancel) {
    if (c.white || c.knots_law || c.static_band) return one_at_a_time(c, seed, first, count, out, cancel);
    return c.rule == StopRule::Bridge ? run_lanes_bridge(c, seed, first, count, out, cancel)
                                      : run_lanes_stuck(c, seed, first, count, out, cancel);
}

bool detail::resolvent_long_excursions_in_lanes_with(const ResolventConstants& c, std::uint64_t seed,
                                                     std::uint64_t first, std::uint64_t count, ExcursionOutcome* out,
                                                     const std::atomic<bool>* cancel, const CorrectorTable& g) {
    if (c.white || c.knots_law || c.static_band) return one_at_a_time_with(c, seed, first, count, out, cancel, g);
    return c.rule == StopRule::Bridge ? run_lanes_bridge_with(c, seed, first, count, out, cancel, g)
                                      : run_lanes_stuck_with(c, seed, first, count, out, cancel, g);
}

bool resolvent_lanes_vectorised() {
#ifdef STICKSLIP_PER_X86_LEVEL
    // GCC 12 vectorises the lane step for AVX-512 only; elsewhere the lanes
    // would run as scalar code, slower than one excursion at a time.
    static const bool avx512 = detail::x86_clone_level() == 4;
    return avx512;
#elif defined(__GNUC__) && !defined(__clang__) && defined(__AVX512F__) && defined(__AVX512DQ__)
    return true; // compiled for AVX-512 (STICKSLIP_NATIVE on such a machine)
#else
    return false;
#endif
}

const char* resolvent_kernel_name() {
    return resolvent_lanes_vectorised() ? "8 SIMD lanes (AVX-512)" : "one excursion at a time";
}

} // namespace stickslip
