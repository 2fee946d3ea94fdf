// SPDX-License-Identifier: BSD-3-Clause
// The Kolmogorov engine's near-white discretisation (src/deterministic/
// near_white/): the noise chain's exact moments and generator, mass
// conservation of the DG operator, convergence uniform in tau' with bounded
// cost, the white-noise limit of three laws, the overlap with the upwind
// chain, and agreement with stored Monte Carlo references.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "deterministic/near_white/discretisation.hpp"
#include "deterministic/near_white/grids.hpp"
#include "stickslip/analytic.hpp"
#include "stickslip/drift_law.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/kolmogorov.hpp"
#include "model_cases.hpp"

namespace ss = stickslip;
namespace nw = stickslip::detail::near_white;

namespace {

/// Pure dry friction at friction = noise = 1 (tau = tau').
ss::ModelParams dry(double tau) { return ss::test::pure_dry_friction(tau); }

/// The Fig. 2 law (relaxation 0.067 s, bias 0.342 m/s^2, friction 3.84, noise
/// 5) at a given tau' (tau' = tau * 2.9491).
ss::ModelParams fig2(double tau_prime) {
    ss::ModelParams p;
    p.tau = tau_prime * (p.noise / (p.friction * p.friction));
    return p;
}

ss::KolmogorovSettings near_white() {
    ss::KolmogorovSettings s;
    s.discretisation = ss::KolmogorovDiscretisation::NearWhite;
    return s;
}

} // namespace

TEST(NearWhiteNoiseChain, MomentsAndGeneratorAreExactOnEveryGrid) {
    // sum w = 1, sum w z = 0, sum w z^2 = 1, detailed balance, and G z =
    // -z/tau' row by row: the force's white-noise intensity is exact on any
    // grid (grids.hpp), whatever tau', the band's place and the level.
    for (double tau : {1.0, 1e-2, 1e-6})
        for (double b0 : {0.0, 0.3})
            for (int level = 0; level <= 3; ++level) {
                const double e = std::sqrt(tau);
                const nw::NoiseGrid g =
                    nw::make_noise_grid(tau, std::sqrt(2.0) * e * (-1 - b0), std::sqrt(2.0) * e * (1 - b0), {}, level);
                double m0 = 0, m1 = 0, m2 = 0;
                for (std::size_t j = 0; j < g.size(); ++j) {
                    m0 += g.weight[j];
                    m1 += g.weight[j] * g.z[j];
                    m2 += g.weight[j] * g.z[j] * g.z[j];
                }
                EXPECT_NEAR(m0, 1.0, 1e-14);
                EXPECT_NEAR(m1, 0.0, 1e-14);
                EXPECT_NEAR(m2, 1.0, 1e-13);
                for (std::size_t j = 0; j + 1 < g.size(); ++j) {
                    ASSERT_GT(g.up[j], 0.0);
                    ASSERT_GT(g.down[j + 1], 0.0);
                    EXPECT_NEAR(g.weight[j] * g.up[j], g.weight[j + 1] * g.down[j + 1],
                                1e-12 * g.weight[j] * g.up[j]);
                }
                for (std::size_t j = 0; j < g.size(); ++j) {
                    const double up = j + 1 < g.size() ? g.up[j] * (g.z[j + 1] - g.z[j]) : 0.0;
                    const double down = j > 0 ? g.down[j] * (g.z[j - 1] - g.z[j]) : 0.0;
                    const double scale = std::abs(up) + std::abs(down) + std::abs(g.z[j]) / tau;
                    EXPECT_NEAR(up + down, -g.z[j] / tau, 1e-9 * scale) << "tau " << tau << " level " << level << " j " << j;
                }
                EXPECT_DOUBLE_EQ(g.z[g.band_lower], std::sqrt(2.0) * e * (-1 - b0));
                EXPECT_DOUBLE_EQ(g.z[g.band_upper], std::sqrt(2.0) * e * (1 - b0));
            }
}

TEST(NearWhiteOperator, ConservesMassColumnByColumn) {
    // The P_0 tests and the stuck states sum to zero over every column: what
    // leaves a cell, a node or the stuck line arrives elsewhere, at v = 0 too.
    const double tau = 0.01;
    const nw::NoiseGrid g = nw::make_noise_grid(tau, -0.2, 0.1, {}, 0);
    nw::VelocityGridShape v;
    v.first_cell = 1e-5;
    const nw::Layout l = nw::make_layout(g, nw::make_velocity_faces(6.0, v, 0), nw::make_velocity_faces(8.0, v, 0));
    for (const ss::DriftLaw& law : {ss::affine_drift_law(INFINITY, 0.0), ss::affine_drift_law(0.5, 0.2)}) {
        const Eigen::SparseMatrix<double> a = nw::forward_operator(l, law, tau);
        std::vector<double> weight(l.size(), 0.0);
        for (std::size_t j = 0; j < g.size(); ++j) {
            for (std::size_t c = 0; c < l.cells_neg(); ++c) weight[l.neg(j, c, 0)] = 1.0;
            for (std::size_t c = 0; c < l.cells_pos(); ++c) weight[l.pos(j, c, 0)] = 1.0;
            if (g.in_band(j)) weight[l.stuck(j)] = 1.0;
        }
        for (Eigen::Index col = 0; col < a.outerSize(); ++col) {
            double sum = 0, largest = 0;
            for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it) {
                sum += weight[static_cast<std::size_t>(it.row())] * it.value();
                largest = std::max(largest, std::abs(it.value()));
            }
            ASSERT_NEAR(sum, 0.0, 1e-12 * largest) << "column " << col;
        }
    }
}

TEST(NearWhiteSolver, TheSameSettingsConvergeUniformlyInTauAtBoundedCost) {
    // Pure dry friction at tau' = 0.05 down to 5e-5 with the default settings
    // (target 0.1%): D within its own estimate of a reference solved to 1e-5 or
    // better (the solver at rel_precision 1e-7 until its 2 GB budget:
    // references below with their estimates), the target reached, and no
    // more rounds or unknowns than a small factor over tau' = 0.05 (the count
    // grows like log(1/tau'): 39075, 48219, 55731, 66555 measured).
    struct Case {
        double tau, reference, reference_error;
    };
    const Case cases[] = {{0.05, 1.158067097, 1.4e-4},
                          {0.005, 1.241894331, 1.7e-5},
                          {5e-4, 1.249230592, 2.7e-6},
                          {5e-5, 1.249924284, 1.2e-6}};
    std::size_t first_states = 0, first_grids = 0;
    for (const Case& c : cases) {
        const ss::KolmogorovResult r = ss::solve_kolmogorov(dry(c.tau), near_white());
        const ss::KolmogorovGridSpan span = ss::grid_span(r);
        if (first_states == 0) first_states = span.largest_states, first_grids = r.levels.size();
        EXPECT_TRUE(r.converged) << "tau' " << c.tau << ": " << r.note;
        const double miss = std::abs(r.diffusivity.value - c.reference);
        EXPECT_LE(miss, r.diffusivity.error + c.reference_error)
            << "tau' " << c.tau << ": D " << r.diffusivity.value << " +- " << r.diffusivity.error << ", reference "
            << c.reference << " (" << miss / r.diffusivity.error << " estimates away)";
        EXPECT_LE(span.largest_states, 2 * first_states) << "tau' " << c.tau;
        EXPECT_LE(r.levels.size(), first_grids) << "tau' " << c.tau;
    }
}

TEST(NearWhiteSolver, TendsToTheWhiteNoiseQuadratureForThreeLaws) {
    // At tau' = 2e-6 D and M0 are within their estimates plus 3.3 tau' D of the
    // white-noise quadrature (the departure, 1 - D/D_white, measured 1.2 tau'
    // and 3.2 tau' for the first two laws: docs/validation.md); below tau' =
    // 1e-6 the solver gives the quadrature itself, with a bound.
    ss::ModelParams tanh_law = dry(2e-6);
    tanh_law.drift = "0.5*tanh(v/0.2) - 0.3*v";
    for (const ss::ModelParams& p : {dry(2e-6), fig2(2e-6), tanh_law}) {
        const ss::WhiteNoiseReference white = ss::white_noise_reference(p);
        const ss::KolmogorovResult r = ss::solve_kolmogorov(p);
        const double tau_prime = ss::to_nondimensional(p).tau;
        EXPECT_NEAR(r.diffusivity.value, white.diffusivity,
                    r.diffusivity.error + 3.3 * tau_prime * white.diffusivity)
            << p.drift;
        EXPECT_NEAR(r.mobility.value, white.mobility,
                    r.mobility.error + 3.3 * tau_prime * std::abs(white.mobility) + 1e-6 * ss::scales_of(p).velocity)
            << p.drift;
        EXPECT_LT(r.diffusivity.error, 1e-4 * white.diffusivity) << p.drift;
        // Var(V) departs faster: 10 tau' relative for the Fig. 2 law (0.10047
        // against 0.10354 at tau' = 0.003).
        EXPECT_NEAR(r.velocity_variance.value, white.variance,
                    r.velocity_variance.error + 20 * tau_prime * white.variance + 1e-6 * white.variance)
            << p.drift;
        ss::ModelParams q = p;
        q.tau *= 1e-3; // tau' = 2e-9: the white-noise limit with a bound
        const ss::KolmogorovResult limit = ss::solve_kolmogorov(q);
        EXPECT_EQ(limit.diffusivity.value, white.diffusivity);
        EXPECT_LT(limit.diffusivity.error, 1e-4 * white.diffusivity);
        EXPECT_EQ(limit.mobility.value, white.mobility);
        EXPECT_EQ(limit.velocity_variance.value, white.variance);
        EXPECT_NE(limit.note.find("white-noise values"), std::string::npos) << limit.note;
    }
}

TEST(NearWhiteSolver, AgreesWithTheChainWhereBothRun) {
    // tau' = 0.05 to 0.1, where the automatic choice switches: D, M0, P(V = 0)
    // and E[t1] within the two estimates (docs/kolmogorov_measurements.md has
    // the comparison up to tau' = 5).
    ss::KolmogorovSettings chain;
    chain.discretisation = ss::KolmogorovDiscretisation::Chain;
    for (double tau : {0.05, 0.07, 0.1})
        for (const ss::ModelParams& p : {dry(tau), fig2(tau)}) {
            const ss::KolmogorovResult a = ss::solve_kolmogorov(p, near_white());
            const ss::KolmogorovResult b = ss::solve_kolmogorov(p, chain);
            auto agree = [&](const char* name, const ss::Estimate& x, const ss::Estimate& y) {
                EXPECT_LE(std::abs(x.value - y.value), x.error + y.error)
                    << name << " at tau' " << tau << ", bias " << p.bias << ": near-white " << x.value << " +- "
                    << x.error << ", chain " << y.value << " +- " << y.error;
            };
            agree("D", a.diffusivity, b.diffusivity);
            // M0 of pure dry friction is 0: both give rounding noise (1e-13).
            const double floor = 1e-9 * ss::scales_of(p).velocity;
            agree("M0", {a.mobility.value, a.mobility.error + floor}, b.mobility);
            // The chain's estimates of P(V = 0) and E[t1] fall short at tau' =
            // 0.05: pure dry friction's P(V = 0) 0.0091133 +- 1.0e-4 against
            // 0.0093290 +- 1.5e-5 (near-white, solved to 1e-7); the Fig. 2 law's
            // E[t1] 0.19053 +- 0.00049 s against 0.19127 +- 0.00004 (near-white)
            // and 0.19144 +- 0.00018 (event scheme, dt = tau/64, 2e6
            // excursions): a reason the chain is not used below 0.1.
            if (tau > 0.05) {
                agree("P(V = 0)", a.stuck_probability, b.stuck_probability);
                agree("E[t1]", a.mean_duration, b.mean_duration);
            }
        }
}

TEST(NearWhiteSolver, AgreesWithStoredMonteCarloReferences) {
    // Event scheme at its automatic step (tau/16) with the control variate
    // (docs/validation.md, "Every correlation time"): pure dry friction,
    // 1e6 excursions, seed 101; the Fig. 2 law, 2e5 excursions, seed 102.
    // Within 3 standard errors plus the solver's estimate.
    struct Case {
        ss::ModelParams p;
        double d, d_se, m0, m0_se;
    };
    const Case cases[] = {{dry(0.01), 1.2334996609, 0.0011932897, -2.1267642e-06, 1.5512867e-05},
                          {fig2(0.01), 0.0084329566, 2.499e-06, 0.013882270, 8.4e-06}};
    for (const Case& c : cases) {
        const ss::KolmogorovResult r = ss::solve_kolmogorov(c.p);
        const double zd = (r.diffusivity.value - c.d) / std::hypot(c.d_se, r.diffusivity.error);
        const double zm = (r.mobility.value - c.m0) / std::hypot(c.m0_se, r.mobility.error);
        EXPECT_LE(std::abs(r.diffusivity.value - c.d), 3 * c.d_se + r.diffusivity.error) << "z = " << zd;
        EXPECT_LE(std::abs(r.mobility.value - c.m0), 3 * c.m0_se + r.mobility.error) << "z = " << zm;
    }
}

TEST(NearWhiteSolver, RefusesWhatIsNotItsOwn) {
    auto parameter_of = [](auto&& f) {
        try {
            f();
        } catch (const ss::InvalidParameter& e) {
            return std::string(e.parameter());
        }
        return std::string("(none)");
    };
    ss::KolmogorovSettings lattice = near_white();
    lattice.pdmp_grid = 0.125;
    EXPECT_EQ(parameter_of([&] { ss::validate_kolmogorov(fig2(0.01), lattice); }), "pdmp_grid");
    EXPECT_EQ(parameter_of([&] { ss::validate_kolmogorov(dry(0.0), near_white()); }), "tau");
    EXPECT_EQ(parameter_of([&] { ss::validate_kolmogorov(dry(1e-30), near_white()); }), "(none)");
    // The automatic choice: near-white below tau' = 0.1 and without drag, the
    // chain with drag from 0.1 up.
    EXPECT_EQ(ss::resolved_discretisation(fig2(0.0999), {}), ss::KolmogorovDiscretisation::NearWhite);
    EXPECT_EQ(ss::resolved_discretisation(fig2(0.11), {}), ss::KolmogorovDiscretisation::Chain);
    EXPECT_EQ(ss::resolved_discretisation(dry(1.0), {}), ss::KolmogorovDiscretisation::NearWhite);
    // Beyond what the grids resolve: the noise leaving the band (stuck for
    // ever) or reaching it (never stuck) with probability below 1e-12.
    EXPECT_EQ(parameter_of([&] { ss::validate_kolmogorov(dry(30.0), {}); }), "tau");
    EXPECT_EQ(parameter_of([&] { ss::validate_kolmogorov(dry(20.0), {}); }), "(none)");
    ss::ModelParams driven; // the Fig. 2 case
    driven.bias = 100.0;    // 26 times the friction: the noise never brings the force back into the band
    EXPECT_EQ(parameter_of([&] { ss::validate_kolmogorov(driven, {}); }), "bias");
}
