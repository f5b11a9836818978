// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Spline back end timings (reference §4.1): surface fitting on m x m grids (m = 16..256),
// Coons volume + harmonic interior for control nets n^3 (n = 8..64), and the whole per-cuboid
// recipe (fit_bspline_volume) from six m x m grids. Baseline: one CHOLMOD factorization and
// solve (internal/sparse_cholesky.h) of a grid Laplacian with the same number of unknowns
// (2D for a surface fit, 3D for a volume interior), measured in the same run.

#include "benchmark_registry.h"

#include <CGAL/Polycube_IGA/Bspline_volume_construction.h>
#include <CGAL/Polycube_IGA/Quality.h>
#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>

#include <cmath>
#include <string>

namespace {

namespace PI = CGAL::Polycube_IGA;

Eigen::Vector3d twist(double u, double v, double w)
{
  const double a = 1.2 * w, x = u - 0.5, y = v - 0.5;
  return Eigen::Vector3d(std::cos(a) * x - std::sin(a) * y, std::sin(a) * x + std::cos(a) * y, 1.5 * w + 0.1 * std::sin(3 * u));
}

/// One Cholesky factorization + solve (3 right-hand sides) of the Dirichlet grid Laplacian
/// with `n` points per direction in `dim` dimensions.
double laplacian_baseline(int dim, int n, int repetitions)
{
  const int total = dim == 2 ? n * n : n * n * n;
  std::vector<Eigen::Triplet<double>> t;
  for(int idx = 0; idx < total; ++idx) {
    int c[3] = {idx % n, (idx / n) % n, dim == 3 ? idx / (n * n) : 0};
    t.emplace_back(idx, idx, 2. * dim);
    for(int d = 0; d < dim; ++d)
      for(int e = -1; e <= 1; e += 2) {
        const int q = c[d] + e;
        if(q < 0 || q >= n) continue;
        int s = 1;
        for(int k = 0; k < d; ++k) s *= n;
        t.emplace_back(idx, idx + e * s, -1.);
      }
  }
  Eigen::SparseMatrix<double> A(total, total);
  A.setFromTriplets(t.begin(), t.end());
  const Eigen::MatrixXd b = Eigen::MatrixXd::Ones(total, 3);
  return polycube_iga_bench::best_time(repetitions, [&] {
    PI::internal::Sparse_cholesky s;
    s.factor(A, "baseline Laplacian");
    volatile double x = s.solve(b)(0, 0);
    (void)x;
  });
}

std::array<PI::Point_grid, 6> face_grids(int m) { return PI::sample_cuboid_faces(twist, m); }

void run(const polycube_iga_bench::Options& opt)
{
  const int reps = opt.repetitions;
  // 1. One face: m x m points, cubic, min(m/4, 61) spans per direction (<= 64 control points).
  for(int m : opt.quick ? std::vector<int>{16, 32, 64} : std::vector<int>{16, 32, 64, 128, 256}) {
    const PI::Point_grid g = face_grids(m)[4];
    PI::Surface_fitting_options o;
    o.spans_u = o.spans_v = std::min(m / 4, 61);
    const int n = o.spans_u + 3;
    double err = 0.;
    const double t = polycube_iga_bench::best_time(reps, [&] { err = PI::fit_bspline_surface(g, o).max_error; });
    polycube_iga_bench::report("spline", "fit_surface " + std::to_string(m) + "^2 pts " + std::to_string(n) + "^2 cps",
                               {{"points", double(m) * m}, {"control_points", double(n) * n}, {"max_error", err}},
                               {{"fit_surface", t}}, "cholesky_laplacian2d_" + std::to_string(n) + "^2",
                               laplacian_baseline(2, n, reps));
  }
  // 2. Coons + harmonic interior for an n^3 control net (faces of an exact twisted volume).
  for(int n : opt.quick ? std::vector<int>{8, 16} : std::vector<int>{8, 16, 32, 48, 64}) {
    const PI::Knot_vector k = PI::Knot_vector::uniform(3, n - 3);
    std::vector<Eigen::Vector3d> P;
    for(int c = 0; c < n; ++c)
      for(int b = 0; b < n; ++b)
        for(int a = 0; a < n; ++a) P.push_back(twist(k.normalized_greville(a), k.normalized_greville(b), k.normalized_greville(c)));
    const PI::Tensor_bspline_volume v({k, k, k}, P);
    std::array<PI::Tensor_bspline_surface, 6> faces;
    for(int s = 1; s <= 6; ++s) faces[std::size_t(s - 1)] = PI::side_surface(v, s);
    std::vector<std::pair<std::string, double>> stages;
    PI::Volume_construction_options o;
    o.smoothing = PI::Interior_smoothing::none;
    stages.emplace_back("coons", polycube_iga_bench::best_time(reps, [&] { PI::build_bspline_volume(faces, o); }));
    o.smoothing = PI::Interior_smoothing::harmonic;
    PI::Tensor_bspline_volume result;
    stages.emplace_back("coons_harmonic", polycube_iga_bench::best_time(reps, [&] { result = PI::build_bspline_volume(faces, o).volume; }));
    int iterations = 0;
    if(n <= 16) {
      o.smoothing = PI::Interior_smoothing::fixed_point_iteration;
      o.iteration_tolerance = 1e-10;
      stages.emplace_back("coons_fixed_point", polycube_iga_bench::best_time(1, [&] { iterations = PI::build_bspline_volume(faces, o).iterations; }));
    }
    stages.emplace_back("certified_bound", polycube_iga_bench::best_time(1, [&] { PI::certified_jacobian_bound(result); }));
    polycube_iga_bench::report("spline", "volume " + std::to_string(n) + "^3 cps",
                               {{"control_points", double(n) * n * n}, {"fixed_point_iterations", double(iterations)}}, stages,
                               "cholesky_laplacian3d_" + std::to_string(n - 2) + "^3", laplacian_baseline(3, n - 2, reps));
  }
  // 3. The whole recipe for one cuboid from six m x m grids.
  for(int m : opt.quick ? std::vector<int>{16, 32} : std::vector<int>{16, 32, 64, 128, 256}) {
    const auto grids = face_grids(m);
    PI::Volume_fitting_options o;
    const int spans = std::min(m / 4, 61), n = spans + 3;
    o.knots = {PI::Knot_vector::uniform(3, spans), PI::Knot_vector::uniform(3, spans), PI::Knot_vector::uniform(3, spans)};
    const double t = polycube_iga_bench::best_time(std::min(reps, m >= 128 ? 1 : reps), [&] { PI::fit_bspline_volume(grids, o); });
    polycube_iga_bench::report("spline", "fit_volume 6x" + std::to_string(m) + "^2 pts " + std::to_string(n) + "^3 cps",
                               {{"points", 6. * m * m}, {"control_points", double(n) * n * n}}, {{"fit_volume", t}},
                               "cholesky_laplacian3d_" + std::to_string(n - 2) + "^3", laplacian_baseline(3, n - 2, 1));
  }
}

const polycube_iga_bench::Register_suite registration("spline", run);

} // namespace
