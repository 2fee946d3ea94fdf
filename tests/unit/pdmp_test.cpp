// SPDX-License-Identifier: BSD-3-Clause
// PDMP engine constants and kernels (pdmp.hpp, theory.md, section 4) against
// independent references: a classical RK4 solve of the between-jump ODE
//   dV/dt = |y| (-V/tauL + bias + a x - y friction),  dU/dt = V,
// brute-force scans of the lattice for the thresholds, and the exact
// birth-death stationary law of the lattice noise.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "stickslip/params.hpp"
#include "stickslip/kernels/pdmp.hpp"

namespace ss = stickslip;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

ss::ModelParams fig2() { return ss::ModelParams{}; } // defaults: the paper's Fig. 2 case

ss::ModelParams dry() {
    ss::ModelParams p;
    p.friction = 1.0;
    p.noise = 1.0;
    p.tau = 0.5;
    p.relaxation = kInf;
    p.bias = 0.2;
    return p;
}

ss::EngineSettings grid(double g) {
    ss::EngineSettings s = ss::fixed_step_settings(ss::Scheme::Resolvent, 1e-4);
    s.engine = ss::Engine::Pdmp;
    s.grid = g;
    return s;
}

// Independent ODE right-hand side built from the model parameters (not from the
// library's constants).
struct Ode {
    double inv_tl, bias, force, friction;
    int y;
    double dv(double v) const { return std::abs(y) * (-v * inv_tl + bias + force - y * friction); }
};

struct OdeState {
    double v, u;
};

OdeState rk4_step(const Ode& f, OdeState s, double h) {
    const double k1v = f.dv(s.v), k1u = s.v;
    const double k2v = f.dv(s.v + 0.5 * h * k1v), k2u = s.v + 0.5 * h * k1v;
    const double k3v = f.dv(s.v + 0.5 * h * k2v), k3u = s.v + 0.5 * h * k2v;
    const double k4v = f.dv(s.v + h * k3v), k4u = s.v + h * k3v;
    return {s.v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v), s.u + h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u)};
}

OdeState rk4_solve(const Ode& f, OdeState s, double t, int steps) {
    const double h = t / steps;
    for (int k = 0; k < steps; ++k) s = rk4_step(f, s, h);
    return s;
}

// First time V reaches 0 (V starts with the sign of y), by RK4 marching with step
// h and a bisection on the length of the last RK4 substep; +inf if V keeps its
// sign up to t_max.
double rk4_hitting_time(const Ode& f, double v0, double h, double t_max) {
    OdeState s{v0, 0.0};
    double t = 0.0;
    while (t < t_max) {
        const OdeState n = rk4_step(f, s, h);
        if (f.y * n.v <= 0.0) {
            double lo = 0.0, hi = h;
            for (int k = 0; k < 200 && hi - lo > 0; ++k) {
                const double mid = 0.5 * (lo + hi);
                if (mid == lo || mid == hi) break;
                (f.y * rk4_step(f, s, mid).v > 0.0 ? lo : hi) = mid;
            }
            return t + 0.5 * (lo + hi);
        }
        s = n;
        t += h;
    }
    return kInf;
}

Ode ode_for(const ss::ModelParams& p, double x, int y) {
    return Ode{std::isinf(p.relaxation) ? 0.0 : 1.0 / p.relaxation, p.bias, std::sqrt(p.noise / 2.0) * x,
               p.friction, y};
}

struct Case {
    int i, y;
    double v;
    bool hits;
};

void check_flow_and_hitting(const ss::ModelParams& p, const ss::PdmpConstants& c, const std::vector<Case>& cases) {
    for (const Case& k : cases) {
        const double x = k.i * c.delta;
        const Ode f = ode_for(p, x, k.y);
        const std::string where = "state (i=" + std::to_string(k.i) + ", y=" + std::to_string(k.y) +
                                  ", v=" + std::to_string(k.v) + ")";
        // Hitting time.
        const double t_hit = ss::pdmp_hitting_time(c, k.i, k.y, k.v);
        const double t_ref = rk4_hitting_time(f, k.v, 1e-4, 20.0);
        if (k.hits) {
            ASSERT_TRUE(std::isfinite(t_ref)) << "test setup: " << where << " should hit 0";
            EXPECT_NEAR(t_hit, t_ref, 1e-10 * t_ref + 1e-14) << where;
        } else {
            ASSERT_FALSE(std::isfinite(t_ref)) << "test setup: " << where << " should never hit 0";
            EXPECT_EQ(t_hit, kInf) << where;
        }
        // Flow over several durations (before the hitting time when it hits).
        for (double frac : {0.01, 0.3, 0.7, 0.999}) {
            const double t = k.hits ? frac * t_ref : frac * 3.0;
            double v_out = -12345.0, du = 0.25; // du accumulates
            ss::pdmp_flow(c, k.i, k.y, k.v, t, v_out, du);
            const OdeState ref = rk4_solve(f, {k.v, 0.25}, t, 20000);
            EXPECT_NEAR(v_out, ref.v, 1e-11 * (std::fabs(ref.v) + std::fabs(k.v) + 1.0)) << where << " t=" << t;
            EXPECT_NEAR(du, ref.u, 1e-11 * (std::fabs(ref.u) + 1.0)) << where << " t=" << t;
        }
        // At the hitting time the flow is at V = 0.
        if (k.hits) {
            double v_out, du = 0.0;
            ss::pdmp_flow(c, k.i, k.y, k.v, t_hit, v_out, du);
            EXPECT_NEAR(v_out, 0.0, 1e-12 * (std::fabs(k.v) + 1.0)) << where;
        }
    }
}

} // namespace

TEST(PdmpConstants, Fig2CaseLatticeAndRates) {
    const ss::ModelParams p = fig2();
    const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(0.125));
    EXPECT_EQ(c.delta, 0.125);
    EXPECT_NEAR(c.rate, 2.0 / std::pow(p.tau * 0.125, 2), 1e-12 * c.rate);
    EXPECT_NEAR(c.half_tau_delta, p.tau * 0.125 / 2, 1e-16);
    EXPECT_NEAR(c.amp, std::sqrt(p.noise / 2), 1e-15);
    EXPECT_TRUE(c.viscous);
    EXPECT_EQ(c.relaxation, p.relaxation);
    // L: 8 stationary sd (tau^-1/2), holds both thresholds, and tau*delta*L < 2.
    const double L = c.n_max * c.delta;
    EXPECT_GE(L, 8.0 / std::sqrt(p.tau) - 1e-12);
    EXPECT_LT(p.tau * c.delta * L, 2.0);
    EXPECT_GE(L, p.upper_threshold() + c.delta);
    EXPECT_LE(-L, p.lower_threshold() - c.delta);
}

TEST(PdmpConstants, ThresholdIndicesByDefinition) {
    for (const ss::ModelParams& p : {fig2(), dry()}) {
        for (double g : {0.125, 0.05, 0.3}) {
            const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(g));
            const double a = std::sqrt(p.noise / 2.0);
            // k+: last lattice index with a x <= friction - b(0); k-: first with a x >= -friction - b(0).
            int kp = -c.n_max - 1, km = c.n_max + 1;
            for (int i = -c.n_max; i <= c.n_max; ++i) {
                const double ax = a * (i * g);
                if (ax <= p.friction - p.bias) kp = i;
                if (ax >= -p.friction - p.bias && km == c.n_max + 1) km = i;
            }
            EXPECT_EQ(c.k_plus, kp) << "grid " << g << " bias " << p.bias;
            EXPECT_EQ(c.k_minus, km) << "grid " << g << " bias " << p.bias;
            // The regeneration states s+- must lie strictly inside the lattice.
            EXPECT_LT(c.k_plus + 1, c.n_max);
            EXPECT_GT(c.k_minus - 1, -c.n_max);
            // Against the continuous thresholds x*, x-*.
            EXPECT_LE(c.k_plus * g, p.upper_threshold() + 1e-12);
            EXPECT_GT((c.k_plus + 1) * g, p.upper_threshold());
            EXPECT_GE(c.k_minus * g, p.lower_threshold() - 1e-12);
            EXPECT_LT((c.k_minus - 1) * g, p.lower_threshold());
        }
    }
    // Fig. 2 numbers by hand: (3.84 - 0.342)/(sqrt(2.5)*0.125) = 17.70, (-3.84 - 0.342)/... = -21.16.
    const ss::PdmpConstants c = ss::make_pdmp_constants(fig2(), grid(0.125));
    EXPECT_EQ(c.k_plus, 17);
    EXPECT_EQ(c.k_minus, -21);
}

TEST(PdmpKernels, FlowAndHittingTimeMatchOdeSolveViscous) {
    const ss::ModelParams p = fig2();
    const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(0.125));
    // Fig. 2: a*delta = 0.198, bias 0.342, friction 3.84, tauL 0.067.
    check_flow_and_hitting(p, c,
                           {
                               {0, +1, 1.0, true},     // k = -3.50: decelerates to 0
                               {10, -1, -2.0, true},   // k = +6.16 pushing a negative velocity up
                               {17, +1, 0.3, true},    // k = -0.14 (top of the band): slow stop
                               {-21, -1, -0.05, true}, // bottom of the band, k = +0.02 -> slow stop
                               {30, +1, 0.5, false},   // k = +2.43: accelerates away
                               {-30, -1, -0.5, false}, // k = -1.75 with y = -1: never stops
                               {18, +1, 0.0, false},   // just above the band, from rest
                               {-22, -1, 0.0, false},  // just below the band, from rest
                               {50, +1, 3.0, false},
                           });
}

TEST(PdmpKernels, FlowAndHittingTimeMatchOdeSolveDryFriction) {
    const ss::ModelParams p = dry();
    const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(0.125));
    EXPECT_FALSE(c.viscous);
    // a*delta = 0.0884, bias 0.2, friction 1.
    check_flow_and_hitting(p, c,
                           {
                               {0, +1, 1.0, true},    // k = -0.8
                               {0, -1, -1.0, true},   // k = +1.2
                               {9, +1, 0.04, true},   // k = -0.0045: long stop (8.9 s)
                               {-13, -1, -0.2, true}, // k = +0.051
                               {10, +1, 0.1, false},  // k = +0.084
                               {-14, -1, -0.1, false},
                               {40, +1, 2.0, false},
                           });
}

TEST(PdmpKernels, StaticModeDoesNotMove) {
    const ss::PdmpConstants c = ss::make_pdmp_constants(fig2(), grid(0.125));
    EXPECT_EQ(ss::pdmp_hitting_time(c, 3, 0, 0.0), kInf);
    double v = 7.0, du = 1.5;
    ss::pdmp_flow(c, 3, 0, 0.0, 2.0, v, du);
    EXPECT_EQ(v, 0.0);
    EXPECT_EQ(du, 1.5);
}

TEST(PdmpKernels, AccelerationAtRest) {
    const ss::ModelParams p = fig2();
    const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(0.125));
    for (int i : {-40, -21, 0, 17, 40})
        for (int y : {-1, 0, 1})
            EXPECT_NEAR(ss::pdmp_acceleration(c, i, y),
                        p.bias + std::sqrt(p.noise / 2) * i * 0.125 - y * p.friction, 1e-14)
                << i << " " << y;
}

TEST(PdmpKernels, UpProbability) {
    for (const ss::ModelParams& p : {fig2(), dry()}) {
        const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(0.125));
        EXPECT_EQ(ss::pdmp_up_probability(c, c.n_max), 0.0);
        EXPECT_EQ(ss::pdmp_up_probability(c, -c.n_max), 1.0);
        EXPECT_DOUBLE_EQ(ss::pdmp_up_probability(c, 0), 0.5);
        for (int i = -c.n_max + 1; i < c.n_max; ++i) {
            const double x = i * 0.125;
            const double alpha = 0.5 * (1.0 - p.tau * 0.125 * x / 2.0);
            EXPECT_NEAR(ss::pdmp_up_probability(c, i), alpha, 1e-15) << "i=" << i;
            EXPECT_GT(ss::pdmp_up_probability(c, i), 0.0);
            EXPECT_LT(ss::pdmp_up_probability(c, i), 1.0);
            // Symmetry alpha(-x) = 1 - alpha(x).
            EXPECT_NEAR(ss::pdmp_up_probability(c, -i), 1.0 - ss::pdmp_up_probability(c, i), 1e-15);
        }
    }
}

TEST(PdmpKernels, ModeAtRestFollowsTheForce) {
    // When V reaches 0 the object sticks if the force at rest, b(0) + a x, is inside
    // [-friction, friction]; otherwise it moves on in the direction of the force.
    for (const ss::ModelParams& p : {fig2(), dry()}) {
        const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(0.125));
        const double a = std::sqrt(p.noise / 2.0);
        for (int i = -c.n_max; i <= c.n_max; ++i) {
            const double force = p.bias + a * i * 0.125;
            // Arriving from positive velocity: sticks unless force < -friction.
            EXPECT_EQ(ss::pdmp_mode_at_rest(c, i, +1), force < -p.friction ? -1 : 0) << "i=" << i;
            // Arriving from negative velocity: sticks unless force > friction.
            EXPECT_EQ(ss::pdmp_mode_at_rest(c, i, -1), force > p.friction ? +1 : 0) << "i=" << i;
        }
    }
}

TEST(PdmpConstants, ValidationErrorsNameTheParameter) {
    auto expect_bad = [](const ss::ModelParams& p, const ss::EngineSettings& s, const char* name) {
        try {
            ss::make_pdmp_constants(p, s);
            ADD_FAILURE() << "no error, expected one naming " << name;
        } catch (const ss::InvalidParameter& e) {
            EXPECT_EQ(e.parameter(), name) << e.what();
        }
    };
    // Fig. 2 with grid 1: tau*grid*L < 2 allows only L <= 3 (n = 3), but x* = 2.21
    // needs index k+ + 2 = 4.
    expect_bad(fig2(), grid(1.0), "grid");
    // grid 2: not even one lattice point fits (tau grid^2 = 2).
    expect_bad(fig2(), grid(2.0), "grid");
    expect_bad(fig2(), grid(0.0), "grid");
    expect_bad(fig2(), grid(-0.1), "grid");
    expect_bad(fig2(), grid(std::numeric_limits<double>::quiet_NaN()), "grid");
    ss::ModelParams w = fig2();
    w.tau = 0.0;
    expect_bad(w, grid(0.125), "tau");
    ss::ModelParams runaway = dry();
    runaway.bias = 1.0; // |bias| >= friction with no viscous drag
    expect_bad(runaway, grid(0.125), "bias");
    // And the boundary case that does fit.
    EXPECT_NO_THROW(ss::make_pdmp_constants(fig2(), grid(0.5)));
}

TEST(PdmpConstants, LatticeStationaryLawHasVarianceOneOverTau) {
    // The jump rate is the same at every lattice point, so the stationary law is that
    // of the embedded birth-death chain: pi_{i+1}/pi_i = alpha_i / (1 - alpha_{i+1}).
    for (const ss::ModelParams& p : {fig2(), dry()}) {
        for (double g : {0.125, 0.25}) {
            const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(g));
            std::vector<long double> w(2 * c.n_max + 1);
            w[0] = 1.0L;
            for (int i = -c.n_max; i < c.n_max; ++i) {
                const long double up = ss::pdmp_up_probability(c, i);
                const long double down_next = 1.0L - ss::pdmp_up_probability(c, i + 1);
                w[i + 1 + c.n_max] = w[i + c.n_max] * up / down_next;
            }
            long double z = 0, m = 0, m2 = 0;
            for (int i = -c.n_max; i <= c.n_max; ++i) {
                const long double x = i * g;
                z += w[i + c.n_max];
                m += x * w[i + c.n_max];
                m2 += x * x * w[i + c.n_max];
            }
            m /= z;
            const double var = static_cast<double>(m2 / z - m * m);
            EXPECT_NEAR(static_cast<double>(m), 0.0, 1e-12) << "grid " << g;
            // The untruncated chain is an Ehrenfest urn whose variance is exactly 1/tau;
            // truncation at 8 sd moves it by far less than the 1e-2 the brief allows.
            EXPECT_NEAR(var, 1.0 / p.tau, 1e-2 / p.tau) << "grid " << g << " n_max " << c.n_max;
            EXPECT_NEAR(var, 1.0 / p.tau, 1e-9 / p.tau) << "grid " << g << " n_max " << c.n_max;
        }
    }
}

namespace {
// Replays fixed uniforms: wait = -log(u0)/rate, jump up iff u1 <= alpha.
struct ScriptedRng {
    std::vector<std::pair<double, double>> script;
    std::size_t next = 0;
    /// The script's pair (u0, u1) as the draw (exponential -log u0, uniform u1).
    void exponential_uniform(double& e, double& u1) {
        e = -std::log(script.at(next).first);
        u1 = script.at(next).second;
        ++next;
    }
};
} // namespace

TEST(PdmpKernels, EventLogicWithScriptedRandomNumbers) {
    const ss::ModelParams p = fig2();
    const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(0.125));
    const double inf = kInf;
    {
        // Static at the top of the band, jump up: starts moving up from x_{k+ +1}.
        ss::PdmpState s{c.k_plus, 0, 0.0};
        ScriptedRng rng{{{0.5, 0.0}}};
        double time = 0.0, disp = 0.0;
        ASSERT_TRUE(ss::pdmp_event(c, s, rng, time, disp, inf));
        EXPECT_EQ(s.i, c.k_plus + 1);
        EXPECT_EQ(s.y, 1);
        EXPECT_EQ(s.v, 0.0);
        EXPECT_NEAR(time, -std::log(0.5) / c.rate, 1e-15);
        EXPECT_EQ(disp, 0.0);
    }
    {
        // Static at the bottom of the band, jump down: starts moving down.
        ss::PdmpState s{c.k_minus, 0, 0.0};
        ScriptedRng rng{{{0.5, 1.0}}};
        double time = 0.0, disp = 0.0;
        ASSERT_TRUE(ss::pdmp_event(c, s, rng, time, disp, inf));
        EXPECT_EQ(s.i, c.k_minus - 1);
        EXPECT_EQ(s.y, -1);
    }
    {
        // Static inside the band, jump up: stays static.
        ss::PdmpState s{0, 0, 0.0};
        ScriptedRng rng{{{0.5, 0.0}}};
        double time = 0.0, disp = 0.0;
        ss::pdmp_event(c, s, rng, time, disp, inf);
        EXPECT_EQ(s.i, 1);
        EXPECT_EQ(s.y, 0);
    }
    {
        // Moving up at x = 0: the velocity reaches 0 before a very late jump (u0 tiny),
        // and the object sticks (force at rest inside the band).
        ss::PdmpState s{0, 1, 1.0};
        ScriptedRng rng{{{1e-300, 0.0}}};
        double time = 0.0, disp = 0.0;
        ss::pdmp_event(c, s, rng, time, disp, inf);
        const double t_hit = ss::pdmp_hitting_time(c, 0, 1, 1.0);
        double v_ref, du_ref = 0.0;
        ss::pdmp_flow(c, 0, 1, 1.0, t_hit, v_ref, du_ref);
        EXPECT_EQ(s.v, 0.0);
        EXPECT_EQ(s.y, 0);
        EXPECT_EQ(s.i, 0); // no jump applied
        EXPECT_NEAR(time, t_hit, 1e-15);
        EXPECT_NEAR(disp, du_ref, 1e-15);
    }
    {
        // Horizon before the event: stops exactly at the horizon, returns false.
        ss::PdmpState s{0, 1, 1.0};
        ScriptedRng rng{{{1e-300, 0.0}}};
        double time = 0.0, disp = 0.0;
        EXPECT_FALSE(ss::pdmp_event(c, s, rng, time, disp, 0.01));
        double v_ref, du_ref = 0.0;
        ss::pdmp_flow(c, 0, 1, 1.0, 0.01, v_ref, du_ref);
        EXPECT_EQ(time, 0.01);
        EXPECT_NEAR(s.v, v_ref, 1e-15);
        EXPECT_NEAR(disp, du_ref, 1e-15);
    }
}

TEST(PdmpKernels, InitialStateRoundsToLatticeAndPicksMode) {
    const ss::PdmpConstants c = ss::make_pdmp_constants(fig2(), grid(0.125));
    EXPECT_EQ(ss::pdmp_initial_state(c, 0.3, 0.0).i, 2); // 0.3/0.125 = 2.4
    EXPECT_EQ(ss::pdmp_initial_state(c, 0.3, 0.0).y, 0);
    EXPECT_EQ(ss::pdmp_initial_state(c, 1e6, 0.0).i, c.n_max);
    EXPECT_EQ(ss::pdmp_initial_state(c, -1e6, 0.0).i, -c.n_max);
    EXPECT_EQ(ss::pdmp_initial_state(c, 0.0, 0.5).y, 1);
    EXPECT_EQ(ss::pdmp_initial_state(c, 0.0, -0.5).y, -1);
    EXPECT_EQ(ss::pdmp_initial_state(c, (c.k_plus + 1) * 0.125, 0.0).y, 1);
    EXPECT_EQ(ss::pdmp_initial_state(c, (c.k_minus - 1) * 0.125, 0.0).y, -1);
    EXPECT_EQ(ss::pdmp_initial_state(c, c.k_plus * 0.125, 0.0).y, 0);
}

TEST(PdmpConstants, StaticBandEdgesAreTheStaticFrictions) {
    // With a static friction Delta_s > Delta the lattice is shifted and its
    // step shortened so that both static edges, where |b(0) + a x| = Delta_s,
    // are lattice points k- - 1 and k+ + 1 (a slip starts there, on time);
    // the band k- .. k+ is the points strictly between: a stuck object stays
    // there and a landing one sticks there; the flows slide against Delta.
    for (double g : {0.125, 0.05, 0.025}) {
        for (ss::ModelParams p : {fig2(), dry()}) {
            p.static_friction = 1.5 * p.friction;
            const ss::PdmpConstants c = ss::make_pdmp_constants(p, grid(g));
            const double a = std::sqrt(p.noise / 2.0);
            EXPECT_LE(c.delta, g);
            EXPECT_GT(c.delta, g * (1.0 - 2.0 * g * a / (2.0 * p.static_friction)));
            EXPECT_LE(std::fabs(c.x_offset), 0.5 * c.delta + 1e-15);
            const double tol = 1e-9 * p.static_friction;
            EXPECT_NEAR(p.bias + a * ss::pdmp_noise(c, c.k_plus + 1), p.static_friction, tol) << "grid " << g;
            EXPECT_NEAR(p.bias + a * ss::pdmp_noise(c, c.k_minus - 1), -p.static_friction, tol) << "grid " << g;
            for (int i = -c.n_max; i <= c.n_max; ++i) {
                const double force = p.bias + a * ss::pdmp_noise(c, i);
                const bool in_band = i >= c.k_minus && i <= c.k_plus;
                if (in_band) {
                    EXPECT_LT(std::fabs(force), p.static_friction - tol) << "i=" << i;
                } else {
                    EXPECT_GT(std::fabs(force), p.static_friction - tol) << "i=" << i;
                }
                EXPECT_EQ(ss::pdmp_mode_at_rest(c, i, +1), i < c.k_minus ? -1 : 0) << "i=" << i;
                EXPECT_EQ(ss::pdmp_mode_at_rest(c, i, -1), i > c.k_plus ? +1 : 0) << "i=" << i;
                EXPECT_NEAR(ss::pdmp_acceleration(c, i, +1), force - p.friction, tol) << "i=" << i;
                // The chain's drift, delta Lambda (2 alpha_i - 1), is the OU's -x/tau at every inner point.
                if (std::abs(i) < c.n_max) {
                    EXPECT_NEAR(c.delta * c.rate * (2.0 * ss::pdmp_up_probability(c, i) - 1.0),
                                -ss::pdmp_noise(c, i) / p.tau, 1e-9 / p.tau)
                        << "i=" << i;
                }
            }
            // The lattice stays where the up probability is in [0, 1].
            EXPECT_GE(ss::pdmp_up_probability(c, c.n_max - 1), 0.0);
            EXPECT_LE(ss::pdmp_up_probability(c, -c.n_max + 1), 1.0);
            // The slip starts with the jump in acceleration Delta_s - Delta > 0.
            EXPECT_NEAR(ss::pdmp_acceleration(c, c.k_plus + 1, +1), p.static_friction - p.friction, tol);
            EXPECT_NEAR(ss::pdmp_acceleration(c, c.k_minus - 1, -1), p.friction - p.static_friction, tol);
            // Equal to the friction, the lattice and band are the one-coefficient model's.
            ss::ModelParams q = p;
            q.static_friction = q.friction;
            ss::ModelParams unset = p;
            unset.static_friction = std::numeric_limits<double>::quiet_NaN();
            const ss::PdmpConstants ce = ss::make_pdmp_constants(q, grid(g));
            const ss::PdmpConstants cu = ss::make_pdmp_constants(unset, grid(g));
            EXPECT_EQ(ce.k_plus, cu.k_plus);
            EXPECT_EQ(ce.k_minus, cu.k_minus);
            EXPECT_EQ(ce.n_max, cu.n_max);
            EXPECT_EQ(ce.delta, g);
            EXPECT_EQ(ce.x_offset, 0.0);
        }
    }
}
