// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Arc relaxation: an arc between two surface patches traced anew as the middle of their
// union, so that it leaves its nodes halfway between the arcs beside it.
//
// The pants path traces its polyedges as straight lines in per-cuboid parameterizations
// (§2.2.2, Step 3) that know nothing of each other, and where they meet a cycle at a small
// angle a patch gets a sliver corner (anchor.off: 57 corners under 25 degrees of 360), on
// which no fitted face keeps its det J positive. The union of the two patches beside an
// arc is a disk whose border holds the arc's two nodes; a harmonic function that is 0 on
// one patch's other three arcs and 1 on the other's leaves each node along the bisector of
// the union's angle there (near a border point where the data jump, a harmonic function
// grows with the polar angle), and its level 1/2 runs between the two sides in the
// middle. The level is inserted into the mesh (the edges it crosses are split where it
// crosses them, so the surface does not move and the arc is as smooth as the function),
// and the new arc kept only when the four corners at its ends come nearer right angles.
// Nodes, patch corners, cuboids and interfaces do not change: only the arc's vertices and
// the two patches' face sets, so the layout stays valid.

#ifndef CGAL_POLYCUBE_IGA_LAYOUT_ARC_RELAXATION_H
#define CGAL_POLYCUBE_IGA_LAYOUT_ARC_RELAXATION_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/internal/cotangent_laplacian.h>
#include <CGAL/Polycube_IGA/internal/layout_corner_angles.h>
#include <CGAL/Polycube_IGA/internal/layout_sweeps.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>
#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>

#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// What relax_layout_arcs() did.
struct Arc_relaxation_result
{
  std::size_t arcs_moved = 0; ///< arc re-tracings kept, over all sweeps
  int sweeps = 0;             ///< sweeps run (the last one moved no arc, or the limit was reached)
  /// Sum over the corners at the moved arcs' ends of (angle - 90)^2, before and after.
  double squared_deviation_before = 0., squared_deviation_after = 0.;
};

namespace internal {

/// The two SURFACE patches beside each arc and the arc's place in them ({patch, side}), or
/// fewer when the arc borders a cap or the mesh's border.
template <class Point_3>
std::vector<std::vector<std::array<std::size_t, 2>>> surface_sides_of_arcs(const Polycube_layout<Point_3>& L)
{
  std::vector<std::vector<std::array<std::size_t, 2>>> sides(L.arcs.size());
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    if(L.patches[p].kind == Polycube_layout<Point_3>::SURFACE)
      for(std::size_t i = 0; i < 4; ++i) sides[L.patches[p].arcs[i]].push_back({{p, i}});
  return sides;
}

/// One arc re-traced through the union of its two patches (see the file comment). Returns
/// false when the union is not a disk bounded by the patches' other arcs, when the level
/// 1/2 is not one path between the arc's nodes, or when the corners at the arc's ends do not
/// come nearer right angles. The mesh may be refined all the same (the level's edges are
/// split, which moves no point of the surface); the old arc and patches then follow it.
template <class Point_3>
bool relax_arc(Polycube_layout<Point_3>& L, std::size_t a, const std::array<std::size_t, 2>& side_a,
               const std::array<std::size_t, 2>& side_b, Arc_relaxation_result& result)
{
  using Layout = Polycube_layout<Point_3>;
  using Mesh = typename Layout::Mesh;
  using V = typename Layout::vertex_descriptor;
  using F = typename Layout::face_descriptor;
  using H = typename Mesh::Halfedge_index;
  Mesh& m = L.mesh;
  const std::size_t pa = side_a[0], pb = side_b[0];
  if(pa == pb) return false;
  // The two patches must share this arc only: otherwise their union is not a disk.
  for(std::size_t i = 0; i < 4; ++i)
    for(std::size_t j = 0; j < 4; ++j)
      if(L.patches[pa].arcs[i] == L.patches[pb].arcs[j] && L.patches[pa].arcs[i] != a) return false;
  // Kept only if the four corners at the arc's ends come nearer right angles (their summed
  // squared deviation from 90 degrees); arcs whose corners are all within 10 degrees of
  // it are left alone (a box's edges).
  std::vector<std::array<std::size_t, 2>> end_corners;
  for(const auto& side : {side_a, side_b})
    for(std::size_t c : {side[1], (side[1] + 1) % 4}) end_corners.push_back({{side[0], c}});
  double largest = 0.;
  const double before = squared_corner_deviation(L, end_corners, &largest);
  if(largest <= 10.) return false;
  std::vector<signed char> in_union(num_faces(m), 0);
  for(F f : L.patches[pa].faces) in_union[std::size_t(f)] = 1;
  for(F f : L.patches[pb].faces) in_union[std::size_t(f)] = 1;
  auto inside = [&](H h) { return !is_border(h, m) && in_union[std::size_t(face(h, m))]; };
  auto edge_inside = [&](H h) { return inside(h) && inside(opposite(h, m)); };
  // Border values: 0 on patch a's other arcs, 1 on patch b's, 1/2 at the arc's nodes. The
  // border's halfedges whose faces are in the union seed the two sides' flood fills.
  std::vector<double> value(num_vertices(m), std::numeric_limits<double>::quiet_NaN());
  std::set<std::size_t> border_edges;
  std::vector<std::vector<H>> seeds(2);
  for(int s = 0; s < 2; ++s) {
    const std::size_t p = s == 0 ? pa : pb;
    for(std::size_t i = 0; i < 4; ++i) {
      const std::size_t b = L.patches[p].arcs[i];
      if(b == a) continue;
      const auto& vs = L.arcs[b].vertices;
      for(std::size_t k = 0; k < vs.size(); ++k) {
        value[std::size_t(vs[k])] = double(s);
        if(k == 0) continue;
        const auto h = halfedge(vs[k - 1], vs[k], m);
        if(!h.second) return false;
        border_edges.insert(std::size_t(edge(h.first, m)));
        for(H g : {h.first, opposite(h.first, m)})
          if(inside(g)) seeds[std::size_t(s)].push_back(g);
      }
    }
  }
  const V from = L.nodes[L.arcs[a].nodes[0]], to = L.nodes[L.arcs[a].nodes[1]];
  value[std::size_t(from)] = value[std::size_t(to)] = 0.5;
  // Inner vertices: those of the union's faces not on its border; all their faces must be
  // in the union.
  std::vector<V> inner;
  std::vector<int> inner_index(num_vertices(m), -1);
  for(std::size_t p : {pa, pb})
    for(F f : L.patches[p].faces)
      for(V v : vertices_around_face(halfedge(f, m), m))
        if(std::isnan(value[std::size_t(v)]) && inner_index[std::size_t(v)] < 0) {
          inner_index[std::size_t(v)] = int(inner.size());
          inner.push_back(v);
        }
  if(inner.empty()) return false;
  for(V v : inner)
    for(H h : halfedges_around_target(v, m))
      if(!edge_inside(h)) return false;
  // The harmonic function: clamped cotangent weights (an M-matrix: no overshoot, so each
  // side of the level 1/2 is one piece that touches its own arcs).
  auto position = [&](V v) { return to_eigen_point(m.point(v)); };
  std::map<std::size_t, double> weight; // by edge index
  for(std::size_t p : {pa, pb})
    for(F f : L.patches[p].faces) {
      const H h0 = halfedge(f, m);
      for(H h : {h0, next(h0, m), prev(h0, m)}) // edge h, the angle opposite it at target(next(h))
        weight[std::size_t(edge(h, m))] += 0.5 * bounded_cotangent(position(target(next(h, m), m)), position(source(h, m)),
                                                                     position(target(h, m)), 1e5);
    }
  Harmonic_extension system(inner.size());
  for(std::size_t i = 0; i < inner.size(); ++i)
    for(H h : halfedges_around_target(inner[i], m)) {
      const V w = source(h, m);
      system.add_edge(int(i), inner_index[std::size_t(w)], weight[std::size_t(edge(h, m))], value[std::size_t(w)]);
    }
  const Eigen::VectorXd x = system.solve("harmonic function of two layout patches");
  for(std::size_t i = 0; i < inner.size(); ++i) value[std::size_t(inner[i])] = x(Eigen::Index(i));

  // An inner vertex within a tenth of an edge of the level joins it (no sliver triangles),
  // then every edge the level crosses is split there (the surface does not move).
  auto crossing = [&](H h) { // parameter from source(h), or -1
    const double u = value[std::size_t(source(h, m))] - 0.5, w = value[std::size_t(target(h, m))] - 0.5;
    return (u < 0. && w > 0.) || (u > 0. && w < 0.) ? u / (u - w) : -1.;
  };
  for(V v : inner)
    for(H h : halfedges_around_source(v, m)) {
      const double t = crossing(h);
      if(t >= 0. && t < 0.1) {
        value[std::size_t(v)] = 0.5;
        break;
      }
    }
  std::vector<std::pair<std::array<V, 2>, double>> splits;
  std::set<std::size_t> seen;
  for(std::size_t p : {pa, pb})
    for(F f : L.patches[p].faces)
      for(H h : halfedges_around_face(halfedge(f, m), m)) {
        const double t = crossing(h);
        if(t >= 0. && edge_inside(h) && seen.insert(std::size_t(edge(h, m))).second) splits.push_back({{{source(h, m), target(h, m)}}, t});
      }
  std::map<std::pair<V, V>, V> split_vertex;
  value.resize(num_vertices(m) + splits.size(), std::numeric_limits<double>::quiet_NaN()); // a vertex per split
  for(const auto& sp : splits) {
    const H h = halfedge(sp.first[0], sp.first[1], m).first;
    const V n = target(split_edge_at(m, h, sp.second), m);
    split_vertex[{sp.first[0], sp.first[1]}] = split_vertex[{sp.first[1], sp.first[0]}] = n;
    value[std::size_t(n)] = 0.5;
  }
  in_union.resize(num_faces(m), 1); // the new faces were cut from the union's
  // The old arc through the split edges' new vertices.
  std::vector<V> old_path;
  for(std::size_t k = 0; k < L.arcs[a].vertices.size(); ++k) {
    if(k > 0)
      if(auto it = split_vertex.find({L.arcs[a].vertices[k - 1], L.arcs[a].vertices[k]}); it != split_vertex.end()) old_path.push_back(it->second);
    old_path.push_back(L.arcs[a].vertices[k]);
  }

  // The two sides of `path` in the union: flood fills from each side's border arcs that
  // cross neither the border nor the path. Empty when a side is empty or they meet.
  const std::size_t total = L.patches[pa].faces.size() + L.patches[pb].faces.size() + 2 * splits.size();
  auto sides_of = [&](const std::vector<V>& path) {
    std::set<std::size_t> barrier = border_edges;
    for(std::size_t k = 1; k < path.size(); ++k) barrier.insert(std::size_t(edge(halfedge(path[k - 1], path[k], m).first, m)));
    return faces_between_barriers(m, seeds, barrier, total);
  };
  auto restore_old = [&] {
    auto faces = sides_of(old_path);
    if(faces.empty()) throw Internal_error("invalid_layout", "the arc relaxation lost patches " + std::to_string(pa) + " and " + std::to_string(pb));
    L.arcs[a].vertices = old_path;
    L.patches[pa].faces = std::move(faces[0]);
    L.patches[pb].faces = std::move(faces[1]);
    return false;
  };

  // The level 1/2 from one node to the other: each of its vertices but the last has one
  // level edge inside the union it has not come by.
  std::vector<V> path{from};
  std::set<V> visited{from};
  while(path.back() != to) {
    V next_vertex = path.back();
    int found = 0;
    for(H h : halfedges_around_source(path.back(), m)) {
      const V w = target(h, m);
      if(!(value[std::size_t(w)] == 0.5) || !edge_inside(h) || (path.size() > 1 && w == path[path.size() - 2])) continue;
      next_vertex = w;
      ++found;
    }
    if(found != 1 || !visited.insert(next_vertex).second) return restore_old();
    path.push_back(next_vertex);
  }
  if(path == old_path) return restore_old();
  auto faces = sides_of(path);
  if(faces.empty()) return restore_old();

  L.arcs[a].vertices = path;
  L.patches[pa].faces = std::move(faces[0]);
  L.patches[pb].faces = std::move(faces[1]);
  const double after = squared_corner_deviation(L, end_corners);
  if(!(after < 0.99 * before)) return restore_old();
  result.squared_deviation_before += before;
  result.squared_deviation_after += after;
  return true;
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// Re-traces the layout's arcs between two surface patches as the middle of the patches'
/// union (see the file comment), in arc order, for up to `sweeps` sweeps or until a sweep
/// moves none. Arcs on a cap's or the mesh's border, and arcs whose two patches share
/// another arc, stay. The result is valid whenever `L` was (checked: throws
/// Internal_error("invalid_layout") otherwise). Deterministic.
template <class Point_3>
Arc_relaxation_result relax_layout_arcs(Polycube_layout<Point_3>& L, int sweeps = 3)
{
  Arc_relaxation_result result;
  const auto sides = internal::surface_sides_of_arcs(L);
  std::tie(result.arcs_moved, result.sweeps) = internal::sweep_layout(L, sweeps, L.arcs.size(), "arc relaxation", [&](std::size_t a) {
    return sides[a].size() == 2 && internal::relax_arc(L, a, sides[a][0], sides[a][1], result);
  });
  return result;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_LAYOUT_ARC_RELAXATION_H
