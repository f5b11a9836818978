// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Cuboid_decomposition: builds the Polycube_layout of a surface of any genus and boundary
// count (reference §2.2.2, §1.2.3).
//
// Pants path (chi < 0): every pants patch of Pants_decomposition becomes 4 cuboids (3 arms
// and a centre). As in §2.2.2, each boundary cycle gets 2 seed points and 4 corners at 1/8,
// 3/8, 5/8, 7/8 of its arc length from a seed, and corners placed by one pants are imposed on
// the pants across the cycle (corner transfer). Where the reference finds the seeds with a
// circular conformal map and traces the polyedges in three cylindrical parameterizations,
// this implementation cuts the pants into two hexagonal disks along three cutting curves
// W (shortest paths joining the seeds of two boundaries, so W passes the "crotch" between
// them like the gradient lines through the saddles of §2.2.2.1), maps each hexagon onto a
// convex polygon with positive (mean-value) weights, and draws the arcs of its half of the
// polycube there as straight segments, refining the mesh with exact predicates: one convex
// domain per half keeps all arcs free of crossings by construction. The seed of a free
// boundary is its point closest to the neighbour it connects to; the other seed is opposite
// by arc length.
//
// chi >= 0 (left out by the reference): a sphere is split into two disks by the bisector of
// two far points and becomes one cube (6 belt nodes, one cube corner inside each disk), or,
// asked (`sphere_chain`) and long enough, a chain of cuboids between caps at those points; a
// disk becomes one cube whose top is the boundary loop; a cylinder, cut open along a
// shortest path between its loops, becomes a chain of cuboids in a rectangle; a torus, cut
// along its handle loop (meridian) and a closed seam crossing it once, becomes a ring of at
// least 3 cuboids.

#ifndef CGAL_POLYCUBE_IGA_CUBOID_DECOMPOSITION_H
#define CGAL_POLYCUBE_IGA_CUBOID_DECOMPOSITION_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/IO/read_triangle_mesh.h>
#include <CGAL/Polycube_IGA/Pants_decomposition.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Polycube_IGA/parameters.h>
#include <CGAL/Polycube_IGA/internal/bbox_diagonal.h>
#include <CGAL/Polycube_IGA/internal/edge_length.h>
#include <CGAL/Polycube_IGA/internal/feature_curves.h>
#include <CGAL/Polycube_IGA/internal/layout_assembly.h>
#include <CGAL/Polycube_IGA/internal/level_set_measures.h>
#include <CGAL/Polycube_IGA/internal/loop_corners.h>
#include <CGAL/Polycube_IGA/internal/mesh_graph.h>
#include <CGAL/Polycube_IGA/internal/mesh_refinement.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>
#include <CGAL/Polycube_IGA/internal/orthogonal_grid.h>
#include <CGAL/Polycube_IGA/internal/polycube_map.h>
#include <CGAL/Polycube_IGA/internal/piece_layout.h>
#include <CGAL/Polycube_IGA/internal/shortest_path_tree.h>

#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

template <class P>
using Piece_mesh = CGAL::Surface_mesh<P>;

/// Border loops of a mesh, each as vertices in the order of the halfedges opposite to its
/// border halfedges (faces on the left), starting at its smallest vertex; loops sorted by
/// that vertex.
template <class P>
std::vector<std::vector<typename Piece_mesh<P>::Vertex_index>> all_border_loops(const Piece_mesh<P>& m)
{
  using V = typename Piece_mesh<P>::Vertex_index;
  std::vector<std::vector<V>> loops;
  std::vector<bool> seen(num_halfedges(m), false);
  for(auto h0 : halfedges(m)) {
    if(!is_border(h0, m) || seen[h0]) continue;
    std::vector<V> loop;
    auto h = h0;
    do {
      seen[h] = true;
      loop.push_back(target(h, m)); // border halfedges run against the faces' orientation
      h = prev(h, m);
    } while(h != h0);
    std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    loops.push_back(loop);
  }
  std::sort(loops.begin(), loops.end(), [](const auto& a, const auto& b) { return a.front() < b.front(); });
  return loops;
}

/// Cumulative 3D arc length along a closed loop (size n+1, last = total).
template <class P>
std::vector<double> loop_arc_length(const Piece_mesh<P>& m, const std::vector<typename Piece_mesh<P>::Vertex_index>& loop)
{
  std::vector<double> s(loop.size() + 1, 0.);
  for(std::size_t i = 0; i < loop.size(); ++i) s[i + 1] = s[i] + edge_length(m, loop[i], loop[(i + 1) % loop.size()]);
  return s;
}

/// Arc length between loop vertices `i` and `j` the shorter way round (`s` as
/// loop_arc_length()).
inline double loop_gap(const std::vector<double>& s, std::size_t i, std::size_t j)
{
  const double g = std::abs(s[i] - s[j]);
  return std::min(g, s.back() - g);
}

/// Index of the loop vertex closest in arc length to `target` (taken modulo the length),
/// measured from index `from` forwards.
inline std::size_t at_arc_length(const std::vector<double>& s, std::size_t from, double target)
{
  const std::size_t n = s.size() - 1;
  const double total = s.back();
  double t = std::fmod(s[from] + target, total);
  if(t < 0) t += total;
  std::size_t best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for(std::size_t i = 0; i < n; ++i) {
    double d = std::abs(s[i] - t);
    d = std::min(d, total - d);
    if(d < bd) {
      bd = d;
      best = i;
    }
  }
  return best;
}

/// Turning, in degrees, of the mesh's border at its vertex `v` within the surface: 180 minus
/// the angles of its faces there (0 where the border runs straight, 90 at a square notch's
/// corner, -90 at a square step's).
template <class P>
double border_turn(const Piece_mesh<P>& m, typename Piece_mesh<P>::Vertex_index v)
{
  double sum = 0.;
  for(auto h : CGAL::halfedges_around_target(halfedge(v, m), m)) {
    if(is_border(h, m)) continue;
    const auto a = m.point(source(h, m)) - m.point(v), b = m.point(target(next(h, m), m)) - m.point(v);
    const double la = std::sqrt(CGAL::to_double(a.squared_length())), lb = std::sqrt(CGAL::to_double(b.squared_length()));
    if(la > 0. && lb > 0.) sum += std::acos(std::clamp(CGAL::to_double(a * b) / (la * lb), -1., 1.));
  }
  return 180. - sum * 180. / CGAL_PI;
}

/// The corners `c` (loop indices, `s` as loop_arc_length()), each one that is within 1/16 of
/// the loop of a step (a vertex where the border turns by over 45 degrees within the surface,
/// border_turn()) moved to the nearest vertex that is not, and is 1/8 of the loop from the
/// other corners; empty if none moved. A corner at a step's end has a side that turns at once
/// along the step: blade.off's is a corner of 172 degrees on the surface.
template <class P>
std::optional<std::array<std::size_t, 4>> clear_of_steps(const Piece_mesh<P>& m,
                                                         const std::vector<typename Piece_mesh<P>::Vertex_index>& loop,
                                                         const std::vector<double>& s, std::array<std::size_t, 4> c)
{
  const std::size_t n = loop.size();
  const double total = s.back();
  auto gap = [&](std::size_t i, std::size_t j) { return loop_gap(s, i, j); };
  std::vector<std::size_t> steps;
  for(std::size_t i = 0; i < n; ++i)
    if(std::abs(border_turn(m, loop[i])) > 45.) steps.push_back(i);
  auto clear = [&](std::size_t i) {
    for(std::size_t j : steps)
      if(gap(i, j) < total / 16.) return false;
    return true;
  };
  bool moved = false;
  for(std::size_t k = 0; k < 4; ++k) {
    if(clear(c[k])) continue;
    std::size_t best = n;
    for(std::size_t i = 0; i < n; ++i) {
      bool apart = clear(i);
      for(std::size_t l = 0; l < 4 && apart; ++l)
        if(l != k && gap(i, c[l]) < total / 8.) apart = false;
      if(apart && (best == n || gap(i, c[k]) < gap(best, c[k]))) best = i;
    }
    if(best == n) continue;
    c[k] = best;
    moved = true;
  }
  if(!moved) return std::nullopt;
  std::sort(c.begin(), c.end());
  return c;
}

/// The loop vertex within `window` of arc length of `at` where the loop runs straightest in
/// the surface's tangent plane, when the loop turns by more than 30 degrees at `at`; else
/// `at`. A corner on a tooth of a zigzag boundary (a mesh cut by deleting faces) gives its
/// patch a corner far from a right angle, and the slab under it a boundary side that turns
/// over (ybranch_jagged.off at 16 samples).
template <class P>
std::size_t straightest_near(const Mesh_graph<Piece_mesh<P>>& g, const std::vector<Eigen::Vector3d>& normal,
                             const std::vector<typename Piece_mesh<P>::Vertex_index>& loop, const std::vector<double>& s,
                             std::size_t at, double window)
{
  const std::size_t n = loop.size();
  auto turn = [&](std::size_t i) { // degrees
    const Eigen::Vector3d& N = normal[std::size_t(loop[i])];
    Eigen::Vector3d in = g.position[std::size_t(loop[i])] - g.position[std::size_t(loop[(i + n - 1) % n])];
    Eigen::Vector3d out = g.position[std::size_t(loop[(i + 1) % n])] - g.position[std::size_t(loop[i])];
    in -= N.dot(in) * N;
    out -= N.dot(out) * N;
    return std::atan2(in.cross(out).norm(), in.dot(out)) * 180. / CGAL_PI;
  };
  double best_turn = turn(at), best_gap = 0.;
  if(best_turn <= 30.) return at;
  std::size_t best = at;
  for(std::size_t i = 0; i < n; ++i) {
    const double gap = loop_gap(s, i, at);
    if(gap > window) continue;
    const double t = turn(i);
    if(t < best_turn || (t == best_turn && gap < best_gap)) {
      best = i;
      best_turn = t;
      best_gap = gap;
    }
  }
  return best;
}

/// Shortest vertex path (by `w`, per edge of `g`) from any root to `target`, entering no
/// blocked vertex but the target; empty when unreachable.
template <class P>
std::vector<int> shortest_vertex_path(const Mesh_graph<Piece_mesh<P>>& g, const std::vector<int>& roots, int target,
                                      std::vector<bool> blocked, const std::vector<double>& w)
{
  blocked[std::size_t(target)] = false;
  const Shortest_path_tree t = shortest_path_tree(g, roots, w, blocked);
  if(!std::isfinite(t.distance[std::size_t(target)])) return {};
  std::vector<int> path{target};
  while(t.parent_edge[std::size_t(path.back())] >= 0) path.push_back(g.other_vertex(t.parent_edge[std::size_t(path.back())], path.back()));
  std::reverse(path.begin(), path.end());
  return path;
}

/// The same by 3D length.
template <class P>
std::vector<int> shortest_vertex_path(const Mesh_graph<Piece_mesh<P>>& g, const std::vector<int>& roots, int target,
                                      std::vector<bool> blocked)
{
  std::vector<double> w(std::size_t(g.number_of_edges()));
  for(int e = 0; e < g.number_of_edges(); ++e) w[std::size_t(e)] = g.length(e);
  return shortest_vertex_path(g, roots, target, std::move(blocked), w);
}

template <class P>
std::vector<double> distances_from(const Mesh_graph<Piece_mesh<P>>& g, const std::vector<int>& roots)
{
  std::vector<double> w(std::size_t(g.number_of_edges()));
  for(int e = 0; e < g.number_of_edges(); ++e) w[std::size_t(e)] = g.length(e);
  return shortest_path_tree(g, roots, w).distance;
}

/// Two far vertices p and q of a connected surface (double sweep from vertex 0) and the
/// distance fields from them, which a closed genus-0 surface's cube and chain both start from.
struct Far_pair
{
  int p = 0, q = 0;
  std::vector<double> dp, dq;
};

template <class P>
Far_pair far_pair(const Mesh_graph<Piece_mesh<P>>& g)
{
  auto farthest = [](const std::vector<double>& d) { return int(std::max_element(d.begin(), d.end()) - d.begin()); };
  Far_pair out;
  out.p = farthest(distances_from<P>(g, {0}));
  out.dp = distances_from<P>(g, {out.p});
  out.q = farthest(out.dp);
  out.dq = distances_from<P>(g, {out.q});
  return out;
}

inline std::size_t read_parent(const std::vector<std::size_t>& map, std::size_t i) { return map[i]; }

template <class P>
std::vector<std::size_t> vertex_parents(const Piece_mesh<P>& m)
{
  auto pm = m.template property_map<typename Piece_mesh<P>::Vertex_index, std::size_t>("v:parent");
  std::vector<std::size_t> out(num_vertices(m), no_parent);
  if(!pm.second) return out;
  for(auto v : vertices(m)) out[v] = pm.first[v];
  return out;
}

[[noreturn]] inline void layout_failure(const std::string& what)
{
  throw Internal_error("cuboid_decomposition_failed", what);
}

/// Collects nodes and arcs in global (final mesh) terms while pieces are processed.
struct Layout_builder
{
  std::vector<std::size_t> node_vertex;                  ///< final-mesh vertex of each node
  std::vector<std::array<std::size_t, 2>> arc_nodes;
  std::vector<std::vector<std::size_t>> arc_path;        ///< final-mesh vertices
  std::vector<bool> arc_inside;                          ///< Polycube_layout::Arc::inside
  std::vector<Interior_quad> interior;
  std::vector<std::array<std::size_t, 8>> cuboids;
  std::vector<int> cuboid_pants;
  std::map<std::size_t, std::size_t> node_of_vertex;

  std::size_t node(std::size_t v)
  {
    auto it = node_of_vertex.find(v);
    if(it != node_of_vertex.end()) return it->second;
    node_of_vertex.emplace(v, node_vertex.size());
    node_vertex.push_back(v);
    return node_vertex.size() - 1;
  }
  void arc(const std::vector<std::size_t>& path, bool inside = false)
  {
    if(path.size() < 2) layout_failure("an arc has fewer than two vertices");
    arc_nodes.push_back({{node(path.front()), node(path.back())}});
    arc_path.push_back(path);
    arc_inside.push_back(inside);
  }
  /// Splits a closed loop of final-mesh vertices into arcs at the vertices that are nodes.
  void loop_arcs(const std::vector<std::size_t>& loop)
  {
    std::size_t first = loop.size();
    for(std::size_t i = 0; i < loop.size(); ++i)
      if(node_of_vertex.count(loop[i])) {
        first = i;
        break;
      }
    if(first == loop.size()) layout_failure("a loop carries no node");
    std::vector<std::size_t> cur{loop[first]};
    for(std::size_t k = 1; k <= loop.size(); ++k) {
      const std::size_t v = loop[(first + k) % loop.size()];
      cur.push_back(v);
      if(node_of_vertex.count(v)) {
        arc(cur);
        cur.assign(1, v);
      }
    }
  }
};

/// Writes the builder into the layout on `mesh` (whose vertices the builder's indices are).
template <class P>
Polycube_layout<P> finish_layout(Piece_mesh<P>&& mesh, Layout_builder& b, Layout_class cls, int genus, std::size_t boundary_loops,
                                 std::size_t pants)
{
  using V = typename Piece_mesh<P>::Vertex_index;
  Polycube_layout<P> L;
  L.layout_class = cls;
  L.genus = genus;
  L.boundary_loops = boundary_loops;
  L.number_of_pants = pants;
  L.mesh = std::move(mesh);
  // Surface patches are counter-clockwise seen from outside, which later stages read as
  // "grid u x v points out of the solid" (the boundary layer's inward normal, the cuboids'
  // handedness). An input whose faces point inwards (head.off) would put the boundary layer
  // outside the solid, so such a surface is turned over before its patches are walked; the
  // capped volume decides, as for the handle/tunnel test. Vertices and faces keep their indices.
  L.turned_outwards = Mesh_graph<Piece_mesh<P>>(L.mesh, get(CGAL::vertex_point, L.mesh)).capped_signed_volume() < 0.;
  if(L.turned_outwards) CGAL::Polygon_mesh_processing::reverse_face_orientations(L.mesh);
  for(std::size_t v : b.node_vertex) L.nodes.push_back(V(std::uint32_t(v)));
  for(std::size_t a = 0; a < b.arc_path.size(); ++a) {
    typename Polycube_layout<P>::Arc arc;
    arc.nodes = b.arc_nodes[a];
    for(std::size_t v : b.arc_path[a]) arc.vertices.push_back(V(std::uint32_t(v)));
    arc.inside = a < b.arc_inside.size() && b.arc_inside[a];
    L.arcs.push_back(std::move(arc));
  }
  assemble_layout(L, b.interior, b.cuboids, b.cuboid_pants);
  return L;
}

/// Index of the square corner (a,b) in cyclic order (0,0), (1,0), (1,1), (0,1).
inline int cyclic_corner(int a, int b) { return b == 0 ? a : 3 - a; }

/// The cube of a disk laid out as disk() does: corners (i,j,0) on the inner square `bottom`,
/// (i,j,1) on the border's `top`, both in the border's cyclic order.
inline std::array<std::size_t, 8> disk_cube(const std::array<std::size_t, 4>& bottom, const std::array<std::size_t, 4>& top)
{
  std::array<std::size_t, 8> cube{};
  for(int k = 0; k < 2; ++k)
    for(int b = 0; b < 2; ++b)
      for(int a = 0; a < 2; ++a) cube[std::size_t(a + 2 * b + 4 * k)] = (k == 0 ? bottom : top)[std::size_t(cyclic_corner(a, b))];
  return cube;
}

/// The graph of disk(): the border corners at loop indices `corner` (increasing) on a unit
/// square, an inner square holding `area_fraction` of the piece, each corner joined to its
/// inner one and the inner ones around.
inline Piece_graph disk_graph(const std::array<std::size_t, 4>& corner, double area_fraction)
{
  const Eigen::Vector2d square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  Piece_graph pg;
  for(std::size_t i = 0; i < 4; ++i) {
    pg.border_nodes.push_back(corner[i]);
    pg.anchors.push_back({corner[i], square[i]});
    pg.interior_uv.push_back(square[i]);
    pg.segments.push_back({{i, 4 + i}});
    pg.segments.push_back({{4 + i, 4 + (i + 1) % 4}});
  }
  pg.interior_area_fraction = area_fraction;
  return pg;
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// Builds the polycube layout of a surface mesh (see the file comment). Named parameters:
/// `surface_topology` (reuse a topology result), `cut_criterion`, `symmetry_plane`,
/// `criterion_strength`, `cut_pair_trials`, `cuts_away_from_holes` (passed to the pants stage),
/// `maximum_refinements` (default 2: midpoint subdivisions of the whole mesh when a cut or arc
/// finds no room), `belt_phase`
/// (default 0, in [0, 1): on a closed genus-0 surface, how far the six belt nodes are moved
/// along the belt, as a fraction of the zigzag's period, a third of the belt),
/// `sphere_chain` (default false: a closed genus-0 surface is one cube; true: one long
/// enough for three cube-like cuboids or more, and not a box, is a chain of them between caps
/// round its two farthest points, sphere_chain()), `orthogonal_blocks` (default true: a closed
/// CAD block whose faces are all planar and perpendicular to three axes, other than a box, is
/// split into the boxes between its faces' planes, orthogonal_blocks(); false: laid out by
/// its genus as any other surface), `polycube_map` (default false: true lays a closed surface
/// out on the boxes of a polycube map of it, polycube_blocks(), and throws
/// Internal_error("no_polycube_map") with the reason when it makes none, Invalid_input_error
/// ("wrong_topology") for a surface with a boundary), `corners_off_steps` (default false: on a cylinder, section corners that the seam puts within
/// 1/16 of a loop of a step of the loop, where it turns by over 45 degrees within the surface,
/// move off it; internal::clear_of_steps()), `balance_pants_corners` (default false: each
/// pants half's four centre nodes stay where Tutte's rule puts them in its convex map; true
/// moves them to where their five arcs meet at even angles on the mesh,
/// internal::balance_piece_graph_corners(): better corners, but no volume more valid).
template <class TriangleMesh>
class Cuboid_decomposition
{
public:
  using Point = typename boost::property_traits<typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type>::value_type;
  using Mesh = CGAL::Surface_mesh<Point>;
  using Layout = Polycube_layout<Point>;
  using V = typename Mesh::Vertex_index;
  using F = typename Mesh::Face_index;

  template <class NamedParameters = parameters::Default_named_parameters>
  Layout operator()(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values()) const
  {
    using CGAL::parameters::get_parameter;
    if(num_faces(tm) == 0) throw Invalid_input_error("empty", "the mesh has no faces");
    const int max_refinements = std::max(0, int(option(np, internal_np::maximum_refinements, 2)));
    const double belt_phase = double(option(np, internal_np::belt_phase, 0.));
    const bool off_steps = option(np, internal_np::corners_off_steps, false);
    const bool balance = option(np, internal_np::balance_pants_corners, false);
    const bool chain = option(np, internal_np::sphere_chain, false);
    const bool blocks = option(np, internal_np::orthogonal_blocks, true);
    const bool polycube = option(np, internal_np::polycube_map, false);
    if(!(belt_phase >= 0. && belt_phase < 1.)) throw Invalid_input_error("invalid_parameter", "belt_phase must be in [0, 1)");
    Surface_topology_result<TriangleMesh> topo = internal::given_or_computed_topology(tm, get_parameter(np, internal_np::surface_topology));
    if(polycube) {
      if(topo.number_of_boundary_loops() > 0)
        throw Invalid_input_error("wrong_topology", "a polycube map needs a closed surface; this one has " +
                                                      std::to_string(topo.number_of_boundary_loops()) + " boundary loop(s)");
      std::string why;
      if(std::optional<Layout> L = polycube_blocks(copy_of(tm), topo.genus, &why)) {
        carry_input_indices(tm, *L);
        return std::move(*L);
      }
      throw Internal_error("no_polycube_map", why);
    }
    // A CAD block of any genus is its boxes, before any pants stage: every other layout
    // crosses its sharp edges.
    if(blocks && topo.number_of_boundary_loops() == 0)
      if(std::optional<Layout> L = orthogonal_blocks(copy_of(tm), topo.genus)) {
        carry_input_indices(tm, *L);
        return std::move(*L);
      }
    // Where a boundary is too coarse for its corners or a half has no room for its arcs, the
    // whole surface is subdivided at edge midpoints (the shape does not change, the input's
    // vertices keep their indices) and the construction starts again. On the pants path the
    // decomposition is kept and carried to the finer mesh: recomputed there, its cycles would
    // hug each other again (two shortest loops around one thin handle stay one edge apart).
    std::optional<Pants_decomposition_result<TriangleMesh>> pd;
    if(topo.euler_characteristic < 0)
      pd = Pants_decomposition<TriangleMesh>()(
        tm, parameters::surface_topology(topo)
              .cut_criterion(option(np, internal_np::cut_criterion, Cut_criterion::LENGTH))
              .symmetry_plane(option(np, internal_np::symmetry_plane, Cut_criterion_options().symmetry_plane))
              .criterion_strength(option(np, internal_np::criterion_strength, 1.0))
              .cut_pair_trials(option(np, internal_np::cut_pair_trials, default_cut_pair_trials))
              .cuts_away_from_holes(option(np, internal_np::cuts_away_from_holes, false)));
    // Refinement keeps the shape, so the bounding box is the input's.
    const double diagonal = internal::mesh_bbox_diagonal(tm);
    std::shared_ptr<TriangleMesh> refined;
    for(int attempt = 0;; ++attempt) {
      const TriangleMesh& mesh = refined ? *refined : tm;
      try {
        Layout L = pd ? pants_layout(tm, *pd, balance) : layout_of(mesh, topo, belt_phase, off_steps, chain);
        // A cube's bottom can be a protrusion again (a long one): a few rounds.
        for(int round = 0; pd && round < 8; ++round) {
          const std::size_t cuboids = L.cuboids.size();
          L = with_protrusions_extruded(std::move(L), diagonal);
          if(L.cuboids.size() == cuboids) break;
        }
        carry_input_indices(tm, L);
        return L;
      } catch(const Internal_error& e) {
        if(attempt >= max_refinements)
          throw Internal_error(e.reason(), std::string(e.what()) + " (after " + std::to_string(attempt) +
                                             " refinement(s) of the mesh; maximum_refinements allows more)");
      }
      if(pd) {
        pd = refined_pants_decomposition(tm, *pd);
        continue;
      }
      auto next = std::make_shared<TriangleMesh>(mesh);
      internal::subdivide_at_edge_midpoints(*next, get(CGAL::vertex_point, *next));
      refined = next;
      topo = Surface_topology<TriangleMesh>()(*refined, parameters::compute_tunnel_loops(false));
    }
  }

  /// The layout with a cube of its own under SURFACE patch `patch` of `L`: the patch becomes
  /// an interface and the cube is laid out in it as a protrusion's (see
  /// with_protrusions_extruded()), its bottom a square around `v`, a vertex of `L.mesh` inside
  /// the patch (not on its border). For a part of the shape that the volume misses
  /// (build_trivariate_model(), `missing_part_cubes`): the patch's map to the square shrinks
  /// it, while a bottom of its own gets a grid of its own. `diagonal` is the bounding box's.
  /// Empty when the cube does not fit (`v` on the border or outside the patch, a border
  /// the cube's top cannot take).
  static std::optional<Layout> with_cube_under(const Layout& L, std::size_t patch, V v, double diagonal)
  {
    if(patch >= L.patches.size() || L.patches[patch].kind != Layout::SURFACE) return std::nullopt;
    Layout out = with_protrusions_extruded(L, diagonal, std::make_pair(patch, v));
    if(out.cuboids.size() != L.cuboids.size() + 1) return std::nullopt;
    return out;
  }

  /// How nearly `tm` is an orthogonal polyhedron (internal::polycube_alignment()): the
  /// area-weighted alignment of its normals with its polycube frame's axes, and whether every
  /// face is within 2 degrees of one.
  static std::pair<double, bool> polycube_alignment(const TriangleMesh& tm) { return internal::polycube_alignment(copy_of(tm)); }

private:
  /// The classes with Euler characteristic >= 0, which have no pants (item 3 of the issue).
  static Layout layout_of(const TriangleMesh& tm, const Surface_topology_result<TriangleMesh>& topo, double belt_phase,
                          bool off_steps, bool chain)
  {
    const int g = topo.genus;
    const std::size_t b = topo.number_of_boundary_loops();
    if(g == 0 && b == 0) return sphere(copy_of(tm), belt_phase, chain);
    if(g == 0 && b == 1) return disk(copy_of(tm));
    if(g == 0 && b == 2) return cylinder(copy_of(tm), off_steps);
    return torus(tm, topo);
  }

  /// A Surface_mesh copy with compact indices (the pieces rely on index order).
  static Mesh copy_of(const TriangleMesh& tm)
  {
    Mesh m;
    std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, V> vmap;
    for(auto v : vertices(tm)) vmap[v] = m.add_vertex(get(CGAL::vertex_point, tm, v));
    for(auto f : faces(tm)) {
      std::vector<V> vs;
      for(auto v : vertices_around_face(halfedge(f, tm), tm)) vs.push_back(vmap[v]);
      m.add_face(vs);
    }
    return m;
  }

  /// "v:input_index": input vertices keep theirs (or their own index), others get -1.
  static void carry_input_indices(const TriangleMesh& tm, Layout& L)
  {
    auto given = tm.template property_map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, std::size_t>(
      input_vertex_index_property());
    auto out = L.mesh.template add_property_map<V, std::size_t>(input_vertex_index_property(), std::size_t(-1)).first;
    const std::size_t n = L.remeshed ? 0 : num_vertices(tm);
    for(auto v : vertices(L.mesh))
      out[v] = std::size_t(v) >= n ? std::size_t(-1)
             : given.second ? given.first[typename boost::graph_traits<TriangleMesh>::vertex_descriptor(std::uint32_t(std::size_t(v)))]
                            : std::size_t(v);
    // A remeshed surface's faces are none of the input's either (the copy carried the map).
    if(L.remeshed)
      if(auto faces_in = L.mesh.template property_map<F, std::size_t>(input_face_index_property()); faces_in.second)
        for(auto f : faces(L.mesh)) faces_in.first[f] = std::size_t(-1);
  }

  using Embedding = internal::Piece_graph_embedding<Point>;

  /// Final-mesh vertex of vertex `v` of piece `k`.
  static std::size_t final_vertex(const internal::Glued_mesh<Point>& gl, std::size_t k, V v)
  {
    return std::size_t(gl.piece_to_result[k][std::size_t(v)]);
  }
  static std::vector<std::size_t> final_path(const internal::Glued_mesh<Point>& gl, std::size_t k, const std::vector<V>& path)
  {
    std::vector<std::size_t> out;
    for(V v : path) out.push_back(final_vertex(gl, k, v));
    return out;
  }

  // ------------------------------------------------------------ protrusions ----------
  /// The layout with every protrusion given a cube of its own. A protrusion is a surface
  /// patch whose faces reach farther from its border (along the mesh's edges) than a quarter
  /// of the border's length, deeper than a hemisphere on that border, and than 1% of the
  /// bounding box's `diagonal` (on the test meshes whose volumes are valid, every patch stays
  /// within 0.15 of its border's length; femur.off 0.89, elephant.off 0.34). A pants patch whose
  /// cycles all lie at one end of the shape (femur.off: two small handles at the knee, the
  /// whole shaft in one patch) leaves the rest of it in one face, which a map to the square
  /// shrinks to nothing (53% of the diagonal away from the volume). The patch becomes an
  /// interface, and the cube under it is laid out in it as disk() lays out a disk: the
  /// patch's corners on top, the bottom a square around the vertex farthest from the border,
  /// as large as a cube's face on it (at most a fifth of the patch). The operator() runs
  /// this again, up to 8 rounds, while a bottom is still a protrusion (the rest of a long
  /// shaft). The layout is returned unchanged if any of its cubes does not fit.
  /// `requested` (SURFACE patch, mesh vertex inside it): that patch alone gets the cube,
  /// its bottom around that vertex, whatever the criterion says (with_cube_under()).
  static Layout with_protrusions_extruded(Layout L, double diagonal,
                                          std::optional<std::pair<std::size_t, V>> requested = std::nullopt)
  {
    using namespace internal;
    // Without the parent map of the first gluing: glue_pieces() would take the layout's mesh
    // for a piece of a larger one. Vertex and face indices stay, so the arcs remain valid.
    Mesh m = L.mesh;
    if(auto fp = m.template property_map<typename Mesh::Face_index, std::size_t>("f:parent"); fp.second) m.remove_property_map(fp.first);
    std::vector<bool> cut(num_edges(m), false);
    for(const auto& a : L.arcs)
      for(std::size_t i = 0; !a.inside && i + 1 < a.vertices.size(); ++i) cut[edge(halfedge(a.vertices[i], a.vertices[i + 1], m).first, m)] = true;
    // Surface patches come first, numbered by their smallest face as the pieces are.
    std::vector<Mesh> pieces = cut_into_pieces(m, cut);
    std::size_t surface = 0;
    while(surface < L.patches.size() && L.patches[surface].kind == Layout::SURFACE) ++surface;
    if(pieces.size() != surface) return L;
    struct Cube
    {
      std::size_t piece;
      std::vector<V> loop;
      double around;                     // the loop's length
      std::size_t far_end;               // the piece's vertex farthest from the loop
      std::array<std::size_t, 4> corner; // loop indices, increasing
      std::array<std::size_t, 4> top;    // their vertices of m
      Embedding e;
    };
    std::vector<Cube> cubes;
    for(std::size_t k = 0; k < surface; ++k) {
      if(num_faces(pieces[k]) != L.patches[k].faces.size()) return L;
      if(requested && requested->first != k) continue;
      std::vector<V> loop = border_loop(pieces[k]);
      const Mesh_graph<Mesh> g(pieces[k], get(CGAL::vertex_point, pieces[k]));
      std::vector<int> roots;
      for(V v : loop) roots.push_back(int(v));
      const std::vector<double> d = distances_from<Point>(g, roots);
      const double around = loop_arc_length(pieces[k], loop).back();
      if(requested) {
        const std::vector<std::size_t> par = vertex_parents(pieces[k]);
        for(V v : vertices(pieces[k]))
          if(par[v] == std::size_t(requested->second) && d[v] > 0.)
            cubes.push_back({k, std::move(loop), around, std::size_t(v), {}, {}, {}});
        break;
      }
      // Deeper than 1% of the diagonal: half of what the volume may miss by default.
      const auto far = std::max_element(d.begin(), d.end());
      if(*far > 0.25 * around && *far > 0.01 * diagonal)
        cubes.push_back({k, std::move(loop), around, std::size_t(far - d.begin()), {}, {}, {}});
    }
    if(cubes.empty()) return L;
    Layout_builder bld;
    for(V n : L.nodes) bld.node(std::size_t(n));
    for(const auto& a : L.arcs) bld.arc(as_indices(a.vertices), a.inside);
    for(const auto& p : L.patches)
      if(p.kind != Layout::SURFACE) bld.interior.push_back({int(p.kind), p.corners});
    for(const auto& c : L.cuboids) {
      bld.cuboids.push_back(c.nodes);
      bld.cuboid_pants.push_back(c.pants);
    }
    try {
      for(Cube& c : cubes) {
        const std::vector<std::size_t> par = vertex_parents(pieces[c.piece]);
        std::size_t found = 0;
        for(std::size_t i = 0; i < c.loop.size(); ++i)
          for(std::size_t n : L.patches[c.piece].corners)
            if(par[c.loop[i]] == std::size_t(L.nodes[n])) {
              if(found == 4) return L;
              c.corner[found] = i;
              c.top[found++] = par[c.loop[i]];
            }
        if(found != 4) return L;
        // The bottom as large as a cube's face on this border: the far end of the protrusion.
        const double area = CGAL::to_double(CGAL::Polygon_mesh_processing::area(pieces[c.piece]));
        Piece_graph pg = disk_graph(c.corner, std::clamp(c.around * c.around / 16. / area, 1e-4, 0.2));
        pg.interior_center_vertex = c.far_end;
        c.e = embed_piece_graph(pieces[c.piece], c.loop, pg);
      }
      Glued_mesh<Point> gl = glue_pieces(m, pieces);
      for(const Cube& c : cubes) {
        std::array<std::size_t, 4> top{}, bottom{};
        for(std::size_t i = 0; i < 4; ++i) {
          top[i] = bld.node(c.top[i]);
          bottom[i] = bld.node(final_vertex(gl, c.piece, c.e.vertex[4 + i]));
        }
        for(const auto& path : c.e.path) bld.arc(final_path(gl, c.piece, path));
        bld.interior.push_back({int(Layout::INTERFACE), top});
        bld.cuboids.push_back(disk_cube(bottom, top));
        int pants = -1;
        for(const auto& cu : L.cuboids)
          if(std::find(cu.patches.begin(), cu.patches.end(), c.piece) != cu.patches.end()) pants = cu.pants;
        bld.cuboid_pants.push_back(pants);
      }
      Layout out = finish_layout(std::move(gl.mesh), bld, L.layout_class, L.genus, L.boundary_loops, L.number_of_pants);
      out.turned_outwards = out.turned_outwards != L.turned_outwards;
      return out;
    } catch(const Internal_error&) {
      return L;
    }
  }

  // ---------------------------------------------------------------- sphere -----------
  /// A closed genus-0 mesh whose sharp edges (more than 45 degrees) form the edges of a
  /// cube, and nothing else (a box exported from CAD), is laid out on them: its 8 corners are
  /// the nodes, its 12 feature curves the arcs, its 6 sides the patches. The generic cube of
  /// sphere() would cross the creases, which no smooth face follows (cube-meshed.off: 6 of 12
  /// patches uncertified, 5.1% of the diagonal off). Empty when the features are anything else.
  static std::optional<Layout> feature_cube(const Mesh& m)
  {
    using namespace internal;
    const Feature_curves fc = feature_curves(m, sharp_edges(m, 45.));
    if(fc.corners.size() != 8 || fc.curves.size() != 12 || fc.closed != 0) return std::nullopt;
    std::map<std::size_t, int> corner; // vertex -> corner number
    for(std::size_t c : fc.corners) {
      if(fc.sharp_degree[c] != 3) return std::nullopt;
      corner.emplace(c, int(corner.size()));
    }
    std::array<std::vector<int>, 8> adjacent;
    for(const auto& path : fc.curves) {
      const int a = corner.at(path.front()), b = corner.at(path.back());
      if(a == b || std::count(adjacent[std::size_t(a)].begin(), adjacent[std::size_t(a)].end(), b)) return std::nullopt;
      adjacent[std::size_t(a)].push_back(b);
      adjacent[std::size_t(b)].push_back(a);
    }
    // Cube coordinates as 3 bits: corner 0 at 000, its neighbours at 001, 010, 100, every
    // other corner the union of two coded neighbours; a cube graph iff each curve then
    // changes exactly one bit and all 8 codes differ.
    std::array<int, 8> code;
    code.fill(-1);
    code[0] = 0;
    for(std::size_t k = 0; k < 3; ++k) code[std::size_t(adjacent[0][k])] = 1 << k;
    for(int round = 0; round < 2; ++round)
      for(std::size_t c = 0; c < 8; ++c) {
        if(code[c] >= 0) continue;
        int bits = 0, known = 0;
        for(int d : adjacent[c])
          if(code[std::size_t(d)] >= 0 && code[std::size_t(d)] != 0) bits |= code[std::size_t(d)], ++known;
        if(known >= 2) code[c] = bits;
      }
    std::array<bool, 8> taken{};
    for(std::size_t c = 0; c < 8; ++c) {
      if(code[c] < 0 || code[c] > 7 || taken[std::size_t(code[c])]) return std::nullopt;
      taken[std::size_t(code[c])] = true;
    }
    for(std::size_t c = 0; c < 8; ++c)
      for(int d : adjacent[c]) {
        const int x = code[c] ^ code[std::size_t(d)];
        if(x != 1 && x != 2 && x != 4) return std::nullopt;
      }
    Layout_builder bld;
    std::array<std::size_t, 8> cube{};
    for(std::size_t c : fc.corners) cube[std::size_t(code[std::size_t(corner.at(c))])] = bld.node(c);
    for(const auto& path : fc.curves) bld.arc(path);
    bld.cuboids.push_back(cube);
    // The curves must cut the surface into 6 quads, the cube's sides: else the generic cube.
    try {
      Mesh copy = m;
      Layout L = finish_layout(std::move(copy), bld, Layout_class::sphere, 0, 0, 0);
      if(L.patches.size() != 6 || !L.validate().is_valid()) return std::nullopt;
      return L;
    } catch(const Internal_error&) {
      return std::nullopt;
    }
  }

  // ---------------------------------------------------------------- blocks -----------
  /// A closed CAD block of genus `genus` whose faces are all planar and perpendicular to three
  /// axes (internal/orthogonal_grid.h: an L, a T, a U, a bracket, a frame), split into the
  /// boxes between the planes of its faces: the grid planes are inserted into the mesh (the
  /// surface does not move), the boxes' corners are the nodes, the grid lines on the surface
  /// the arcs (every sharp edge among them; a box edge through the solid, such as a
  /// staircase's inner corner line, is an arc `inside`, a straight segment), the boxes the
  /// cuboids and the faces they share the interfaces. Any other layout would cross the sharp
  /// edges, which no smooth face follows (an L-block as a chain of cuboids: 2.4% of the
  /// diagonal off at a corner inside a cap). Empty for a box (feature_cube()), when a box
  /// corner would lie inside the solid (no mesh vertex can be its node), or when the boxes
  /// do not make a valid layout; `why` then says which, unless the mesh
  /// is not an orthogonal polyhedron at all.
  ///
  /// With `layout_class` polycube, `m` is a polycube map of a surface whose points are the
  /// map "v:original_point" of `m` (polycube_blocks()): the grid is that of the polycube, the
  /// layout's mesh the surface, and one box is a layout too.
  static std::optional<Layout> orthogonal_blocks(Mesh m, int genus, Layout_class layout_class = Layout_class::blocks,
                                                 std::string* why = nullptr)
  {
    using namespace internal;
    const std::optional<Orthogonal_grid> grid = orthogonal_grid(m, 2., 256, why);
    const long boxes = grid ? long(std::count(grid->inside.begin(), grid->inside.end(), true)) : 0;
    if(boxes < (layout_class == Layout_class::polycube ? 1 : 2)) return std::nullopt;
    const Orthogonal_grid& G = *grid;
    try {
      insert_grid_planes(m, G);
      // Each vertex's plane indices (-1: on none); grid points are the vertices on three.
      std::vector<std::array<int, 3>> at(num_vertices(m));
      std::map<std::array<int, 3>, std::size_t> vertex_at;
      auto coordinate = [&](V v, std::size_t k) { return G.coordinate(m.point(v), k); };
      for(V v : vertices(m)) {
        for(std::size_t k = 0; k < 3; ++k) at[std::size_t(v)][k] = G.plane_at(k, coordinate(v, k));
        const std::array<int, 3>& a = at[std::size_t(v)];
        if(a[0] >= 0 && a[1] >= 0 && a[2] >= 0 && !vertex_at.emplace(a, std::size_t(v)).second)
          layout_failure("two vertices at one grid point");
      }
      add_interior_corners(m, G, vertex_at, at);
      Layout_builder bld;
      auto node_at = [&](const std::array<int, 3>& a) {
        auto it = vertex_at.find(a);
        if(it == vertex_at.end()) layout_failure("a box corner is not a mesh vertex");
        return bld.node(it->second);
      };
      // The grid line from grid point a one step along axis k: the mesh path through the
      // vertices on that line.
      auto line_path = [&](const std::array<int, 3>& a, std::size_t k) {
        std::array<int, 3> b = a;
        ++b[k];
        node_at(a), node_at(b);
        // A box edge inside the solid (its four boxes all there) is the straight segment
        // between its ends, on the surface or interior nodes.
        if(G.edge_inside(a, k)) return std::vector<std::size_t>{vertex_at.at(a), vertex_at.at(b)};
        const double end = G.planes[k][std::size_t(b[k])];
        std::vector<std::size_t> path{vertex_at.at(a)};
        while(path.back() != vertex_at.at(b)) {
          const V x(std::uint32_t(path.back()));
          const double from = coordinate(x, k);
          std::optional<std::size_t> next;
          double best = std::numeric_limits<double>::infinity();
          for(V y : vertices_around_target(halfedge(x, m), m)) {
            const std::array<int, 3>& c = at[std::size_t(y)];
            bool on_line = true;
            for(std::size_t i = 0; i < 3; ++i)
              if(i != k && c[i] != a[i]) on_line = false;
            const double t = coordinate(y, k);
            if(on_line && t > from && t <= end + G.tolerance && t < best) best = t, next = std::size_t(y);
          }
          if(!next || path.size() > num_vertices(m)) layout_failure("a grid line is not a path of mesh edges");
          path.push_back(*next);
        }
        return path;
      };
      const std::array<int, 3> n = G.cells();
      std::set<std::pair<std::array<int, 3>, std::size_t>> lines; // (start, axis) of the arcs
      for(int l = 0; l < n[2]; ++l)
        for(int j = 0; j < n[1]; ++j)
          for(int i = 0; i < n[0]; ++i) {
            if(!G.is_inside({i, j, l})) continue;
            std::array<std::size_t, 8> cube{};
            for(int c = 0; c < 8; ++c) cube[std::size_t(c)] = node_at({i + (c & 1), j + ((c >> 1) & 1), l + (c >> 2)});
            bld.cuboids.push_back(cube);
            bld.cuboid_pants.push_back(-1);
            for(std::size_t k = 0; k < 3; ++k) {
              const std::size_t b = (k + 1) % 3, d = (k + 2) % 3;
              for(int s = 0; s < 4; ++s) {
                std::array<int, 3> start{i, j, l};
                start[b] += s & 1, start[d] += s >> 1;
                lines.insert({start, k});
              }
              // The face shared with the next box along k, corners in cyclic order.
              std::array<int, 3> next{i, j, l};
              ++next[k];
              if(!G.is_inside(next)) continue;
              Interior_quad q;
              q.kind = int(Layout::INTERFACE);
              for(int s = 0; s < 4; ++s) {
                std::array<int, 3> corner = next;
                corner[b] += s & 1, corner[d] += s >> 1;
                q.corners[std::size_t(cyclic_corner(s & 1, s >> 1))] = node_at(corner);
              }
              bld.interior.push_back(q);
            }
          }
      for(const auto& line : lines) bld.arc(line_path(line.first, line.second), G.edge_inside(line.first, line.second));
      auto original = m.template property_map<V, Point>("v:original_point");
      if(original.second) {
        for(V v : vertices(m)) m.point(v) = original.first[v];
        m.remove_property_map(original.first);
      }
      // An interior node placed outside the solid would turn its boxes over.
      CGAL::Side_of_triangle_mesh<Mesh, typename CGAL::Kernel_traits<Point>::Kernel> side(m);
      for(const auto& [a, v] : vertex_at)
        if(m.is_isolated(V(std::uint32_t(v))) && side(m.point(V(std::uint32_t(v)))) != CGAL::ON_BOUNDED_SIDE) {
          const Point& x = m.point(V(std::uint32_t(v)));
          if(why)
            *why = "a box corner inside the polycube falls outside the solid, at (" + std::to_string(CGAL::to_double(x.x())) + ", " +
                   std::to_string(CGAL::to_double(x.y())) + ", " + std::to_string(CGAL::to_double(x.z())) + ")";
          return std::nullopt;
        }
      Layout L = finish_layout(std::move(m), bld, layout_class, genus, 0, 0);
      const Layout_validation v = L.validate();
      if(!v.is_valid()) {
        if(why) *why = "its boxes make no valid layout: " + v.problems.front();
        return std::nullopt;
      }
      return L;
    } catch(const Internal_error& e) {
      if(why) *why = e.what();
      return std::nullopt;
    }
  }

  /// The box corners of `G` inside the solid (its eight boxes round it all there), added to
  /// `m` as vertices on no face (interior nodes) and to `vertex_at` and `at`. On a polycube
  /// map (`m` carries "v:original_point") the corner's place in the surface's space is the
  /// mean over the three axes of its place between the two surface corners that end its grid
  /// line there: exact for a box, and the boxes of a polycube map are near affine images.
  static void add_interior_corners(Mesh& m, const internal::Orthogonal_grid& G, std::map<std::array<int, 3>, std::size_t>& vertex_at,
                                   std::vector<std::array<int, 3>>& at)
  {
    auto original = m.template property_map<V, Point>("v:original_point");
    const std::array<int, 3> n = G.cells();
    auto grid_point = [&](const std::array<int, 3>& a) {
      Eigen::Vector3d u;
      for(std::size_t k = 0; k < 3; ++k) u[Eigen::Index(k)] = G.planes[k][std::size_t(a[k])];
      return u;
    };
    auto surface_point = [&](const std::array<int, 3>& a) {
      const auto it = vertex_at.find(a);
      if(it == vertex_at.end()) internal::layout_failure("a box corner is not a mesh vertex");
      const Point& x = original.first[V(std::uint32_t(it->second))];
      return Eigen::Vector3d(CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z()));
    };
    for(int l = 0; l <= n[2]; ++l)
      for(int j = 0; j <= n[1]; ++j)
        for(int i = 0; i <= n[0]; ++i) {
          const std::array<int, 3> a{i, j, l};
          if(!G.point_inside(a)) continue;
          const Eigen::Vector3d u = grid_point(a), x = G.frame.transpose() * u;
          const V v = m.add_vertex(Point(x.x(), x.y(), x.z()));
          if(original.second) {
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            for(std::size_t k = 0; k < 3; ++k) {
              std::array<int, 3> lo = a, hi = a;
              while(G.point_inside(lo)) --lo[k];
              while(G.point_inside(hi)) ++hi[k];
              const double t = (u[Eigen::Index(k)] - G.planes[k][std::size_t(lo[k])]) / (G.planes[k][std::size_t(hi[k])] - G.planes[k][std::size_t(lo[k])]);
              sum += (1. - t) * surface_point(lo) + t * surface_point(hi);
            }
            sum /= 3.;
            original.first[v] = Point(sum.x(), sum.y(), sum.z());
          }
          vertex_at.emplace(a, std::size_t(v));
          at.push_back(a);
        }
  }

  /// A closed surface of genus `genus` laid out on the boxes of a polycube map of it
  /// (internal/polycube_map.h): faces labelled with their nearest axis direction, the surface
  /// deformed until each chart of one label is planar, that polycube split into the boxes
  /// between its faces' planes (orthogonal_blocks()), and the boxes' corners, edges and faces
  /// carried back to the surface, where they follow its own directions. Empty, with the
  /// reason in `why`, when the deformed surface is not a polycube (a face turned over or
  /// flat, the surface through itself) or its boxes make no layout.
  static std::optional<Layout> polycube_blocks(Mesh m, int genus, std::string* why = nullptr)
  {
    using namespace internal;
    auto fail = [&](const std::string& reason) -> std::optional<Layout> {
      if(why) *why = reason;
      return std::nullopt;
    };
    // The nearest directions, small charts merged, not smoothed (polycube_map_attempt()): a
    // fillet's border then lies on its 45-degree line. Smoothed at border weight 1 (the plate
    // with six filleted round holes of the benchmark corpus: 2 of 150 patches uncertified,
    // valid before; the T with filleted edges: min scaled Jacobian 0.23 -> 0.06), the volumes
    // were worse on the whole, and no refused map became a polycube (anchor.off: 438 -> 195
    // faces turned). Graph-cut labels at a smaller weight come only when these are refused.
    Polycube_map_attempt<Point> attempt = polycube_map_attempt(m);
    if(!attempt.position) return fail("the surface deformed to its labels is not a polycube: " + attempt.why);
    m = std::move(attempt.mesh);
    const std::vector<Eigen::Vector3d>& position = *attempt.position;
    auto original = m.template add_property_map<V, Point>("v:original_point").first;
    for(V v : vertices(m)) {
      original[v] = m.point(v);
      const Eigen::Vector3d& p = position[std::size_t(v)];
      m.point(v) = Point(p.x(), p.y(), p.z());
    }
    std::string boxes;
    std::optional<Layout> L = orthogonal_blocks(std::move(m), genus, Layout_class::polycube, &boxes);
    if(!L) return fail("the polycube makes no layout of boxes: " + boxes);
    L->remeshed = attempt.remeshed_edge > 0.;
    return L;
  }

  /// `phase`: the belt's zigzag and its six nodes are moved along the belt by this fraction
  /// of the zigzag's period (a third of the belt); which cube corners land in hollows or on
  /// ridges depends on it (femurs S014, S018, S027 of the population: invalid at 0, valid at
  /// 1/8, 1/8 and 2/8). With `chain`, a long surface that is not a box is laid out as a
  /// chain of cuboids (sphere_chain()).
  static Layout sphere(Mesh m, double phase = 0., bool chain = false)
  {
    using namespace internal;
    if(std::optional<Layout> box = feature_cube(m)) return std::move(*box);
    Mesh_graph<Mesh> g(m, get(CGAL::vertex_point, m));
    // Two far points by a double sweep; the bisector of their distance fields splits the
    // sphere into two connected vertex sets (every vertex reaches its source inside its set).
    const Far_pair far = far_pair<Point>(g);
    if(chain)
      if(std::optional<Layout> L = sphere_chain(m, g, far)) return std::move(*L);
    const int q = far.q;
    const std::vector<double>&dp = far.dp, &dq = far.dq;
    // The belt must zigzag: a cube seen along its diagonal (corners p and q) has its other
    // six corners alternately nearer p and nearer q. On the bisector, every face would have
    // a 180-degree corner at its middle belt node (det J = 0 there). So the cut is the level
    // set f = dp - dq = (A/2) cos(6 pi t), t in [0, 1) the arc-length position of the
    // nearest bisector vertex along the bisector, A = (acos(1/3) - acos(-1/3)) / pi d(p, q)
    // < 0 the value of f at the corners nearer p of an inscribed cube, and the six nodes sit
    // at its extremes. Half that amplitude measured best on sphere.off (boundary-layer
    // volume: mean scaled Jacobian 0.89, against 0.79 with the full one, 0.80 on the bisector).
    auto sides_of = [&](const std::vector<double>& shift) {
      std::vector<int> side(num_faces(m));
      for(auto f : faces(m)) {
        int s = 0;
        for(auto v : vertices_around_face(halfedge(f, m), m)) s |= dp[v] - dq[v] < shift[v] ? 0 : 1;
        side[f] = s;
      }
      return side;
    };
    auto split = [&](const std::vector<int>& side) {
      std::vector<bool> cut(num_edges(m), false);
      for(auto e : edges(m)) {
        const auto h = halfedge(e, m);
        cut[e] = side[face(h, m)] != side[face(opposite(h, m), m)];
      }
      return cut_into_pieces(m, cut);
    };
    const std::size_t nv = num_vertices(m);
    std::vector<int> face_side = sides_of(std::vector<double>(nv, 0.));
    std::vector<double> zigzag(nv, 0.);
    std::vector<double> position(nv, -1.); // t of the nearest bisector vertex
    bool zigzag_cut = false;
    {
      std::vector<double> belt_position(nv, -1.);
      // The bisector, in loop order: the border of one half of the plain split.
      std::vector<Mesh> halves = split(face_side);
      if(halves.size() == 2) {
        const std::vector<V> loop = border_loop(halves[0]);
        const std::vector<std::size_t> par = vertex_parents(halves[0]);
        const std::vector<double> t = loop_arc_length(halves[0], loop);
        std::vector<int> roots;
        for(std::size_t i = 0; i < loop.size(); ++i) {
          const std::size_t v = par[loop[i]];
          if(v < nv && belt_position[v] < 0.) { belt_position[v] = t[i] / t.back(); roots.push_back(int(v)); }
        }
        std::vector<double> w(std::size_t(g.number_of_edges()));
        for(int e = 0; e < g.number_of_edges(); ++e) w[std::size_t(e)] = g.length(e);
        const Shortest_path_tree tree = shortest_path_tree(g, roots, w);
        position = belt_position;
        for(int v : tree.order) {
          const int e = tree.parent_edge[std::size_t(v)];
          if(e < 0) continue;
          const auto& ev = g.edge_vertices[std::size_t(e)];
          position[std::size_t(v)] = position[std::size_t(ev[0] == v ? ev[1] : ev[0])];
        }
        const double A = (std::acos(1. / 3.) - std::acos(-1. / 3.)) / CGAL_PI * dp[std::size_t(q)];
        for(std::size_t v = 0; v < nv; ++v)
          if(position[v] >= 0.) zigzag[v] = 0.5 * A * std::cos(6. * CGAL_PI * (position[v] - phase / 3.));
        std::vector<int> zig = sides_of(zigzag);
        if(std::count(zig.begin(), zig.end(), 0) > 0 && std::count(zig.begin(), zig.end(), 1) > 0) {
          face_side = std::move(zig);
          zigzag_cut = true;
        }
      }
    }
    std::vector<Mesh> pieces = split(face_side);
    if(zigzag_cut && pieces.size() != 2) { // the zigzag did not leave two disks: the plain cut
      zigzag_cut = false;
      zigzag.assign(nv, 0.);
      pieces = split(sides_of(zigzag));
    }
    if(pieces.size() != 2) layout_failure("the sphere does not split into two disks");
    std::vector<std::vector<V>> loops;
    for(auto& piece : pieces) loops.push_back(border_loop(piece));
    // The belt (piece 0's border, as vertices of m) carries the 6 cube nodes.
    const std::vector<std::size_t> par0 = vertex_parents(pieces[0]);
    const std::vector<double> s0 = loop_arc_length(pieces[0], loops[0]);
    std::vector<std::size_t> belt_index;
    for(int i = 0; i < 6; ++i) belt_index.push_back(at_arc_length(s0, 0, s0.back() * i / 6.));
    if(zigzag_cut) {
      // The nodes are the zigzag's extremes (t = i/6 + phase/3), in piece 0's loop order, starting
      // with one where piece 0 is narrow (its corner's neighbours): t = 0, 2/6, 4/6 when
      // piece 0 lies on the side dp - dq < shift, the others otherwise.
      std::vector<bool> on_loop(num_vertices(pieces[0]), false);
      for(V v : loops[0]) on_loop[v] = true;
      bool side1 = false;
      for(V v : vertices(pieces[0]))
        if(!on_loop[v] && par0[v] < nv && dp[par0[v]] - dq[par0[v]] >= zigzag[par0[v]]) side1 = true;
      std::vector<std::pair<std::size_t, int>> extremes; // (loop index, i)
      for(int i = 0; i < 6; ++i) {
        std::size_t best = 0;
        double gap = 2.;
        for(std::size_t k = 0; k < loops[0].size(); ++k) {
          const std::size_t v = par0[loops[0][k]];
          if(v >= nv || position[v] < 0.) continue;
          double d = std::abs(position[v] - std::fmod(i / 6. + phase / 3., 1.));
          d = std::min(d, 1. - d);
          if(d < gap) { gap = d; best = k; }
        }
        extremes.push_back({best, i});
      }
      std::sort(extremes.begin(), extremes.end());
      std::size_t first = 0;
      while(first < 6 && (extremes[first].second % 2 == 0) == side1) ++first;
      if(first < 6) {
        std::vector<std::size_t> zig_index;
        for(std::size_t j = 0; j < 6; ++j) zig_index.push_back(extremes[(first + j) % 6].first);
        // Rotate the loop so that its first node is at index 0 (indices must increase).
        std::rotate(loops[0].begin(), loops[0].begin() + std::ptrdiff_t(zig_index[0]), loops[0].end());
        const std::size_t shift = zig_index[0], n = loops[0].size();
        bool increasing = true;
        for(std::size_t j = 0; j < 6; ++j) zig_index[j] = (zig_index[j] + n - shift) % n;
        for(std::size_t j = 0; j + 1 < 6; ++j) increasing = increasing && zig_index[j] < zig_index[j + 1];
        if(increasing) belt_index = zig_index;
        else std::rotate(loops[0].begin(), loops[0].begin() + std::ptrdiff_t((n - shift) % n), loops[0].end());
      }
    }
    for(int i = 0; i < 5; ++i)
      if(belt_index[std::size_t(i)] >= belt_index[std::size_t(i + 1)]) layout_failure("the sphere's belt is too coarse for 6 nodes");
    std::array<std::size_t, 6> belt;
    for(int j = 0; j < 6; ++j) belt[std::size_t(j)] = par0[loops[0][belt_index[std::size_t(j)]]];
    // Piece 0 holds cube corner (0,0,0), joined to belt nodes 0, 2, 4; piece 1 holds
    // (1,1,1), joined to 1, 3, 5 (belt order: 100 110 010 011 001 101).
    std::vector<Embedding> emb;
    for(std::size_t k = 0; k < 2; ++k) {
      const std::vector<std::size_t> par = vertex_parents(pieces[k]);
      Piece_graph pg;
      pg.anchors = circle_anchors(pieces[k], loops[k]);
      for(std::size_t j = k; j < 6; j += 2)
        for(std::size_t i = 0; i < loops[k].size(); ++i)
          if(par[loops[k][i]] == belt[j]) pg.border_nodes.push_back(i);
      if(pg.border_nodes.size() != 3) layout_failure("the sphere's belt is not a simple loop");
      pg.interior_uv.push_back(Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 0.));
      for(std::size_t j = 0; j < 3; ++j) pg.segments.push_back({{3, j}});
      emb.push_back(embed_piece_graph(pieces[k], loops[k], pg));
    }
    Glued_mesh<Point> gl = glue_pieces(m, pieces);
    Layout_builder bld;
    const std::size_t c0 = bld.node(final_vertex(gl, 0, emb[0].vertex[3]));
    const std::size_t c1 = bld.node(final_vertex(gl, 1, emb[1].vertex[3]));
    std::array<std::size_t, 6> bn;
    for(int j = 0; j < 6; ++j) bn[std::size_t(j)] = bld.node(belt[std::size_t(j)]);
    for(std::size_t k = 0; k < 2; ++k)
      for(const auto& path : emb[k].path) bld.arc(final_path(gl, k, path));
    std::vector<std::size_t> belt_loop;
    for(V v : loops[0]) belt_loop.push_back(par0[v]);
    bld.loop_arcs(belt_loop);
    const int code_of_belt[6] = {4, 6, 2, 3, 1, 5}; // x*4 + y*2 + z
    std::array<std::size_t, 8> cube{};
    for(int c = 0; c < 8; ++c) {
      const int x = c & 1, y = (c >> 1) & 1, z = (c >> 2) & 1, code = x * 4 + y * 2 + z;
      if(code == 0) cube[std::size_t(c)] = c0;
      else if(code == 7) cube[std::size_t(c)] = c1;
      else
        for(int j = 0; j < 6; ++j)
          if(code_of_belt[j] == code) cube[std::size_t(c)] = bn[std::size_t(j)];
    }
    bld.cuboids.push_back(cube);
    return finish_layout(std::move(gl.mesh), bld, Layout_class::sphere, 0, 0, 0);
  }

  /// A closed genus-0 surface long enough for a chain of three or more cube-like cuboids (a
  /// bone, a capsule) laid out as one: a cap around each of its two farthest points (double
  /// sweep) is an end face, and the tube between them is laid out as strip() lays a
  /// cylinder's. sphere()'s one cube puts a long shape's length into the six faces round its
  /// belt, which are then long strips. Empty when the shape is not that long or its caps
  /// are not disks. `g` and `far` are sphere()'s graph of `m` and its two far points.
  static std::optional<Layout> sphere_chain(Mesh m, const internal::Mesh_graph<Mesh>& g, const internal::Far_pair& far)
  {
    try {
      return chain_between_caps(std::move(m), g, far);
    } catch(const Internal_error&) { // a cut or piece the chain cannot use: one cube instead
      return std::nullopt;
    }
  }

  static std::optional<Layout> chain_between_caps(Mesh m, const internal::Mesh_graph<Mesh>& g, const internal::Far_pair& far)
  {
    using namespace internal;
    const int p = far.p, q = far.q;
    const std::vector<double>&dp = far.dp, &dq = far.dq;
    const double D = dp[std::size_t(q)];
    // Each cap is the far face of the chain's end cube. Such a face on a round end (its
    // corners 54.7 degrees from the pole) holds 1.61 times the square of a quarter of its
    // border's length, a flat end's disk 1.27 times: the cap is the first sublevel set (of 64
    // up to D/2) that holds 1.5 times, 46 degrees round a round end, just past a flat one's rim.
    auto cap_radius = [&](const std::vector<double>& d) {
      for(int i = 1; i <= 64; ++i) {
        const double a = 0.5 * D * i / 64.;
        const Level_set_measure c = level_set_measure(g.position, g.face_vertices, d, a);
        if(c.sublevel_area >= 1.5 * (c.level_length / 4.) * (c.level_length / 4.)) return a;
      }
      return 0.;
    };
    const double ap = cap_radius(dp), aq = cap_radius(dq);
    if(!(ap > 0. && aq > 0. && ap + aq < 0.8 * D)) return std::nullopt;
    // A cap: the faces wholly within its radius that are joined by edges to those at its
    // point, with the holes they leave (a scan's noise) filled: every face that the far
    // point's faces do not reach round it. The cut follows mesh edges.
    std::vector<int> face_label(num_faces(m), 1);
    auto faces_at = [&](int v) {
      std::vector<std::size_t> out;
      for(auto f : CGAL::faces_around_target(halfedge(V(std::uint32_t(v)), m), m))
        if(f != Mesh::null_face()) out.push_back(std::size_t(f));
      return out;
    };
    auto flood = [&](const std::vector<std::size_t>& seeds, const std::function<bool(std::size_t)>& allowed) {
      std::vector<bool> reached(num_faces(m), false);
      std::vector<std::size_t> stack;
      for(std::size_t f : seeds)
        if(allowed(f) && !reached[f]) reached[f] = true, stack.push_back(f);
      while(!stack.empty()) {
        const auto f = F(std::uint32_t(stack.back()));
        stack.pop_back();
        for(auto h : CGAL::halfedges_around_face(halfedge(f, m), m)) {
          const auto o = face(opposite(h, m), m);
          if(o != Mesh::null_face() && allowed(std::size_t(o)) && !reached[o]) reached[o] = true, stack.push_back(std::size_t(o));
        }
      }
      return reached;
    };
    for(int end = 0; end < 2; ++end) {
      const std::vector<double>& d = end == 0 ? dp : dq;
      const double a = end == 0 ? ap : aq;
      const std::vector<bool> inside = flood(faces_at(end == 0 ? p : q), [&](std::size_t f) {
        for(auto v : vertices_around_face(halfedge(F(std::uint32_t(f)), m), m))
          if(!(d[v] < a)) return false;
        return true;
      });
      const std::vector<bool> outside = flood(faces_at(end == 0 ? q : p), [&](std::size_t f) { return !inside[f]; });
      for(std::size_t f = 0; f < num_faces(m); ++f)
        if(!outside[f]) {
          if(face_label[f] != 1) return std::nullopt; // the caps overlap
          face_label[f] = 2 * end;
        }
    }
    std::vector<bool> cut(num_edges(m), false);
    for(auto e : edges(m)) {
      const auto h = halfedge(e, m);
      cut[e] = face_label[face(h, m)] != face_label[face(opposite(h, m), m)];
    }
    std::vector<std::vector<V>> loops; // the tube's two border loops, as vertices of m
    {
      const std::vector<Mesh> pieces = cut_into_pieces(m, cut);
      if(pieces.size() != 3) return std::nullopt;
      std::size_t one_loop = 0;
      for(const Mesh& piece : pieces) {
        const auto border = all_border_loops<Point>(piece);
        if(border.size() == 1) ++one_loop;
        if(border.size() != 2) continue;
        const std::vector<std::size_t> par = vertex_parents(piece);
        for(const auto& l : border) {
          loops.emplace_back();
          for(V v : l) loops.back().push_back(V(std::uint32_t(par[v])));
        }
      }
      if(one_loop != 2 || loops.size() != 2) return std::nullopt;
    }
    const std::vector<int> path = seam_between(g, loops, loops[0], loops[1]);
    if(path.size() < 2) return std::nullopt;
    const std::vector<std::size_t> seam(path.begin(), path.end());
    double W = 0.;
    for(std::size_t i = 0; i + 1 < seam.size(); ++i) {
      const V a(std::uint32_t(seam[i])), b(std::uint32_t(seam[i + 1]));
      W += edge_length(m, a, b);
      cut[edge(halfedge(a, b, m).first, m)] = true;
    }
    const double H = 0.5 * (loop_arc_length(m, loops[0]).back() + loop_arc_length(m, loops[1]).back());
    // Two cuboids split the shape at its middle as the cube's belt does: femur_S025.ply as a
    // chain of two is too far from the mesh at every grid, as one cube valid at 32 samples.
    if(std::lround(4. * W / H) < 3) return std::nullopt;
    return strip(std::move(m), cut, seam, rotated_to(loops[0], seam.front()), rotated_to(loops[1], seam.back()), false, 0, 0,
                 std::nullopt, true);
  }

  // ---------------------------------------------------------------- disk -------------
  static Layout disk(Mesh m)
  {
    using namespace internal;
    std::vector<Mesh> pieces = cut_into_pieces(m, std::vector<bool>(num_edges(m), false));
    Mesh& piece = pieces[0];
    const std::vector<V> loop = border_loop(piece);
    const std::vector<double> s = loop_arc_length(piece, loop);
    std::array<std::size_t, 4> corner{};
    for(std::size_t i = 0; i < 4; ++i) {
      corner[i] = at_arc_length(s, 0, s.back() * double(i) / 4.);
      if(i > 0 && corner[i] <= corner[i - 1]) layout_failure("the boundary loop is too coarse for 4 corners");
    }
    // The bottom of the cube: an inner square holding a fifth of the area, the share of
    // each of the cube's five surface patches (a fixed square put a mushroom's whole stem
    // and head in it, 9% of the diagonal away from the fitted volume).
    const Piece_graph pg = disk_graph(corner, 0.2);
    const std::vector<std::size_t> par = vertex_parents(piece);
    const Embedding e = embed_piece_graph(piece, loop, pg);
    Glued_mesh<Point> gl = glue_pieces(m, pieces);
    Layout_builder bld;
    std::array<std::size_t, 4> top{}, bottom{};
    for(std::size_t i = 0; i < 4; ++i) {
      top[i] = bld.node(par[loop[pg.border_nodes[i]]]);
      bottom[i] = bld.node(final_vertex(gl, 0, e.vertex[4 + i]));
    }
    for(const auto& path : e.path) bld.arc(final_path(gl, 0, path));
    std::vector<std::size_t> border;
    for(V v : loop) border.push_back(par[v]);
    bld.loop_arcs(border);
    bld.interior.push_back({int(Layout::CAP), top});
    bld.cuboids.push_back(disk_cube(bottom, top));
    return finish_layout(std::move(gl.mesh), bld, Layout_class::disk, 0, 1, 0);
  }

  // ------------------------------------------------------- cylinder and torus ----------
  /// The sections of a chain (caps at both ends) or ring (interfaces only, `section.back()`
  /// the same nodes as `section.front()`) of cuboids, each section's four nodes in cyclic
  /// order round it, and the cuboids between consecutive sections.
  static void add_sections(internal::Layout_builder& bld, const std::vector<std::array<std::size_t, 4>>& section, bool ring,
                           bool closed_ends = false)
  {
    const int k = int(section.size()) - 1;
    for(int j = 0; j < (ring ? k : k + 1); ++j) {
      const bool end = !ring && (j == 0 || j == k);
      if(end && closed_ends) continue; // a surface patch: the arcs round it find it
      bld.interior.push_back({int(end ? Layout::CAP : Layout::INTERFACE), section[std::size_t(j)]});
    }
    for(int c = 0; c < k; ++c) {
      std::array<std::size_t, 8> cube{};
      for(int i = 0; i < 2; ++i)
        for(int b = 0; b < 2; ++b)
          for(int a = 0; a < 2; ++a)
            cube[std::size_t(i + 2 * a + 4 * b)] = section[std::size_t(c + i)][std::size_t(internal::cyclic_corner(a, b))];
      bld.cuboids.push_back(cube);
    }
  }

  /// Lays a chain (or ring) of `k` cuboids in the disk `m` cut open along `cut`: the
  /// disk's border runs seam (bottom), loop 2 (right), seam back (top), loop 1 (left); it is
  /// mapped to a rectangle as long as the seam and as high as the loops, longitudinal arcs
  /// are the straight lines joining the three level nodes of loop 1 to those of loop 2 (the
  /// seam itself is the fourth) and the sections are vertical lines at j/k of the seam's
  /// length. The level nodes are `levels` (mesh vertices on loop 1 and on loop 2) if given,
  /// else at 1/4, 1/2, 3/4 of each loop's length from the seam. With `closed_ends`, `m` is
  /// a closed surface and `cut` also cuts off the two caps that loops 1 and 2 bound: they
  /// become the chain's end faces, surface patches (sphere_chain()).
  static Layout strip(Mesh m, const std::vector<bool>& cut, const std::vector<std::size_t>& seam,
                      const std::vector<std::size_t>& loop1, const std::vector<std::size_t>& loop2, bool ring, int genus,
                      std::size_t boundary_loops,
                      const std::optional<std::array<std::array<std::size_t, 3>, 2>>& levels = std::nullopt,
                      bool closed_ends = false)
  {
    using namespace internal;
    std::vector<Mesh> pieces = cut_into_pieces(m, cut);
    if(pieces.size() != (closed_ends ? 3 : 1)) layout_failure("cutting along the seam does not leave one disk");
    // The strip is the piece whose border has the copy of seam[0] followed by seam[1]; the
    // border starts there.
    std::size_t tube = pieces.size();
    V start;
    for(std::size_t k = 0; k < pieces.size() && tube == pieces.size(); ++k) {
      const std::vector<std::size_t> pk = vertex_parents(pieces[k]);
      const std::vector<V> any = border_loop(pieces[k]);
      for(std::size_t i = 0; i < any.size(); ++i)
        if(pk[any[i]] == seam[0] && pk[any[(i + 1) % any.size()]] == seam[1]) {
          start = any[i];
          tube = k;
          break;
        }
    }
    if(tube == pieces.size()) layout_failure("the seam is not on the border of the cut disk");
    Mesh& piece = pieces[tube];
    const std::vector<std::size_t> par = vertex_parents(piece);
    const std::vector<V> loop = border_loop(piece, start);
    const std::size_t n = loop.size(), ms = seam.size() - 1;
    for(std::size_t i = 0; i <= ms; ++i)
      if(par[loop[i]] != seam[i]) layout_failure("the seam's bottom side is not where it should be");
    std::size_t r = ms + 1;
    while(r < n && par[loop[r]] != seam[ms]) ++r;
    if(r + ms >= n + 1) layout_failure("the cut disk's border is not a rectangle");
    const std::vector<double> s = loop_arc_length(piece, loop);
    const double W = s[ms], H = 0.5 * ((s[r] - s[ms]) + (s.back() - s[r + ms]));
    // Cuboids close to cubes: a section's side is about H/4, so about 4W/H of them. Long
    // bent cuboids fold (a torus ring of 3 has negative det J, of 6 it is certified valid).
    int k = std::max(ring ? 3 : 1, int(std::lround(4. * W / H)));
    k = std::min(k, 32);
    Piece_graph pg;
    pg.anchors = {{0, {0, 0}}, {ms, {W, 0}}, {r, {W, H}}, {r + ms, {0, H}}};
    // Border nodes: left levels 1..3, right levels 1..3, seam bottom j, seam top j.
    auto left_level = [&](int l) { return at_arc_length(s, 0, -(s.back() - s[r + ms]) * l / 4.); };
    std::array<std::size_t, 3> left{}, right{};
    for(int l = 1; l <= 3; ++l) {
      left[std::size_t(l - 1)] = left_level(l);
      if(ring) { // the same meridian vertices on both sides
        right[std::size_t(l - 1)] = n;
        for(std::size_t i = ms; i <= r; ++i)
          if(par[loop[i]] == par[loop[left[std::size_t(l - 1)]]]) right[std::size_t(l - 1)] = i;
        if(right[std::size_t(l - 1)] == n) layout_failure("the meridian's two sides disagree");
      } else
        right[std::size_t(l - 1)] = at_arc_length(s, ms, (s[r] - s[ms]) * l / 4.);
    }
    if(levels) {
      // Left levels by decreasing border index (upwards from the seam), right increasing.
      for(int side = 0; side < 2; ++side) {
        std::array<std::size_t, 3> at{n, n, n};
        const std::size_t from = side == 0 ? r + ms + 1 : ms + 1, to = side == 0 ? n : r;
        for(std::size_t l = 0; l < 3; ++l)
          for(std::size_t i = from; i < to; ++i)
            if(par[loop[i]] == (*levels)[std::size_t(side)][l]) at[l] = i;
        if(std::count(at.begin(), at.end(), n) > 0) layout_failure("a section corner is not on its loop");
        std::sort(at.begin(), at.end());
        if(side == 0) std::reverse(at.begin(), at.end());
        (side == 0 ? left : right) = at;
      }
    }
    // Heights of the levels on the rectangle's left and right sides.
    std::array<double, 3> hl{}, hr{};
    for(std::size_t l = 0; l < 3; ++l) {
      hl[l] = H * (s.back() - s[left[l]]) / (s.back() - s[r + ms]);
      hr[l] = H * (s[right[l]] - s[ms]) / (s[r] - s[ms]);
    }
    for(int l = 0; l < 3; ++l) pg.border_nodes.push_back(left[std::size_t(l)]);
    for(int l = 0; l < 3; ++l) pg.border_nodes.push_back(right[std::size_t(l)]);
    std::vector<std::size_t> seam_node(std::size_t(k + 1));
    seam_node[0] = 0;
    seam_node[std::size_t(k)] = ms;
    for(int j = 1; j < k; ++j) {
      std::size_t best = 1;
      for(std::size_t i = 1; i < ms; ++i)
        if(std::abs(s[i] - W * j / k) < std::abs(s[best] - W * j / k)) best = i;
      seam_node[std::size_t(j)] = best;
    }
    for(int j = 1; j <= k; ++j)
      if(seam_node[std::size_t(j)] <= seam_node[std::size_t(j - 1)]) layout_failure("the seam is too coarse for the sections");
    for(int j = 1; j < k; ++j) pg.border_nodes.push_back(seam_node[std::size_t(j)]);
    for(int j = 1; j < k; ++j) pg.border_nodes.push_back(r + ms - seam_node[std::size_t(j)]);
    const std::size_t nb = pg.border_nodes.size();
    auto bottom = [&](int j) { return 6 + std::size_t(j - 1); };
    auto top = [&](int j) { return 6 + std::size_t(k - 1) + std::size_t(j - 1); };
    auto inner = [&](int j, int l) { return nb + std::size_t(j - 1) * 3 + std::size_t(l - 1); };
    for(int j = 1; j < k; ++j)
      for(std::size_t l = 0; l < 3; ++l) pg.interior_uv.push_back(Eigen::Vector2d(W * j / k, hl[l] + (hr[l] - hl[l]) * j / k));
    for(int l = 1; l <= 3; ++l) {
      std::size_t prev = std::size_t(l - 1);
      for(int j = 1; j < k; ++j) {
        pg.segments.push_back({{prev, inner(j, l)}});
        prev = inner(j, l);
      }
      pg.segments.push_back({{prev, 3 + std::size_t(l - 1)}});
    }
    for(int j = 1; j < k; ++j) {
      pg.segments.push_back({{bottom(j), inner(j, 1)}});
      pg.segments.push_back({{inner(j, 1), inner(j, 2)}});
      pg.segments.push_back({{inner(j, 2), inner(j, 3)}});
      pg.segments.push_back({{inner(j, 3), top(j)}});
    }
    const Embedding e = embed_piece_graph(piece, loop, pg);
    Glued_mesh<Point> gl = glue_pieces(m, pieces);
    Layout_builder bld;
    // Section j, level l (0 on the seam).
    std::vector<std::array<std::size_t, 4>> section(std::size_t(k + 1));
    section[0][0] = bld.node(seam[0]);
    section[std::size_t(k)][0] = bld.node(seam[ms]);
    for(int l = 1; l <= 3; ++l) {
      section[0][std::size_t(l)] = bld.node(par[loop[left[std::size_t(l - 1)]]]);
      section[std::size_t(k)][std::size_t(l)] = bld.node(par[loop[right[std::size_t(l - 1)]]]);
    }
    for(int j = 1; j < k; ++j) {
      section[std::size_t(j)][0] = bld.node(seam[seam_node[std::size_t(j)]]);
      for(int l = 1; l <= 3; ++l) section[std::size_t(j)][std::size_t(l)] = bld.node(final_vertex(gl, tube, e.vertex[inner(j, l)]));
    }
    for(const auto& path : e.path) bld.arc(final_path(gl, tube, path));
    bld.loop_arcs(loop1);
    if(!ring) bld.loop_arcs(loop2);
    // The seam, split at its nodes (closed for a ring: its ends are the same vertex).
    {
      std::vector<std::size_t> cur{seam[0]};
      for(std::size_t i = 1; i <= ms; ++i) {
        cur.push_back(seam[i]);
        if(bld.node_of_vertex.count(seam[i])) {
          bld.arc(cur);
          cur.assign(1, seam[i]);
        }
      }
    }
    add_sections(bld, section, ring, closed_ends);
    const Layout_class cls = closed_ends ? Layout_class::sphere : ring ? Layout_class::torus : Layout_class::cylinder;
    return finish_layout(std::move(gl.mesh), bld, cls, genus, boundary_loops, 0);
  }

  static std::vector<std::size_t> as_indices(const std::vector<V>& vs)
  {
    std::vector<std::size_t> out;
    for(V v : vs) out.push_back(std::size_t(v));
    return out;
  }

  /// A loop's vertices as indices, starting at `v`.
  static std::vector<std::size_t> rotated_to(const std::vector<V>& loop, std::size_t v)
  {
    std::vector<std::size_t> out = as_indices(loop);
    std::rotate(out.begin(), std::find(out.begin(), out.end(), v), out.end());
    return out;
  }

  /// Shortest vertex path from a vertex of `from` to the nearest vertex of `to` that enters
  /// no vertex of the `loops` but its ends; empty if there is none.
  static std::vector<int> seam_between(const internal::Mesh_graph<Mesh>& g, const std::vector<std::vector<V>>& loops,
                                       const std::vector<V>& from, const std::vector<V>& to)
  {
    using namespace internal;
    std::vector<int> roots;
    for(V v : from) roots.push_back(int(v));
    const std::vector<double> d = distances_from<Point>(g, roots);
    V target = to[0];
    for(V v : to)
      if(d[v] < d[target]) target = v;
    std::vector<bool> blocked(std::size_t(g.number_of_vertices()), false);
    for(const auto& l : loops)
      for(V v : l) blocked[v] = true;
    for(int r : roots) blocked[std::size_t(r)] = false;
    // Roots may be entered only as roots: the path leaves loop 1 at once.
    return shortest_vertex_path<Point>(g, roots, int(target), blocked);
  }

  /// The axis of the tube around the border loop `loop` of `m` (internal::tube_axis() of
  /// the faces at its vertices); zero if there is no clear one.
  static Eigen::Vector3d axis_at_loop(const Mesh& m, const internal::Mesh_graph<Mesh>& g, const std::vector<V>& loop)
  {
    std::vector<Eigen::Vector3d> normals;
    for(V v : loop)
      for(auto f : CGAL::faces_around_target(halfedge(v, m), m)) {
        if(f == Mesh::null_face()) continue;
        const auto h = halfedge(f, m);
        const Eigen::Vector3d& a = g.position[std::size_t(source(h, m))];
        const Eigen::Vector3d& b = g.position[std::size_t(target(h, m))];
        const Eigen::Vector3d& c = g.position[std::size_t(target(next(h, m), m))];
        normals.push_back((b - a).cross(c - a));
      }
    const auto a = internal::tube_axis(normals);
    return a ? *a : Eigen::Vector3d::Zero();
  }

  static Layout cylinder(Mesh m, bool off_steps)
  {
    using namespace internal;
    const auto loops = all_border_loops<Point>(m);
    Mesh_graph<Mesh> g(m, get(CGAL::vertex_point, m));
    // The seam joins the loops' nearest points, and each section's corners are at equal arc
    // lengths from it (of the section seen along the tube, see below), unless that makes a
    // section's quad skewed (a flat blade's section a diamond with two flat corners) and the
    // corners that split the loops' turning in
    // quarters make a squarer one; then the seam joins the nearest two of those. Each loop is
    // seen along the tube's axis there (internal::tube_axis()), not across a stepped end.
    std::array<std::vector<Eigen::Vector3d>, 2> p;
    std::array<Eigen::Vector3d, 2> axis;
    for(std::size_t i = 0; i < 2; ++i) {
      for(V v : loops[i]) p[i].push_back(g.position[std::size_t(v)]);
      axis[i] = axis_at_loop(m, g, loops[i]);
    }
    std::vector<int> path = seam_between(g, loops, loops[0], loops[1]);
    std::optional<std::array<std::array<std::size_t, 4>, 2>> corner;
    if(path.size() >= 2) {
      std::array<std::optional<std::array<std::size_t, 4>>, 2> turned;
      std::array<std::array<std::size_t, 4>, 2> equal{};
      bool stepped = false, along_tube = false;
      double equal_sine = 1., turned_sine = 1.;
      for(std::size_t i = 0; i < 2; ++i) {
        turned[i] = quarter_turn_corners(p[i], axis[i]);
        const std::vector<double> s = loop_arc_length(m, loops[i]);
        const V end(std::uint32_t(i == 0 ? path.front() : path.back()));
        const std::size_t at = std::size_t(std::find(loops[i].begin(), loops[i].end(), end) - loops[i].begin());
        // Asked for the first time, the corners are at equal arc lengths of the section, the
        // loop seen along the tube, and on a knife edge beside them (sharpest_turn_near()): a
        // stepped end's step edges run along the tube and would shift its corners against
        // the other end's (blade.off: 1.3 back from a sharp edge at one end, 0.25 at the
        // other, the arcs between running across the edge). Moved off the steps, they are
        // at equal arc lengths of the loop, which keeps them off the steps' ends.
        const auto q = off_steps || axis[i].isZero() ? std::nullopt : in_mean_plane(p[i], axis[i]);
        const std::vector<double> seen = q ? section_arc_length(*q) : s;
        for(std::size_t k = 0; k < 4; ++k) {
          equal[i][k] = at_arc_length(seen, at, seen.back() * double(k) / 4.);
          if(q && k > 0) equal[i][k] = sharpest_turn_near(*q, seen, equal[i][k], seen.back() / 32.);
          // Corners where 3D arc lengths put them too leave strip() to place them (the
          // layouts of round tubes stay as they were).
          along_tube = along_tube || equal[i][k] != at_arc_length(s, at, s.back() * double(k) / 4.);
        }
        equal_sine = std::min(equal_sine, corner_sine(p[i], equal[i], axis[i]));
        if(turned[i]) turned_sine = std::min(turned_sine, corner_sine(p[i], *turned[i], axis[i]));
        // The seam joins the loops' nearest points, on a tube cut at two heights the ends of
        // a step: asked, corners move off steps, where the section gets no more skewed.
        if(off_steps)
          if(const auto c = clear_of_steps(m, loops[i], s, equal[i]))
            if(corner_sine(p[i], *c, axis[i]) >= corner_sine(p[i], equal[i], axis[i])) {
              equal[i] = *c;
              stepped = true;
            }
      }
      const double skewed = 0.7; // the sine of 44 degrees
      if(turned[0] && turned[1] && equal_sine < skewed && turned_sine > equal_sine) corner = std::array<std::array<std::size_t, 4>, 2>{{*turned[0], *turned[1]}};
      else if(stepped || along_tube) corner = equal;
    }
    if(corner) {
      std::array<std::vector<V>, 2> ends;
      for(std::size_t i = 0; i < 2; ++i)
        for(std::size_t c : (*corner)[i]) ends[i].push_back(loops[i][c]);
      path = seam_between(g, loops, ends[0], ends[1]);
    }
    if(path.size() < 2) layout_failure("no seam joins the cylinder's two loops");
    std::vector<std::size_t> seam(path.begin(), path.end());
    std::vector<bool> cut(num_edges(m), false);
    for(std::size_t i = 0; i + 1 < seam.size(); ++i) cut[edge(halfedge(V(std::uint32_t(seam[i])), V(std::uint32_t(seam[i + 1])), m).first, m)] = true;
    std::optional<std::array<std::array<std::size_t, 3>, 2>> levels;
    if(corner) {
      std::array<std::array<std::size_t, 3>, 2> lv{};
      bool three = true;
      for(std::size_t i = 0; i < 2; ++i) {
        std::size_t l = 0;
        for(std::size_t c : (*corner)[i]) {
          const std::size_t v = std::size_t(loops[i][c]);
          if(v == seam.front() || v == seam.back()) continue;
          if(l < 3) lv[i][l] = v;
          ++l;
        }
        three = three && l == 3;
      }
      if(three) levels = lv;
    }
    return strip(std::move(m), cut, seam, rotated_to(loops[0], seam.front()), rotated_to(loops[1], seam.back()), false, 0, 2, levels);
  }

  /// A torus whose meridian crosses exactly four sharp feature curves (more than 45
  /// degrees), each of which runs once around the ring (a CAD ring: a washer, a gear, a pipe
  /// of rectangular section), is laid out on them: the four longitudinal loops of the ring
  /// are traced along those curves (sharp edges cost a twentieth of their length), so that
  /// no patch folds over the creases, and each band between two loops is mapped to a
  /// rectangle of its own, in which the sections are straight. The generic ring of torus()
  /// takes its levels at quarters of the meridian and its longitudinal arcs straight in one
  /// map of the whole annulus: they cross the creases (`pinion.off`, a gear: a node on the
  /// root of a tooth with a reflex corner, 16 of 30 patches uncertified). Empty when the
  /// features are anything else. `m` and `meridian` as in torus().
  static std::optional<Layout> feature_ring(const Mesh& m, const std::vector<std::size_t>& meridian)
  {
    using namespace internal;
    const std::size_t nm = meridian.size();
    const std::vector<bool> sharp = sharp_edges(m, 45.);
    auto edge_of = [&](std::size_t a, std::size_t b) {
      const auto h = halfedge(V(std::uint32_t(a)), V(std::uint32_t(b)), m);
      if(!h.second) layout_failure("a loop is not an edge path");
      return edge(h.first, m);
    };
    // Crossings: meridian vertices where a feature curve crosses it, i.e. with a sharp edge
    // strictly between the meridian's two edges on either side of it (a curve that only
    // touches the meridian, or that the meridian follows for a while, has sharp edges on
    // one side only); neighbouring ones are one crossing, taken at their middle.
    std::vector<bool> candidate(nm, false);
    for(std::size_t i = 0; i < nm; ++i) {
      const V v(std::uint32_t(meridian[i])), p(std::uint32_t(meridian[(i + nm - 1) % nm])), q(std::uint32_t(meridian[(i + 1) % nm]));
      std::vector<V> around;
      std::vector<bool> around_sharp;
      for(auto h : halfedges_around_target(halfedge(v, m), m)) {
        around.push_back(source(h, m));
        around_sharp.push_back(sharp[std::size_t(edge(h, m))]);
      }
      const std::size_t n = around.size(), ip = std::size_t(std::find(around.begin(), around.end(), p) - around.begin()),
                        iq = std::size_t(std::find(around.begin(), around.end(), q) - around.begin());
      if(ip == n || iq == n) layout_failure("a loop is not an edge path");
      auto sharp_between = [&](std::size_t from, std::size_t to) {
        for(std::size_t k = (from + 1) % n; k != to; k = (k + 1) % n)
          if(around_sharp[k]) return true;
        return false;
      };
      candidate[i] = sharp_between(ip, iq) && sharp_between(iq, ip);
    }
    // Neighbouring candidates joined by an edge shorter than 1/32 of the meridian are one
    // crossing (a meridian that zigzags across a crease); on a coarse CAD mesh every
    // meridian vertex can be a crossing of its own (a gear's section: four vertices).
    double meridian_length = 0.;
    std::vector<double> link(nm); // edge from i - 1 to i
    for(std::size_t i = 0; i < nm; ++i) {
      link[i] = edge_length(m, V(std::uint32_t(meridian[(i + nm - 1) % nm])), V(std::uint32_t(meridian[i])));
      meridian_length += link[i];
    }
    auto joined = [&](std::size_t i) { return candidate[i] && candidate[(i + nm - 1) % nm] && link[i] < meridian_length / 32.; };
    std::vector<std::size_t> crossing; // meridian indices
    for(std::size_t i = 0; i < nm; ++i) {
      if(!candidate[i] || joined(i)) continue;
      std::size_t len = 1;
      while(len < nm && joined((i + len) % nm)) ++len;
      crossing.push_back((i + len / 2) % nm);
    }
    if(crossing.size() != 4) return std::nullopt;
    std::sort(crossing.begin(), crossing.end());
    // The annulus (the torus cut along its meridian) and the four loops, each the cheapest
    // path between the two copies of its crossing that no earlier loop touches.
    std::vector<bool> cut(num_edges(m), false);
    for(std::size_t i = 0; i < nm; ++i) cut[std::size_t(edge_of(meridian[i], meridian[(i + 1) % nm]))] = true;
    std::vector<Mesh> annulus = cut_into_pieces(m, cut);
    if(annulus.size() != 1) return std::nullopt;
    const std::vector<std::size_t> par = vertex_parents(annulus[0]);
    const auto sides = all_border_loops<Point>(annulus[0]);
    if(sides.size() != 2) return std::nullopt;
    Mesh_graph<Mesh> g(annulus[0], get(CGAL::vertex_point, annulus[0]));
    std::vector<double> w(std::size_t(g.number_of_edges()));
    std::vector<bool> edge_sharp(w.size(), false);
    for(int e = 0; e < g.number_of_edges(); ++e) {
      const auto h = halfedge(V(std::uint32_t(g.edge_vertices[std::size_t(e)][0])), V(std::uint32_t(g.edge_vertices[std::size_t(e)][1])), annulus[0]);
      const std::size_t a = par[std::size_t(g.edge_vertices[std::size_t(e)][0])], b = par[std::size_t(g.edge_vertices[std::size_t(e)][1])];
      edge_sharp[std::size_t(e)] = h.second && !is_border_edge(h.first, annulus[0]) && sharp[std::size_t(edge_of(a, b))];
      w[std::size_t(e)] = g.length(e) * (edge_sharp[std::size_t(e)] ? 0.05 : 1.);
    }
    std::vector<bool> blocked(num_vertices(annulus[0]), false);
    for(const auto& l : sides)
      for(V v : l) blocked[v] = true;
    std::array<std::vector<std::size_t>, 4> loop; // mesh vertices, from the crossing round to it (not repeated)
    for(std::size_t l = 0; l < 4; ++l) {
      const std::size_t c = meridian[crossing[l]];
      V a, b;
      for(V v : sides[0])
        if(par[v] == c) a = v;
      for(V v : sides[1])
        if(par[v] == c) b = v;
      if(a == V() || b == V()) return std::nullopt;
      std::vector<bool> bl = blocked;
      bl[a] = false;
      const std::vector<int> path = shortest_vertex_path<Point>(g, {int(a)}, int(b), bl, w);
      if(path.size() < 4) return std::nullopt;
      // A feature loop: most of its length on sharp edges.
      double on = 0., total = 0.;
      for(std::size_t i = 0; i + 1 < path.size(); ++i)
        for(int e = g.offset[std::size_t(path[i])]; e < g.offset[std::size_t(path[i]) + 1]; ++e)
          if(g.adjacent_vertex[std::size_t(e)] == path[i + 1]) {
            const int ed = g.adjacent_edge[std::size_t(e)];
            total += g.length(ed);
            if(edge_sharp[std::size_t(ed)]) on += g.length(ed);
          }
      if(!(on >= 0.8 * total)) return std::nullopt;
      for(std::size_t i = 0; i + 1 < path.size(); ++i) {
        loop[l].push_back(par[std::size_t(path[i])]);
        blocked[std::size_t(path[i])] = true;
      }
      blocked[std::size_t(path.back())] = true;
    }
    // Sections: about as many as make the cuboids cube-like, as in strip(); the nodes on
    // loop 0 at equal arc length, on each next loop its vertex nearest to the node below.
    auto arc_length_along = [&](const std::vector<std::size_t>& l) {
      std::vector<V> vs;
      for(std::size_t v : l) vs.push_back(V(std::uint32_t(v)));
      return loop_arc_length(m, vs);
    };
    std::array<std::vector<double>, 4> loop_s;
    double W = 0.;
    for(std::size_t l = 0; l < 4; ++l) {
      loop_s[l] = arc_length_along(loop[l]);
      W += loop_s[l].back() / 4.;
    }
    const double H = meridian_length;
    const int k = std::min(32, std::max(3, int(std::lround(4. * W / H))));
    std::array<std::vector<std::size_t>, 4> node_at; // loop index of section j's node
    for(int j = 0; j < k; ++j) node_at[0].push_back(j == 0 ? 0 : at_arc_length(loop_s[0], 0, loop_s[0].back() * j / k));
    for(std::size_t l = 1; l < 4; ++l) {
      node_at[l].push_back(0);
      for(int j = 1; j < k; ++j) {
        const auto& p = m.point(V(std::uint32_t(loop[l - 1][node_at[l - 1][std::size_t(j)]])));
        std::size_t best = 1;
        for(std::size_t i = 1; i < loop[l].size(); ++i)
          if(CGAL::squared_distance(m.point(V(std::uint32_t(loop[l][i]))), p) < CGAL::squared_distance(m.point(V(std::uint32_t(loop[l][best]))), p))
            best = i;
        node_at[l].push_back(best);
      }
    }
    for(const auto& at : node_at)
      for(int j = 1; j < k; ++j)
        if(at[std::size_t(j)] <= at[std::size_t(j - 1)]) return std::nullopt;
    // The four bands: cut along the meridian and the loops, each band a disk whose border
    // runs loop l (bottom), the meridian up to loop l+1, loop l+1 back, the meridian down.
    for(const auto& l : loop)
      for(std::size_t i = 0; i < l.size(); ++i) cut[std::size_t(edge_of(l[i], l[(i + 1) % l.size()]))] = true;
    std::vector<Mesh> bands = cut_into_pieces(m, cut);
    if(bands.size() != 4) return std::nullopt;
    std::map<std::size_t, std::pair<std::size_t, std::size_t>> node_vertex; // mesh vertex -> (loop, section)
    for(std::size_t l = 0; l < 4; ++l)
      for(int j = 0; j < k; ++j) node_vertex[loop[l][node_at[l][std::size_t(j)]]] = {l, std::size_t(j)};
    std::vector<Embedding> emb;
    try { // an embedding that fails (a map that flips) leaves the generic ring
      for(Mesh& band : bands) {
        const std::vector<std::size_t> bpar = vertex_parents(band);
        std::vector<V> border = border_loop(band);
        // Its corners: the copies of crossings (section 0 on two loops, twice each).
        std::vector<std::size_t> corner;
        for(std::size_t i = 0; i < border.size(); ++i) {
          auto it = node_vertex.find(bpar[border[i]]);
          if(it != node_vertex.end() && it->second.second == 0) corner.push_back(i);
        }
        if(corner.size() != 4) return std::nullopt;
        // Start at a corner followed by a loop side (a side of the meridian runs through no
        // node but its ends; a loop side through k - 1).
        auto nodes_after = [&](std::size_t q) { // strictly between corner q and the next one
          const std::size_t n = border.size(), to = corner[(q + 1) % 4] + (q == 3 ? n : 0);
          std::size_t c = 0;
          for(std::size_t i = corner[q] + 1; i < to; ++i) c += node_vertex.count(bpar[border[i % n]]);
          return c;
        };
        std::size_t first = 0;
        while(first < 4 && nodes_after(first) == 0) ++first;
        if(first == 4 || nodes_after(first) != std::size_t(k - 1) || nodes_after((first + 1) % 4) != 0 ||
           nodes_after((first + 2) % 4) != std::size_t(k - 1) || nodes_after((first + 3) % 4) != 0)
          return std::nullopt;
        const std::size_t offset = corner[first];
        std::rotate(border.begin(), border.begin() + std::ptrdiff_t(offset), border.end());
        for(std::size_t& c : corner) c = (c + border.size() - offset) % border.size();
        std::sort(corner.begin(), corner.end());
        const std::vector<double> s = loop_arc_length(band, border);
        const double bw = 0.5 * ((s[corner[1]] - s[corner[0]]) + (s[corner[3]] - s[corner[2]]));
        const double bh = 0.5 * ((s[corner[2]] - s[corner[1]]) + (s.back() - s[corner[3]]));
        Piece_graph pg;
        pg.anchors = {{corner[0], {0, 0}}, {corner[1], {bw, 0}}, {corner[2], {bw, bh}}, {corner[3], {0, bh}}};
        // Section j's node on the bottom and on the top side.
        std::map<std::size_t, std::size_t> bottom, top;
        for(std::size_t i = corner[0] + 1; i < corner[3]; ++i) {
          auto it = node_vertex.find(bpar[border[i]]);
          if(it != node_vertex.end() && it->second.second != 0) (i < corner[1] ? bottom : top)[it->second.second] = i;
        }
        if(bottom.size() != std::size_t(k - 1) || top.size() != std::size_t(k - 1)) return std::nullopt;
        for(int j = 1; j < k; ++j) {
          pg.border_nodes.push_back(bottom.at(std::size_t(j)));
          pg.border_nodes.push_back(top.at(std::size_t(j)));
          pg.segments.push_back({{pg.border_nodes.size() - 2, pg.border_nodes.size() - 1}});
        }
        emb.push_back(embed_piece_graph(band, border, pg));
      }
    } catch(const Internal_error&) {
      return std::nullopt;
    }
    Glued_mesh<Point> gl = glue_pieces(m, bands);
    Layout_builder bld;
    std::vector<std::array<std::size_t, 4>> section(std::size_t(k + 1));
    for(int j = 0; j < k; ++j)
      for(std::size_t l = 0; l < 4; ++l) section[std::size_t(j)][l] = bld.node(loop[l][node_at[l][std::size_t(j)]]);
    section[std::size_t(k)] = section[0];
    for(std::size_t b = 0; b < bands.size(); ++b)
      for(const auto& path : emb[b].path) bld.arc(final_path(gl, b, path));
    for(const auto& l : loop) bld.loop_arcs(l);
    bld.loop_arcs(meridian);
    add_sections(bld, section, true);
    try {
      Layout L = finish_layout(std::move(gl.mesh), bld, Layout_class::torus, 1, 0, 0);
      if(!L.validate().is_valid()) return std::nullopt;
      return L;
    } catch(const Internal_error&) {
      return std::nullopt;
    }
  }

  static Layout torus(const TriangleMesh& tm, const Surface_topology_result<TriangleMesh>& topo)
  {
    using namespace internal;
    if(topo.handle_loops.empty()) layout_failure("the torus has no handle loop");
    Mesh m = copy_of(topo.loop_mesh(tm));
    std::vector<std::size_t> meridian;
    for(auto v : topo.handle_loops[0].vertices) meridian.push_back(std::size_t(v));
    if(std::optional<Layout> ring = feature_ring(m, meridian)) return std::move(*ring);
    std::vector<bool> cut(num_edges(m), false);
    auto mark = [&](std::size_t a, std::size_t b) {
      const auto h = halfedge(V(std::uint32_t(a)), V(std::uint32_t(b)), m);
      if(!h.second) layout_failure("a loop is not an edge path");
      cut[edge(h.first, m)] = true;
    };
    for(std::size_t i = 0; i < meridian.size(); ++i) mark(meridian[i], meridian[(i + 1) % meridian.size()]);
    std::vector<Mesh> annulus = cut_into_pieces(m, cut);
    if(annulus.size() != 1) layout_failure("the meridian separates the torus");
    const std::vector<std::size_t> par = vertex_parents(annulus[0]);
    const auto sides = all_border_loops<Point>(annulus[0]);
    if(sides.size() != 2) layout_failure("cutting the torus along its meridian does not give an annulus");
    Mesh_graph<Mesh> g(annulus[0], get(CGAL::vertex_point, annulus[0]));
    std::vector<bool> blocked(num_vertices(annulus[0]), false);
    for(const auto& l : sides)
      for(V v : l) blocked[v] = true;
    // The seam: the shortest path between the two copies of a meridian vertex, over a few
    // meridian vertices (deterministic choice: shortest, then first).
    std::vector<int> best;
    double best_length = std::numeric_limits<double>::infinity();
    for(int t = 0; t < 4; ++t) {
      const V a = sides[0][sides[0].size() * std::size_t(t) / 4];
      V b;
      for(V v : sides[1])
        if(par[v] == par[a]) b = v;
      if(b == V()) continue;
      std::vector<bool> bl = blocked;
      bl[a] = false;
      const std::vector<int> path = shortest_vertex_path<Point>(g, {int(a)}, int(b), bl);
      if(path.size() < 2) continue;
      double len = 0;
      for(std::size_t i = 0; i + 1 < path.size(); ++i) len += edge_length(annulus[0], V(std::uint32_t(path[i])), V(std::uint32_t(path[i + 1])));
      if(len < best_length) {
        best_length = len;
        best = path;
      }
    }
    if(best.empty()) layout_failure("no seam crosses the torus' meridian");
    std::vector<std::size_t> seam;
    for(int v : best) seam.push_back(par[std::size_t(v)]);
    for(std::size_t i = 0; i + 1 < seam.size(); ++i) mark(seam[i], seam[i + 1]);
    std::rotate(meridian.begin(), std::find(meridian.begin(), meridian.end(), seam.front()), meridian.end());
    return strip(std::move(m), cut, seam, meridian, meridian, true, 1, 0);
  }

  // ---------------------------------------------------------------- pants ------------
  static Layout pants_layout(const TriangleMesh& tm, const Pants_decomposition_result<TriangleMesh>& pd, bool balance)
  {
    using namespace internal;
    Mesh m = copy_of(pd.mesh(tm));
    const std::size_t nc = pd.cycles.size();
    std::vector<int> cycle_of(num_vertices(m), -1);
    std::vector<bool> cut(num_edges(m), false);
    for(std::size_t c = 0; c < nc; ++c) {
      const auto& vs = pd.cycles[c].vertices;
      for(std::size_t i = 0; i < vs.size(); ++i) {
        cycle_of[std::size_t(vs[i])] = int(c);
        if(pd.cycles[c].kind == Pants_cycle<TriangleMesh>::INPUT_BOUNDARY) continue;
        const auto h = halfedge(V(std::uint32_t(std::size_t(vs[i]))), V(std::uint32_t(std::size_t(vs[(i + 1) % vs.size()]))), m);
        if(!h.second) layout_failure("a cycle is not an edge path");
        cut[edge(h.first, m)] = true;
      }
    }
    std::vector<Mesh> pants = cut_into_pieces(m, cut);
    if(pants.size() != pd.pants.size()) layout_failure("the cycles do not cut the surface into its pants");
    // corners[c]: the 4 vertices of m on cycle c, in the cycle's order, once placed.
    std::vector<std::vector<std::size_t>> corners(nc);
    Layout_builder bld;
    std::vector<std::vector<Mesh>> hexagons(pants.size());
    std::vector<std::vector<Embedding>> embeddings(pants.size());
    std::vector<std::array<int, 3>> loop_cycle(pants.size());
    std::vector<int> stem(pants.size(), 0);
    std::vector<bool> input_cycle(nc);
    for(std::size_t c = 0; c < nc; ++c) input_cycle[c] = pd.cycles[c].kind == Pants_cycle<TriangleMesh>::INPUT_BOUNDARY;
    for(std::size_t k = 0; k < pants.size(); ++k)
      pants_piece(pants[k], cycle_of, input_cycle, corners, hexagons[k], embeddings[k], loop_cycle[k], stem[k], balance);
    // Glue the refined halves into their pants, the pants into the surface.
    std::vector<Glued_mesh<Point>> glued_pants;
    std::vector<Mesh> refined_pants;
    for(std::size_t k = 0; k < pants.size(); ++k) {
      glued_pants.push_back(glue_pieces(pants[k], hexagons[k]));
      refined_pants.push_back(glued_pants.back().mesh);
    }
    Glued_mesh<Point> gl = glue_pieces(m, refined_pants);
    auto final_of = [&](std::size_t k, std::size_t h, V v) {
      return std::size_t(gl.piece_to_result[k][std::size_t(glued_pants[k].piece_to_result[h][std::size_t(v)])]);
    };
    // Nodes: the corners of every cycle first (cycle order), then the centre nodes.
    for(std::size_t c = 0; c < nc; ++c)
      for(std::size_t v : corners[c]) bld.node(v);
    for(std::size_t k = 0; k < pants.size(); ++k) {
      const auto& E = embeddings[k];
      // Graph layout per hexagon (see pants_piece): 0..5 corners, 6..9 crossings, 10..13
      // centre nodes N_AS, N_SB, N_BT, N_AT; segments 0..5 corner links, 6..9 crossing
      // links, 10..13 the centre face.
      std::array<std::array<std::size_t, 4>, 2> N{};
      for(std::size_t h = 0; h < 2; ++h)
        for(std::size_t i = 0; i < 4; ++i) N[h][i] = bld.node(final_of(k, h, E[h].vertex[10 + i]));
      for(std::size_t h = 0; h < 2; ++h) {
        for(std::size_t sgm = 0; sgm < 6; ++sgm) {
          std::vector<std::size_t> p;
          for(V v : E[h].path[sgm]) p.push_back(final_of(k, h, v));
          bld.arc(p);
        }
        for(std::size_t sgm = 10; sgm < 14; ++sgm) {
          std::vector<std::size_t> p;
          for(V v : E[h].path[sgm]) p.push_back(final_of(k, h, v));
          bld.arc(p);
        }
      }
      // Crossing links: the halves in both hexagons meeting at the same crossing vertex
      // form one arc from a front centre node to a back one.
      for(std::size_t i = 6; i < 10; ++i) {
        std::vector<std::size_t> front;
        for(V v : E[0].path[i]) front.push_back(final_of(k, 0, v));
        bool joined = false;
        for(std::size_t j = 6; j < 10 && !joined; ++j) {
          std::vector<std::size_t> back;
          for(V v : E[1].path[j]) back.push_back(final_of(k, 1, v));
          if(back.front() != front.front()) continue;
          std::vector<std::size_t> arc(front.rbegin(), front.rend());
          arc.insert(arc.end(), back.begin() + 1, back.end());
          bld.arc(arc);
          joined = true;
        }
        if(!joined) layout_failure("the two halves of a pants disagree on a cutting curve");
      }
      // Centre cube (x from arm A of half 0 to arm B, y from half 0 to half 1, z from the
      // stem up): half 0: N_AS (0,0,0), N_SB (1,0,0), N_BT (1,0,1), N_AT (0,0,1); half 1 has
      // A and B swapped: N_AS (1,1,0), N_SB (0,1,0), N_BT (0,1,1), N_AT (1,1,1).
      std::array<std::size_t, 8> centre{};
      centre[0] = N[0][0]; centre[1] = N[0][1]; centre[5] = N[0][2]; centre[4] = N[0][3];
      centre[3] = N[1][0]; centre[2] = N[1][1]; centre[6] = N[1][2]; centre[7] = N[1][3];
      bld.cuboids.push_back(centre);
      bld.cuboid_pants.push_back(int(k));
      // Arms: each corner link joins a corner (graph 0..5) to a centre node; segment s
      // joins corner s to the centre node listed here (see pants_piece).
      const std::size_t link_node[6] = {3, 0, 0, 1, 1, 2};
      // Which arm each corner link belongs to: 0 = A, 1 = S, 2 = B (of that half).
      const int link_arm[6] = {0, 0, 1, 1, 2, 2};
      // Arm of half 0's A = L (x = 0), B = R (x = 1); in half 1 they swap.
      std::array<std::array<std::size_t, 8>, 3> arm{}; // L, R, S
      std::array<int, 3> filled{{0, 0, 0}};
      auto coords = [&](std::size_t node, int c[3]) {
        for(int q = 0; q < 8; ++q)
          if(centre[std::size_t(q)] == node) { c[0] = q & 1; c[1] = (q >> 1) & 1; c[2] = (q >> 2) & 1; return; }
        layout_failure("an arm does not end at the centre cuboid");
      };
      for(std::size_t h = 0; h < 2; ++h)
        for(std::size_t sgm = 0; sgm < 6; ++sgm) {
          const std::size_t inner = N[h][link_node[sgm]];
          const std::size_t outer = bld.node(final_of(k, h, E[h].vertex[sgm]));
          int which = link_arm[sgm] == 1 ? 2 : ((link_arm[sgm] == 0) == (h == 0) ? 0 : 1);
          int c[3];
          coords(inner, c);
          // Local axes of an arm: i from its cycle (0) to the centre (1); (a, b) the two
          // other centre coordinates.
          const int a = which == 2 ? c[0] : c[1], b = which == 2 ? c[1] : c[2];
          arm[std::size_t(which)][std::size_t(1 + 2 * a + 4 * b)] = inner;
          arm[std::size_t(which)][std::size_t(0 + 2 * a + 4 * b)] = outer;
          ++filled[std::size_t(which)];
        }
      for(int w = 0; w < 3; ++w) {
        if(filled[std::size_t(w)] != 4) layout_failure("an arm of a pants has " + std::to_string(filled[std::size_t(w)]) + " corners instead of 4");
        bld.cuboids.push_back(arm[std::size_t(w)]);
        bld.cuboid_pants.push_back(int(k));
        // The arm's interface with the centre.
        const auto& q = arm[std::size_t(w)];
        bld.interior.push_back({int(Layout::INTERFACE), {{q[1], q[3], q[7], q[5]}}});
      }
    }
    // Cycle arcs and the quads spanning the cycles.
    for(std::size_t c = 0; c < nc; ++c) {
      std::vector<std::size_t> loop;
      for(auto v : pd.cycles[c].vertices) loop.push_back(std::size_t(v));
      bld.loop_arcs(loop);
      std::array<std::size_t, 4> q{};
      for(std::size_t i = 0; i < 4; ++i) q[i] = bld.node(corners[c][i]);
      const bool cap = pd.cycles[c].kind == Pants_cycle<TriangleMesh>::INPUT_BOUNDARY;
      bld.interior.push_back({int(cap ? Layout::CAP : Layout::INTERFACE), q});
    }
    return finish_layout(std::move(gl.mesh), bld, Layout_class::pants, pd.genus, pd.boundary_loops, pd.pants.size());
  }

  /// Places seeds, corners and the cutting curves of one pants `P` (a piece of `m`), cuts it
  /// into two halves and embeds the half-polycube graph in each.
  static void pants_piece(Mesh& P, const std::vector<int>& cycle_of, const std::vector<bool>& input_cycle,
                          std::vector<std::vector<std::size_t>>& corners,
                          std::vector<Mesh>& halves, std::vector<Embedding>& emb, std::array<int, 3>& loop_cycle, int& stem,
                          bool balance)
  {
    using namespace internal;
    const std::vector<std::size_t> par = vertex_parents(P);
    const auto loops = all_border_loops<Point>(P);
    if(loops.size() != 3) layout_failure("a pants patch does not have 3 boundaries");
    Mesh_graph<Mesh> g(P, get(CGAL::vertex_point, P));
    const std::vector<Eigen::Vector3d> normal = g.vertex_normals();
    std::array<std::vector<double>, 3> dist, s;
    for(int i = 0; i < 3; ++i) {
      std::vector<int> roots;
      for(V v : loops[std::size_t(i)]) roots.push_back(int(v));
      dist[std::size_t(i)] = distances_from<Point>(g, roots);
      s[std::size_t(i)] = loop_arc_length(P, loops[std::size_t(i)]);
      loop_cycle[std::size_t(i)] = cycle_of[par[loops[std::size_t(i)][0]]];
    }
    // seed[i][j]: index on loop i of the seed joined to loop j; corner[i]: 4 loop indices.
    std::array<std::array<std::size_t, 3>, 3> seed{};
    std::array<std::array<std::size_t, 4>, 3> corner{};
    for(int i = 0; i < 3; ++i) {
      const auto& L = loops[std::size_t(i)];
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      std::vector<std::size_t>& placed = corners[std::size_t(loop_cycle[std::size_t(i)])];
      // Seeds in two opposite gaps between the corners, at the gaps' middles: the pair and
      // assignment that bring the seeds nearest to the loops they join.
      auto seeds_between_corners = [&]() {
        std::array<std::size_t, 4> mid{};
        for(int c = 0; c < 4; ++c) {
          const std::size_t a = corner[std::size_t(i)][std::size_t(c)], b = corner[std::size_t(i)][std::size_t((c + 1) % 4)];
          double gap = s[std::size_t(i)][b] - s[std::size_t(i)][a];
          if(gap <= 0) gap += s[std::size_t(i)].back();
          mid[std::size_t(c)] = at_arc_length(s[std::size_t(i)], a, 0.5 * gap);
        }
        double best = std::numeric_limits<double>::infinity();
        for(int pair = 0; pair < 2; ++pair)
          for(int swap = 0; swap < 2; ++swap) {
            const std::size_t sj = mid[std::size_t(pair + 2 * swap)], sk = mid[std::size_t(pair + 2 * (1 - swap))];
            const double cost = dist[std::size_t(j)][L[sj]] + dist[std::size_t(k)][L[sk]];
            if(cost < best) {
              best = cost;
              seed[std::size_t(i)][std::size_t(j)] = sj;
              seed[std::size_t(i)][std::size_t(k)] = sk;
            }
          }
      };
      std::optional<std::array<std::size_t, 4>> sharp;
      if(placed.empty()) {
        std::vector<Eigen::Vector3d> p;
        for(V v : L) p.push_back(g.position[std::size_t(v)]);
        sharp = sharp_corners(p, axis_at_loop(P, g, L));
      }
      if(sharp) {
        // Free, on a tube of rectangular section (CAD): the corners on its four sharp edges.
        // At 1/8, ..., 7/8 of the loop they fell in the middle of its flat sides (anchor.off:
        // every corner of its handle loops), every patch then folded over a sharp edge.
        corner[std::size_t(i)] = *sharp;
        for(int c = 0; c < 4; ++c) placed.push_back(par[L[corner[std::size_t(i)][std::size_t(c)]]]);
        seeds_between_corners();
      } else if(placed.empty()) {
        // Free: the seed toward the nearer neighbour is its closest point, the other seed
        // opposite by arc length, corners at 1/8, 3/8, 5/8, 7/8 (§2.2.2.2 c).
        std::size_t bj = 0, bk = 0;
        for(std::size_t x = 0; x < L.size(); ++x) {
          if(dist[std::size_t(j)][L[x]] < dist[std::size_t(j)][L[bj]]) bj = x;
          if(dist[std::size_t(k)][L[x]] < dist[std::size_t(k)][L[bk]]) bk = x;
        }
        const bool toward_j = dist[std::size_t(j)][L[bj]] <= dist[std::size_t(k)][L[bk]];
        const std::size_t first = toward_j ? bj : bk;
        const std::size_t second = at_arc_length(s[std::size_t(i)], first, 0.5 * s[std::size_t(i)].back());
        seed[std::size_t(i)][std::size_t(j)] = toward_j ? first : second;
        seed[std::size_t(i)][std::size_t(k)] = toward_j ? second : first;
        for(int c = 0; c < 4; ++c) corner[std::size_t(i)][std::size_t(c)] = at_arc_length(s[std::size_t(i)], first, s[std::size_t(i)].back() * (0.125 + 0.25 * c));
        // An input boundary's corners move off the teeth of its zigzag, by at most 1/32 of the
        // loop, so they keep clear of the seeds (1/8 away) and of each other. Not the cycles
        // the pants stage traced: edge paths zigzag too, and their corners are where they are
        // (moved, plate6.off's volume is no longer valid at any grid).
        std::array<std::size_t, 4> nudged = corner[std::size_t(i)];
        if(input_cycle[std::size_t(loop_cycle[std::size_t(i)])])
          for(std::size_t& c : nudged) c = straightest_near<Point>(g, normal, L, s[std::size_t(i)], c, s[std::size_t(i)].back() / 32.);
        std::array<std::size_t, 4> sorted = nudged;
        std::sort(sorted.begin(), sorted.end());
        const bool apart = std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end() &&
                           std::find(sorted.begin(), sorted.end(), first) == sorted.end() &&
                           std::find(sorted.begin(), sorted.end(), second) == sorted.end();
        if(apart) corner[std::size_t(i)] = nudged;
        std::sort(corner[std::size_t(i)].begin(), corner[std::size_t(i)].end());
        // Record in the cycle's own order (the cycle is a loop of m vertices).
        for(int c = 0; c < 4; ++c) placed.push_back(par[L[corner[std::size_t(i)][std::size_t(c)]]]);
      } else {
        // Imposed by a neighbour: the seeds between its corners.
        int found = 0;
        for(std::size_t x = 0; x < L.size(); ++x)
          if(std::find(placed.begin(), placed.end(), par[L[x]]) != placed.end()) corner[std::size_t(i)][std::size_t(found++ % 4)] = x;
        if(found != 4) layout_failure("imposed corners are not on the pants' boundary");
        seeds_between_corners();
      }
      for(int c = 0; c < 4; ++c)
        for(int t : {j, k})
          if(corner[std::size_t(i)][std::size_t(c)] == seed[std::size_t(i)][std::size_t(t)]) layout_failure("a boundary is too coarse for its seeds and corners");
    }
    // Cutting curves W_ij, shortest first, disjoint from each other and from the borders.
    std::vector<bool> blocked(num_vertices(P), false);
    for(const auto& L : loops)
      for(V v : L) blocked[v] = true;
    std::array<std::pair<int, int>, 3> pairs{{{0, 1}, {1, 2}, {2, 0}}};
    std::sort(pairs.begin(), pairs.end(), [&](auto a, auto b) {
      const double da = dist[std::size_t(a.second)][loops[std::size_t(a.first)][seed[std::size_t(a.first)][std::size_t(a.second)]]];
      const double db = dist[std::size_t(b.second)][loops[std::size_t(b.first)][seed[std::size_t(b.first)][std::size_t(b.second)]]];
      return da != db ? da < db : a < b;
    });
    std::array<std::array<std::vector<V>, 3>, 3> W; // W[i][j] from loop i to loop j
    std::array<std::array<double, 3>, 3> W_length{};
    std::vector<bool> cut(num_edges(P), false);
    for(auto [i, j] : pairs) {
      const V a = loops[std::size_t(i)][seed[std::size_t(i)][std::size_t(j)]], b = loops[std::size_t(j)][seed[std::size_t(j)][std::size_t(i)]];
      std::vector<bool> bl = blocked;
      bl[a] = false;
      const std::vector<int> path = shortest_vertex_path<Point>(g, {int(a)}, int(b), bl);
      if(path.size() < 2) layout_failure("no room for a cutting curve between two boundaries of a pants");
      std::vector<V> w;
      for(int v : path) w.push_back(V(std::uint32_t(v)));
      for(std::size_t x = 0; x + 1 < w.size(); ++x) {
        blocked[w[x]] = blocked[w[x + 1]] = true;
        cut[edge(halfedge(w[x], w[x + 1], P).first, P)] = true;
        W_length[std::size_t(i)][std::size_t(j)] += edge_length(P, w[x], w[x + 1]);
      }
      W_length[std::size_t(j)][std::size_t(i)] = W_length[std::size_t(i)][std::size_t(j)];
      W[std::size_t(j)][std::size_t(i)] = std::vector<V>(w.rbegin(), w.rend());
      W[std::size_t(i)][std::size_t(j)] = std::move(w);
    }
    // The stem is the boundary opposite the longest cutting curve (that curve crosses the
    // centre cuboid's top, §2.2.2.4).
    {
      double longest = -1;
      for(auto [i, j] : pairs)
        if(W_length[std::size_t(i)][std::size_t(j)] > longest) {
          longest = W_length[std::size_t(i)][std::size_t(j)];
          stem = 3 - i - j;
        }
    }
    // Crossing vertices on the W curves, as vertices of P: 1/2 of each stem curve, 1/3 and
    // 2/3 of the long one.
    auto point_on = [&](int i, int j, double f) {
      const auto& w = W[std::size_t(i)][std::size_t(j)];
      const double target = f * W_length[std::size_t(i)][std::size_t(j)];
      double acc = 0;
      std::size_t best = 1;
      double bd = std::numeric_limits<double>::infinity();
      for(std::size_t x = 1; x + 1 < w.size(); ++x) {
        acc += edge_length(P, w[x - 1], w[x]);
        if(std::abs(acc - target) < bd) {
          bd = std::abs(acc - target);
          best = x;
        }
      }
      if(w.size() < 3) layout_failure("a cutting curve is too short for its crossings");
      return w[best];
    };
    halves = cut_into_pieces(P, cut);
    if(halves.size() != 2) layout_failure("the cutting curves do not split a pants into two halves");
    for(std::size_t h = 0; h < 2; ++h) {
      Mesh& H = halves[h];
      const std::vector<std::size_t> hp = vertex_parents(H); // -> P
      const std::vector<V> loop = border_loop(H);
      const std::size_t n = loop.size();
      // Which loop of P each border vertex of the half lies on (-1 on a W curve only).
      auto loop_of = [&](std::size_t x) {
        const V v = V(static_cast<std::uint32_t>(hp[loop[x]]));
        for(int i = 0; i < 3; ++i)
          if(std::find(loops[std::size_t(i)].begin(), loops[std::size_t(i)].end(), v) != loops[std::size_t(i)].end()) return i;
        return -1;
      };
      // Runs of boundary vertices: find, going around, the boundary halves (maximal runs on
      // one loop with at least one edge along it) in order.
      std::vector<int> on(n);
      for(std::size_t x = 0; x < n; ++x) on[x] = loop_of(x);
      auto along_loop = [&](std::size_t x) { // edge x -> x+1 lies on a loop of P
        const std::size_t y = (x + 1) % n;
        if(on[x] < 0 || on[x] != on[y]) return false;
        const auto& L = loops[std::size_t(on[x])];
        const V a = V(static_cast<std::uint32_t>(hp[loop[x]])), b = V(static_cast<std::uint32_t>(hp[loop[y]]));
        const auto pa = std::find(L.begin(), L.end(), a) - L.begin(), pb = std::find(L.begin(), L.end(), b) - L.begin();
        const long d = std::labs(long(pa) - long(pb));
        return d == 1 || d == long(L.size()) - 1;
      };
      // Order of boundaries met; the long curve joins the two non-stem boundaries: A is the
      // one after it.
      std::vector<int> order;
      std::vector<std::size_t> run_start;
      for(std::size_t x = 0; x < n; ++x)
        if(along_loop(x) && !along_loop((x + n - 1) % n)) {
          order.push_back(on[x]);
          run_start.push_back(x);
        }
      if(order.size() != 3) layout_failure("a half of a pants is not a hexagon");
      std::size_t a_run = 3;
      for(std::size_t r = 0; r < 3; ++r)
        if(order[r] != stem && order[(r + 2) % 3] != stem) a_run = r;
      if(a_run == 3 || order[(a_run + 1) % 3] != stem) layout_failure("a half of a pants has its boundaries in an unexpected order");
      const int A = order[a_run], B = order[(a_run + 2) % 3];
      Piece_graph pg;
      pg.anchors = circle_anchors(H, loop);
      // Corners of each boundary half in loop order: A c1 c2, S c1 c2, B c1 c2 (0..5).
      for(int r = 0; r < 3; ++r) {
        const std::size_t run = (a_run + std::size_t(r)) % 3;
        const int i = order[run];
        int got = 0;
        for(std::size_t x = run_start[run]; got < 2; x = (x + 1) % n) {
          if(on[x] != i) layout_failure("a boundary half lost its corners");
          const V v = V(static_cast<std::uint32_t>(hp[loop[x]]));
          for(int c = 0; c < 4; ++c)
            if(loops[std::size_t(i)][corner[std::size_t(i)][std::size_t(c)]] == v) {
              pg.border_nodes.push_back(x);
              ++got;
            }
          if(!along_loop(x) && got < 2) layout_failure("a boundary half does not carry two corners");
        }
      }
      // Crossings 6..9: W(A,S) at 1/2, W(S,B) at 1/2, then on W(B,A) the one nearer B and
      // the one nearer A.
      const V crossing[4] = {point_on(A, stem, 0.5), point_on(stem, B, 0.5), point_on(B, A, 1. / 3.), point_on(B, A, 2. / 3.)};
      for(const V c : crossing) {
        std::size_t at = n;
        for(std::size_t x = 0; x < n; ++x)
          if(hp[loop[x]] == std::size_t(c)) at = x;
        if(at == n) layout_failure("a crossing is not on the border of its half");
        pg.border_nodes.push_back(at);
      }
      for(int c = 0; c < 4; ++c) pg.interior_uv.push_back(Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 0.));
      // Centre nodes 10..13: N_AS, N_SB, N_BT, N_AT.
      const std::array<std::array<std::size_t, 2>, 14> seg{{{{0, 13}}, {{1, 10}}, {{2, 10}}, {{3, 11}}, {{4, 11}}, {{5, 12}},
                                                             {{6, 10}}, {{7, 11}}, {{8, 12}}, {{9, 13}},
                                                             {{10, 11}}, {{11, 12}}, {{12, 13}}, {{13, 10}}}};
      pg.segments.assign(seg.begin(), seg.end());
      pg.balance_corners = balance;
      emb.push_back(embed_piece_graph(H, loop, pg));
    }
  }
};

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_CUBOID_DECOMPOSITION_H
