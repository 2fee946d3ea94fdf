// SPDX-License-Identifier: BSD-3-Clause
// The corrector of the control variate (corrector.hpp): chi_x from one coarse
// grid of the Kolmogorov solver's chain, or white noise's closed form,
// resampled on the uniform tables the kernels read in O(1).
#include "stickslip/corrector.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

#include "core/format.hpp"
#include "deterministic/kolmogorov/chain.hpp"
#include "deterministic/near_white/corrector_table.hpp"
#include "stickslip/drift_input.hpp"
#include "stickslip/drift_law_quadrature.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/setting.hpp"

namespace stickslip {

namespace {

/// Velocity nodes of the sliding table: the table is uniform in v, and the
/// chain's cells are graded at 0, so it takes more nodes than the chain has
/// cells (measured: 257 and 1025 nodes removed the same variance within 2%
/// on the Fig. 2 case).
constexpr int slide_v_nodes = 513;

/// Linear interpolation of the samples (xs increasing, ys) at x, constant
/// beyond the ends.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
    if (x <= xs.front()) return ys.front();
    if (x >= xs.back()) return ys.back();
    const auto it = std::upper_bound(xs.begin(), xs.end(), x);
    const std::size_t i = static_cast<std::size_t>(it - xs.begin()) - 1;
    const double f = (x - xs[i]) / (xs[i + 1] - xs[i]);
    return ys[i] + f * (ys[i + 1] - ys[i]);
}

/// The chain's corrector from tau' = 0.1 up, unless its velocity range holds
/// more than this of the mass at its edges: a weakly confining law (no drag
/// and a bias near the friction) reaches far beyond it, and the chain's
/// corrector then removed no variance at all (measured: a factor 1.0 at
/// --relaxation inf --bias 3.5, tail mass 0.06), where the near-white one
/// follows the law's range. The Fig. 2 case's is 5e-12, pure dry friction's
/// at tau' = 1 1e-7.
constexpr double kCorrectorEdgeMass = 1e-3;

std::shared_ptr<Corrector> coloured_corrector(const Model& model) {
    namespace k = detail::kolmogorov;
    const ModelParams& p = model.params;
    const stickslip::DriftLaw& law = *model.law;
    const k::DriftLaw drift(law);
    KolmogorovSettings settings;
    const KolmogorovGrid grid = k::make_kolmogorov_grid(p, settings, corrector_grid_level, drift);
    const k::ChainGrid cg = k::make_grid(p, grid);
    const k::Chain chain = k::build_chain(p, cg, drift);
    const k::ChainSolution sol = k::solve_chain(chain);
    if (sol.tail_mass > kCorrectorEdgeMass) return detail::near_white::make_corrector(p, law);

    const std::size_t nx = cg.x.size(), mn = cg.cells_neg(), mp = cg.cells_pos();
    // chi per node on the sliding cells, in increasing v (the chain orders each
    // node's negative cells from the far end towards 0, then its stuck state,
    // then its positive cells from 0 outwards), and on the stuck state.
    std::vector<double> mids(mn + mp);
    std::vector<std::vector<double>> chi(nx, std::vector<double>(mn + mp));
    std::vector<double> chi_stuck(nx, 0.0);
    for (std::size_t j = 0; j < nx; ++j) {
        std::size_t s = chain.first[j];
        for (std::size_t i = 0; i < mn; ++i, ++s) {
            chi[j][i] = sol.chi[s];
            mids[i] = chain.velocity[s];
        }
        if (cg.in_band(j)) chi_stuck[j] = sol.chi[s++];
        for (std::size_t i = 0; i < mp; ++i, ++s) {
            chi[j][mn + i] = sol.chi[s];
            mids[mn + i] = chain.velocity[s];
        }
    }
    auto c = std::make_shared<Corrector>();
    c->source = "kolmogorov";
    c->diffusivity = sol.diffusivity;
    const double h = cg.x[1] - cg.x[0];
    // Sliding: chi_x at the midpoints between nodes, per cell, then resampled
    // on a uniform velocity grid.
    const int tx = static_cast<int>(nx) - 1;
    const double v_lo = mids.front(), v_hi = mids.back();
    const double dv = (v_hi - v_lo) / (slide_v_nodes - 1);
    c->slide.resize(static_cast<std::size_t>(tx) * slide_v_nodes);
    std::vector<double> g_cells(mn + mp);
    for (int i = 0; i < tx; ++i) {
        for (std::size_t m = 0; m < mn + mp; ++m) g_cells[m] = (chi[i + 1][m] - chi[i][m]) / h;
        for (int kv = 0; kv < slide_v_nodes; ++kv)
            c->slide[static_cast<std::size_t>(i) * slide_v_nodes + kv] = interpolate(mids, g_cells, v_lo + kv * dv);
    }
    // Stuck: chi_x along the band, from x-* to x*; at the band's edges a
    // stuck path launches, so chi there is that of the first sliding cell in
    // the launch's direction.
    const std::size_t lo = cg.stuck_first - 1, hi = cg.stuck_last + 1;
    std::vector<double> line(hi - lo + 1);
    for (std::size_t j = lo; j <= hi; ++j)
        line[j - lo] = j == lo ? chi[j][mn - 1] : (j == hi ? chi[j][mn] : chi_stuck[j]);
    c->stuck.resize(line.size() - 1);
    for (std::size_t j = 0; j + 1 < line.size(); ++j) c->stuck[j] = (line[j + 1] - line[j]) / h;

    CorrectorTable& t = c->table;
    t.nx = tx;
    t.nv = slide_v_nodes;
    t.x_first = cg.x[0] + 0.5 * h;
    t.inv_dx = 1.0 / h;
    t.v_first = v_lo;
    t.inv_dv = 1.0 / dv;
    t.ns = static_cast<int>(c->stuck.size());
    t.s_first = cg.x[lo] + 0.5 * h;
    t.inv_ds = 1.0 / h;
    if (t.ns < 2) { // a band of one interval: its one value, twice
        c->stuck.push_back(c->stuck.back());
        t.ns = 2;
    }
    c->grid = "x " + std::to_string(nx) + " nodes, v " + std::to_string(mn) + " + " + std::to_string(mp) + " cells";
    return c;
}

/// White noise: chi' = -(2/noise) F/p with F(v) = int (u - M0) p(u) du from
/// the nearer end of the velocity range (so that F/p keeps its digits in both
/// tails), on a uniform grid.
std::shared_ptr<Corrector> white_corrector(const ModelParams& p) {
    const DriftLawWhiteNoise law(p);
    constexpr int n = 4097;
    // The range: where the density has fallen below 1e-15 of its largest value.
    const double unit = p.noise / p.friction, dv0 = unit / 64.0;
    double p_max = law.density(0.0);
    auto edge = [&](double sign) {
        double v = 0.0;
        for (int k = 0; k < 1 << 22; ++k) {
            v += sign * dv0;
            const double d = law.density(v);
            p_max = std::max(p_max, d);
            if (d < 1e-15 * p_max && std::fabs(v) > unit) break;
        }
        return v;
    };
    const double hi = edge(+1.0), lo = edge(-1.0);
    const double dv = (hi - lo) / (n - 1);
    std::vector<double> v(n), dens(n);
    for (int i = 0; i < n; ++i) {
        v[i] = lo + i * dv;
        dens[i] = law.density(v[i]);
    }
    double m0 = 0.0, mass = 0.0;
    for (int i = 0; i < n; ++i) {
        const double w = (i == 0 || i == n - 1) ? 0.5 : 1.0;
        m0 += w * v[i] * dens[i];
        mass += w * dens[i];
    }
    m0 /= mass;
    std::vector<double> below(n, 0.0), above(n, 0.0); // int from lo to v, from v to hi
    for (int i = 1; i < n; ++i)
        below[i] = below[i - 1] + 0.5 * dv * ((v[i - 1] - m0) * dens[i - 1] + (v[i] - m0) * dens[i]);
    for (int i = n - 2; i >= 0; --i)
        above[i] = above[i + 1] + 0.5 * dv * ((v[i + 1] - m0) * dens[i + 1] + (v[i] - m0) * dens[i]);
    auto c = std::make_shared<Corrector>();
    c->source = "closed-form";
    c->slide.resize(n);
    double d = 0.0;
    for (int i = 0; i < n; ++i) {
        const double f = v[i] <= m0 ? below[i] : -above[i];
        const double g = dens[i] > 0 ? -(2.0 / p.noise) * f / dens[i] : 0.0;
        c->slide[i] = std::isfinite(g) ? g : 0.0;
        const double w = (i == 0 || i == n - 1) ? 0.5 : 1.0;
        d += w * dv * dens[i] * p.noise * c->slide[i] * c->slide[i];
    }
    c->diffusivity = d / (mass * dv);
    CorrectorTable& t = c->table;
    t.nx = 1;
    t.nv = n;
    t.v_first = lo;
    t.inv_dv = 1.0 / dv;
    c->grid = "v " + std::to_string(n) + " nodes";
    return c;
}

} // namespace

bool has_corrector(const ModelParams& p, std::string* why) {
    if (p.white()) return true;
    const double tau_prime = to_nondimensional(p).tau;
    if (tau_prime >= kolmogorov_white_limit_below) return true;
    if (why)
        *why = "tau' = " + detail::format_number(tau_prime) + " is below " +
               detail::format_number(kolmogorov_white_limit_below) +
               ", where the Kolmogorov solver's grids give way to the white-noise limit and no corrector";
    return false;
}

std::shared_ptr<const Corrector> make_corrector(const ModelParams& p) { return make_corrector(make_model(p)); }

std::shared_ptr<const Corrector> make_corrector(const Model& m) {
    const ModelParams& p = m.params;
    std::string why;
    if (!has_corrector(p, &why)) throw InvalidParameter("control-variate", "no corrector: " + why);
    // The last corrector made is kept: a sweep's --check-dt twin, a loop of
    // runs from Python and a coverage study ask for the same model again and
    // again, and the table depends on the model alone: its settings and the
    // bits of its law (the settings do not show a callable's behaviour, nor a
    // table file's rows, which two runs of one process may see differ).
    static std::mutex mutex;
    static std::string last_key;
    static std::shared_ptr<const Corrector> last;
    std::string key;
    ModelParams copy = p;
    visit_settings(copy, [&](auto&& field, const SettingInfo&) { key += format_setting(field) + '\n'; });
    const DriftLaw& law = *m.law;
    for (double x : {law.slope, law.intercept, law.first, law.spacing}) key.append(reinterpret_cast<const char*>(&x), sizeof x);
    key.append(reinterpret_cast<const char*>(law.values), sizeof(double) * static_cast<std::size_t>(law.knots));
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (last && key == last_key) return last;
    }
    const auto start = std::chrono::steady_clock::now();
    // Below tau' = 0.1 from the near-white discretisation (the chain runs only
    // down to 0.05, poorly); above, from the chain whatever the law, as the
    // measured factors in docs/validation.md were (the solver's own choice
    // also weighs drag and the velocity range, which a corrector need not).
    std::shared_ptr<Corrector> c =
        p.white() ? white_corrector(p)
                  : (to_nondimensional(p).tau < kolmogorov_near_white_below
                         ? detail::near_white::make_corrector(p, *m.law)
                         : coloured_corrector(m));
    c->table.slide = c->slide.data();
    c->table.stuck = c->stuck.empty() ? nullptr : c->stuck.data();
    c->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::lock_guard<std::mutex> lock(mutex);
    last_key = std::move(key);
    last = c;
    return c;
}

} // namespace stickslip
