// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Least-squares fitting of B-spline curves and tensor B-spline surfaces to structured point
// grids (reference §4.1.1, eq. 4.1, 4.3, 4.4): minimise
//   lambda1 * E_stretching + lambda2 * E_bending + lambda3 * E_error,
// E_stretching = int |S_u|^2 + |S_v|^2, E_bending = int |S_uu|^2 + 2|S_uv|^2 + |S_vv|^2 (exact
// Gram matrices), E_error = mean squared distance to the grid points at their parameters
// (chord-length, uniform or given). The normal equations are one sparse SPD system solved
// by CHOLMOD. Boundary curves can be fixed: the boundary control points are then copied
// from the curve (made compatible by degree elevation and knot insertion), so neighbouring
// patches fitted separately share their common boundary exactly (C0 compatibility).
// The G1 constraints of eq. 4.2 are not implemented.

#ifndef CGAL_POLYCUBE_IGA_BSPLINE_SURFACE_FITTING_H
#define CGAL_POLYCUBE_IGA_BSPLINE_SURFACE_FITTING_H

#include <CGAL/Polycube_IGA/Bspline_refinement.h>
#include <CGAL/Polycube_IGA/Tensor_bspline_surface.h>
#include <CGAL/Polycube_IGA/internal/spline_gram.h>
#include <CGAL/Polycube_IGA/parameters.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// A structured grid of points, `size_u` x `size_v`, u fastest: point (i, j) is
/// `points[i + size_u * j]`.
struct Point_grid
{
  int size_u = 0, size_v = 0;
  std::vector<Eigen::Vector3d> points;

  Point_grid() = default;
  Point_grid(int nu, int nv) : size_u(nu), size_v(nv), points(std::size_t(std::max(nu, 0)) * std::size_t(std::max(nv, 0))) {}
  Eigen::Vector3d& operator()(int i, int j) { return points[std::size_t(i) + std::size_t(size_u) * std::size_t(j)]; }
  const Eigen::Vector3d& operator()(int i, int j) const
  {
    return points[std::size_t(i) + std::size_t(size_u) * std::size_t(j)];
  }
  /// Points of side 1..4 (u0, u1, v0, v1), along the increasing remaining index.
  std::vector<Eigen::Vector3d> side(int s) const
  {
    std::vector<Eigen::Vector3d> r;
    if(s <= 2)
      for(int j = 0; j < size_v; ++j) r.push_back((*this)(s == 1 ? 0 : size_u - 1, j));
    else
      for(int i = 0; i < size_u; ++i) r.push_back((*this)(i, s == 3 ? 0 : size_v - 1));
    return r;
  }
};

enum class Parameterization
{
  uniform,      ///< equally spaced parameters
  chord_length, ///< cumulative chord length, averaged over the grid lines (The NURBS Book 9.2.5)
  given         ///< the caller's u_parameters / v_parameters
};

/// Options of fit_bspline_curve().
struct Curve_fitting_options
{
  int degree = 3;
  int spans = 8;                      ///< uniform knot spans, unless `knots` is set
  std::optional<Knot_vector> knots;   ///< overrides degree and spans
  double stretching_weight = 0.;      ///< lambda1
  double bending_weight = 1e-6;       ///< lambda2
  double data_weight = 1.;            ///< lambda3 (relative to the mean squared error)
  Parameterization parameterization = Parameterization::chord_length;
  std::vector<double> parameters;     ///< with Parameterization::given, one per point, in the knot domain
  bool interpolate_end_points = true; ///< end control points = end data points (curves of a net then meet)
};

/// Options of fit_bspline_surface(). Knot vectors default to uniform ones on [0,1].
struct Surface_fitting_options
{
  int degree_u = 3, degree_v = 3;
  int spans_u = 8, spans_v = 8;
  std::optional<Knot_vector> knots_u, knots_v;
  double stretching_weight = 0.;  ///< lambda1 (eq. 4.3)
  double bending_weight = 1e-6;   ///< lambda2 (eq. 4.4)
  double data_weight = 1.;        ///< lambda3 (mean squared distance to the points)
  Parameterization parameterization = Parameterization::chord_length;
  std::vector<double> u_parameters, v_parameters; ///< with Parameterization::given (size_u and size_v values)
  /// Fixed boundary curves of sides 1..4 (index side-1: u0, u1, v0, v1), each oriented along
  /// the increasing remaining parameter. Where two fixed curves meet, their end points must agree.
  std::array<std::optional<Bspline_curve>, 4> fixed_boundaries;
};

template <int N>
struct Fitting_result
{
  Tensor_bspline<N> spline;
  double max_error = 0.; ///< largest distance to a data point at its parameter
  double rms_error = 0.;
  std::array<std::vector<double>, N> parameters; ///< the parameters used, per direction
};
using Curve_fitting_result = Fitting_result<1>;
using Surface_fitting_result = Fitting_result<2>;

namespace internal {

inline void check_fitting_weights(double l1, double l2, double l3)
{
  for(double l : {l1, l2, l3})
    if(!(std::isfinite(l) && l >= 0.))
      throw Invalid_input_error("invalid_fitting_weights", "the fitting weights lambda1..3 must be finite and >= 0");
  if(!(l3 > 0.))
    throw Invalid_input_error("invalid_fitting_weights", "the data weight lambda3 must be positive");
}

inline void check_points(const std::vector<Eigen::Vector3d>& pts)
{
  for(std::size_t i = 0; i < pts.size(); ++i)
    if(!pts[i].allFinite())
      throw Invalid_input_error("invalid_points", "point " + std::to_string(i) + " of the grid is not finite (NaN or infinity)");
}

/// Parameters of `lines` polylines of `n` points each (point (i, line) = at(i, line)),
/// averaged over the lines, mapped to [a, b].
template <class At>
std::vector<double> averaged_parameters(int n, int lines, At at, Parameterization how, double a, double b)
{
  std::vector<double> t(std::size_t(n), 0.);
  int used = 0;
  if(how == Parameterization::chord_length)
    for(int l = 0; l < lines; ++l) {
      std::vector<double> c(std::size_t(n), 0.);
      for(int i = 1; i < n; ++i) c[std::size_t(i)] = c[std::size_t(i - 1)] + (at(i, l) - at(i - 1, l)).norm();
      if(!(c.back() > 0.)) continue;
      for(int i = 0; i < n; ++i) t[std::size_t(i)] += c[std::size_t(i)] / c.back();
      ++used;
    }
  for(int i = 0; i < n; ++i)
    t[std::size_t(i)] = used ? t[std::size_t(i)] / used : double(i) / double(n - 1);
  std::vector<double> r(static_cast<std::size_t>(n));
  for(int i = 0; i < n; ++i) r[std::size_t(i)] = a + (b - a) * t[std::size_t(i)];
  r.front() = a;
  r.back() = b;
  return r;
}

inline void check_given_parameters(const std::vector<double>& t, int n, const Knot_vector& kv, const char* what)
{
  if(int(t.size()) != n)
    throw Invalid_input_error("invalid_parameters", std::string(what) + ": expected " + std::to_string(n) +
                                                        " parameter values, got " + std::to_string(t.size()));
  for(std::size_t i = 0; i < t.size(); ++i)
    if(!(std::isfinite(t[i]) && t[i] >= kv.first() && t[i] <= kv.last() && (i == 0 || t[i] >= t[i - 1])))
      throw Invalid_input_error("invalid_parameters", std::string(what) +
                                                          ": parameters must be finite, non-decreasing and inside the knot domain");
}

/// Least-squares system of one direction: data term and the Gram matrices of orders 0..2.
struct Direction_system
{
  Sparse_matrix B, BtB, G0, G1, G2;
  Direction_system(const Knot_vector& kv, const std::vector<double>& params)
    : B(collocation_matrix(kv, params)), G0(gram_matrix(kv, 0)), G1(gram_matrix(kv, 1)),
      G2(kv.degree() >= 2 ? gram_matrix(kv, 2) : Sparse_matrix(kv.number_of_basis_functions(), kv.number_of_basis_functions()))
  {
    BtB = Sparse_matrix(B.transpose()) * B;
  }
};

/// Brings `c` to degree and knots of `target` (elevation, then insertion), exactly.
inline Bspline_curve make_compatible(const Bspline_curve& c, const Knot_vector& target)
{
  if(c.is_rational())
    throw Invalid_input_error("incompatible_boundary", "a fixed boundary curve must be polynomial (no weights)");
  const Knot_vector& kv = c.knot_vector(0);
  if(kv.first() != target.first() || kv.last() != target.last())
    throw Invalid_input_error("incompatible_boundary", "a fixed boundary curve must have the parameter domain of the surface direction");
  if(kv.degree() > target.degree())
    throw Invalid_input_error("incompatible_boundary", "a fixed boundary curve has a higher degree than the surface");
  Bspline_curve r = elevate_degree<1>(c, 0, target.degree() - kv.degree());
  std::vector<double> missing;
  for(double b : target.breaks()) {
    const int m = target.multiplicity(b) - r.knot_vector(0).multiplicity(b);
    if(m < 0)
      throw Invalid_input_error("incompatible_boundary", "a fixed boundary curve has a knot (" + std::to_string(b) +
                                                             ") that the surface direction does not have");
    if(b != target.first() && b != target.last()) missing.insert(missing.end(), std::size_t(m), b);
  }
  r = refine_knots<1>(r, 0, missing);
  if(r.knot_vector(0) != target)
    throw Invalid_input_error("incompatible_boundary", "a fixed boundary curve cannot be made compatible with the surface knots");
  return r;
}

template <int N>
void measure_errors(Fitting_result<N>& res, const std::vector<Eigen::Vector3d>& pts, const std::array<int, N>& size)
{
  double mx = 0., sq = 0.;
  std::size_t k = 0;
  for_each_multi_index<N>(size, [&](const std::array<int, N>& a) {
    std::array<double, N> t;
    for(int d = 0; d < N; ++d) t[std::size_t(d)] = res.parameters[std::size_t(d)][std::size_t(a[std::size_t(d)])];
    const double e = (res.spline.evaluate(t) - pts[k++]).norm();
    mx = std::max(mx, e);
    sq += e * e;
  });
  res.max_error = mx;
  res.rms_error = std::sqrt(sq / double(std::max<std::size_t>(k, 1)));
}

inline Eigen::MatrixXd to_matrix(const std::vector<Eigen::Vector3d>& pts)
{
  Eigen::MatrixXd m(Eigen::Index(pts.size()), 3);
  for(std::size_t i = 0; i < pts.size(); ++i) m.row(Eigen::Index(i)) = pts[i].transpose();
  return m;
}

inline std::vector<Eigen::Vector3d> to_points(const Eigen::MatrixXd& m)
{
  std::vector<Eigen::Vector3d> pts(std::size_t(m.rows()));
  for(Eigen::Index i = 0; i < m.rows(); ++i) pts[std::size_t(i)] = m.row(i).transpose();
  return pts;
}

} // namespace internal

/// Fits a B-spline curve to `points` (at least two), with the same energy as the surfaces.
inline Curve_fitting_result fit_bspline_curve(const std::vector<Eigen::Vector3d>& points,
                                              const Curve_fitting_options& o = Curve_fitting_options())
{
  using namespace internal;
  check_fitting_weights(o.stretching_weight, o.bending_weight, o.data_weight);
  if(points.size() < 2) throw Invalid_input_error("invalid_grid", "curve fitting needs at least two points");
  check_points(points);
  const Knot_vector kv = o.knots ? *o.knots : Knot_vector::uniform(o.degree, o.spans);
  const int n = kv.number_of_basis_functions(), K = int(points.size());
  if(o.stretching_weight == 0. && o.bending_weight == 0. && K < n)
    throw Invalid_input_error("underdetermined_fit", std::to_string(K) + " points cannot determine " +
                                                         std::to_string(n) + " control points without regularization");
  Curve_fitting_result res;
  if(o.parameterization == Parameterization::given) {
    check_given_parameters(o.parameters, K, kv, "curve fitting");
    res.parameters[0] = o.parameters;
  } else
    res.parameters[0] = averaged_parameters(K, 1, [&](int i, int) { return points[std::size_t(i)]; },
                                            o.parameterization, kv.first(), kv.last());
  const Direction_system S(kv, res.parameters[0]);
  const double wd = o.data_weight / K;
  Sparse_matrix A = wd * S.BtB + o.stretching_weight * S.G1 + o.bending_weight * S.G2;
  Eigen::MatrixXd b = wd * (Sparse_matrix(S.B.transpose()) * to_matrix(points));
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, 3);
  std::vector<bool> fixed(std::size_t(n), false);
  if(o.interpolate_end_points) {
    fixed.front() = fixed.back() = true;
    x.row(0) = points.front().transpose();
    x.row(n - 1) = points.back().transpose();
  }
  solve_with_fixed_unknowns(A, b, fixed, x, "curve fitting");
  res.spline = Bspline_curve({kv}, to_points(x));
  measure_errors<1>(res, points, {K});
  return res;
}

/// Fits a tensor B-spline surface to the grid `g` (eq. 4.1 without the G1 constraints).
inline Surface_fitting_result fit_bspline_surface(const Point_grid& g,
                                                  const Surface_fitting_options& o = Surface_fitting_options())
{
  using namespace internal;
  check_fitting_weights(o.stretching_weight, o.bending_weight, o.data_weight);
  if(g.size_u < 2 || g.size_v < 2 || g.points.size() != std::size_t(g.size_u) * std::size_t(g.size_v))
    throw Invalid_input_error("invalid_grid", "a point grid needs at least 2 x 2 points and size_u * size_v points, got " +
                                                  std::to_string(g.size_u) + " x " + std::to_string(g.size_v) + " and " +
                                                  std::to_string(g.points.size()) + " points");
  check_points(g.points);
  const Knot_vector ku = o.knots_u ? *o.knots_u : Knot_vector::uniform(o.degree_u, o.spans_u);
  const Knot_vector kv = o.knots_v ? *o.knots_v : Knot_vector::uniform(o.degree_v, o.spans_v);
  const int nu = ku.number_of_basis_functions(), nv = kv.number_of_basis_functions();
  if(o.stretching_weight == 0. && o.bending_weight == 0. && (g.size_u < nu || g.size_v < nv))
    throw Invalid_input_error("underdetermined_fit", "a " + std::to_string(g.size_u) + " x " + std::to_string(g.size_v) +
                                                         " grid cannot determine " + std::to_string(nu) + " x " +
                                                         std::to_string(nv) + " control points without regularization");
  Surface_fitting_result res;
  if(o.parameterization == Parameterization::given) {
    check_given_parameters(o.u_parameters, g.size_u, ku, "u parameters");
    check_given_parameters(o.v_parameters, g.size_v, kv, "v parameters");
    res.parameters[0] = o.u_parameters;
    res.parameters[1] = o.v_parameters;
  } else {
    res.parameters[0] = averaged_parameters(g.size_u, g.size_v, [&](int i, int j) { return g(i, j); },
                                            o.parameterization, ku.first(), ku.last());
    res.parameters[1] = averaged_parameters(g.size_v, g.size_u, [&](int j, int i) { return g(i, j); },
                                            o.parameterization, kv.first(), kv.last());
  }
  const Direction_system U(ku, res.parameters[0]), V(kv, res.parameters[1]);
  const double wd = o.data_weight / double(g.points.size());
  Sparse_matrix A = wd * kronecker(V.BtB, U.BtB);
  if(o.stretching_weight > 0.)
    A += o.stretching_weight * (kronecker(V.G0, U.G1) + kronecker(V.G1, U.G0));
  if(o.bending_weight > 0.)
    A += o.bending_weight * (kronecker(V.G0, U.G2) + 2. * kronecker(V.G1, U.G1) + kronecker(V.G2, U.G0));
  // Right-hand side Bu^T Q Bv per coordinate, Q(i, j) the grid.
  Eigen::MatrixXd b(nu * nv, 3);
  const Sparse_matrix BuT = U.B.transpose();
  for(int c = 0; c < 3; ++c) {
    Eigen::MatrixXd Q(g.size_u, g.size_v);
    for(int j = 0; j < g.size_v; ++j)
      for(int i = 0; i < g.size_u; ++i) Q(i, j) = g(i, j)[c];
    const Eigen::MatrixXd R = (BuT * Q) * V.B;
    b.col(c) = wd * Eigen::Map<const Eigen::VectorXd>(R.data(), nu * nv);
  }
  // Fixed boundaries: copy their control points, check that fixed curves meet at corners.
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(nu * nv, 3);
  std::vector<bool> fixed(std::size_t(nu * nv), false);
  std::vector<Eigen::Vector3d> set_value(std::size_t(nu * nv));
  double scale = 0.;
  for(const auto& p : g.points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  const double tol = 1e-9 * std::max(scale, 1.);
  for(int s = 1; s <= 4; ++s) {
    const auto& curve = o.fixed_boundaries[std::size_t(s - 1)];
    if(!curve) continue;
    const Bspline_curve c = make_compatible(*curve, s <= 2 ? kv : ku);
    const int n = s <= 2 ? nv : nu;
    for(int k = 0; k < n; ++k) {
      const int i = s <= 2 ? (s == 1 ? 0 : nu - 1) : k;
      const int j = s <= 2 ? k : (s == 3 ? 0 : nv - 1);
      const std::size_t li = std::size_t(i + nu * j);
      const Eigen::Vector3d& P = c.control_points()[std::size_t(k)];
      if(fixed[li]) {
        if((set_value[li] - P).norm() > tol)
          throw Invalid_input_error("incompatible_boundaries", "fixed boundary curves of sides meeting at a corner do not share their end point");
        continue; // the first curve's point wins, bit for bit
      }
      fixed[li] = true;
      set_value[li] = P;
      x.row(Eigen::Index(li)) = P.transpose();
    }
  }
  solve_with_fixed_unknowns(A, b, fixed, x, "surface fitting");
  res.spline = Tensor_bspline_surface({ku, kv}, to_points(x));
  measure_errors<2>(res, g.points, {g.size_u, g.size_v});
  return res;
}

/*!
 * Named-parameter form of fit_bspline_surface(): `stretching_weight` (lambda1),
 * `bending_weight` (lambda2), `data_weight` (lambda3), `spline_degree` and
 * `number_of_spans` (both directions) override the corresponding fields of `base`.
 * Example: `fit_bspline_surface(grid, parameters::bending_weight(1e-4).spline_degree(3))`.
 */
template <class NamedParameters>
Surface_fitting_result fit_bspline_surface(const Point_grid& g, const NamedParameters& np,
                                           Surface_fitting_options base = Surface_fitting_options())
{
  base.stretching_weight = option(np, internal_np::stretching_weight, base.stretching_weight);
  base.bending_weight = option(np, internal_np::bending_weight, base.bending_weight);
  base.data_weight = option(np, internal_np::data_weight, base.data_weight);
  base.degree_u = base.degree_v = int(option(np, internal_np::spline_degree, base.degree_u));
  base.spans_u = base.spans_v = int(option(np, internal_np::number_of_spans, base.spans_u));
  return fit_bspline_surface(g, base);
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_BSPLINE_SURFACE_FITTING_H
