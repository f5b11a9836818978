// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Minimum s-t cut through Boost.Graph's Boykov–Kolmogorov maximum flow, which is fast on
// the mesh-like graphs it was designed for (a first Dinic version spent seconds in its
// phases on 60k-face regions). On the dual graph of a genus-0 region, a minimum cut between
// two face sets is a shortest closed curve separating them: the pants decomposition traces
// its cycles this way (reference §2.2.1.2, Algorithm 2, which finds the same curve by
// sweeping paths across a cylinder).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_MIN_CUT_H
#define CGAL_POLYCUBE_IGA_INTERNAL_MIN_CUT_H

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>

#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

class Min_cut
{
public:
  static constexpr double infinity() { return 1e30; }

  explicit Min_cut(int nodes) : graph_(nodes) {}

  /// An edge a-b with capacity c in both directions (an undirected dual edge).
  void add_undirected(int a, int b, double c) { add(a, b, c, c); }
  /// An edge a->b with capacity c.
  void add_directed(int a, int b, double c) { add(a, b, c, 0); }

  /// Maximum flow value from s to t.
  double max_flow(int s, int t) { return boost::boykov_kolmogorov_max_flow(graph_, s, t); }

  /// After max_flow: 1 for the nodes on the source side of a minimum cut.
  std::vector<char> source_side(int) const
  {
    std::vector<char> side(num_vertices(graph_), 0);
    auto color = get(boost::vertex_color, graph_);
    for(std::size_t v = 0; v < side.size(); ++v) side[v] = get(color, v) == boost::black_color;
    return side;
  }

private:
  using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
  using Graph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS,
    boost::property<boost::vertex_index_t, long,
      boost::property<boost::vertex_color_t, boost::default_color_type,
        boost::property<boost::vertex_distance_t, long,
          boost::property<boost::vertex_predecessor_t, Traits::edge_descriptor>>>>,
    boost::property<boost::edge_capacity_t, double,
      boost::property<boost::edge_residual_capacity_t, double,
        boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;

  void add(int a, int b, double ab, double ba)
  {
    auto e1 = add_edge(a, b, graph_).first, e2 = add_edge(b, a, graph_).first;
    put(boost::edge_capacity, graph_, e1, ab);
    put(boost::edge_capacity, graph_, e2, ba);
    put(boost::edge_reverse, graph_, e1, e2);
    put(boost::edge_reverse, graph_, e2, e1);
  }

  Graph graph_;
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
