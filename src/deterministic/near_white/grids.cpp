// SPDX-License-Identifier: BSD-3-Clause
// The noise nodes with their moment-exact chain, and the velocity faces
// (grids.hpp says why the chain is built this way).
#include "deterministic/near_white/grids.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "stickslip/random/portable_math.hpp"

namespace stickslip::detail::near_white {

namespace {

/// P(a < Z < b) for a standard normal Z, without cancellation in either tail.
double normal_mass(double a, double b) {
    const double s = 1.0 / std::sqrt(2.0);
    if (a >= 0) return 0.5 * (std::erfc(a * s) - std::erfc(b * s));
    if (b <= 0) return 0.5 * (std::erfc(-b * s) - std::erfc(-a * s));
    return 1.0 - 0.5 * (std::erfc(-a * s) + std::erfc(b * s));
}

/// Splits every interval of `nodes` into 2^level equal ones.
std::vector<double> refined(const std::vector<double>& nodes, int level) {
    const std::size_t split = std::size_t{1} << level;
    std::vector<double> out;
    out.reserve((nodes.size() - 1) * split + 1);
    out.push_back(nodes.front());
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
        const double a = nodes[i], b = nodes[i + 1];
        for (std::size_t k = 1; k < split; ++k) out.push_back(a + (b - a) * static_cast<double>(k) / static_cast<double>(split));
        out.push_back(b);
    }
    return out;
}

/// Tilts the weights w to w exp(mu z - lambda z^2) / sum so that the mean is
/// 0 and the second moment 1 (Newton on (mu, lambda); the Jacobian is the
/// covariance of (z, z^2) under the tilted weights). exp is the project's
/// portable one: glibc's exp is chosen at run time among variants that
/// differ in the last bit, and every number of the solver would follow it.
std::vector<double> moment_exact(const std::vector<double>& z, const std::vector<double>& w0) {
    const std::size_t n = z.size();
    double mu = 0, lambda = 0;
    std::vector<double> w(n);
    auto tilt = [&] {
        double total = 0;
        // Relative to the largest exponent, so that no weight overflows.
        double top = -HUGE_VAL;
        for (std::size_t i = 0; i < n; ++i) top = std::max(top, mu * z[i] - lambda * z[i] * z[i]);
        for (std::size_t i = 0; i < n; ++i) total += w[i] = w0[i] * portable_exp(mu * z[i] - lambda * z[i] * z[i] - top);
        for (double& x : w) x /= total;
    };
    for (int iteration = 0; iteration < 100; ++iteration) {
        tilt();
        double m1 = 0, m2 = 0, m3 = 0, m4 = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double z2 = z[i] * z[i];
            m1 += w[i] * z[i];
            m2 += w[i] * z2;
            m3 += w[i] * z2 * z[i];
            m4 += w[i] * z2 * z2;
        }
        const double r1 = -m1, r2 = 1.0 - m2;
        if (std::abs(r1) < 1e-15 && std::abs(r2) < 1e-15) return w;
        // d(m1, m2)/d(mu, -lambda) = [[var z, cov(z, z^2)], [cov(z, z^2), var z^2]].
        const double a = m2 - m1 * m1, b = m3 - m1 * m2, d = m4 - m2 * m2;
        const double det = a * d - b * b;
        mu += (d * r1 - b * r2) / det;
        lambda -= (a * r2 - b * r1) / det;
    }
    tilt();
    return w;
}

} // namespace

NoiseGrid make_noise_grid(double tau, double z_lower, double z_upper, const NoiseGridShape& shape, int level) {
    if (!(tau > 0) || !(z_upper > z_lower)) throw std::invalid_argument("near_white: invalid noise band");
    const double band = z_upper - z_lower;
    const int inside = std::max(shape.band_intervals, static_cast<int>(std::ceil(band / shape.max_spacing)));
    const double h_band = band / inside;
    // Beyond the band the intervals grow from the band's spacing; the reach is
    // at least a few intervals past either edge (a band beyond the reach: tau'
    // large, almost always stuck).
    std::vector<double> above{z_upper}, below{z_lower};
    for (double h = h_band; above.back() < std::max(shape.reach, z_upper + 2 * h_band);) {
        h = std::min(h * shape.ratio, shape.max_spacing);
        above.push_back(above.back() + h);
    }
    for (double h = h_band; below.back() > std::min(-shape.reach, z_lower - 2 * h_band);) {
        h = std::min(h * shape.ratio, shape.max_spacing);
        below.push_back(below.back() - h);
    }
    std::vector<double> base(below.rbegin(), below.rend());
    for (int k = 1; k < inside; ++k) base.push_back(z_lower + band * k / inside);
    base.push_back(z_upper);
    base.insert(base.end(), above.begin() + 1, above.end());

    NoiseGrid g;
    g.z = refined(base, level);
    const std::size_t split = std::size_t{1} << level;
    g.band_lower = (below.size() - 1) * split;
    g.band_upper = g.band_lower + static_cast<std::size_t>(inside) * split;
    g.z[g.band_lower] = z_lower; // exactly
    g.z[g.band_upper] = z_upper;

    const std::size_t n = g.z.size();
    std::vector<double> mass(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double lo = i == 0 ? -HUGE_VAL : 0.5 * (g.z[i - 1] + g.z[i]);
        const double hi = i + 1 == n ? HUGE_VAL : 0.5 * (g.z[i] + g.z[i + 1]);
        mass[i] = normal_mass(lo, hi);
    }
    g.weight = moment_exact(g.z, mass);

    g.up.assign(n, 0.0);
    g.down.assign(n, 0.0);
    // The partial sums S_j = sum_{i <= j} w_i z_i, from below up to the
    // middle and as -sum_{i > j} w_i z_i above it (sum w z = 0), so that both
    // tails keep their digits (a sum from one end cancels to rounding at the
    // other, and a refined grid then lost a positive rate there).
    std::vector<double> partial(n, 0.0);
    const std::size_t middle = n / 2;
    double sum = 0;
    for (std::size_t j = 0; j < middle; ++j) partial[j] = sum += g.weight[j] * g.z[j];
    sum = 0;
    for (std::size_t j = n - 1; j-- > middle;) partial[j] = -(sum += g.weight[j + 1] * g.z[j + 1]);
    for (std::size_t j = 0; j + 1 < n; ++j) {
        const double conductance = -partial[j] / (tau * (g.z[j + 1] - g.z[j]));
        if (!(conductance > 0)) throw std::runtime_error("near_white: the noise chain lost a positive rate");
        g.up[j] = conductance / g.weight[j];
        g.down[j + 1] = conductance / g.weight[j + 1];
    }
    return g;
}

std::vector<double> make_velocity_faces(double end, const VelocityGridShape& shape, int level) {
    std::vector<double> base{0.0};
    for (double h = shape.first_cell; base.back() < end; h = std::min(h * shape.ratio, shape.max_cell))
        base.push_back(base.back() + h);
    // The last face is the range's end: the last cell takes what is left, or
    // merges with the one before when that is less than half a cell.
    if (base.size() > 2 && end - base[base.size() - 2] < 0.5 * (base[base.size() - 2] - base[base.size() - 3]))
        base.pop_back();
    base.back() = end;
    return refined(base, level);
}

} // namespace stickslip::detail::near_white
