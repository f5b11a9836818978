// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Trivariate B-spline patch from six compatible boundary surfaces (reference §4.1.2):
// the boundary control points are copied from the faces, the interior ones start from the
// discrete Coons volume of eq. 4.5 (the Boolean sum of the linear interpolants between
// opposite faces, evaluated at the Greville abscissae so that a trilinear block is
// reproduced exactly for any knot vectors), and are then smoothed by the uniform-weight
// Laplacian energy of eq. 4.6 with the boundary fixed. By default the smoothing is solved
// as one sparse SPD system (the discrete harmonic interior, CHOLMOD); the thesis'
// fixed-point iteration is kept as an option. fit_bspline_volume() chains the whole §4.1
// recipe from six point grids: edge curves, faces with fixed edges, then the volume.

#ifndef CGAL_POLYCUBE_IGA_BSPLINE_VOLUME_CONSTRUCTION_H
#define CGAL_POLYCUBE_IGA_BSPLINE_VOLUME_CONSTRUCTION_H

#include <CGAL/Polycube_IGA/Bspline_surface_fitting.h>
#include <CGAL/Polycube_IGA/Tensor_bspline_volume.h>
#include <CGAL/Polycube_IGA/internal/spline_gram.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

enum class Interior_smoothing
{
  none,                 ///< keep the Coons control points
  harmonic,             ///< one sparse solve: each interior point the mean of its 6 neighbours
  fixed_point_iteration ///< the thesis' iteration (Gauss-Seidel sweeps) until changes are small
};

struct Volume_construction_options
{
  Interior_smoothing smoothing = Interior_smoothing::harmonic;
  double iteration_tolerance = 1e-10; ///< fixed-point: stop when no point moves more (x bbox diagonal)
  int maximum_iterations = 100000;
  /// Faces must agree on shared edges within this tolerance (x bbox diagonal).
  double compatibility_tolerance = 1e-9;
};

struct Volume_construction_result
{
  Tensor_bspline_volume volume;
  int iterations = 0;      ///< fixed-point sweeps done (0 otherwise)
  double last_change = 0.; ///< largest move of the last sweep
};

namespace internal {

/// Knot vector of direction `d` as seen by face `side` (faces keep increasing directions).
inline const Knot_vector& face_knots(const std::array<Tensor_bspline_surface, 6>& f, int side, int d)
{
  const int n = side_direction(side);
  return f[std::size_t(side - 1)].knot_vector(d < n ? d : d - 1);
}

/// Discrete Coons volume (eq. 4.5) at every interior node of the net `P` whose boundary
/// nodes are set: sum over non-empty subsets S of {u,v,w} of (-1)^{|S|+1} times the
/// multilinear interpolation, in the directions of S, of the boundary values.
inline void coons_interior(std::vector<Eigen::Vector3d>& P, const std::array<int, 3>& n,
                           const std::array<std::vector<double>, 3>& s)
{
  auto at = [&](int i, int j, int k) -> Eigen::Vector3d& {
    return P[std::size_t(i) + std::size_t(n[0]) * (std::size_t(j) + std::size_t(n[1]) * std::size_t(k))];
  };
  for(int k = 1; k + 1 < n[2]; ++k)
    for(int j = 1; j + 1 < n[1]; ++j)
      for(int i = 1; i + 1 < n[0]; ++i) {
        const std::array<int, 3> idx{{i, j, k}};
        Eigen::Vector3d v = Eigen::Vector3d::Zero();
        for(int S = 1; S < 8; ++S) {
          const int size = (S & 1) + ((S >> 1) & 1) + ((S >> 2) & 1);
          const double sign = (size % 2) ? 1. : -1.;
          for(int c = 0; c < 8; ++c) {
            if(c & ~S) continue; // corner bits only in directions of S
            std::array<int, 3> g = idx;
            double w = 1.;
            for(int d = 0; d < 3; ++d) {
              if(!(S >> d & 1)) continue;
              const bool hi = c >> d & 1;
              g[std::size_t(d)] = hi ? n[std::size_t(d)] - 1 : 0;
              const double t = s[std::size_t(d)][std::size_t(idx[std::size_t(d)])];
              w *= hi ? t : 1. - t;
            }
            v += sign * w * at(g[0], g[1], g[2]);
          }
        }
        at(i, j, k) = v;
      }
}

} // namespace internal

/// Builds a volume patch from six boundary surfaces given in G+Smo's side order
/// (faces[0] = side 1 (u0) ... faces[5] = side 6 (w1)), each parameterized by the two
/// remaining directions in increasing order. The faces must be polynomial, share degrees and
/// knots per direction, and coincide on their shared edges.
inline Volume_construction_result build_bspline_volume(const std::array<Tensor_bspline_surface, 6>& faces,
                                                       const Volume_construction_options& o = Volume_construction_options())
{
  using namespace internal;
  for(int s = 1; s <= 6; ++s) {
    if(faces[std::size_t(s - 1)].number_of_control_points() == 0)
      throw Invalid_input_error("incompatible_surfaces", "boundary surface of side " + std::to_string(s) + " is empty");
    if(faces[std::size_t(s - 1)].is_rational())
      throw Invalid_input_error("incompatible_surfaces", "the Coons construction takes polynomial (non-rational) surfaces");
  }
  std::array<Knot_vector, 3> knots;
  for(int d = 0; d < 3; ++d) {
    bool have = false;
    for(int s = 1; s <= 6; ++s) {
      if(side_direction(s) == d) continue;
      const Knot_vector& k = face_knots(faces, s, d);
      if(!have) {
        knots[std::size_t(d)] = k;
        have = true;
      } else if(k != knots[std::size_t(d)])
        throw Invalid_input_error("incompatible_surfaces", "the boundary surfaces do not share degree and knots in direction " +
                                                               std::string(1, "uvw"[d]) + " (side " + std::to_string(s) + ")");
    }
  }
  const std::array<int, 3> n{{knots[0].number_of_basis_functions(), knots[1].number_of_basis_functions(),
                              knots[2].number_of_basis_functions()}};
  const std::size_t total = std::size_t(n[0]) * std::size_t(n[1]) * std::size_t(n[2]);
  std::vector<Eigen::Vector3d> P(total, Eigen::Vector3d::Zero());
  std::vector<bool> set(total, false);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for(const auto& f : faces)
    for(const auto& p : f.control_points()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const double diag = (hi - lo).norm(), tol = o.compatibility_tolerance * std::max(diag, 1e-300);
  for(int s = 1; s <= 6; ++s) {
    const Tensor_bspline_surface& f = faces[std::size_t(s - 1)];
    const int d = side_direction(s);
    const int a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;
    for(int jb = 0; jb < n[std::size_t(b)]; ++jb)
      for(int ja = 0; ja < n[std::size_t(a)]; ++ja) {
        std::array<int, 3> g;
        g[std::size_t(d)] = side_parameter(s) ? n[std::size_t(d)] - 1 : 0;
        g[std::size_t(a)] = ja;
        g[std::size_t(b)] = jb;
        const std::size_t li = std::size_t(g[0]) + std::size_t(n[0]) * (std::size_t(g[1]) + std::size_t(n[1]) * std::size_t(g[2]));
        const Eigen::Vector3d& p = f.control_point({ja, jb});
        if(set[li]) {
          if((P[li] - p).norm() > tol)
            throw Invalid_input_error("incompatible_surfaces", "boundary surface of side " + std::to_string(s) +
                                                                   " does not meet its neighbours on a shared edge");
          continue;
        }
        set[li] = true;
        P[li] = p;
      }
  }
  std::array<std::vector<double>, 3> greville;
  for(int d = 0; d < 3; ++d)
    for(int i = 0; i < n[std::size_t(d)]; ++i) greville[std::size_t(d)].push_back(knots[std::size_t(d)].normalized_greville(i));
  coons_interior(P, n, greville);

  Volume_construction_result res;
  auto index = [&](int i, int j, int k) {
    return std::size_t(i) + std::size_t(n[0]) * (std::size_t(j) + std::size_t(n[1]) * std::size_t(k));
  };
  const bool has_interior = n[0] > 2 && n[1] > 2 && n[2] > 2;
  if(has_interior && o.smoothing == Interior_smoothing::harmonic) {
    // Uniform graph Laplacian of the control grid; boundary rows are fixed (eq. 4.6 minimised).
    Triplets t;
    t.reserve(total * 7);
    for(int k = 0; k < n[2]; ++k)
      for(int j = 0; j < n[1]; ++j)
        for(int i = 0; i < n[0]; ++i) {
          const std::size_t li = index(i, j, k);
          if(set[li]) continue;
          const std::array<int, 3> g{{i, j, k}};
          for(int d = 0; d < 3; ++d)
            for(int e = -1; e <= 1; e += 2) {
              std::array<int, 3> h = g;
              h[std::size_t(d)] += e;
              t.emplace_back(int(li), int(index(h[0], h[1], h[2])), -1.);
            }
          t.emplace_back(int(li), int(li), 6.);
        }
    Sparse_matrix A(static_cast<Eigen::Index>(total), static_cast<Eigen::Index>(total));
    A.setFromTriplets(t.begin(), t.end());
    Eigen::MatrixXd x = to_matrix(P);
    solve_with_fixed_unknowns(A, Eigen::MatrixXd::Zero(Eigen::Index(total), 3), set, x, "harmonic volume smoothing");
    P = to_points(x);
  } else if(has_interior && o.smoothing == Interior_smoothing::fixed_point_iteration) {
    const double stop = o.iteration_tolerance * std::max(diag, 1e-300);
    for(res.iterations = 1; res.iterations <= o.maximum_iterations; ++res.iterations) {
      double change = 0.;
      for(int k = 1; k + 1 < n[2]; ++k)
        for(int j = 1; j + 1 < n[1]; ++j)
          for(int i = 1; i + 1 < n[0]; ++i) {
            const Eigen::Vector3d q = (P[index(i - 1, j, k)] + P[index(i + 1, j, k)] + P[index(i, j - 1, k)] +
                                       P[index(i, j + 1, k)] + P[index(i, j, k - 1)] + P[index(i, j, k + 1)]) / 6.;
            change = std::max(change, (q - P[index(i, j, k)]).norm());
            P[index(i, j, k)] = q;
          }
      res.last_change = change;
      if(change <= stop) break;
    }
    res.iterations = std::min(res.iterations, o.maximum_iterations);
  }
  res.volume = Tensor_bspline_volume(knots, std::move(P));
  return res;
}

/// Options of fit_bspline_volume(): knots per direction u, v, w and the fitting energy.
struct Volume_fitting_options
{
  std::array<Knot_vector, 3> knots{{Knot_vector::uniform(3, 4), Knot_vector::uniform(3, 4), Knot_vector::uniform(3, 4)}};
  double stretching_weight = 0., bending_weight = 1e-6, data_weight = 1.;
  Parameterization parameterization = Parameterization::chord_length;
  Volume_construction_options construction;
};

/// Six m x m point grids sampling `f` on the sides of [0,1]^3, in the layout
/// fit_bspline_volume() expects (side s indexed by its two remaining directions, increasing).
/// Handy for analytic shapes, examples and tests.
inline std::array<Point_grid, 6> sample_cuboid_faces(const std::function<Eigen::Vector3d(double, double, double)>& f, int m)
{
  if(m < 2) throw Invalid_input_error("invalid_grid", "a face grid needs at least 2 x 2 points");
  std::array<Point_grid, 6> grids;
  for(int s = 1; s <= 6; ++s) {
    Point_grid g(m, m);
    const int d = side_direction(s), a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;
    for(int j = 0; j < m; ++j)
      for(int i = 0; i < m; ++i) {
        double x[3];
        x[d] = double(side_parameter(s));
        x[a] = double(i) / double(m - 1);
        x[b] = double(j) / double(m - 1);
        g(i, j) = f(x[0], x[1], x[2]);
      }
    grids[std::size_t(s - 1)] = g;
  }
  return grids;
}

/// The §4.1 recipe for one cuboid: `grids[s-1]` samples side s (G+Smo order), indexed by the
/// two remaining directions in increasing order. Corners are averaged over the faces that
/// share them, each of the 12 edges is fitted once (ends interpolated), every face is fitted
/// with its four edges fixed, then build_bspline_volume() fills the interior. Faces of
/// neighbouring cuboids fitted from the same samples therefore coincide exactly.
inline Volume_construction_result fit_bspline_volume(const std::array<Point_grid, 6>& grids,
                                                     const Volume_fitting_options& o = Volume_fitting_options())
{
  using namespace internal;
  // Sample counts per direction, checked across faces.
  std::array<int, 3> m{{-1, -1, -1}};
  for(int s = 1; s <= 6; ++s) {
    const Point_grid& g = grids[std::size_t(s - 1)];
    if(g.size_u < 2 || g.size_v < 2 || g.points.size() != std::size_t(g.size_u) * std::size_t(g.size_v))
      throw Invalid_input_error("invalid_grid", "the point grid of side " + std::to_string(s) + " is malformed");
    check_points(g.points);
    const int d = side_direction(s), a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;
    for(auto [dir, size] : {std::pair<int, int>{a, g.size_u}, std::pair<int, int>{b, g.size_v}}) {
      if(m[std::size_t(dir)] < 0) m[std::size_t(dir)] = size;
      else if(m[std::size_t(dir)] != size)
        throw Invalid_input_error("invalid_grid", "the point grids disagree on the number of samples along direction " +
                                                      std::string(1, "uvw"[dir]));
    }
  }
  // Point of face s at volume sample index g (g[d] ignored for the normal direction).
  auto face_point = [&](int s, const std::array<int, 3>& g) {
    const int d = side_direction(s), a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;
    return grids[std::size_t(s - 1)](g[std::size_t(a)], g[std::size_t(b)]);
  };
  double scale = 1.;
  for(const auto& g : grids)
    for(const auto& p : g.points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  const double tol = 1e-6 * scale;
  // Edges: direction t, the two other directions at ends (e1, e2).
  std::array<std::array<std::array<Bspline_curve, 2>, 2>, 3> edges;
  for(int t = 0; t < 3; ++t) {
    const int d1 = t == 0 ? 1 : 0, d2 = t == 2 ? 1 : 2;
    for(int e1 = 0; e1 < 2; ++e1)
      for(int e2 = 0; e2 < 2; ++e2) {
        const int s1 = side_number(d1, e1), s2 = side_number(d2, e2);
        std::vector<Eigen::Vector3d> pts;
        for(int i = 0; i < m[std::size_t(t)]; ++i) {
          std::array<int, 3> g;
          g[std::size_t(t)] = i;
          g[std::size_t(d1)] = e1 ? m[std::size_t(d1)] - 1 : 0;
          g[std::size_t(d2)] = e2 ? m[std::size_t(d2)] - 1 : 0;
          const Eigen::Vector3d p1 = face_point(s1, g), p2 = face_point(s2, g);
          if((p1 - p2).norm() > tol)
            throw Invalid_input_error("incompatible_grids", "the point grids of sides " + std::to_string(s1) + " and " +
                                                                std::to_string(s2) + " differ on their shared edge");
          Eigen::Vector3d p = 0.5 * (p1 + p2);
          if(i == 0 || i + 1 == m[std::size_t(t)]) { // a corner: the mean of its three faces, summed
            Eigen::Vector3d c = Eigen::Vector3d::Zero();  // in side order so all three edges agree bitwise
            for(int dd = 0; dd < 3; ++dd) c += face_point(side_number(dd, g[std::size_t(dd)] == 0 ? 0 : 1), g);
            p = c / 3.;
          }
          pts.push_back(p);
        }
        Curve_fitting_options co;
        co.knots = o.knots[std::size_t(t)];
        co.stretching_weight = o.stretching_weight;
        co.bending_weight = o.bending_weight;
        co.data_weight = o.data_weight;
        co.parameterization = o.parameterization;
        edges[std::size_t(t)][std::size_t(e1)][std::size_t(e2)] = fit_bspline_curve(pts, co).spline;
      }
  }
  std::array<Tensor_bspline_surface, 6> faces;
  for(int s = 1; s <= 6; ++s) {
    const int d = side_direction(s), e = side_parameter(s), a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;
    Surface_fitting_options so;
    so.knots_u = o.knots[std::size_t(a)];
    so.knots_v = o.knots[std::size_t(b)];
    so.stretching_weight = o.stretching_weight;
    so.bending_weight = o.bending_weight;
    so.data_weight = o.data_weight;
    so.parameterization = o.parameterization;
    // Edge along b at a = 0|1 (surface sides 1, 2), edge along a at b = 0|1 (sides 3, 4).
    auto edge = [&](int t, int dir_fixed, int end_fixed) -> const Bspline_curve& {
      const int d1 = t == 0 ? 1 : 0;
      std::array<int, 3> ends{};
      ends[std::size_t(d)] = e;
      ends[std::size_t(dir_fixed)] = end_fixed;
      const int d2 = t == 2 ? 1 : 2;
      return edges[std::size_t(t)][std::size_t(ends[std::size_t(d1)])][std::size_t(ends[std::size_t(d2)])];
    };
    so.fixed_boundaries[0] = edge(b, a, 0);
    so.fixed_boundaries[1] = edge(b, a, 1);
    so.fixed_boundaries[2] = edge(a, b, 0);
    so.fixed_boundaries[3] = edge(a, b, 1);
    faces[std::size_t(s - 1)] = fit_bspline_surface(grids[std::size_t(s - 1)], so).spline;
  }
  return build_bspline_volume(faces, o.construction);
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_BSPLINE_VOLUME_CONSTRUCTION_H
