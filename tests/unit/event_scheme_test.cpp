// SPDX-License-Identifier: BSD-3-Clause
// The event scheme (event_scheme.hpp): time kept in whole leaves, results
// bitwise the same for any thread count, paths that end exactly at their
// times, the start of a walk from any state, the white-noise step (exact far
// from zero, the exact law of leaving zero, thread invariance), and the
// first-passage law of a stuck step against its closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "stickslip/analytic.hpp"
#include "stickslip/bruteforce.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/drift_input.hpp"
#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/random/rng_batch.hpp"
#include "stickslip/sample_runs.hpp"
#include "model_cases.hpp"

namespace ss = stickslip;

namespace {

ss::EngineSettings event(double dt) {
    ss::EngineSettings e = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    e.scheme = ss::Scheme::Event;
    e.dt = dt;
    return e;
}

TEST(EventScheme, BitwiseTheSameForAnyThreadCount) {
    const ss::ModelParams p;
    ss::RunTotals t[3];
    const unsigned threads[3] = {1, 2, 7};
    for (int k = 0; k < 3; ++k) {
        ss::RunControl ctl;
        ctl.threads = threads[k];
        ctl.seed = 99;
        t[k] = ss::run_long_excursions(p, event(2e-2), 300, ctl);
    }
    for (int k = 1; k < 3; ++k) {
        EXPECT_EQ(t[k].moments.mean_x(), t[0].moments.mean_x()) << threads[k] << " threads";
        EXPECT_EQ(t[k].moments.central_sum(2, 0), t[0].moments.central_sum(2, 0)) << threads[k] << " threads";
        EXPECT_EQ(t[k].moments.mean_y(), t[0].moments.mean_y()) << threads[k] << " threads";
        EXPECT_EQ(t[k].work, t[0].work);
    }
}

TEST(EventScheme, DurationIsWholeLeavesAndTheLongExcursionAlternates) {
    const ss::EventConstants c = ss::make_event_constants(ss::ModelParams{}, event(3e-2));
    EXPECT_EQ(c.leaf, std::ldexp(3e-2, -ss::event_depth));
    for (std::uint64_t k = 0; k < 20; ++k) {
        ss::BatchedCounterRng rng(5, ss::StreamPurpose::LongExcursion, k);
        ss::CounterRng ref(5, ss::StreamPurpose::Refinement, k);
        int last_phase = 2;
        std::uint64_t last_t = 0;
        bool ordered = true;
        const auto o = ss::event_long_excursion(c, rng, ref, [&](const ss::EventPiece& piece) {
            ordered = ordered && piece.t0 == last_t && piece.t1 > piece.t0;
            last_t = piece.t1;
            last_phase = piece.phase;
            if (piece.phase == 0) ordered = ordered && piece.u0 == piece.u1 && piece.v0 == 0.0;
        });
        ASSERT_FALSE(o.capped);
        EXPECT_TRUE(ordered) << "pieces must tile the excursion in time, stuck ones without motion";
        EXPECT_EQ(o.duration, c.leaf * static_cast<double>(last_t));
        EXPECT_GT(o.first_half, 0.0);
        EXPECT_LT(o.first_half, o.duration);
        EXPECT_EQ(last_phase, 0) << "a long excursion ends stuck, at its regeneration state";
    }
}

TEST(EventScheme, PathsEndExactlyAtTheirTimes) {
    const ss::EventConstants c = ss::make_event_constants(ss::ModelParams{}, event(2e-2));
    ss::BatchedCounterRng rng(1, ss::StreamPurpose::BruteForce, 0);
    ss::CounterRng ref(1, ss::StreamPurpose::Refinement, 0);
    ss::EventWalk w = ss::event_walk_from(c, 3.0, 0.0); // beyond x*: launched upwards
    EXPECT_EQ(w.phase, +1);
    ss::NoPieceObserver none;
    for (std::uint64_t at : {std::uint64_t{12345}, std::uint64_t{1} << 20, std::uint64_t{3'000'001}}) {
        ASSERT_EQ(ss::event_advance_to(c, w, at, rng, ref, none), ss::EventStatus::Running);
        EXPECT_EQ(w.t, at);
    }
    EXPECT_EQ(ss::event_walk_from(c, 0.0, 0.0).phase, 0);
    EXPECT_EQ(ss::event_walk_from(c, -9.0, 0.0).phase, -1);
    EXPECT_EQ(ss::event_walk_from(c, 0.0, -0.1).phase, -1);
}

TEST(EventScheme, CappedExcursionsAreCounted) {
    ss::EngineSettings e = event(1e-2);
    e.max_work_per_excursion = 50;
    ss::RunControl ctl;
    const auto t = ss::run_long_excursions(ss::ModelParams{}, e, 64, ctl);
    EXPECT_GT(t.capped, 0u);
    EXPECT_EQ(t.capped + t.moments.count(), 64u);
}

ss::ModelParams dry_white() { return ss::test::pure_dry_friction(0.0); } // white noise

TEST(EventScheme, WhiteNoiseStepFarFromZeroIsTheExactGaussianStep) {
    // Far from both levels no touch is possible: the step is the exact law of
    // (V, U) applied to the step's two normals, bit for bit, and draws nothing
    // from the refinement stream.
    ss::ModelParams p = dry_white();
    p.relaxation = 0.5;
    p.bias = 0.2;
    const ss::EventConstants c = ss::make_event_constants(p, event(1e-2));
    ss::EventWalk w = ss::event_walk_from(c, 0.0, 3.0);
    ss::BatchedCounterRng rng(5, ss::StreamPurpose::Test, 0), twin(5, ss::StreamPurpose::Test, 0);
    ss::CounterRng ref(5, ss::StreamPurpose::Refinement, 0);
    ss::NoPieceObserver none;
    ASSERT_EQ(ss::event_step(c, w, 0, rng, ref, none), ss::EventStatus::Running);
    const ss::NormalPair z = twin.normal2();
    const double a[2] = {3.0, 0.0}, n[2] = {z.x, z.y};
    double b[2];
    ss::apply(c.lv[0].wslide, a, p.bias - p.friction, n, b);
    EXPECT_EQ(w.v, b[0]);
    EXPECT_EQ(w.u, b[1]);
    EXPECT_EQ(w.t, c.lv[0].leaves);
    EXPECT_EQ(w.midpoints, 0u);
    EXPECT_EQ(ref.draws(), 0u);
}

TEST(EventScheme, WhiteNoiseLeavesZeroWithTheDryFrictionPropagator) {
    // From V = 0 without bias or drag the law of V(r) is exact: against the
    // propagator p(v, r | 0) (analytic.hpp), P(V > 0), E|V| and E[V^2].
    const ss::ModelParams p = dry_white();
    const ss::EventConstants c = ss::make_event_constants(p, event(1e-2));
    for (double r : {0.01, 0.3}) {
        const int n = 200000;
        double pos = 0, abs1 = 0, sq = 0, sq4 = 0;
        ss::CounterRng rng(9, ss::StreamPurpose::Test, static_cast<std::uint64_t>(r * 1000));
        for (int k = 0; k < n; ++k) {
            const double z = rng.normal2().x;
            const double u_sign = rng.side_draw().y;
            const double u_max = rng.uniform();
            const double v = ss::detail::white_leave_zero(c, r, z, u_sign, u_max);
            pos += v > 0;
            abs1 += std::fabs(v);
            sq += v * v;
            sq4 += v * v * v * v;
        }
        double e_abs = 0, e_sq = 0;
        const double hi = 12 * std::sqrt(r) + 12 * r, dv = hi / 200000;
        for (int i = 0; i < 200000; ++i) {
            const double v = (i + 0.5) * dv, q = 2 * ss::dry_friction_propagator(p, v, r, 0.0) * dv;
            e_abs += v * q;
            e_sq += v * v * q;
        }
        const double mean_abs = abs1 / n, mean_sq = sq / n;
        const double se_abs = std::sqrt((mean_sq - mean_abs * mean_abs) / n);
        const double se_sq = std::sqrt((sq4 / n - mean_sq * mean_sq) / n);
        EXPECT_NEAR(pos / n, 0.5, 4 * std::sqrt(0.25 / n)) << "r = " << r;
        EXPECT_NEAR(mean_abs, e_abs, 4 * se_abs) << "r = " << r << ", z = " << (mean_abs - e_abs) / se_abs;
        EXPECT_NEAR(mean_sq, e_sq, 4 * se_sq) << "r = " << r << ", z = " << (mean_sq - e_sq) / se_sq;
    }
}

TEST(EventScheme, WhiteNoiseIsBitwiseTheSameForAnyThreadCount) {
    ss::ModelParams p = dry_white();
    p.bias = 0.3;
    ss::RunTotals t[2];
    const unsigned threads[2] = {1, 3};
    for (int k = 0; k < 2; ++k) {
        ss::RunControl ctl;
        ctl.seed = 4;
        ctl.threads = threads[k];
        t[k] = ss::run_long_excursions(p, event(0.05), 300, ctl);
    }
    EXPECT_EQ(t[0].moments.count(), 300u);
    EXPECT_EQ(t[0].work, t[1].work);
    EXPECT_EQ(t[0].moments.mean_x(), t[1].moments.mean_x());
    EXPECT_EQ(t[0].moments.central_sum(2, 0), t[1].moments.central_sum(2, 0));
    EXPECT_EQ(t[0].moments.mean_y(), t[1].moments.mean_y());
}

// The stuck step's crossing: for a Brownian bridge (tau large against the
// step, where the clock change is the identity to first order) the crossing
// probability is exp(-2 a b / (sigma^2 len)) and the first-passage time of a
// bridge that ends beyond the level has the mean of its closed form
// (integrated numerically here from the density a/sqrt(2 pi s^2 t^3) exp(...)).
TEST(EventScheme, FirstPassageOfAStuckStepMatchesTheBridgeLaw) {
    ss::ModelParams p;
    p.tau = 1e6; // X is a Brownian motion over the step, to 1e-8
    const ss::EventConstants c = ss::make_event_constants(p, event(1e-3));
    const ss::EventLevel& L = c.lv[0];
    const double sigma2 = L.x_var_rate, len = L.len;
    const double a = 0.7 * std::sqrt(sigma2 * len), b = 0.4 * std::sqrt(sigma2 * len);
    // Crossing probability, both ends on the near side.
    const int n = 200000;
    int crossed = 0;
    ss::CounterRng u_rng(3, ss::StreamPurpose::Test, 0), ref(3, ss::StreamPurpose::Refinement, 0);
    for (int k = 0; k < n; ++k) crossed += ss::detail::first_passage(L, a, b, u_rng.uniform(), ref) >= 0.0;
    const double p_exact = std::exp(-2 * a * b / (sigma2 * len)), f = static_cast<double>(crossed) / n;
    const double se = std::sqrt(p_exact * (1 - p_exact) / n);
    EXPECT_LE(std::fabs(f - p_exact), 4 * se) << "crossing frequency " << f << " vs " << p_exact
                                              << ", z = " << (f - p_exact) / se;
    // Mean first-passage time of the bridge from a to -b (it must cross).
    double mean = 0, mean2 = 0;
    for (int k = 0; k < n; ++k) {
        const double t = ss::detail::first_passage(L, a, -b, 0.5, ref);
        mean += t;
        mean2 += t * t;
    }
    mean /= n;
    const double sd = std::sqrt(mean2 / n - mean * mean) / std::sqrt(static_cast<double>(n));
    // Density of the hitting time of 0 by a bridge from a to -b over [0, len]:
    // f(t) = a / sqrt(2 pi sigma2 t^3) e^{-a^2/(2 sigma2 t)} phi_{len-t}(b) / phi_len(a + b).
    auto phi = [&](double x, double t) { return std::exp(-x * x / (2 * sigma2 * t)) / std::sqrt(2 * M_PI * sigma2 * t); };
    double exact = 0, norm = 0;
    const int m = 200000;
    for (int i = 0; i < m; ++i) {
        const double t = len * (i + 0.5) / m;
        const double fd = a / std::sqrt(2 * M_PI * sigma2 * t * t * t) * std::exp(-a * a / (2 * sigma2 * t)) *
                          phi(b, len - t) / phi(a + b, len);
        exact += t * fd * len / m;
        norm += fd * len / m;
    }
    EXPECT_NEAR(norm, 1.0, 1e-3) << "the reference density must integrate to 1";
    EXPECT_LE(std::fabs(mean - exact / norm), 4 * sd) << "mean first passage " << mean << " vs " << exact / norm
                                                      << ", z = " << (mean - exact / norm) / sd;
}

// Every piece a walk is made of, at every step a user may choose (dt/tau from
// 1e-1 down to 1e-5) and far from the origin (U = 1e3 m, as a long excursion
// reaches): its noise (coloured) or velocity (white) moves by at most 7
// standard deviations of the exact law over the piece's length. The midpoint
// bridges once weighed an absolute displacement whose rounding swamped what
// it tells at fine depths: X then moved by 9 to 5e10 standard deviations
// within a piece (measured with this test on the code before the fix; 5.2 at
// most after it, over 4e6 pieces per case), and D came out up to 2e4 times too
// large (docs/validation.md, "The event scheme at fine steps"). A knots drift
// law (tau 1, its own laws per piece, positive slopes near 0) is one more case.
TEST(EventScheme, PiecesStayWithinTheSpreadOfTheirLawAtEveryStep) {
    for (double tau : {1.0, 0.1, 0.01, -1.0}) { // -1: tau 1 with a knots drift law
        for (double ratio : {1e-1, 1e-3, 1e-5}) {
            ss::ModelParams p;
            p.friction = 1;
            p.noise = 1;
            p.tau = tau;
            p.relaxation = tau == 0.1 ? 0.3 : INFINITY;
            p.bias = tau == 1.0 ? 0.3 : 0.0;
            if (tau < 0) {
                p.tau = tau = 1.0;
                p.drift = "0.3 + 0.8*v - 0.5*v^3";
            }
            std::shared_ptr<const std::vector<ss::EventDriftPiece>> laws;
            const ss::EventConstants c = ss::make_event_constants(p, event(ratio * tau), &laws);
            double worst = 0;
            std::uint64_t pieces = 0;
            for (std::uint64_t k = 0; k < 6; ++k) {
                ss::BatchedCounterRng rng(3, ss::StreamPurpose::Test, k);
                ss::CounterRng ref(3, ss::StreamPurpose::Refinement, k);
                ss::EventWalk w = ss::event_walk_from(c, c.x_up, 0.0); // a launch: refined to the finest depth
                w.u = 1e3;
                auto observe = [&](const ss::EventPiece& q) {
                    const double len = c.leaf * static_cast<double>(q.t1 - q.t0);
                    const double sd = std::sqrt(-std::expm1(-2 * len / tau) / tau);
                    worst = std::fmax(worst, std::fabs(q.x1 - q.x0) / sd);
                    ++pieces;
                };
                ss::event_advance_to(c, w, static_cast<std::uint64_t>(2 * tau / c.leaf), rng, ref, observe);
            }
            EXPECT_LT(worst, 7.0) << "tau " << tau << " s, dt/tau " << ratio << (laws ? ", drift law" : "")
                                  << ": a piece's X moved by " << worst << " standard deviations (" << pieces
                                  << " pieces)";
        }
    }
    for (double dt : {1e-1, 1e-3, 1e-5}) {
        ss::ModelParams p;
        p.friction = 1;
        p.noise = 1;
        p.tau = 0;
        p.relaxation = INFINITY;
        p.bias = 0.3;
        const ss::EventConstants c = ss::make_event_constants(p, event(dt));
        double worst = 0;
        std::uint64_t pieces = 0;
        for (std::uint64_t k = 0; k < 6; ++k) {
            ss::BatchedCounterRng rng(4, ss::StreamPurpose::Test, k);
            ss::CounterRng ref(4, ss::StreamPurpose::Refinement, k);
            ss::EventWalk w = ss::event_walk_from(c, 0.0, 1e-3); // near 0: touches, refined
            w.u = 1e3;
            auto observe = [&](const ss::EventPiece& q) {
                const double len = c.leaf * static_cast<double>(q.t1 - q.t0);
                const double drift = (p.friction + std::fabs(p.bias)) * len;
                worst = std::fmax(worst, (std::fabs(q.v1 - q.v0) - drift) / std::sqrt(p.noise * len));
                ++pieces;
            };
            ss::event_advance_to(c, w, static_cast<std::uint64_t>(std::fmin(2.0, 2e5 * dt) / c.leaf), rng, ref,
                                 observe);
        }
        EXPECT_LT(worst, 7.0) << "white noise, dt " << dt << " s: a piece's V moved by " << worst
                              << " standard deviations (" << pieces << " pieces)";
    }
}

// A knots drift law: the event scheme's table holds every piece of the law
// (slope, intercept, ends), the lookup finds the piece of any velocity (at 0
// the one on the sliding side), a law without a place for its table or with
// white noise is refused, and along paths no piece of the refinement slides
// across more than one knot (a step ends at the end of the finest piece
// beyond a knot) while the pieces tile the time. Few knots (65), so that a
// piece is wide against a step's move and a crossing is a visible event.
TEST(EventScheme, KnotsLawSlidesOnThePieceThatHoldsV) {
    ss::ModelParams p;
    p.friction = 1;
    p.noise = 1;
    p.tau = 1;
    p.drift = "0.1 + 0.4*tanh(v/0.1) - v/2"; // replaces relaxation and bias
    p.knots = 65;
    const ss::DriftLaw b = ss::make_drift_law(p);
    EXPECT_THROW(ss::make_event_constants(p, event(0.05)), ss::InvalidParameter);
    std::shared_ptr<const std::vector<ss::EventDriftPiece>> table;
    const ss::EventConstants c = ss::make_event_constants(p, event(0.05), &table);
    ASSERT_TRUE(table);
    ASSERT_EQ(c.piece_count, b.pieces());
    ASSERT_EQ(table->size(), static_cast<std::size_t>(b.pieces()));
    EXPECT_EQ(c.pieces, table->data());
    EXPECT_EQ(c.bias, b(0.0)) << "the static band is set by b(0)";
    for (int j = 0; j < b.pieces(); ++j) {
        const ss::EventDriftPiece& q = (*table)[static_cast<std::size_t>(j)];
        EXPECT_EQ(q.inv_relaxation, -b.piece_slope(j));
        EXPECT_EQ(q.intercept, b.piece_intercept(j));
        EXPECT_EQ(q.lower, b.piece_lower(j));
        EXPECT_EQ(q.upper, b.piece_upper(j));
        const double mid = j == 0 ? b.knot(0) - 1.0 : (j == b.pieces() - 1 ? b.knot(j) + 1.0 : b.knot(j) + 0.5 * b.spacing);
        for (int s : {-1, +1}) EXPECT_EQ(&ss::event_drift_piece(c, mid, s), &q) << "piece " << j;
        if (j > 0) { // just above and just below knot j
            EXPECT_EQ(&ss::event_drift_piece(c, std::nextafter(b.knot(j), INFINITY), +1), &q) << "knot " << j;
            EXPECT_EQ(&ss::event_drift_piece(c, std::nextafter(b.knot(j), -INFINITY), -1), &q - 1) << "knot " << j;
        }
    }
    EXPECT_EQ(ss::event_drift_piece(c, 0.0, +1).lower, 0.0);
    EXPECT_EQ(ss::event_drift_piece(c, 0.0, -1).upper, 0.0);
    ss::ModelParams white = p;
    white.tau = 0;
    EXPECT_THROW(ss::make_event_constants(white, event(0.05), &table), ss::InvalidParameter);

    const auto piece_of = [&](double v, int s) { return &ss::event_drift_piece(c, v, s) - c.pieces; };
    std::uint64_t crossings = 0, sliding = 0;
    for (std::uint64_t k = 0; k < 40; ++k) {
        ss::BatchedCounterRng rng(6, ss::StreamPurpose::Test, k);
        ss::CounterRng ref(6, ss::StreamPurpose::Refinement, k);
        std::uint64_t last_t = 0;
        bool tiled = true;
        const auto o = ss::event_long_excursion(c, rng, ref, [&](const ss::EventPiece& q) {
            tiled = tiled && q.t0 == last_t && q.t1 > q.t0;
            last_t = q.t1;
            if (q.phase == 0) return;
            ++sliding;
            const long moved = std::labs(piece_of(q.v1, q.phase) - piece_of(q.v0, q.phase));
            EXPECT_LE(moved, 1) << "a piece of the refinement slid across " << moved << " knots, from v = " << q.v0
                                << " to " << q.v1 << " m/s";
            crossings += static_cast<std::uint64_t>(moved);
        });
        ASSERT_FALSE(o.capped);
        EXPECT_TRUE(tiled);
    }
    EXPECT_GT(crossings, 100u) << "the paths must cross knots for this test to mean anything (" << sliding
                               << " sliding pieces)";
}

} // namespace
