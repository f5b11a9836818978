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

struct Ignore_child_face
{
  template <class F> void operator()(F, F) const {}
};

/// Subdivides every face into four. `on_child(child, parent)` is called for every face
/// after the subdivision with the face it came from (some faces more than once).
template <class TriangleMesh, class VertexPointMap, class OnChildFace = Ignore_child_face>
void subdivide_at_edge_midpoints(TriangleMesh& tm, VertexPointMap vpm, OnChildFace on_child = OnChildFace())
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
      h = CGAL::Euler::split_face(h, h2, tm); // returned halfedge stays on the central face
      on_child(face(h, tm), f);
      on_child(face(opposite(h, tm), tm), f);
    }
  }
}

/// A closed loop of old vertices, after `subdivide_at_edge_midpoints`, with the midpoint of
/// each of its edges inserted (a, m_ab, b, ...); `old_vertices` is the vertex count before.
template <class TriangleMesh>
std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>
refined_loop(const TriangleMesh& m, const std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& loop,
             std::size_t old_vertices)
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  std::vector<vertex_descriptor> refined;
  for(std::size_t i = 0; i < loop.size(); ++i) {
    const vertex_descriptor a = loop[i], b = loop[(i + 1) % loop.size()];
    refined.push_back(a);
    // The midpoint of ab is the one new neighbour of a that is also b's neighbour.
    for(auto h : halfedges_around_target(a, m)) {
      const vertex_descriptor x = source(h, m);
      if(std::size_t(x) >= old_vertices && halfedge(x, b, m).second) { refined.push_back(x); break; }
    }
  }
  return refined;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
