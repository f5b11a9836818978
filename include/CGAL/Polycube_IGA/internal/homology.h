// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Homology of a (capped) surface mesh, reference §2.1.1.2 "Cut graphs, homotopy and
// homology basis": a tree T of primal edges and a cotree C of dual edges avoiding T leave
// 2g edges; their fundamental loops generate H1. Peeling the cotree from its leaves gives
// every edge e a coordinate vector h(e) in Z^2g such that any cycle's homology class is
// the signed sum of h over its edges. Border cycles are capped (one dual node each), so
// the classes are those of the closed surface, where boundary loops are trivial.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_HOMOLOGY_H
#define CGAL_POLYCUBE_IGA_INTERNAL_HOMOLOGY_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/internal/shortest_path_tree.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

using Homology_class = std::vector<int>;

template <class Graph>
class Homology_coordinates
{
public:
  /// `tree`: a spanning tree of the primal graph; `cotree_priority[e]`: dual edges of
  /// higher priority enter the cotree first (the greedy system of loops of Erickson and
  /// Whittlesey uses the length of the loop through e).
  Homology_coordinates(const Graph& g, const Shortest_path_tree& tree, const std::vector<double>& cotree_priority)
    : g_(g)
  {
    const int ne = g.number_of_edges(), nd = g.number_of_dual_nodes();
    std::vector<char> in_tree(ne, 0), in_cotree(ne, 0);
    for(int v = 0; v < g.number_of_vertices(); ++v)
      if(tree.parent_edge[v] >= 0) in_tree[tree.parent_edge[v]] = 1;
    std::vector<int> candidates;
    for(int e = 0; e < ne; ++e) if(!in_tree[e]) candidates.push_back(e);
    std::stable_sort(candidates.begin(), candidates.end(),
                     [&](int a, int b) { return cotree_priority[a] > cotree_priority[b]; });
    std::vector<int> parent(nd);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) { while(parent[x] != x) { parent[x] = parent[parent[x]]; x = parent[x]; } return x; };
    for(int e : candidates) {
      const int a = find(g.edge_faces[e][0]), b = find(g.edge_faces[e][1]);
      if(a != b) { parent[std::max(a, b)] = std::min(a, b); in_cotree[e] = 1; }
      else generators_.push_back(e);
    }
    dimension_ = int(generators_.size());
    h_.assign(std::size_t(ne) * dimension_, 0);
    for(int k = 0; k < dimension_; ++k) at(generators_[k])[k] = 1;

    // Cotree BFS from dual node 0, then peel from the leaves.
    std::vector<std::vector<int>> dual_adjacency(nd);
    for(int e = 0; e < ne; ++e)
      if(in_cotree[e]) {
        dual_adjacency[g.edge_faces[e][0]].push_back(e);
        dual_adjacency[g.edge_faces[e][1]].push_back(e);
      }
    std::vector<int> parent_edge(nd, -1), order{0};
    std::vector<char> visited(nd, 0);
    visited[0] = 1;
    for(std::size_t i = 0; i < order.size(); ++i)
      for(int e : dual_adjacency[order[i]]) {
        const int m = g.edge_faces[e][0] == order[i] ? g.edge_faces[e][1] : g.edge_faces[e][0];
        if(!visited[m]) { visited[m] = 1; parent_edge[m] = e; order.push_back(m); }
      }
    if(int(order.size()) != nd)
      throw Internal_error("disconnected_surface", "the dual graph is disconnected: the surface is not connected");
    std::vector<long long> sum(dimension_);
    for(auto it = order.rbegin(); it != order.rend(); ++it) {
      const int n = *it, pe = parent_edge[n];
      if(pe < 0) continue;
      std::fill(sum.begin(), sum.end(), 0);
      int pe_sign = 0;
      g.for_each_dual_boundary_edge(n, [&](int e, int sign) {
        if(e == pe) { pe_sign = sign; return; }
        const int* he = at(e);
        for(int k = 0; k < dimension_; ++k) sum[k] += sign * he[k];
      });
      int* hp = at(pe);
      for(int k = 0; k < dimension_; ++k) hp[k] = int(-pe_sign * sum[k]);
    }
  }

  int dimension() const { return dimension_; }
  const std::vector<int>& generators() const { return generators_; }

  /// Class of the closed vertex path `loop` (edge k joins loop[k] and loop[k+1 mod n]).
  Homology_class class_of_loop(const std::vector<int>& loop_vertices, const std::vector<int>& loop_edges) const
  {
    Homology_class c(dimension_, 0);
    for(std::size_t k = 0; k < loop_edges.size(); ++k) add_edge(c, loop_edges[k], loop_vertices[k]);
    return c;
  }

  /// Adds the class of edge e walked from vertex `from`.
  void add_edge(Homology_class& c, int e, int from) const
  {
    const int s = g_.direction(e, from);
    const int* he = at(e);
    for(int k = 0; k < dimension_; ++k) c[k] += s * he[k];
  }
  const int* at(int e) const { return h_.data() + std::size_t(e) * dimension_; }

private:
  int* at(int e) { return h_.data() + std::size_t(e) * dimension_; }

  const Graph& g_;
  int dimension_ = 0;
  std::vector<int> generators_;
  std::vector<int> h_;
};

/// Incremental rank of integer vectors, exact modulo a large prime (classes have small
/// entries, so rank mod p equals rank over Q in practice; a false dependence only makes
/// the greedy skip a candidate).
class Independence_tracker
{
public:
  explicit Independence_tracker(int dimension) : dim_(dimension) {}
  int rank() const { return int(rows_.size()); }

  bool is_independent(const std::vector<int>& v) const { return !reduce(v).empty(); }

  /// Adds v if independent; returns whether it was.
  bool insert(const std::vector<int>& v)
  {
    std::vector<std::int64_t> r = reduce(v);
    if(r.empty()) return false;
    rows_.push_back(r);
    return true;
  }

private:
  static constexpr std::int64_t P = 2147483647; // 2^31 - 1
  static std::int64_t inverse(std::int64_t a)
  {
    std::int64_t r = 1, e = P - 2;
    a %= P;
    while(e) { if(e & 1) r = r * a % P; a = a * a % P; e >>= 1; }
    return r;
  }
  // Rows are kept normalised with a leading 1 at a distinct pivot.
  std::vector<std::int64_t> reduce(const std::vector<int>& v) const
  {
    std::vector<std::int64_t> x(dim_);
    for(int k = 0; k < dim_; ++k) x[k] = ((v[k] % P) + P) % P;
    for(const auto& row : rows_) {
      int pivot = 0;
      while(row[pivot] == 0) ++pivot;
      if(x[pivot] == 0) continue;
      const std::int64_t f = x[pivot];
      for(int k = 0; k < dim_; ++k) x[k] = ((x[k] - f * row[k]) % P + P) % P;
    }
    int pivot = 0;
    while(pivot < dim_ && x[pivot] == 0) ++pivot;
    if(pivot == dim_) return {};
    const std::int64_t inv = inverse(x[pivot]);
    for(int k = 0; k < dim_; ++k) x[k] = x[k] * inv % P;
    return x;
  }

  int dim_;
  std::vector<std::vector<std::int64_t>> rows_;
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
