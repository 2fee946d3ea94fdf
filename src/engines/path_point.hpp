// SPDX-License-Identifier: BSD-3-Clause
// Internal: one point of a recorded path, as every engine reports it.
#pragma once

namespace stickslip::detail {

/// The state of a path at time t: what `trajectory` records.
struct PathPoint {
    double t;  ///< time from the path's start [s]
    double x;  ///< noise X [s^-1/2] (0 for white noise)
    int mode;  ///< +1 sliding forward, -1 backward, 0 stuck
    double v;  ///< velocity V [m/s]
    double u;  ///< displacement since the start [m]
};

} // namespace stickslip::detail
