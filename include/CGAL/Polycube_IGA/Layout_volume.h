// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The first end-to-end pipeline: Polycube_layout -> patch grids (Patch_sampling.h) ->
// one trivariate B-spline per cuboid by the §4.1 recipe (edge curves, faces fitted with
// their edges fixed, Coons + harmonic interior, as fit_bspline_volume() does per cuboid) ->
// Multipatch_volume with the layout's interfaces declared, plus its quality (Quality.h) and
// its fidelity to the mesh (Boundary_distance.h). By default the curves and faces are fitted
// once per layout arc and patch and shared by the cuboids, so the two sides of an interface
// have bit-identical control nets whatever the cuboids' frames; fitting each cuboid on its
// own with fit_bspline_volume() is an option (the faces then agree to rounding only).
//
// Per cuboid, side s gets the grid of its patch re-indexed by the symmetry of the square
// that sends the patch's corners onto Polycube_layout::side_nodes(cuboid, s), so every side
// grid runs along the cuboid's local directions. Layouts may come with left-handed cuboid
// frames; such a cuboid (by the mesh's orientation, frame_handedness(), or else by the sign
// of the volume its six side grids enclose) is fitted with its u direction reversed, so every patch has det J > 0 where
// the fit is valid. Interfaces are declared from the layout (compute_topology() finds the
// same ones geometrically), boundaries are the remaining sides.

#ifndef CGAL_POLYCUBE_IGA_LAYOUT_VOLUME_H
#define CGAL_POLYCUBE_IGA_LAYOUT_VOLUME_H

#include <CGAL/Polycube_IGA/Boundary_distance.h>
#include <CGAL/Polycube_IGA/Bspline_volume_construction.h>
#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Grid_relaxation.h>
#include <CGAL/Polycube_IGA/Layout_chains.h>
#include <CGAL/Polycube_IGA/Layout_padding.h>
#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/Patch_sampling.h>
#include <CGAL/Polycube_IGA/Quality.h>
#include <CGAL/Polycube_IGA/Volume_untangling.h>
#include <CGAL/Polycube_IGA/internal/cuboid_frames.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Options of layout_volume().
struct Layout_volume_options
{
  Patch_sampling_options sampling; ///< N (grid_segments, default 16) and the interior-patch fill
  int degree = 3;                  ///< spline degree in every direction
  /// Uniform knot spans per direction; 0 picks max(1, N / 4): at least 4 samples per span,
  /// so the least-squares data term, not the bending regulariser, determines the fit.
  int spans = 0;
  double stretching_weight = 0., bending_weight = 1e-6, data_weight = 1.; ///< lambda1..3 (eq. 4.1)
  Parameterization parameterization = Parameterization::chord_length;
  Volume_construction_options construction;
  /// Fit every cuboid on its own with fit_bspline_volume() from its six side grids. By
  /// default each arc and patch is fitted once and shared, which makes the two sides of an
  /// interface bit-identical; per cuboid, they agree to rounding only (and cost twice).
  bool per_cuboid_fit = false;
  /// Boundary layer (Layout_padding.h): its depth at a node as a fraction of the shortest
  /// arc there; 0 (the default here) builds one volume per cuboid without a layer.
  /// build_trivariate_model() uses 0.25.
  double boundary_layer = 0.;
  /// Tubes longer than this many times their width become chains of cube-like cuboids
  /// (Layout_chains.h) before the volume is built; 0 (the default here) keeps the layout's
  /// cuboids. build_trivariate_model() uses 2.
  double maximum_cuboid_aspect = 0.;
  /// Move the free control points of patches with poor or negative Jacobians
  /// (Volume_untangling.h); the boundary sides stay as fitted. Off by default: it costs
  /// seconds to minutes on large invalid models and cannot repair a layout whose surface
  /// patches themselves have folded or reflex corners.
  bool untangle = false;
  Volume_untangling_options untangling;
  /// Let the untangling slide the control points of the caps (sides on the layout's CAP
  /// patches, which span input boundary loops where the mesh has nothing) in their tangent
  /// planes, the loops themselves fixed: a planar cap stays in its plane, and a cap side
  /// meeting the surface at a step of its loop need not keep the angle the fit gave it.
  bool slide_caps = true;
  /// Relax the SURFACE grids as one quad mesh on the surface (Grid_relaxation.h) after the
  /// chains and before the boundary layer; maximum_sweeps = 0 (the default here) skips it.
  Grid_relaxation_options relaxation = Grid_relaxation_options::none();
  bool evaluate_quality = true;        ///< Jacobians, interface conformity, boundary distance
  int quality_samples_per_span = 5;    ///< Jacobian and conformity sampling
  int distance_samples_per_direction = 32; ///< per boundary side, for the Hausdorff distance
  Jacobian_bound_options bound;
};

/// Result of layout_volume(): the model, what it was fitted to and how good it is.
struct Layout_volume_result
{
  Multipatch_volume volume;  ///< patch c is cuboid c; interfaces from the layout, other sides boundaries
  Patch_grids samples;       ///< the per-patch grids the faces were fitted to
  int degree = 0, spans = 0;
  /// With a boundary layer or chains, per volume patch: the layout cuboid it is (a piece of)
  /// the core of, or the layout's SURFACE patch its slab lies under (-1 otherwise). Empty
  /// when neither is used (then patch c is cuboid c).
  std::vector<long> core_of, slab_of;
  Volume_untangling_result untangling; ///< what untangle_volume() did (if asked)
  Grid_relaxation_result relaxation;   ///< what relax_surface_grids() did (if asked)
  /// Per cuboid: fitted with u reversed because its layout frame is left-handed.
  std::vector<bool> mirrored;
  /// Per cuboid: side s (1..6) of the volume patch is side layout_side[c][s-1] of the layout
  /// cuboid (the identity unless mirrored, which swaps 1 and 2).
  std::vector<std::array<int, 6>> layout_side;
  /// Per cuboid: signed volume enclosed by its six side grids in the layout's frame.
  std::vector<double> enclosed_volume;
  /// The boundary sides on the layout's SURFACE patches: those the boundary distance measures.
  std::vector<Patch_side> surface_sides;

  bool quality_evaluated = false;
  Multipatch_quality quality;  ///< sampled and certified Jacobians per patch, interface conformity
  Boundary_distance distance;  ///< two-sided Hausdorff distance, boundary sides on SURFACE patches vs the mesh
  /// The settings `quality` and `distance` were measured with: untangle_layout_volume() with
  /// the same ones measures again only the patches the untangling moved.
  int quality_samples_per_span = 0, distance_samples_per_direction = 0;
  Jacobian_bound_options quality_bound;

  double sampling_seconds = 0., fitting_seconds = 0., untangling_seconds = 0., quality_seconds = 0.;
};

namespace internal {

/// The grid of side s of cuboid `cu`, indexed by its two remaining local directions
/// increasing (the layout fit_bspline_volume() expects).
template <class Layout>
Point_grid cuboid_side_grid(const Layout& L, const Patch_grids& G, const typename Layout::Cuboid& cu, int s)
{
  const int sym = side_symmetry(L, cu, s);
  const int N = G.segments;
  const Point_grid& g = G.grids[cu.patches[std::size_t(s - 1)]];
  Point_grid out(N + 1, N + 1);
  for(int b = 0; b <= N; ++b)
    for(int a = 0; a <= N; ++a) {
      const std::array<int, 2> ij = square_symmetry(sym, a, b, N);
      out(a, b) = g(ij[0], ij[1]);
    }
  return out;
}

/// The same surface with its control net re-indexed by symmetry `sym` (exact: control points
/// are only moved). Valid because both directions share one knot vector symmetric about the
/// middle of its domain (uniform knots), so reversing a direction is reversing its points.
inline Tensor_bspline_surface transformed_surface(const Tensor_bspline_surface& f, int sym)
{
  const int n = f.number_of_control_points(0);
  std::vector<Eigen::Vector3d> pts(std::size_t(n) * std::size_t(n));
  for(int b = 0; b < n; ++b)
    for(int a = 0; a < n; ++a) {
      const std::array<int, 2> ij = square_symmetry(sym, a, b, n - 1);
      pts[std::size_t(a) + std::size_t(n) * std::size_t(b)] = f.control_point({{ij[0], ij[1]}});
    }
  return Tensor_bspline_surface({{f.knot_vector(0), f.knot_vector(1)}}, std::move(pts));
}

/// Signed volume enclosed by six side grids, each triangle oriented by the local frame
/// (side (d, end) has outward normal +-(X_a x X_b): + for u1, v0, w1). Positive for a
/// right-handed cuboid. The grids share their edges exactly, so the surface is closed and
/// the value does not depend on the origin; the corner centroid is used for accuracy.
inline double enclosed_volume(const std::array<Point_grid, 6>& grids)
{
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for(const auto& g : grids) c += (g(0, 0) + g(g.size_u - 1, g.size_v - 1)) / 12.;
  double vol = 0.;
  for(int s = 1; s <= 6; ++s) {
    const Point_grid& g = grids[std::size_t(s - 1)];
    const int d = side_direction(s);
    const double sign = (side_parameter(s) ? 1. : -1.) * (d == 1 ? -1. : 1.);
    double part = 0.;
    for(int j = 0; j + 1 < g.size_v; ++j)
      for(int i = 0; i + 1 < g.size_u; ++i) {
        const Eigen::Vector3d p00 = g(i, j) - c, p10 = g(i + 1, j) - c, p11 = g(i + 1, j + 1) - c, p01 = g(i, j + 1) - c;
        part += p00.dot(p10.cross(p11)) + p00.dot(p11.cross(p01));
      }
    vol += sign * part / 6.;
  }
  return vol;
}

/// The same cuboid with local u reversed: nodes (i,j,k) -> (1-i,j,k), sides 1 and 2 swapped.
template <class Cuboid>
Cuboid mirror_u(const Cuboid& cu)
{
  Cuboid m = cu;
  for(int k = 0; k < 2; ++k)
    for(int j = 0; j < 2; ++j)
      for(int i = 0; i < 2; ++i) m.nodes[std::size_t(i + 2 * j + 4 * k)] = cu.nodes[std::size_t((1 - i) + 2 * j + 4 * k)];
  std::swap(m.patches[0], m.patches[1]);
  return m;
}

/// G+Smo interface data between side sa of a cuboid with side nodes na and side sb of one
/// with side nodes nb (both as side_nodes() orders them): tangential direction k of the
/// first runs from na[0] to na[1 << k]; where those nodes sit in nb says which direction of
/// the second it becomes and in which sense.
inline Patch_interface interface_from_nodes(std::size_t pa, int sa, const std::array<std::size_t, 4>& na, std::size_t pb,
                                            int sb, const std::array<std::size_t, 4>& nb)
{
  auto where = [&](std::size_t node) {
    for(int q = 0; q < 4; ++q)
      if(nb[std::size_t(q)] == node) return q;
    throw Invalid_input_error("invalid_layout", "the two sides of an interface do not share their corners");
  };
  const int da = side_direction(sa), db = side_direction(sb);
  const std::array<int, 2> ta{{da == 0 ? 1 : 0, da == 2 ? 1 : 2}}, tb{{db == 0 ? 1 : 0, db == 2 ? 1 : 2}};
  Patch_interface f;
  f.first = {pa, sa};
  f.second = {pb, sb};
  const int q0 = where(na[0]);
  for(int k = 0; k < 2; ++k) {
    const int q1 = where(na[std::size_t(1 << k)]);
    const int diff = q0 ^ q1;
    if(diff != 1 && diff != 2)
      throw Invalid_input_error("invalid_layout", "the two sides of an interface do not share their corners in a compatible order");
    const int bit = diff == 1 ? 0 : 1;
    f.direction_map[std::size_t(ta[std::size_t(k)])] = tb[std::size_t(bit)];
    f.direction_orientation[std::size_t(ta[std::size_t(k)])] = ((q1 >> bit) & 1) != 0;
  }
  f.direction_map[std::size_t(da)] = db;
  f.direction_orientation[std::size_t(da)] = side_parameter(sa) != side_parameter(sb);
  return f;
}

} // namespace internal

namespace internal {

// The end of layout_volume(): untangling (if o.untangle) and quality (if o.evaluate_quality),
// the boundary distance measured on r.surface_sides.
template <class TriangleMesh>
void untangle_and_evaluate(const TriangleMesh& mesh, Layout_volume_result& r, const Layout_volume_options& o)
{
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  // Figures measured before on this very volume with these settings (an untangling after a
  // first evaluation, as build_trivariate_model() does) serve again where nothing moved.
  const std::size_t np = r.volume.number_of_patches();
  const bool measured = r.quality_evaluated && r.quality.certified.size() == np && r.quality.sampled.size() == np &&
                        r.quality_samples_per_span == o.quality_samples_per_span &&
                        r.distance_samples_per_direction == o.distance_samples_per_direction && r.quality_bound == o.bound;
  // The untangler certifies with the default options.
  const bool default_certificates = measured && o.bound == Jacobian_bound_options();
  if(o.untangle) {
    r.untangling = untangle_volume(r.volume, o.untangling, default_certificates ? &r.quality.certified : nullptr);
    // A second pass from there with the caps sliding, for the patches the first left
    // uncertified: from the start it gives other optima, at head.off's eye holes worse ones
    // (4 patches uncertified, where the caps fixed leave none).
    std::vector<Patch_side> caps;
    if(o.slide_caps && !r.untangling.skipped && !r.untangling.uncertified_patches.empty())
      for(const Patch_side& b : r.volume.boundaries())
        if(std::find(r.surface_sides.begin(), r.surface_sides.end(), b) == r.surface_sides.end()) caps.push_back(b);
    if(!caps.empty()) {
      const Volume_untangling_result second = untangle_volume(r.volume, o.untangling, nullptr, caps);
      if(!second.skipped && !second.reverted) r.untangling.add_pass(second);
    }
  }
  const auto t1 = Clock::now();
  r.untangling_seconds = std::chrono::duration<double>(t1 - t0).count();
  if(!o.evaluate_quality) return;
  std::vector<bool> moved(np, !measured);
  if(measured && o.untangle && !r.untangling.skipped && !r.untangling.reverted)
    for(std::size_t c : r.untangling.patches) moved[c] = true;
  r.quality = evaluate_quality(r.volume, o.quality_samples_per_span, o.bound, measured ? &r.quality : nullptr, moved);
  // Untangling moves no control point of a boundary side: a distance measured stands.
  if(!measured) {
    Multipatch_volume on_surface; // the same patches, boundary = sides on SURFACE patches
    for(const auto& v : r.volume.patches()) on_surface.add_patch(v);
    for(const Patch_side& b : r.surface_sides) on_surface.add_boundary(b);
    if(!on_surface.boundaries().empty()) r.distance = boundary_hausdorff_distance(on_surface, mesh, o.distance_samples_per_direction);
  }
  r.quality_samples_per_span = o.quality_samples_per_span;
  r.distance_samples_per_direction = o.distance_samples_per_direction;
  r.quality_bound = o.bound;
  r.quality_evaluated = true;
  r.quality_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
}

// layout_volume() without a boundary layer; cuboid c is built without interior smoothing
// where coons_only[c] (if given).
template <class Point_3>
Layout_volume_result layout_volume(const Polycube_layout<Point_3>& layout, Patch_grids samples, const Layout_volume_options& o,
                                   const std::vector<bool>& coons_only)
{
  using Layout = Polycube_layout<Point_3>;
  using Clock = std::chrono::steady_clock;
  const int N = samples.segments;
  bool fits = N >= 1 && samples.grids.size() == layout.patches.size() && samples.arc_samples.size() == layout.arcs.size();
  for(std::size_t p = 0; fits && p < samples.grids.size(); ++p)
    fits = samples.grids[p].size_u == N + 1 && samples.grids[p].size_v == N + 1 &&
           samples.grids[p].points.size() == std::size_t(N + 1) * std::size_t(N + 1);
  for(std::size_t a = 0; fits && a < samples.arc_samples.size(); ++a) fits = samples.arc_samples[a].size() == std::size_t(N + 1);
  if(!fits) throw Invalid_input_error("invalid_grid", "the patch grids do not belong to this layout");
  if(o.degree < 1) throw Invalid_input_error("invalid_degree", "the spline degree must be at least 1");
  Layout_volume_result r;
  r.degree = o.degree;
  r.spans = o.spans > 0 ? o.spans : std::max(1, N / 4);
  const auto t0 = Clock::now();

  Volume_fitting_options vo;
  const Knot_vector kv = Knot_vector::uniform(r.degree, r.spans);
  vo.knots = {{kv, kv, kv}};
  vo.stretching_weight = o.stretching_weight;
  vo.bending_weight = o.bending_weight;
  vo.data_weight = o.data_weight;
  vo.parameterization = o.parameterization;
  vo.construction = o.construction;

  // The §4.1 recipe once per layout element rather than per cuboid: every arc's curve is
  // fitted once (ends interpolated), every patch's surface once with its four arc curves
  // fixed, and each cuboid only re-indexes these control nets. The two cuboids of an
  // interface thus get bit-identical control nets on it, and every edge is shared exactly.
  std::vector<Tensor_bspline_surface> patch_surface;
  if(!o.per_cuboid_fit) {
    Curve_fitting_options co;
    co.knots = kv;
    co.stretching_weight = o.stretching_weight;
    co.bending_weight = o.bending_weight;
    co.data_weight = o.data_weight;
    co.parameterization = o.parameterization;
    std::vector<Bspline_curve> arc_curve;
    arc_curve.reserve(layout.arcs.size());
    for(const auto& pts : samples.arc_samples) arc_curve.push_back(fit_bspline_curve(pts, co).spline);
    // Arc a's curve run from node `from` (reversal keeps the knots: they are symmetric).
    auto oriented = [&](std::size_t a, std::size_t from) {
      const Bspline_curve& c = arc_curve[a];
      if(layout.arcs[a].nodes[0] == from) return c;
      return Bspline_curve({{c.knot_vector(0)}},
                           std::vector<Eigen::Vector3d>(c.control_points().rbegin(), c.control_points().rend()));
    };
    Surface_fitting_options so;
    so.knots_u = so.knots_v = kv;
    so.stretching_weight = o.stretching_weight;
    so.bending_weight = o.bending_weight;
    so.data_weight = o.data_weight;
    so.parameterization = o.parameterization;
    patch_surface.reserve(layout.patches.size());
    for(std::size_t p = 0; p < layout.patches.size(); ++p) {
      const auto& pa = layout.patches[p];
      // Grid sides u0 (i = 0), u1 (i = N), v0 (j = 0), v1 (j = N), each along the increasing
      // other index: arcs 3, 1, 0, 2 run from corners 0, 1, 0, 3.
      so.fixed_boundaries[0] = oriented(pa.arcs[3], pa.corners[0]);
      so.fixed_boundaries[1] = oriented(pa.arcs[1], pa.corners[1]);
      so.fixed_boundaries[2] = oriented(pa.arcs[0], pa.corners[0]);
      so.fixed_boundaries[3] = oriented(pa.arcs[2], pa.corners[3]);
      patch_surface.push_back(fit_bspline_surface(samples.grids[p], so).spline);
    }
  }

  const std::vector<int> handedness = internal::frame_handedness(layout);
  std::vector<typename Layout::Cuboid> frame(layout.cuboids.size());
  for(std::size_t c = 0; c < layout.cuboids.size(); ++c) {
    typename Layout::Cuboid cu = layout.cuboids[c];
    std::array<Point_grid, 6> grids;
    for(int s = 1; s <= 6; ++s) grids[std::size_t(s - 1)] = internal::cuboid_side_grid(layout, samples, cu, s);
    const double vol = internal::enclosed_volume(grids);
    const bool mirror = handedness[c] != 0 ? handedness[c] < 0 : vol < 0.;
    if(mirror) {
      cu = internal::mirror_u(cu);
      for(int s = 1; s <= 6; ++s) grids[std::size_t(s - 1)] = internal::cuboid_side_grid(layout, samples, cu, s);
    }
    r.enclosed_volume.push_back(vol);
    r.mirrored.push_back(mirror);
    r.layout_side.push_back(mirror ? std::array<int, 6>{{2, 1, 3, 4, 5, 6}} : std::array<int, 6>{{1, 2, 3, 4, 5, 6}});
    frame[c] = cu;
    if(o.per_cuboid_fit) {
      r.volume.add_patch(fit_bspline_volume(grids, vo).volume);
      continue;
    }
    std::array<Tensor_bspline_surface, 6> faces;
    for(int s = 1; s <= 6; ++s)
      faces[std::size_t(s - 1)] =
        internal::transformed_surface(patch_surface[cu.patches[std::size_t(s - 1)]], internal::side_symmetry(layout, cu, s));
    Volume_construction_options construction = o.construction;
    if(c < coons_only.size() && coons_only[c]) construction.smoothing = Interior_smoothing::none;
    r.volume.add_patch(build_bspline_volume(faces, construction).volume);
  }

  // Interfaces from the layout; every other side is a boundary.
  auto volume_side = [&](std::size_t c, int layout_s) {
    return r.mirrored[c] && layout_s <= 2 ? 3 - layout_s : layout_s;
  };
  std::vector<std::array<bool, 6>> glued(layout.cuboids.size(), std::array<bool, 6>{});
  for(const auto& I : layout.interfaces()) {
    const int sa = volume_side(I.cuboid_a, I.side_a), sb = volume_side(I.cuboid_b, I.side_b);
    r.volume.add_interface(internal::interface_from_nodes(I.cuboid_a, sa, Layout::side_nodes(frame[I.cuboid_a], sa), I.cuboid_b,
                                                          sb, Layout::side_nodes(frame[I.cuboid_b], sb)));
    glued[I.cuboid_a][std::size_t(sa - 1)] = glued[I.cuboid_b][std::size_t(sb - 1)] = true;
  }
  for(std::size_t c = 0; c < layout.cuboids.size(); ++c)
    for(int s = 1; s <= 6; ++s)
      if(!glued[c][std::size_t(s - 1)]) r.volume.add_boundary({c, s});
  r.fitting_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  for(const Patch_side& b : r.volume.boundaries()) {
    const int ls = r.layout_side[b.patch][std::size_t(b.side - 1)];
    if(layout.patches[layout.cuboids[b.patch].patches[std::size_t(ls - 1)]].kind == Layout::SURFACE) r.surface_sides.push_back(b);
  }
  untangle_and_evaluate(layout.mesh, r, o);
  r.samples = std::move(samples);
  return r;
}

} // namespace internal

/*!
 * \ingroup PkgPolycubeIGARef
 * Builds the multipatch volume of `layout` from its patch grids `samples`
 * (sample_layout_patches()): one volume per cuboid (§4.1 recipe) with uniform knots of
 * degree `o.degree` and `o.spans` spans (0: max(1, N/4)) in every direction, the layout's
 * interfaces declared, left-handed cuboids fitted mirrored, and (if `o.evaluate_quality`)
 * per-patch Jacobians, interface conformity and the boundary Hausdorff distance to
 * `layout.mesh` measured on the sides that lie on SURFACE patches (caps span boundary
 * loops, the mesh has nothing there). With `o.boundary_layer` > 0 the
 * volume is that of pad_layout(): cores first (patch c the core of cuboid c), then one slab
 * per SURFACE patch (Layout_volume_result::core_of / slab_of). Deterministic.
 */
template <class Point_3>
Layout_volume_result layout_volume(const Polycube_layout<Point_3>& layout, Patch_grids samples,
                                   const Layout_volume_options& o = Layout_volume_options())
{
  if(!(o.boundary_layer > 0.) && !(o.maximum_cuboid_aspect > 0.) && o.relaxation.maximum_sweeps <= 0) return internal::layout_volume(layout, std::move(samples), o, {});
  const Polycube_layout<Point_3>* L = &layout;
  Chained_layout<Point_3> chained;
  if(o.maximum_cuboid_aspect > 0.) {
    Cuboid_chain_options co;
    co.maximum_aspect = o.maximum_cuboid_aspect;
    chained = split_long_cuboids(layout, samples, o.sampling, co);
    samples = std::move(chained.samples);
    L = &chained.layout;
  }
  Grid_relaxation_result relaxed = relax_surface_grids(*L, samples, o.relaxation, o.sampling.smooth_interior_patches);
  auto input_cuboid = [&](long c) { return c < 0 || chained.cuboid_of.empty() ? c : chained.cuboid_of[std::size_t(c)]; };
  auto input_patch = [&](long p) { return p < 0 || chained.patch_of.empty() ? p : chained.patch_of[std::size_t(p)]; };
  Layout_volume_options plain = o;
  plain.boundary_layer = 0.;
  plain.maximum_cuboid_aspect = 0.;
  Layout_volume_result r;
  if(o.boundary_layer > 0.) {
    Padding_options po;
    po.thickness = o.boundary_layer;
    Padded_layout<Point_3> padded = pad_layout(*L, samples, po);
    // Slabs keep their Coons interiors: the uniform control-net Laplacian of the harmonic
    // smoothing treats a thin curved slab as a cube and pulls it towards its chords.
    std::vector<bool> coons_only(padded.layout.cuboids.size(), false);
    for(std::size_t c = 0; c < coons_only.size(); ++c) coons_only[c] = padded.slab_of[c] >= 0;
    r = internal::layout_volume(padded.layout, std::move(padded.samples), plain, coons_only);
    for(long c : padded.core_of) r.core_of.push_back(input_cuboid(c));
    for(long p : padded.slab_of) r.slab_of.push_back(input_patch(p));
  } else {
    r = internal::layout_volume(*L, std::move(samples), plain, {});
    for(long c : chained.cuboid_of) r.core_of.push_back(c);
    r.slab_of.assign(r.core_of.size(), -1);
  }
  r.relaxation = relaxed;
  return r;
}

/// Samples the patches (sample_layout_patches()) and builds the volume from them.
template <class Point_3>
Layout_volume_result layout_volume(const Polycube_layout<Point_3>& layout, const Layout_volume_options& o)
{
  const auto t0 = std::chrono::steady_clock::now();
  Patch_grids g = sample_layout_patches(layout, o.sampling);
  const double ts = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Layout_volume_result r = layout_volume(layout, std::move(g), o);
  r.sampling_seconds = ts;
  return r;
}

/// Untangles the volume of `r`, built by layout_volume() from `layout` with `untangle` off,
/// with `o.untangling` (Volume_untangling.h), and evaluates its quality again: what
/// layout_volume() with `o.untangle` would have given, for a caller that first compares
/// constructions (build_trivariate_model() untangles only the better of two). Figures that
/// layout_volume() measured with the same settings are reused where untangling moved nothing
/// (certificates, sampled Jacobians, the boundary distance), so `r.volume` must be as
/// layout_volume() left it.
template <class Point_3>
void untangle_layout_volume(const Polycube_layout<Point_3>& layout, Layout_volume_result& r, const Layout_volume_options& o)
{
  Layout_volume_options u = o;
  u.untangle = true;
  internal::untangle_and_evaluate(layout.mesh, r, u);
}

/// The fields of `base` that the named parameters of layout_volume() override, overridden.
template <class NamedParameters>
Layout_volume_options layout_volume_options(const NamedParameters& np, Layout_volume_options base = Layout_volume_options())
{
  base.sampling.grid_segments = int(option(np, internal_np::grid_resolution, base.sampling.grid_segments));
  base.sampling.smooth_interior_patches =
    bool(option(np, internal_np::smooth_interior_patches, base.sampling.smooth_interior_patches));
  base.sampling.stretch_rounds = int(option(np, internal_np::stretch_rounds, base.sampling.stretch_rounds));
  base.sampling.sharp_boundary_turn = option(np, internal_np::sharp_boundary_turn, base.sampling.sharp_boundary_turn);
  internal::check_sharp_boundary_turn(base.sampling.sharp_boundary_turn);
  base.degree = int(option(np, internal_np::spline_degree, base.degree));
  base.spans = int(option(np, internal_np::number_of_spans, base.spans));
  base.stretching_weight = option(np, internal_np::stretching_weight, base.stretching_weight);
  base.bending_weight = option(np, internal_np::bending_weight, base.bending_weight);
  base.data_weight = option(np, internal_np::data_weight, base.data_weight);
  base.boundary_layer = option(np, internal_np::boundary_layer, base.boundary_layer);
  base.maximum_cuboid_aspect = option(np, internal_np::maximum_cuboid_aspect, base.maximum_cuboid_aspect);
  base.untangle = option(np, internal_np::untangle_volume, base.untangle);
  base.untangling.focused_sample_rounds = int(option(np, internal_np::focused_sample_rounds, base.untangling.focused_sample_rounds));
  if(base.untangling.focused_sample_rounds < 0)
    throw Invalid_input_error("invalid_parameter", "focused_sample_rounds must not be negative");
  base.relaxation.maximum_sweeps = int(option(np, internal_np::grid_relaxation_sweeps, base.relaxation.maximum_sweeps));
  return base;
}

/*!
 * Named-parameter form: `grid_resolution` (N, default 16), `smooth_interior_patches`
 * (true), `spline_degree` (3), `number_of_spans` (max(1, N/4)), `stretching_weight` (0),
 * `bending_weight` (1e-6), `data_weight` (1), `boundary_layer` (0: none),
 * `maximum_cuboid_aspect` (0: no chains), `untangle_volume` (false) and
 * `focused_sample_rounds` (4, Volume_untangling_options)
 * override the fields of `base`.
 * Example: `layout_volume(layout, parameters::grid_resolution(32).spline_degree(2))`.
 */
template <class Point_3, class NamedParameters = parameters::Default_named_parameters>
Layout_volume_result layout_volume(const Polycube_layout<Point_3>& layout,
                                   const NamedParameters& np = parameters::default_values(),
                                   Layout_volume_options base = Layout_volume_options())
{
  return layout_volume(layout, layout_volume_options(np, std::move(base)));
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_LAYOUT_VOLUME_H
