// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Exact insertion of points and straight segments of a piece's uv map into the mesh
// (§2.2.2.3: polyedges are straight lines of a parametric domain). Which triangle contains a
// point, which edge a segment leaves a triangle through and whether it passes exactly through
// a vertex are decided by the kernel's exact Orientation_2 on the uv coordinates, always
// against the segment's own line (its two end vertices never move), so rounding in the
// vertices a walk creates never changes which triangles it crosses. Crossed edges are split
// at the crossing (3D and uv interpolated with the same parameter, so the surface never
// moves) and the mesh stays triangulated. A crossing very close to an edge end joins that
// vertex instead, to avoid slivers; the vertex's uv moves onto the segment (its 3D point
// stays) when its triangles stay positive. Vertices of earlier paths and nodes ("v:locked",
// edges "e:locked"; border vertices count as locked) never snap or move: paths only meet
// where the layout graph says they do.
//
// Reason codes: point_outside, point_on_border, point_on_path (insert_point);
// segment_crossing (insert_segment would cross, run along or pass through an earlier path,
// a locked vertex or the border). A failed call may leave the piece partly refined.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_SEGMENT_INSERTION_H
#define CGAL_POLYCUBE_IGA_INTERNAL_SEGMENT_INSERTION_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/internal/convex_embedding.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>

#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

template <class P>
struct Segment_inserter
{
  using Mesh = CGAL::Surface_mesh<P>;
  using V = typename Mesh::Vertex_index;
  using H = typename Mesh::Halfedge_index;
  using F = typename Mesh::Face_index;
  using E = typename Mesh::Edge_index;
  using Vec = Eigen::Vector2d;

  Mesh& m;
  Uv_map<P> uv;
  Vertex_parent_map<P> vpar;
  Face_parent_map<P> fpar;
  typename Mesh::template Property_map<V, bool> locked;
  typename Mesh::template Property_map<E, bool> locked_edge;

  explicit Segment_inserter(Mesh& mesh)
    : m(mesh), uv(uv_map(mesh)), vpar(vertex_parent_map(mesh)), fpar(face_parent_map(mesh)),
      locked(mesh.template add_property_map<V, bool>("v:locked", false).first),
      locked_edge(mesh.template add_property_map<E, bool>("e:locked", false).first)
  {}

  bool is_locked(V v) const { return locked[v] || m.is_border(v); }

  static double cross(const Vec& a, const Vec& b) { return a.x() * b.y() - a.y() * b.x(); }

  /// Whether every triangle around v stays positive with v at q, and not flat to within
  /// rounding: the sine of its angle at q above 1e-10. A snap that leaves a triangle positive
  /// by rounding alone (pipe.off scaled by 2: a corner a hair off the line a path snapped two
  /// vertices onto) is exactly the one refused when the corner lies on that line (pipe.off
  /// as read), so scaling the mesh does not change the decision; the triangle, flat in uv but
  /// not in 3D, would later stop a segment reaching the corner.
  bool star_positive_at(V v, const Vec& q) const
  {
    for(H h : halfedges_around_target(halfedge(v, m), m)) {
      if(is_border(h, m)) continue;
      // h: x -> v; the triangle is (v, a, x) counter-clockwise.
      const V a = target(next(h, m), m), x = source(h, m);
      if(uv_orientation(q, uv[a], uv[x]) != CGAL::LEFT_TURN) return false;
      const Vec qa = uv[a] - q, qx = uv[x] - q;
      if(!(cross(qa, qx) > 1e-10 * qa.norm() * qx.norm())) return false;
    }
    return true;
  }

  bool try_move(V v, const Vec& q)
  {
    if(uv[v] == q) return true;
    if(!star_positive_at(v, q)) return false;
    uv[v] = q;
    return true;
  }

  /// Splits the edge of h at parameter t, 3D and uv alike; returns the new vertex.
  V split(H h, double t)
  {
    const Vec x = (1 - t) * uv[source(h, m)] + t * uv[target(h, m)];
    const V nv = target(split_edge_at(m, h, t), m);
    uv[nv] = x;
    return nv;
  }

  V insert_point(const Vec& p, double snap)
  {
    if(!p.allFinite()) throw Internal_error("point_outside", "a layout node has no finite parametric position");
    for(F f : faces(m)) {
      const H h0 = halfedge(f, m);
      const std::array<H, 3> hs{{h0, next(h0, m), next(next(h0, m), m)}};
      std::array<CGAL::Orientation, 3> o;
      bool inside = uv_orientation(uv[source(h0, m)], uv[target(h0, m)], uv[target(hs[1], m)]) == CGAL::LEFT_TURN;
      for(int k = 0; k < 3 && inside; ++k) {
        o[std::size_t(k)] = uv_orientation(uv[source(hs[std::size_t(k)], m)], uv[target(hs[std::size_t(k)], m)], p);
        inside = o[std::size_t(k)] != CGAL::RIGHT_TURN;
      }
      if(!inside) continue;
      for(const H h : hs)
        if(uv[target(h, m)] == p) {
          locked[target(h, m)] = true;
          return target(h, m);
        }
      double shortest = std::numeric_limits<double>::infinity();
      for(const H h : hs) shortest = std::min(shortest, (uv[target(h, m)] - uv[source(h, m)]).norm());
      const double reach = snap * shortest;
      // The nearest unlocked vertex within reach joins, moved onto p if its triangles allow.
      V near;
      double nd = std::numeric_limits<double>::infinity();
      for(const H h : hs) {
        const V v = target(h, m);
        const double d = (uv[v] - p).norm();
        if(!is_locked(v) && d <= reach && d < nd) {
          nd = d;
          near = v;
        }
      }
      if(near != V()) {
        try_move(near, p);
        locked[near] = true;
        return near;
      }
      // Exactly on an edge: split it there.
      for(std::size_t k = 0; k < 3; ++k) {
        if(o[k] != CGAL::COLLINEAR) continue;
        const H h = hs[k];
        if(is_border(edge(h, m), m)) throw Internal_error("point_on_border", "a layout node falls on the border of its piece between two border vertices");
        if(locked_edge[edge(h, m)]) throw Internal_error("point_on_path", "a layout node falls on a path inserted before");
        const Vec a = uv[source(h, m)], b = uv[target(h, m)];
        const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0., 1.);
        const V v = split(h, t);
        uv[v] = p; // exactly on the edge, strictly between its ends: every triangle stays positive
        locked[v] = true;
        return v;
      }
      // Within reach of an interior edge: split it at the projection, then move onto p.
      std::size_t best = 3;
      double bd = std::numeric_limits<double>::infinity(), bt = 0.;
      for(std::size_t k = 0; k < 3; ++k) {
        const H h = hs[k];
        if(is_border(edge(h, m), m) || locked_edge[edge(h, m)]) continue;
        const Vec a = uv[source(h, m)], b = uv[target(h, m)];
        const double t = (p - a).dot(b - a) / (b - a).squaredNorm();
        if(!(t > 0 && t < 1)) continue;
        const double d = std::abs(cross(b - a, p - a)) / (b - a).norm();
        if(d <= reach && d < bd) {
          bd = d;
          bt = t;
          best = k;
        }
      }
      if(best < 3) {
        const V v = split(hs[best], bt);
        try_move(v, p);
        locked[v] = true;
        return v;
      }
      // Strictly inside: a centre vertex, 3D by barycentric interpolation.
      const V a = source(h0, m), b = target(h0, m), c = target(hs[1], m);
      const double area = cross(uv[b] - uv[a], uv[c] - uv[a]);
      const double la = cross(uv[b] - p, uv[c] - p) / area, lb = cross(uv[c] - p, uv[a] - p) / area, lc = 1 - la - lb;
      const Eigen::Vector3d x = la * point3(m, a) + lb * point3(m, b) + lc * point3(m, c);
      const std::size_t pf = fpar[f];
      const H hn = CGAL::Euler::add_center_vertex(h0, m);
      const V v = target(hn, m);
      m.point(v) = P(x.x(), x.y(), x.z());
      uv[v] = p;
      vpar[v] = no_parent;
      locked[v] = true;
      for(const H g : halfedges_around_target(hn, m))
        if(!is_border(g, m)) fpar[face(g, m)] = pf;
      return v;
    }
    throw Internal_error("point_outside", "a layout node falls outside its piece's parametric domain");
  }

  std::vector<V> insert_segment(V a, V b, double snap)
  {
    std::vector<V> path{a};
    locked[a] = locked[b] = true;
    if(a == b) return path;
    const Vec A = uv[a], B = uv[b], D = B - A;
    auto side = [&](V v) { return uv_orientation(A, B, uv[v]); };
    auto ahead = [&](const Vec& x) { return (x - A).dot(D); };
    auto step = [&](V from, V to) {
      const auto he = halfedge(from, to, m);
      if(!he.second) throw Internal_error("segment_crossing", "a layout path step is not a mesh edge");
      locked_edge[edge(he.first, m)] = true;
      locked[to] = true;
      path.push_back(to);
    };
    const std::size_t limit = 4 * (num_faces(m) + num_vertices(m)) + 16;
    std::size_t guard = 0;
    V cur = a;
    while(cur != b) {
      // At a vertex on the line (exactly, or moved onto it by a snap): leave it forward,
      // through a vertex on the line or across the opposite edge of a triangle around it.
      const double s_cur = ahead(uv[cur]);
      V via;
      H across;
      double best = std::numeric_limits<double>::infinity();
      for(const H h : halfedges_around_target(halfedge(cur, m), m)) {
        if(is_border(h, m)) continue;
        // h: w -> cur; triangle (cur, u, w) counter-clockwise; g = u -> w.
        const V u = target(next(h, m), m), w = source(h, m);
        const CGAL::Orientation su = side(u), sw = side(w);
        for(const auto& [x, sx] : {std::make_pair(u, su), std::make_pair(w, sw)}) {
          const double s = ahead(uv[x]);
          if(sx == CGAL::COLLINEAR && s > s_cur && s < best) {
            best = s;
            via = x;
            across = H();
          }
        }
        if(su == CGAL::RIGHT_TURN && sw == CGAL::LEFT_TURN) {
          const double du = cross(D, uv[u] - A), dw = cross(D, uv[w] - A);
          const double t = std::clamp(du / (du - dw), 0., 1.);
          const double s = ahead((1 - t) * uv[u] + t * uv[w]);
          if(s > s_cur && s < best) {
            best = s;
            via = V();
            across = next(next(h, m), m);
          }
        }
      }
      if(via != V()) {
        if(locked_edge[edge(halfedge(cur, via, m).first, m)]) throw Internal_error("segment_crossing", "a layout segment runs along a path inserted before");
        if(via != b && is_locked(via)) throw Internal_error("segment_crossing", "a layout segment passes through a locked vertex");
        step(cur, via);
        cur = via;
        if(++guard > limit) throw Internal_error("segment_crossing", "a layout segment does not reach its end");
        continue;
      }
      if(across == H()) throw Internal_error("segment_crossing", "a layout segment finds no triangle to enter");
      // Across edges: g = u -> w with u right and w left of the line, the triangle on its left
      // holding the previous path vertex.
      H g = across;
      V prev = cur;
      while(true) {
        if(++guard > limit) throw Internal_error("segment_crossing", "a layout segment does not reach its end");
        const V u = source(g, m), w = target(g, m);
        if(locked_edge[edge(g, m)]) throw Internal_error("segment_crossing", "a layout segment crosses a path inserted before");
        const double du = cross(D, uv[u] - A), dw = cross(D, uv[w] - A);
        const double t = std::clamp(du / (du - dw), 0., 1.);
        const Vec X = (1 - t) * uv[u] + t * uv[w];
        if(t <= snap && !is_locked(u) && try_move(u, X)) {
          step(prev, u);
          cur = u;
          break;
        }
        if(1 - t <= snap && !is_locked(w) && try_move(w, X)) {
          step(prev, w);
          cur = w;
          break;
        }
        const H o = opposite(g, m);
        if(is_border(o, m)) throw Internal_error("segment_crossing", "a layout segment would split a border edge");
        // Far triangle (w, u, r): o = w -> u, then u -> r, r -> w.
        const H ur = next(o, m), rw = next(ur, m);
        const V r = target(ur, m);
        const CGAL::Orientation sr = side(r);
        if(sr == CGAL::COLLINEAR && r != b && is_locked(r)) throw Internal_error("segment_crossing", "a layout segment passes through a locked vertex");
        // The four triangles around the crossing must be positive: they are unless the line
        // passes within rounding of a vertex that cannot snap.
        const V c = target(next(g, m), m);
        if(uv_orientation(uv[u], X, uv[c]) != CGAL::LEFT_TURN || uv_orientation(X, uv[w], uv[c]) != CGAL::LEFT_TURN ||
           uv_orientation(uv[w], X, uv[r]) != CGAL::LEFT_TURN || uv_orientation(X, uv[u], uv[r]) != CGAL::LEFT_TURN)
          throw Internal_error("segment_crossing", "a layout segment passes within rounding of a locked vertex");
        const V x = split(g, t);
        uv[x] = X;
        step(prev, x);
        if(sr == CGAL::COLLINEAR) { // r == b or an unlocked vertex exactly on the segment
          step(x, r);
          cur = r;
          break;
        }
        g = sr == CGAL::RIGHT_TURN ? rw : ur;
        prev = x;
      }
    }
    return path;
  }
};

/// Inserts the uv point p: an existing vertex if p is on it or within `snap` (relative to the
/// shortest edge of the containing triangle) of an unlocked one (moved onto p when its
/// triangles stay positive); else splits an edge p is exactly on, or an interior unlocked
/// edge within the snap distance (the new vertex moved onto p likewise); else splits the
/// containing triangle into three, 3D by barycentric interpolation. The vertex is locked.
/// Throws Internal_error("point_outside") if p is in no triangle, ("point_on_border") if it
/// lies exactly on a border edge, ("point_on_path") if exactly on an earlier path's edge.
template <class P>
typename CGAL::Surface_mesh<P>::Vertex_index insert_point(CGAL::Surface_mesh<P>& piece, const Eigen::Vector2d& p, double snap = 1e-3)
{
  return Segment_inserter<P>(piece).insert_point(p, snap);
}

/// Inserts the straight uv segment from a to b and returns the vertex path a..b along mesh
/// edges (locked, with its edges). See the file comment; throws Internal_error
/// ("segment_crossing") when it would cross, run along or pass through an earlier path or a
/// locked vertex, or split a border edge.
template <class P>
std::vector<typename CGAL::Surface_mesh<P>::Vertex_index> insert_segment(CGAL::Surface_mesh<P>& piece,
                                                                         typename CGAL::Surface_mesh<P>::Vertex_index a,
                                                                         typename CGAL::Surface_mesh<P>::Vertex_index b,
                                                                         double snap = 1e-3)
{
  return Segment_inserter<P>(piece).insert_segment(a, b, snap);
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_SEGMENT_INSERTION_H
