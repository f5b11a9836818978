// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A compact, index-based copy of a triangle mesh's combinatorics (edges, faces, border
// cycles, vertex adjacency) and of its vertex positions. Graph searches (Dijkstra, tree-
// cotree, loop tracing) run on these arrays: contiguous and cache-friendly, whatever the
// FaceListGraph model the user holds. Indices follow the mesh's own index maps.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_MESH_GRAPH_H
#define CGAL_POLYCUBE_IGA_INTERNAL_MESH_GRAPH_H

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

template <class TriangleMesh>
struct Mesh_graph
{
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;

  std::vector<vertex_descriptor> vertex;           ///< index -> descriptor
  std::vector<halfedge_descriptor> edge_halfedge;  ///< edge index -> a halfedge of it (the "canonical" direction)
  std::vector<face_descriptor> face;               ///< face index -> descriptor
  std::vector<Eigen::Vector3d> position;
  std::vector<std::array<int, 2>> edge_vertices;   ///< canonical direction: source, target
  std::vector<std::array<int, 2>> edge_faces;      ///< left (of canonical) and right face; border cycle k is nf + k
  std::vector<std::array<int, 3>> face_edges;      ///< the 3 edges of a triangle, in order
  std::vector<std::array<int, 3>> face_vertices;
  std::vector<std::vector<int>> border_cycles;     ///< edge indices of each border cycle, in order
  std::vector<bool> is_border_vertex;
  // Vertex adjacency in CSR form: neighbours of v are adjacency[offset[v] .. offset[v+1]).
  std::vector<int> offset, adjacent_vertex, adjacent_edge;

  int number_of_vertices() const { return int(vertex.size()); }
  /// Vertices with at least one edge: isolated ones are not part of the surface.
  int number_of_used_vertices() const
  {
    int n = 0;
    for(std::size_t v = 0; v + 1 < offset.size(); ++v) n += offset[v] < offset[v + 1];
    return n;
  }
  int number_of_edges() const { return int(edge_vertices.size()); }
  int number_of_faces() const { return int(face.size()); }
  /// Faces plus one "cap" node per border cycle: the dual graph of the capped surface.
  int number_of_dual_nodes() const { return int(face.size() + border_cycles.size()); }

  /// +1 when walking the edge from `from` follows its canonical direction, -1 otherwise.
  int direction(int e, int from) const { return edge_vertices[e][0] == from ? 1 : -1; }
  int other_vertex(int e, int v) const { return edge_vertices[e][0] == v ? edge_vertices[e][1] : edge_vertices[e][0]; }
  double length(int e) const { return (position[edge_vertices[e][0]] - position[edge_vertices[e][1]]).norm(); }

  template <class VertexPointMap>
  Mesh_graph(const TriangleMesh& tm, VertexPointMap vpm)
  {
    auto vim = CGAL::get_initialized_vertex_index_map(tm);
    auto him = CGAL::get_initialized_halfedge_index_map(tm);
    auto fim = CGAL::get_initialized_face_index_map(tm);
    const std::size_t nv = num_vertices(tm), nh = num_halfedges(tm), nf = num_faces(tm);
    vertex.resize(nv);
    position.resize(nv);
    for(vertex_descriptor v : vertices(tm)) {
      const std::size_t i = get(vim, v);
      vertex[i] = v;
      const auto& p = get(vpm, v);
      position[i] = Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
    face.resize(nf);
    for(face_descriptor f : faces(tm)) face[get(fim, f)] = f;

    std::vector<int> halfedge_edge(nh, -1);
    for(edge_descriptor ed : edges(tm)) {
      halfedge_descriptor h = halfedge(ed, tm);
      const int e = int(edge_halfedge.size());
      edge_halfedge.push_back(h);
      halfedge_edge[get(him, h)] = e;
      halfedge_edge[get(him, opposite(h, tm))] = e;
      edge_vertices.push_back({int(get(vim, source(h, tm))), int(get(vim, target(h, tm)))});
      edge_faces.push_back({-1, -1});
    }
    // Faces: the left face of the canonical halfedge is edge_faces[e][0].
    auto side_of = [&](halfedge_descriptor h) {
      const int e = halfedge_edge[get(him, h)];
      return std::make_pair(e, edge_halfedge[e] == h ? 0 : 1);
    };
    face_edges.resize(nf);
    face_vertices.resize(nf);
    for(std::size_t fi = 0; fi < nf; ++fi) {
      int k = 0;
      for(halfedge_descriptor h : halfedges_around_face(halfedge(face[fi], tm), tm)) {
        auto [e, side] = side_of(h);
        edge_faces[e][side] = int(fi);
        if(k < 3) {
          face_edges[fi][k] = e;
          face_vertices[fi][k] = int(get(vim, source(h, tm)));
        }
        ++k;
      }
    }
    // Border cycles become cap nodes numbered after the faces.
    is_border_vertex.assign(nv, false);
    std::vector<bool> seen(nh, false);
    for(halfedge_descriptor h : halfedges(tm)) {
      if(!is_border(h, tm) || seen[get(him, h)]) continue;
      const int cap = int(nf + border_cycles.size());
      border_cycles.emplace_back();
      for(halfedge_descriptor b : halfedges_around_face(h, tm)) {
        seen[get(him, b)] = true;
        auto [e, side] = side_of(b);
        edge_faces[e][side] = cap;
        border_cycles.back().push_back(e);
        is_border_vertex[get(vim, source(b, tm))] = true;
      }
    }
    // CSR adjacency.
    offset.assign(nv + 1, 0);
    for(const auto& ev : edge_vertices) { ++offset[ev[0] + 1]; ++offset[ev[1] + 1]; }
    for(std::size_t i = 0; i < nv; ++i) offset[i + 1] += offset[i];
    adjacent_vertex.resize(offset[nv]);
    adjacent_edge.resize(offset[nv]);
    std::vector<int> fill(offset.begin(), offset.end() - 1);
    for(int e = 0; e < number_of_edges(); ++e) {
      const int a = edge_vertices[e][0], b = edge_vertices[e][1];
      adjacent_vertex[fill[a]] = b; adjacent_edge[fill[a]++] = e;
      adjacent_vertex[fill[b]] = a; adjacent_edge[fill[b]++] = e;
    }
  }

  /// Edges of dual node `n` (a face or a cap), each with the sign of the node's boundary
  /// orientation relative to the edge's canonical direction.
  template <class F>
  void for_each_dual_boundary_edge(int n, F&& f) const
  {
    if(n < number_of_faces()) {
      for(int e : face_edges[n]) f(e, edge_faces[e][0] == n ? 1 : -1);
    } else {
      for(int e : border_cycles[n - number_of_faces()]) f(e, edge_faces[e][0] == n ? 1 : -1);
    }
  }

  /// Unit directions d_v maximising min_f d_v . n_f over the faces f incident to v
  /// (subgradient ascent from the angle-weighted normal). Where that minimum is positive
  /// (`clearance[v] > 0`), a point moved from v along d_v, or a segment between two such
  /// moved points of an edge, lies on the positive side of every incident face, hence off
  /// the surface locally. A vertex whose star admits no such direction gets clearance <= 0.
  std::vector<Eigen::Vector3d> vertex_push_directions(std::vector<double>& clearance) const
  {
    std::vector<Eigen::Vector3d> d = vertex_normals();
    std::vector<std::vector<Eigen::Vector3d>> incident(vertex.size());
    for(const auto& fv : face_vertices) {
      Eigen::Vector3d fn = (position[fv[1]] - position[fv[0]]).cross(position[fv[2]] - position[fv[0]]);
      if(fn.norm() == 0) continue;
      fn.normalize();
      for(int v : fv) incident[v].push_back(fn);
    }
    clearance.assign(vertex.size(), -1);
    auto worst_of = [&](std::size_t v, const Eigen::Vector3d& x) {
      const Eigen::Vector3d* worst = &incident[v][0];
      for(const auto& n : incident[v]) if(n.dot(x) < worst->dot(x)) worst = &n;
      return worst;
    };
    for(std::size_t v = 0; v < vertex.size(); ++v) {
      if(incident[v].empty()) continue;
      Eigen::Vector3d best = d[v], x = d[v];
      double best_value = worst_of(v, x)->dot(x);
      for(int it = 0; it < 200 && best_value < 0.2; ++it) {
        x = (x + (1.0 / (it + 2)) * *worst_of(v, x)).normalized();
        const double value = worst_of(v, x)->dot(x);
        if(value > best_value) { best_value = value; best = x; }
      }
      d[v] = best;
      clearance[v] = best_value;
    }
    return d;
  }

  /// Angle-weighted unit vertex normals (consistent with the face orientation).
  std::vector<Eigen::Vector3d> vertex_normals() const
  {
    std::vector<Eigen::Vector3d> n(vertex.size(), Eigen::Vector3d::Zero());
    for(const auto& fv : face_vertices) {
      const Eigen::Vector3d& a = position[fv[0]];
      const Eigen::Vector3d& b = position[fv[1]];
      const Eigen::Vector3d& c = position[fv[2]];
      Eigen::Vector3d fn = (b - a).cross(c - a);
      const double len = fn.norm();
      if(len == 0) continue;
      fn /= len;
      const Eigen::Vector3d* p[3] = {&a, &b, &c};
      for(int k = 0; k < 3; ++k) {
        Eigen::Vector3d u = *p[(k + 1) % 3] - *p[k], w = *p[(k + 2) % 3] - *p[k];
        const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
        n[fv[k]] += angle * fn;
      }
    }
    for(auto& x : n) { const double l = x.norm(); if(l > 0) x /= l; }
    return n;
  }

  /// Signed volume enclosed by the surface with each border cycle capped by a fan to its
  /// centroid: positive when the faces are oriented outwards.
  double capped_signed_volume() const
  {
    Eigen::Vector3d o = Eigen::Vector3d::Zero();
    for(const auto& p : position) o += p;
    o /= double(std::max<std::size_t>(1, position.size()));
    double vol = 0;
    auto tet = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
      vol += (a - o).dot((b - o).cross(c - o)) / 6.0;
    };
    for(const auto& fv : face_vertices) tet(position[fv[0]], position[fv[1]], position[fv[2]]);
    for(std::size_t k = 0; k < border_cycles.size(); ++k) {
      const int cap = int(face.size() + k);
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for(int e : border_cycles[k]) c += position[edge_vertices[e][0]];
      c /= double(border_cycles[k].size());
      for(int e : border_cycles[k]) {
        // Cap orientation follows the border halfedges: left side of the edge as the cap sees it.
        const bool canonical = edge_faces[e][0] == cap;
        const int a = canonical ? edge_vertices[e][0] : edge_vertices[e][1];
        const int b = canonical ? edge_vertices[e][1] : edge_vertices[e][0];
        tet(position[a], position[b], c);
      }
    }
    return vol;
  }
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
