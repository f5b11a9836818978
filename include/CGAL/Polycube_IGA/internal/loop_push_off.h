// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Push-offs of loops on a surface, off the surface to the outside (or the inside) of the
// solid, for linking numbers (Alexander duality): a cycle c on the surface bounds in the
// solid iff lk(c, z+) = 0 for the outward push-off z+ of every loop z of a homology basis.
// Each vertex moves along its push direction (Mesh_graph::vertex_push_directions) by a
// twentieth of its shortest edge; the outside is told by the sign of the capped volume.
// Surface_topology classifies handle and tunnel loops with these push-offs and
// Pants_decomposition::validate() checks with them that cut cycles bound inside.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LOOP_PUSH_OFF_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LOOP_PUSH_OFF_H

#include <CGAL/Polycube_IGA/internal/linking_number.h>

#include <Eigen/Dense>

#include <algorithm>
#include <limits>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

template <class Graph>
struct Loop_push_off
{
  const Graph* g;
  std::vector<Eigen::Vector3d> direction; ///< per vertex, unit
  std::vector<double> clearance;          ///< per vertex; <= 0.01: no clean direction
  std::vector<double> step;               ///< per vertex: how far a push-off moves it
  double outward;                         ///< +1 when the faces are oriented outwards, else -1

  explicit Loop_push_off(const Graph& graph)
    : g(&graph), outward(graph.capped_signed_volume() >= 0 ? 1.0 : -1.0)
  {
    direction = graph.vertex_push_directions(clearance);
    step.assign(std::size_t(graph.number_of_vertices()), std::numeric_limits<double>::infinity());
    for(int e = 0; e < graph.number_of_edges(); ++e) {
      const double l = graph.length(e);
      for(int v : graph.edge_vertices[e]) step[std::size_t(v)] = std::min(step[std::size_t(v)], 0.05 * l);
    }
  }

  /// False at a vertex whose star admits no push direction: loops through it are not for linking.
  bool reliable(int v) const { return clearance[std::size_t(v)] > 0.01; }

  std::vector<Eigen::Vector3d> on_surface(const std::vector<int>& loop) const
  {
    std::vector<Eigen::Vector3d> p;
    p.reserve(loop.size());
    for(int v : loop) p.push_back(g->position[std::size_t(v)]);
    return p;
  }

  /// side +1: the outward push-off; -1: the inward one.
  std::vector<Eigen::Vector3d> pushed(const std::vector<int>& loop, double side) const
  {
    std::vector<Eigen::Vector3d> p;
    p.reserve(loop.size());
    for(int v : loop)
      p.push_back(g->position[std::size_t(v)] + side * outward * step[std::size_t(v)] * direction[std::size_t(v)]);
    return p;
  }

  /// Lp(i, j) = lk(b_i, b_j pushed out), Lm(i, j) = lk(b_i, b_j pushed in).
  void linking_matrices(const std::vector<const std::vector<int>*>& basis, Eigen::MatrixXd& Lp, Eigen::MatrixXd& Lm) const
  {
    const int n = int(basis.size());
    Lp.resize(n, n);
    Lm.resize(n, n);
    std::vector<std::vector<Eigen::Vector3d>> on(n), plus(n), minus(n);
    for(int i = 0; i < n; ++i) {
      on[i] = on_surface(*basis[i]);
      plus[i] = pushed(*basis[i], +1);
      minus[i] = pushed(*basis[i], -1);
    }
    for(int i = 0; i < n; ++i)
      for(int j = 0; j < n; ++j) {
        Lp(i, j) = projected_linking_number(on[i], plus[j]);
        Lm(i, j) = projected_linking_number(on[i], minus[j]);
      }
  }

  /// Linking matrices of a homology basis of a genus-g surface, consistent with duality:
  /// rank Lp = rank Lm = g and Lp - Lm (the intersection form) of rank 2g. A push-off that
  /// crosses the surface elsewhere (a thin part) breaks that: the steps shrink and the
  /// matrices are computed again, a few times; false if they never agree.
  bool consistent_linking_matrices(const std::vector<const std::vector<int>*>& basis, int genus,
                                   Eigen::MatrixXd& Lp, Eigen::MatrixXd& Lm)
  {
    for(int tries = 0; tries < 6; ++tries) {
      linking_matrices(basis, Lp, Lm);
      if(Eigen::FullPivLU<Eigen::MatrixXd>(Lp).rank() == genus && Eigen::FullPivLU<Eigen::MatrixXd>(Lm).rank() == genus &&
         Eigen::FullPivLU<Eigen::MatrixXd>(Lp - Lm).rank() == 2 * genus)
        return true;
      for(double& x : step) x *= 0.25;
    }
    return false;
  }
};

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LOOP_PUSH_OFF_H
