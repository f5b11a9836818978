// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The unit normal of a mesh face, and the point of a triangle closest to a point with the
// feature of the triangle (inside, an edge, a vertex) that holds it: a walk over a mesh towards a closest point (Mesh_probe in
// Layout_padding.h) needs the feature to know which neighbouring faces may be closer.
// Regions by the signs of dot products against the edges (Voronoi regions of the
// features), in doubles.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_TRIANGLE_PROJECTION_H
#define CGAL_POLYCUBE_IGA_INTERNAL_TRIANGLE_PROJECTION_H

#include <CGAL/boost/graph/iterator.h>
#include <CGAL/number_utils.h>

#include <Eigen/Dense>

#include <array>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// The unit normal of face `f` of `m` from its first three vertices (the mesh's orientation);
/// zero for a face without area.
template <class Mesh, class Face>
Eigen::Vector3d unit_face_normal(const Mesh& m, Face f)
{
  std::array<Eigen::Vector3d, 3> x;
  std::size_t k = 0;
  for(auto v : vertices_around_face(halfedge(f, m), m)) {
    const auto& q = get(CGAL::vertex_point, m, v);
    if(k < 3) x[k] = Eigen::Vector3d(CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z()));
    ++k;
  }
  const Eigen::Vector3d n = (x[1] - x[0]).cross(x[2] - x[0]);
  return n.norm() > 0. ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
}

/// The closest point of a triangle t[0] t[1] t[2], on vertex k (`vertex` = k), on edge
/// t[k] t[k+1 mod 3] (`edge` = k), or inside (both -1).
struct Triangle_projection
{
  Eigen::Vector3d point;
  int vertex = -1;
  int edge = -1;
};

inline Triangle_projection project_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                              int a_index, int b_index, int edge)
{
  const Eigen::Vector3d ab = b - a;
  const double l = ab.squaredNorm();
  const double s = l > 0. ? (p - a).dot(ab) / l : 0.;
  if(s <= 0.) return {a, a_index, -1};
  if(s >= 1.) return {b, b_index, -1};
  return {a + s * ab, -1, edge};
}

inline Triangle_projection project_on_triangle(const Eigen::Vector3d& p, const std::array<Eigen::Vector3d, 3>& t)
{
  const Eigen::Vector3d ab = t[1] - t[0], ac = t[2] - t[0];
  const Eigen::Vector3d ap = p - t[0], bp = p - t[1], cp = p - t[2];
  const double d1 = ab.dot(ap), d2 = ac.dot(ap), d3 = ab.dot(bp), d4 = ac.dot(bp), d5 = ab.dot(cp), d6 = ac.dot(cp);
  const double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
  // va + vb + vc = |ab x ac|^2, but computed with cancellation: where the triangle's sine
  // is below 1e-5 the regions are not to be trusted, and the triangle, as good as a segment,
  // has its closest point on an edge (within 1e-5 of its size of the exact one).
  if(!(ab.cross(ac).squaredNorm() > 1e-10 * ab.squaredNorm() * ac.squaredNorm())) {
    Triangle_projection best = project_on_segment(p, t[0], t[1], 0, 1, 0);
    for(int k = 1; k < 3; ++k) {
      const Triangle_projection q = project_on_segment(p, t[std::size_t(k)], t[std::size_t((k + 1) % 3)], k, (k + 1) % 3, k);
      if((q.point - p).squaredNorm() < (best.point - p).squaredNorm()) best = q;
    }
    return best;
  }
  if(d1 <= 0. && d2 <= 0.) return {t[0], 0, -1};
  if(d3 >= 0. && d4 <= d3) return {t[1], 1, -1};
  if(d6 >= 0. && d5 <= d6) return {t[2], 2, -1};
  if(vc <= 0. && d1 >= 0. && d3 <= 0.) return {t[0] + (d1 / (d1 - d3)) * ab, -1, 0};
  if(va <= 0. && d4 - d3 >= 0. && d5 - d6 >= 0.) return {t[1] + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (t[2] - t[1]), -1, 1};
  if(vb <= 0. && d2 >= 0. && d6 <= 0.) return {t[0] + (d2 / (d2 - d6)) * ac, -1, 2};
  const double s = 1. / (va + vb + vc);
  return {t[0] + (vb * s) * ab + (vc * s) * ac, -1, -1};
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_TRIANGLE_PROJECTION_H
