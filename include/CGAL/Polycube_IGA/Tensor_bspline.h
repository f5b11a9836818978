// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tensor-product B-splines and NURBS of any parametric dimension N (1 curve, 2 surface,
// 3 volume) in R^3 (reference §2.1.2.2, eq. 2.8-2.11): one clamped knot vector and degree
// per direction, control points with the first direction varying fastest (G+Smo's order),
// optional positive weights. Evaluation of points and of first and second partial
// derivatives; rational derivatives follow from the homogeneous ones by the quotient rule.
// Bspline_curve, Tensor_bspline_surface and Tensor_bspline_volume are the named
// instances users hold; this header holds what they share.

#ifndef CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_H
#define CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_H

#include <CGAL/Polycube_IGA/Bspline_basis.h>
#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Knot_vector.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Point and partial derivatives of an N-variate map at one parameter.
template <int N>
struct Tensor_bspline_derivatives
{
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector3d, N> first;                  ///< first[d] = dX/dt_d
  std::array<std::array<Eigen::Vector3d, N>, N> second;  ///< second[d][e] = d2X/dt_d dt_e (symmetric)
  Tensor_bspline_derivatives()
  {
    for(int d = 0; d < N; ++d) {
      first[d].setZero();
      for(int e = 0; e < N; ++e) second[d][e].setZero();
    }
  }
};

namespace internal {

/// Calls f(index) for every multi-index 0 <= index[d] < extent[d], direction 0 fastest.
template <int N, class F>
void for_each_multi_index(const std::array<int, N>& extent, F&& f)
{
  for(int d = 0; d < N; ++d)
    if(extent[d] <= 0) return;
  std::array<int, N> i{};
  for(;;) {
    f(static_cast<const std::array<int, N>&>(i));
    int d = 0;
    while(d < N && ++i[d] == extent[d]) i[d++] = 0;
    if(d == N) return;
  }
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// A tensor-product B-spline (or NURBS when weighted) map from N parameters into R^3.
template <int N>
class Tensor_bspline
{
public:
  static_assert(N >= 1 && N <= 3, "Tensor_bspline: parametric dimension 1, 2 or 3");
  static constexpr int dimension = N;
  using Point = Eigen::Vector3d;
  using Parameter = std::array<double, N>;
  using Index = std::array<int, N>;
  using Derivatives = Tensor_bspline_derivatives<N>;

  Tensor_bspline() = default;

  /// `control_points` has prod_d n_d entries, direction 0 fastest; `weights` is empty
  /// (polynomial B-spline) or has one positive weight per control point (NURBS).
  Tensor_bspline(std::array<Knot_vector, N> knots, std::vector<Point> control_points,
                 std::vector<double> weights = {})
    : knots_(std::move(knots)), points_(std::move(control_points)), weights_(std::move(weights))
  {
    std::size_t n = 1;
    for(int d = 0; d < N; ++d) {
      if(knots_[d].size() == 0)
        throw Invalid_input_error("invalid_knot_vector", "knot vector of direction " + std::to_string(d) + " is empty");
      n *= std::size_t(knots_[d].number_of_basis_functions());
    }
    if(points_.size() != n)
      throw Invalid_input_error("invalid_control_net", "the knot vectors need " + std::to_string(n) +
                                                           " control points, got " + std::to_string(points_.size()));
    for(std::size_t i = 0; i < n; ++i)
      if(!points_[i].allFinite())
        throw Invalid_input_error("invalid_control_net", "control point " + std::to_string(i) + " is not finite");
    if(!weights_.empty()) {
      if(weights_.size() != n)
        throw Invalid_input_error("invalid_control_net", "expected " + std::to_string(n) + " weights, got " +
                                                             std::to_string(weights_.size()));
      for(std::size_t i = 0; i < n; ++i)
        if(!(std::isfinite(weights_[i]) && weights_[i] > 0.))
          throw Invalid_input_error("invalid_control_net", "weight " + std::to_string(i) + " is not a positive number");
    }
  }

  const std::array<Knot_vector, N>& knot_vectors() const { return knots_; }
  const Knot_vector& knot_vector(int d) const { return knots_[std::size_t(d)]; }
  int degree(int d) const { return knot_vector(d).degree(); }
  int number_of_control_points(int d) const { return knot_vector(d).number_of_basis_functions(); }
  std::size_t number_of_control_points() const { return points_.size(); }
  Index control_net_size() const
  {
    Index s;
    for(int d = 0; d < N; ++d) s[d] = number_of_control_points(d);
    return s;
  }

  std::size_t linear_index(const Index& i) const
  {
    std::size_t k = 0;
    for(int d = N - 1; d >= 0; --d) k = k * std::size_t(number_of_control_points(d)) + std::size_t(i[d]);
    return k;
  }
  const Point& control_point(const Index& i) const { return points_[linear_index(i)]; }
  /// Moving control points keeps the basis; the net size cannot change.
  Point& control_point(const Index& i) { return points_[linear_index(i)]; }
  const std::vector<Point>& control_points() const { return points_; }
  std::vector<Point>& control_points() { return points_; }

  bool is_rational() const { return !weights_.empty(); }
  const std::vector<double>& weights() const { return weights_; }
  double weight(std::size_t linear) const { return weights_.empty() ? 1. : weights_[linear]; }

  /// Homogeneous control points (w x, w y, w z, w): knot insertion and degree elevation are
  /// linear in them, which is why refinement keeps NURBS exact.
  std::vector<Eigen::Vector4d> homogeneous_control_points() const
  {
    std::vector<Eigen::Vector4d> h(points_.size());
    for(std::size_t i = 0; i < points_.size(); ++i) {
      const double w = weight(i);
      h[i] << w * points_[i], w;
    }
    return h;
  }

  /// Inverse of homogeneous_control_points(); weights are dropped when `rational` is false.
  static Tensor_bspline from_homogeneous(std::array<Knot_vector, N> knots, const std::vector<Eigen::Vector4d>& h,
                                         bool rational)
  {
    std::vector<Point> pts(h.size());
    std::vector<double> w;
    if(rational) w.resize(h.size());
    for(std::size_t i = 0; i < h.size(); ++i) {
      pts[i] = h[i].template head<3>() / h[i][3];
      if(rational) w[i] = h[i][3];
    }
    return Tensor_bspline(std::move(knots), std::move(pts), std::move(w));
  }

  /// Parameter domain of direction d.
  std::pair<double, double> domain(int d) const { return {knot_vector(d).first(), knot_vector(d).last()}; }

  /// Parameter of the point with normalized coordinates `s` in [0,1]^N.
  Parameter from_normalized(const Parameter& s) const
  {
    Parameter t;
    for(int d = 0; d < N; ++d) {
      const double a = knot_vector(d).first(), b = knot_vector(d).last();
      t[d] = s[d] == 1. ? b : a + s[d] * (b - a);
    }
    return t;
  }

  Point evaluate(const Parameter& t) const { return derivatives(t, 0).point; }

  /// Point and partial derivatives up to `order` (0, 1 or 2) at `t`.
  Derivatives derivatives(const Parameter& t, int order = 1) const
  {
    constexpr int P = Knot_vector::maximum_degree + 1;
    const int ord = order < 0 ? 0 : (order > 2 ? 2 : order);
    double B[N][3][P];
    Index span, first, extent;
    for(int d = 0; d < N; ++d) {
      const Knot_vector& kv = knots_[d];
      const int p = kv.degree();
      span[d] = kv.find_span(t[d]);
      double ders[3 * P];
      basis_function_derivatives(kv, span[d], t[d], ord, ders);
      for(int k = 0; k <= ord; ++k)
        for(int j = 0; j <= p; ++j) B[d][k][j] = ders[k * (p + 1) + j];
      first[d] = span[d] - p;
      extent[d] = p + 1;
    }
    // Homogeneous sums: value, first partials, second partials.
    Eigen::Vector4d A = Eigen::Vector4d::Zero();
    std::array<Eigen::Vector4d, N> A1;
    std::array<std::array<Eigen::Vector4d, N>, N> A2;
    for(int d = 0; d < N; ++d) {
      A1[d].setZero();
      for(int e = 0; e < N; ++e) A2[d][e].setZero();
    }
    const bool rational = is_rational();
    internal::for_each_multi_index<N>(extent, [&](const Index& a) {
      Index g;
      for(int d = 0; d < N; ++d) g[d] = first[d] + a[d];
      const std::size_t li = linear_index(g);
      Eigen::Vector4d h;
      const double w = rational ? weights_[li] : 1.;
      h << w * points_[li], w;
      double v0 = 1.;
      for(int d = 0; d < N; ++d) v0 *= B[d][0][a[d]];
      A += v0 * h;
      if(ord == 0) return;
      for(int d = 0; d < N; ++d) {
        double v = 1.;
        for(int e = 0; e < N; ++e) v *= B[e][e == d ? 1 : 0][a[e]];
        A1[d] += v * h;
        if(ord < 2) continue;
        for(int f = d; f < N; ++f) {
          double s = 1.;
          for(int e = 0; e < N; ++e) s *= B[e][(e == d) + (e == f)][a[e]];
          A2[d][f] += s * h;
        }
      }
    });
    Derivatives r;
    const double w = A[3];
    r.point = A.template head<3>() / w;
    if(ord >= 1)
      for(int d = 0; d < N; ++d) r.first[d] = (A1[d].template head<3>() - A1[d][3] * r.point) / w;
    if(ord >= 2)
      for(int d = 0; d < N; ++d)
        for(int f = d; f < N; ++f) {
          r.second[d][f] = (A2[d][f].template head<3>() - A2[d][f][3] * r.point - A1[d][3] * r.first[f] -
                            A1[f][3] * r.first[d]) / w;
          r.second[f][d] = r.second[d][f];
        }
    return r;
  }

private:
  std::array<Knot_vector, N> knots_;
  std::vector<Point> points_;
  std::vector<double> weights_;
};

/// The (N-1)-variate map on the side t_d = first (e = 0) or t_d = last (e = 1) of `s`,
/// its remaining directions kept in increasing order. Exact: a clamped spline
/// interpolates its boundary control net.
template <int N>
Tensor_bspline<N - 1> boundary_of(const Tensor_bspline<N>& s, int d, int e)
{
  static_assert(N >= 2, "boundary_of needs a surface or a volume");
  std::array<Knot_vector, N - 1> knots;
  std::array<int, N - 1> extent;
  for(int k = 0, j = 0; k < N; ++k)
    if(k != d) {
      knots[std::size_t(j)] = s.knot_vector(k);
      extent[std::size_t(j++)] = s.number_of_control_points(k);
    }
  std::vector<Eigen::Vector3d> pts;
  std::vector<double> w;
  const int fixed = e == 0 ? 0 : s.number_of_control_points(d) - 1;
  internal::for_each_multi_index<N - 1>(extent, [&](const std::array<int, N - 1>& a) {
    std::array<int, N> g;
    for(int k = 0, j = 0; k < N; ++k) g[std::size_t(k)] = (k == d) ? fixed : a[std::size_t(j++)];
    const std::size_t li = s.linear_index(g);
    pts.push_back(s.control_points()[li]);
    if(s.is_rational()) w.push_back(s.weights()[li]);
  });
  return Tensor_bspline<N - 1>(knots, std::move(pts), std::move(w));
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_H
