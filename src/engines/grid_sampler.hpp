// SPDX-License-Identifier: BSD-3-Clause
// Internal: the one sampler of a continuous-time path on a time grid.
//
// The density, the correlation and a recorded trajectory see an engine's path
// at the grid times phase + n dt (n = 0, 1, ...). The engines whose path is
// known between its events (the PDMP: the closed-form flow; the event scheme:
// its pieces' own cubics) hand every piece to this sampler, which asks the
// engine for the end of the piece and for the state at each grid time inside
// it (EngineAdapter::piece_end, sample_piece). With a phase uniform in [0, dt),
// independent of the path, the Riemann sum dt * sum g(phase + n dt) over a
// duration T is an unbiased estimate of int_0^T g, and E[#samples] = T/dt
// exactly, so the renewal-reward ratios carry no O(dt) bias (with phase 0
// every excursion would be sampled at its start, where V = 0). `offset` [s] is
// the absolute time of the path's own time 0, for continuing a path after a
// regeneration.
#pragma once

#include <cstdint>
#include <utility>

#include "engines/path_point.hpp"

namespace stickslip::detail {

/// f(x [s^-1/2], mode, v [m/s], u [m]) at every grid time of every piece the
/// engine `Engine` hands it, until sample index `stop_at`.
template <class Engine, class F>
struct GridSampler {
    const Engine& engine;
    double dt;                                 ///< grid spacing [s]
    F f;                                       ///< called at every grid time
    double phase = 0.0;                        ///< time of sample 0 [s], in [0, dt)
    std::uint64_t next = 0;                    ///< index of the next sample
    double offset = 0.0;                       ///< absolute time of the path's time 0 [s]
    std::uint64_t stop_at = ~std::uint64_t{0}; ///< no samples at or beyond this index

    template <class Piece>
    void operator()(const Piece& p) {
        const double end = engine.piece_end(p, offset);
        while (next < stop_at) {
            const double g = phase + static_cast<double>(next) * dt;
            if (!(g < end)) break;
            engine.sample_piece(p, g, offset, f);
            ++next;
        }
    }
};

template <class Engine, class F>
GridSampler<Engine, F> grid_sampler(const Engine& engine, double dt, F f, double phase = 0.0) {
    return GridSampler<Engine, F>{engine, dt, std::move(f), phase};
}

/// A sampler on the grid n * every [s] (phase 0) that hands f the PathPoint
/// at each grid time: what a recorded trajectory takes.
template <class Engine, class F>
auto point_sampler(const Engine& engine, double every, F& f) {
    return grid_sampler(engine, every, [&f, every, n = std::uint64_t{0}](double x, int y, double v, double u) mutable {
        f(PathPoint{static_cast<double>(n++) * every, x, y, v, u});
    });
}

} // namespace stickslip::detail
