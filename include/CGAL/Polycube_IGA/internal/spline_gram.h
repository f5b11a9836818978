// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Sparse building blocks of spline least squares: Gauss-Legendre rules, collocation
// matrices B(i,j) = N_j(t_i), Gram matrices of basis derivatives G_r(i,j) = int N_i^(r) N_j^(r)
// (exact: p+1 Gauss points per knot span integrate degree 2p), sparse Kronecker products
// for tensor-product systems, and an SPD solve with some unknowns fixed (Dirichlet rows),
// which fitting with fixed boundaries and harmonic volume smoothing both need.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_SPLINE_GRAM_H
#define CGAL_POLYCUBE_IGA_INTERNAL_SPLINE_GRAM_H

#include <CGAL/Polycube_IGA/Bspline_basis.h>
#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

using Sparse_matrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

/// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1] (Newton on P_n).
inline std::pair<std::vector<double>, std::vector<double>> gauss_legendre(int n)
{
  std::vector<double> x(static_cast<std::size_t>(n)), w(static_cast<std::size_t>(n));
  const double pi = 3.14159265358979323846;
  for(int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 1.;
    for(int it = 0; it < 100; ++it) {
      double p0 = 1., p1 = 0.;
      for(int j = 1; j <= n; ++j) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2. * j - 1.) * z * p1 - (j - 1.) * p2) / j;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.);
      const double z1 = z;
      z = z1 - p0 / dp;
      if(std::abs(z - z1) < 1e-16) break;
    }
    x[std::size_t(i)] = -z;
    x[std::size_t(n - 1 - i)] = z;
    w[std::size_t(i)] = w[std::size_t(n - 1 - i)] = 2. / ((1. - z * z) * dp * dp);
  }
  return {x, w};
}

/// Collocation matrix B(i, j) = N_j(params[i]).
inline Sparse_matrix collocation_matrix(const Knot_vector& kv, const std::vector<double>& params)
{
  const int p = kv.degree();
  Triplets t;
  t.reserve(params.size() * std::size_t(p + 1));
  double N[Knot_vector::maximum_degree + 1];
  for(std::size_t i = 0; i < params.size(); ++i) {
    const int span = kv.find_span(params[i]);
    basis_functions(kv, span, params[i], N);
    for(int j = 0; j <= p; ++j) t.emplace_back(int(i), span - p + j, N[j]);
  }
  Sparse_matrix B(int(params.size()), kv.number_of_basis_functions());
  B.setFromTriplets(t.begin(), t.end());
  return B;
}

/// Gram matrix of the order-r derivatives of the basis over the whole domain.
inline Sparse_matrix gram_matrix(const Knot_vector& kv, int r)
{
  const int p = kv.degree();
  const auto [gx, gw] = gauss_legendre(p + 1);
  const std::vector<double> br = kv.breaks();
  Triplets t;
  double ders[(Knot_vector::maximum_degree + 1) * (Knot_vector::maximum_degree + 1)];
  for(std::size_t s = 0; s + 1 < br.size(); ++s) {
    const double a = br[s], b = br[s + 1], h = 0.5 * (b - a);
    for(std::size_t q = 0; q < gx.size(); ++q) {
      const double x = a + h * (gx[q] + 1.);
      const int span = kv.find_span(x);
      basis_function_derivatives(kv, span, x, r, ders);
      const double* D = ders + r * (p + 1);
      for(int i = 0; i <= p; ++i)
        for(int j = 0; j <= p; ++j) t.emplace_back(span - p + i, span - p + j, gw[q] * h * D[i] * D[j]);
    }
  }
  const int n = kv.number_of_basis_functions();
  Sparse_matrix G(n, n);
  G.setFromTriplets(t.begin(), t.end());
  return G;
}

/// Kronecker product: K(i*rows(B) + k, j*cols(B) + l) = A(i,j) B(k,l). With control points
/// indexed u fastest, the tensor operator Au (x) Av is kronecker(Av, Au).
inline Sparse_matrix kronecker(const Sparse_matrix& A, const Sparse_matrix& B)
{
  Triplets t;
  t.reserve(std::size_t(A.nonZeros()) * std::size_t(B.nonZeros()));
  for(int ja = 0; ja < A.outerSize(); ++ja)
    for(Sparse_matrix::InnerIterator ia(A, ja); ia; ++ia)
      for(int jb = 0; jb < B.outerSize(); ++jb)
        for(Sparse_matrix::InnerIterator ib(B, jb); ib; ++ib)
          t.emplace_back(int(ia.row() * B.rows() + ib.row()), int(ia.col() * B.cols() + ib.col()),
                         ia.value() * ib.value());
  Sparse_matrix K(A.rows() * B.rows(), A.cols() * B.cols());
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

/// Solves A x = b for the unknowns with fixed[i] == false, the others keeping their value
/// in `x` (moved to the right-hand side). A is symmetric; its free block must be SPD.
inline void solve_with_fixed_unknowns(const Sparse_matrix& A, const Eigen::MatrixXd& b,
                                      const std::vector<bool>& fixed, Eigen::MatrixXd& x,
                                      const std::string& what)
{
  const int n = int(A.rows());
  std::vector<int> free_index(std::size_t(n), -1);
  int nf = 0;
  for(int i = 0; i < n; ++i)
    if(!fixed[std::size_t(i)]) free_index[std::size_t(i)] = nf++;
  if(nf == 0) return;
  Eigen::MatrixXd rhs(nf, b.cols());
  for(int i = 0; i < n; ++i)
    if(!fixed[std::size_t(i)]) rhs.row(free_index[std::size_t(i)]) = b.row(i);
  Triplets t;
  t.reserve(std::size_t(A.nonZeros()));
  for(int j = 0; j < A.outerSize(); ++j)
    for(Sparse_matrix::InnerIterator it(A, j); it; ++it) {
      const int r = int(it.row()), c = int(it.col());
      const int fr = free_index[std::size_t(r)], fc = free_index[std::size_t(c)];
      if(fr < 0) continue;
      if(fc >= 0) t.emplace_back(fr, fc, it.value());
      else rhs.row(fr) -= it.value() * x.row(c);
    }
  Sparse_matrix Aff(nf, nf);
  Aff.setFromTriplets(t.begin(), t.end());
  Sparse_cholesky solver;
  solver.factor(Aff, what);
  const Eigen::MatrixXd sol = solver.solve(rhs);
  for(int i = 0; i < n; ++i)
    if(!fixed[std::size_t(i)]) x.row(i) = sol.row(free_index[std::size_t(i)]);
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_SPLINE_GRAM_H
