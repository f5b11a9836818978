// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Pants_decomposition: cuts a connected orientable surface with chi = 2-2g-b < 0 into
// 2g+b-2 pants patches (genus 0, three boundaries) along 3g+b-3 cycles, following the
// reference §2.2.1 (Algorithms 1 and 2). The surface is first sliced along its g handle
// loops (Surface_topology: they bound disks inside the solid, so every cut can later become
// a face between cuboids). The sliced surface is a sphere with 2g+b holes W. Repeatedly, the
// pair (w_i, w_j) whose enclosing cycle promises to be shortest (length of both plus twice
// their distance) is chosen, and the cycle w_ij homotopic to w_i o w_j is traced as a
// minimum cut in the dual graph between {w_i, w_j, a shortest path joining them} and {the
// other holes joined by shortest paths}: on a genus-0 region that is the shortest closed
// curve separating them, which Algorithm 2 finds by sweeping paths across a cylinder. The
// pants bounded by w_i, w_j, w_ij is removed, until three holes remain.
//
// Every cycle runs along mesh edges and keeps off the vertices of the other cycles (the cut
// capacities of edges touching them are infinite), so the cycles are simple and pairwise
// vertex-disjoint and every pants is a valid surface. Where a region is too thin for that,
// the mesh is refined at edge midpoints (geometry unchanged, decisions combinatorial) and the
// decomposition restarted. Edge weights follow the chosen geometric criterion (Cut_criteria.h).

#ifndef CGAL_POLYCUBE_IGA_PANTS_DECOMPOSITION_H
#define CGAL_POLYCUBE_IGA_PANTS_DECOMPOSITION_H

#include <CGAL/Polycube_IGA/Cut_criteria.h>
#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Polycube_IGA/parameters.h>
#include <CGAL/Polycube_IGA/internal/mesh_graph.h>
#include <CGAL/Polycube_IGA/internal/mesh_refinement.h>
#include <CGAL/Polycube_IGA/internal/min_cut.h>

#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <queue>
#include <set>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// A cycle of the decomposition, along edges of the decomposition's mesh.
template <class TriangleMesh>
struct Pants_cycle
{
  enum Kind { INPUT_BOUNDARY, HANDLE_LOOP, CUT };
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  Kind kind = CUT;
  std::vector<vertex_descriptor> vertices;   ///< in order; the last joins the first
  std::vector<std::array<double, 3>> points; ///< positions of `vertices`
  double length = 0;                          ///< Euclidean length

  static const char* kind_name(Kind k) { return k == INPUT_BOUNDARY ? "boundary" : (k == HANDLE_LOOP ? "handle" : "cut"); }
};

/// \ingroup PkgPolycubeIGARef
/// A pants patch: its faces, its three boundary cycles and the pants across each
/// (-1 across an input boundary loop; itself across a handle loop with both sides in it).
template <class TriangleMesh>
struct Pants_patch
{
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  std::vector<face_descriptor> faces;
  std::array<int, 3> boundaries{{-1, -1, -1}};
  std::array<int, 3> neighbours{{-1, -1, -1}};
};

/// \ingroup PkgPolycubeIGARef
/// Result of `Pants_decomposition::validate()`.
struct Pants_validation
{
  std::vector<std::string> problems;
  bool is_valid() const { return problems.empty(); }
};

/// \ingroup PkgPolycubeIGARef
/// Result of `Pants_decomposition`.
template <class TriangleMesh>
struct Pants_decomposition_result
{
  int genus = 0;
  std::size_t boundary_loops = 0;
  /// Cycles: the b input boundary loops first, then the g handle loops, then the cuts.
  std::vector<Pants_cycle<TriangleMesh>> cycles;
  std::vector<Pants_patch<TriangleMesh>> pants;
  /// Midpoint subdivisions needed; when nonzero, faces and vertices refer to `refined_mesh`,
  /// whose first vertices are the input's.
  int refinements = 0;
  std::shared_ptr<TriangleMesh> refined_mesh;

  const TriangleMesh& mesh(const TriangleMesh& input) const { return refinements ? *refined_mesh : input; }
  std::size_t number_of_cut_cycles() const { return cycles.size() - boundary_loops; }
};

namespace internal {

/// Builds pants `k` as a surface of its own: vertices on a cycle with both sides in the
/// pants are split, as slicing would. `vertex_map[i]` is the source vertex of new vertex i.
template <class TriangleMesh, class OutputMesh>
void extract_pants_mesh(const TriangleMesh& tm, const Pants_decomposition_result<TriangleMesh>& r, std::size_t k,
                        OutputMesh& out,
                        std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>* vertex_map = nullptr)
{
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  const TriangleMesh& m = r.mesh(tm);
  std::map<face_descriptor, int> local;
  for(face_descriptor f : r.pants[k].faces) local.emplace(f, int(local.size()));
  std::set<std::pair<vertex_descriptor, vertex_descriptor>> cut;
  for(const auto& c : r.cycles)
    for(std::size_t i = 0; i < c.vertices.size(); ++i) {
      auto a = c.vertices[i], b = c.vertices[(i + 1) % c.vertices.size()];
      cut.insert({std::min(a, b), std::max(a, b)});
    }
  // Corners (face, vertex) joined across non-cut edges of the pants form its vertices.
  std::map<std::pair<int, vertex_descriptor>, int> corner;
  std::vector<int> parent;
  auto find = [&](int x) { while(parent[x] != x) { parent[x] = parent[parent[x]]; x = parent[x]; } return x; };
  for(face_descriptor f : r.pants[k].faces)
    for(vertex_descriptor v : vertices_around_face(halfedge(f, m), m)) {
      corner.emplace(std::make_pair(local[f], v), int(parent.size()));
      parent.push_back(int(parent.size()));
    }
  for(face_descriptor f : r.pants[k].faces)
    for(auto h : halfedges_around_face(halfedge(f, m), m)) {
      auto a = source(h, m), b = target(h, m);
      if(cut.count({std::min(a, b), std::max(a, b)}) || is_border(opposite(h, m), m)) continue;
      auto it = local.find(face(opposite(h, m), m));
      if(it == local.end()) continue;
      for(auto v : {a, b}) {
        const int x = find(corner[{local[f], v}]), y = find(corner[{it->second, v}]);
        if(x != y) parent[std::max(x, y)] = std::min(x, y);
      }
    }
  out.clear();
  std::map<int, typename boost::graph_traits<OutputMesh>::vertex_descriptor> made;
  if(vertex_map) vertex_map->clear();
  for(const auto& [key, id] : corner) {
    const int root = find(id);
    if(made.count(root)) continue;
    const auto& p = get(CGAL::vertex_point, m, key.second);
    made[root] = add_vertex(typename boost::property_traits<
      typename boost::property_map<OutputMesh, CGAL::vertex_point_t>::type>::value_type(p.x(), p.y(), p.z()), out);
    if(vertex_map) vertex_map->push_back(key.second);
  }
  for(face_descriptor f : r.pants[k].faces) {
    std::vector<typename boost::graph_traits<OutputMesh>::vertex_descriptor> fv;
    for(vertex_descriptor v : vertices_around_face(halfedge(f, m), m)) fv.push_back(made[find(corner[{local[f], v}])]);
    CGAL::Euler::add_face(fv, out);
  }
}

} // namespace internal

/*!
 * \ingroup PkgPolycubeIGARef
 * Function object computing the pants decomposition of a connected, orientable, valid
 * triangle mesh with negative Euler characteristic (`TriangleMesh` a `MutableFaceGraph`
 * with an internal `vertex_point` map, e.g. `Surface_mesh`).
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{cut_criterion}
 *     \cgalParamDescription{`Cut_criterion::LENGTH` (shortest cycles), `SYMMETRY` (cycles near
 *       a plane), `MINIMA_RULE` (cycles through concave regions)}
 *     \cgalParamDefault{`Cut_criterion::LENGTH`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{symmetry_plane}
 *     \cgalParamDescription{`std::array<double,4>` {a,b,c,d} of the plane ax+by+cz+d=0}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{criterion_strength}
 *     \cgalParamDefault{`1`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{surface_topology}
 *     \cgalParamDescription{a `Surface_topology_result` computed before (saves its cost)}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{maximum_refinements}
 *     \cgalParamDescription{midpoint subdivisions allowed when cycles do not fit}
 *     \cgalParamDefault{`4`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 *
 * Throws `Unsupported_topology_error("no_pants_decomposition")` for chi >= 0 (sphere, disk,
 * cylinder, torus), the errors of `Surface_topology`, and
 * `Internal_error("pants_decomposition_failed")` when no valid cycle fits even after refinement.
 */
template <class TriangleMesh>
class Pants_decomposition
{
public:
  using Result = Pants_decomposition_result<TriangleMesh>;
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Graph = internal::Mesh_graph<TriangleMesh>;

  template <class NamedParameters = parameters::Default_named_parameters>
  Result operator()(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values()) const
  {
    using CGAL::parameters::get_parameter;
    Cut_criterion_options criterion;
    criterion.criterion = option(np, internal_np::cut_criterion, Cut_criterion::LENGTH);
    criterion.symmetry_plane = option(np, internal_np::symmetry_plane, criterion.symmetry_plane);
    criterion.strength = option(np, internal_np::criterion_strength, 1.0);
    const int max_refinements = std::max(0, int(option(np, internal_np::maximum_refinements, 4)));

    auto given = get_parameter(np, internal_np::surface_topology);
    Surface_topology_result<TriangleMesh> topology = topology_of(tm, given);
    const long chi = topology.euler_characteristic;
    if(chi >= 0)
      throw Unsupported_topology_error("no_pants_decomposition",
        "a surface of genus " + std::to_string(topology.genus) + " with " +
        std::to_string(topology.number_of_boundary_loops()) + " boundary loops (Euler characteristic " +
        std::to_string(chi) + " >= 0) has no pants decomposition; the cuboid stage handles it directly");

    Result result;
    result.genus = topology.genus;
    result.boundary_loops = topology.number_of_boundary_loops();
    // Work on the input, or on a refined copy when loops need room (never on the user's objects).
    std::shared_ptr<TriangleMesh> refined = topology.refinements ? topology.refined_mesh : nullptr;
    result.refinements = topology.refinements;
    std::vector<std::vector<vertex_descriptor>> handles;
    for(const auto& h : topology.handle_loops) handles.push_back(h.vertices);

    for(int attempt = 0;; ++attempt) {
      const TriangleMesh& m = refined ? *refined : tm;
      Graph g(m, get(CGAL::vertex_point, m));
      const std::vector<double> w = cut_edge_weights(g, criterion);
      if(decompose(g, w, handles, result)) break;
      if(attempt == max_refinements)
        throw Internal_error("pants_decomposition_failed",
                             "no set of disjoint simple cutting cycles fits, even after " +
                             std::to_string(max_refinements) + " refinements");
      refined = std::make_shared<TriangleMesh>(m);
      handles = refine(*refined, handles);
      ++result.refinements;
    }
    result.refined_mesh = refined;
    return result;
  }

  /// Checks every invariant: counts, each pants connected with genus 0 and 3 boundary
  /// loops, cycles simple and pairwise disjoint, every face in exactly one pants.
  static Pants_validation validate(const TriangleMesh& tm, const Result& r)
  {
    Pants_validation v;
    const TriangleMesh& m = r.mesh(tm);
    const long g = r.genus, b = long(r.boundary_loops);
    if(long(r.pants.size()) != 2 * g + b - 2)
      v.problems.push_back("expected " + std::to_string(2 * g + b - 2) + " pants, found " + std::to_string(r.pants.size()));
    if(long(r.number_of_cut_cycles()) != 3 * g + b - 3)
      v.problems.push_back("expected " + std::to_string(3 * g + b - 3) + " cut cycles, found " +
                           std::to_string(r.number_of_cut_cycles()));
    std::map<vertex_descriptor, int> owner;
    for(std::size_t c = 0; c < r.cycles.size(); ++c) {
      const auto& cyc = r.cycles[c];
      if(cyc.vertices.size() < 3) v.problems.push_back("cycle " + std::to_string(c) + " has fewer than 3 vertices");
      for(std::size_t i = 0; i < cyc.vertices.size(); ++i) {
        auto a = cyc.vertices[i], bb = cyc.vertices[(i + 1) % cyc.vertices.size()];
        if(!halfedge(a, bb, m).second) v.problems.push_back("cycle " + std::to_string(c) + " leaves the mesh edges");
        auto it = owner.emplace(a, int(c));
        if(!it.second)
          v.problems.push_back(it.first->second == int(c) ? "cycle " + std::to_string(c) + " is not simple"
                                                          : "cycles " + std::to_string(it.first->second) + " and " +
                                                              std::to_string(c) + " share a vertex");
      }
    }
    std::map<face_descriptor, int> face_owner;
    for(std::size_t k = 0; k < r.pants.size(); ++k)
      for(face_descriptor f : r.pants[k].faces)
        if(!face_owner.emplace(f, int(k)).second) v.problems.push_back("a face lies in two pants");
    if(face_owner.size() != num_faces(m)) v.problems.push_back("the pants do not cover every face");
    for(std::size_t k = 0; k < r.pants.size(); ++k) {
      CGAL::Surface_mesh<typename boost::property_traits<
        typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type>::value_type> sub;
      internal::extract_pants_mesh(tm, r, k, sub);
      std::size_t borders = 0;
      std::set<typename decltype(sub)::Halfedge_index> seen;
      for(auto h : halfedges(sub))
        if(is_border(h, sub) && !seen.count(h)) {
          ++borders;
          for(auto x : halfedges_around_face(h, sub)) seen.insert(x);
        }
      const long chi = long(num_vertices(sub)) - long(num_edges(sub)) + long(num_faces(sub));
      std::vector<int> comp(num_faces(sub), -1);
      // connectivity of the pants through its edges
      std::size_t components = 0;
      for(auto f0 : faces(sub)) {
        if(comp[f0] != -1) continue;
        ++components;
        std::vector<typename decltype(sub)::Face_index> stack{f0};
        comp[f0] = 0;
        while(!stack.empty()) {
          auto f = stack.back(); stack.pop_back();
          for(auto h : halfedges_around_face(halfedge(f, sub), sub)) {
            auto o = opposite(h, sub);
            if(is_border(o, sub)) continue;
            auto nf = face(o, sub);
            if(comp[nf] == -1) { comp[nf] = 0; stack.push_back(nf); }
          }
        }
      }
      const std::string name = "pants " + std::to_string(k);
      if(components != 1) v.problems.push_back(name + " is not connected");
      if(borders != 3) v.problems.push_back(name + " has " + std::to_string(borders) + " boundary loops instead of 3");
      if(chi != -1) v.problems.push_back(name + " has Euler characteristic " + std::to_string(chi) + " instead of -1 (genus 0, 3 boundaries)");
    }
    return v;
  }

private:
  template <class Given>
  static Surface_topology_result<TriangleMesh> topology_of(const TriangleMesh& tm, const Given& given)
  {
    if constexpr(std::is_same<Given, CGAL::internal_np::Param_not_found>::value)
      return Surface_topology<TriangleMesh>()(tm, parameters::compute_tunnel_loops(false));
    else
      return given;
  }

  // A side of a cycle, as a hole of the current region.
  struct Hole { int cycle; int side; }; // side: 0 = left of the cycle's direction, 1 = right

  struct Cycle_edges { std::vector<int> vertices, edges; };

  static Cycle_edges cycle_edges(const Graph& g, const std::vector<int>& vertices)
  {
    Cycle_edges c;
    c.vertices = vertices;
    for(std::size_t i = 0; i < vertices.size(); ++i) {
      const int a = vertices[i], b = vertices[(i + 1) % vertices.size()];
      int e = -1;
      for(int k = g.offset[a]; k < g.offset[a + 1]; ++k) if(g.adjacent_vertex[k] == b) e = g.adjacent_edge[k];
      if(e < 0) throw Internal_error("pants_decomposition_failed", "a cycle leaves the mesh edges");
      c.edges.push_back(e);
    }
    return c;
  }

  // Face on `side` of the cycle's i-th edge (left = the face whose boundary runs along it).
  static int face_on_side(const Graph& g, const Cycle_edges& c, std::size_t i, int side)
  {
    const int e = c.edges[i];
    const bool along = g.direction(e, c.vertices[i]) == 1;
    return g.edge_faces[e][(along ? 0 : 1) ^ side];
  }

  static bool decompose(const Graph& g, const std::vector<double>& w,
                        const std::vector<std::vector<vertex_descriptor>>& handle_vertices, Result& result)
  {
    const int nf = g.number_of_faces(), nv = g.number_of_vertices();
    std::map<vertex_descriptor, int> index;
    for(int v = 0; v < nv; ++v) index[g.vertex[v]] = v;

    std::vector<Cycle_edges> cycles;
    std::vector<typename Pants_cycle<TriangleMesh>::Kind> kinds;
    std::vector<Hole> holes;
    for(const auto& border : g.border_cycles) {
      // Follow the border halfedges (the cap on their left): the sources in order.
      std::vector<int> vs;
      for(int e : border) vs.push_back(g.edge_faces[e][0] >= nf ? g.edge_vertices[e][0] : g.edge_vertices[e][1]);
      cycles.push_back(cycle_edges(g, vs));
      kinds.push_back(Pants_cycle<TriangleMesh>::INPUT_BOUNDARY);
      const int left = face_on_side(g, cycles.back(), 0, 0);
      holes.push_back({int(cycles.size()) - 1, left < nf ? 0 : 1});
    }
    for(const auto& h : handle_vertices) {
      std::vector<int> vs;
      for(auto v : h) vs.push_back(index.at(v));
      cycles.push_back(cycle_edges(g, vs));
      kinds.push_back(Pants_cycle<TriangleMesh>::HANDLE_LOOP);
      holes.push_back({int(cycles.size()) - 1, 0});
      holes.push_back({int(cycles.size()) - 1, 1});
    }

    std::vector<char> is_cut(g.number_of_edges(), 0), on_cycle(nv, 0);
    for(const auto& c : cycles) {
      for(int e : c.edges) is_cut[e] = 1;
      for(int v : c.vertices) on_cycle[v] = 1;
    }
    std::vector<int> pants_of(nf, -1);
    struct Patch { std::array<int, 3> boundary; };
    std::vector<Patch> patches;

    auto hole_faces = [&](const Hole& h) {
      std::vector<int> fs;
      for(std::size_t i = 0; i < cycles[h.cycle].edges.size(); ++i) {
        const int f = face_on_side(g, cycles[h.cycle], i, h.side);
        if(f < nf && pants_of[f] == -1) fs.push_back(f);
      }
      return fs;
    };
    auto in_region = [&](int f) { return f >= 0 && f < nf && pants_of[f] == -1; };

    // Face centroids: paths between holes are chains of faces that never cross a cycle
    // edge, i.e. paths on the surface sliced along the cycles.
    std::vector<Eigen::Vector3d> centroid(nf);
    for(int f = 0; f < nf; ++f)
      centroid[f] = (g.position[g.face_vertices[f][0]] + g.position[g.face_vertices[f][1]] +
                     g.position[g.face_vertices[f][2]]) / 3.0;

    while(holes.size() > 3) {
      const int k = int(holes.size());
      std::vector<std::vector<int>> faces_of_hole(k);
      for(int i = 0; i < k; ++i) faces_of_hole[i] = hole_faces(holes[i]);
      // Dual distances from each hole.
      std::vector<Face_tree> trees;
      std::vector<std::vector<double>> dist(k, std::vector<double>(k, std::numeric_limits<double>::infinity()));
      std::vector<std::vector<int>> closest(k, std::vector<int>(k, -1));
      const std::vector<char> none(nf, 0);
      for(int i = 0; i < k; ++i) {
        trees.push_back(face_tree(g, faces_of_hole[i], is_cut, pants_of, centroid, none));
        for(int j = 0; j < k; ++j) {
          if(j == i) continue;
          for(int f : faces_of_hole[j])
            if(trees[i].distance[f] < dist[i][j]) { dist[i][j] = trees[i].distance[f]; closest[i][j] = f; }
        }
      }
      auto cycle_length = [&](int h) {
        double l = 0;
        for(int e : cycles[holes[h].cycle].edges) l += w[e];
        return l;
      };
      int bi = -1, bj = -1;
      double best = std::numeric_limits<double>::infinity();
      for(int i = 0; i < k; ++i)
        for(int j = i + 1; j < k; ++j) {
          const double estimate = cycle_length(i) + cycle_length(j) + 2 * dist[i][j];
          if(estimate < best) { best = estimate; bi = i; bj = j; }
        }
      if(bi < 0 || closest[bi][bj] < 0) return false;

      // Source: faces along holes i, j and along a shortest face chain joining them.
      std::vector<char> source(nf, 0), sink(nf, 0), near_source(nf, 0);
      auto mark_chain = [&](const Face_tree& t, int from, std::vector<char>& side) {
        for(int f = from; f >= 0; f = t.parent[f]) side[f] = 1;
      };
      for(int f : faces_of_hole[bi]) source[f] = 1;
      for(int f : faces_of_hole[bj]) source[f] = 1;
      mark_chain(trees[bi], closest[bi][bj], source);
      // Sink: the other holes, joined by face chains kept off the source's vertices.
      std::vector<char> source_vertex(nv, 0);
      // (Vertices on cycles excepted: the faces across a cycle belong to another hole.)
      for(int f = 0; f < nf; ++f) if(source[f]) for(int v : g.face_vertices[f]) source_vertex[v] = !on_cycle[v];
      for(int f = 0; f < nf; ++f)
        for(int v : g.face_vertices[f]) if(source_vertex[v]) near_source[f] = 1;
      std::vector<int> others;
      for(int i = 0; i < k; ++i) if(i != bi && i != bj) others.push_back(i);
      std::vector<int> joined{others[0]};
      std::vector<int> seeds(faces_of_hole[others[0]]);
      for(int f : seeds) sink[f] = 1;
      for(std::size_t n = 1; n < others.size(); ++n) {
        Face_tree t = face_tree(g, seeds, is_cut, pants_of, centroid, near_source);
        int next = -1, target = -1;
        double d = std::numeric_limits<double>::infinity();
        for(int h : others) {
          if(std::find(joined.begin(), joined.end(), h) != joined.end()) continue;
          for(int f : faces_of_hole[h])
            if(t.distance[f] < d) { d = t.distance[f]; next = h; target = f; }
        }
        if(next < 0) return false; // the source walls the other holes apart: refine
        joined.push_back(next);
        for(int f : faces_of_hole[next]) { sink[f] = 1; seeds.push_back(f); }
        for(int f = target; f >= 0; f = t.parent[f]) { sink[f] = 1; seeds.push_back(f); }
      }
      for(int f = 0; f < nf; ++f) if(source[f] && sink[f]) return false;

      // Minimum cut in the dual graph of the region; edges touching a cycle are uncuttable.
      std::vector<int> node(nf, -1);
      int nodes = 0;
      for(int f = 0; f < nf; ++f) if(in_region(f)) node[f] = nodes++;
      const int S = nodes, T = nodes + 1;
      internal::Min_cut cut(nodes + 2);
      for(int e = 0; e < g.number_of_edges(); ++e) {
        const int f0 = g.edge_faces[e][0], f1 = g.edge_faces[e][1];
        if(is_cut[e] || !in_region(f0) || !in_region(f1)) continue;
        const bool touches = on_cycle[g.edge_vertices[e][0]] || on_cycle[g.edge_vertices[e][1]];
        cut.add_undirected(node[f0], node[f1], touches ? internal::Min_cut::infinity() : w[e]);
      }
      for(int f = 0; f < nf; ++f) {
        if(source[f]) cut.add_directed(S, node[f], internal::Min_cut::infinity());
        if(sink[f]) cut.add_directed(node[f], T, internal::Min_cut::infinity());
      }
      if(cut.max_flow(S, T) >= 0.5 * internal::Min_cut::infinity()) return false;
      const std::vector<char> side = cut.source_side(S);

      // The cut edges must form one simple cycle.
      std::vector<int> cut_edges;
      for(int e = 0; e < g.number_of_edges(); ++e) {
        const int f0 = g.edge_faces[e][0], f1 = g.edge_faces[e][1];
        if(is_cut[e] || !in_region(f0) || !in_region(f1)) continue;
        if(side[node[f0]] != side[node[f1]]) cut_edges.push_back(e);
      }
      std::vector<int> new_cycle;
      if(!order_simple_cycle(g, cut_edges, new_cycle)) return false;
      // Orient it with the pants (source side) on its left.
      Cycle_edges c = cycle_edges(g, new_cycle);
      const int left = face_on_side(g, c, 0, 0);
      if(!(left >= 0 && left < nf && node[left] >= 0 && side[node[left]])) {
        std::reverse(new_cycle.begin(), new_cycle.end());
        c = cycle_edges(g, new_cycle);
      }
      const int id = int(patches.size());
      for(int f = 0; f < nf; ++f) if(node[f] >= 0 && side[node[f]]) pants_of[f] = id;
      patches.push_back({{holes[bi].cycle, holes[bj].cycle, int(cycles.size())}});
      for(int e : c.edges) is_cut[e] = 1;
      for(int v : c.vertices) on_cycle[v] = 1;
      cycles.push_back(c);
      kinds.push_back(Pants_cycle<TriangleMesh>::CUT);
      std::vector<Hole> rest;
      for(int i = 0; i < k; ++i) if(i != bi && i != bj) rest.push_back(holes[i]);
      rest.push_back({int(cycles.size()) - 1, 1}); // the remaining region is on its right
      holes = rest;
    }
    const int last = int(patches.size());
    for(int f = 0; f < nf; ++f) if(pants_of[f] == -1) pants_of[f] = last;
    patches.push_back({{holes[0].cycle, holes[1].cycle, holes[2].cycle}});

    // Record the result; neighbours from the faces on either side of each cycle.
    result.cycles.clear();
    result.pants.assign(patches.size(), Pants_patch<TriangleMesh>());
    for(std::size_t c = 0; c < cycles.size(); ++c) {
      Pants_cycle<TriangleMesh> pc;
      pc.kind = kinds[c];
      for(int v : cycles[c].vertices) {
        pc.vertices.push_back(g.vertex[v]);
        pc.points.push_back({g.position[v].x(), g.position[v].y(), g.position[v].z()});
      }
      for(int e : cycles[c].edges) pc.length += g.length(e);
      result.cycles.push_back(std::move(pc));
    }
    for(int f = 0; f < nf; ++f) result.pants[pants_of[f]].faces.push_back(g.face[f]);
    for(std::size_t p = 0; p < patches.size(); ++p) {
      result.pants[p].boundaries = patches[p].boundary;
      for(int s = 0; s < 3; ++s) {
        const int c = patches[p].boundary[s];
        int across = -1;
        for(int side = 0; side < 2; ++side) {
          const int f = face_on_side(g, cycles[c], 0, side);
          if(f < nf && pants_of[f] != int(p)) across = pants_of[f];
        }
        // Both sides in this pants (a handle loop kept whole): the pants is its own neighbour.
        if(across == -1 && kinds[c] != Pants_cycle<TriangleMesh>::INPUT_BOUNDARY) across = int(p);
        result.pants[p].neighbours[s] = across;
      }
    }
    return true;
  }

  struct Face_tree { std::vector<double> distance; std::vector<int> parent; };

  // Dijkstra over the faces of the region (pants_of == -1) across non-cut edges, from
  // `seeds`, never entering `blocked` faces (seeds excepted); lengths between centroids.
  static Face_tree face_tree(const Graph& g, const std::vector<int>& seeds, const std::vector<char>& is_cut,
                             const std::vector<int>& pants_of, const std::vector<Eigen::Vector3d>& centroid,
                             const std::vector<char>& blocked)
  {
    const int nf = g.number_of_faces();
    Face_tree t{std::vector<double>(nf, std::numeric_limits<double>::infinity()), std::vector<int>(nf, -1)};
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for(int f : seeds) { t.distance[f] = 0; queue.push({0.0, f}); }
    std::vector<char> settled(nf, 0);
    while(!queue.empty()) {
      auto [d, f] = queue.top();
      queue.pop();
      if(settled[f]) continue;
      settled[f] = 1;
      for(int e : g.face_edges[f]) {
        if(is_cut[e]) continue;
        const int h = g.edge_faces[e][0] == f ? g.edge_faces[e][1] : g.edge_faces[e][0];
        if(h < 0 || h >= nf || pants_of[h] != -1 || settled[h] || blocked[h]) continue;
        const double nd = d + (centroid[f] - centroid[h]).norm();
        if(nd < t.distance[h]) { t.distance[h] = nd; t.parent[h] = f; queue.push({nd, h}); }
      }
    }
    return t;
  }

  // Orders `edges` into one simple closed vertex cycle; false if they form anything else.
  static bool order_simple_cycle(const Graph& g, const std::vector<int>& edges, std::vector<int>& out)
  {
    if(edges.size() < 3) return false;
    std::map<int, std::vector<int>> incident;
    for(int e : edges) for(int v : g.edge_vertices[e]) incident[v].push_back(e);
    for(const auto& kv : incident) if(kv.second.size() != 2) return false;
    out.clear();
    const int start = g.edge_vertices[edges.front()][0];
    int v = start, e = edges.front();
    do {
      out.push_back(v);
      v = g.other_vertex(e, v);
      const auto& inc = incident[v];
      e = inc[0] == e ? inc[1] : inc[0];
    } while(v != start && out.size() <= edges.size());
    return out.size() == edges.size();
  }

  // Midpoint refinement of the working mesh; cycles follow (a, m_ab, b, ...).
  static std::vector<std::vector<vertex_descriptor>> refine(TriangleMesh& m,
                                                            const std::vector<std::vector<vertex_descriptor>>& loops)
  {
    const std::size_t old_vertices = num_vertices(m);
    internal::subdivide_at_edge_midpoints(m, get(CGAL::vertex_point, m));
    std::vector<std::vector<vertex_descriptor>> out;
    for(const auto& loop : loops) {
      std::vector<vertex_descriptor> refined;
      for(std::size_t i = 0; i < loop.size(); ++i) {
        const vertex_descriptor a = loop[i], b = loop[(i + 1) % loop.size()];
        refined.push_back(a);
        for(auto h : halfedges_around_target(a, m)) {
          const vertex_descriptor x = source(h, m);
          if(std::size_t(x) >= old_vertices && halfedge(x, b, m).second) { refined.push_back(x); break; }
        }
      }
      out.push_back(refined);
    }
    return out;
  }

};

/// \ingroup PkgPolycubeIGARef
/// Convenience: `Pants_decomposition<TriangleMesh>()(tm, np)`.
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Pants_decomposition_result<TriangleMesh> pants_decomposition(const TriangleMesh& tm,
                                                             const NamedParameters& np = parameters::default_values())
{
  return Pants_decomposition<TriangleMesh>()(tm, np);
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_PANTS_DECOMPOSITION_H
