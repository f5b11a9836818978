// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Minimum s-t cut by Dinic's maximum flow (BFS level graph + blocking flow). On the dual
// graph of a genus-0 region, a minimum cut between two face sets is a shortest closed curve
// separating them: the pants decomposition traces its cycles this way (reference §2.2.1.2,
// Algorithm 2, which finds the same curve by sweeping paths across a cylinder).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_MIN_CUT_H
#define CGAL_POLYCUBE_IGA_INTERNAL_MIN_CUT_H

#include <algorithm>
#include <limits>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

class Min_cut
{
public:
  static constexpr double infinity() { return 1e30; }

  explicit Min_cut(int nodes) : head_(nodes, -1), level_(nodes), cursor_(nodes) {}

  /// An edge a-b with capacity c in both directions (an undirected dual edge).
  void add_undirected(int a, int b, double c) { add(a, b, c, c); }
  /// An edge a->b with capacity c.
  void add_directed(int a, int b, double c) { add(a, b, c, 0); }

  /// Maximum flow value from s to t.
  double max_flow(int s, int t)
  {
    double flow = 0;
    while(bfs(s, t)) {
      std::copy(head_.begin(), head_.end(), cursor_.begin());
      for(double f; (f = dfs(s, t, infinity())) > 0;) flow += f;
    }
    return flow;
  }

  /// After max_flow: nodes reachable from s in the residual graph (the source side).
  std::vector<char> source_side(int s) const
  {
    std::vector<char> seen(head_.size(), 0);
    std::vector<int> stack{s};
    seen[s] = 1;
    while(!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for(int a = head_[v]; a != -1; a = arcs_[a].next)
        if(arcs_[a].capacity > eps_ && !seen[arcs_[a].to]) { seen[arcs_[a].to] = 1; stack.push_back(arcs_[a].to); }
    }
    return seen;
  }

private:
  struct Arc { int to, next; double capacity; };

  void add(int a, int b, double ab, double ba)
  {
    arcs_.push_back({b, head_[a], ab});
    head_[a] = int(arcs_.size()) - 1;
    arcs_.push_back({a, head_[b], ba});
    head_[b] = int(arcs_.size()) - 1;
  }

  bool bfs(int s, int t)
  {
    std::fill(level_.begin(), level_.end(), -1);
    std::vector<int> queue{s};
    level_[s] = 0;
    for(std::size_t i = 0; i < queue.size(); ++i) {
      const int v = queue[i];
      for(int a = head_[v]; a != -1; a = arcs_[a].next)
        if(arcs_[a].capacity > eps_ && level_[arcs_[a].to] < 0) {
          level_[arcs_[a].to] = level_[v] + 1;
          queue.push_back(arcs_[a].to);
        }
    }
    return level_[t] >= 0;
  }

  // Iterative blocking-flow search along the level graph (no recursion: regions can be large).
  double dfs(int s, int t, double limit)
  {
    std::vector<int> path_arcs;
    int v = s;
    while(true) {
      if(v == t) {
        double f = limit;
        for(int a : path_arcs) f = std::min(f, arcs_[a].capacity);
        for(int a : path_arcs) { arcs_[a].capacity -= f; arcs_[a ^ 1].capacity += f; }
        return f;
      }
      int& a = cursor_[v];
      while(a != -1 && !(arcs_[a].capacity > eps_ && level_[arcs_[a].to] == level_[v] + 1)) a = arcs_[a].next;
      if(a == -1) {
        if(path_arcs.empty()) return 0;
        level_[v] = -1; // dead end
        const int back = path_arcs.back();
        path_arcs.pop_back();
        v = arcs_[back ^ 1].to;
        cursor_[v] = arcs_[cursor_[v]].next;
        continue;
      }
      path_arcs.push_back(a);
      v = arcs_[a].to;
    }
  }

  std::vector<Arc> arcs_;
  std::vector<int> head_, level_, cursor_;
  double eps_ = 1e-12;
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
