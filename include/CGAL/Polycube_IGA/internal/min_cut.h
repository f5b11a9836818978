// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Minimum s-t cut by the Boykov–Kolmogorov maximum-flow algorithm (Y. Boykov, V. Kolmogorov,
// "An experimental comparison of min-cut/max-flow algorithms for energy minimization in
// vision", PAMI 2004): two search trees grown from s and t, augmentation where they meet,
// adoption of the orphans that saturated arcs leave, tree reuse between augmentations. On
// the dual graph of a genus-0 region, a minimum cut between two face sets is a shortest
// closed curve separating them: the pants decomposition traces its cycles this way
// (reference §2.2.1.2, Algorithm 2, which finds the same curve by sweeping paths across a
// cylinder).
//
// This is a compact implementation on arrays (arcs in CSR order, FIFO active and orphan
// queues, distance/timestamp marks for the origin checks). Capacities are quantised to 64-bit
// integers (total finite capacity 2^50 units) so that saturation is exact: floating-point
// residues would leave nearly saturated arcs that attract long series of tiny augmentations,
// and the result would depend on rounding. Boost.Graph's boykov_kolmogorov_max_flow, used
// before, spent about 1 s per cut on 30-60k-face regions where this one needs a few tens of
// milliseconds; the cuts have the same weight.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_MIN_CUT_H
#define CGAL_POLYCUBE_IGA_INTERNAL_MIN_CUT_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

class Min_cut
{
public:
  /// Capacities at least half of this are infinite.
  static constexpr double infinity() { return 1e30; }

  explicit Min_cut(int nodes) : nodes_(nodes) {}

  /// An edge a-b with capacity c in both directions (an undirected dual edge).
  void add_undirected(int a, int b, double c) { edges_.push_back({a, b, c, c}); }
  /// An edge a->b with capacity c.
  void add_directed(int a, int b, double c) { edges_.push_back({a, b, c, 0}); }

  /// Maximum flow value from s to t (the weight of a minimum cut), `infinity()` when every
  /// cut has an infinite capacity. Call once.
  double max_flow(int s, int t)
  {
    build();
    source_ = s;
    const double value = solve(s, t);
    return value;
  }

  /// After max_flow: 1 for the nodes on the source side of a minimum cut (those the source
  /// tree reaches through unsaturated arcs; the source side is then minimal).
  std::vector<char> source_side(int) const
  {
    std::vector<char> side(nodes_, 0);
    for(int v = 0; v < nodes_; ++v) side[v] = tree_[v] == SOURCE;
    return side;
  }

private:
  using Cap = std::int64_t;
  struct Edge { int a, b; double ab, ba; };
  enum { FREE = 0, SOURCE = 1, SINK = 2 };
  static constexpr int TERMINAL = -1, ORPHAN = -2, NONE = -3;
  static constexpr Cap INF = Cap(1) << 60;
  static constexpr double UNITS = double(Cap(1) << 50);

  int nodes_;
  int source_ = -1;
  std::vector<Edge> edges_;
  double unit_ = 1;
  Cap finite_total_ = 0;
  // Arcs: those of node v are first_[v] .. first_[v+1]; arc i's sister is sister_[i].
  std::vector<int> first_, head_, sister_;
  std::vector<Cap> cap_;
  // Trees.
  std::vector<char> tree_;
  std::vector<int> parent_;  // arc from the node to its parent, TERMINAL or ORPHAN
  std::vector<int> dist_;
  std::vector<long> time_;

  Cap quantise(double c) const
  {
    if(c >= 0.5 * infinity()) return INF;
    if(!(c > 0)) return 0;
    return std::max<Cap>(1, Cap(std::llround(c / unit_)));
  }

  void build()
  {
    double total = 0;
    for(const Edge& e : edges_)
      for(double c : {e.ab, e.ba})
        if(c > 0 && c < 0.5 * infinity()) total += c;
    unit_ = total > 0 ? total / UNITS : 1;
    first_.assign(nodes_ + 1, 0);
    for(const Edge& e : edges_) { ++first_[e.a + 1]; ++first_[e.b + 1]; }
    for(int v = 0; v < nodes_; ++v) first_[v + 1] += first_[v];
    const int arcs = first_[nodes_];
    head_.resize(arcs);
    sister_.resize(arcs);
    cap_.resize(arcs);
    std::vector<int> fill(first_.begin(), first_.end() - 1);
    finite_total_ = 0;
    for(const Edge& e : edges_) {
      const int i = fill[e.a]++, j = fill[e.b]++;
      head_[i] = e.b; head_[j] = e.a;
      sister_[i] = j; sister_[j] = i;
      cap_[i] = quantise(e.ab); cap_[j] = quantise(e.ba);
      for(Cap c : {cap_[i], cap_[j]}) if(c < INF) finite_total_ += c;
    }
    edges_.clear();
    edges_.shrink_to_fit();
  }

  // Residual capacity of the arc by which flow enters v from its tree neighbour along arc
  // `a` (a leaves v): in the source tree flow runs parent -> v (the sister arc), in the sink
  // tree v -> parent (the arc itself).
  Cap tree_cap(char tree, int a) const { return tree == SOURCE ? cap_[sister_[a]] : cap_[a]; }

  double solve(int s, int t)
  {
    tree_.assign(nodes_, FREE);
    parent_.assign(nodes_, NONE);
    dist_.assign(nodes_, 0);
    time_.assign(nodes_, 0);
    std::vector<int> active, orphans;
    std::vector<char> is_active(nodes_, 0);
    std::size_t active_begin = 0;
    auto activate = [&](int v) {
      if(!is_active[v]) { is_active[v] = 1; active.push_back(v); }
    };
    tree_[s] = SOURCE; parent_[s] = TERMINAL;
    tree_[t] = SINK; parent_[t] = TERMINAL;
    activate(s);
    activate(t);
    long now = 0;
    Cap flow = 0;
    for(;;) {
      // Growth: find an arc from the source tree to the sink tree.
      int meet = -1;
      while(active_begin < active.size()) {
        const int v = active[active_begin];
        if(tree_[v] == FREE) { is_active[v] = 0; ++active_begin; continue; }
        const char tv = tree_[v];
        for(int a = first_[v]; a < first_[v + 1]; ++a) {
          const Cap residual = tv == SOURCE ? cap_[a] : cap_[sister_[a]];
          if(residual == 0) continue;
          const int u = head_[a];
          if(tree_[u] == FREE) {
            tree_[u] = tv;
            parent_[u] = sister_[a];
            dist_[u] = dist_[v] + 1;
            time_[u] = time_[v];
            activate(u);
          } else if(tree_[u] != tv) {
            meet = tv == SOURCE ? a : sister_[a];
            break;
          } else if(time_[u] <= time_[v] && dist_[u] > dist_[v] && parent_[u] >= 0) {
            // A shorter way to the root (the heuristic of the paper).
            parent_[u] = sister_[a];
            dist_[u] = dist_[v] + 1;
            time_[u] = time_[v];
          }
        }
        if(meet >= 0) break;
        is_active[v] = 0;
        ++active_begin;
      }
      if(meet < 0) break;
      if(active_begin > 4096 && active_begin * 2 > active.size()) {
        active.erase(active.begin(), active.begin() + long(active_begin));
        active_begin = 0;
      }

      // Augmentation along source ... tail(meet) -> head(meet) ... sink.
      ++now;
      const int tail = head_[sister_[meet]], tip = head_[meet];
      Cap b = cap_[meet];
      for(int v = tail; parent_[v] != TERMINAL; v = head_[parent_[v]]) b = std::min(b, cap_[sister_[parent_[v]]]);
      for(int v = tip; parent_[v] != TERMINAL; v = head_[parent_[v]]) b = std::min(b, cap_[parent_[v]]);
      if(b >= INF) return infinity();
      cap_[meet] -= b;
      cap_[sister_[meet]] += b;
      for(int v = tail; parent_[v] != TERMINAL;) {
        const int a = parent_[v], up = head_[a];
        cap_[sister_[a]] -= b;
        cap_[a] += b;
        if(cap_[sister_[a]] == 0) { parent_[v] = ORPHAN; orphans.push_back(v); }
        v = up;
      }
      for(int v = tip; parent_[v] != TERMINAL;) {
        const int a = parent_[v], up = head_[a];
        cap_[a] -= b;
        cap_[sister_[a]] += b;
        if(cap_[a] == 0) { parent_[v] = ORPHAN; orphans.push_back(v); }
        v = up;
      }
      flow += b;
      if(flow > finite_total_) return infinity(); // more than any finite cut carries

      // Adoption.
      for(std::size_t o = 0; o < orphans.size(); ++o) {
        const int v = orphans[o];
        const char tv = tree_[v];
        int best_arc = -1, best_dist = -1;
        for(int a = first_[v]; a < first_[v + 1]; ++a) {
          if(tree_cap(tv, a) == 0) continue;
          int u = head_[a];
          if(tree_[u] != tv) continue;
          // Does u still hang from a terminal? Walk up, using the marks of this round.
          int d = 0;
          bool rooted = false;
          for(int x = u;;) {
            if(time_[x] == now) { d += dist_[x]; rooted = true; break; }
            const int p = parent_[x];
            ++d;
            if(p == TERMINAL) { time_[x] = now; dist_[x] = 1; rooted = true; break; }
            if(p < 0) break; // an orphan
            x = head_[p];
          }
          if(!rooted) continue;
          if(best_arc < 0 || d < best_dist) { best_arc = a; best_dist = d; }
          for(int x = u; time_[x] != now; x = head_[parent_[x]]) { time_[x] = now; dist_[x] = d--; }
        }
        if(best_arc >= 0) {
          parent_[v] = best_arc;
          time_[v] = now;
          dist_[v] = best_dist + 1;
          continue;
        }
        // No parent: v becomes free, its children orphans, its tree neighbours active.
        for(int a = first_[v]; a < first_[v + 1]; ++a) {
          const int u = head_[a];
          if(tree_[u] != tv) continue;
          if(tree_cap(tv, a) > 0) activate(u);
          const int p = parent_[u];
          if(p >= 0 && head_[p] == v) { parent_[u] = ORPHAN; orphans.push_back(u); }
        }
        tree_[v] = FREE;
        parent_[v] = NONE;
      }
      orphans.clear();
    }
    (void)s;
    return double(flow) * unit_;
  }
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
