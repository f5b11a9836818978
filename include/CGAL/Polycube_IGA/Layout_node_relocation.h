// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Node relocation: a layout node moved inside the union of its patches, to where the
// corners around it come nearer right angles, and its arcs traced anew as straight lines
// of a convex map of that union.
//
// Arc relaxation (Layout_arc_relaxation.h) moves arcs between fixed nodes; a node that the
// pants path left where its patches cannot all have sane corners stays bad (a valence-3
// node on a flat side, with corners of 165, 150 and 45 degrees). The reference moves the nodes too, after its global parameterization (§3.3, after [Cam14]);
// this is the same step for the baseline layout, with the corner angles as the measure.
//
// The union of the k patches around a node is a disk whose border is their 2k arcs away
// from the node, and whose inside holds the node and its k arcs ("spokes"). A Tutte map
// onto the unit circle (convex_embedding.h: positive weights, so one-to-one) turns every
// straight segment from an inner point to a border point into a simple path that meets
// the other segments from that point only there. Each inner vertex is a candidate; its
// corners (at the node, and where its spokes end) are estimated from the map, and the best
// one's spokes are inserted into the mesh (edges split where a segment crosses them: the
// surface does not move). The move is kept only when the corners, measured on the mesh as
// surface_corner_angle() measures them, come nearer right angles; otherwise the old arcs
// are put back (through the new split vertices). Nodes, arcs and patches keep their
// indices, cuboids and interfaces do not change: the layout stays valid.

#ifndef CGAL_POLYCUBE_IGA_LAYOUT_NODE_RELOCATION_H
#define CGAL_POLYCUBE_IGA_LAYOUT_NODE_RELOCATION_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/internal/convex_embedding.h>
#include <CGAL/Polycube_IGA/internal/layout_corner_angles.h>
#include <CGAL/Polycube_IGA/internal/layout_sweeps.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// What relocate_layout_nodes() did.
struct Node_relocation_result
{
  std::size_t nodes_moved = 0; ///< relocations kept, over all sweeps
  int sweeps = 0;              ///< sweeps run (the last one moved no node, or the limit was reached)
  /// Sum over the corners around the moved nodes and at their arcs' other ends of
  /// (angle - 90)^2, before and after.
  double squared_deviation_before = 0., squared_deviation_after = 0.;
};

namespace internal {

/// Point location in a piece's uv map (a bucket grid over the unit disk), and the 3D point
/// at a uv position by barycentric interpolation.
template <class P>
class Uv_locator
{
  using Mesh = CGAL::Surface_mesh<P>;
  using F = typename Mesh::Face_index;

public:
  Uv_locator(const Mesh& piece, const Uv_map<P>& uv) : m_(piece), uv_(uv)
  {
    n_ = std::max(1, int(std::sqrt(double(num_faces(piece)))));
    cells_.resize(std::size_t(n_ * n_));
    for(F f : faces(piece)) {
      Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
      for(auto v : vertices_around_face(halfedge(f, piece), piece)) {
        lo = lo.cwiseMin(uv[v]);
        hi = hi.cwiseMax(uv[v]);
      }
      const std::array<int, 2> a = cell(lo), b = cell(hi);
      for(int j = a[1]; j <= b[1]; ++j)
        for(int i = a[0]; i <= b[0]; ++i) cells_[std::size_t(j * n_ + i)].push_back(f);
    }
  }

  /// The 3D point at uv position q, or nothing when q is in no triangle.
  bool point_at(const Eigen::Vector2d& q, Eigen::Vector3d& out) const
  {
    const std::array<int, 2> c = cell(q);
    for(F f : cells_[std::size_t(c[1] * n_ + c[0])]) {
      std::array<typename Mesh::Vertex_index, 3> t;
      int k = 0;
      for(auto v : vertices_around_face(halfedge(f, m_), m_)) t[std::size_t(k++)] = v;
      const Eigen::Vector2d a = uv_[t[0]], b = uv_[t[1]], d = uv_[t[2]];
      const double area = cross(b - a, d - a);
      if(!(std::abs(area) > 0.)) continue;
      const double l1 = cross(q - a, d - a) / area, l2 = cross(b - a, q - a) / area, l0 = 1. - l1 - l2;
      const double eps = -1e-9;
      if(l0 < eps || l1 < eps || l2 < eps) continue;
      out = l0 * point3(m_, t[0]) + l1 * point3(m_, t[1]) + l2 * point3(m_, t[2]);
      return true;
    }
    return false;
  }

private:
  static double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
  std::array<int, 2> cell(const Eigen::Vector2d& q) const
  {
    std::array<int, 2> c;
    for(int d = 0; d < 2; ++d) c[std::size_t(d)] = std::clamp(int((q[d] + 1.) * 0.5 * n_), 0, n_ - 1);
    return c;
  }
  const Mesh& m_;
  const Uv_map<P>& uv_;
  int n_ = 1;
  std::vector<std::vector<F>> cells_;
};

/// One node moved (see the file comment). False when its patches are not k distinct
/// surface patches meeting only along its arcs, when no candidate is estimated better than
/// where it is, when a spoke cannot be traced, or when the measured corners do not come
/// nearer right angles (the mesh may be refined all the same; the old arcs then follow it).
template <class Point_3>
bool relocate_node(Polycube_layout<Point_3>& L, std::size_t n, Node_relocation_result& result)
{
  using Layout = Polycube_layout<Point_3>;
  using Mesh = typename Layout::Mesh;
  using V = typename Layout::vertex_descriptor;
  using F = typename Layout::face_descriptor;
  using H = typename Mesh::Halfedge_index;
  Mesh& m = L.mesh;
  const V node = L.nodes[n];
  if(is_border(node, m)) return false;

  // The star: (patch, corner index of n) for every surface patch with a corner at n.
  std::vector<std::array<std::size_t, 2>> star;
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    for(std::size_t i = 0; i < 4; ++i)
      if(L.patches[p].corners[i] == n) {
        if(L.patches[p].kind == Layout::CAP) return false;
        if(L.patches[p].kind == Layout::SURFACE) star.push_back({{p, i}}); // interfaces follow the arcs
      }
  const std::size_t k = star.size();
  if(k < 3) return false;
  // Cyclic order around n: after patch p (corner i) comes the patch whose spoke arcs[j] is
  // p's arcs[i+3]. Every spoke is shared by two star patches, every outer arc used once.
  std::vector<std::size_t> order{0};
  std::set<std::size_t> used_patches{star[0][0]};
  while(order.size() < k) {
    const auto& s = star[order.back()];
    const std::size_t spoke = L.patches[s[0]].arcs[(s[1] + 3) % 4];
    std::size_t found = k;
    for(std::size_t t = 0; t < k; ++t)
      if(L.patches[star[t][0]].arcs[star[t][1]] == spoke) found = t;
    if(found == k || !used_patches.insert(star[found][0]).second) return false;
    order.push_back(found);
  }
  if(L.patches[star[order.back()][0]].arcs[(star[order.back()][1] + 3) % 4] != L.patches[star[order[0]][0]].arcs[star[order[0]][1]])
    return false;
  std::vector<std::array<std::size_t, 2>> ring;
  for(std::size_t t : order) ring.push_back(star[t]);
  // spokes[t] = arcs[i] of ring[t] (from n to its corner i+1); ring[t-1] has it as arcs[i+3].
  std::vector<std::size_t> spokes, far_nodes;
  std::set<std::size_t> arcs_seen, far_seen;
  for(const auto& s : ring) {
    const auto& pa = L.patches[s[0]];
    spokes.push_back(pa.arcs[s[1]]);
    far_nodes.push_back(pa.corners[(s[1] + 1) % 4]);
    if(!arcs_seen.insert(pa.arcs[s[1]]).second || !far_seen.insert(pa.corners[(s[1] + 1) % 4]).second) return false;
  }
  for(const auto& s : ring)
    for(std::size_t j : {std::size_t(1), std::size_t(2)})
      if(!arcs_seen.insert(L.patches[s[0]].arcs[(s[1] + j) % 4]).second) return false;
  if(far_seen.count(n)) return false;

  // The corners the move changes: at n, and at both ends of every patch's spokes.
  std::vector<std::array<std::size_t, 2>> changed_corners;
  for(const auto& s : ring)
    for(std::size_t c : {s[1], (s[1] + 1) % 4, (s[1] + 3) % 4}) changed_corners.push_back({{s[0], c}});
  double largest = 0.;
  const double before = squared_corner_deviation(L, changed_corners, &largest);
  if(largest <= 30.) return false;

  // The union's border loop, counter-clockwise: each ring patch's two outer arcs.
  std::vector<V> loop;
  auto arc_from = [&](std::size_t a, std::size_t from_node) {
    std::vector<V> vs = L.arcs[a].vertices;
    if(L.arcs[a].nodes[0] != from_node) std::reverse(vs.begin(), vs.end());
    return vs;
  };
  for(const auto& s : ring) {
    const auto& pa = L.patches[s[0]];
    for(std::size_t j : {std::size_t(1), std::size_t(2)}) {
      const std::vector<V> vs = arc_from(pa.arcs[(s[1] + j) % 4], pa.corners[(s[1] + j) % 4]);
      loop.insert(loop.end(), vs.begin(), vs.end() - 1);
    }
  }
  std::vector<bool> cut(num_edges(m), false);
  for(std::size_t i = 0; i < loop.size(); ++i) {
    const auto h = halfedge(loop[i], loop[(i + 1) % loop.size()], m);
    if(!h.second) return false;
    cut[std::size_t(edge(h.first, m))] = true;
  }
  std::vector<signed char> in_union(num_faces(m), 0);
  std::size_t union_faces = 0;
  for(const auto& s : ring)
    for(F f : L.patches[s[0]].faces) {
      in_union[std::size_t(f)] = 1;
      ++union_faces;
    }

  // The union as a piece, mapped onto the unit circle by arc length.
  std::vector<Mesh> pieces = cut_into_pieces(m, cut);
  Mesh* piece = nullptr;
  const F first_face = L.patches[ring[0][0]].faces.front();
  for(Mesh& q : pieces) {
    const auto fpar = q.template property_map<F, std::size_t>("f:parent").first;
    for(F f : faces(q))
      if(fpar[f] == std::size_t(first_face)) piece = &q;
    if(piece) break;
  }
  if(!piece || num_faces(*piece) != union_faces) return false;
  const auto vpar = piece->template property_map<V, std::size_t>("v:parent").first;
  std::vector<V> piece_vertex(num_vertices(m), V());
  for(V v : vertices(*piece)) piece_vertex[vpar[v]] = v;
  std::vector<V> piece_loop;
  try {
    piece_loop = border_loop(*piece, piece_vertex[std::size_t(loop[0])]);
  } catch(const Internal_error&) {
    return false;
  }
  if(piece_loop.size() != loop.size()) return false;
  for(std::size_t i = 0; i < loop.size(); ++i)
    if(vpar[piece_loop[i]] != std::size_t(loop[i])) return false; // the union's border is not the outer arcs
  std::vector<Eigen::Vector3d> border_points;
  for(V v : loop) border_points.push_back(to_eigen_point(m.point(v)));
  border_points.push_back(border_points.front());
  const std::vector<double> along = cumulative_lengths(border_points);
  std::vector<Eigen::Vector2d> loop_uv;
  for(std::size_t i = 0; i < loop.size(); ++i) {
    const double a = 2. * CGAL_PI * along[i] / along.back();
    loop_uv.emplace_back(std::cos(a), std::sin(a));
  }
  if(embed_in_convex_polygon(*piece, piece_loop, loop_uv) != 0) return false;
  const auto uv = uv_map(*piece);
  for(V v : vertices(*piece))
    if(vpar[v] == no_parent) return false; // an edge was split: not a plain copy of the union
  const Uv_locator<Point_3> locate(*piece, uv);

  // Candidates: the union's inner vertices. Estimated corners: each spoke's direction at
  // both ends is the chord to its point a quarter of the way (leaving_direction()'s).
  std::vector<Eigen::Vector2d> far_uv;
  std::vector<Eigen::Vector3d> far_point;
  for(std::size_t f : far_nodes) {
    far_uv.push_back(uv[piece_vertex[std::size_t(L.nodes[f])]]);
    far_point.push_back(to_eigen_point(m.point(L.nodes[f])));
  }
  // At far node t the outer arcs leave in fixed directions: ring[t]'s arcs[i+1], and
  // arcs[i+2] of ring[t-1] (whose arcs[i+3] is spoke t).
  std::vector<Eigen::Vector3d> far_normal, outer_next, outer_previous;
  for(std::size_t t = 0; t < k; ++t) {
    const auto& s = ring[t];
    const auto& s2 = ring[(t + k - 1) % k];
    const V fv = L.nodes[far_nodes[t]];
    far_normal.push_back(layout_vertex_normal(L, fv));
    outer_next.push_back(leaving_direction(L, arc_from(L.patches[s[0]].arcs[(s[1] + 1) % 4], far_nodes[t]), far_normal.back()));
    outer_previous.push_back(leaving_direction(L, arc_from(L.patches[s2[0]].arcs[(s2[1] + 2) % 4], far_nodes[t]), far_normal.back()));
  }
  auto estimate = [&](V pv, double& out) {
    const Eigen::Vector2d c = uv[pv];
    const Eigen::Vector3d x = point3(*piece, pv);
    const Eigen::Vector3d normal = layout_vertex_normal(L, V(vpar[pv]));
    std::vector<Eigen::Vector3d> at_node(k), at_far(k);
    for(std::size_t t = 0; t < k; ++t) {
      Eigen::Vector3d q0, q1;
      if(!locate.point_at(c + 0.25 * (far_uv[t] - c), q0) || !locate.point_at(far_uv[t] + 0.25 * (c - far_uv[t]), q1)) return false;
      at_node[t] = q0 - x;
      at_far[t] = q1 - far_point[t];
    }
    double sum = 0.;
    for(std::size_t t = 0; t < k; ++t) {
      // ring[t]: corner at n between spoke t (next) and spoke t+1 (previous); at far node
      // t, ring[t]'s corner i+1 (outer arc next, spoke previous) and ring[t-1]'s corner
      // i+3 (spoke next, outer arc previous).
      const double a0 = corner_angle_between(normal, at_node[t], at_node[(t + 1) % k]) - 90.;
      const double a1 = corner_angle_between(far_normal[t], outer_next[t], at_far[t]) - 90.;
      const double a2 = corner_angle_between(far_normal[t], at_far[t], outer_previous[t]) - 90.;
      sum += a0 * a0 + a1 * a1 + a2 * a2;
    }
    out = sum;
    return true;
  };
  const V piece_node = piece_vertex[std::size_t(node)];
  double here = std::numeric_limits<double>::infinity();
  if(piece_node == V() || !estimate(piece_node, here)) return false;
  std::vector<bool> on_border(num_vertices(*piece), false);
  for(V v : piece_loop) on_border[std::size_t(v)] = true;
  std::vector<bool> on_loop(num_vertices(m), false); // by mesh vertex; split vertices are inner
  for(V v : loop) on_loop[std::size_t(v)] = true;
  V best = piece_node;
  double best_value = here;
  for(V v : vertices(*piece)) {
    if(on_border[std::size_t(v)] || v == piece_node) continue;
    double value;
    if(estimate(v, value) && value < best_value) {
      best_value = value;
      best = v;
    }
  }
  if(best == piece_node || !(best_value < 0.8 * here)) return false;

  // Insert the spokes from the chosen vertex: every inner edge a segment crosses strictly
  // between its ends is split there (uv interpolated with the point).
  const V centre(static_cast<std::uint32_t>(vpar[best]));
  std::vector<Eigen::Vector2d> uvm(num_vertices(m), Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 0.));
  for(V v : vertices(*piece)) uvm[vpar[v]] = uv[v];
  std::set<std::size_t> border_edges;
  for(std::size_t e = 0; e < cut.size(); ++e)
    if(cut[e]) border_edges.insert(e);
  auto inside = [&](H h) { return !is_border(h, m) && in_union[std::size_t(face(h, m))]; };
  auto edge_inside = [&](H h) { return inside(h) && inside(opposite(h, m)); };
  std::map<std::pair<V, V>, V> split_of; // both orders
  std::vector<std::vector<V>> new_paths(k);
  std::set<V> locked{centre};
  bool traced = true;
  for(std::size_t t = 0; t < k && traced; ++t) {
    const V target_vertex = L.nodes[far_nodes[t]];
    const Eigen::Vector2d c = uvm[std::size_t(centre)], d = uvm[std::size_t(target_vertex)] - c;
    const double len2 = d.squaredNorm();
    // Signed distance to the segment's line and position along it (0 at the centre).
    auto side = [&](V v) { return (d.x() * (uvm[std::size_t(v)].y() - c.y()) - d.y() * (uvm[std::size_t(v)].x() - c.x())) / std::sqrt(len2); };
    auto along_of = [&](V v) { return (uvm[std::size_t(v)] - c).dot(d) / len2; };
    std::vector<signed char> on_line(num_vertices(m), 0);
    on_line[std::size_t(centre)] = on_line[std::size_t(target_vertex)] = 1;
    // Inner vertices within a tenth of an edge of the segment join it (no slivers).
    std::vector<F> union_face_list;
    for(F f : faces(m))
      if(in_union[std::size_t(f)]) union_face_list.push_back(f);
    std::set<V> inner;
    for(F f : union_face_list)
      for(V v : vertices_around_face(halfedge(f, m), m))
        if(std::isfinite(uvm[std::size_t(v)].x()) && !(std::size_t(v) < on_loop.size() && on_loop[std::size_t(v)])) inner.insert(v);
    for(V v : inner) {
      if(locked.count(v) || on_line[std::size_t(v)]) continue;
      const double s = along_of(v);
      if(!(s > 0. && s < 1.)) continue;
      double shortest = std::numeric_limits<double>::infinity();
      for(H h : halfedges_around_target(v, m)) shortest = std::min(shortest, (uvm[std::size_t(source(h, m))] - uvm[std::size_t(v)]).norm());
      if(std::abs(side(v)) < 0.1 * shortest) on_line[std::size_t(v)] = 1;
    }
    std::vector<std::pair<std::array<V, 2>, double>> splits;
    std::set<std::size_t> seen;
    for(F f : union_face_list)
      for(H h : halfedges_around_face(halfedge(f, m), m)) {
        const V a = source(h, m), b = target(h, m);
        if(on_line[std::size_t(a)] || on_line[std::size_t(b)] || !edge_inside(h)) continue;
        const double ga = side(a), gb = side(b);
        if(!((ga < 0. && gb > 0.) || (ga > 0. && gb < 0.))) continue;
        const double u = ga / (ga - gb);
        const Eigen::Vector2d x = (1. - u) * uvm[std::size_t(a)] + u * uvm[std::size_t(b)];
        const double s = (x - c).dot(d) / len2;
        if(s > 0. && s < 1. && seen.insert(std::size_t(edge(h, m))).second) splits.push_back({{{a, b}}, u});
      }
    for(const auto& sp : splits) {
      const H h = halfedge(sp.first[0], sp.first[1], m).first;
      const V a = sp.first[0], b = sp.first[1];
      const V x = target(split_edge_at(m, h, sp.second), m);
      uvm.push_back((1. - sp.second) * uvm[std::size_t(a)] + sp.second * uvm[std::size_t(b)]);
      on_line.push_back(1);
      split_of[{a, b}] = split_of[{b, a}] = x;
    }
    in_union.resize(num_faces(m), 1); // the new faces were cut from the union's
    // The path from the centre: each step to the on-line neighbour inside the union that
    // is farthest along without passing the target.
    std::vector<V> path{centre};
    while(path.back() != target_vertex) {
      const V v = path.back();
      const double s = v == centre ? 0. : along_of(v);
      V next_vertex = v;
      double next_s = std::numeric_limits<double>::infinity();
      for(H h : halfedges_around_source(v, m)) {
        const V w = target(h, m);
        if(!on_line[std::size_t(w)] || !edge_inside(h) || locked.count(w)) continue;
        const double sw = w == target_vertex ? 1. : along_of(w);
        if(sw > s && sw < next_s) {
          next_s = sw;
          next_vertex = w;
        }
      }
      if(next_vertex == v || path.size() > num_vertices(m)) {
        traced = false;
        break;
      }
      path.push_back(next_vertex);
    }
    if(traced) {
      for(std::size_t i = 1; i + 1 < path.size(); ++i) locked.insert(path[i]);
      new_paths[t] = path;
    }
  }

  // The old spokes through the split vertices.
  std::vector<std::vector<V>> old_paths(k);
  std::function<void(V, V, std::vector<V>&)> expand = [&](V a, V b, std::vector<V>& out) {
    if(halfedge(a, b, m).second) {
      out.push_back(b);
      return;
    }
    const auto it = split_of.find({a, b});
    if(it == split_of.end()) throw Internal_error("invalid_layout", "the node relocation lost an arc");
    expand(a, it->second, out);
    expand(it->second, b, out);
  };
  for(std::size_t t = 0; t < k; ++t) {
    const std::vector<V> vs = arc_from(spokes[t], n);
    old_paths[t].push_back(vs.front());
    for(std::size_t i = 1; i < vs.size(); ++i) expand(vs[i - 1], vs[i], old_paths[t]);
  }
  // The ring's patches as the union's faces between consecutive spokes: flood fills from
  // each patch's outer arcs (the seeds: their halfedges inside the union) that cross
  // neither the border nor a spoke.
  const std::size_t total = std::size_t(std::count(in_union.begin(), in_union.end(), 1));
  std::vector<std::vector<H>> seeds(k);
  for(std::size_t t = 0; t < k; ++t)
    for(std::size_t j : {std::size_t(1), std::size_t(2)}) {
      const auto& pa = L.patches[ring[t][0]];
      const std::vector<V>& vs = L.arcs[pa.arcs[(ring[t][1] + j) % 4]].vertices;
      for(std::size_t i = 1; i < vs.size(); ++i)
        for(H h : {halfedge(vs[i - 1], vs[i], m).first, halfedge(vs[i], vs[i - 1], m).first})
          if(inside(h)) seeds[t].push_back(h);
    }
  auto sectors = [&](const std::vector<std::vector<V>>& paths) {
    std::set<std::size_t> barrier = border_edges;
    for(const auto& path : paths)
      for(std::size_t i = 1; i < path.size(); ++i) {
        const auto h = halfedge(path[i - 1], path[i], m);
        if(!h.second) return std::vector<std::vector<F>>{};
        barrier.insert(std::size_t(edge(h.first, m)));
      }
    return faces_between_barriers(m, seeds, barrier, total);
  };
  auto apply = [&](V at, const std::vector<std::vector<V>>& paths, std::vector<std::vector<F>>&& faces_of) {
    L.nodes[n] = at;
    for(std::size_t t = 0; t < k; ++t) {
      std::vector<V> vs = paths[t];
      if(L.arcs[spokes[t]].nodes[0] != n) std::reverse(vs.begin(), vs.end());
      L.arcs[spokes[t]].vertices = std::move(vs);
      L.patches[ring[t][0]].faces = std::move(faces_of[t]);
    }
  };
  auto restore_old = [&] {
    auto faces_of = sectors(old_paths);
    if(faces_of.empty()) throw Internal_error("invalid_layout", "the node relocation lost the patches around node " + std::to_string(n));
    apply(node, old_paths, std::move(faces_of));
    return false;
  };
  if(!traced) return restore_old();
  auto faces_of = sectors(new_paths);
  if(faces_of.empty()) return restore_old();
  apply(centre, new_paths, std::move(faces_of));
  const double after = squared_corner_deviation(L, changed_corners);
  if(!(after < 0.9 * before)) return restore_old();
  result.squared_deviation_before += before;
  result.squared_deviation_after += after;
  return true;
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// Moves the layout's nodes whose corners are far from right angles (see the file
/// comment), in node order, for up to `sweeps` sweeps or until a sweep moves none. Nodes on
/// the mesh's border or at a cap's corner stay. The result is valid whenever `L` was
/// (checked: throws Internal_error("invalid_layout") otherwise). Deterministic.
template <class Point_3>
Node_relocation_result relocate_layout_nodes(Polycube_layout<Point_3>& L, int sweeps = 2)
{
  Node_relocation_result result;
  std::tie(result.nodes_moved, result.sweeps) = internal::sweep_layout(L, sweeps, L.nodes.size(), "node relocation", [&](std::size_t n) {
    return internal::relocate_node(L, n, result);
  });
  return result;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_LAYOUT_NODE_RELOCATION_H
