// SPDX-License-Identifier: BSD-3-Clause
// bench/baselines/plain_loop.cpp -- the computation "the way users write it
// today": one thread, std::mt19937_64 + std::normal_distribution, no library.
//
// Fig. 2 case of the paper (friction 3.84, noise 5, tau 0.5, relaxation 0.067,
// bias 0.342, SI units), inclusion scheme of docs/theory.md section 5: exact OU pair
// step, soft threshold, left-point displacement; long excursions of section 6
// with rule Q (Brownian-bridge stop test while stuck), the detecting step not
// applied, each half excursion restarted exactly at its threshold state.
// Prints {"D","stderr","steps","seconds", ...} as JSON on stdout.
//
// Usage: plain_loop [--excursions N] [--dt H] [--seed S]
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

int main(int argc, char** argv) {
    std::uint64_t n_exc = 2000;
    double h = 1e-3;
    std::uint64_t seed = 1;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--excursions")) n_exc = std::strtoull(argv[i + 1], nullptr, 10);
        else if (!std::strcmp(argv[i], "--dt")) h = std::strtod(argv[i + 1], nullptr);
        else if (!std::strcmp(argv[i], "--seed")) seed = std::strtoull(argv[i + 1], nullptr, 10);
        else { std::fprintf(stderr, "unknown argument %s\n", argv[i]); return 2; }
    }
    if (n_exc < 2 || !(h > 0)) { std::fprintf(stderr, "need --excursions >= 2 and --dt > 0\n"); return 2; }

    // Model (Fig. 2) and derived constants.
    const double friction = 3.84, noise = 5.0, tau = 0.5, relax = 0.067, bias = 0.342;
    const double a = std::sqrt(noise / 2);
    const double x_up = (friction - bias) / a, x_down = (-friction - bias) / a;
    const double r = h / tau, e1 = std::exp(-r), e2 = std::exp(-2 * r);
    const double m1 = tau / h * (1 - e1), m2 = e1;
    const double s11 = tau / (h * h) * (2 * r - 3 + 4 * e1 - e2);
    const double s12 = (1 - e1) * (1 - e1) / h;
    const double s22 = (1 - e2) / tau;
    const double l11 = std::sqrt(s11), l21 = s12 / l11, l22 = std::sqrt(s22 - l21 * l21);
    const double band = h * friction, bridge_rate = tau * tau / h;

    std::mt19937_64 gen(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::uniform_real_distribution<double> unif(0.0, 1.0);

    std::vector<double> U(n_exc), T(n_exc);
    std::uint64_t total_steps = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::uint64_t k = 0; k < n_exc; ++k) {
        double vsum = 0.0;
        std::uint64_t steps = 0;
        for (int dir = 1; dir >= -1; dir -= 2) { // +HLE then -HLE
            double x = dir > 0 ? x_up : x_down, v = 0.0;
            const double target = dir > 0 ? x_down : x_up;
            for (;;) {
                const double z1 = normal(gen), z2 = normal(gen);
                const double xbar = m1 * x + l11 * z1;
                const double x_next = m2 * x + l21 * z1 + l22 * z2;
                const double f = v + h * (-v / relax + bias + a * xbar);
                if (v == 0.0 && x >= x_down && x <= x_up) { // stuck at the start of the step: rule Q
                    bool crossed = dir > 0 ? x_next <= target : x_next >= target;
                    if (!crossed) {
                        const double e = (x - target) * (x_next - target) * bridge_rate;
                        crossed = e < 50.0 && unif(gen) < std::exp(-e);
                    }
                    if (crossed) break; // the detecting step is not applied
                }
                const double v_next = f - std::fmin(std::fmax(f, -band), band);
                vsum += v; // left-point rule
                ++steps;
                x = x_next;
                v = v_next;
            }
        }
        U[k] = h * vsum;
        T[k] = h * static_cast<double>(steps);
        total_steps += steps;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // Renewal-reward estimator and delta-method standard error (docs/theory.md, section 7).
    const double n = static_cast<double>(n_exc);
    double su = 0, st = 0;
    for (std::uint64_t k = 0; k < n_exc; ++k) { su += U[k]; st += T[k]; }
    const double m0 = su / st, et = st / n;
    double sr2 = 0, srt = 0;
    for (std::uint64_t k = 0; k < n_exc; ++k) {
        const double rk = U[k] - m0 * T[k];
        sr2 += rk * rk;
        srt += rk * T[k];
    }
    const double D = sr2 / st, c = (srt / n) / et;
    double sp = 0, sp2 = 0;
    for (std::uint64_t k = 0; k < n_exc; ++k) {
        const double rk = U[k] - m0 * T[k];
        const double phi = (rk * rk - D * T[k] - 2 * c * rk) / et;
        sp += phi;
        sp2 += phi * phi;
    }
    const double var_phi = (sp2 - sp * sp / n) / (n - 1);
    const double se = std::sqrt(var_phi / n);
    std::printf("{\"D\": %.10g, \"stderr\": %.10g, \"M0\": %.10g, \"steps\": %llu, \"seconds\": %.6g, "
                "\"excursions\": %llu, \"dt\": %g, \"seed\": %llu}\n",
                D, se, m0, static_cast<unsigned long long>(total_steps), seconds,
                static_cast<unsigned long long>(n_exc), h, static_cast<unsigned long long>(seed));
    return 0;
}
