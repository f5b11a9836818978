// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Evaluation of the univariate B-spline basis of a clamped knot vector (reference §2.1.2.2,
// eq. 2.7): the p+1 functions that are non-zero on a knot span, and their derivatives, by
// the triangular Cox-de Boor scheme of Piegl and Tiller (The NURBS Book, A2.2 and A2.3).
// No allocation: the scratch lives on the stack, bounded by Knot_vector::maximum_degree.

#ifndef CGAL_POLYCUBE_IGA_BSPLINE_BASIS_H
#define CGAL_POLYCUBE_IGA_BSPLINE_BASIS_H

#include <CGAL/Polycube_IGA/Knot_vector.h>

#include <algorithm>

namespace CGAL {
namespace Polycube_IGA {

/// Values `N[0..p]` of the basis functions `N_{span-p}, ..., N_{span}` at `t`
/// (A2.2; `span` from Knot_vector::find_span). They are >= 0 and sum to one.
inline void basis_functions(const Knot_vector& kv, int span, double t, double* N)
{
  constexpr int P = Knot_vector::maximum_degree + 1;
  const int p = kv.degree();
  double left[P], right[P];
  N[0] = 1.;
  for(int j = 1; j <= p; ++j) {
    left[j] = t - kv[std::size_t(span + 1 - j)];
    right[j] = kv[std::size_t(span + j)] - t;
    double saved = 0.;
    for(int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

/// Derivatives of order 0..n of the p+1 non-zero basis functions at `t` (A2.3):
/// `ders[k*(p+1) + j]` is the k-th derivative of `N_{span-p+j}`. Orders above p are zero.
inline void basis_function_derivatives(const Knot_vector& kv, int span, double t, int n, double* ders)
{
  constexpr int P = Knot_vector::maximum_degree + 1;
  const int p = kv.degree();
  double ndu[P][P], left[P], right[P], a[2][P];
  ndu[0][0] = 1.;
  for(int j = 1; j <= p; ++j) {
    left[j] = t - kv[std::size_t(span + 1 - j)];
    right[j] = kv[std::size_t(span + j)] - t;
    double saved = 0.;
    for(int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];   // lower triangle: knot differences
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;  // upper triangle: basis values
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for(int j = 0; j <= p; ++j) ders[j] = ndu[j][p];
  for(int k = 1; k <= n; ++k)
    for(int j = 0; j <= p; ++j) ders[k * (p + 1) + j] = 0.;
  const int nmax = std::min(n, p);
  for(int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.;
    for(int k = 1; k <= nmax; ++k) {
      double d = 0.;
      const int rk = r - k, pk = p - k;
      if(r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = (rk >= -1) ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for(int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if(r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k * (p + 1) + r] = d;
      std::swap(s1, s2);
    }
  }
  int factor = p;
  for(int k = 1; k <= nmax; ++k) {
    for(int j = 0; j <= p; ++j) ders[k * (p + 1) + j] *= double(factor);
    factor *= (p - k);
  }
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_BSPLINE_BASIS_H
