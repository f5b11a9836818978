// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Midpoint (1-to-4) subdivision without smoothing: the surface is unchanged as a point
// set, and vertex descriptors of the original vertices stay valid, so anything traced on
// the refined mesh keeps its meaning on the input. Used when a coarse mesh has no room for
// disjoint loops along its edges.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_MESH_REFINEMENT_H
#define CGAL_POLYCUBE_IGA_INTERNAL_MESH_REFINEMENT_H

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/Dynamic_property_map.h>

#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

template <class TriangleMesh, class VertexPointMap>
void subdivide_at_edge_midpoints(TriangleMesh& tm, VertexPointMap vpm)
{
  using GT = boost::graph_traits<TriangleMesh>;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using Point = typename boost::property_traits<VertexPointMap>::value_type;
  const std::vector<typename GT::edge_descriptor> old_edges(edges(tm).begin(), edges(tm).end());
  const std::vector<typename GT::face_descriptor> old_faces(faces(tm).begin(), faces(tm).end());
  auto is_new = get(CGAL::dynamic_vertex_property_t<bool>(), tm);
  for(auto v : vertices(tm)) put(is_new, v, false);
  for(auto e : old_edges) {
    halfedge_descriptor h = halfedge(e, tm);
    const Point a = get(vpm, source(h, tm)), b = get(vpm, target(h, tm));
    halfedge_descriptor hnew = CGAL::Euler::split_edge(h, tm);
    put(vpm, target(hnew, tm), CGAL::midpoint(a, b));
    put(is_new, target(hnew, tm), true);
  }
  // Each old face is now a hexagon o m o m o m: cut its three corners off.
  for(auto f : old_faces) {
    halfedge_descriptor h = halfedge(f, tm);
    while(!get(is_new, target(h, tm))) h = next(h, tm);
    for(int corner = 0; corner < 3; ++corner) {
      halfedge_descriptor h2 = next(next(h, tm), tm);
      if(corner == 2) { CGAL::Euler::split_face(h, h2, tm); break; }
      h = CGAL::Euler::split_face(h, h2, tm); // returned halfedge stays on the central face
    }
  }
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
