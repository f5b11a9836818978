// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Structured point grids on the quad patches of a Polycube_layout: the "regular and
// structured points grid ... mapped to the boundary triangle mesh using barycentric
// coordinates" of reference §4.1.1, with a baseline per-patch parameterization instead of
// the aligned global one of chapter 3.
//
// * Every arc is sampled once, at N+1 points equally spaced in 3D arc length along its
//   vertex path. Every patch copies its border rows from these samples, so the grids of
//   two patches sharing an arc agree there bit for bit (and so do the faces fitted to them).
// * A SURFACE patch (a disk of mesh faces with 4 corners) is mapped onto the unit square by
//   a Tutte-type embedding (§2.1.3, eq. 2.12): its border on the square's sides by arc
//   length, each interior vertex a weighted mean of its neighbours. The weights are
//   Floater's mean-value weights (eq. 2.13) symmetrised, w_ij + w_ji: positive, so by
//   Floater's theorem the map is one-to-one onto the convex square (unless an inner edge
//   joins two vertices of one arc: the triangles cut off are flat, and counted as flipped),
//   and symmetric, so the system is SPD and one Cholesky factorization serves both
//   coordinates. Grid point (i,j)
//   at (i/N, j/N) is located in the uv triangulation (exact orientation predicates) and
//   interpolated barycentrically in 3D.
// * A CAP or INTERFACE patch has no faces: its grid is the discrete Coons patch of its four
//   arc samples, optionally (default) replaced by the discrete harmonic interior with the
//   border fixed (the surface analogue of §4.1.2, eq. 4.6 solved exactly). All such patches
//   share one matrix, factored once.
//
// Grid convention: patch corners c0 c1 c2 c3 sit at (0,0), (1,0), (1,1), (0,1); arcs[i]
// (c_i -> c_{i+1}) is side i of the square; grid(i, j) samples (i/N, j/N). For a surface
// patch (corners counter-clockwise from outside) grid u x grid v points out of the solid.

#ifndef CGAL_POLYCUBE_IGA_PATCH_SAMPLING_H
#define CGAL_POLYCUBE_IGA_PATCH_SAMPLING_H

#include <CGAL/Polycube_IGA/Bspline_surface_fitting.h>
#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>
#include <CGAL/Polycube_IGA/parameters.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Options of sample_layout_patches().
struct Patch_sampling_options
{
  /// N: grid segments per patch side, the same for every patch so that the two sides of an
  /// arc agree. 16 gives 4 samples per knot span with the default 4 spans of the volume fit.
  int grid_segments = 16;
  /// CAP and INTERFACE patches: replace the Coons interior by the discrete harmonic one.
  bool smooth_interior_patches = true;
  /// SURFACE patches: rounds of stretch reduction after the mean-value map (0: none), which
  /// give a protrusion that the map shrinks its share of the grid (map_surface_patch()).
  int stretch_rounds = 0;
  /// Arcs on the mesh's border (input boundary loops) are rounded where they turn by more
  /// than this many degrees at a vertex inside the arc (round_sharp_turns(); 0: never).
  double sharp_boundary_turn = 60.;
};

namespace internal {

/// Grid index of sample k (from corner i) along side i of a patch square whose corners
/// 0..3 sit at (0,0), (N,0), (N,N), (0,N).
inline std::array<int, 2> border_index(int i, int k, int N)
{
  switch(i) {
  case 0: return {{k, 0}};
  case 1: return {{N, k}};
  case 2: return {{N - k, N}};
  default: return {{0, N - k}};
  }
}

} // namespace internal

/// Point grids of every patch of a layout, (N+1) x (N+1) each.
struct Patch_grids
{
  int segments = 0;                                        ///< N
  std::vector<std::vector<Eigen::Vector3d>> arc_samples;   ///< per arc, N+1 points from arc.nodes[0] to arc.nodes[1]
  std::vector<Point_grid> grids;                           ///< per patch, grid(i,j) at (i/N, j/N) of its corner square
  /// Per patch: uv triangles of non-positive orientation, degenerate ones included (0 expected;
  /// a triangle with its three vertices on one arc is necessarily degenerate). 0 off the surface.
  std::vector<int> flipped_triangles;
  std::vector<int> unlocated_points;  ///< per patch: interior grid points no positive uv triangle contains (0 expected)

  /// Grid points along side i (0..3) of patch p's square, from corner i to corner i+1.
  std::vector<Eigen::Vector3d> side(std::size_t p, int i) const
  {
    const Point_grid& g = grids[p];
    const int N = segments;
    std::vector<Eigen::Vector3d> r;
    for(int k = 0; k <= N; ++k) {
      const std::array<int, 2> ij = internal::border_index(i, k, N);
      r.push_back(g(ij[0], ij[1]));
    }
    return r;
  }
};

namespace internal {

template <class Point_3>
Eigen::Vector3d to_eigen_point(const Point_3& p)
{
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

/// Cumulative 3D length along an arc's vertex path (0 at nodes[0]).
inline std::vector<double> cumulative_lengths(const std::vector<Eigen::Vector3d>& pts)
{
  std::vector<double> c(pts.size(), 0.);
  for(std::size_t k = 1; k < pts.size(); ++k) c[k] = c[k - 1] + (pts[k] - pts[k - 1]).norm();
  return c;
}

/// Unit tangent of arc samples `s` leaving their first (or last) point; zero if degenerate.
inline Eigen::Vector3d end_tangent(const std::vector<Eigen::Vector3d>& s, bool at_start)
{
  if(s.size() < 2) return Eigen::Vector3d::Zero();
  const std::size_t m = s.size() - 1;
  const Eigen::Vector3d d = at_start ? Eigen::Vector3d(s[1] - s[0]) : Eigen::Vector3d(s[m - 1] - s[m]);
  const double l = d.norm();
  return l > 0. ? Eigen::Vector3d(d / l) : Eigen::Vector3d::Zero();
}

/// N+1 points equally spaced in arc length along a polyline; the ends are its end points
/// exactly (so every arc meeting at a node starts from the same bits).
inline std::vector<Eigen::Vector3d> sample_polyline(const std::vector<Eigen::Vector3d>& pts,
                                                    const std::vector<double>& cum, int N)
{
  std::vector<Eigen::Vector3d> r(std::size_t(N) + 1);
  const double total = cum.back();
  std::size_t k = 0;
  for(int i = 0; i <= N; ++i) {
    if(i == 0 || !(total > 0.)) {
      r[std::size_t(i)] = i == N ? pts.back() : pts.front();
      continue;
    }
    if(i == N) {
      r[std::size_t(i)] = pts.back();
      continue;
    }
    const double target = total * double(i) / double(N);
    while(k + 2 < pts.size() && cum[k + 1] < target) ++k;
    const double len = cum[k + 1] - cum[k];
    const double t = len > 0. ? std::min(1., std::max(0., (target - cum[k]) / len)) : 0.;
    r[std::size_t(i)] = pts[k] + t * (pts[k + 1] - pts[k]);
  }
  return r;
}

/// Rejects a `sharp_boundary_turn` outside [0, 180] degrees (Invalid_input_error).
inline void check_sharp_boundary_turn(double degrees)
{
  if(!(degrees >= 0. && degrees <= 180.))
    throw Invalid_input_error("invalid_parameter", "sharp_boundary_turn must be between 0 and 180 degrees");
}

/// Whether the vertex path `path` runs along the border of `mesh` (an input boundary loop).
template <class Mesh, class Vertex>
bool on_mesh_border(const Mesh& mesh, const std::vector<Vertex>& path)
{
  for(std::size_t k = 0; k + 1 < path.size(); ++k) {
    const auto h = halfedge(path[k], path[k + 1], mesh);
    if(!h.second || !(is_border(h.first, mesh) || is_border(opposite(h.first, mesh), mesh))) return false;
  }
  return path.size() > 1;
}

/// Rounds the samples `r` of the polyline `pts` (cumulative lengths `cum`, samples at
/// i/N of its length) where it turns by more than `sharp_turn` degrees at an inner vertex:
/// the samples near that vertex move to the quadratic Bezier curve with the vertex as its
/// control point, at the same arc-length parameter. Why: on an input boundary loop such a
/// vertex is inside a patch side (a tip of head.off's eye holes turns by 105 degrees), and
/// a side with a kink is a reflex crease in the middle of the face of the slab under the
/// surface, where det J of a smooth map cannot stay positive. The curve stays in the
/// triangle of the vertex's two edges, so it cuts across the hole by less than half an edge.
inline void round_sharp_turns(const std::vector<Eigen::Vector3d>& pts, const std::vector<double>& cum, double sharp_turn,
                              std::vector<Eigen::Vector3d>& r)
{
  const int N = int(r.size()) - 1;
  const double total = cum.back(), cos_sharp = std::cos(sharp_turn * CGAL_PI / 180.);
  if(N < 2 || !(total > 0.)) return;
  // The inner vertices where the polyline turns sharply (a zero-length edge never does).
  std::vector<bool> sharp(pts.size(), false);
  for(std::size_t k = 1; k + 1 < pts.size(); ++k) {
    const Eigen::Vector3d in = pts[k] - pts[k - 1], out = pts[k + 1] - pts[k];
    sharp[k] = in.dot(out) < cos_sharp * in.norm() * out.norm();
  }
  for(std::size_t k = 1; k + 1 < pts.size(); ++k) {
    if(!sharp[k]) continue;
    const Eigen::Vector3d in = pts[k] - pts[k - 1], out = pts[k + 1] - pts[k];
    const double li = in.norm(), lo = out.norm();
    // Along each edge, half of it if its other end is rounded too (no overlap), three
    // quarters otherwise. head.off is valid so; with half of each edge one eye tip stays
    // pinned, with half of the shorter edge on both sides two do.
    const double wa = (sharp[k - 1] ? 0.5 : 0.75) * li, wb = (sharp[k + 1] ? 0.5 : 0.75) * lo;
    const Eigen::Vector3d A = pts[k] - wa * in / li, B = pts[k] + wb * out / lo;
    for(int i = 1; i < N; ++i) {
      const double t = (total * double(i) / double(N) - (cum[k] - wa)) / (wa + wb);
      if(t <= 0. || t >= 1.) continue;
      r[std::size_t(i)] = (1. - t) * (1. - t) * A + 2. * t * (1. - t) * pts[k] + t * t * B;
    }
  }
}

/// Copies the four arc samples into the border rows of an (N+1)^2 grid (corner i of the
/// patch at (0,0), (N,0), (N,N), (0,N)); `forward[i]` says whether arc i runs c_i -> c_{i+1}.
inline void set_grid_border(Point_grid& g, int N, const std::array<const std::vector<Eigen::Vector3d>*, 4>& arc,
                            const std::array<bool, 4>& forward)
{
  for(int i = 0; i < 4; ++i)
    for(int k = 0; k <= N; ++k) {
      const std::array<int, 2> ij = border_index(i, k, N);
      g(ij[0], ij[1]) = (*arc[std::size_t(i)])[std::size_t(forward[std::size_t(i)] ? k : N - k)];
    }
}

/// Discrete Coons patch of the border rows (parameters i/N, j/N: the border is sampled
/// uniformly in arc length).
inline void coons_grid_interior(Point_grid& g, int N)
{
  for(int j = 1; j < N; ++j)
    for(int i = 1; i < N; ++i) {
      const double s = double(i) / N, t = double(j) / N;
      g(i, j) = (1. - s) * g(0, j) + s * g(N, j) + (1. - t) * g(i, 0) + t * g(i, N) -
                ((1. - s) * (1. - t) * g(0, 0) + s * (1. - t) * g(N, 0) + (1. - s) * t * g(0, N) + s * t * g(N, N));
    }
}

/// The border rows of patch `pa` of layout `L` from the arcs' samples (set_grid_border()).
template <class Layout>
void set_patch_border(Point_grid& g, int N, const Layout& L, const typename Layout::Patch& pa,
                      const std::vector<std::vector<Eigen::Vector3d>>& arc_samples)
{
  std::array<const std::vector<Eigen::Vector3d>*, 4> arc;
  std::array<bool, 4> forward;
  for(int i = 0; i < 4; ++i) {
    arc[std::size_t(i)] = &arc_samples[pa.arcs[std::size_t(i)]];
    forward[std::size_t(i)] = L.arcs[pa.arcs[std::size_t(i)]].nodes[0] == pa.corners[std::size_t(i)];
  }
  set_grid_border(g, N, arc, forward);
}

/// The 5-point graph Laplacian of the (N-1)^2 interior grid nodes, factored once and shared
/// by every CAP and INTERFACE patch (they all have the same grid).
class Grid_harmonic_solver
{
public:
  explicit Grid_harmonic_solver(int N) : N_(N)
  {
    const int m = N - 1;
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(std::size_t(5 * m * m));
    for(int j = 0; j < m; ++j)
      for(int i = 0; i < m; ++i) {
        const int r = i + m * j;
        t.emplace_back(r, r, 4.);
        if(i > 0) t.emplace_back(r, r - 1, -1.);
        if(i + 1 < m) t.emplace_back(r, r + 1, -1.);
        if(j > 0) t.emplace_back(r, r - m, -1.);
        if(j + 1 < m) t.emplace_back(r, r + m, -1.);
      }
    Eigen::SparseMatrix<double> A(m * m, m * m);
    A.setFromTriplets(t.begin(), t.end());
    chol_.factor(A, "harmonic grid of an interior patch");
  }

  /// Replaces the interior of `g` by the discrete harmonic grid with its border fixed.
  void solve(Point_grid& g) const
  {
    const int N = N_, m = N - 1;
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(m * m, 3);
    for(int j = 1; j < N; ++j)
      for(int i = 1; i < N; ++i) {
        const int r = (i - 1) + m * (j - 1);
        if(i == 1) b.row(r) += g(0, j).transpose();
        if(i == N - 1) b.row(r) += g(N, j).transpose();
        if(j == 1) b.row(r) += g(i, 0).transpose();
        if(j == N - 1) b.row(r) += g(i, N).transpose();
      }
    const Eigen::MatrixXd x = chol_.solve(b);
    for(int j = 1; j < N; ++j)
      for(int i = 1; i < N; ++i) g(i, j) = x.row((i - 1) + m * (j - 1)).transpose();
  }

private:
  int N_;
  Sparse_cholesky chol_;
};

/// Fills the interior of CAP and INTERFACE grids whose border rows are set: the discrete
/// Coons patch, replaced (if `smooth`) by the discrete harmonic one; the harmonic solver is
/// factored on first use and shared by every grid filled. The border rows are kept.
class Interior_grid_filler
{
public:
  Interior_grid_filler(int N, bool smooth) : N_(N), smooth_(smooth) {}

  void fill(Point_grid& g)
  {
    coons_grid_interior(g, N_);
    if(!smooth_) return;
    if(!harmonic_) harmonic_.reset(new Grid_harmonic_solver(N_));
    harmonic_->solve(g);
  }

private:
  int N_;
  bool smooth_;
  std::unique_ptr<Grid_harmonic_solver> harmonic_;
};

/// One surface patch as its own small triangle mesh with its uv embedding in [0,1]^2.
struct Surface_patch_map
{
  std::vector<std::size_t> vertex;         ///< local -> mesh vertex index
  std::vector<Eigen::Vector3d> position;   ///< local positions
  std::vector<Eigen::Vector2d> uv;
  std::vector<std::array<int, 3>> triangles; ///< local indices, mesh orientation
  std::vector<bool> positive;              ///< per triangle: counter-clockwise in uv (exact test)
  int flipped = 0;
};

using Epick_2 = CGAL::Exact_predicates_inexact_constructions_kernel;

/// tan(alpha/2) of the angle at `o` of triangle (o, a, b), as |u x v| / (|u||v| + u.v)
/// (no cancellation for small angles), kept in [1e-8, 1e8] so that every weight is
/// positive and finite on degenerate triangles.
inline double half_angle_tangent(const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const Eigen::Vector3d u = a - o, v = b - o;
  const double s = u.cross(v).norm(), c = u.norm() * v.norm() + u.dot(v);
  double t = c > 0. ? s / c : 1e8;
  if(!(t >= 1e-8)) t = 1e-8; // also catches NaN
  return std::min(t, 1e8);
}

/// Splits, at its midpoint, every inner edge of the patch that joins two border vertices on
/// one side of the square: the triangles it cuts off would have all their corners on that
/// side, flat in the map, and the grid would skip their part of the surface (where a
/// corner's fan has a single triangle, every femur of the population has a few). The new
/// vertex is free, and lies on the mesh, so the surface sampled does not change.
inline void split_side_chords(Surface_patch_map& M, std::vector<bool>& fixed)
{
  auto sides = [&](int v) { // bit i: on side i of the square (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0)
    if(!fixed[std::size_t(v)]) return 0u;
    const Eigen::Vector2d& q = M.uv[std::size_t(v)];
    return unsigned(q.y() == 0.) | unsigned(q.x() == 1.) << 1 | unsigned(q.y() == 1.) << 2 | unsigned(q.x() == 0.) << 3;
  };
  // Undirected edge -> the triangles holding it; inner edges have two.
  std::map<std::pair<int, int>, std::vector<std::size_t>> faces_of;
  auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for(std::size_t f = 0; f < M.triangles.size(); ++f)
    for(int c = 0; c < 3; ++c) faces_of[key(M.triangles[f][std::size_t(c)], M.triangles[f][std::size_t((c + 1) % 3)])].push_back(f);
  std::vector<std::pair<int, int>> chords;
  for(const auto& e : faces_of)
    if(e.second.size() == 2 && (sides(e.first.first) & sides(e.first.second)) != 0u) chords.push_back(e.first);
  for(const auto& e : chords) {
    const int m = int(M.position.size());
    M.vertex.push_back(std::numeric_limits<std::size_t>::max()); // no mesh vertex
    M.position.push_back(0.5 * (M.position[std::size_t(e.first)] + M.position[std::size_t(e.second)]));
    M.uv.push_back(Eigen::Vector2d::Zero());
    fixed.push_back(false);
    for(std::size_t f : std::vector<std::size_t>(faces_of[e])) {
      // Triangle (a, b, c) with edge a -> b the chord: (a, m, c) in place, (m, b, c) appended.
      std::array<int, 3> t = M.triangles[f];
      int c = 0;
      while(key(t[std::size_t(c)], t[std::size_t((c + 1) % 3)]) != e) ++c;
      const int a = t[std::size_t(c)], b = t[std::size_t((c + 1) % 3)], o = t[std::size_t((c + 2) % 3)];
      M.triangles[f] = {{a, m, o}};
      M.triangles.push_back({{m, b, o}});
      const std::size_t g = M.triangles.size() - 1;
      auto& bo = faces_of[key(b, o)];
      std::replace(bo.begin(), bo.end(), f, g);
      faces_of[key(a, m)].push_back(f);
      faces_of[key(m, o)].push_back(f);
      faces_of[key(m, o)].push_back(g);
      faces_of[key(m, b)].push_back(g);
    }
    faces_of.erase(e);
  }
}

/// Builds surface patch p as its own small mesh (border = its four arcs' vertices, fixed on
/// the square by arc length) and solves its Tutte-type embedding. `arc_cum` holds every
/// arc's cumulative lengths; `local_of` is scratch over the mesh's vertices, all -1 on entry
/// and on exit (so a patch costs O(its size), not O(mesh)). `stretch_rounds` rounds of
/// stretch reduction follow (Patch_sampling_options::stretch_rounds).
template <class Layout>
Surface_patch_map map_surface_patch(const Layout& L, std::size_t p, const std::vector<std::vector<double>>& arc_cum,
                                    std::vector<int>& local_of, int stretch_rounds = 0)
{
  const auto& pa = L.patches[p];
  const auto& mesh = L.mesh;
  Surface_patch_map M;
  static const std::array<Eigen::Vector2d, 4> C{{Eigen::Vector2d(0., 0.), Eigen::Vector2d(1., 0.),
                                                 Eigen::Vector2d(1., 1.), Eigen::Vector2d(0., 1.)}};
  std::vector<bool> fixed;
  auto add = [&](typename Layout::vertex_descriptor vd, bool is_fixed, const Eigen::Vector2d& uv) {
    const std::size_t v = std::size_t(vd);
    local_of[v] = int(M.vertex.size());
    M.vertex.push_back(v);
    M.position.push_back(to_eigen_point(mesh.point(vd)));
    M.uv.push_back(uv);
    fixed.push_back(is_fixed);
  };
  // Border: arc i on side i of the square, its vertices placed by arc length.
  for(int i = 0; i < 4; ++i) {
    const auto& arc = L.arcs[pa.arcs[std::size_t(i)]];
    const std::vector<double>& cum = arc_cum[pa.arcs[std::size_t(i)]];
    const bool forward = arc.nodes[0] == pa.corners[std::size_t(i)];
    const Eigen::Vector2d& a = C[std::size_t(i)];
    const Eigen::Vector2d& b = C[std::size_t((i + 1) % 4)];
    const std::size_t m = arc.vertices.size();
    for(std::size_t k = 0; k < m; ++k) {
      if(local_of[std::size_t(arc.vertices[k])] >= 0) continue; // a corner, placed by the previous arc
      double f = cum.back() > 0. ? cum[k] / cum.back() : double(k) / double(m - 1);
      if(k == 0) f = 0.;
      if(k + 1 == m) f = 1.;
      if(!forward) f = 1. - f;
      // Corners exactly at the square's corners; the rest on the segment.
      const Eigen::Vector2d uv = f == 0. ? a : (f == 1. ? b : Eigen::Vector2d(a + f * (b - a)));
      add(arc.vertices[k], true, uv);
    }
  }
  M.triangles.reserve(pa.faces.size());
  for(auto f : pa.faces) {
    std::array<int, 3> t{};
    int c = 0;
    for(auto h : halfedges_around_face(halfedge(f, mesh), mesh)) {
      if(c == 3) throw Invalid_input_error("not_triangle_mesh", "the layout's surface must be made of triangles");
      const auto vd = target(h, mesh);
      if(local_of[std::size_t(vd)] < 0) add(vd, false, Eigen::Vector2d::Zero());
      t[std::size_t(c++)] = local_of[std::size_t(vd)];
    }
    if(c != 3) throw Invalid_input_error("not_triangle_mesh", "the layout's surface must be made of triangles");
    M.triangles.push_back(t);
  }
  for(std::size_t v : M.vertex) local_of[v] = -1;
  split_side_chords(M, fixed);

  // Free unknowns and the SPD system: sum_j W_ij (uv_i - uv_j) = 0 for interior i, with
  // W_ij = lambda_ij + lambda_ji, lambda_ij = (tan(theta/2) + tan(phi/2)) / |v_i v_j| (eq. 2.13).
  const int n = int(M.vertex.size());
  std::vector<int> free_index(std::size_t(n), -1);
  int nf = 0;
  for(int v = 0; v < n; ++v)
    if(!fixed[std::size_t(v)]) free_index[std::size_t(v)] = nf++;
  if(nf > 0) {
    // Edge lengths are floored relative to the patch size: positive weights on degenerate edges.
    Eigen::Vector3d lo = M.position[0], hi = M.position[0];
    for(const auto& x : M.position) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    const double min_length = 1e-12 * std::max((hi - lo).norm(), 1e-300);
    // Mean-value weight of each triangle's edge c (t[c] -> t[c+1]).
    std::vector<std::array<double, 3>> weight(M.triangles.size());
    for(std::size_t f = 0; f < M.triangles.size(); ++f) {
      const auto& t = M.triangles[f];
      std::array<double, 3> tan_half;
      for(int c = 0; c < 3; ++c)
        tan_half[std::size_t(c)] = half_angle_tangent(M.position[std::size_t(t[std::size_t(c)])],
                                                      M.position[std::size_t(t[std::size_t((c + 1) % 3)])],
                                                      M.position[std::size_t(t[std::size_t((c + 2) % 3)])]);
      for(int c = 0; c < 3; ++c) {
        const int a = t[std::size_t(c)], b = t[std::size_t((c + 1) % 3)];
        const double len = std::max((M.position[std::size_t(a)] - M.position[std::size_t(b)]).norm(), min_length);
        weight[f][std::size_t(c)] = (tan_half[std::size_t(c)] + tan_half[std::size_t((c + 1) % 3)]) / len;
      }
    }
    // Edge ab weighs weight x scale_a x scale_b: positive, so the map stays one-to-one, and
    // symmetric, so the system stays SPD.
    std::vector<double> scale(std::size_t(n), 1.);
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(M.triangles.size() * 12);
    Eigen::MatrixXd rhs(nf, 2);
    auto edge = [&](int a, int b, double w) {
      const int fa = free_index[std::size_t(a)], fb = free_index[std::size_t(b)];
      if(fa >= 0) {
        trip.emplace_back(fa, fa, w);
        if(fb >= 0) trip.emplace_back(fa, fb, -w);
        else rhs.row(fa) += w * M.uv[std::size_t(b)].transpose();
      }
      if(fb >= 0) {
        trip.emplace_back(fb, fb, w);
        if(fa >= 0) trip.emplace_back(fb, fa, -w);
        else rhs.row(fb) += w * M.uv[std::size_t(a)].transpose();
      }
    };
    auto solve = [&] {
      trip.clear();
      rhs.setZero();
      for(std::size_t f = 0; f < M.triangles.size(); ++f)
        for(int c = 0; c < 3; ++c) {
          const int a = M.triangles[f][std::size_t(c)], b = M.triangles[f][std::size_t((c + 1) % 3)];
          edge(a, b, weight[f][std::size_t(c)] * scale[std::size_t(a)] * scale[std::size_t(b)]);
        }
      Eigen::SparseMatrix<double> A(nf, nf);
      A.setFromTriplets(trip.begin(), trip.end());
      Sparse_cholesky chol;
      chol.factor(A, "Tutte map of surface patch " + std::to_string(p));
      const Eigen::MatrixXd x = chol.solve(rhs);
      for(int v = 0; v < n; ++v)
        if(free_index[std::size_t(v)] >= 0) M.uv[std::size_t(v)] = x.row(free_index[std::size_t(v)]).transpose();
    };
    solve();
    // Stretch reduction (Yoshizawa, Belyaev, Seidel, "A fast and simple stretch-minimizing
    // mesh parameterization", 2004): a conformal-like map shrinks a protrusion's faces
    // exponentially with its height (a nose, a bone's shaft), so a uniform grid on the square
    // misses it. Each round divides the weights at a vertex by its linear stretch s (the
    // square root of the surface-to-square area ratio of its faces, relative to the patch's):
    // row i of sum_j W_ij / (s_i s_j) (uv_i - uv_j) = 0 is Yoshizawa's w_ij / s_j, which
    // pulls a vertex less towards stretched neighbours, so the shrunken region opens up.
    // Surface areas do not change from round to round; the square's do.
    std::vector<double> area3(stretch_rounds > 0 ? M.triangles.size() : 0);
    double total3 = 0.;
    for(std::size_t f = 0; f < area3.size(); ++f) {
      const auto& t = M.triangles[f];
      const Eigen::Vector3d &x0 = M.position[std::size_t(t[0])], &x1 = M.position[std::size_t(t[1])], &x2 = M.position[std::size_t(t[2])];
      area3[f] = 0.5 * (x1 - x0).cross(x2 - x0).norm();
      total3 += area3[f];
    }
    for(int round = 0; round < stretch_rounds; ++round) {
      std::vector<double> area2(M.triangles.size());
      double total2 = 0.;
      for(std::size_t f = 0; f < M.triangles.size(); ++f) {
        const auto& t = M.triangles[f];
        const Eigen::Vector2d a = M.uv[std::size_t(t[1])] - M.uv[std::size_t(t[0])], b = M.uv[std::size_t(t[2])] - M.uv[std::size_t(t[0])];
        area2[f] = 0.5 * (a.x() * b.y() - a.y() * b.x());
        total2 += std::max(area2[f], 0.);
      }
      if(!(total3 > 0.) || !(total2 > 0.)) break;
      // Per vertex: the mean area ratio of its faces, weighted by surface area; ratios kept
      // in [1e-4, 1e4] (a flat or flipped uv triangle counts as the largest).
      std::vector<double> sum(std::size_t(n), 0.), weight_sum(std::size_t(n), 0.);
      for(std::size_t f = 0; f < M.triangles.size(); ++f) {
        const double ratio = area2[f] > 0. ? std::min(std::max((area3[f] / total3) / (area2[f] / total2), 1e-4), 1e4) : 1e4;
        for(int c : M.triangles[f]) {
          sum[std::size_t(c)] += area3[f] * ratio;
          weight_sum[std::size_t(c)] += area3[f];
        }
      }
      for(int v = 0; v < n; ++v)
        if(weight_sum[std::size_t(v)] > 0.) scale[std::size_t(v)] /= std::sqrt(sum[std::size_t(v)] / weight_sum[std::size_t(v)]);
      solve();
    }
  }
  // Orientation in uv, exactly: the mesh's faces are counter-clockwise seen from outside and
  // so is the corner square, so a one-to-one map keeps every triangle counter-clockwise.
  M.positive.resize(M.triangles.size());
  for(std::size_t f = 0; f < M.triangles.size(); ++f) {
    const auto& t = M.triangles[f];
    auto P = [&](int c) {
      const Eigen::Vector2d& q = M.uv[std::size_t(t[std::size_t(c)])];
      return Epick_2::Point_2(q.x(), q.y());
    };
    M.positive[f] = CGAL::orientation(P(0), P(1), P(2)) == CGAL::LEFT_TURN;
    if(!M.positive[f]) ++M.flipped;
  }
  return M;
}

/// Fills the interior of grid `g` from the uv map: grid point (i, j) at uv (cu[i], cv[j])
/// (increasing coordinates from 0 to 1; g is cu.size() x cv.size()) located in a
/// counter-clockwise uv triangle (exact predicates; each triangle visits only the grid
/// points of its bounding box, so the cost is O(triangles + grid)), then interpolated
/// barycentrically in 3D. Returns the number of points no triangle contained (they take
/// the nearest triangle's closest point; 0 for a one-to-one map).
inline int sample_surface_grid(const Surface_patch_map& M, const std::vector<double>& cu, const std::vector<double>& cv,
                               Point_grid& g)
{
  using P2 = Epick_2::Point_2;
  const int Nu = int(cu.size()) - 1, Nv = int(cv.size()) - 1;
  if(Nu < 2 || Nv < 2) return 0;
  const int mu = Nu - 1;
  std::vector<int> owner(std::size_t(mu) * std::size_t(Nv - 1), -1);
  // First index whose coordinate is >= x, and last whose coordinate is <= x.
  auto first_at_least = [](const std::vector<double>& c, double x) { return int(std::lower_bound(c.begin(), c.end(), x) - c.begin()); };
  auto last_at_most = [](const std::vector<double>& c, double x) { return int(std::upper_bound(c.begin(), c.end(), x) - c.begin()) - 1; };
  auto interpolate = [&](std::size_t f, const Eigen::Vector2d& q) {
    const auto& t = M.triangles[f];
    const Eigen::Vector2d& a = M.uv[std::size_t(t[0])];
    const Eigen::Vector2d& b = M.uv[std::size_t(t[1])];
    const Eigen::Vector2d& c = M.uv[std::size_t(t[2])];
    auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) { return x.x() * y.y() - x.y() * y.x(); };
    double la = std::max(0., cross(b - q, c - q)), lb = std::max(0., cross(c - q, a - q)), lc = std::max(0., cross(a - q, b - q));
    const double s = la + lb + lc;
    if(!(s > 0.)) la = lb = lc = 1.;
    const double sum = la + lb + lc;
    return Eigen::Vector3d((la * M.position[std::size_t(t[0])] + lb * M.position[std::size_t(t[1])] +
                            lc * M.position[std::size_t(t[2])]) / sum);
  };
  for(std::size_t f = 0; f < M.triangles.size(); ++f) {
    if(!M.positive[f]) continue;
    const auto& t = M.triangles[f];
    const Eigen::Vector2d& a = M.uv[std::size_t(t[0])];
    const Eigen::Vector2d& b = M.uv[std::size_t(t[1])];
    const Eigen::Vector2d& c = M.uv[std::size_t(t[2])];
    const double u0 = std::min({a.x(), b.x(), c.x()}), u1 = std::max({a.x(), b.x(), c.x()});
    const double v0 = std::min({a.y(), b.y(), c.y()}), v1 = std::max({a.y(), b.y(), c.y()});
    // One index of slack either way; the exact test decides.
    const int i0 = std::max(1, first_at_least(cu, u0) - 1), i1 = std::min(Nu - 1, last_at_most(cu, u1) + 1);
    const int j0 = std::max(1, first_at_least(cv, v0) - 1), j1 = std::min(Nv - 1, last_at_most(cv, v1) + 1);
    if(i0 > i1 || j0 > j1) continue;
    const P2 A(a.x(), a.y()), B(b.x(), b.y()), Cc(c.x(), c.y());
    for(int j = j0; j <= j1; ++j)
      for(int i = i0; i <= i1; ++i) {
        int& o = owner[std::size_t(i - 1) + std::size_t(mu) * std::size_t(j - 1)];
        if(o >= 0) continue;
        const P2 q(cu[std::size_t(i)], cv[std::size_t(j)]);
        if(CGAL::orientation(A, B, q) == CGAL::RIGHT_TURN || CGAL::orientation(B, Cc, q) == CGAL::RIGHT_TURN ||
           CGAL::orientation(Cc, A, q) == CGAL::RIGHT_TURN)
          continue;
        o = int(f);
        g(i, j) = interpolate(f, Eigen::Vector2d(cu[std::size_t(i)], cv[std::size_t(j)]));
      }
  }
  // Points left over (only when the map folds): the closest point of the nearest triangle.
  int unlocated = 0;
  for(int j = 1; j < Nv; ++j)
    for(int i = 1; i < Nu; ++i) {
      if(owner[std::size_t(i - 1) + std::size_t(mu) * std::size_t(j - 1)] >= 0) continue;
      ++unlocated;
      const Eigen::Vector2d q(cu[std::size_t(i)], cv[std::size_t(j)]);
      double best = std::numeric_limits<double>::infinity();
      Eigen::Vector3d bp = Eigen::Vector3d::Zero();
      for(std::size_t f = 0; f < M.triangles.size(); ++f) {
        const auto& t = M.triangles[f];
        std::array<Eigen::Vector2d, 3> x{{M.uv[std::size_t(t[0])], M.uv[std::size_t(t[1])], M.uv[std::size_t(t[2])]}};
        // Closest point on the border of the triangle (the point is in no positive triangle).
        for(int e = 0; e < 3; ++e) {
          const Eigen::Vector2d& p0 = x[std::size_t(e)];
          const Eigen::Vector2d& p1 = x[std::size_t((e + 1) % 3)];
          const Eigen::Vector2d d = p1 - p0;
          const double dd = d.squaredNorm();
          const double s = dd > 0. ? std::min(1., std::max(0., (q - p0).dot(d) / dd)) : 0.;
          const double dist = (p0 + s * d - q).squaredNorm();
          if(dist < best) {
            best = dist;
            bp = (1. - s) * M.position[std::size_t(t[std::size_t(e)])] + s * M.position[std::size_t(t[std::size_t((e + 1) % 3)])];
          }
        }
      }
      g(i, j) = bp;
    }
  return unlocated;
}

/// N + 1 coordinates i / N.
inline std::vector<double> uniform_coordinates(int N)
{
  std::vector<double> c(std::size_t(std::max(N, 0)) + 1);
  for(int i = 0; i <= N; ++i) c[std::size_t(i)] = double(i) / double(N);
  return c;
}

/// The (N+1)^2 grid at (i/N, j/N).
inline int sample_surface_grid(const Surface_patch_map& M, int N, Point_grid& g)
{
  const std::vector<double> c = uniform_coordinates(N);
  return sample_surface_grid(M, c, c, g);
}

/// Checks what the sampler relies on (index ranges, arcs joining their corners), so that a
/// malformed layout is an Invalid_input_error rather than undefined behaviour.
template <class Layout>
void check_layout_for_sampling(const Layout& L)
{
  // Index ranges include removed elements, as the mesh's own property arrays do.
  const std::size_t nv = L.mesh.num_vertices(), nf = L.mesh.num_faces();
  auto fail = [](const std::string& s) { throw Invalid_input_error("invalid_layout", s); };
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    const auto& arc = L.arcs[a];
    if(arc.vertices.size() < 2 || arc.nodes[0] >= L.nodes.size() || arc.nodes[1] >= L.nodes.size())
      fail("arc " + std::to_string(a) + " is malformed");
    for(auto v : arc.vertices)
      if(std::size_t(v) >= nv) fail("arc " + std::to_string(a) + " lists a vertex that is not in the mesh");
    if(arc.vertices.front() != L.nodes[arc.nodes[0]] || arc.vertices.back() != L.nodes[arc.nodes[1]])
      fail("arc " + std::to_string(a) + " does not start and end at its nodes");
  }
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    const auto& pa = L.patches[p];
    for(int i = 0; i < 4; ++i) {
      const std::size_t a = pa.arcs[std::size_t(i)];
      const std::size_t c0 = pa.corners[std::size_t(i)], c1 = pa.corners[std::size_t((i + 1) % 4)];
      if(a >= L.arcs.size() || c0 == c1 ||
         !((L.arcs[a].nodes[0] == c0 && L.arcs[a].nodes[1] == c1) || (L.arcs[a].nodes[0] == c1 && L.arcs[a].nodes[1] == c0)))
        fail("patch " + std::to_string(p) + ": arc " + std::to_string(i) + " does not join its corners");
    }
    if(pa.kind == Layout::SURFACE && pa.faces.empty()) fail("surface patch " + std::to_string(p) + " has no faces");
    for(auto f : pa.faces)
      if(std::size_t(f) >= nf) fail("patch " + std::to_string(p) + " lists a face that is not in the mesh");
  }
}

} // namespace internal

/*!
 * \ingroup PkgPolycubeIGARef
 * Samples every patch of `layout` on an (N+1) x (N+1) grid (see the file comment for the
 * method and the grid convention). The layout should pass `validate()`; only what the
 * sampler needs to be memory-safe is checked here (Invalid_input_error `invalid_layout`).
 * Cost: one sparse Cholesky factorization per surface patch, one shared by all interior
 * patches, and O(faces + grid points) point location.
 */
template <class Point_3>
Patch_grids sample_layout_patches(const Polycube_layout<Point_3>& layout, const Patch_sampling_options& o)
{
  using Layout = Polycube_layout<Point_3>;
  const int N = o.grid_segments;
  if(N < 1) throw Invalid_input_error("invalid_grid", "grid_resolution must be at least 1, got " + std::to_string(N));
  internal::check_layout_for_sampling(layout);
  Patch_grids r;
  r.segments = N;
  // Arcs: positions, cumulative lengths, N+1 samples; computed once, shared by both sides.
  std::vector<std::vector<double>> cum(layout.arcs.size());
  r.arc_samples.resize(layout.arcs.size());
  for(std::size_t a = 0; a < layout.arcs.size(); ++a) {
    std::vector<Eigen::Vector3d> pts;
    pts.reserve(layout.arcs[a].vertices.size());
    for(auto v : layout.arcs[a].vertices) pts.push_back(internal::to_eigen_point(layout.mesh.point(v)));
    cum[a] = internal::cumulative_lengths(pts);
    r.arc_samples[a] = internal::sample_polyline(pts, cum[a], N);
    if(o.sharp_boundary_turn > 0. && internal::on_mesh_border(layout.mesh, layout.arcs[a].vertices))
      internal::round_sharp_turns(pts, cum[a], o.sharp_boundary_turn, r.arc_samples[a]);
  }
  r.grids.assign(layout.patches.size(), Point_grid(N + 1, N + 1));
  r.flipped_triangles.assign(layout.patches.size(), 0);
  r.unlocated_points.assign(layout.patches.size(), 0);
  std::vector<int> local_of(layout.mesh.num_vertices(), -1);
  internal::Interior_grid_filler interior(N, o.smooth_interior_patches);
  for(std::size_t p = 0; p < layout.patches.size(); ++p) {
    const auto& pa = layout.patches[p];
    Point_grid& g = r.grids[p];
    internal::set_patch_border(g, N, layout, pa, r.arc_samples);
    if(N < 2) continue;
    if(pa.kind == Layout::SURFACE) {
      const internal::Surface_patch_map M = internal::map_surface_patch(layout, p, cum, local_of, o.stretch_rounds);
      r.flipped_triangles[p] = M.flipped;
      r.unlocated_points[p] = internal::sample_surface_grid(M, N, g);
    } else {
      interior.fill(g);
    }
    // The border rows stay the arc samples, bit for bit.
    internal::set_patch_border(g, N, layout, pa, r.arc_samples);
  }
  return r;
}

/*!
 * Named-parameter form: `grid_resolution` (N, default 16) and `smooth_interior_patches`
 * (default true) override the fields of `base`.
 * Example: `sample_layout_patches(layout, parameters::grid_resolution(32))`.
 */
template <class Point_3, class NamedParameters = parameters::Default_named_parameters>
Patch_grids sample_layout_patches(const Polycube_layout<Point_3>& layout,
                                  const NamedParameters& np = parameters::default_values(),
                                  Patch_sampling_options base = Patch_sampling_options())
{
  base.grid_segments = int(option(np, internal_np::grid_resolution, base.grid_segments));
  base.smooth_interior_patches = bool(option(np, internal_np::smooth_interior_patches, base.smooth_interior_patches));
  base.stretch_rounds = int(option(np, internal_np::stretch_rounds, base.stretch_rounds));
  if(base.stretch_rounds < 0) throw Invalid_input_error("invalid_parameter", "stretch_rounds must not be negative");
  base.sharp_boundary_turn = option(np, internal_np::sharp_boundary_turn, base.sharp_boundary_turn);
  internal::check_sharp_boundary_turn(base.sharp_boundary_turn);
  return sample_layout_patches(layout, base);
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_PATCH_SAMPLING_H
