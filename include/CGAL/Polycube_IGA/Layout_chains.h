// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Long tube-like cuboids split into chains of cube-like ones.
//
// Why: a cuboid whose four sides along one axis all lie on the surface is a tube (the arms
// of a pants, §2.2.2, and the pieces of a torus ring or a cylinder chain). A long bent tube
// is one trivariate patch whose interior comes from Coons interpolation between its two
// ends (§4.1): along a strong bend the blend folds and det J changes sign. The torus showed
// it (a ring of 3 long cuboids is invalid, of 6 cube-like ones valid); the same split helps
// every tube. Splitting a cuboid along its own axis touches nothing else (its four long
// sides are surface patches of its own, their long arcs belong to no other patch), so it is
// done here on the layout and its grids, without touching the mesh:
//
//   * each long arc is resampled at k N + 1 points by arc length (the k pieces then have N
//     segments each and the split nodes sit at fractions 1/k, ..., (k-1)/k of the arc);
//   * each long side patch is sampled by its own map to the square (Patch_sampling.h: the
//     border is placed by arc length, so fraction l/k of both long arcs lies on the line
//     at parameter l/k) on a (k N + 1) x (N + 1) grid: its blocks are the k sub-patches, its
//     lines at l/k the cross arcs;
//   * the cross-section at l/k is a new interior patch spanned by the four cross arcs
//     (Coons + harmonic grid, as for every interior patch).
//
// k = round(length / (perimeter / 4)): the mean long-arc length over the mean side of the
// two end faces; a tube whose long arcs turn by more than 60 degrees between their ends gets
// at least ceil(turn / 60 degrees) pieces (a third of a ring around a thick pipe is short but
// folds, like the torus ring of 3); both capped by `maximum_pieces`. The result is a Polycube_layout (new nodes
// reuse a vertex of their arc as a placeholder; sub-patches carry no faces) with its
// Patch_grids, so layout_volume() and pad_layout() use it like any other.

#ifndef CGAL_POLYCUBE_IGA_LAYOUT_CHAINS_H
#define CGAL_POLYCUBE_IGA_LAYOUT_CHAINS_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Layout_padding.h>
#include <CGAL/Polycube_IGA/Patch_sampling.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Options of split_long_cuboids().
struct Cuboid_chain_options
{
  /// A tube is split when its length exceeds this many times the side of its cross-section
  /// (into round(length / width) pieces); 0 splits nothing.
  double maximum_aspect = 2.;
  /// A tube whose axis turns by more than this angle (radians) between its two ends is split
  /// into pieces turning by at most this much each; 0 splits nothing for its bend.
  double maximum_bend = 1.0471975511965976; // 60 degrees
  int maximum_pieces = 12;
};

namespace internal {

/// Angle (radians) between the directions of a polyline's first and last segments: how much
/// an arc turns between its ends.
inline double end_tangent_angle(const std::vector<Eigen::Vector3d>& pts)
{
  if(pts.size() < 3) return 0.;
  const Eigen::Vector3d a = end_tangent(pts, true), b = -end_tangent(pts, false);
  if(a.isZero() || b.isZero()) return 0.;
  return std::acos(std::max(-1., std::min(1., a.dot(b))));
}

} // namespace internal

/// A layout whose long tubes are chains, with its grids.
template <class Point_3>
struct Chained_layout
{
  Polycube_layout<Point_3> layout;
  Patch_grids samples;
  std::vector<long> cuboid_of; ///< per cuboid: the cuboid of the input layout it is a piece of
  std::vector<long> patch_of;  ///< per patch: the input patch it is (a piece of), -1 for new cross-sections
  std::vector<int> pieces;     ///< per input cuboid: number of pieces (1: unchanged)
};

/*!
 * \ingroup PkgPolycubeIGARef
 * Splits every long tube of `layout` (a cuboid whose four sides along an axis are SURFACE
 * patches, longer than `o.maximum_aspect` times its width) into a chain of cube-like
 * cuboids, as described in this header, given the layout's grids `samples`
 * (sample_layout_patches() with options `so`). Deterministic.
 */
template <class Point_3>
Chained_layout<Point_3> split_long_cuboids(const Polycube_layout<Point_3>& layout, const Patch_grids& samples,
                                           const Patch_sampling_options& so, const Cuboid_chain_options& o = Cuboid_chain_options())
{
  using Layout = Polycube_layout<Point_3>;
  const int N = samples.segments;
  const std::size_t nc = layout.cuboids.size(), np = layout.patches.size(), na = layout.arcs.size();
  if(N < 2 || samples.grids.size() != np || samples.arc_samples.size() != na)
    throw Invalid_input_error("invalid_grid", "splitting cuboids needs the layout's patch grids with at least 2 segments");
  std::vector<double> arc_length(na);
  for(std::size_t a = 0; a < na; ++a) arc_length[a] = internal::cumulative_lengths(samples.arc_samples[a]).back();
  // The arc of patch p joining nodes x and y (npos if none).
  const std::size_t none = std::size_t(-1);
  auto arc_between = [&](std::size_t p, std::size_t x, std::size_t y) {
    for(std::size_t a : layout.patches[p].arcs) {
      const auto& n = layout.arcs[a].nodes;
      if((n[0] == x && n[1] == y) || (n[0] == y && n[1] == x)) return a;
    }
    return none;
  };
  auto is_surface = [&](std::size_t p) { return layout.patches[p].kind == Layout::SURFACE; };
  // The long arc of cuboid corner x (bit d clear) along axis d: in the side of axis (d+1)%3
  // at x's bit, which holds both of its nodes.
  auto long_arc = [&](const typename Layout::Cuboid& cu, int d, int x) {
    const int e = (d + 1) % 3;
    return arc_between(cu.patches[std::size_t(2 * e + ((x >> e) & 1))], cu.nodes[std::size_t(x)], cu.nodes[std::size_t(x | (1 << d))]);
  };
  std::vector<int> arc_users(na, 0);
  for(const auto& pa : layout.patches)
    for(std::size_t a : pa.arcs) ++arc_users[a];

  // Per cuboid: axis and number of pieces.
  std::vector<int> axis(nc, -1), pieces(nc, 1);
  for(std::size_t c = 0; c < nc && (o.maximum_aspect > 0. || o.maximum_bend > 0.); ++c) {
    const auto& cu = layout.cuboids[c];
    double best = 0., bend = 0.;
    for(int d = 0; d < 3; ++d) {
      bool tube = true;
      for(int s = 1; s <= 6; ++s)
        if((s - 1) / 2 != d) tube = tube && is_surface(cu.patches[std::size_t(s - 1)]);
      if(!tube) continue;
      double along = 0., across = 0., turn = 0.;
      bool ok = true;
      for(int x = 0; x < 8; ++x) {
        if(x & (1 << d)) continue;
        const std::size_t a = long_arc(cu, d, x);
        // A long arc must belong to the tube's two sides only, or the split would not conform.
        if(a == none || arc_users[a] != 2) { ok = false; break; }
        along += arc_length[a] / 4.;
        turn += internal::end_tangent_angle(samples.arc_samples[a]) / 4.;
      }
      for(int end = 0; end < 2 && ok; ++end)
        for(std::size_t a : layout.patches[cu.patches[std::size_t(2 * d + end)]].arcs) across += arc_length[a] / 8.;
      if(!ok || !(across > 0.)) continue;
      const double ratio = along / across;
      if(axis[c] < 0 || ratio > best) { best = ratio; bend = turn; axis[c] = d; }
    }
    if(axis[c] >= 0 && o.maximum_aspect > 0. && best > o.maximum_aspect)
      pieces[c] = std::max(2, std::min(o.maximum_pieces, int(std::lround(best))));
    // A strongly bent tube (a third of a ring around a thick pipe) folds even when short.
    if(axis[c] >= 0 && o.maximum_bend > 0. && bend > o.maximum_bend)
      pieces[c] = std::max(pieces[c], std::min(o.maximum_pieces, int(std::ceil(bend / o.maximum_bend - 1e-9))));
  }

  Chained_layout<Point_3> r;
  r.pieces = pieces;
  Layout& L = r.layout;
  Patch_grids& G = r.samples;
  L.layout_class = layout.layout_class;
  L.genus = layout.genus;
  L.boundary_loops = layout.boundary_loops;
  L.number_of_pants = layout.number_of_pants;
  L.mesh = layout.mesh;
  L.nodes = layout.nodes;
  G.segments = N;
  // Arcs and patches are rebuilt: those of split tubes are replaced, the others copied.
  std::vector<std::size_t> new_arc(na, none), new_patch(np, none);
  auto add_arc = [&](std::size_t n0, std::size_t n1, std::vector<Eigen::Vector3d> pts) {
    typename Layout::Arc a;
    a.nodes = {{n0, n1}};
    L.arcs.push_back(a);
    G.arc_samples.push_back(std::move(pts));
    return L.arcs.size() - 1;
  };
  auto add_patch = [&](typename Layout::Patch pa, Point_grid g, long from, int flipped) {
    L.patches.push_back(std::move(pa));
    G.grids.push_back(std::move(g));
    G.flipped_triangles.push_back(flipped);
    G.unlocated_points.push_back(0);
    r.patch_of.push_back(from);
    return L.patches.size() - 1;
  };

  // Long arcs of split cuboids (to be resampled) are found per cuboid below; every other arc
  // is copied when first needed.
  auto copied_arc = [&](std::size_t a) {
    if(new_arc[a] == none) {
      new_arc[a] = add_arc(layout.arcs[a].nodes[0], layout.arcs[a].nodes[1], samples.arc_samples[a]);
      L.arcs[new_arc[a]].inside = layout.arcs[a].inside; // stays straight between its nodes
    }
    return new_arc[a];
  };
  auto copied_patch = [&](std::size_t p) {
    if(new_patch[p] == none) {
      typename Layout::Patch pa = layout.patches[p];
      for(auto& a : pa.arcs) a = copied_arc(a);
      new_patch[p] = add_patch(pa, samples.grids[p], long(p), p < samples.flipped_triangles.size() ? samples.flipped_triangles[p] : 0);
    }
    return new_patch[p];
  };

  std::vector<std::vector<double>> cum(na);
  for(std::size_t a = 0; a < na; ++a) {
    std::vector<Eigen::Vector3d> pts;
    for(auto v : layout.arcs[a].vertices) pts.push_back(internal::to_eigen_point(layout.mesh.point(v)));
    cum[a] = internal::cumulative_lengths(pts);
  }
  std::vector<int> local_of(layout.mesh.num_vertices(), -1);
  internal::Interior_grid_filler interior(N, so.smooth_interior_patches);

  for(std::size_t c = 0; c < nc; ++c) {
    const auto& cu = layout.cuboids[c];
    if(pieces[c] < 2) {
      typename Layout::Cuboid out = cu;
      for(auto& p : out.patches) p = copied_patch(p);
      L.cuboids.push_back(out);
      r.cuboid_of.push_back(long(c));
      continue;
    }
    const int d = axis[c], k = pieces[c], K = k * N;
    // Long edge of corner x (bit d cleared): its node at level l = 0..k.
    std::array<std::vector<std::size_t>, 8> level_node;
    std::array<std::vector<Eigen::Vector3d>, 8> fine; // the long arc at K + 1 samples, from level 0
    for(int x = 0; x < 8; ++x) {
      if(x & (1 << d)) continue;
      const std::size_t n0 = cu.nodes[std::size_t(x)], n1 = cu.nodes[std::size_t(x | (1 << d))];
      const std::size_t a = long_arc(cu, d, x);
      const auto& arc = layout.arcs[a];
      std::vector<Eigen::Vector3d> pts;
      for(auto v : arc.vertices) pts.push_back(internal::to_eigen_point(layout.mesh.point(v)));
      // From the arc's first node; the ends stay the nodes' own samples, bit for bit.
      std::vector<Eigen::Vector3d> f = internal::sample_polyline(pts, cum[a], K);
      f.front() = samples.arc_samples[a].front();
      f.back() = samples.arc_samples[a].back();
      if(arc.nodes[0] != n0) std::reverse(f.begin(), f.end());
      fine[std::size_t(x)] = std::move(f);
      auto& ln = level_node[std::size_t(x)];
      ln.push_back(n0);
      for(int l = 1; l < k; ++l) {
        // Placeholder vertex: the arc's vertex nearest in arc length.
        const double target = cum[a].back() * (arc.nodes[0] == n0 ? double(l) / k : 1. - double(l) / k);
        const std::size_t i = std::size_t(std::lower_bound(cum[a].begin(), cum[a].end(), target) - cum[a].begin());
        L.nodes.push_back(arc.vertices[std::min(i, arc.vertices.size() - 1)]);
        ln.push_back(L.nodes.size() - 1);
      }
      ln.push_back(n1);
    }
    // Long sub-arcs, per edge and piece.
    std::array<std::vector<std::size_t>, 8> sub_arc;
    for(int x = 0; x < 8; ++x) {
      if(x & (1 << d)) continue;
      for(int m = 0; m < k; ++m) {
        const auto& f = fine[std::size_t(x)];
        std::vector<Eigen::Vector3d> pts(f.begin() + m * N, f.begin() + (m + 1) * N + 1);
        sub_arc[std::size_t(x)].push_back(add_arc(level_node[std::size_t(x)][std::size_t(m)],
                                                  level_node[std::size_t(x)][std::size_t(m + 1)], std::move(pts)));
      }
    }
    // Side patches: fine grid, cross arcs, sub-patches.
    std::array<std::vector<std::size_t>, 6> sub_patch;            // per side, per piece
    std::array<std::vector<std::size_t>, 6> cross;                // per side, per level 1..k-1 (index l-1)
    std::array<std::array<int, 2>, 6> cross_ends{};               // per side: edges (x) the cross arcs run from, to
    for(int s = 1; s <= 6; ++s) {
      if((s - 1) / 2 == d) continue;
      const std::size_t p = cu.patches[std::size_t(s - 1)];
      const auto& pa = layout.patches[p];
      std::array<int, 4> pos{}; // corner -> position in the cuboid
      for(int q = 0; q < 4; ++q)
        pos[std::size_t(q)] = int(std::find(cu.nodes.begin(), cu.nodes.end(), pa.corners[std::size_t(q)]) - cu.nodes.begin());
      auto level = [&](int q) { return (pos[std::size_t(q)] >> d) & 1; };
      auto edge = [&](int q) { return pos[std::size_t(q)] & ~(1 << d); };
      const bool u_long = level(0) != level(1);       // square u runs along the tube
      const bool increasing = level(0) == 0;          // ... from level 0 at u (or v) = 0
      const int nu = u_long ? K : N, nv = u_long ? N : K;
      std::vector<double> cu_coord = internal::uniform_coordinates(nu), cv_coord = internal::uniform_coordinates(nv);
      Point_grid g(nu + 1, nv + 1);
      // Border: the long sides from the fine arcs, the end sides from the layout's samples.
      for(int i = 0; i < 4; ++i) {
        const int q0 = i, q1 = (i + 1) % 4;
        const bool is_long = level(q0) != level(q1);
        const int n = (i % 2 == 0) ? nu : nv; // sides 0, 2 run along u
        for(int t = 0; t <= n; ++t) {
          Eigen::Vector3d pt;
          if(is_long) {
            const int l = level(q0) == 0 ? t : n - t; // fine index from level 0
            pt = fine[std::size_t(edge(q0))][std::size_t(l)];
          } else {
            const std::size_t a = pa.arcs[std::size_t(i)];
            const bool fwd = layout.arcs[a].nodes[0] == pa.corners[std::size_t(q0)];
            pt = samples.arc_samples[a][std::size_t(fwd ? t : N - t)];
          }
          switch(i) {
          case 0: g(t, 0) = pt; break;
          case 1: g(nu, t) = pt; break;
          case 2: g(nu - t, nv) = pt; break;
          default: g(0, nv - t) = pt; break;
          }
        }
      }
      const internal::Surface_patch_map M = internal::map_surface_patch(layout, p, cum, local_of, so.stretch_rounds);
      internal::sample_surface_grid(M, cu_coord, cv_coord, g);
      // Fine index along the tube -> grid index along u (or v).
      auto along = [&](int l) { return increasing ? l : K - l; };
      auto at = [&](int l, int t) -> const Eigen::Vector3d& { return u_long ? g(along(l), t) : g(t, along(l)); };
      // Cross arcs at levels 1..k-1, running like the level-0 end side (corner i -> i+1).
      int i0 = 0;
      while(!(level(i0) == 0 && level((i0 + 1) % 4) == 0)) ++i0;
      const int qa = i0, qb = (i0 + 1) % 4;
      cross_ends[std::size_t(s - 1)] = {{edge(qa), edge(qb)}};
      // Index t of corner qa / qb across the tube (0 or N).
      auto across_index = [&](int q) { return u_long ? (q == 0 || q == 1 ? 0 : N) : (q == 0 || q == 3 ? 0 : N); };
      const int ta = across_index(qa), tb = across_index(qb);
      for(int l = 1; l < k; ++l) {
        std::vector<Eigen::Vector3d> pts(std::size_t(N + 1));
        for(int t = 0; t <= N; ++t) pts[std::size_t(t)] = at(l * N, ta + (tb - ta) / N * t);
        pts.front() = fine[std::size_t(edge(qa))][std::size_t(l * N)];
        pts.back() = fine[std::size_t(edge(qb))][std::size_t(l * N)];
        cross[std::size_t(s - 1)].push_back(add_arc(level_node[std::size_t(edge(qa))][std::size_t(l)],
                                                    level_node[std::size_t(edge(qb))][std::size_t(l)], std::move(pts)));
      }
      // Sub-patches: corners and arcs follow the patch's, moved to levels m and m+1.
      for(int m = 0; m < k; ++m) {
        typename Layout::Patch sp;
        sp.kind = Layout::SURFACE;
        for(int q = 0; q < 4; ++q) sp.corners[std::size_t(q)] = level_node[std::size_t(edge(q))][std::size_t(m + level(q))];
        for(int i = 0; i < 4; ++i) {
          const int q0 = i, q1 = (i + 1) % 4;
          if(level(q0) != level(q1)) sp.arcs[std::size_t(i)] = sub_arc[std::size_t(edge(q0))][std::size_t(m)];
          else {
            const int l = m + level(q0);
            sp.arcs[std::size_t(i)] = (l == 0 || l == k) ? copied_arc(pa.arcs[std::size_t(i)]) : cross[std::size_t(s - 1)][std::size_t(l - 1)];
          }
        }
        Point_grid sg(N + 1, N + 1);
        for(int j = 0; j <= N; ++j)
          for(int i = 0; i <= N; ++i) {
            // (i, j) of the sub-square; the fine grid's index along the tube is offset.
            const int lo = increasing ? m * N : (k - 1 - m) * N;
            sg(i, j) = u_long ? g(lo + i, j) : g(i, lo + j);
          }
        // The border rows stay the arcs' samples, bit for bit.
        internal::set_patch_border(sg, N, L, sp, G.arc_samples);
        const int flipped = p < samples.flipped_triangles.size() ? samples.flipped_triangles[p] : 0;
        sub_patch[std::size_t(s - 1)].push_back(add_patch(sp, std::move(sg), long(p), m == 0 ? flipped : 0));
      }
    }
    // Cross-sections at levels 1..k-1: corners on the four long edges in cyclic order.
    const int a1 = (d + 1) % 3, a2 = (d + 2) % 3;
    const std::array<int, 4> ring{{0, 1 << a1, (1 << a1) | (1 << a2), 1 << a2}};
    std::vector<std::size_t> section(std::size_t(k + 1), none);
    for(int l = 1; l < k; ++l) {
      typename Layout::Patch sp;
      sp.kind = Layout::INTERFACE;
      for(int q = 0; q < 4; ++q) {
        const int x = ring[std::size_t(q)], y = ring[std::size_t((q + 1) % 4)];
        sp.corners[std::size_t(q)] = level_node[std::size_t(x)][std::size_t(l)];
        // The side holding edges x and y: the axis where they agree (other than d), at that bit.
        const int t = ((x ^ y) == (1 << a1)) ? a2 : a1;
        sp.arcs[std::size_t(q)] = cross[std::size_t(2 * t + ((x >> t) & 1))][std::size_t(l - 1)];
      }
      Point_grid g(N + 1, N + 1);
      internal::set_patch_border(g, N, L, sp, G.arc_samples);
      interior.fill(g);
      section[std::size_t(l)] = add_patch(sp, std::move(g), -1, 0);
    }
    for(int m = 0; m < k; ++m) {
      typename Layout::Cuboid piece = cu;
      for(int y = 0; y < 8; ++y)
        piece.nodes[std::size_t(y)] = level_node[std::size_t(y & ~(1 << d))][std::size_t(m + ((y >> d) & 1))];
      for(int s = 1; s <= 6; ++s) {
        if((s - 1) / 2 != d) { piece.patches[std::size_t(s - 1)] = sub_patch[std::size_t(s - 1)][std::size_t(m)]; continue; }
        const int l = (s - 1) % 2 == 0 ? m : m + 1;
        piece.patches[std::size_t(s - 1)] = (l == 0 || l == k) ? copied_patch(cu.patches[std::size_t(s - 1)]) : section[std::size_t(l)];
      }
      L.cuboids.push_back(piece);
      r.cuboid_of.push_back(long(c));
    }
  }
  return r;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_LAYOUT_CHAINS_H
