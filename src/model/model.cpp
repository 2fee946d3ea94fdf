// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/model.hpp"

#include <cmath>

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

Model make_model(const ModelParams& p) {
    detail::validate_numbers(p);
    Model m;
    m.params = p;
    m.law = std::make_shared<const DriftLaw>(make_drift_law(p, &m.law_report));
    return m;
}

void require_stationary_state(const Model& m) {
    if (!m.params.has_drift_law()) require_stationary_state(m.params);
}

} // namespace stickslip
