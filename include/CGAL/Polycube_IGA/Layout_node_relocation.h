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
//
// A node on an input boundary loop (a cap's corner) has one inner arc, and where the cap
// corners at 1/8, 3/8, ... of the loop put it, that arc may leave almost along the rim
// (mech-holes-shark.off: 191 and 17 degrees). Such a node (one of its corners a sliver,
// nearly flat or reflex) slides along the rim instead: its two surface patches' union has
// the node on its border, the candidates are the rim vertices of its two cap arcs (keeping
// each at least a quarter of their joint length, so the cap's sides stay within 1:3), and
// its inner arc is the map's straight chord to the far node, estimated, inserted and kept
// or undone the same way.

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

/// The union of some surface patches, cut out of the layout's mesh and mapped onto the
/// unit circle by arc length along `loop` (its border, counter-clockwise).
template <class Point_3>
struct Union_disk
{
  using Mesh = typename Polycube_layout<Point_3>::Mesh;
  using V = typename Mesh::Vertex_index;
  using F = typename Mesh::Face_index;
  std::vector<Mesh> pieces; ///< the union's pieces (one, if it is a disk); `piece` points into it
  Mesh* piece = nullptr;
  typename Mesh::template Property_map<V, std::size_t> parent; ///< piece vertex -> mesh vertex
  std::vector<V> piece_vertex;           ///< mesh vertex -> piece vertex (V() outside)
  std::vector<V> piece_loop;             ///< the border loop in the piece
  std::vector<bool> cut;                 ///< by mesh edge: on the union's border
  std::vector<bool> in_union;            ///< by mesh face
  std::vector<F> union_faces;            ///< in index order (insertions append the faces they split off)
  std::vector<bool> on_loop;             ///< by mesh vertex (as built; later splits are inner)
  Uv_map<Point_3> uv;

  Union_disk() = default;
  Union_disk(const Union_disk&) = delete; // `piece` points into `pieces`
  Union_disk& operator=(const Union_disk&) = delete;

  /// Builds the map; false when `loop` is not the border of exactly `patches`' faces, or the
  /// piece is not a plain copy of them.
  bool build(Polycube_layout<Point_3>& L, const std::vector<std::size_t>& patches, const std::vector<V>& loop)
  {
    Mesh& m = L.mesh;
    cut.assign(num_edges(m), false);
    for(std::size_t i = 0; i < loop.size(); ++i) {
      const auto h = halfedge(loop[i], loop[(i + 1) % loop.size()], m);
      if(!h.second) return false;
      cut[std::size_t(edge(h.first, m))] = true;
    }
    in_union.assign(num_faces(m), false);
    union_faces.clear();
    for(std::size_t p : patches)
      for(F f : L.patches[p].faces) {
        in_union[std::size_t(f)] = true;
        union_faces.push_back(f);
      }
    std::sort(union_faces.begin(), union_faces.end());
    // The union's faces alone: copying the whole mesh for each node is most of the work.
    // Every piece is then part of the union, so a disk union is the only piece.
    pieces = cut_into_pieces(m, cut, in_union);
    if(pieces.size() != 1 || num_faces(pieces.front()) != union_faces.size()) return false;
    piece = &pieces.front();
    parent = piece->template property_map<V, std::size_t>("v:parent").first;
    piece_vertex.assign(num_vertices(m), V());
    for(V v : vertices(*piece)) piece_vertex[parent[v]] = v;
    try {
      piece_loop = border_loop(*piece, piece_vertex[std::size_t(loop[0])]);
    } catch(const Internal_error&) {
      return false;
    }
    if(piece_loop.size() != loop.size()) return false;
    for(std::size_t i = 0; i < loop.size(); ++i)
      if(parent[piece_loop[i]] != std::size_t(loop[i])) return false; // the union's border is not `loop`
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
    uv = uv_map(*piece);
    for(V v : vertices(*piece))
      if(parent[v] == no_parent) return false; // an edge was split: not a plain copy of the union
    on_loop.assign(num_vertices(m), false);
    for(V v : loop) on_loop[std::size_t(v)] = true;
    return true;
  }
};

/// Straight segments of a Union_disk's map inserted into the layout's mesh: every inner
/// edge a segment crosses strictly between its ends is split there (the surface does not
/// move), and the segment's vertex path found. Split edges are remembered, so that the old
/// arcs can be followed through the new vertices (path_through_splits()).
template <class Point_3>
class Union_segment_inserter
{
  using Mesh = typename Polycube_layout<Point_3>::Mesh;
  using V = typename Mesh::Vertex_index;
  using F = typename Mesh::Face_index;
  using H = typename Mesh::Halfedge_index;

public:
  Union_segment_inserter(Mesh& m, Union_disk<Point_3>& u)
    : m_(m), u_(u), uvm_(num_vertices(m), Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 0.))
  {
    for(V v : vertices(*u.piece)) uvm_[u.parent[v]] = u.uv[v];
  }

  /// A halfedge with the union on both sides.
  bool edge_inside(H h) const { return inside(h) && inside(opposite(h, m_)); }
  bool inside(H h) const { return !is_border(h, m_) && u_.in_union[std::size_t(face(h, m_))]; }

  /// The vertex path from `from` to `to` (mesh vertices of the union, both in the map)
  /// along the straight segment between them, through no vertex of `locked`; empty when
  /// there is none. The path's inner vertices are locked for the next segments.
  std::vector<V> insert(V from, V to)
  {
    const Eigen::Vector2d c = uvm_[std::size_t(from)], d = uvm_[std::size_t(to)] - c;
    const double len2 = d.squaredNorm();
    // Signed distance to the segment's line and position along it (0 at `from`).
    auto side = [&](V v) { return (d.x() * (uvm_[std::size_t(v)].y() - c.y()) - d.y() * (uvm_[std::size_t(v)].x() - c.x())) / std::sqrt(len2); };
    auto along_of = [&](V v) { return (uvm_[std::size_t(v)] - c).dot(d) / len2; };
    locked_.insert(from);
    std::vector<signed char> on_line(num_vertices(m_), 0);
    on_line[std::size_t(from)] = on_line[std::size_t(to)] = 1;
    // Inner vertices within a tenth of an edge of the segment join it (no slivers).
    std::set<V> inner;
    for(F f : u_.union_faces)
      for(V v : vertices_around_face(halfedge(f, m_), m_))
        if(std::isfinite(uvm_[std::size_t(v)].x()) && !(std::size_t(v) < u_.on_loop.size() && u_.on_loop[std::size_t(v)])) inner.insert(v);
    for(V v : inner) {
      if(locked_.count(v) || on_line[std::size_t(v)]) continue;
      const double s = along_of(v);
      if(!(s > 0. && s < 1.)) continue;
      double shortest = std::numeric_limits<double>::infinity();
      for(H h : halfedges_around_target(v, m_)) shortest = std::min(shortest, (uvm_[std::size_t(source(h, m_))] - uvm_[std::size_t(v)]).norm());
      if(std::abs(side(v)) < 0.1 * shortest) on_line[std::size_t(v)] = 1;
    }
    std::vector<std::pair<std::array<V, 2>, double>> splits;
    std::set<std::size_t> seen;
    for(F f : u_.union_faces)
      for(H h : halfedges_around_face(halfedge(f, m_), m_)) {
        const V a = source(h, m_), b = target(h, m_);
        if(on_line[std::size_t(a)] || on_line[std::size_t(b)] || !edge_inside(h)) continue;
        const double ga = side(a), gb = side(b);
        if(!((ga < 0. && gb > 0.) || (ga > 0. && gb < 0.))) continue;
        const double t = ga / (ga - gb);
        const Eigen::Vector2d x = (1. - t) * uvm_[std::size_t(a)] + t * uvm_[std::size_t(b)];
        const double s = (x - c).dot(d) / len2;
        if(s > 0. && s < 1. && seen.insert(std::size_t(edge(h, m_))).second) splits.push_back({{{a, b}}, t});
      }
    for(const auto& sp : splits) {
      const H h = halfedge(sp.first[0], sp.first[1], m_).first;
      const V a = sp.first[0], b = sp.first[1];
      const V x = target(split_edge_at(m_, h, sp.second), m_);
      uvm_.push_back((1. - sp.second) * uvm_[std::size_t(a)] + sp.second * uvm_[std::size_t(b)]);
      on_line.push_back(1);
      split_of_[{a, b}] = split_of_[{b, a}] = x;
    }
    // The new faces were cut from the union's; their indices follow all others.
    for(std::size_t f = u_.in_union.size(); f < num_faces(m_); ++f) u_.union_faces.push_back(F(typename F::size_type(f)));
    u_.in_union.resize(num_faces(m_), true);
    // The path from `from`: each step to the on-line neighbour inside the union that is
    // farthest along without passing `to`.
    std::vector<V> path{from};
    while(path.back() != to) {
      const V v = path.back();
      const double s = v == from ? 0. : along_of(v);
      V next_vertex = v;
      double next_s = std::numeric_limits<double>::infinity();
      for(H h : halfedges_around_source(v, m_)) {
        const V w = target(h, m_);
        if(!on_line[std::size_t(w)] || !edge_inside(h) || locked_.count(w)) continue;
        const double sw = w == to ? 1. : along_of(w);
        if(sw > s && sw < next_s) {
          next_s = sw;
          next_vertex = w;
        }
      }
      if(next_vertex == v || path.size() > num_vertices(m_)) return {};
      path.push_back(next_vertex);
    }
    for(std::size_t i = 1; i + 1 < path.size(); ++i) locked_.insert(path[i]);
    return path;
  }

  /// A vertex path of the mesh before the insertions, followed through the split vertices.
  std::vector<V> path_through_splits(const std::vector<V>& vs) const
  {
    std::vector<V> out{vs.front()};
    std::function<void(V, V)> expand = [&](V a, V b) {
      if(halfedge(a, b, m_).second) {
        out.push_back(b);
        return;
      }
      const auto it = split_of_.find({a, b});
      if(it == split_of_.end()) throw Internal_error("invalid_layout", "the node relocation lost an arc");
      expand(a, it->second);
      expand(it->second, b);
    };
    for(std::size_t i = 1; i < vs.size(); ++i) expand(vs[i - 1], vs[i]);
    return out;
  }

private:
  Mesh& m_;
  Union_disk<Point_3>& u_;
  std::vector<Eigen::Vector2d> uvm_; ///< by mesh vertex; NaN outside the union
  std::map<std::pair<V, V>, V> split_of_; ///< both orders
  std::set<V> locked_;
};

/// The faces of `patches` (after insertions) between the barriers: the union's border and
/// the paths' edges; seeds[t] are the halfedges inside the union along patch t's fixed arcs.
/// Empty when a path is no longer a path of edges or the fill fails.
template <class Point_3>
std::vector<std::vector<typename Polycube_layout<Point_3>::face_descriptor>>
union_sectors(const Polycube_layout<Point_3>& L, const Union_disk<Point_3>& u,
              const std::vector<std::vector<typename Polycube_layout<Point_3>::Mesh::Halfedge_index>>& seeds,
              const std::vector<std::vector<typename Polycube_layout<Point_3>::vertex_descriptor>>& paths)
{
  const auto& m = L.mesh;
  std::set<std::size_t> barrier;
  for(std::size_t e = 0; e < u.cut.size(); ++e)
    if(u.cut[e]) barrier.insert(e);
  for(const auto& path : paths)
    for(std::size_t i = 1; i < path.size(); ++i) {
      const auto h = halfedge(path[i - 1], path[i], m);
      if(!h.second) return {};
      barrier.insert(std::size_t(edge(h.first, m)));
    }
  return faces_between_barriers(m, seeds, barrier, u.union_faces.size());
}

/// The halfedges inside the union along an arc's vertex path (flood-fill seeds).
template <class Point_3>
void add_seeds(const Polycube_layout<Point_3>& L, const Union_segment_inserter<Point_3>& ins,
               const std::vector<typename Polycube_layout<Point_3>::vertex_descriptor>& vs,
               std::vector<typename Polycube_layout<Point_3>::Mesh::Halfedge_index>& seeds)
{
  for(std::size_t i = 1; i < vs.size(); ++i)
    for(auto h : {halfedge(vs[i - 1], vs[i], L.mesh).first, halfedge(vs[i], vs[i - 1], L.mesh).first})
      if(ins.inside(h)) seeds.push_back(h);
}

/// An arc's vertices in order from one of its nodes.
template <class Point_3>
std::vector<typename Polycube_layout<Point_3>::vertex_descriptor> arc_from(const Polycube_layout<Point_3>& L, std::size_t a, std::size_t from_node)
{
  auto vs = L.arcs[a].vertices;
  if(L.arcs[a].nodes[0] != from_node) std::reverse(vs.begin(), vs.end());
  return vs;
}

/// Sets an arc's vertices given in order from one of its nodes.
template <class Point_3>
void set_arc_from(Polycube_layout<Point_3>& L, std::size_t a, std::size_t from_node,
                  std::vector<typename Polycube_layout<Point_3>::vertex_descriptor> vs)
{
  if(L.arcs[a].nodes[0] != from_node) std::reverse(vs.begin(), vs.end());
  L.arcs[a].vertices = std::move(vs);
}

/// The end of a move: the patches as the sectors between `new_paths` (empty when a path
/// could not be traced), applied by `apply(true, sectors)`; undone by `apply(false, ...)`
/// with the sectors between `old_paths` unless it is traced, fills its patches and brings
/// `changed_corners` nearer right angles by a tenth of `before`. Returns whether it is kept.
template <class Point_3, class Apply>
bool keep_if_better(Polycube_layout<Point_3>& L, const Union_disk<Point_3>& u,
                    const std::vector<std::vector<typename Polycube_layout<Point_3>::Mesh::Halfedge_index>>& seeds,
                    const std::vector<std::vector<typename Polycube_layout<Point_3>::vertex_descriptor>>& old_paths,
                    const std::vector<std::vector<typename Polycube_layout<Point_3>::vertex_descriptor>>& new_paths,
                    const std::vector<std::array<std::size_t, 2>>& changed_corners, double before, std::size_t n,
                    Node_relocation_result& result, Apply&& apply)
{
  auto restore_old = [&] {
    auto faces_of = union_sectors(L, u, seeds, old_paths);
    if(faces_of.empty()) throw Internal_error("invalid_layout", "the node relocation lost the patches around node " + std::to_string(n));
    apply(false, std::move(faces_of));
    return false;
  };
  for(const auto& path : new_paths)
    if(path.empty()) return restore_old();
  auto faces_of = union_sectors(L, u, seeds, new_paths);
  if(faces_of.empty()) return restore_old();
  apply(true, std::move(faces_of));
  const double after = squared_corner_deviation(L, changed_corners);
  if(!(after < 0.9 * before)) return restore_old();
  result.squared_deviation_before += before;
  result.squared_deviation_after += after;
  return true;
}

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
  std::vector<std::size_t> ring_patches;
  for(const auto& s : ring) {
    const auto& pa = L.patches[s[0]];
    ring_patches.push_back(s[0]);
    for(std::size_t j : {std::size_t(1), std::size_t(2)}) {
      const std::vector<V> vs = arc_from(L, pa.arcs[(s[1] + j) % 4], pa.corners[(s[1] + j) % 4]);
      loop.insert(loop.end(), vs.begin(), vs.end() - 1);
    }
  }
  Union_disk<Point_3> u;
  if(!u.build(L, ring_patches, loop)) return false;
  const Mesh& piece = *u.piece;
  const auto& uv = u.uv;
  const Uv_locator<Point_3> locate(piece, uv);

  // Candidates: the union's inner vertices. Estimated corners: each spoke's direction at
  // both ends is the chord to its point a quarter of the way (leaving_direction()'s).
  std::vector<Eigen::Vector2d> far_uv;
  std::vector<Eigen::Vector3d> far_point;
  for(std::size_t f : far_nodes) {
    far_uv.push_back(uv[u.piece_vertex[std::size_t(L.nodes[f])]]);
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
    outer_next.push_back(leaving_direction(L, arc_from(L, L.patches[s[0]].arcs[(s[1] + 1) % 4], far_nodes[t]), far_normal.back()));
    outer_previous.push_back(leaving_direction(L, arc_from(L, L.patches[s2[0]].arcs[(s2[1] + 2) % 4], far_nodes[t]), far_normal.back()));
  }
  auto estimate = [&](V pv, double& out) {
    const Eigen::Vector2d c = uv[pv];
    const Eigen::Vector3d x = point3(piece, pv);
    const Eigen::Vector3d normal = layout_vertex_normal(L, V(u.parent[pv]));
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
  const V piece_node = u.piece_vertex[std::size_t(node)];
  double here = std::numeric_limits<double>::infinity();
  if(piece_node == V() || !estimate(piece_node, here)) return false;
  std::vector<bool> on_border(num_vertices(piece), false);
  for(V v : u.piece_loop) on_border[std::size_t(v)] = true;
  V best = piece_node;
  double best_value = here;
  for(V v : vertices(piece)) {
    if(on_border[std::size_t(v)] || v == piece_node) continue;
    double value;
    if(estimate(v, value) && value < best_value) {
      best_value = value;
      best = v;
    }
  }
  if(best == piece_node || !(best_value < 0.8 * here)) return false;

  // Insert the spokes from the chosen vertex.
  const V centre(static_cast<std::uint32_t>(u.parent[best]));
  Union_segment_inserter<Point_3> ins(m, u);
  std::vector<std::vector<V>> new_paths(k);
  bool traced = true;
  for(std::size_t t = 0; t < k && traced; ++t) {
    new_paths[t] = ins.insert(centre, L.nodes[far_nodes[t]]);
    traced = !new_paths[t].empty();
  }
  std::vector<std::vector<V>> old_paths(k);
  for(std::size_t t = 0; t < k; ++t) old_paths[t] = ins.path_through_splits(arc_from(L, spokes[t], n));
  // The ring's patches as the union's faces between consecutive spokes: flood fills from
  // each patch's outer arcs.
  std::vector<std::vector<H>> seeds(k);
  for(std::size_t t = 0; t < k; ++t)
    for(std::size_t j : {std::size_t(1), std::size_t(2)})
      add_seeds(L, ins, L.arcs[L.patches[ring[t][0]].arcs[(ring[t][1] + j) % 4]].vertices, seeds[t]);
  return keep_if_better(L, u, seeds, old_paths, new_paths, changed_corners, before, n, result,
                        [&](bool moved, std::vector<std::vector<F>>&& faces_of) {
                          L.nodes[n] = moved ? centre : node;
                          for(std::size_t t = 0; t < k; ++t) {
                            set_arc_from(L, spokes[t], n, moved ? new_paths[t] : old_paths[t]);
                            L.patches[ring[t][0]].faces = std::move(faces_of[t]);
                          }
                        });
}

/// A node on an input boundary loop moved along the loop (see the file comment). Its star
/// is two surface patches A and B and a cap: A's arcs at the node are the inner arc s (to
/// the far node) and the border arc to the cap's previous corner, B's the border arc to
/// its next corner and s. The union of A and B is mapped onto the unit circle; every
/// vertex of the two border arcs that leaves each at least a quarter of their joint length
/// is a candidate, s its straight chord to the far node. False as relocate_node().
template <class Point_3>
bool relocate_border_node(Polycube_layout<Point_3>& L, std::size_t n, Node_relocation_result& result)
{
  using Layout = Polycube_layout<Point_3>;
  using Mesh = typename Layout::Mesh;
  using V = typename Layout::vertex_descriptor;
  using F = typename Layout::face_descriptor;
  using H = typename Mesh::Halfedge_index;
  Mesh& m = L.mesh;
  const V node = L.nodes[n];
  if(!is_border(node, m)) return false;

  std::vector<std::array<std::size_t, 2>> star;
  std::set<std::size_t> cap_arcs;
  std::size_t caps = 0;
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    for(std::size_t i = 0; i < 4; ++i)
      if(L.patches[p].corners[i] == n) {
        if(L.patches[p].kind == Layout::SURFACE) star.push_back({{p, i}});
        if(L.patches[p].kind == Layout::CAP) {
          ++caps;
          cap_arcs.insert(L.patches[p].arcs[i]);
          cap_arcs.insert(L.patches[p].arcs[(i + 3) % 4]);
        }
      }
  if(star.size() != 2 || caps != 1 || cap_arcs.size() != 2) return false;
  // A: arcs[i] = s inner, arcs[i+3] = its border arc; B: arcs[j] border, arcs[j+3] = s.
  auto inner_next = [&](const std::array<std::size_t, 2>& c) {
    const auto& pa = L.patches[c[0]];
    return !cap_arcs.count(pa.arcs[c[1]]) && cap_arcs.count(pa.arcs[(c[1] + 3) % 4]);
  };
  if(!inner_next(star[0])) std::swap(star[0], star[1]);
  const std::size_t pa_index = star[0][0], i = star[0][1], pb_index = star[1][0], j = star[1][1];
  const auto& A = L.patches[pa_index];
  const auto& B = L.patches[pb_index];
  if(!inner_next(star[0]) || pa_index == pb_index || !cap_arcs.count(B.arcs[j]) || B.arcs[(j + 3) % 4] != A.arcs[i]) return false;
  const std::size_t s = A.arcs[i], far = A.corners[(i + 1) % 4];
  const std::size_t border_a = A.arcs[(i + 3) % 4], border_b = B.arcs[j];
  const std::size_t node_a = A.corners[(i + 3) % 4], node_b = B.corners[(j + 1) % 4];
  if(B.corners[(j + 3) % 4] != far || far == n || node_a == node_b || node_a == far || node_b == far) return false;
  std::set<std::size_t> loop_arcs{border_b, B.arcs[(j + 1) % 4], B.arcs[(j + 2) % 4], A.arcs[(i + 1) % 4], A.arcs[(i + 2) % 4], border_a};
  if(loop_arcs.size() != 6 || loop_arcs.count(s)) return false;

  // Only a corner at the node that lets a fitted face degenerate moves it: cap corners
  // elsewhere sit where the cap's quarters put them, or off a step of the rim
  // (Cuboid_decomposition's corners_off_steps), and blade.off's stepped ends are no longer
  // valid when its corners there slide to lower a 55-degree deviation.
  if(!is_bad_corner(surface_corner_angle(L, pa_index, int(i))) && !is_bad_corner(surface_corner_angle(L, pb_index, int(j))))
    return false;
  const std::vector<std::array<std::size_t, 2>> changed_corners{
      {{pa_index, i}}, {{pa_index, (i + 1) % 4}}, {{pa_index, (i + 3) % 4}},
      {{pb_index, j}}, {{pb_index, (j + 1) % 4}}, {{pb_index, (j + 3) % 4}}};
  double largest = 0.;
  const double before = squared_corner_deviation(L, changed_corners, &largest);
  if(largest <= 30.) return false;

  // The union's border loop, counter-clockwise from the node: B's arcs j..j+2, A's i+1..i+3.
  std::vector<V> loop;
  auto append = [&](std::size_t a, std::size_t from_node) {
    const std::vector<V> vs = arc_from(L, a, from_node);
    loop.insert(loop.end(), vs.begin(), vs.end() - 1);
  };
  for(std::size_t t = 0; t < 3; ++t) append(B.arcs[(j + t) % 4], B.corners[(j + t) % 4]);
  for(std::size_t t = 1; t < 4; ++t) append(A.arcs[(i + t) % 4], A.corners[(i + t) % 4]);
  Union_disk<Point_3> u;
  if(!u.build(L, {pa_index, pb_index}, loop)) return false;
  const Uv_locator<Point_3> locate(*u.piece, u.uv);

  // The border path from node_a through the node to node_b, and the fixed directions.
  std::vector<V> path = arc_from(L, border_a, node_a);
  const std::size_t at_node = path.size() - 1;
  {
    const std::vector<V> vs = arc_from(L, border_b, n);
    path.insert(path.end(), vs.begin() + 1, vs.end());
  }
  std::vector<Eigen::Vector3d> points;
  for(V v : path) points.push_back(to_eigen_point(m.point(v)));
  const std::vector<double> length = cumulative_lengths(points);
  const V far_vertex = L.nodes[far];
  const Eigen::Vector2d far_uv = u.uv[u.piece_vertex[std::size_t(far_vertex)]];
  const Eigen::Vector3d far_point = to_eigen_point(m.point(far_vertex));
  const Eigen::Vector3d far_normal = layout_vertex_normal(L, far_vertex);
  const Eigen::Vector3d far_next = leaving_direction(L, arc_from(L, A.arcs[(i + 1) % 4], far), far_normal);
  const Eigen::Vector3d far_previous = leaving_direction(L, arc_from(L, B.arcs[(j + 2) % 4], far), far_normal);
  const Eigen::Vector3d normal_a = layout_vertex_normal(L, L.nodes[node_a]), normal_b = layout_vertex_normal(L, L.nodes[node_b]);
  const Eigen::Vector3d a_previous = leaving_direction(L, arc_from(L, A.arcs[(i + 2) % 4], node_a), normal_a);
  const Eigen::Vector3d b_next = leaving_direction(L, arc_from(L, B.arcs[(j + 1) % 4], node_b), normal_b);
  auto estimate = [&](std::size_t q, double& out) {
    const V v = path[q];
    const Eigen::Vector2d c = u.uv[u.piece_vertex[std::size_t(v)]];
    const Eigen::Vector3d normal = layout_vertex_normal(L, v);
    Eigen::Vector3d q0, q1;
    if(!locate.point_at(c + 0.25 * (far_uv - c), q0) || !locate.point_at(far_uv + 0.25 * (c - far_uv), q1)) return false;
    const Eigen::Vector3d chord = q0 - points[q], chord_far = q1 - far_point;
    const std::vector<V> to_a(path.rend() - std::ptrdiff_t(q) - 1, path.rend()), to_b(path.begin() + std::ptrdiff_t(q), path.end());
    const std::vector<V> from_a(path.begin(), path.begin() + std::ptrdiff_t(q) + 1), from_b(path.rbegin(), path.rend() - std::ptrdiff_t(q));
    const double d[6] = {
        corner_angle_between(normal, chord, leaving_direction(L, to_a, normal)),             // A at the node
        corner_angle_between(normal, leaving_direction(L, to_b, normal), chord),             // B at the node
        corner_angle_between(far_normal, far_next, chord_far),                               // A at the far node
        corner_angle_between(far_normal, chord_far, far_previous),                           // B at the far node
        corner_angle_between(normal_a, leaving_direction(L, from_a, normal_a), a_previous),  // A at node_a
        corner_angle_between(normal_b, b_next, leaving_direction(L, from_b, normal_b))};     // B at node_b
    out = 0.;
    for(double a : d) out += (a - 90.) * (a - 90.);
    return true;
  };
  double here = std::numeric_limits<double>::infinity();
  if(!estimate(at_node, here)) return false;
  std::size_t best = at_node;
  double best_value = here;
  for(std::size_t q = 1; q + 1 < path.size(); ++q) {
    if(q == at_node || length[q] < length.back() / 4. || length[q] > 3. * length.back() / 4.) continue;
    double value;
    if(estimate(q, value) && value < best_value) {
      best_value = value;
      best = q;
    }
  }
  if(best == at_node || !(best_value < 0.8 * here)) return false;

  Union_segment_inserter<Point_3> ins(m, u);
  const std::vector<V> new_path = ins.insert(path[best], far_vertex);
  const std::vector<V> old_path = ins.path_through_splits(arc_from(L, s, n));
  std::vector<std::vector<H>> seeds(2);
  for(std::size_t t : {std::size_t(1), std::size_t(2)}) {
    add_seeds(L, ins, L.arcs[A.arcs[(i + t) % 4]].vertices, seeds[0]);
    add_seeds(L, ins, L.arcs[B.arcs[(j + t) % 4]].vertices, seeds[1]);
  }
  return keep_if_better(L, u, seeds, {old_path}, {new_path}, changed_corners, before, n, result,
                        [&](bool moved, std::vector<std::vector<F>>&& faces_of) {
                          const std::size_t q = moved ? best : at_node;
                          L.nodes[n] = path[q];
                          set_arc_from(L, s, n, moved ? new_path : old_path);
                          set_arc_from(L, border_a, node_a, std::vector<V>(path.begin(), path.begin() + std::ptrdiff_t(q) + 1));
                          set_arc_from(L, border_b, n, std::vector<V>(path.begin() + std::ptrdiff_t(q), path.end()));
                          L.patches[pa_index].faces = std::move(faces_of[0]);
                          L.patches[pb_index].faces = std::move(faces_of[1]);
                        });
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// Moves the layout's nodes whose corners are far from right angles (see the file
/// comment), in node order, for up to `sweeps` sweeps or until a sweep moves none. Nodes on
/// the mesh's border slide along it (relocate_border_node()). The result is valid whenever `L` was
/// (checked: throws Internal_error("invalid_layout") otherwise). Deterministic.
template <class Point_3>
Node_relocation_result relocate_layout_nodes(Polycube_layout<Point_3>& L, int sweeps = 2)
{
  Node_relocation_result result;
  // A node at the end of an arc inside the solid stays: the segment is a box edge.
  std::vector<bool> fixed(L.nodes.size(), false);
  for(const auto& a : L.arcs)
    if(a.inside) fixed[a.nodes[0]] = fixed[a.nodes[1]] = true;
  std::tie(result.nodes_moved, result.sweeps) = internal::sweep_layout(L, sweeps, L.nodes.size(), "node relocation", [&](std::size_t n) {
    if(fixed[n]) return false;
    return is_border(L.nodes[n], L.mesh) ? internal::relocate_border_node(L, n, result) : internal::relocate_node(L, n, result);
  });
  return result;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_LAYOUT_NODE_RELOCATION_H
