// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The one sparse symmetric positive definite solver of the package: CHOLMOD's supernodal
// Cholesky through Eigen. Factor once, solve many right-hand sides. Failures (matrix not
// SPD, numerical breakdown) become Internal_error with a reason code, never NaNs.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_SPARSE_CHOLESKY_H
#define CGAL_POLYCUBE_IGA_INTERNAL_SPARSE_CHOLESKY_H

#include <CGAL/Polycube_IGA/Errors.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>

#include <memory>
#include <string>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

class Sparse_cholesky
{
public:
  using Matrix = Eigen::SparseMatrix<double>;
  using Vector = Eigen::VectorXd;
  using Dense = Eigen::MatrixXd;

  Sparse_cholesky() : solver_(new Solver) {}

  /// Factors the SPD matrix `A` (only its lower triangle is read).
  /// `what` names the system in the error message.
  void factor(const Matrix& A, const std::string& what = "linear system")
  {
    what_ = what;
    if(A.rows() != A.cols() || A.rows() == 0)
      throw Internal_error("solver_failed", what + ": matrix is empty or not square");
    solver_->compute(A);
    if(solver_->info() != Eigen::Success)
      throw Internal_error("solver_failed", what + ": Cholesky factorization failed "
                                                   "(matrix not positive definite)");
  }

  template <class Rhs>
  Dense solve(const Rhs& b) const
  {
    Dense x = solver_->solve(b);
    if(solver_->info() != Eigen::Success || !x.allFinite())
      throw Internal_error("solver_failed", what_ + ": Cholesky solve failed");
    return x;
  }

private:
  using Solver = Eigen::CholmodSupernodalLLT<Matrix, Eigen::Lower>;
  std::unique_ptr<Solver> solver_;
  std::string what_;
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
