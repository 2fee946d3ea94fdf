// SPDX-License-Identifier: BSD-3-Clause
// Shared helpers for the statistical tests: every check compares a seeded
// Monte Carlo estimate with a reference using a tolerance of a few standard
// errors computed by the run itself, plus (where stated) a discretisation
// allowance measured in docs/validation.md. Failure messages state the z-score.
#pragma once

#include <cmath>
#include <cstdint>
#include <iostream>
#include <sstream>
#include <string>

#include "stickslip/bruteforce.hpp"
#include "stickslip/diffusivity.hpp"

namespace sstest {

namespace ss = stickslip;

inline ss::DiffusivityResult run_le(const ss::ModelParams& p, const ss::EngineSettings& e, std::uint64_t n,
                                    std::uint64_t seed = 12345, unsigned threads = 0,
                                    ss::Estimator est = ss::Estimator::RenewalReward) {
    ss::DiffusivityRequest r;
    r.params = p;
    r.engine = e;
    r.excursions = n;
    r.estimator = est;
    r.control.seed = seed;
    r.control.threads = threads;
    return ss::compute_diffusivity(r);
}

inline ss::BruteForceResult run_bf(const ss::ModelParams& p, const ss::EngineSettings& e, double horizon,
                                   std::uint64_t n, std::uint64_t seed = 777, unsigned threads = 0) {
    ss::BruteForceRequest r;
    r.params = p;
    r.engine = e;
    r.horizon = horizon;
    r.trajectories = n;
    r.control.seed = seed;
    r.control.threads = threads;
    return ss::compute_bruteforce(r);
}

/// Describes a comparison |a - b| <= k * se + allowance, with its z-score.
struct Comparison {
    double a, b, se, allowance, k;
    double z() const { return (a - b) / se; }
    bool ok() const { return std::fabs(a - b) <= k * se + allowance; }
    std::string message(const std::string& what) const {
        std::ostringstream os;
        os.precision(6);
        os << what << ": " << a << " vs " << b << ", difference " << (a - b) << ", combined stderr " << se
           << ", z = " << z() << " (allowed |diff| <= " << k << " se + " << allowance << ")";
        return os.str();
    }
};

/// Prints the comparison (so the test log documents every number) and
/// returns whether it passes.
inline bool check(const Comparison& c, const std::string& what) {
    std::cout << "[measured] " << c.message(what) << (c.ok() ? "" : "  <-- FAILS") << std::endl;
    return c.ok();
}

inline Comparison compare(double a, double se_a, double b, double se_b, double allowance = 0.0,
                          double k = 4.0) {
    return {a, b, std::sqrt(se_a * se_a + se_b * se_b), allowance, k};
}

} // namespace sstest
