// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Bijective maps of disk pieces onto convex polygons (reference §2.1.3): the border is placed
// on the polygon by arc length between anchor vertices, the interior by a Tutte-type
// embedding with symmetrised mean-value weights w_ij + w_ji. Those weights are positive for
// any triangle shape, so Floater's theorem makes the map one-to-one onto the convex polygon,
// and the system is symmetric positive definite (one CHOLMOD factorisation, two solves).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_CONVEX_EMBEDDING_H
#define CGAL_POLYCUBE_IGA_INTERNAL_CONVEX_EMBEDDING_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
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

template <class P>
Uv_map<P> uv_map(CGAL::Surface_mesh<P>& m)
{
  return m.template add_property_map<typename CGAL::Surface_mesh<P>::Vertex_index, Eigen::Vector2d>("v:uv", Eigen::Vector2d(0, 0)).first;
}

/// Border positions: loop[anchors[i].first] at anchors[i].second (sorted by loop index, a
/// convex counter-clockwise polygon), the vertices between two anchors on the segment
/// joining them in proportion to 3D arc length (wrapping around the loop's end).
template <class P>
std::vector<Eigen::Vector2d> place_border(const CGAL::Surface_mesh<P>& piece,
                                          const std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>& loop,
                                          const std::vector<std::pair<std::size_t, Eigen::Vector2d>>& anchors)
{
  const std::size_t n = loop.size(), na = anchors.size();
  if(na < 3 || n < 3) throw Internal_error("parameterization_failed", "a convex border needs at least 3 anchors");
  std::vector<double> s(n + 1, 0.);
  for(std::size_t i = 0; i < n; ++i) s[i + 1] = s[i] + (point3(piece, loop[(i + 1) % n]) - point3(piece, loop[i])).norm();
  std::vector<Eigen::Vector2d> uv(n);
  for(std::size_t a = 0; a < na; ++a) {
    const std::size_t i0 = anchors[a].first, i1 = anchors[(a + 1) % na].first;
    const Eigen::Vector2d p0 = anchors[a].second, p1 = anchors[(a + 1) % na].second;
    const std::size_t count = (i1 + n - i0) % n == 0 ? n : (i1 + n - i0) % n;
    double total = 0.;
    for(std::size_t k = 0; k < count; ++k) {
      const std::size_t i = (i0 + k) % n;
      total += s[i + 1] - s[i];
    }
    double acc = 0.;
    for(std::size_t k = 0; k < count; ++k) {
      const std::size_t i = (i0 + k) % n;
      const double t = total > 0 ? acc / total : double(k) / double(count);
      uv[i] = (1 - t) * p0 + t * p1;
      acc += s[i + 1] - s[i];
    }
  }
  return uv;
}

/// Tutte-type embedding with symmetrised mean-value weights; writes "v:uv" and returns the
/// number of triangles whose uv orientation (exact predicate) is not positive.
template <class P>
std::size_t embed_in_convex_polygon(CGAL::Surface_mesh<P>& piece,
                                    const std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>& loop,
                                    const std::vector<Eigen::Vector2d>& loop_uv)
{
  using Mesh = CGAL::Surface_mesh<P>;
  using V = typename Mesh::Vertex_index;
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
  // Mean-value weight of edge (i,j) at i: (tan(a/2) + tan(b/2)) / |x_j - x_i| over the two
  // angles at i next to the edge; accumulated per face corner, symmetrised per edge.
  std::vector<double> w(num_edges(piece), 0.);
  for(auto f : faces(piece)) {
    auto h = halfedge(f, piece);
    for(int k = 0; k < 3; ++k, h = next(h, piece)) {
      const V i = source(h, piece), j = target(h, piece), l = target(next(h, piece), piece);
      const Eigen::Vector3d a = point3(piece, j) - point3(piece, i), b = point3(piece, l) - point3(piece, i);
      const double la = a.norm(), lb = b.norm();
      if(la <= 0 || lb <= 0) continue;
      const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
      const double t = std::tan(0.5 * std::min(angle, 3.14159));
      w[std::size_t(edge(h, piece))] += t / la;
      w[std::size_t(edge(prev(h, piece), piece))] += t / lb;
    }
  }
  double mean = 0.;
  for(double x : w) mean += x;
  mean = w.empty() ? 1. : mean / double(w.size());
  for(double& x : w) x = std::max(x, 1e-9 * mean + 1e-300); // degenerate corners: keep positive
  if(n > 0) {
    std::vector<Eigen::Triplet<double>> t;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
    for(auto e : edges(piece)) {
      const V a = source(halfedge(e, piece), piece), b = target(halfedge(e, piece), piece);
      const double x = w[std::size_t(e)];
      for(int side = 0; side < 2; ++side) {
        const V p = side ? b : a, q = side ? a : b;
        if(unknown[p] < 0) continue;
        t.emplace_back(unknown[p], unknown[p], x);
        if(unknown[q] >= 0) {
          if(unknown[q] < unknown[p]) t.emplace_back(unknown[p], unknown[q], -x);
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
  std::size_t bad = 0;
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  for(auto f : faces(piece)) {
    std::vector<K::Point_2> q;
    for(V v : vertices_around_face(halfedge(f, piece), piece)) q.emplace_back(uv[v].x(), uv[v].y());
    if(CGAL::orientation(q[0], q[1], q[2]) != CGAL::LEFT_TURN) ++bad;
  }
  return bad;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_CONVEX_EMBEDDING_H
