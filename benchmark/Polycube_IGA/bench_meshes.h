// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Shared by the mesh suites (topology, pants): the mesh type, one-core pinning, CPU time,
// loading a data file with midpoint subdivisions, and the common baseline, one CHOLMOD
// supernodal factorization and solve of L + 1e-8 M (cotangent Laplacian plus a scale-free
// mass shift, SPD) on the same mesh.

#ifndef POLYCUBE_IGA_BENCH_MESHES_H
#define POLYCUBE_IGA_BENCH_MESHES_H

#include "benchmark_registry.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polycube_IGA/IO/read_triangle_mesh.h>
#include <CGAL/Polycube_IGA/internal/cotangent_laplacian.h>
#include <CGAL/Polycube_IGA/internal/mesh_graph.h>
#include <CGAL/Polycube_IGA/internal/mesh_refinement.h>
#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>

#ifdef __linux__
#include <sched.h>
#endif

namespace polycube_iga_bench {
namespace meshes {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

/// Restricts the process to one CPU for the lifetime of the object (Linux), then restores.
class One_core
{
public:
  One_core()
  {
#ifdef __linux__
    if(sched_getaffinity(0, sizeof(saved_), &saved_) == 0) {
      cpu_set_t one;
      CPU_ZERO(&one);
      int cpu = sched_getcpu();
      if(cpu < 0 || !CPU_ISSET(cpu, &saved_))
        for(cpu = 0; cpu < CPU_SETSIZE && !CPU_ISSET(cpu, &saved_); ++cpu) {}
      CPU_SET(cpu, &one);
      pinned_ = sched_setaffinity(0, sizeof(one), &one) == 0;
    }
#endif
  }
  ~One_core()
  {
#ifdef __linux__
    if(pinned_) sched_setaffinity(0, sizeof(saved_), &saved_);
#endif
  }
  One_core(const One_core&) = delete;
  One_core& operator=(const One_core&) = delete;
  bool pinned() const { return pinned_; }
  /// How the suite's header says it ran.
  const char* description() const { return pinned_ ? "pinned to one core" : "not pinned (one thread)"; }

private:
  bool pinned_ = false;
#ifdef __linux__
  cpu_set_t saved_;
#endif
};

/// The header line of a suite timed as the best of its repetitions against the same-run
/// CHOLMOD baseline; `best_by` qualifies "best" (" (by total)").
inline void print_timed_suite_header(const char* suite, const Options& opt, const One_core& core, const char* best_by = "")
{
  std::printf("# suite %s: best of %d%s, %s; baseline = CHOLMOD LLT factor + solve of cotangent Laplacian + 1e-8 M\n", suite,
              std::max(1, opt.repetitions), best_by, core.description());
}

/// One benchmark input: a shared-data mesh, subdivided `subdivisions` times.
struct Case
{
  const char* file;   ///< relative to the data directory
  int subdivisions;   ///< midpoint subdivisions (x4 faces each)
  bool quick;         ///< part of --quick
};

inline double process_cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

inline std::string base_name(const std::string& path)
{
  return std::filesystem::path(path).filename().string();
}

/// Reads `path` (no self-intersection test) and applies `subdivisions` midpoint
/// subdivisions (x4 faces each, geometry unchanged). False when the file is not valid.
inline bool read_subdivided(const std::string& path, int subdivisions, Mesh& m)
{
  namespace PI = CGAL::Polycube_IGA;
  const PI::Validation_report r =
    PI::read_triangle_mesh(path, m, CGAL::Polycube_IGA::parameters::check_self_intersections(false));
  if(!r.is_valid()) return false;
  for(int k = 0; k < subdivisions; ++k) PI::internal::subdivide_at_edge_midpoints(m, get(CGAL::vertex_point, m));
  return true;
}

/// The boundary of a union of unit cubes (a CAD block: an L, a T, a step), each cube face
/// on the boundary split into `n` x `n` squares of two triangles, outward. `cells` must make
/// a manifold solid (no two cubes sharing only an edge or a corner). The faces are regular,
/// unlike a CAD mesher's, and every sharp edge is a mesh polyline.
inline void union_of_cubes(const std::vector<std::array<int, 3>>& cells, int n, Mesh& m)
{
  std::set<std::array<int, 3>> solid(cells.begin(), cells.end());
  std::map<std::array<int, 3>, Mesh::Vertex_index> lattice; // points at 1/n steps
  auto vertex = [&](std::array<int, 3> x) {
    auto it = lattice.find(x);
    if(it != lattice.end()) return it->second;
    const auto v = m.add_vertex(Point(double(x[0]) / n, double(x[1]) / n, double(x[2]) / n));
    lattice.emplace(x, v);
    return v;
  };
  for(const auto& c : solid)
    for(int a = 0; a < 3; ++a)
      for(int side = 0; side < 2; ++side) {
        std::array<int, 3> next = c;
        next[std::size_t(a)] += side ? 1 : -1;
        if(solid.count(next)) continue;
        const std::size_t b = std::size_t((a + 1) % 3), d = std::size_t((a + 2) % 3);
        for(int i = 0; i < n; ++i)
          for(int j = 0; j < n; ++j) {
            std::array<Mesh::Vertex_index, 4> q;
            const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
            for(int k = 0; k < 4; ++k) {
              std::array<int, 3> x{c[0] * n, c[1] * n, c[2] * n};
              x[std::size_t(a)] += side * n;
              x[b] += i + du[k];
              x[d] += j + dv[k];
              q[std::size_t(k)] = vertex(x);
            }
            // e_b x e_d = e_a: counter-clockwise in (b, d) faces +a.
            if(side) m.add_face(q[0], q[1], q[2]), m.add_face(q[0], q[2], q[3]);
            else m.add_face(q[0], q[2], q[1]), m.add_face(q[0], q[3], q[2]);
          }
      }
}

/// The baseline of the mesh suites on `mesh`: best of `repetitions` CHOLMOD factor + solve of
/// L + 1e-8 M. The assembly time (once) goes to `assembly_seconds`, the relative residual
/// of the solve to `residual`.
inline double cholmod_laplacian_baseline(const Mesh& mesh, int repetitions, double& assembly_seconds,
                                         double& residual)
{
  namespace PI = CGAL::Polycube_IGA;
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd b;
  assembly_seconds = best_time(1, [&] {
    PI::internal::Mesh_graph<Mesh> graph(mesh, get(CGAL::vertex_point, mesh));
    const Eigen::SparseMatrix<double> L = PI::internal::cotangent_laplacian(graph);
    const Eigen::SparseMatrix<double> M = PI::internal::lumped_mass_matrix(graph);
    const double mean_mass = M.sum() / double(std::max<Eigen::Index>(1, M.rows()));
    A = L + (1e-8 / mean_mass) * M;
    // Right-hand side M (x - mean x): orthogonal to the constants, a well-posed Poisson
    // problem whose solution stays O(|b| / lambda_2) despite the tiny shift.
    const int n = graph.number_of_vertices();
    double mean_x = 0;
    for(int v = 0; v < n; ++v) mean_x += M.coeff(v, v) * graph.position[v].x();
    mean_x /= M.sum();
    b.resize(n);
    for(int v = 0; v < n; ++v) b[v] = M.coeff(v, v) * (graph.position[v].x() - mean_x);
  });
  residual = 0;
  return best_time(repetitions, [&] {
    PI::internal::Sparse_cholesky solver;
    solver.factor(A, "benchmark Laplacian");
    const Eigen::MatrixXd x = solver.solve(b);
    residual = (A * x - b).norm() / std::max(1e-300, b.norm());
  });
}

} // namespace meshes
} // namespace polycube_iga_bench

#endif
