// SPDX-License-Identifier: BSD-3-Clause
// The complex resolvent solve that both discretisations of the Kolmogorov
// engine use for the velocity spectrum. Internal to the library (it speaks
// Eigen).
//
// Why a resolvent. For a stationary Markov process with generator L and
// f = V - M0, the autocovariance is C(t) = E_pi[f e^{|t| L} f], so the
// two-sided spectrum in the project's convention,
//   S(w) = int over all t of C(t) e^{-i w t} dt,
// is 2 Re <f, (i w - L)^{-1} f>_pi: one complex linear solve per frequency,
// with no time integration and no truncation of C(t). At w = 0 the solve is
// the cell (Poisson) problem of D, so S(0) = D (Green-Kubo; the project's
// D = lim Var U(t)/t). For w > 0, i w - L is invertible on a conservative
// chain (every eigenvalue of L has a real part <= 0, and 0 is simple), so no
// state is pinned as in D's solve.
//
// A discretisation in weak form (the near-white DG) reads M dp/dt = A p with
// a diagonal mass matrix M; its forward resolvent is (i w M - A) r = s, s the
// weak form of f p. A chain is the case M = I, A = Q^T, and its backward
// form (i w - Q) phi = f is the same problem transposed; this file solves
// (i w diag(weight) - op) x = rhs for either.
#pragma once

#include <Eigen/SparseCore>
#include <complex>
#include <vector>

namespace stickslip::detail {

/// Solves (i w diag(weight) - op) x = rhs for the frequencies of one grid:
/// the matrix's pattern and its COLAMD ordering are made once, a sparse LU of
/// the complex matrix per frequency.
class ResolventSolver {
public:
    /// `op` square, `weight` of its size (both kept by reference: they must
    /// outlive the solver).
    ResolventSolver(const Eigen::SparseMatrix<double>& op, const std::vector<double>& weight);
    ~ResolventSolver();
    ResolventSolver(const ResolventSolver&) = delete;
    ResolventSolver& operator=(const ResolventSolver&) = delete;
    /// x for the angular frequency w > 0 [rad/s, or the caller's
    /// nondimensional unit] and rhs of op's size. std::runtime_error when the
    /// factorisation fails.
    std::vector<std::complex<double>> solve(double w, const std::vector<double>& rhs);

private:
    struct Factors;
    const Eigen::SparseMatrix<double>& op_;
    const std::vector<double>& weight_;
    Factors* factors_;
};

} // namespace stickslip::detail
