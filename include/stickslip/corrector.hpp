// SPDX-License-Identifier: BSD-3-Clause
// stickslip/corrector.hpp -- the corrector g ~ chi_x of the control variate,
// made once per run (theory.md, section 12).
//
// Why here, in the deterministic layer: g is the derivative of the solution
// chi of the Poisson equation L chi = -(v - M0), which the Kolmogorov solver
// computes on a grid (kolmogorov.hpp) and which white noise has in closed
// form (chi' = -(2/noise) F/p, F(v) = int_-inf^v (u - M0) p(u) du, p the
// stationary velocity density). The control variate stays unbiased for any
// g, so a coarse grid (a fraction of a second) is enough: the finer g, the
// more variance it removes (measured in docs/validation.md).
#pragma once

/// \file
/// make_corrector: the table of g(x, v) for a run's model, from a coarse
/// Kolmogorov solve (coloured noise) or the closed form (white noise). The
/// comment at the top of this header explains the design.

#include <memory>
#include <string>
#include <vector>

#include "stickslip/kernels/corrector.hpp"
#include "stickslip/model.hpp"
#include "stickslip/params.hpp"

namespace stickslip {

/// The corrector of a run: its table and where it came from.
struct Corrector {
    /// "kolmogorov" (coloured noise: chi_x from a coarse grid solve) or
    /// "closed-form" (white noise: chi' of the one-dimensional diffusion).
    std::string source;
    /// The grid it came from, e.g. "x 61 nodes, v 2 x 64 cells", for reports.
    std::string grid;
    /// D of the coarse solve [m^2/s] (coloured noise; a hint of how close g is
    /// to chi_x: the control variate does not use it), or the closed form's.
    double diffusivity = 0.0;
    /// Wall time of making it [s].
    double seconds = 0.0;
    std::vector<double> slide; ///< the sliding table's values (CorrectorTable::slide)
    std::vector<double> stuck; ///< the stuck line's values (CorrectorTable::stuck; empty for white noise)
    /// The view the kernels read (its pointers into slide and stuck: valid
    /// while this Corrector lives and is not copied; make_corrector returns a
    /// shared pointer for that reason).
    CorrectorTable table;
};

/// Resolution of the corrector's grid: the Kolmogorov solver's refinement
/// level (kolmogorov_grid) for coloured noise. Level 1: 32 velocity cells per
/// half line and half the solver's automatic x nodes; 0.05 to 0.5 s. Level 2
/// took 8 times longer (3.6 s at tau' = 0.1) and removed no more variance
/// (measured, 6000 excursions: 29.9x against 34.6x at level 1 for pure dry
/// friction at tau' = 1, 42.6x against 38.2x at tau' = 0.1, 21.6x against
/// 21.4x on the Fig. 2 case): what is left is not the grid's error.
inline constexpr int corrector_grid_level = 1;

/// Whether make_corrector has a corrector for p (SI units): white noise, or
/// coloured noise where the Kolmogorov solver's grids run (tau' >=
/// kolmogorov_white_limit_below; below kolmogorov_near_white_below from the
/// near-white discretisation, near_white/corrector_table.hpp).
/// When not, *why (if given) says why, in words for a note.
bool has_corrector(const ModelParams& p, std::string* why = nullptr);

/// The corrector of p (valid, SI units; has_corrector(p) must hold, else
/// InvalidParameter("control-variate")). Deterministic: the same p gives the
/// same table, bit for bit, on every machine with the same build.
std::shared_ptr<const Corrector> make_corrector(const ModelParams& p);
/// make_corrector on a model made once (model.hpp): the solve takes its law.
std::shared_ptr<const Corrector> make_corrector(const Model& m);

} // namespace stickslip
