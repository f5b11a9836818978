// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Trivariate polynomials in tensor Bernstein form on the unit box: products (degrees add),
// differences, derivatives of a Bezier net and de Casteljau subdivision. A polynomial in
// Bernstein form lies between its smallest and largest coefficient, and its corner
// coefficients are its values at the corners: the certified Jacobian bound rests on both.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_BERNSTEIN_H
#define CGAL_POLYCUBE_IGA_INTERNAL_BERNSTEIN_H

#include <algorithm>
#include <array>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

struct Bernstein3
{
  std::array<int, 3> degree{{0, 0, 0}};
  std::vector<double> c; // (i, j, k) at i + (p+1) * (j + (q+1) * k)

  Bernstein3() = default;
  explicit Bernstein3(const std::array<int, 3>& deg)
    : degree(deg), c(std::size_t(deg[0] + 1) * std::size_t(deg[1] + 1) * std::size_t(deg[2] + 1), 0.) {}
  std::size_t index(int i, int j, int k) const
  {
    return std::size_t(i) + std::size_t(degree[0] + 1) * (std::size_t(j) + std::size_t(degree[1] + 1) * std::size_t(k));
  }
  double& operator()(int i, int j, int k) { return c[index(i, j, k)]; }
  double operator()(int i, int j, int k) const { return c[index(i, j, k)]; }
  double min_coefficient() const { return *std::min_element(c.begin(), c.end()); }
  double max_coefficient() const { return *std::max_element(c.begin(), c.end()); }
  /// Where the smallest coefficient sits, in the box's [0, 1]^3 (its Greville point i / p):
  /// det J is small near there, so it is where a search for negative values looks first.
  std::array<double, 3> min_coefficient_point() const
  {
    const std::size_t m = std::size_t(std::min_element(c.begin(), c.end()) - c.begin());
    const std::size_t n0 = std::size_t(degree[0] + 1), n1 = std::size_t(degree[1] + 1);
    const std::array<std::size_t, 3> at{{m % n0, (m / n0) % n1, m / (n0 * n1)}};
    std::array<double, 3> t{};
    for(int d = 0; d < 3; ++d) t[std::size_t(d)] = degree[std::size_t(d)] > 0 ? double(at[std::size_t(d)]) / degree[std::size_t(d)] : 0.5;
    return t;
  }
  /// Smallest of the 8 corner values (exact values of the polynomial).
  double min_corner_value() const
  {
    double m = c[0];
    for(int k : {0, degree[2]})
      for(int j : {0, degree[1]})
        for(int i : {0, degree[0]}) m = std::min(m, (*this)(i, j, k));
    return m;
  }
};

inline double binomial(int n, int k)
{
  double r = 1.;
  for(int i = 1; i <= k; ++i) r = r * double(n - k + i) / double(i);
  return r;
}

/// binomial(n, k) for k = 0..n, the same values, tabulated once for n < 64: the products of
/// the certified Jacobian bound asked for them per coefficient, two thirds of its time.
inline const double* binomial_row(int n, std::vector<double>& spare)
{
  struct Table
  {
    std::vector<std::vector<double>> rows;
    Table() : rows(64)
    {
      for(int m = 0; m < 64; ++m)
        for(int k = 0; k <= m; ++k) rows[std::size_t(m)].push_back(binomial(m, k));
    }
  };
  static const Table table; // thread-safe initialisation
  if(n < 64) return table.rows[std::size_t(n)].data();
  spare.clear();
  for(int k = 0; k <= n; ++k) spare.push_back(binomial(n, k));
  return spare.data();
}

/// Product of two Bernstein polynomials (degrees add).
inline Bernstein3 multiply(const Bernstein3& a, const Bernstein3& b)
{
  std::array<int, 3> d;
  for(int e = 0; e < 3; ++e) d[std::size_t(e)] = a.degree[std::size_t(e)] + b.degree[std::size_t(e)];
  Bernstein3 r(d);
  std::array<std::vector<double>, 3> spare;
  auto rows = [&spare](const std::array<int, 3>& deg) {
    return std::array<const double*, 3>{{binomial_row(deg[0], spare[0]), binomial_row(deg[1], spare[1]),
                                         binomial_row(deg[2], spare[2])}};
  };
  // Scale to the unnormalized (scaled) basis C(n,i) t^i (1-t)^(n-i): products are then plain
  // convolutions; scale back at the end.
  auto scaled = [&rows](const Bernstein3& x) {
    Bernstein3 s = x;
    const std::array<const double*, 3> C = rows(x.degree);
    for(int k = 0; k <= x.degree[2]; ++k)
      for(int j = 0; j <= x.degree[1]; ++j)
        for(int i = 0; i <= x.degree[0]; ++i) s(i, j, k) *= C[0][i] * C[1][j] * C[2][k];
    return s;
  };
  const Bernstein3 sa = scaled(a), sb = scaled(b);
  for(int k1 = 0; k1 <= a.degree[2]; ++k1)
    for(int j1 = 0; j1 <= a.degree[1]; ++j1)
      for(int i1 = 0; i1 <= a.degree[0]; ++i1) {
        const double x = sa(i1, j1, k1);
        if(x == 0.) continue;
        // Rows of b's coefficients added into rows of r, in the same order as index by index.
        const double* from = sb.c.data();
        for(int k2 = 0; k2 <= b.degree[2]; ++k2)
          for(int j2 = 0; j2 <= b.degree[1]; ++j2) {
            double* to = &r(i1, j1 + j2, k1 + k2);
            for(int i2 = 0; i2 <= b.degree[0]; ++i2) to[i2] += x * *from++;
          }
      }
  const std::array<const double*, 3> C = rows(d);
  for(int k = 0; k <= d[2]; ++k)
    for(int j = 0; j <= d[1]; ++j)
      for(int i = 0; i <= d[0]; ++i) r(i, j, k) /= C[0][i] * C[1][j] * C[2][k];
  return r;
}

/// a + s * b (same degrees).
inline Bernstein3 add(const Bernstein3& a, const Bernstein3& b, double s = 1.)
{
  Bernstein3 r = a;
  for(std::size_t i = 0; i < r.c.size(); ++i) r.c[i] += s * b.c[i];
  return r;
}

/// Derivative along direction d of a polynomial on [0, h_d] in that direction.
inline Bernstein3 derivative(const Bernstein3& a, int d, double h)
{
  std::array<int, 3> deg = a.degree;
  const int p = deg[std::size_t(d)];
  if(p == 0) {
    Bernstein3 z(deg);
    return z;
  }
  deg[std::size_t(d)] = p - 1;
  Bernstein3 r(deg);
  for(int k = 0; k <= deg[2]; ++k)
    for(int j = 0; j <= deg[1]; ++j)
      for(int i = 0; i <= deg[0]; ++i) {
        std::array<int, 3> n{{i, j, k}};
        const double lo = a(n[0], n[1], n[2]);
        ++n[std::size_t(d)];
        r(i, j, k) = double(p) / h * (a(n[0], n[1], n[2]) - lo);
      }
  return r;
}

/// de Casteljau split at the midpoint of direction d.
inline std::pair<Bernstein3, Bernstein3> split_half(const Bernstein3& a, int d)
{
  Bernstein3 left = a, right = a;
  const int p = a.degree[std::size_t(d)];
  std::array<int, 3> ext{{a.degree[0] + 1, a.degree[1] + 1, a.degree[2] + 1}};
  ext[std::size_t(d)] = 1;
  std::vector<double> b(std::size_t(p + 1));
  for(int k = 0; k < ext[2]; ++k)
    for(int j = 0; j < ext[1]; ++j)
      for(int i = 0; i < ext[0]; ++i) {
        auto at = [&](int m) {
          std::array<int, 3> n{{i, j, k}};
          n[std::size_t(d)] = m;
          return a.index(n[0], n[1], n[2]);
        };
        for(int m = 0; m <= p; ++m) b[std::size_t(m)] = a.c[at(m)];
        for(int r = 1; r <= p; ++r) {
          left.c[at(r - 1)] = b[0];
          right.c[at(p - r + 1)] = b[std::size_t(p - r + 1)];
          for(int m = 0; m + r <= p; ++m) b[std::size_t(m)] = 0.5 * (b[std::size_t(m)] + b[std::size_t(m + 1)]);
        }
        left.c[at(p)] = b[0];
        right.c[at(0)] = b[0];
      }
  return {left, right};
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
