// SPDX-License-Identifier: BSD-3-Clause
// The complex resolvent solve of the velocity spectrum (spectral_resolvent.hpp).
#include "deterministic/spectral_resolvent.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <stdexcept>
#include <string>

namespace stickslip::detail {

namespace {
using Complex = std::complex<double>;
using ComplexMatrix = Eigen::SparseMatrix<Complex>;
} // namespace

struct ResolventSolver::Factors {
    ComplexMatrix matrix;               ///< i w diag(weight) - op at the last frequency
    std::vector<Eigen::Index> diagonal; ///< where each diagonal entry sits in matrix's values
    Eigen::SparseLU<ComplexMatrix, Eigen::COLAMDOrdering<int>> lu;
};

ResolventSolver::ResolventSolver(const Eigen::SparseMatrix<double>& op, const std::vector<double>& weight)
    : op_(op), weight_(weight), factors_(new Factors) {
    const auto n = op.rows();
    std::vector<Eigen::Triplet<Complex>> entries;
    entries.reserve(static_cast<std::size_t>(op.nonZeros() + n));
    for (Eigen::Index col = 0; col < op.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(op, col); it; ++it)
            entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), Complex(-it.value(), 0.0));
    // Every diagonal entry present (0 + i w weight is added per frequency).
    for (Eigen::Index i = 0; i < n; ++i) entries.emplace_back(static_cast<int>(i), static_cast<int>(i), Complex(0.0, 0.0));
    ComplexMatrix& a = factors_->matrix;
    a.resize(n, n);
    a.setFromTriplets(entries.begin(), entries.end()); // duplicates are summed
    a.makeCompressed();
    factors_->diagonal.assign(static_cast<std::size_t>(n), -1);
    for (Eigen::Index col = 0; col < n; ++col)
        for (Eigen::Index k = a.outerIndexPtr()[col]; k < a.outerIndexPtr()[col + 1]; ++k)
            if (a.innerIndexPtr()[k] == col) factors_->diagonal[static_cast<std::size_t>(col)] = k;
    factors_->lu.analyzePattern(a);
}

ResolventSolver::~ResolventSolver() { delete factors_; }

std::vector<std::complex<double>> ResolventSolver::solve(double w, const std::vector<double>& rhs) {
    ComplexMatrix& a = factors_->matrix;
    const auto n = a.rows();
    // Reset the diagonal to -op's, then add i w weight.
    for (Eigen::Index i = 0; i < n; ++i) a.valuePtr()[factors_->diagonal[static_cast<std::size_t>(i)]] = Complex(-op_.coeff(i, i), 0.0);
    for (Eigen::Index i = 0; i < n; ++i)
        a.valuePtr()[factors_->diagonal[static_cast<std::size_t>(i)]] += Complex(0.0, w * weight_[static_cast<std::size_t>(i)]);
    factors_->lu.factorize(a);
    if (factors_->lu.info() != Eigen::Success)
        throw std::runtime_error("Kolmogorov engine: the spectrum's complex sparse LU failed: " +
                                 factors_->lu.lastErrorMessage());
    Eigen::VectorXcd b(n);
    for (Eigen::Index i = 0; i < n; ++i) b[i] = Complex(rhs[static_cast<std::size_t>(i)], 0.0);
    const Eigen::VectorXcd x = factors_->lu.solve(b);
    return {x.data(), x.data() + n};
}

} // namespace stickslip::detail
