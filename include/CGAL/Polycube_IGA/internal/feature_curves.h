// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Sharp edges of a surface mesh and the feature curves they form. CAD exports (a box, a
// machined part) have creases that a smooth spline face cannot follow: a layout whose arcs
// run along them gives faces that are smooth inside and meet at the crease. Read by the
// cuboid decomposition (a box laid out on its own edges).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_FEATURE_CURVES_H
#define CGAL_POLYCUBE_IGA_INTERNAL_FEATURE_CURVES_H

#include <CGAL/Polycube_IGA/internal/triangle_projection.h>

#include <Eigen/Dense>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// Per edge (by index): true where the normals of its two faces differ by more than
/// `angle_degrees` (border edges are not sharp; a face without area has no normal and
/// makes no edge sharp).
template <class Mesh>
std::vector<bool> sharp_edges(const Mesh& m, double angle_degrees)
{
  std::vector<Eigen::Vector3d> normal(num_faces(m));
  for(auto f : faces(m)) normal[std::size_t(f)] = unit_face_normal(m, f);
  const double c = std::cos(angle_degrees * 3.14159265358979323846 / 180.);
  std::vector<bool> sharp(num_edges(m), false);
  for(auto e : edges(m)) {
    const auto h = halfedge(e, m);
    if(is_border_edge(h, m)) continue;
    const Eigen::Vector3d &a = normal[std::size_t(face(h, m))], &b = normal[std::size_t(face(opposite(h, m), m))];
    if(a.squaredNorm() > 0. && b.squaredNorm() > 0.) sharp[std::size_t(e)] = a.dot(b) < c;
  }
  return sharp;
}

/// The curves that sharp edges form: `corners` are the vertices with other than two sharp
/// edges (ends and junctions), `curves` the vertex paths between corners through vertices
/// with two; `closed` counts the curves that are loops without a corner (not listed).
struct Feature_curves
{
  std::vector<std::size_t> corners;               ///< increasing vertex indices
  std::vector<std::size_t> sharp_degree;          ///< per vertex
  std::vector<std::vector<std::size_t>> curves;   ///< from a corner to a corner
  std::size_t closed = 0;
};

/// Traces the curves of `sharp` (per edge), from the corners in increasing order and their
/// sharp edges in order around them: deterministic.
template <class Mesh>
Feature_curves feature_curves(const Mesh& m, const std::vector<bool>& sharp)
{
  Feature_curves fc;
  fc.sharp_degree.assign(num_vertices(m), 0);
  for(auto e : edges(m))
    if(sharp[std::size_t(e)]) {
      ++fc.sharp_degree[std::size_t(source(halfedge(e, m), m))];
      ++fc.sharp_degree[std::size_t(target(halfedge(e, m), m))];
    }
  for(auto v : vertices(m))
    if(fc.sharp_degree[std::size_t(v)] > 0 && fc.sharp_degree[std::size_t(v)] != 2) fc.corners.push_back(std::size_t(v));
  std::vector<bool> used(num_edges(m), false);
  for(std::size_t c : fc.corners)
    for(auto h0 : halfedges_around_source(typename Mesh::Vertex_index(std::uint32_t(c)), m)) {
      if(!sharp[std::size_t(edge(h0, m))] || used[std::size_t(edge(h0, m))]) continue;
      std::vector<std::size_t> path{c};
      auto h = h0;
      while(true) {
        used[std::size_t(edge(h, m))] = true;
        const auto v = target(h, m);
        path.push_back(std::size_t(v));
        if(fc.sharp_degree[std::size_t(v)] != 2) break;
        // The other sharp edge at v.
        auto next = h;
        for(auto g : halfedges_around_source(v, m))
          if(sharp[std::size_t(edge(g, m))] && !used[std::size_t(edge(g, m))]) next = g;
        if(next == h) break; // back at the start of a curve that closes on its corner
        h = next;
      }
      fc.curves.push_back(std::move(path));
    }
  // Sharp edges left are loops through vertices of degree 2 only.
  std::vector<bool> seen = used;
  for(auto e : edges(m)) {
    if(!sharp[std::size_t(e)] || seen[std::size_t(e)]) continue;
    ++fc.closed;
    auto h = halfedge(e, m);
    while(!seen[std::size_t(edge(h, m))]) {
      seen[std::size_t(edge(h, m))] = true;
      for(auto g : halfedges_around_source(target(h, m), m))
        if(sharp[std::size_t(edge(g, m))] && !seen[std::size_t(edge(g, m))]) h = g;
    }
  }
  return fc;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_FEATURE_CURVES_H
