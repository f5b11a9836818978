// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Exact insertion of points and straight segments of a piece's uv map into the mesh
// (§2.2.2.3: polyedges are straight lines of a parametric domain). Which triangle contains a
// point, which edge a segment leaves a triangle through and whether it passes exactly through
// a vertex are decided by the kernel's exact Orientation_2 on the uv coordinates; crossed edges
// are split at the crossing (3D and uv interpolated with the same parameter, so the surface
// never moves) and the mesh stays triangulated. A crossing very close to an edge end joins
// that vertex instead, to avoid slivers, unless the vertex belongs to an earlier path or is a
// node ("v:locked"; border vertices count as locked): paths then only meet where the layout
// graph says they do.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_SEGMENT_INSERTION_H
#define CGAL_POLYCUBE_IGA_INTERNAL_SEGMENT_INSERTION_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/internal/convex_embedding.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

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
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;

  Mesh& m;
  Uv_map<P> uv;
  Vertex_parent_map<P> vpar;
  Face_parent_map<P> fpar;
  typename Mesh::template Property_map<V, bool> locked;
  typename Mesh::template Property_map<typename Mesh::Edge_index, bool> locked_edge;

  explicit Segment_inserter(Mesh& mesh)
    : m(mesh), uv(uv_map(mesh)), vpar(vertex_parent_map(mesh)), fpar(face_parent_map(mesh)),
      locked(mesh.template add_property_map<V, bool>("v:locked", false).first),
      locked_edge(mesh.template add_property_map<typename Mesh::Edge_index, bool>("e:locked", false).first)
  {}

  K::Point_2 pt(V v) const { return K::Point_2(uv[v].x(), uv[v].y()); }
  bool is_locked(V v) const { return locked[v] || is_border(v, m); }

  /// Splits the edge of `h` at parameter t (from source to target) and re-triangulates
  /// both sides; returns the new vertex.
  V split(H h, double t)
  {
    const V a = source(h, m), b = target(h, m);
    const H o = opposite(h, m);
    const bool left = !is_border(h, m), right = !is_border(o, m);
    const F fl = left ? face(h, m) : F(), fr = right ? face(o, m) : F();
    const std::size_t pl = left ? fpar[fl] : no_parent, pr = right ? fpar[fr] : no_parent;
    const Eigen::Vector3d x = (1 - t) * point3(m, a) + t * point3(m, b);
    const Eigen::Vector2d u = (1 - t) * uv[a] + t * uv[b];
    const H hn = CGAL::Euler::split_edge(h, m); // hn: a -> new, next(hn) == h
    const V nv = target(hn, m);
    m.point(nv) = P(x.x(), x.y(), x.z());
    uv[nv] = u;
    vpar[nv] = no_parent;
    if(left) {
      const H g = CGAL::Euler::split_face(hn, next(h, m), m);
      fpar[face(g, m)] = pl;
      fpar[face(opposite(g, m), m)] = pl;
    }
    if(right) {
      const H on = opposite(hn, m); // new -> a
      const H g = CGAL::Euler::split_face(opposite(h, m), next(on, m), m);
      fpar[face(g, m)] = pr;
      fpar[face(opposite(g, m), m)] = pr;
    }
    if(locked_edge[edge(h, m)]) {
      locked_edge[edge(hn, m)] = true;
      locked[nv] = true;
    }
    return nv;
  }

  V insert_point(const Eigen::Vector2d& p, double snap)
  {
    const K::Point_2 q(p.x(), p.y());
    for(F f : faces(m)) {
      const H h0 = halfedge(f, m);
      const H hs[3] = {h0, next(h0, m), next(next(h0, m), m)};
      CGAL::Orientation o[3];
      bool inside = true;
      for(int k = 0; k < 3 && inside; ++k) {
        o[k] = CGAL::orientation(pt(source(hs[k], m)), pt(target(hs[k], m)), q);
        inside = o[k] != CGAL::RIGHT_TURN;
      }
      if(!inside) continue;
      double shortest = std::numeric_limits<double>::infinity();
      for(const H h : hs) shortest = std::min(shortest, (uv[target(h, m)] - uv[source(h, m)]).norm());
      // Exactly on, or within the snap distance of, an unlocked vertex.
      for(const H h : hs) {
        const V v = target(h, m);
        if(uv[v] == p || (!is_locked(v) && (uv[v] - p).norm() <= snap * shortest)) {
          locked[v] = true;
          return v;
        }
      }
      // On (or near) an interior edge: split it at the projection.
      for(int k = 0; k < 3; ++k) {
        const H h = hs[k];
        const Eigen::Vector2d a = uv[source(h, m)], b = uv[target(h, m)];
        const double len2 = (b - a).squaredNorm();
        const double t = std::clamp((p - a).dot(b - a) / len2, 0., 1.);
        const double d = (a + t * (b - a) - p).norm();
        if((o[k] == CGAL::COLLINEAR || d <= snap * shortest) && !is_border(edge(h, m), m) && !locked_edge[edge(h, m)]) {
          const V v = split(h, t);
          uv[v] = p;
          locked[v] = true;
          return v;
        }
      }
      // Strictly inside: a centre vertex, by barycentric interpolation.
      const V a = source(hs[0], m), b = target(hs[0], m), c = target(hs[1], m);
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

  static double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

  void lock_step(V a, V b)
  {
    locked[a] = locked[b] = true;
    locked_edge[edge(halfedge(a, b, m).first, m)] = true;
  }

  std::vector<V> insert_segment(V a, V b, double snap)
  {
    std::vector<V> path{a};
    locked[a] = true;
    const K::Point_2 B = pt(b);
    V cur = a;
    std::size_t guard = 0;
    while(cur != b) {
      if(++guard > 4 * num_halfedges(m) + 16) throw Internal_error("segment_crossing", "a layout segment does not reach its end");
      const auto direct = halfedge(cur, b, m);
      if(direct.second) {
        if(locked_edge[edge(direct.first, m)]) throw Internal_error("segment_crossing", "a layout segment runs along another one");
        lock_step(cur, b);
        path.push_back(b);
        break;
      }
      const K::Point_2 C = pt(cur);
      const Eigen::Vector2d dir = uv[b] - uv[cur];
      bool moved = false;
      for(const H h : halfedges_around_target(halfedge(cur, m), m)) {
        // Triangle (cur, p, q) counter-clockwise: h' = opposite(h) leaves cur.
        const H out = opposite(h, m);
        if(is_border(out, m)) continue;
        const V p = target(out, m), q = target(next(out, m), m);
        const CGAL::Orientation op = CGAL::orientation(C, B, pt(p)), oq = CGAL::orientation(C, B, pt(q));
        // Through a vertex exactly on the ray.
        for(const V w : {p, q}) {
          if((w == p ? op : oq) == CGAL::COLLINEAR && (uv[w] - uv[cur]).dot(dir) > 0) {
            if(w != b && is_locked(w)) throw Internal_error("segment_crossing", "a layout segment passes through a locked vertex");
            if(locked_edge[edge(halfedge(cur, w, m).first, m)]) throw Internal_error("segment_crossing", "a layout segment runs along another one");
            lock_step(cur, w);
            path.push_back(w);
            cur = w;
            moved = true;
            break;
          }
        }
        if(moved) break;
        // The ray leaves through the opposite edge (p, q): p right of it, q left.
        if(!(op == CGAL::RIGHT_TURN && oq == CGAL::LEFT_TURN)) continue;
        const H pq = next(out, m); // p -> q
        if(is_border(edge(pq, m), m)) throw Internal_error("segment_crossing", "a layout segment leaves its piece");
        const double dp = cross(uv[b] - uv[cur], uv[p] - uv[cur]), dq = cross(uv[b] - uv[cur], uv[q] - uv[cur]);
        const double t = dp / (dp - dq);
        const double len = (uv[q] - uv[p]).norm();
        V next_v;
        if(t * len <= snap * len && !is_locked(p)) next_v = p;
        else if((1 - t) * len <= snap * len && !is_locked(q)) next_v = q;
        else {
          if(locked_edge[edge(pq, m)]) throw Internal_error("segment_crossing", "a layout segment crosses another one");
          next_v = split(pq, std::clamp(t, 1e-9, 1 - 1e-9));
        }
        lock_step(cur, next_v);
        path.push_back(next_v);
        cur = next_v;
        moved = true;
        break;
      }
      if(!moved) throw Internal_error("segment_crossing", "a layout segment finds no triangle to enter");
    }
    return path;
  }
};

template <class P>
typename CGAL::Surface_mesh<P>::Vertex_index insert_point(CGAL::Surface_mesh<P>& piece, const Eigen::Vector2d& p, double snap = 1e-3)
{
  return Segment_inserter<P>(piece).insert_point(p, snap);
}

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
