// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Refinement that leaves the geometry unchanged, for curves, surfaces and volumes (and
// NURBS, through homogeneous control points): knot insertion (h-refinement, Boehm's
// algorithm as in The NURBS Book A5.1) and degree elevation (p-refinement: the elevated
// space, every distinct knot's multiplicity raised by one per degree, contains the old one,
// so interpolation at its Greville points recovers the same map to round-off). Tensor
// products are refined one direction at a time along every line of the control net.
// Bezier extraction (every interior knot to multiplicity p) feeds the certified Jacobian
// bound of Quality.h.

#ifndef CGAL_POLYCUBE_IGA_BSPLINE_REFINEMENT_H
#define CGAL_POLYCUBE_IGA_BSPLINE_REFINEMENT_H

#include <CGAL/Polycube_IGA/Tensor_bspline.h>

#include <Eigen/Dense>

#include <functional>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

using Homogeneous_line = std::vector<Eigen::Vector4d>;

/// Applies `op(line_in, line_out)` to every line of the homogeneous control net of `s` along
/// direction `d`, giving a net whose direction d follows `new_kv`.
template <int N>
Tensor_bspline<N> transform_lines(const Tensor_bspline<N>& s, int d, const Knot_vector& new_kv,
                                  const std::function<void(const Homogeneous_line&, Homogeneous_line&)>& op)
{
  if(d < 0 || d >= N)
    throw Invalid_input_error("invalid_direction", "parametric direction " + std::to_string(d) + " does not exist");
  const std::vector<Eigen::Vector4d> h = s.homogeneous_control_points();
  std::array<int, N> extent = s.control_net_size(), new_extent = extent;
  const int n_old = extent[std::size_t(d)], n_new = new_kv.number_of_basis_functions();
  new_extent[std::size_t(d)] = n_new;
  std::size_t total = 1;
  for(int k = 0; k < N; ++k) total *= std::size_t(new_extent[std::size_t(k)]);
  std::vector<Eigen::Vector4d> out(total);
  std::size_t stride_old = 1, stride_new = 1;
  for(int k = 0; k < d; ++k) {
    stride_old *= std::size_t(extent[std::size_t(k)]);
    stride_new *= std::size_t(new_extent[std::size_t(k)]);
  }
  std::array<int, N> lines = extent;
  lines[std::size_t(d)] = 1;
  Homogeneous_line in(static_cast<std::size_t>(n_old)), res(static_cast<std::size_t>(n_new));
  for_each_multi_index<N>(lines, [&](const std::array<int, N>& a) {
    std::size_t base_old = 0, base_new = 0;
    for(int k = N - 1; k >= 0; --k) {
      base_old = base_old * std::size_t(extent[std::size_t(k)]) + std::size_t(a[std::size_t(k)]);
      base_new = base_new * std::size_t(new_extent[std::size_t(k)]) + std::size_t(a[std::size_t(k)]);
    }
    for(int i = 0; i < n_old; ++i) in[std::size_t(i)] = h[base_old + std::size_t(i) * stride_old];
    op(in, res);
    for(int i = 0; i < n_new; ++i) out[base_new + std::size_t(i) * stride_new] = res[std::size_t(i)];
  });
  std::array<Knot_vector, N> knots = s.knot_vectors();
  knots[std::size_t(d)] = new_kv;
  return Tensor_bspline<N>::from_homogeneous(std::move(knots), out, s.is_rational());
}

} // namespace internal

/// Inserts the value `t` (strictly inside the domain) `times` times into direction `d`.
/// The resulting multiplicity may not exceed the degree. Boehm's algorithm: exact.
template <int N>
Tensor_bspline<N> insert_knot(const Tensor_bspline<N>& s, int d, double t, int times = 1)
{
  if(d < 0 || d >= N)
    throw Invalid_input_error("invalid_direction", "parametric direction " + std::to_string(d) + " does not exist");
  const Knot_vector& kv = s.knot_vector(d);
  const int p = kv.degree();
  if(times <= 0) return s;
  if(!(t > kv.first() && t < kv.last()))
    throw Invalid_input_error("invalid_knot_insertion", "a knot can only be inserted strictly inside the domain [" +
                                                            std::to_string(kv.first()) + ", " + std::to_string(kv.last()) + "]");
  const int mult = kv.multiplicity(t);
  if(mult + times > p)
    throw Invalid_input_error("invalid_knot_insertion", "inserting " + std::to_string(t) + " " + std::to_string(times) +
                                                            " time(s) would raise its multiplicity above the degree");
  const int k = kv.find_span(t), r = times;
  std::vector<double> uq(kv.knots().begin(), kv.knots().begin() + k + 1);
  uq.insert(uq.end(), std::size_t(r), t);
  uq.insert(uq.end(), kv.knots().begin() + k + 1, kv.knots().end());
  const Knot_vector new_kv(p, std::move(uq));
  const std::vector<double>& U = kv.knots();
  return internal::transform_lines<N>(s, d, new_kv, [&](const internal::Homogeneous_line& P, internal::Homogeneous_line& Q) {
    const int n = int(P.size()) - 1;
    for(int i = 0; i <= k - p; ++i) Q[std::size_t(i)] = P[std::size_t(i)];
    for(int i = k - mult; i <= n; ++i) Q[std::size_t(i + r)] = P[std::size_t(i)];
    Eigen::Vector4d R[Knot_vector::maximum_degree + 1];
    for(int i = 0; i <= p - mult; ++i) R[i] = P[std::size_t(k - p + i)];
    int L = k - p;
    for(int j = 1; j <= r; ++j) {
      L = k - p + j;
      for(int i = 0; i <= p - j - mult; ++i) {
        const double alpha = (t - U[std::size_t(L + i)]) / (U[std::size_t(i + k + 1)] - U[std::size_t(L + i)]);
        R[i] = alpha * R[i + 1] + (1. - alpha) * R[i];
      }
      Q[std::size_t(L)] = R[0];
      Q[std::size_t(k + r - j - mult)] = R[p - j - mult];
    }
    for(int i = L + 1; i < k - mult; ++i) Q[std::size_t(i)] = R[i - L];
  });
}

/// Inserts every value of `values` (each strictly inside the domain) into direction `d`.
template <int N>
Tensor_bspline<N> refine_knots(const Tensor_bspline<N>& s, int d, const std::vector<double>& values)
{
  Tensor_bspline<N> r = s;
  for(double t : values) r = insert_knot<N>(r, d, t, 1);
  return r;
}

/// Splits every knot span of every direction into `parts` equal parts (h-refinement).
template <int N>
Tensor_bspline<N> refine_uniformly(const Tensor_bspline<N>& s, int parts = 2)
{
  if(parts < 1) throw Invalid_input_error("invalid_refinement", "a knot span is split into at least one part");
  Tensor_bspline<N> r = s;
  for(int d = 0; d < N; ++d) {
    std::vector<double> values;
    const std::vector<double> b = s.knot_vector(d).breaks();
    for(std::size_t i = 0; i + 1 < b.size(); ++i)
      for(int j = 1; j < parts; ++j) values.push_back(b[i] + (b[i + 1] - b[i]) * double(j) / double(parts));
    r = refine_knots<N>(r, d, values);
  }
  return r;
}

/// Raises the degree of direction `d` by `times`, keeping the map and its continuity
/// (every distinct knot gains `times` in multiplicity).
template <int N>
Tensor_bspline<N> elevate_degree(const Tensor_bspline<N>& s, int d, int times = 1)
{
  if(d < 0 || d >= N)
    throw Invalid_input_error("invalid_direction", "parametric direction " + std::to_string(d) + " does not exist");
  if(times <= 0) return s;
  const Knot_vector& kv = s.knot_vector(d);
  const int p = kv.degree(), q = p + times;
  std::vector<double> k;
  for(double b : kv.breaks()) k.insert(k.end(), std::size_t(kv.multiplicity(b) + times), b);
  const Knot_vector new_kv(q, std::move(k)); // validates q <= maximum_degree
  // Collocation at the Greville points of the new space (Schoenberg-Whitney holds, so the
  // banded matrix is invertible): M = A_new^{-1} A_old maps old to new coefficients.
  const int n_old = kv.number_of_basis_functions(), n_new = new_kv.number_of_basis_functions();
  Eigen::MatrixXd A_new = Eigen::MatrixXd::Zero(n_new, n_new), A_old = Eigen::MatrixXd::Zero(n_new, n_old);
  double N_new[Knot_vector::maximum_degree + 1], N_old[Knot_vector::maximum_degree + 1];
  for(int r = 0; r < n_new; ++r) {
    const double tau = new_kv.greville(r);
    const int sn = new_kv.find_span(tau), so = kv.find_span(tau);
    basis_functions(new_kv, sn, tau, N_new);
    basis_functions(kv, so, tau, N_old);
    for(int j = 0; j <= q; ++j) A_new(r, sn - q + j) = N_new[j];
    for(int j = 0; j <= p; ++j) A_old(r, so - p + j) = N_old[j];
  }
  const Eigen::MatrixXd M = A_new.partialPivLu().solve(A_old);
  return internal::transform_lines<N>(s, d, new_kv, [&](const internal::Homogeneous_line& P, internal::Homogeneous_line& Q) {
    for(int i = 0; i < n_new; ++i) {
      Eigen::Vector4d acc = Eigen::Vector4d::Zero();
      for(int j = 0; j < n_old; ++j)
        if(M(i, j) != 0.) acc += M(i, j) * P[std::size_t(j)];
      Q[std::size_t(i)] = acc;
    }
    // The clamped ends interpolate: keep them bit-exact, so shared boundaries stay shared.
    Q.front() = P.front();
    Q.back() = P.back();
  });
}

/// Raises the degree of every direction by `times`.
template <int N>
Tensor_bspline<N> elevate_degree_uniformly(const Tensor_bspline<N>& s, int times = 1)
{
  Tensor_bspline<N> r = s;
  for(int d = 0; d < N; ++d) r = elevate_degree<N>(r, d, times);
  return r;
}

/// Bezier extraction: every interior knot raised to multiplicity p in every direction, so
/// that the control net of each knot span is that span's Bernstein (Bezier) net.
template <int N>
Tensor_bspline<N> to_bezier_form(const Tensor_bspline<N>& s)
{
  Tensor_bspline<N> r = s;
  for(int d = 0; d < N; ++d) {
    const Knot_vector& kv = s.knot_vector(d);
    const std::vector<double> b = kv.breaks();
    for(std::size_t i = 1; i + 1 < b.size(); ++i) {
      const int missing = kv.degree() - kv.multiplicity(b[i]);
      if(missing > 0) r = insert_knot<N>(r, d, b[i], missing);
    }
  }
  return r;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_BSPLINE_REFINEMENT_H
