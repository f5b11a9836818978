// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The cotangent Laplacian of a triangle mesh (the P1 finite-element stiffness matrix of the
// Dirichlet energy) and its lumped mass matrix, built on a Mesh_graph. Every stage that needs
// a harmonic solve, a heat flow or a smoothing reuses these two builders, and with
// Sparse_cholesky factors them once.
//
// Sign convention: L is positive semidefinite, L(i,i) = sum_j w_ij, L(i,j) = -w_ij with
//   w_ij = (cot alpha_ij + cot beta_ij) / 2
// (alpha, beta the angles opposite edge ij; a border edge has one term). The null space of
// L on a connected mesh is the constant vectors, so `L + epsilon * M` is SPD for epsilon > 0.
//
// Robustness. An obtuse angle has a negative cotangent, and two of them opposite one edge
// make w_ij < 0: the matrix stays semidefinite (it is a stiffness matrix) but loses the
// discrete maximum principle that harmonic solves rely on (no overshoot, monotone fields).
// By default w_ij is clamped to >= 0 (`clamp_negative_weights`), which gives an M-matrix, a
// weighted graph Laplacian, whatever the triangles. Cotangents of near-zero angles (needle
// and degenerate triangles) are bounded by `maximum_cotangent`, so that no entry is infinite
// or NaN and the conditioning stays bounded. Both clamps leave a Delaunay mesh unchanged.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_COTANGENT_LAPLACIAN_H
#define CGAL_POLYCUBE_IGA_INTERNAL_COTANGENT_LAPLACIAN_H

#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// Options of `cotangent_laplacian()`; the defaults suit harmonic solves on meshes of any quality.
struct Cotangent_laplacian_options
{
  /// Clamp edge weights (cot alpha + cot beta) / 2 to >= 0: an M-matrix, maximum principle kept.
  bool clamp_negative_weights = true;
  /// Upper bound on |cot| of one angle (about 1e-5 rad); degenerate triangles contribute this.
  double maximum_cotangent = 1e5;
};

/// Cotangent of the angle at `o` of triangle (o, a, b), bounded by `max_cot` in absolute value.
inline double bounded_cotangent(const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                double max_cot)
{
  const Eigen::Vector3d u = a - o, v = b - o;
  const double c = u.dot(v), s = u.cross(v).norm();
  if(!(s > 0) || std::abs(c) >= max_cot * s) // zero or tiny angle (or pi): bounded
    return c >= 0 ? max_cot : -max_cot;
  return c / s;
}

/// Per-edge cotangent weights w_e = (cot alpha + cot beta) / 2, indexed like `g`'s edges.
template <class Mesh_graph>
std::vector<double> cotangent_edge_weights(const Mesh_graph& g,
                                           const Cotangent_laplacian_options& options = Cotangent_laplacian_options())
{
  std::vector<double> w(std::size_t(g.number_of_edges()), 0.0);
  for(int f = 0; f < g.number_of_faces(); ++f) {
    const auto& fv = g.face_vertices[f];
    const auto& fe = g.face_edges[f];
    // Edge k joins vertices k and k+1; the angle opposite it is at vertex k+2.
    for(int k = 0; k < 3; ++k)
      w[fe[k]] += 0.5 * bounded_cotangent(g.position[fv[(k + 2) % 3]], g.position[fv[k]],
                                          g.position[fv[(k + 1) % 3]], options.maximum_cotangent);
  }
  if(options.clamp_negative_weights)
    for(double& x : w) x = std::max(0.0, x);
  return w;
}

/*!
 * Cotangent Laplacian of the triangle mesh behind `g` (an `internal::Mesh_graph`): an
 * n x n symmetric positive semidefinite matrix, n = g.number_of_vertices(), indexed by the
 * mesh's vertex indices. Isolated vertices get an empty row. O(F) time and memory.
 */
template <class Mesh_graph>
Eigen::SparseMatrix<double> cotangent_laplacian(const Mesh_graph& g,
                                                const Cotangent_laplacian_options& options = Cotangent_laplacian_options())
{
  const std::vector<double> w = cotangent_edge_weights(g, options);
  const int n = g.number_of_vertices();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(4 * w.size());
  for(int e = 0; e < g.number_of_edges(); ++e) {
    const int a = g.edge_vertices[e][0], b = g.edge_vertices[e][1];
    entries.emplace_back(a, b, -w[e]);
    entries.emplace_back(b, a, -w[e]);
    entries.emplace_back(a, a, w[e]);
    entries.emplace_back(b, b, w[e]);
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

/// Lumped (barycentric) mass matrix: M(i,i) = one third of the area of the faces around i.
template <class Mesh_graph>
Eigen::SparseMatrix<double> lumped_mass_matrix(const Mesh_graph& g)
{
  const int n = g.number_of_vertices();
  std::vector<double> m(std::size_t(n), 0.0);
  for(int f = 0; f < g.number_of_faces(); ++f) {
    const auto& fv = g.face_vertices[f];
    const double area = 0.5 * (g.position[fv[1]] - g.position[fv[0]]).cross(g.position[fv[2]] - g.position[fv[0]]).norm();
    for(int v : fv) m[v] += area / 3.0;
  }
  Eigen::SparseMatrix<double> M(n, n);
  M.reserve(Eigen::VectorXi::Constant(n, 1));
  for(int i = 0; i < n; ++i) M.insert(i, i) = m[i];
  M.makeCompressed();
  return M;
}

/*!
 * The Dirichlet problem of a weighted graph Laplacian: values at `n` free unknowns such that
 * each is the weighted mean of its neighbours, the other vertices' values fixed. Callers add
 * every edge at each free unknown once from that unknown's side (so an edge between two free
 * unknowns twice, once per end); weights below 1e-9 are raised to it, so that every unknown
 * stays tied to its ring and the matrix is positive definite when each component of free
 * unknowns touches a fixed vertex. With clamped cotangent weights it is an M-matrix: no
 * overshoot, no inner extremum, so each side of a level set touches fixed vertices (what
 * the centring of Pants_decomposition.h and the arc relaxation of Layout_arc_relaxation.h
 * rely on).
 */
class Harmonic_extension
{
public:
  explicit Harmonic_extension(std::size_t n) : diagonal_(n, 0.), rhs_(Eigen::VectorXd::Zero(Eigen::Index(n))) {}

  /// The edge from free unknown `i` to free unknown `j`, or, with `j < 0`, to a fixed
  /// vertex of value `fixed`; weight `k`.
  void add_edge(int i, int j, double k, double fixed = 0.)
  {
    k = std::max(k, 1e-9);
    diagonal_[std::size_t(i)] += k;
    if(j < 0) rhs_(Eigen::Index(i)) += k * fixed;
    else if(j < i) lower_.emplace_back(i, j, -k); // the solver reads the lower triangle only
  }

  /// The free unknowns' values; `what` names the system in a solver failure.
  Eigen::VectorXd solve(const std::string& what) const
  {
    const Eigen::Index n = rhs_.size();
    std::vector<Eigen::Triplet<double>> entries(lower_);
    for(Eigen::Index i = 0; i < n; ++i) entries.emplace_back(int(i), int(i), diagonal_[std::size_t(i)]);
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(entries.begin(), entries.end());
    Sparse_cholesky solver;
    solver.factor(A, what);
    return solver.solve(rhs_);
  }

private:
  std::vector<double> diagonal_;
  Eigen::VectorXd rhs_;
  std::vector<Eigen::Triplet<double>> lower_;
};

/// The harmonic extension over the `free` vertices of `g` (`index`: each vertex's place in
/// `free`, -1 for a fixed one) of the values `fixed_value(v)` at the fixed vertices next to
/// them, edge `e` weighted by `weight[e]`: Harmonic_extension assembled from the graph's
/// adjacency. Returns the free vertices' values, in the order of `free`.
template <class Mesh_graph, class Fixed_value>
Eigen::VectorXd harmonic_extension(const Mesh_graph& g, const std::vector<double>& weight, const std::vector<int>& free,
                                   const std::vector<int>& index, const Fixed_value& fixed_value, const std::string& what)
{
  Harmonic_extension system(free.size());
  for(std::size_t i = 0; i < free.size(); ++i)
    for(int a = g.offset[std::size_t(free[i])]; a < g.offset[std::size_t(free[i]) + 1]; ++a) {
      const int x = g.adjacent_vertex[std::size_t(a)];
      const int j = index[std::size_t(x)];
      system.add_edge(int(i), j, weight[std::size_t(g.adjacent_edge[std::size_t(a)])], j < 0 ? fixed_value(x) : 0.);
    }
  return system.solve(what);
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_COTANGENT_LAPLACIAN_H
