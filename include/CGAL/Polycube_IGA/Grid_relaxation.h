// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Relaxation of the surface grids as one quad mesh on the input surface.
//
// Why: the per-patch maps of Patch_sampling.h are only as good as the layout. Where the
// cuboid decomposition leaves a sliver patch, or a corner of nearly 180 degrees, a patch's
// map squeezes its grid lines together and some cells turn over; the faces fitted to those
// grids fold and no volume built on them is valid (eight.off, 3holes.obj). Reference
// chapter 3 answers with a global parameterization whose layout nodes move to lower its
// distortion. This is the grid-level counterpart: the grids of all SURFACE patches, glued
// along their shared arc samples, form one quad mesh (regular except at the layout's nodes);
// every point not on an input boundary loop moves towards the mean of its edge neighbours
// and is projected back onto the mesh (the closest point), arc samples and nodes included,
// so arcs slide sideways and nodes move until neighbouring cells have similar sizes; a point
// on a crease of the mesh slides along it instead, and one at a corner of creases stays. Each
// grid keeps its N x N structure and the grids keep sharing their borders bit for bit.
//
// A move is refused when the closest point's face faces against the point's current face,
// which would put it on the other side of a thin wall (a blade). Points on arcs of CAP
// patches stay where they are: they must stay on their boundary loop. The CAP and
// INTERFACE grids are then rebuilt from their new borders (Coons + harmonic, as sampled).
// Gauss-Seidel sweeps in index order: deterministic.

#ifndef CGAL_POLYCUBE_IGA_GRID_RELAXATION_H
#define CGAL_POLYCUBE_IGA_GRID_RELAXATION_H

#include <CGAL/Polycube_IGA/Layout_padding.h>
#include <CGAL/Polycube_IGA/Patch_sampling.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/internal/feature_curves.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Options of relax_surface_grids().
struct Grid_relaxation_options
{
  int maximum_sweeps = 100;  ///< Gauss-Seidel sweeps at most; 0 leaves the grids alone
  double step = 0.8;         ///< fraction of the way to the neighbours' mean per sweep
  /// Stop when no point moved by more than this fraction of the mean grid edge length.
  double tolerance = 1e-3;
  bool move_nodes = true;    ///< layout nodes move too (not those on input boundary loops)

  /// Options that leave the grids as they are.
  static Grid_relaxation_options none()
  {
    Grid_relaxation_options o;
    o.maximum_sweeps = 0;
    return o;
  }
};

/// What relax_surface_grids() did.
struct Grid_relaxation_result
{
  int points = 0;          ///< distinct points of the surface quad mesh
  int fixed_points = 0;    ///< of which kept in place (boundary loops, nodes if asked)
  int sweeps = 0;
  int refused_moves = 0;   ///< projections that would have crossed to the other side of a wall
  double last_move = 0.;   ///< largest move in the last sweep / mean edge length
};

namespace internal {

/// Distinct points of the SURFACE grids of a layout: node n is point n, then the inner
/// samples of every arc a SURFACE patch uses, then the inner points of every SURFACE grid.
class Surface_quad_mesh
{
public:
  template <class Layout>
  Surface_quad_mesh(const Layout& L, int N) : N_(N)
  {
    const std::size_t na = L.arcs.size(), np = L.patches.size();
    arc_base_.assign(na, -1);
    patch_base_.assign(np, -1);
    int next = int(L.nodes.size());
    for(std::size_t p = 0; p < np; ++p) {
      if(L.patches[p].kind != Layout::SURFACE) continue;
      for(std::size_t a : L.patches[p].arcs)
        if(arc_base_[a] < 0) {
          arc_base_[a] = next;
          next += N - 1;
        }
    }
    for(std::size_t p = 0; p < np; ++p)
      if(L.patches[p].kind == Layout::SURFACE) {
        patch_base_[p] = next;
        next += (N - 1) * (N - 1);
      }
    size_ = next;
  }

  int size() const { return size_; }
  int arc_point(std::size_t a, int k) const { return arc_base_[a] + k - 1; } ///< 0 < k < N
  bool arc_used(std::size_t a) const { return arc_base_[a] >= 0; }

  /// Point of grid (i, j) of SURFACE patch p.
  template <class Layout>
  int grid_point(const Layout& L, std::size_t p, int i, int j) const
  {
    const int N = N_;
    const auto& pa = L.patches[p];
    if(i > 0 && i < N && j > 0 && j < N) return patch_base_[p] + (i - 1) + (N - 1) * (j - 1);
    // Border: side s, k samples from corner s (inverse of border_index()).
    int s, k;
    if(j == 0) { s = 0; k = i; }
    else if(i == N) { s = 1; k = j; }
    else if(j == N) { s = 2; k = N - i; }
    else { s = 3; k = N - j; }
    if(k == 0) return int(pa.corners[std::size_t(s)]);
    if(k == N) return int(pa.corners[std::size_t((s + 1) % 4)]);
    const std::size_t a = pa.arcs[std::size_t(s)];
    const bool forward = L.arcs[a].nodes[0] == pa.corners[std::size_t(s)];
    return arc_point(a, forward ? k : N - k);
  }

private:
  int N_, size_ = 0;
  std::vector<int> arc_base_, patch_base_;
};

} // namespace internal

/*!
 * \ingroup PkgPolycubeIGARef
 * Relaxes the SURFACE grids of `G` (the grids of `L`, e.g. from sample_layout_patches() or
 * split_long_cuboids()) as one quad mesh on `L.mesh` (see the file comment), then rebuilds
 * the CAP and INTERFACE grids from their borders (`smooth_interior_patches` as in
 * Patch_sampling_options). The layout itself is not changed: from here on the geometry of
 * its arcs is in `G`.
 */
template <class Point_3>
Grid_relaxation_result relax_surface_grids(const Polycube_layout<Point_3>& L, Patch_grids& G, const Grid_relaxation_options& o,
                                           bool smooth_interior_patches = true)
{
  using Layout = Polycube_layout<Point_3>;
  Grid_relaxation_result r;
  const int N = G.segments;
  if(o.maximum_sweeps <= 0 || N < 2 || G.grids.size() != L.patches.size()) return r;
  const internal::Surface_quad_mesh Q(L, N);
  const int n = Q.size();
  r.points = n;
  const std::size_t sn = static_cast<std::size_t>(n);
  // Positions and neighbours (grid edges; each edge once per side of an arc, deduplicated).
  std::vector<Eigen::Vector3d> x(sn, Eigen::Vector3d::Zero());
  std::vector<bool> used(sn, false), fixed(sn, false);
  std::vector<std::vector<int>> nb(sn);
  double edge_sum = 0.;
  std::size_t edges = 0;
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    if(L.patches[p].kind != Layout::SURFACE) continue;
    const Point_grid& g = G.grids[p];
    for(int j = 0; j <= N; ++j)
      for(int i = 0; i <= N; ++i) {
        const int a = Q.grid_point(L, p, i, j);
        x[std::size_t(a)] = g(i, j);
        used[std::size_t(a)] = true;
        for(int d = 0; d < 2; ++d) {
          const int ii = i + (d == 0), jj = j + (d == 1);
          if(ii > N || jj > N) continue;
          const int b = Q.grid_point(L, p, ii, jj);
          nb[std::size_t(a)].push_back(b);
          nb[std::size_t(b)].push_back(a);
          edge_sum += (g(ii, jj) - g(i, j)).norm();
          ++edges;
        }
      }
  }
  for(auto& v : nb) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  // Points that stay: the arcs of CAP patches (input boundary loops) and their nodes.
  for(const auto& pa : L.patches) {
    if(pa.kind != Layout::CAP) continue;
    for(std::size_t c : pa.corners) fixed[c] = true;
    for(std::size_t a : pa.arcs)
      if(Q.arc_used(a))
        for(int k = 1; k < N; ++k) fixed[std::size_t(Q.arc_point(a, k))] = true;
  }
  if(!o.move_nodes)
    for(std::size_t v = 0; v < L.nodes.size(); ++v) fixed[v] = true;
  const double mean_edge = edges > 0 ? edge_sum / double(edges) : 0.;
  if(!(mean_edge > 0.)) return r;

  using Probe = internal::Mesh_probe<typename Layout::Mesh>;
  const Probe probe(L.mesh);
  std::vector<typename Probe::Surface_point> at(sn);
  for(int v = 0; v < n; ++v)
    if(used[std::size_t(v)] && !fixed[std::size_t(v)]) at[std::size_t(v)] = probe.closest_point(x[std::size_t(v)]);
  // A point on a crease (a sharp edge, 45 degrees as the cuboid stage's) slides along it, and
  // one at a corner of creases stays: moved freely, a node on a hole's rim went down the
  // hole's wall, the patch beside it wrapped round the rim and its fitted face folded there,
  // and a box's corner nodes moved in from the corners (the cube with crossing holes of the
  // unseen corpus: 2 patches uncertified, its boundary 1.61% of the diagonal off).
  const internal::Crease_network<typename Layout::Mesh> creases(L.mesh, 45.);
  std::vector<std::size_t> crease_edge(sn, 0);
  std::vector<bool> on_crease(sn, false);
  for(int v = 0; v < n; ++v) {
    if(!used[std::size_t(v)] || fixed[std::size_t(v)]) continue;
    const internal::Crease_position c = creases.locate(at[std::size_t(v)].point, std::size_t(at[std::size_t(v)].hint.second), 1e-7 * mean_edge);
    if(c.kind == internal::Crease_position::at_corner) fixed[std::size_t(v)] = true;
    if(c.kind == internal::Crease_position::on_edge) on_crease[std::size_t(v)] = true, crease_edge[std::size_t(v)] = c.edge;
  }
  for(int v = 0; v < n; ++v) r.fixed_points += int(used[std::size_t(v)] && fixed[std::size_t(v)]);
  for(r.sweeps = 0; r.sweeps < o.maximum_sweeps;) {
    ++r.sweeps;
    double largest = 0.;
    for(int v = 0; v < n; ++v) {
      if(!used[std::size_t(v)] || fixed[std::size_t(v)] || nb[std::size_t(v)].empty()) continue;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for(int w : nb[std::size_t(v)]) mean += x[std::size_t(w)];
      mean /= double(nb[std::size_t(v)].size());
      const Eigen::Vector3d target = x[std::size_t(v)] + o.step * (mean - x[std::size_t(v)]);
      if(on_crease[std::size_t(v)]) {
        const Eigen::Vector3d y = creases.slide(target, &crease_edge[std::size_t(v)]);
        largest = std::max(largest, (y - x[std::size_t(v)]).norm());
        x[std::size_t(v)] = y;
        continue;
      }
      const auto q = probe.closest_point(target, at[std::size_t(v)]);
      if(q.normal.dot(at[std::size_t(v)].normal) <= 0.) {
        ++r.refused_moves;
        continue;
      }
      largest = std::max(largest, (q.point - x[std::size_t(v)]).norm());
      x[std::size_t(v)] = q.point;
      at[std::size_t(v)] = q;
    }
    r.last_move = largest / mean_edge;
    if(r.last_move < o.tolerance) break;
  }
  // Write back: SURFACE grids, the arc samples they use, then the other grids' borders.
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    if(L.patches[p].kind != Layout::SURFACE) continue;
    Point_grid& g = G.grids[p];
    for(int j = 0; j <= N; ++j)
      for(int i = 0; i <= N; ++i) g(i, j) = x[std::size_t(Q.grid_point(L, p, i, j))];
  }
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    auto& s = G.arc_samples[a];
    if(L.arcs[a].inside) { // a straight segment between its (relaxed) nodes, sampled as at first
      // An interior node is on no surface grid, so it stays.
      const std::size_t n0 = L.arcs[a].nodes[0], n1 = L.arcs[a].nodes[1];
      const std::vector<Eigen::Vector3d> ends{used[n0] ? x[n0] : s.front(), used[n1] ? x[n1] : s.back()};
      s = internal::sample_polyline(ends, internal::cumulative_lengths(ends), N);
      continue;
    }
    if(!Q.arc_used(a)) continue;
    s.front() = x[L.arcs[a].nodes[0]];
    s.back() = x[L.arcs[a].nodes[1]];
    for(int k = 1; k < N; ++k) s[std::size_t(k)] = x[std::size_t(Q.arc_point(a, k))];
  }
  internal::Interior_grid_filler interior(N, smooth_interior_patches);
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    if(L.patches[p].kind == Layout::SURFACE) continue;
    internal::set_patch_border(G.grids[p], N, L, L.patches[p], G.arc_samples);
    interior.fill(G.grids[p]);
  }
  return r;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_GRID_RELAXATION_H
