// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Surface_topology: the first stage. For a connected, orientable triangle mesh it gives the
// genus g, the boundary loops b, the Euler characteristic, a homology basis of 2g cycles,
// and g handle loops and g tunnel loops (reference §2.1.1 and §2.2.1.2).
//
// A handle loop bounds a disk inside the solid (a meridian of a handle); a tunnel loop
// bounds a disk outside it. Only handle loops can become faces between cuboids, so the
// pants decomposition cuts along them. The classification uses linking numbers (Alexander
// duality): with the solid I and its complement O, a cycle c on the surface bounds in I iff
// lk(c, z) = 0 for every cycle z in O, and the outward push-offs b+ of a homology basis b
// span H1(O). So c = sum x_i b_i is a handle class iff x . L+ = 0 with L+_ij = lk(b_i, b_j+),
// and a tunnel class iff x . L- = 0 (inward push-offs). Loops with a boundary are
// classified on the surface closed by caps over its boundary loops.
//
// Candidate loops are the shortest loops through a set of roots (Erickson–Whittlesey:
// a shortest-path tree plus one edge, trimmed at the common ancestor, hence simple), the
// roots chosen by farthest-point sampling and then refined on the loops found. Greedy
// selection by length keeps independent classes; the g handle loops are in addition
// pairwise vertex-disjoint and avoid the boundary, so that cutting along all of them leaves
// one connected genus-0 surface with 2g+b boundary loops (independent disjoint simple
// cycles never separate). When a coarse mesh leaves no room for disjoint loops, the mesh is
// refined at edge midpoints (geometry unchanged) and the search repeated.

#ifndef CGAL_POLYCUBE_IGA_SURFACE_TOPOLOGY_H
#define CGAL_POLYCUBE_IGA_SURFACE_TOPOLOGY_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/parameters.h>
#include <CGAL/Polycube_IGA/internal/homology.h>
#include <CGAL/Polycube_IGA/internal/linking_number.h>
#include <CGAL/Polycube_IGA/internal/loop_push_off.h>
#include <CGAL/Polycube_IGA/internal/mesh_graph.h>
#include <CGAL/Polycube_IGA/internal/mesh_refinement.h>
#include <CGAL/Polycube_IGA/internal/shortest_path_tree.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <boost/property_map/property_map.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// A closed loop along mesh edges: vertices in order (the last joins the first).
template <class TriangleMesh>
struct Surface_loop
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  std::vector<vertex_descriptor> vertices;
  std::vector<std::array<double, 3>> points; ///< positions of `vertices`
  double length = 0;                          ///< sum of the edge weights along the loop
  std::vector<int> homology_class;            ///< coordinates in the tree-cotree basis of H1
};

/// \ingroup PkgPolycubeIGARef
/// Result of `Surface_topology`.
template <class TriangleMesh>
struct Surface_topology_result
{
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  using Loop = Surface_loop<TriangleMesh>;

  std::size_t number_of_vertices = 0; ///< vertices with at least one incident edge
  std::size_t number_of_edges = 0;
  std::size_t number_of_faces = 0;
  int genus = 0;
  long euler_characteristic = 0;
  /// Each boundary loop as its border halfedges, in order (halfedges of the input mesh).
  std::vector<std::vector<halfedge_descriptor>> boundary_cycles;
  std::vector<Loop> homology_basis; ///< 2g cycles
  std::vector<Loop> handle_loops;   ///< g simple, pairwise disjoint, together non-separating
  std::vector<Loop> tunnel_loops;   ///< g simple, independent
  /// lk(handle_i, tunnel_j pushed inwards): unimodular (det +-1) when handles and tunnels are dual
  /// bases; lk(handle_i, tunnel_j pushed outwards) is always 0, as the handle bounds inside.
  std::vector<std::vector<int>> handle_tunnel_linking;
  /// Things the user should know, e.g. fewer tunnel loops than the genus: a knotted handle
  /// has no disk outside the solid, and its homological tunnel loop may be very long.
  std::vector<std::string> warnings;
  /// Midpoint subdivisions that were needed to find disjoint loops. When nonzero, the loops'
  /// vertices refer to `refined_mesh`, whose first vertices are the input's.
  int refinements = 0;
  std::shared_ptr<TriangleMesh> refined_mesh;

  std::size_t number_of_boundary_loops() const { return boundary_cycles.size(); }
  /// The mesh the loops' vertex descriptors refer to.
  const TriangleMesh& loop_mesh(const TriangleMesh& input) const { return refinements ? *refined_mesh : input; }
};

/*!
 * \ingroup PkgPolycubeIGARef
 * Function object computing the topology of a connected, orientable triangle mesh: genus,
 * boundary loops, homology basis, handle and tunnel loops. `TriangleMesh` is a model of
 * `FaceListGraph` and `MutableFaceGraph` (the latter only used when a refinement is needed).
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{vertex_point_map}
 *     \cgalParamDefault{`get(CGAL::vertex_point, tm)`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{loop_edge_weight}
 *     \cgalParamDescription{readable property map edge_descriptor -> double (>= 0): the
 *       metric in which loops are short}
 *     \cgalParamDefault{Euclidean edge length}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{number_of_roots}
 *     \cgalParamDescription{roots of shortest-path trees sampled (farthest-point) for candidate loops}
 *     \cgalParamDefault{`16`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{compute_tunnel_loops}
 *     \cgalParamDefault{`true`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{maximum_refinements}
 *     \cgalParamDescription{midpoint subdivisions allowed when disjoint handle loops do not fit}
 *     \cgalParamDefault{`3`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 *
 * Throws `Invalid_input_error` (`multiple_components`, `empty`, `invalid_edge_weight`) and
 * `Internal_error` (`loop_search_failed`, `handle_tunnel_classification_failed`).
 */
template <class TriangleMesh>
class Surface_topology
{
public:
  using Result = Surface_topology_result<TriangleMesh>;
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;

  template <class NamedParameters = parameters::Default_named_parameters>
  Result operator()(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values()) const
  {
    using CGAL::parameters::choose_parameter;
    using CGAL::parameters::get_parameter;
    auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
    const int number_of_roots = std::max(1, int(option(np, internal_np::number_of_roots, 16)));
    const bool tunnels = option(np, internal_np::compute_tunnel_loops, true);
    const int max_refinements = std::max(0, int(option(np, internal_np::maximum_refinements, 3)));
    auto weight_map = get_parameter(np, internal_np::loop_edge_weight);
    constexpr bool has_weights = !std::is_same<decltype(weight_map), CGAL::internal_np::Param_not_found>::value;

    Result result;
    if(num_faces(tm) == 0) throw Invalid_input_error("empty", "the mesh has no faces");
    internal::Mesh_graph<TriangleMesh> graph(tm, vpm);
    count_and_check(graph, tm, result);
    if(result.genus == 0) return result; // no non-trivial loop exists: nothing to search

    // Loops are searched on the input, or on its midpoint refinements when they do not fit.
    const TriangleMesh* mesh = &tm;
    std::unique_ptr<internal::Mesh_graph<TriangleMesh>> refined_graph;
    for(int attempt = 0;; ++attempt) {
      const auto& g = refined_graph ? *refined_graph : graph;
      // A user's weight map knows the input's edges only: refined meshes use lengths.
      std::vector<double> w = refined_graph
        ? edge_weights(g, *mesh, weight_map, std::false_type())
        : edge_weights(g, *mesh, weight_map, std::integral_constant<bool, has_weights>());
      if(search_loops(g, w, result, number_of_roots, tunnels)) break;
      if(attempt == max_refinements)
        throw Internal_error("loop_search_failed",
                             "no set of " + std::to_string(result.genus) +
                             " disjoint handle loops found, even after " + std::to_string(max_refinements) +
                             " refinements of the mesh");
      if(!result.refined_mesh) result.refined_mesh = std::make_shared<TriangleMesh>(tm);
      auto rvpm = get(CGAL::vertex_point, *result.refined_mesh);
      internal::subdivide_at_edge_midpoints(*result.refined_mesh, rvpm);
      result.refinements = attempt + 1;
      mesh = result.refined_mesh.get();
      refined_graph.reset(new internal::Mesh_graph<TriangleMesh>(*mesh, rvpm));
    }
    return result;
  }

private:
  using Graph = internal::Mesh_graph<TriangleMesh>;

  struct Candidate
  {
    double length;
    std::vector<int> vertices, edges;
    internal::Homology_class cls;
    bool touches_border;
    bool unreliable; // passes a vertex without a clean push-off direction: not for linking
  };

  static void count_and_check(const Graph& g, const TriangleMesh& tm, Result& r)
  {
    // Connectivity over the edge graph; isolated vertices are ignored.
    const int nv = g.number_of_vertices();
    std::vector<int> comp(nv, -1);
    int components = 0;
    std::size_t used_vertices = 0;
    for(int s = 0; s < nv; ++s) {
      if(comp[s] != -1 || g.offset[s] == g.offset[s + 1]) continue;
      ++components;
      std::vector<int> stack{s};
      comp[s] = s;
      while(!stack.empty()) {
        int v = stack.back(); stack.pop_back();
        ++used_vertices;
        for(int k = g.offset[v]; k < g.offset[v + 1]; ++k)
          if(comp[g.adjacent_vertex[k]] == -1) { comp[g.adjacent_vertex[k]] = s; stack.push_back(g.adjacent_vertex[k]); }
      }
    }
    if(components > 1)
      throw Invalid_input_error("multiple_components",
                                "the mesh has " + std::to_string(components) + " connected components; one solid is expected");
    r.number_of_vertices = used_vertices;
    r.number_of_edges = std::size_t(g.number_of_edges());
    r.number_of_faces = std::size_t(g.number_of_faces());
    r.euler_characteristic = long(used_vertices) - long(r.number_of_edges) + long(r.number_of_faces);
    const long b = long(g.border_cycles.size());
    const long twice_genus = 2 - r.euler_characteristic - b;
    if(twice_genus < 0 || twice_genus % 2 != 0)
      throw Invalid_input_error("non_manifold_vertex", "the Euler characteristic (" +
                                std::to_string(r.euler_characteristic) + ") and " + std::to_string(b) +
                                " boundary loops fit no orientable surface: the mesh is not a manifold");
    r.genus = int(twice_genus / 2);
    for(const auto& cycle : g.border_cycles) {
      r.boundary_cycles.emplace_back();
      for(int e : cycle) {
        halfedge_descriptor h = g.edge_halfedge[e];
        if(!is_border(h, tm)) h = opposite(h, tm);
        r.boundary_cycles.back().push_back(h);
      }
    }
  }

  template <class WeightMap>
  static std::vector<double> edge_weights(const Graph& g, const TriangleMesh& tm, const WeightMap& wm, std::true_type)
  {
    std::vector<double> w(g.number_of_edges());
    for(int e = 0; e < g.number_of_edges(); ++e) {
      w[e] = double(get(wm, edge(g.edge_halfedge[e], tm)));
      if(!(w[e] >= 0) || !std::isfinite(w[e]))
        throw Invalid_input_error("invalid_edge_weight", "loop_edge_weight must be finite and non-negative");
    }
    return w;
  }
  template <class WeightMap>
  static std::vector<double> edge_weights(const Graph& g, const TriangleMesh&, const WeightMap&, std::false_type)
  {
    std::vector<double> w(g.number_of_edges());
    for(int e = 0; e < g.number_of_edges(); ++e) w[e] = g.length(e);
    return w;
  }

  // Shortest loops through `root`, one per distinct non-trivial class (the shortest),
  // the `keep` shortest of them, plus the loops of `always` (edges) when given.
  static void loops_through_root(const Graph& g, const std::vector<double>& w,
                                 const std::vector<char>& unreliable_vertex,
                                 const internal::Homology_coordinates<Graph>& H,
                                 const internal::Shortest_path_tree& t, std::size_t keep,
                                 const std::vector<int>& always, std::vector<Candidate>& out)
  {
    const int d = H.dimension(), nv = g.number_of_vertices();
    std::vector<int> P(std::size_t(nv) * d, 0);
    for(int v : t.order) {
      const int pe = t.parent_edge[v];
      if(pe < 0) continue;
      const int u = g.other_vertex(pe, v);
      const int s = g.direction(pe, u);
      const int* hp = H.at(pe);
      for(int k = 0; k < d; ++k) P[std::size_t(v) * d + k] = P[std::size_t(u) * d + k] + s * hp[k];
    }
    std::map<internal::Homology_class, std::pair<double, int>> best; // class -> (length, edge)
    internal::Homology_class c(d);
    // Only the edges of the explored ball, each once (from its canonical source).
    for(int v : t.order)
    for(int k = g.offset[v]; k < g.offset[v + 1]; ++k) {
      const int e = g.adjacent_edge[k];
      const int a = g.edge_vertices[e][0], b = g.edge_vertices[e][1];
      if(a != v) continue;
      if(t.parent_edge[a] == e || t.parent_edge[b] == e) continue;
      if(!std::isfinite(t.distance[a]) || !std::isfinite(t.distance[b])) continue;
      const int* he = H.at(e);
      bool zero = true;
      for(int k = 0; k < d; ++k) {
        c[k] = P[std::size_t(a) * d + k] + he[k] - P[std::size_t(b) * d + k];
        zero = zero && c[k] == 0;
      }
      if(zero) continue;
      const double len = t.distance[a] + w[e] + t.distance[b];
      // A class and its opposite are the same loop reversed: key on the one whose first
      // non-zero entry is positive (in place: lookups allocate nothing).
      for(int k = 0; k < d; ++k) if(c[k] != 0) { if(c[k] < 0) for(int& x : c) x = -x; break; }
      auto it = best.find(c);
      if(it == best.end()) best.emplace(c, std::make_pair(len, e));
      else if(len < it->second.first) it->second = {len, e};
    }
    std::vector<std::pair<double, int>> chosen;
    for(const auto& kv : best) chosen.push_back(kv.second);
    std::sort(chosen.begin(), chosen.end());
    if(chosen.size() > keep) chosen.resize(keep);
    for(int e : always) chosen.push_back({0.0, e});
    for(const auto& [len, e] : chosen) {
      Candidate cand;
      cand.vertices = internal::tree_loop(g, t, e, &cand.edges);
      cand.length = 0;
      for(int x : cand.edges) cand.length += w[x];
      cand.cls = H.class_of_loop(cand.vertices, cand.edges);
      cand.touches_border = cand.unreliable = false;
      for(int v : cand.vertices) {
        cand.touches_border = cand.touches_border || g.is_border_vertex[v];
        cand.unreliable = cand.unreliable || unreliable_vertex[v];
      }
      out.push_back(std::move(cand));
    }
  }

  static bool search_loops(const Graph& g, const std::vector<double>& w, Result& result,
                           int number_of_roots, bool want_tunnels)
  {
    const int genus = result.genus, nv = g.number_of_vertices();
    // Root 0: the first non-border vertex with an edge (deterministic).
    int root0 = -1;
    for(int v = 0; v < nv && root0 < 0; ++v)
      if(g.offset[v] < g.offset[v + 1] && !g.is_border_vertex[v]) root0 = v;
    if(root0 < 0) root0 = 0;
    internal::Shortest_path_tree t0 = internal::shortest_path_tree(g, root0, w);
    std::vector<double> priority(g.number_of_edges());
    for(int e = 0; e < g.number_of_edges(); ++e)
      priority[e] = t0.distance[g.edge_vertices[e][0]] + w[e] + t0.distance[g.edge_vertices[e][1]];
    internal::Homology_coordinates<Graph> H(g, t0, priority);
    if(H.dimension() != 2 * genus)
      throw Internal_error("loop_search_failed", "tree-cotree found " + std::to_string(H.dimension()) +
                                                 " generators for genus " + std::to_string(genus));

    // Push-offs for the linking numbers; loops avoid vertices that have no direction.
    const internal::Loop_push_off<Graph> push(g);
    std::vector<char> unreliable(nv, 0);
    for(int v = 0; v < nv; ++v) unreliable[v] = !push.reliable(v);

    // Candidates from farthest-point-sampled roots.
    std::vector<Candidate> candidates;
    const std::size_t keep = std::size_t(8 * genus + 8);
    std::vector<double> nearest(t0.distance);
    loops_through_root(g, w, unreliable, H, t0, keep, H.generators(), candidates);
    for(int r = 1; r < number_of_roots; ++r) {
      int far = -1;
      double far_d = -1;
      for(int v = 0; v < nv; ++v)
        if(std::isfinite(nearest[v]) && nearest[v] > far_d) { far_d = nearest[v]; far = v; }
      if(far < 0 || far_d <= 0) break;
      internal::Shortest_path_tree t = internal::shortest_path_tree(g, far, w);
      for(int v = 0; v < nv; ++v) nearest[v] = std::min(nearest[v], t.distance[v]);
      loops_through_root(g, w, unreliable, H, t, keep, {}, candidates);
    }

    // Later rounds add roots on the loops the previous round chose, where the shortest
    // loops of those classes pass, while that shortens them (a few rounds at most). A
    // last one, only when tunnel loops are missing (a knotted handle's tunnel class is a
    // long, twisted loop), keeps every class seen.
    Selection sel;
    auto total_length = [](const Selection& x) {
      double t = 0;
      for(const Candidate* c : x.handles) t += c->length;
      for(const Candidate* c : x.tunnels) t += c->length;
      return t;
    };
    double previous = std::numeric_limits<double>::infinity();
    bool exhaustive = false;
    std::set<int> used_roots;
    for(int round = 0;; ++round) {
      std::stable_sort(candidates.begin(), candidates.end(),
                       [](const Candidate& a, const Candidate& b) { return a.length < b.length; });
      sel = select(g, candidates, genus, want_tunnels, push);
      if(!sel.ok) return false;
      const bool tunnels_missing = want_tunnels && int(sel.tunnels.size()) < genus;
      const double total = total_length(sel);
      const bool improving = total < previous * (1 - 1e-9) && round < 5;
      previous = total;
      if(exhaustive || (!improving && !tunnels_missing)) break;
      exhaustive = !improving && tunnels_missing;
      std::vector<int> roots;
      double longest = 0;
      auto add_roots = [&](const std::vector<const Candidate*>& loops) {
        for(const Candidate* c : loops) {
          longest = std::max(longest, c->length);
          for(int k = 0; k < 4; ++k) {
            const int r = c->vertices[c->vertices.size() * k / 4];
            if(used_roots.insert(r).second) roots.push_back(r);
          }
        }
      };
      add_roots(sel.handles);
      add_roots(sel.tunnels);
      // A loop through r no longer than the longest chosen one stays within half that
      // distance of r: the improvement rounds search balls, not the whole mesh.
      const std::size_t round_keep = exhaustive ? std::numeric_limits<std::size_t>::max() : keep;
      const double radius = exhaustive ? std::numeric_limits<double>::infinity() : 0.5 * longest * (1 + 1e-9);
      std::vector<Candidate> more;
      for(int r : roots)
        loops_through_root(g, w, unreliable, H, internal::shortest_path_tree(g, r, w, {}, radius), round_keep, {}, more);
      for(auto& c : more) candidates.push_back(std::move(c));
    }

    auto to_loop = [&](const Candidate& c) {
      Surface_loop<TriangleMesh> loop;
      for(int v : c.vertices) {
        loop.vertices.push_back(g.vertex[v]);
        const Eigen::Vector3d& p = g.position[v];
        loop.points.push_back({p.x(), p.y(), p.z()});
      }
      loop.length = c.length;
      loop.homology_class = c.cls;
      return loop;
    };
    result.homology_basis.clear(); result.handle_loops.clear(); result.tunnel_loops.clear();
    for(const Candidate* c : sel.basis) result.homology_basis.push_back(to_loop(*c));
    for(const Candidate* c : sel.handles) result.handle_loops.push_back(to_loop(*c));
    for(const Candidate* c : sel.tunnels) result.tunnel_loops.push_back(to_loop(*c));
    result.warnings.clear();
    if(want_tunnels && int(sel.tunnels.size()) < genus)
      result.warnings.push_back("only " + std::to_string(sel.tunnels.size()) + " of " + std::to_string(genus) +
                                " tunnel loops found among the candidate loops (a knotted handle has no "
                                "disk outside the solid)");
    result.handle_tunnel_linking.assign(sel.handles.size(), std::vector<int>(sel.tunnels.size(), 0));
    for(std::size_t i = 0; i < sel.handles.size(); ++i)
      for(std::size_t j = 0; j < sel.tunnels.size(); ++j)
        result.handle_tunnel_linking[i][j] = internal::projected_linking_number(
          push.on_surface(sel.handles[i]->vertices), push.pushed(sel.tunnels[j]->vertices, -1));
    return true;
  }

  struct Selection
  {
    bool ok = false;
    std::vector<const Candidate*> basis, handles, tunnels;
  };

  // `push` is a copy: its steps shrink here when the linking matrices need it.
  static Selection select(const Graph& g, const std::vector<Candidate>& candidates, int genus, bool want_tunnels,
                          internal::Loop_push_off<Graph> push)
  {
    Selection s;
    const int d = 2 * genus;
    internal::Independence_tracker basis_rank(d);
    for(const Candidate& c : candidates)
      if(!c.unreliable && basis_rank.insert(c.cls)) { s.basis.push_back(&c); if(basis_rank.rank() == d) break; }
    if(basis_rank.rank() != d) return s; // refine: loops avoiding unreliable vertices will exist

    // Linking matrices (shrinking the push-offs where they cross a thin part).
    Eigen::MatrixXd Lp, Lm;
    std::vector<const std::vector<int>*> basis_loops;
    for(const Candidate* c : s.basis) basis_loops.push_back(&c->vertices);
    if(!push.consistent_linking_matrices(basis_loops, genus, Lp, Lm))
      throw Internal_error("handle_tunnel_classification_failed",
                           "linking numbers of the homology basis are inconsistent (is the surface "
                           "self-intersecting or are normals inconsistent?)");
    Eigen::MatrixXd B(d, d);
    for(int i = 0; i < d; ++i) for(int k = 0; k < d; ++k) B(i, k) = s.basis[i]->cls[k];
    // Class y (tree-cotree coordinates) -> coefficients x = y B^-1; handle iff x Lp = 0.
    const Eigen::MatrixXd Binv = B.inverse();
    const Eigen::MatrixXd Kp = Binv * Lp, Km = Binv * Lm;
    auto in_kernel = [&](const Candidate& c, const Eigen::MatrixXd& K) {
      Eigen::RowVectorXd y(d);
      for(int k = 0; k < d; ++k) y(k) = c.cls[k];
      return (y * K).cwiseAbs().maxCoeff() < 1e-6;
    };

    std::vector<char> used(g.number_of_vertices(), 0);
    auto disjoint = [&](const Candidate& c) {
      for(int v : c.vertices) if(used[v]) return false;
      return true;
    };
    internal::Independence_tracker handle_rank(d);
    for(const Candidate& c : candidates) {
      if(int(s.handles.size()) == genus) break;
      if(c.touches_border || !disjoint(c) || !in_kernel(c, Kp) || !handle_rank.is_independent(c.cls)) continue;
      handle_rank.insert(c.cls);
      s.handles.push_back(&c);
      for(int v : c.vertices) used[v] = 1;
    }
    if(int(s.handles.size()) < genus) return s;

    if(want_tunnels) {
      // Prefer pairwise disjoint tunnel loops; fill up with overlapping ones if needed.
      std::fill(used.begin(), used.end(), 0);
      internal::Independence_tracker tunnel_rank(d);
      for(int pass = 0; pass < 2 && int(s.tunnels.size()) < genus; ++pass)
        for(const Candidate& c : candidates) {
          if(int(s.tunnels.size()) == genus) break;
          if((pass == 0 && !disjoint(c)) || !in_kernel(c, Km) || !tunnel_rank.is_independent(c.cls)) continue;
          tunnel_rank.insert(c.cls);
          s.tunnels.push_back(&c);
          for(int v : c.vertices) used[v] = 1;
        }
    }
    s.ok = true;
    return s;
  }
};

/// \ingroup PkgPolycubeIGARef
/// Convenience: `Surface_topology<TriangleMesh>()(tm, np)`.
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Surface_topology_result<TriangleMesh> surface_topology(const TriangleMesh& tm,
                                                       const NamedParameters& np = parameters::default_values())
{
  return Surface_topology<TriangleMesh>()(tm, np);
}

namespace internal {

/// The topology the cutting stages start from (genus, boundary loops, homology basis, handle
/// loops; no tunnel loops). On a genus-1 surface with boundary loops, the handle loop is
/// shortest in a metric that doubles the length of an edge on a boundary and fades to the
/// plain length at the points farthest from every boundary. All meridians of a torus are
/// about as short, and the plain search put the handle loop wherever it met the shortest:
/// beside the hole of a torus with one hole, whose single pants then had one arm a quarter of
/// the ring long and the other three quarters, and layout slivers of 2 degrees (nothing valid
/// at any grid, 381 s); opposite the hole it is valid at once, in 2 s. Not at higher genus:
/// there the metric left more patches uncertified (double-torus-3-holes.off 44 -> 57).
template <class TriangleMesh>
Surface_topology_result<TriangleMesh> cutting_topology(const TriangleMesh& tm)
{
  // The class from the Euler characteristic, so the loop search runs once; an invalid mesh
  // (several components, non-manifold) gets its error from that search either way.
  Mesh_graph<TriangleMesh> g(tm, get(CGAL::vertex_point, tm));
  const long b = long(g.border_cycles.size());
  const long chi = long(g.number_of_used_vertices()) - long(g.number_of_edges()) + long(g.number_of_faces());
  if(b == 0 || 2 - chi - b != 2) // not genus 1 with boundary loops
    return Surface_topology<TriangleMesh>()(tm, parameters::compute_tunnel_loops(false));
  std::vector<int> border;
  for(int v = 0; v < g.number_of_vertices(); ++v)
    if(g.is_border_vertex[std::size_t(v)]) border.push_back(v);
  std::vector<double> length(std::size_t(g.number_of_edges()));
  for(int e = 0; e < g.number_of_edges(); ++e) length[std::size_t(e)] = g.length(e);
  const std::vector<double> away = weights_away_from(g, border, length);
  using edge_descriptor = typename boost::graph_traits<TriangleMesh>::edge_descriptor;
  std::map<edge_descriptor, double> weight;
  for(int e = 0; e < g.number_of_edges(); ++e) weight[edge(g.edge_halfedge[std::size_t(e)], tm)] = away[std::size_t(e)];
  return Surface_topology<TriangleMesh>()(
    tm, parameters::compute_tunnel_loops(false).loop_edge_weight(boost::make_assoc_property_map(weight)));
}

/// The `surface_topology` named parameter of a later stage when it was given, else
/// cutting_topology().
template <class TriangleMesh, class Given>
Surface_topology_result<TriangleMesh> given_or_computed_topology(const TriangleMesh& tm, const Given& given)
{
  if constexpr(std::is_same<Given, CGAL::internal_np::Param_not_found>::value)
    return cutting_topology(tm);
  else
    return given;
}

} // namespace internal

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_SURFACE_TOPOLOGY_H
