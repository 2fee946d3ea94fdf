// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/model.hpp"

#include <cmath>
#include <cstring>
#include <mutex>

#include "model/params_checks.hpp"

namespace stickslip {

// The formulas of ModelParams (params.cpp), on the law made once, so that a
// run's numbers are bit for bit those of the parameters' own.

double Model::drift_at_zero() const { return params.has_drift_law() ? (*law)(0.0) : params.bias; }

double Model::upper_threshold() const { return noise_threshold(params, drift_at_zero(), +1); }

double Model::lower_threshold() const { return noise_threshold(params, drift_at_zero(), -1); }

double Model::drift_time_scale() const {
    if (!params.has_drift_law()) return params.relaxation;
    const double lip = lipschitz_constant(*law);
    return lip > 0 ? 1.0 / lip : HUGE_VAL;
}

namespace {

/// The affine law depends on the relaxation and the bias alone, so the points
/// of a sweep over noise and tau share one (a prepared point keeps its Model:
/// 16 KiB each, a GiB for 65536 points). The last one made is kept.
std::shared_ptr<const DriftLaw> shared_affine_law(const DriftLaw& made) {
    static std::mutex mutex;
    static std::shared_ptr<const DriftLaw> last;
    const auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    std::lock_guard lock(mutex);
    if (!last || !same_bits(last->slope, made.slope) || !same_bits(last->intercept, made.intercept))
        last = std::make_shared<const DriftLaw>(made);
    return last;
}

} // namespace

Model make_model(const ModelParams& p) {
    detail::validate_numbers(p);
    Model m;
    m.params = p;
    const DriftLaw law = make_drift_law(p, &m.law_report);
    m.law = p.has_drift_law() ? std::make_shared<const DriftLaw>(law) : shared_affine_law(law);
    return m;
}

void require_stationary_state(const Model& m) {
    if (!m.params.has_drift_law()) require_stationary_state(m.params);
}

} // namespace stickslip
