// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Dijkstra shortest-path trees on a Mesh_graph with per-edge weights. Ties are broken by
// vertex index, so trees (and every loop traced from them) are deterministic.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_SHORTEST_PATH_TREE_H
#define CGAL_POLYCUBE_IGA_INTERNAL_SHORTEST_PATH_TREE_H

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

struct Shortest_path_tree
{
  int root = -1;
  std::vector<double> distance;   ///< +inf where unreachable
  std::vector<int> parent_edge;   ///< -1 at the root and where unreachable
  std::vector<int> order;         ///< vertices in the order they were settled
  std::vector<int> depth;         ///< number of edges to the root

  bool is_tree_edge(int e, const std::vector<std::array<int, 2>>& ev) const
  {
    return parent_edge[ev[e][0]] == e || parent_edge[ev[e][1]] == e;
  }
};

/// Shortest-path tree (forest) from `roots` (all at distance 0); `weight[e]` >= 0; vertices with `blocked[v]` are never
/// entered (except the root). Pass an empty `blocked` to allow all. The search stops at
/// `max_distance`: farther vertices keep an infinite distance (a local search costs only
/// the size of the ball it explores).
template <class Graph>
Shortest_path_tree shortest_path_tree(const Graph& g, const std::vector<int>& roots, const std::vector<double>& weight,
                                      const std::vector<bool>& blocked = {},
                                      double max_distance = std::numeric_limits<double>::infinity())
{
  const int root = roots.front();
  const int n = g.number_of_vertices();
  Shortest_path_tree t;
  t.root = root;
  t.distance.assign(n, std::numeric_limits<double>::infinity());
  t.parent_edge.assign(n, -1);
  t.depth.assign(n, 0);
  t.order.reserve(n);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  std::vector<bool> settled(n, false);
  for(int r : roots) { t.distance[r] = 0; queue.push({0.0, r}); }
  while(!queue.empty()) {
    auto [d, v] = queue.top();
    queue.pop();
    if(settled[v]) continue;
    if(d > max_distance) break;
    settled[v] = true;
    t.order.push_back(v);
    for(int k = g.offset[v]; k < g.offset[v + 1]; ++k) {
      const int w = g.adjacent_vertex[k], e = g.adjacent_edge[k];
      if(settled[w] || (!blocked.empty() && blocked[w])) continue;
      const double nd = d + weight[e];
      if(nd < t.distance[w] || (nd == t.distance[w] && t.parent_edge[w] != -1 &&
                                 g.other_vertex(t.parent_edge[w], w) > v)) {
        t.distance[w] = nd;
        t.parent_edge[w] = e;
        t.depth[w] = t.depth[v] + 1;
        queue.push({nd, w});
      }
    }
  }
  if(std::isfinite(max_distance))
    for(int v = 0; v < n; ++v)
      if(!settled[v]) { t.distance[v] = std::numeric_limits<double>::infinity(); t.parent_edge[v] = -1; }
  return t;
}

/// Single-root version.
template <class Graph>
Shortest_path_tree shortest_path_tree(const Graph& g, int root, const std::vector<double>& weight,
                                      const std::vector<bool>& blocked = {},
                                      double max_distance = std::numeric_limits<double>::infinity())
{
  return shortest_path_tree(g, std::vector<int>{root}, weight, blocked, max_distance);
}

/// `weight` scaled up near `roots`: each edge's weight times 1 + max(0, 1 - d/d_max), d the
/// distance (in `weight`) of its midpoint from the roots and d_max the largest finite one.
/// An edge at a root counts double, one farthest from them plain: among cycles of about
/// the same length (the meridians of a torus), the shortest in this metric keeps away from
/// the roots. Edges with an end never reached keep their weight.
template <class Graph>
std::vector<double> weights_away_from(const Graph& g, const std::vector<int>& roots, const std::vector<double>& weight)
{
  if(roots.empty()) return weight;
  const std::vector<double> d = shortest_path_tree(g, roots, weight).distance;
  double farthest = 0.;
  for(double x : d)
    if(std::isfinite(x)) farthest = std::max(farthest, x);
  std::vector<double> out(weight);
  for(std::size_t e = 0; e < out.size(); ++e) {
    const auto& ev = g.edge_vertices[e];
    const double mid = 0.5 * (d[std::size_t(ev[0])] + d[std::size_t(ev[1])]);
    if(farthest > 0. && std::isfinite(mid)) out[e] *= 1. + std::max(0., 1. - mid / farthest);
  }
  return out;
}

/// Vertex path from the root's subtree: the loop closed by the non-tree edge `e`, trimmed
/// at the lowest common ancestor, so it is a simple cycle. Returned as vertices in order
/// starting at the ancestor; the edge between the last and first vertex is implied.
template <class Graph>
std::vector<int> tree_loop(const Graph& g, const Shortest_path_tree& t, int e, std::vector<int>* loop_edges = nullptr)
{
  int a = g.edge_vertices[e][0], b = g.edge_vertices[e][1];
  std::vector<int> left{a}, right{b}, left_e, right_e;
  while(a != b) {
    if(t.depth[a] >= t.depth[b]) {
      const int pe = t.parent_edge[a];
      left_e.push_back(pe);
      a = g.other_vertex(pe, a);
      left.push_back(a);
    } else {
      const int pe = t.parent_edge[b];
      right_e.push_back(pe);
      b = g.other_vertex(pe, b);
      right.push_back(b);
    }
  }
  // left: u ... lca, right: v ... lca. Loop: lca ... u -> v ... (before lca).
  std::vector<int> loop(left.rbegin(), left.rend());
  for(std::size_t i = 0; i + 1 < right.size(); ++i) loop.push_back(right[i]);
  if(loop_edges) {
    loop_edges->assign(left_e.rbegin(), left_e.rend());
    loop_edges->push_back(e);
    loop_edges->insert(loop_edges->end(), right_e.begin(), right_e.end());
  }
  return loop;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
