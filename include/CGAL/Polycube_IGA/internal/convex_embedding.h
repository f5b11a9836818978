// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Bijective maps of disk pieces onto convex polygons (reference §2.1.3): the border is placed
// on the polygon by arc length between anchor vertices, the interior by a Tutte-type
// embedding with symmetrised mean-value weights w_ij + w_ji. Those weights are positive for
// any triangle shape, so Floater's theorem makes the map one-to-one onto the convex polygon,
// and the system is symmetric positive definite (one CHOLMOD factorisation, two solves).
// The theorem has one more hypothesis when the polygon has straight sides carrying several
// border vertices: no interior edge may join two vertices of the same side (a "dividing
// edge" flattens everything between it and the side). Such edges are split first.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_CONVEX_EMBEDDING_H
#define CGAL_POLYCUBE_IGA_INTERNAL_CONVEX_EMBEDDING_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>
#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

template <class P>
Eigen::Vector3d point3(const CGAL::Surface_mesh<P>& m, typename CGAL::Surface_mesh<P>::Vertex_index v)
{
  const P& p = m.point(v);
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

template <class P>
using Uv_map = typename CGAL::Surface_mesh<P>::template Property_map<typename CGAL::Surface_mesh<P>::Vertex_index, Eigen::Vector2d>;

/// "v:uv" of `m`, added (all (0,0)) when missing.
template <class P>
Uv_map<P> uv_map(CGAL::Surface_mesh<P>& m)
{
  return m.template add_property_map<typename CGAL::Surface_mesh<P>::Vertex_index, Eigen::Vector2d>("v:uv", Eigen::Vector2d(0, 0)).first;
}

/// Point location in a piece's uv map (a bucket grid over the unit disk), and the 3D point
/// at a uv position by barycentric interpolation.
template <class P>
class Uv_locator
{
  using Mesh = CGAL::Surface_mesh<P>;
  using F = typename Mesh::Face_index;

public:
  Uv_locator(const Mesh& piece, const Uv_map<P>& uv) : m_(piece), uv_(uv)
  {
    n_ = std::max(1, int(std::sqrt(double(num_faces(piece)))));
    cells_.resize(std::size_t(n_ * n_));
    for(F f : faces(piece)) {
      Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
      for(auto v : vertices_around_face(halfedge(f, piece), piece)) {
        lo = lo.cwiseMin(uv[v]);
        hi = hi.cwiseMax(uv[v]);
      }
      const std::array<int, 2> a = cell(lo), b = cell(hi);
      for(int j = a[1]; j <= b[1]; ++j)
        for(int i = a[0]; i <= b[0]; ++i) cells_[std::size_t(j * n_ + i)].push_back(f);
    }
  }

  /// The 3D point at uv position q, or nothing when q is in no triangle.
  bool point_at(const Eigen::Vector2d& q, Eigen::Vector3d& out) const
  {
    Eigen::Vector3d normal;
    return point_at(q, out, normal);
  }

  /// The same, and the unit normal of the triangle holding q.
  bool point_at(const Eigen::Vector2d& q, Eigen::Vector3d& out, Eigen::Vector3d& normal) const
  {
    const std::array<int, 2> c = cell(q);
    for(F f : cells_[std::size_t(c[1] * n_ + c[0])]) {
      std::array<typename Mesh::Vertex_index, 3> t;
      int k = 0;
      for(auto v : vertices_around_face(halfedge(f, m_), m_)) t[std::size_t(k++)] = v;
      const Eigen::Vector2d a = uv_[t[0]], b = uv_[t[1]], d = uv_[t[2]];
      const double area = cross(b - a, d - a);
      if(!(std::abs(area) > 0.)) continue;
      const double l1 = cross(q - a, d - a) / area, l2 = cross(b - a, q - a) / area, l0 = 1. - l1 - l2;
      const double eps = -1e-9;
      if(l0 < eps || l1 < eps || l2 < eps) continue;
      const Eigen::Vector3d x0 = point3(m_, t[0]), x1 = point3(m_, t[1]), x2 = point3(m_, t[2]);
      out = l0 * x0 + l1 * x1 + l2 * x2;
      normal = (x1 - x0).cross(x2 - x0).normalized();
      return true;
    }
    return false;
  }

private:
  static double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
  std::array<int, 2> cell(const Eigen::Vector2d& q) const
  {
    std::array<int, 2> c;
    for(int d = 0; d < 2; ++d) c[std::size_t(d)] = std::clamp(int((q[d] + 1.) * 0.5 * n_), 0, n_ - 1);
    return c;
  }
  const Mesh& m_;
  const Uv_map<P>& uv_;
  int n_ = 1;
  std::vector<std::vector<F>> cells_;
};

/// Exact orientation of the uv triangle (a, b, c).
inline CGAL::Orientation uv_orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c)
{
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  return CGAL::orientation(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()), K::Point_2(c.x(), c.y()));
}

/// Whether p lies strictly inside the convex counter-clockwise polygon `polygon` (exact).
inline bool strictly_inside_convex_polygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p)
{
  for(std::size_t i = 0; i < polygon.size(); ++i)
    if(uv_orientation(polygon[i], polygon[(i + 1) % polygon.size()], p) != CGAL::LEFT_TURN) return false;
  return true;
}

/// Number of triangles of `m` whose "v:uv" orientation (exact) is not positive.
template <class P>
std::size_t count_nonpositive_uv_triangles(CGAL::Surface_mesh<P>& m)
{
  const Uv_map<P> uv = uv_map(m);
  std::size_t bad = 0;
  for(auto f : faces(m)) {
    const auto h = halfedge(f, m);
    if(uv_orientation(uv[source(h, m)], uv[target(h, m)], uv[target(next(h, m), m)]) != CGAL::LEFT_TURN) ++bad;
  }
  return bad;
}

/// Border positions: loop[anchors[i].first] at anchors[i].second (sorted by loop index, at
/// least 3, a convex counter-clockwise polygon), the vertices between two anchors on the
/// segment joining them in proportion to 3D arc length (wrapping around the loop's end).
/// Throws Internal_error("parameterization_failed") for anchors that break these rules.
template <class P>
std::vector<Eigen::Vector2d> place_border(const CGAL::Surface_mesh<P>& piece,
                                          const std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>& loop,
                                          const std::vector<std::pair<std::size_t, Eigen::Vector2d>>& anchors)
{
  const std::size_t n = loop.size(), na = anchors.size();
  if(na < 3 || n < 3) throw Internal_error("parameterization_failed", "a convex border needs at least 3 anchors on a loop of at least 3 vertices");
  for(std::size_t a = 0; a < na; ++a) {
    if(anchors[a].first >= n || (a > 0 && anchors[a].first <= anchors[a - 1].first))
      throw Internal_error("parameterization_failed", "border anchors must be distinct loop indices in increasing order");
    if(!anchors[a].second.allFinite()) throw Internal_error("parameterization_failed", "a border anchor is not finite");
  }
  // Convex and counter-clockwise: no right turn, and the turns add up to one full turn
  // (which rules out a star polygon winding several times).
  double turning = 0.;
  for(std::size_t a = 0; a < na; ++a) {
    const Eigen::Vector2d& p = anchors[(a + na - 1) % na].second;
    const Eigen::Vector2d& q = anchors[a].second;
    const Eigen::Vector2d& r = anchors[(a + 1) % na].second;
    const Eigen::Vector2d d1 = q - p, d2 = r - q;
    const double cross = d1.x() * d2.y() - d1.y() * d2.x();
    // A right turn within rounding is tolerated: dense circle anchors have tiny turns.
    if(p == q || cross < -1e-12 * d1.norm() * d2.norm())
      throw Internal_error("parameterization_failed", "the border anchors do not form a convex counter-clockwise polygon");
    turning += std::atan2(cross, d1.dot(d2));
  }
  if(std::abs(turning - 2 * M_PI) > 1e-6)
    throw Internal_error("parameterization_failed", "the border anchors do not form a convex counter-clockwise polygon");
  std::vector<double> s(n + 1, 0.);
  for(std::size_t i = 0; i < n; ++i) s[i + 1] = s[i] + (point3(piece, loop[(i + 1) % n]) - point3(piece, loop[i])).norm();
  std::vector<Eigen::Vector2d> uv(n);
  for(std::size_t a = 0; a < na; ++a) {
    const std::size_t i0 = anchors[a].first, i1 = anchors[(a + 1) % na].first;
    const Eigen::Vector2d p0 = anchors[a].second, p1 = anchors[(a + 1) % na].second;
    const std::size_t count = (i1 + n - i0) % n; // edges from anchor a to anchor a+1
    double total = 0.;
    for(std::size_t k = 0; k < count; ++k) {
      const std::size_t i = (i0 + k) % n;
      total += s[i + 1] - s[i];
    }
    double acc = 0.;
    for(std::size_t k = 0; k < count; ++k) {
      const std::size_t i = (i0 + k) % n;
      const double t = total > 0 ? acc / total : double(k) / double(count);
      uv[i] = k == 0 ? p0 : Eigen::Vector2d((1 - t) * p0 + t * p1);
      acc += s[i + 1] - s[i];
    }
  }
  return uv;
}

/// Splits every interior edge whose two ends are border vertices on the same straight side of
/// the border polygon `loop_uv` (such an edge would flatten the region between it and the
/// side onto the side). The new vertex is the 3D midpoint, an interior vertex with no parent;
/// faces keep their "f:parent". Returns the number of edges split. Sides are maximal runs of
/// loop vertices turning by less than 1e-9 (sine of the angle), so the rounding of
/// place_border's interpolation does not create corners.
template <class P>
std::size_t split_dividing_edges(CGAL::Surface_mesh<P>& piece, const std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>& loop,
                                 const std::vector<Eigen::Vector2d>& loop_uv)
{
  using Mesh = CGAL::Surface_mesh<P>;
  const std::size_t n = loop.size();
  if(n < 3 || loop_uv.size() != n) return 0;
  std::vector<std::size_t> corners;
  for(std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d d1 = loop_uv[i] - loop_uv[(i + n - 1) % n], d2 = loop_uv[(i + 1) % n] - loop_uv[i];
    const double cross = d1.x() * d2.y() - d1.y() * d2.x();
    if(std::abs(cross) > 1e-9 * d1.norm() * d2.norm() || d1.dot(d2) <= 0) corners.push_back(i);
  }
  if(corners.empty()) return 0;
  // side[i]: the side starting at the last corner at or before i; a corner also ends the
  // side of its predecessor.
  std::vector<bool> is_corner(n, false);
  for(std::size_t c : corners) is_corner[c] = true;
  std::vector<std::size_t> side(n), position(num_vertices(piece), no_parent);
  for(std::size_t k = 0, c = 0; k < n; ++k) {
    const std::size_t i = (corners[0] + k) % n;
    if(k > 0 && is_corner[i]) ++c;
    side[i] = c;
  }
  for(std::size_t i = 0; i < n; ++i) position[loop[i]] = i;
  auto on_side = [&](std::size_t i, std::size_t c) { return side[i] == c || (is_corner[i] && side[(i + n - 1) % n] == c); };
  std::vector<typename Mesh::Halfedge_index> dividing;
  for(auto e : edges(piece)) {
    const auto h = halfedge(e, piece);
    if(is_border(e, piece)) continue;
    const std::size_t i = position[source(h, piece)], j = position[target(h, piece)];
    if(i == no_parent || j == no_parent) continue;
    if(on_side(j, side[i]) || (is_corner[i] && on_side(j, side[(i + n - 1) % n]))) dividing.push_back(h);
  }
  for(auto h : dividing) split_edge_at(piece, h, 0.5);
  return dividing.size();
}

/// Writes "v:uv" for every vertex: the loop vertices at loop_uv, the others by a Tutte-type
/// embedding with symmetrised mean-value weights (positive, so the map is one-to-one onto a
/// convex polygon; the system is SPD, solved with Sparse_cholesky). Interior edges joining
/// two vertices of one straight side are split first (split_dividing_edges: the piece may
/// gain interior vertices, appended, with v:parent no_parent). Returns the number of
/// triangles whose uv orientation (exact) is not positive: 0 expected.
template <class P>
std::size_t embed_in_convex_polygon(CGAL::Surface_mesh<P>& piece,
                                    const std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>& loop,
                                    const std::vector<Eigen::Vector2d>& loop_uv)
{
  using Mesh = CGAL::Surface_mesh<P>;
  using V = typename Mesh::Vertex_index;
  if(loop.size() != loop_uv.size()) throw Internal_error("parameterization_failed", "the border positions do not match the border loop");
  split_dividing_edges(piece, loop, loop_uv);
  auto uv = uv_map(piece);
  const std::size_t nv = num_vertices(piece);
  std::vector<int> unknown(nv, -1);
  std::vector<bool> fixed(nv, false);
  for(std::size_t i = 0; i < loop.size(); ++i) {
    fixed[loop[i]] = true;
    uv[loop[i]] = loop_uv[i];
  }
  int n = 0;
  for(V v : vertices(piece))
    if(!fixed[v]) unknown[v] = n++;
  // Mean-value weight of edge (i,j) at i: (tan(a/2) + tan(b/2)) / |x_j - x_i|, a and b the
  // angles at i beside the edge; accumulated per face corner, so each edge sums both ends.
  // tan(a/2) = |u x v| / (|u||v| + u.v), capped where the angle nears pi; edge lengths are
  // floored so that degenerate triangles give large or zero terms, never inf or NaN.
  double mean_length = 0.;
  for(auto e : edges(piece)) mean_length += (point3(piece, source(halfedge(e, piece), piece)) - point3(piece, target(halfedge(e, piece), piece))).norm();
  mean_length = num_edges(piece) > 0 ? mean_length / double(num_edges(piece)) : 1.;
  const double min_length = 1e-12 * mean_length;
  std::vector<double> w(num_edges(piece), 0.);
  for(auto f : faces(piece)) {
    auto h = halfedge(f, piece);
    for(int k = 0; k < 3; ++k, h = next(h, piece)) {
      const V i = source(h, piece), j = target(h, piece), l = target(next(h, piece), piece);
      const Eigen::Vector3d a = point3(piece, j) - point3(piece, i), b = point3(piece, l) - point3(piece, i);
      const double la = a.norm(), lb = b.norm();
      if(!(la > 0) || !(lb > 0)) continue; // no angle at a collapsed corner
      const double denominator = la * lb + a.dot(b), sine = a.cross(b).norm();
      const double t = std::min(denominator > 0 ? sine / denominator : 1e6, 1e6);
      if(!std::isfinite(t)) continue;
      w[std::size_t(edge(h, piece))] += t / std::max(la, min_length);
      w[std::size_t(edge(prev(h, piece), piece))] += t / std::max(lb, min_length);
    }
  }
  double mean = 0.;
  for(double x : w) mean += x;
  mean = w.empty() || !(mean > 0) ? 1. : mean / double(w.size());
  for(double& x : w) x = std::max(x, 1e-9 * mean); // every weight positive: Floater's theorem holds
  if(n > 0) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(std::size_t(n) * 7);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
    for(auto e : edges(piece)) {
      const V a = source(halfedge(e, piece), piece), b = target(halfedge(e, piece), piece);
      const double x = w[std::size_t(e)];
      for(int side = 0; side < 2; ++side) {
        const V p = side ? b : a, q = side ? a : b;
        if(unknown[p] < 0) continue;
        t.emplace_back(unknown[p], unknown[p], x);
        if(unknown[q] >= 0) {
          if(unknown[q] < unknown[p]) t.emplace_back(unknown[p], unknown[q], -x); // lower triangle only
        } else
          rhs.row(unknown[p]) += x * uv[q].transpose();
      }
    }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(t.begin(), t.end());
    Sparse_cholesky solver;
    solver.factor(A, "convex embedding of a layout piece");
    const Eigen::MatrixXd x = solver.solve(rhs);
    for(V v : vertices(piece))
      if(unknown[v] >= 0) uv[v] = x.row(unknown[v]).transpose();
  }
  return count_nonpositive_uv_triangles(piece);
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_CONVEX_EMBEDDING_H
