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

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
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

/// The number of `sharp` edges (per edge) at each vertex.
template <class Mesh>
std::vector<std::size_t> sharp_degrees(const Mesh& m, const std::vector<bool>& sharp)
{
  std::vector<std::size_t> degree(num_vertices(m), 0);
  for(auto e : edges(m))
    if(sharp[std::size_t(e)]) {
      ++degree[std::size_t(source(halfedge(e, m), m))];
      ++degree[std::size_t(target(halfedge(e, m), m))];
    }
  return degree;
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
  fc.sharp_degree = sharp_degrees(m, sharp);
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

/// Where a point of the mesh lies on its creases (Crease_network::locate()).
struct Crease_position
{
  enum Kind { off, on_edge, at_corner } kind = off;
  std::size_t edge = 0; ///< with on_edge: the sharp edge (by index) holding the point
};

/// The sharp edges of a mesh as paths a point can slide along (the grid relaxation's). A
/// path runs through vertices with two sharp edges and ends at the others (corners: a
/// box's, or where a crease ends). A path of fewer than `shortest` edges with a loose end
/// (a vertex with one sharp edge) is not a crease but noise: a scanned surface's odd sharp
/// edge; between two corners it is one (a coarse box's edge).
template <class Mesh>
class Crease_network
{
public:
  Crease_network(const Mesh& m, double angle_degrees, std::size_t shortest = 3)
    : m_(m), sharp_(sharp_edges(m, angle_degrees)), degree_(sharp_degrees(m, sharp_)), keep_(num_edges(m), false), ends_(num_edges(m))
  {
    for(auto e : edges(m)) ends_[std::size_t(e)] = {source(halfedge(e, m), m), target(halfedge(e, m), m)};
    // Path lengths: each path walked once from its lowest edge index, in index order.
    std::vector<bool> seen(num_edges(m), false);
    for(auto e : edges(m)) {
      if(!sharp_[std::size_t(e)] || seen[std::size_t(e)]) continue;
      std::vector<std::size_t> path;
      std::vector<std::size_t> todo{std::size_t(e)};
      seen[std::size_t(e)] = true;
      bool loose = false;
      while(!todo.empty()) {
        const std::size_t f = todo.back();
        todo.pop_back();
        path.push_back(f);
        loose = loose || degree_[std::size_t(ends_[f].first)] == 1 || degree_[std::size_t(ends_[f].second)] == 1;
        for(std::size_t g : next_edges(f))
          if(!seen[g]) seen[g] = true, todo.push_back(g);
      }
      if(path.size() >= shortest || !loose)
        for(std::size_t f : path) keep_[f] = true;
    }
  }

  /// Whether `p`, a point of face `f` (index), lies on a crease: on one of the face's kept
  /// sharp edges, or at a corner of the creases, within `tolerance`.
  Crease_position locate(const Eigen::Vector3d& p, std::size_t f, double tolerance) const
  {
    Crease_position r;
    for(auto h : halfedges_around_face(halfedge(face_descriptor(f), m_), m_)) {
      const std::size_t e = std::size_t(edge(h, m_));
      if(!keep_[e]) continue;
      const auto [a, b] = ends(e);
      const Eigen::Vector3d q = project_on_segment(p, point(a), point(b), 0, 1, 0).point;
      if((q - p).norm() > tolerance) continue;
      for(auto v : {a, b})
        if((point(v) - p).norm() <= tolerance && degree_[std::size_t(v)] != 2) return {Crease_position::at_corner, e};
      if(r.kind == Crease_position::off) r = {Crease_position::on_edge, e};
    }
    return r;
  }

  /// The point nearest `target` on the crease path through `*edge`, within `reach` edges of
  /// it either way; `*edge` becomes the edge holding it (the first found of equals).
  Eigen::Vector3d slide(const Eigen::Vector3d& target, std::size_t* edge, std::size_t reach = 64) const
  {
    // A path is a chain (its inner vertices have two sharp edges): walk it from both ends of
    // *edge in lockstep, end a's step first, and stop a walk at a corner or where it meets
    // the other on a closed path. Equals keep the first found.
    const std::size_t start = *edge;
    const auto [a0, b0] = ends(start);
    Eigen::Vector3d best = project_on_segment(target, point(a0), point(b0), 0, 1, 0).point;
    double d = (best - target).squaredNorm();
    struct Walk { std::size_t edge; vertex_descriptor far; bool on; };
    Walk w[2] = {{start, a0, true}, {start, b0, true}};
    for(std::size_t k = 0; k < reach && (w[0].on || w[1].on); ++k)
      for(int s = 0; s < 2; ++s) {
        Walk& x = w[s];
        if(!x.on) continue;
        const std::size_t g = continuation(x.edge, x.far);
        if(g == x.edge || g == w[1 - s].edge) { // a corner, or the other walk's edge
          x.on = false;
          continue;
        }
        const auto [a, b] = ends(g);
        x.edge = g;
        x.far = a == x.far ? b : a;
        const Eigen::Vector3d q = project_on_segment(target, point(a), point(b), 0, 1, 0).point;
        if((q - target).squaredNorm() < d) d = (q - target).squaredNorm(), best = q, *edge = g;
      }
    return best;
  }

private:
  using vertex_descriptor = typename boost::graph_traits<Mesh>::vertex_descriptor;
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;

  std::pair<vertex_descriptor, vertex_descriptor> ends(std::size_t e) const { return ends_[e]; }
  Eigen::Vector3d point(vertex_descriptor v) const
  {
    const auto& q = get(CGAL::vertex_point, m_, v);
    return Eigen::Vector3d(CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z()));
  }
  /// The sharp edge other than `e` at `v` if v has two, else `e` (v is a corner).
  std::size_t continuation(std::size_t e, vertex_descriptor v) const
  {
    if(degree_[std::size_t(v)] != 2) return e;
    for(auto h : halfedges_around_source(v, m_)) {
      const std::size_t g = std::size_t(edge(h, m_));
      if(g != e && sharp_[g]) return g;
    }
    return e;
  }
  /// The sharp edges that continue the path of sharp edge e at its ends (not past corners).
  std::vector<std::size_t> next_edges(std::size_t e) const
  {
    std::vector<std::size_t> r;
    const auto [a, b] = ends(e);
    for(auto v : {a, b})
      if(const std::size_t g = continuation(e, v); g != e) r.push_back(g);
    return r;
  }

  const Mesh& m_;
  std::vector<bool> sharp_;
  std::vector<std::size_t> degree_;
  std::vector<bool> keep_;
  std::vector<std::pair<vertex_descriptor, vertex_descriptor>> ends_;
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_FEATURE_CURVES_H
