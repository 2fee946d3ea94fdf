// SPDX-License-Identifier: BSD-3-Clause
// The control variate's corrector from the near-white solver (corrector.hpp
// at the top level says what the corrector is): chi_x from the backward
// solution chi on one coarse grid, resampled on the uniform tables the
// kernels read in O(1).
//
// Why the table looks as it does. chi varies in z on the band's scale eps
// near the band and smoothly elsewhere; the kernels' table is uniform in x,
// so its spacing is the band's spacing (capped at 4097 nodes: a corrector
// only loses variance reduction where it is coarse, never its unbiasedness).
// In v the table is uniform over white noise's e^-25 range, 1025 nodes. Units:
// z = sqrt(tau) X, so chi_x = u0 sqrt(tau) d chi'/dz, u0 the length unit and
// chi' the nondimensional solution.
#pragma once

#include <memory>

#include "stickslip/corrector.hpp"
#include "stickslip/drift_law.hpp"
#include "stickslip/params.hpp"

namespace stickslip::detail::near_white {

/// The corrector of p (SI, valid, tau > 0) with its drift law `law` (SI),
/// from the near-white grid of levels (1, 1); its table's pointers are not
/// set (make_corrector sets them).
std::shared_ptr<Corrector> make_corrector(const ModelParams& p, const DriftLaw& law);

} // namespace stickslip::detail::near_white
