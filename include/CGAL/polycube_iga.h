// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The one-call driver: triangle mesh -> topology -> (pants) -> cuboid decomposition ->
// polycube layout -> patch grids -> B-spline faces and volumes -> multipatch volume, with the
// quality figures of every stage. It only chains the stages (each is usable on its own);
// named parameters are passed through to the stage that reads them.

#ifndef CGAL_POLYCUBE_IGA_H
#define CGAL_POLYCUBE_IGA_H

#include <CGAL/Polycube_IGA/Cuboid_decomposition.h>
#include <CGAL/Polycube_IGA/Boundary_distance.h>
#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Layout_arc_relaxation.h>
#include <CGAL/Polycube_IGA/Layout_node_relocation.h>
#include <CGAL/Polycube_IGA/Layout_volume.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Polycube_IGA/internal/layout_corner_angles.h>
#include <CGAL/Polycube_IGA/internal/layout_measures.h>
#include <CGAL/Polycube_IGA/parameters.h>

#include <algorithm>
#include <limits>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

namespace internal {

/// A mesh point much farther from the volume than any volume point is from the mesh: a part
/// of the shape is missing (not fitted too coarsely), which no finer grid recovers.
inline bool part_missing(const Boundary_distance& d) { return d.mesh_to_spline > 4. * d.spline_to_mesh; }

/// x with 3 significant digits.
inline std::string short_number(double x)
{
  std::ostringstream os;
  os << std::setprecision(3) << x;
  return os.str();
}

/// (a, b, c), each with 3 significant digits.
inline std::string triple_text(double a, double b, double c)
{
  return "(" + short_number(a) + ", " + short_number(b) + ", " + short_number(c) + ")";
}

/// The points of the layout's nodes, in order.
template <class Point_3>
std::vector<Point_3> node_points(const Polycube_layout<Point_3>& L)
{
  std::vector<Point_3> out;
  for(auto v : L.nodes) out.push_back(L.mesh.point(v));
  return out;
}

/// A fraction as a percentage with 3 significant digits.
inline std::string percent_text(double fraction) { return short_number(100. * fraction) + "%"; }

/// The layout patch holding face `f` of the layout's mesh, or -1.
template <class Point_3>
int patch_of_face(const Polycube_layout<Point_3>& layout, std::size_t f)
{
  for(std::size_t p = 0; p < layout.patches.size(); ++p)
    for(auto g : layout.patches[p].faces)
      if(std::size_t(g) == f) return int(p);
  return -1;
}

/// Says where the boundary is too far from the mesh. A mesh point much farther from the
/// volume than any volume point is from the mesh means a part of the shape is missing,
/// typically a protrusion that one layout patch covers and its map to the square shrinks to
/// almost nothing; otherwise the faces are fitted too coarsely or bulge away from the mesh.
template <class Point_3>
std::string boundary_distance_message(const Polycube_layout<Point_3>& layout, const Boundary_distance& d, double limit)
{
  auto number = short_number;
  auto percent = percent_text;
  auto point = [&](const std::array<double, 3>& p) { return triple_text(p[0], p[1], p[2]); };
  std::string s = "boundary distance " + percent(d.relative) + " of the bounding-box diagonal exceeds " + percent(limit) + ": ";
  if(d.mesh_to_spline >= d.spline_to_mesh) {
    const int patch = patch_of_face(layout, d.farthest_mesh_face);
    s += "the mesh point " + point(d.farthest_mesh_point) + " (layout patch " + std::to_string(patch) + ") is " +
         number(d.mesh_to_spline) + " from the volume's boundary";
    s += part_missing(d)
           ? ": that part of the shape is not represented (likely a protrusion that the patch's map to the square shrinks to almost nothing)"
           : ": the faces are fitted too coarsely there (a finer grid may help)";
  } else {
    s += "the volume's boundary point " + point(d.farthest_spline_point) + " is " + number(d.spline_to_mesh) +
         " from the mesh";
  }
  return s;
}

/// The strings, separated by commas.
inline std::string comma_list(const std::vector<std::string>& items)
{
  std::string list;
  for(const auto& x : items) list += (list.empty() ? "" : ", ") + x;
  return list;
}

/// Patches of `v` whose det J is not certified positive (all of them if not evaluated).
inline std::size_t uncertified_patches(const Layout_volume_result& v)
{
  if(!v.quality_evaluated) return std::numeric_limits<std::size_t>::max();
  return std::size_t(std::count_if(v.quality.certified.begin(), v.quality.certified.end(),
                                   [](const auto& b) { return !b.certified_positive; }));
}

/// The folded boundary sides of `v` (Boundary_distance::folded_sides) on patches whose det J
/// is not certified positive. On a certified patch the side's normal is the volume's outward
/// normal; one that faces against its nearest mesh face there lies on a part thinner than
/// the fit's distance to the mesh, nearer the far side (blade.off: 8 such sides, 0.65 thick,
/// 0.3 off), not on a fold, and untangling the other patches can still make the volume valid.
inline std::vector<Boundary_distance::Folded_side> folded_uncertified_sides(const Layout_volume_result& v)
{
  std::vector<Boundary_distance::Folded_side> out;
  for(const auto& f : v.distance.folded_sides)
    if(!v.quality_evaluated || f.side.patch >= v.quality.certified.size() || !v.quality.certified[f.side.patch].certified_positive)
      out.push_back(f);
  return out;
}

/// Whether invalid volume `a` is nearer a valid one than invalid volume `b`, though their
/// layouts differ (a polycube map's boxes against a genus layout): its boundary within
/// `maximum_boundary_distance` where b's is not; both off, the nearer boundary (a volume
/// that misses a leg is no nearer for folding less); both within, the smaller share of
/// patches uncertified (their counts differ). Ties go to the other measure.
inline bool nearer_valid(const Layout_volume_result& a, const Layout_volume_result& b, double maximum_boundary_distance)
{
  if(!a.quality_evaluated || a.quality.certified.empty()) return false;
  if(!b.quality_evaluated || b.quality.certified.empty()) return true;
  const bool a_near = a.distance.relative <= maximum_boundary_distance, b_near = b.distance.relative <= maximum_boundary_distance;
  if(a_near != b_near) return a_near;
  const double share_a = double(uncertified_patches(a)) / double(a.quality.certified.size());
  const double share_b = double(uncertified_patches(b)) / double(b.quality.certified.size());
  if(a_near) return share_a != share_b ? share_a < share_b : a.distance.relative < b.distance.relative;
  return a.distance.relative != b.distance.relative ? a.distance.relative < b.distance.relative : share_a < share_b;
}

/// "k of n patches uncertified, d% of the diagonal off" for volume `v`.
inline std::string volume_shortfall(const Layout_volume_result& v)
{
  if(!v.quality_evaluated) return "quality not evaluated";
  return std::to_string(uncertified_patches(v)) + " of " + std::to_string(v.quality.certified.size()) + " patches uncertified, " +
         short_number(100. * v.distance.relative) + "% of the diagonal off";
}

/// Reason codes of Trivariate_model::invalidity_reasons() for volume `v`.
inline std::vector<std::string> invalidity_reasons(const Layout_volume_result& v, double maximum_boundary_distance)
{
  if(!v.quality_evaluated || v.quality.certified.empty()) return {"quality_not_evaluated"};
  std::vector<std::string> reasons;
  for(const auto& b : v.quality.certified)
    if(!b.certified_positive) {
      reasons.push_back("nonpositive_jacobian");
      break;
    }
  if(!(v.distance.relative <= maximum_boundary_distance)) reasons.push_back("boundary_distance");
  return reasons;
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// The default `minimum_grid_resolution` of build_trivariate_model() for a first grid of
/// `grid` samples per patch side: one halving if that leaves 8 or more, else `grid` (no
/// coarser retry).
inline int default_minimum_grid_resolution(int grid) { return grid / 2 >= 8 ? grid / 2 : grid; }

/// The default `minimum_spline_degree` of build_trivariate_model() for splines of `degree`:
/// quadratic (C1 across knots, what IGA solvers most often take) when the degree is higher.
inline int default_minimum_spline_degree(int degree) { return std::min(2, degree); }

/// Jacobian samples that the untangling of one build_trivariate_model() run may visit in
/// all (Untangling_budget): three times the most a valid result has needed (the gear
/// `pinion.off` split at its edges' midpoints, 3.3e9, valid after the node relocation retry
/// at 32 samples), about 12 minutes on 2 cores.
constexpr double default_untangling_budget = 1e10;

/// \ingroup PkgPolycubeIGARef
/// Everything `build_trivariate_model()` produced.
template <class Point_3>
struct Trivariate_model
{
  Polycube_layout<Point_3> layout;
  Layout_validation layout_validation;
  Layout_volume_result volume; ///< the multipatch volume, its samples and quality
  /// Wall-clock seconds per stage, in the order they ran.
  std::vector<std::pair<std::string, double>> stage_seconds;
  std::vector<std::string> warnings;

  /// The largest two-sided Hausdorff distance between the volume's boundary and the mesh that
  /// a valid model may have, relative to the mesh's bounding-box diagonal.
  double maximum_boundary_distance = 0.02;

  /// Why the volume is not fit for analysis, as reason codes (empty when it is):
  /// `quality_not_evaluated`, `nonpositive_jacobian` (a patch's det J is not certified
  /// positive), `boundary_distance` (the boundary is farther from the mesh than
  /// `maximum_boundary_distance`).
  std::vector<std::string> invalidity_reasons() const { return internal::invalidity_reasons(volume, maximum_boundary_distance); }

  /// The grid resolutions the volume was built with, in order; the last valid one, or else
  /// the first, is `volume` (see `maximum_grid_resolution` in build_trivariate_model()).
  std::vector<int> grid_attempts;
  /// The spline degree of each of `grid_attempts` (see `minimum_spline_degree`).
  std::vector<int> degree_attempts;
  /// Cubes added to the layout under parts of the shape the volume missed (see
  /// `missing_part_cubes` in build_trivariate_model()).
  int missing_part_cubes = 0;
  /// True when the volume at the first grid was invalid and was built again on relaxed
  /// surface grids (`grid_relaxation_sweeps`); `volume.relaxation` says whether it was kept.
  bool relaxation_attempted = false;
  /// True when the volume was far from the mesh after that and was built again from
  /// stretch-reduced patch maps (`stretch_rounds`); `volume.samples` were so built if kept.
  bool stretch_attempted = false;
  /// The rounds of stretch reduction of the kept volume's patch maps (0: plain mean-value).
  int stretch_rounds = 0;
  /// True when a boundary side of an uncertified patch turned over after that and the faces
  /// were fitted again stiffer (`fold_bending_weight`); `bending_weight` is the kept one's.
  bool stiffer_faces_attempted = false;
  double bending_weight = 0.;
  /// The layout's belt phase (Cuboid_decomposition's `belt_phase`; see `belt_phases` in
  /// build_trivariate_model()).
  double belt_phase = 0.;
  /// True when a closed genus-0 surface is laid out as a chain of cuboids between caps at
  /// its two ends (Cuboid_decomposition's `sphere_chain`; see build_trivariate_model()).
  bool sphere_chain = false;
  /// True when a cylinder's section corners were moved off the steps of its cut ends
  /// (Cuboid_decomposition's `corners_off_steps`; see `step_retry` in build_trivariate_model()).
  bool corners_off_steps = false;
  /// What the arc relaxation did, when the layout's arcs were relaxed (see
  /// `arc_relaxation_sweeps` in build_trivariate_model()); sweeps 0 otherwise.
  Arc_relaxation_result arc_relaxation;
  /// What the node relocation did (see `node_relocation_sweeps` in build_trivariate_model()).
  Node_relocation_result node_relocation;
  /// True when the volume on the decomposition's own nodes was not valid and the layout was
  /// built again with its nodes relocated (see `node_relocation_retry` in
  /// build_trivariate_model()); `node_relocation.nodes_moved` is 0 if that was not kept.
  bool relocation_retried = false;
  /// Whether a layout on a polycube map was tried after the first layouts gave no valid
  /// volume (see `polycube_retry` in build_trivariate_model()).
  bool polycube_retried = false;
  /// Whether the pants were traced again with their cuts away from the holes after the
  /// layouts above gave no valid volume (see `cuts_away_retry` in build_trivariate_model()).
  bool cuts_away_retried = false;
  /// Whether a layout on a polycube map was tried first, the surface being nearly an
  /// orthogonal polyhedron (see `polycube_first_alignment` in build_trivariate_model()).
  bool polycube_first = false;
  /// Jacobian samples that the untangling's energy evaluations visited over the whole run,
  /// and whether that reached `untangling_budget` (build_trivariate_model()), which then
  /// stopped the untangling.
  double untangling_work = 0.;
  bool untangling_budget_exhausted = false;

  /// True when every patch's det J is certified positive and the boundary is within
  /// `maximum_boundary_distance` of the mesh.
  bool is_valid() const { return invalidity_reasons().empty(); }
};

namespace internal {

/// The layout options that build_trivariate_model() varies when a volume is not valid
/// (Cuboid_decomposition's named parameters of the same names).
struct Layout_variant
{
  double belt_phase = 0.;
  bool corners_off_steps = false;
  /// Laid out on a polycube map (Cuboid_decomposition's `polycube_map`).
  bool polycube_map = false;
  /// A long closed genus-0 surface laid out as a chain of cuboids (Cuboid_decomposition's
  /// `sphere_chain`); false: one cube.
  bool sphere_chain = true;
  /// Sweeps of relocate_layout_nodes(); -1: the `node_relocation_sweeps` named parameter.
  int node_relocation_sweeps = -1;
  /// A closed surface's pants cut away from the holes (Pants_decomposition's
  /// `cuts_away_from_holes`); false: the named parameter.
  bool cuts_away_from_holes = false;
};

/// Appends `from`'s stage seconds to `to`, each name followed by `suffix`.
inline void append_stage_seconds(std::vector<std::pair<std::string, double>>& to,
                                 const std::vector<std::pair<std::string, double>>& from, const std::string& suffix)
{
  for(const auto& x : from) to.push_back({x.first + suffix, x.second});
}

/// Puts the stage seconds of an earlier attempt, `earlier`, before those of `to`, each of
/// its names followed by `suffix`.
inline void prepend_stage_seconds(std::vector<std::pair<std::string, double>>& to,
                                  const std::vector<std::pair<std::string, double>>& earlier, const std::string& suffix)
{
  std::vector<std::pair<std::string, double>> seconds;
  append_stage_seconds(seconds, earlier, suffix);
  seconds.insert(seconds.end(), to.begin(), to.end());
  to = std::move(seconds);
}

/// build_trivariate_model() on the layout `variant`, untangling an invalid result at the end
/// if `untangle_invalid`, unless the layout is a sphere's and `other_phases_follow` (other
/// belt phases may give a valid one; a chain's is not deferred): then `*untangling_deferred` says whether that
/// untangling was left out. Returns nothing, having built no volume, if the layout's nodes
/// are `unless_nodes` (the variant does not change the layout: a box laid out on its own
/// edges, a cylinder with no corner near a step).
template <class TriangleMesh, class NamedParameters>
std::optional<Trivariate_model<typename Cuboid_decomposition<TriangleMesh>::Point>>
build_on_layout(const TriangleMesh& tm, const NamedParameters& np, const std::function<void(const std::string&)>& progress,
                Untangling_budget& budget, const Layout_variant& variant, bool untangle_invalid, bool other_phases_follow,
                const std::vector<typename Cuboid_decomposition<TriangleMesh>::Point>* unless_nodes,
                bool* untangling_deferred = nullptr)
{
  using Decomposition = Cuboid_decomposition<TriangleMesh>;
  Trivariate_model<typename Decomposition::Point> model;
  using clock = std::chrono::steady_clock;
  auto stage = [&](const std::string& name, auto&& f) {
    if(progress) progress(name);
    const auto t0 = clock::now();
    f();
    model.stage_seconds.push_back({name, std::chrono::duration<double>(clock::now() - t0).count()});
  };
  // Options first: a bad one is rejected before any work.
  // A boundary layer by default (Layout_padding.h): without it, cuboid edges on a smooth
  // surface have det J -> 0.
  Layout_volume_options volume_defaults;
  volume_defaults.boundary_layer = 0.25;
  // Long tubes (pants arms) as chains of cube-like cuboids (Layout_chains.h).
  volume_defaults.maximum_cuboid_aspect = 2.;
  // Inner control points moved where det J is poor or negative (Volume_untangling.h).
  volume_defaults.untangle = true;
  Layout_volume_options volume_options = layout_volume_options(np, volume_defaults);
  volume_options.untangling.budget = &budget; // one for the whole run, retries included
  volume_options.relaxation = Grid_relaxation_options::none(); // the second attempt's (below)
  volume_options.sampling.stretch_rounds = 0;                  // the third attempt's (below)
  // Untangling costs more than building (eight.off: 3 s against 1 s) and cannot repair
  // folded surface grids, so the first two constructions are compared untangled-free and
  // the better one is untangled (below).
  const bool untangle = volume_options.untangle;
  volume_options.untangle = false;
  model.maximum_boundary_distance = option(np, internal_np::maximum_boundary_distance, 0.02);
  const int maximum_grid = int(option(np, internal_np::maximum_grid_resolution, 2 * volume_options.sampling.grid_segments));
  if(maximum_grid > 1024)
    throw Invalid_input_error("invalid_parameter", "maximum_grid_resolution must be at most 1024 samples per patch side");
  const int minimum_grid = int(option(np, internal_np::minimum_grid_resolution,
                                      default_minimum_grid_resolution(volume_options.sampling.grid_segments)));
  if(minimum_grid < 2)
    throw Invalid_input_error("invalid_parameter", "minimum_grid_resolution must be at least 2 samples per patch side");
  const int minimum_degree = int(option(np, internal_np::minimum_spline_degree, default_minimum_spline_degree(volume_options.degree)));
  if(minimum_degree < 1 || minimum_degree > volume_options.degree)
    throw Invalid_input_error("invalid_parameter", "minimum_spline_degree must be from 1 to the spline degree");
  const int sweeps = int(option(np, internal_np::grid_relaxation_sweeps, 100));
  if(sweeps < 0) throw Invalid_input_error("invalid_parameter", "grid_relaxation_sweeps must not be negative");
  const int stretch_rounds = int(option(np, internal_np::stretch_rounds, 3));
  if(stretch_rounds < 0) throw Invalid_input_error("invalid_parameter", "stretch_rounds must not be negative");
  const double fold_bending = option(np, internal_np::fold_bending_weight, 1e-4);
  if(!(std::isfinite(fold_bending) && fold_bending >= 0.))
    throw Invalid_input_error("invalid_parameter", "fold_bending_weight must be finite and not negative");
  model.bending_weight = volume_options.bending_weight;
  const int arc_sweeps = int(option(np, internal_np::arc_relaxation_sweeps, 0));
  if(arc_sweeps < 0) throw Invalid_input_error("invalid_parameter", "arc_relaxation_sweeps must not be negative");
  const int polycube_arc_sweeps = int(option(np, internal_np::polycube_arc_relaxation_sweeps, 3));
  if(polycube_arc_sweeps < 0) throw Invalid_input_error("invalid_parameter", "polycube_arc_relaxation_sweeps must not be negative");
  const int asked_node_sweeps = int(option(np, internal_np::node_relocation_sweeps, 0));
  if(asked_node_sweeps < 0) throw Invalid_input_error("invalid_parameter", "node_relocation_sweeps must not be negative");
  const int node_sweeps = variant.node_relocation_sweeps >= 0 ? variant.node_relocation_sweeps : asked_node_sweeps;
  const int missing_part_cubes = int(option(np, internal_np::missing_part_cubes, 2));
  if(missing_part_cubes < 0) throw Invalid_input_error("invalid_parameter", "missing_part_cubes must not be negative");
  Surface_topology_result<TriangleMesh> topology;
  stage("topology", [&] { topology = internal::cutting_topology(tm); });
  for(const auto& w : topology.warnings) model.warnings.push_back(w);
  stage("cuboid decomposition", [&] {
    model.layout = Decomposition()(tm, parameters::surface_topology(topology)
                                         .cut_criterion(option(np, internal_np::cut_criterion, Cut_criterion::LENGTH))
                                         .symmetry_plane(option(np, internal_np::symmetry_plane, Cut_criterion_options().symmetry_plane))
                                         .criterion_strength(option(np, internal_np::criterion_strength, 1.0))
                                         .maximum_refinements(option(np, internal_np::maximum_refinements, 2))
                                         .belt_phase(variant.belt_phase)
                                         .corners_off_steps(variant.corners_off_steps)
                                         .sphere_chain(variant.sphere_chain)
                                         .orthogonal_blocks(option(np, internal_np::orthogonal_blocks, true))
                                         .polycube_map(variant.polycube_map)
                                         .balance_pants_corners(option(np, internal_np::balance_pants_corners, false))
                                         .cut_pair_trials(option(np, internal_np::cut_pair_trials, default_cut_pair_trials))
                                         .cuts_away_from_holes(variant.cuts_away_from_holes ||
                                                               option(np, internal_np::cuts_away_from_holes, false)));
  });
  model.sphere_chain = model.layout.layout_class == Layout_class::sphere && model.layout.cuboids.size() > 1;
  if(node_sweeps > 0)
    stage("node relocation", [&] { model.node_relocation = relocate_layout_nodes(model.layout, node_sweeps); });
  if(unless_nodes && node_points(model.layout) == *unless_nodes) return std::nullopt;
  if(variant.node_relocation_sweeps > 0 && model.node_relocation.nodes_moved == 0) return std::nullopt;
  // A polycube map's arcs follow its charts' borders, which zigzag from triangle to triangle
  // where a chart meets another on a curved face (a round hole's wall, a fillet).
  const int layout_arc_sweeps = model.layout.layout_class == Layout_class::polycube ? std::max(arc_sweeps, polycube_arc_sweeps) : arc_sweeps;
  if(layout_arc_sweeps > 0)
    stage("arc relaxation", [&] { model.arc_relaxation = relax_layout_arcs(model.layout, layout_arc_sweeps); });
  if(model.layout.turned_outwards)
    model.warnings.push_back("the input's faces point into the solid; the layout and the volume use them turned outwards");
  stage("layout validation", [&] { model.layout_validation = model.layout.validate(); });
  if(!model.layout_validation.is_valid())
    throw Internal_error("invalid_layout", "the polycube layout violates an invariant: " + model.layout_validation.problems.front());
  stage("volume construction", [&] { model.volume = layout_volume(model.layout, volume_options); });
  model.grid_attempts.push_back(volume_options.sampling.grid_segments);
  model.degree_attempts.push_back(volume_options.degree);
  auto far_from_mesh = [&] {
    const std::vector<std::string> reasons = model.invalidity_reasons();
    return std::find(reasons.begin(), reasons.end(), "boundary_distance") != reasons.end();
  };
  auto worth_retrying = [&] {
    return !model.is_valid() && model.volume.quality_evaluated && !(far_from_mesh() && internal::part_missing(model.volume.distance));
  };
  // A construction replaces the kept one if it is valid, or leaves fewer patches uncertified
  // without its boundary moving farther off the mesh, or as many and brings a boundary that
  // is too far closer.
  auto better_than_kept = [&](const Layout_volume_result& r) {
    if(!r.quality_evaluated) return false;
    if(internal::invalidity_reasons(r, model.maximum_boundary_distance).empty()) return true;
    const double kept = model.volume.distance.relative;
    const bool closer = r.distance.relative <= std::max(model.maximum_boundary_distance, kept);
    const std::size_t fewer = internal::uncertified_patches(r), before = internal::uncertified_patches(model.volume);
    return (fewer < before && closer) || (fewer == before && kept > model.maximum_boundary_distance && r.distance.relative < kept);
  };
  // Another construction (of `layout`, by default the model's); one that fails leaves a
  // warning and the kept one.
  auto attempt = [&](const std::string& name, const Layout_volume_options& o, const std::string& what,
                     const typename Decomposition::Layout* layout = nullptr) {
    Layout_volume_result r;
    try {
      stage(name, [&] { r = layout_volume(layout ? *layout : model.layout, o); });
    } catch(const Error& e) {
      model.warnings.push_back(what + " failed: " + e.reason() + ": " + e.what());
    }
    return r;
  };
  auto patch_list = [](const std::vector<std::size_t>& patches) {
    std::string list;
    for(std::size_t c : patches) list += (list.empty() ? "" : ", ") + std::to_string(c);
    return list;
  };
  // A part of the shape that the volume misses (internal::part_missing(): a protrusion that
  // one patch covers and its map to the square shrinks, which Cuboid_decomposition's own
  // criterion did not see, e.g. elephant.off's hind leg in a patch that holds a flank too)
  // gets a cube of its own under that patch, the cube's bottom around the farthest mesh
  // point, and the volume is built again; kept if its boundary comes closer to the mesh.
  // Before the other attempts, which all keep the layout.
  for(int round = 0; round < missing_part_cubes && far_from_mesh() && internal::part_missing(model.volume.distance); ++round) {
    const Boundary_distance d = model.volume.distance;
    const int patch = internal::patch_of_face(model.layout, d.farthest_mesh_face);
    if(patch < 0) break;
    // The vertex of the farthest face nearest the farthest point.
    const Eigen::Vector3d x(d.farthest_mesh_point[0], d.farthest_mesh_point[1], d.farthest_mesh_point[2]);
    const auto& mesh = model.layout.mesh;
    typename Decomposition::V nearest;
    double best = std::numeric_limits<double>::infinity();
    for(auto v : vertices_around_face(halfedge(typename Decomposition::Mesh::Face_index(std::uint32_t(d.farthest_mesh_face)), mesh), mesh)) {
      const double dist = (internal::to_eigen_point(mesh.point(v)) - x).norm();
      if(dist < best) best = dist, nearest = v;
    }
    const std::string where = "layout patch " + std::to_string(patch) + " (the mesh point " +
                              internal::triple_text(x.x(), x.y(), x.z()) + " " + internal::short_number(d.mesh_to_spline) +
                              " from the volume)";
    std::optional<typename Decomposition::Layout> extruded;
    stage("missing part cube", [&] { extruded = Decomposition::with_cube_under(model.layout, std::size_t(patch), nearest, d.mesh_bbox_diagonal); });
    if(!extruded) {
      model.warnings.push_back("a cube under " + where + " does not fit in the patch: the missing part stays missing");
      break;
    }
    const Layout_validation validation = extruded->validate();
    if(!validation.is_valid()) {
      model.warnings.push_back("a cube under " + where + " breaks the layout (" + validation.problems.front() + "): not used");
      break;
    }
    Layout_volume_result r =
      attempt("volume construction, missing part cube", volume_options, "the volume with a cube under " + where, &*extruded);
    if(!r.quality_evaluated) break;
    if(!(r.distance.relative < d.relative)) {
      model.warnings.push_back("a cube under " + where + " was tried and left the boundary " +
                               internal::percent_text(r.distance.relative) + " of the diagonal from the mesh: not used");
      break;
    }
    model.warnings.push_back(where + " held a part of the shape that its map to the square shrank: it got a cube of its own, "
                             "and the boundary is " + internal::percent_text(r.distance.relative) +
                             " of the diagonal from the mesh instead of " + internal::percent_text(d.relative));
    model.layout = std::move(*extruded);
    model.layout_validation = validation;
    model.volume = std::move(r);
    ++model.missing_part_cubes;
  }
  std::optional<Layout_volume_result> other; // the construction not chosen, if any
  int other_stretch_rounds = 0;
  // Whether each attempt served its end, kept or not: the finer grids combine those that did.
  bool relaxation_helped = false, stretch_helped = false;
  Layout_volume_options kept_options = volume_options; // those that built model.volume
  // An invalid volume is built again with its surface grids relaxed as one quad mesh
  // (Grid_relaxation.h): that widens sliver patches and unfolds squeezed cells, but moves
  // grid lines off ridges and tips, so it is a second attempt, kept only when it leaves
  // fewer patches uncertified. The finer grids below are relaxed only if it served here.
  Grid_relaxation_options relaxation;
  relaxation.maximum_sweeps = sweeps;
  if(sweeps > 0 && worth_retrying()) {
    Layout_volume_options relaxed = volume_options;
    relaxed.relaxation = relaxation;
    model.relaxation_attempted = true;
    Layout_volume_result r = attempt("volume construction, relaxed grids", relaxed, "relaxing the surface grids");
    const std::size_t before = internal::uncertified_patches(model.volume), after = internal::uncertified_patches(r);
    relaxation_helped = r.quality_evaluated && after <= before;
    if(better_than_kept(r)) {
      model.warnings.push_back("the surface grids were relaxed (" + std::to_string(r.relaxation.sweeps) + " sweeps): " +
                               std::to_string(after) + " patches not certified instead of " + std::to_string(before) +
                               " (before untangling)");
      std::swap(model.volume, r);
      kept_options.relaxation = relaxation;
    } else if(r.quality_evaluated) {
      model.warnings.push_back("relaxed surface grids were tried and kept " + std::to_string(after) +
                               " patches uncertified (" + std::to_string(before) + " without, before untangling): not used");
    }
    if(r.quality_evaluated) other = std::move(r);
  }
  // A boundary far from the mesh is mostly a protrusion that one patch covers and its
  // mean-value map shrinks (a nose, a trunk, a bone's shaft): a uniform grid on the square
  // samples it too sparsely. The volume is built again from stretch-reduced maps
  // (Patch_sampling_options::stretch_rounds), kept on the same terms as the relaxed one.
  // Not for the first construction: on some valid shapes they cost det J
  // (double-torus-example.off is no longer valid at 16 samples).
  if(stretch_rounds > 0 && model.volume.quality_evaluated && far_from_mesh()) {
    Layout_volume_options stretched = volume_options;
    stretched.sampling.stretch_rounds = stretch_rounds;
    model.stretch_attempted = true;
    Layout_volume_result r = attempt("volume construction, stretch-reduced maps", stretched, "stretch-reducing the patch maps");
    stretch_helped = r.quality_evaluated && r.distance.relative < model.volume.distance.relative;
    if(better_than_kept(r)) {
      model.warnings.push_back("the patches' maps were stretch-reduced (" + std::to_string(stretch_rounds) +
                               " rounds): the boundary is " + internal::percent_text(r.distance.relative) +
                               " of the diagonal from the mesh instead of " + internal::percent_text(model.volume.distance.relative) +
                               ", " + std::to_string(internal::uncertified_patches(r)) + " patches not certified instead of " +
                               std::to_string(internal::uncertified_patches(model.volume)) + " (before untangling)");
      other = std::move(model.volume);
      other_stretch_rounds = 0;
      model.volume = std::move(r);
      volume_options.sampling.stretch_rounds = stretch_rounds; // the finer grids too
      model.stretch_rounds = stretch_rounds;
      kept_options = stretched;
    } else if(r.quality_evaluated) {
      model.warnings.push_back("stretch-reduced maps were tried and left the boundary " + internal::percent_text(r.distance.relative) +
                               " of the diagonal from the mesh with " + std::to_string(internal::uncertified_patches(r)) +
                               " patches not certified: not used");
    }
  }
  // The better construction is untangled; if it stays invalid, the other one too, and the
  // one with fewer uncertified patches (its boundary no farther off the mesh) is kept.
  // Untangling moves no control point of a side on the surface (inner ones, and caps' in
  // their tangent planes): a volume whose boundary is too far from the
  // mesh or turns over stays invalid whatever it does. Such a volume is untangled only if no
  // other grid below gives a valid one, for the best invalid result; before, every femur of
  // the population spent 40% of its run untangling its first grid, valid at the second.
  auto too_far = [&](const Layout_volume_result& r) { return !(r.distance.relative <= model.maximum_boundary_distance); };
  auto why_untangling_cannot_validate = [&](const Layout_volume_result& r) -> std::string {
    if(too_far(r))
      return "its boundary is " + internal::percent_text(r.distance.relative) + " of the diagonal from the mesh";
    if(!internal::folded_uncertified_sides(r).empty()) return "a boundary side turns over";
    return "";
  };
  // A boundary side that turns over on an uncertified patch is mostly a face fitted beside a
  // crease: its first row of inner control points, fitted to samples that follow the
  // crease's polygon, crosses the smooth curve fitted along the crease, and no untangling
  // reaches there (the cube with crossing holes of the unseen corpus, where its two holes
  // meet). The faces are fitted again stiffer (bending weight lambda2 = fold_bending_weight,
  // against 1e-6), which keeps that row inside; kept on the same terms as the attempts above,
  // and the other grids follow if it is.
  // Kept only if no side turns over any more: blade.off's first grid has such sides (a thin
  // part's: the verdict is heuristic) and untangles valid, where its stiffer faces, kept for
  // fewer patches uncertified (41 of 105 against 52), did not, and it went down the whole
  // ladder.
  if(fold_bending > kept_options.bending_weight && model.volume.quality_evaluated &&
     !internal::folded_uncertified_sides(model.volume).empty()) {
    Layout_volume_options stiffer = kept_options;
    stiffer.bending_weight = fold_bending;
    model.stiffer_faces_attempted = true;
    Layout_volume_result r = attempt("volume construction, stiffer faces", stiffer, "fitting stiffer faces");
    const std::size_t before = internal::uncertified_patches(model.volume), after = internal::uncertified_patches(r);
    const std::size_t folded = internal::folded_uncertified_sides(r).size();
    if(better_than_kept(r) && folded == 0) { // a valid volume has none: its patches are all certified
      model.warnings.push_back("the faces were fitted stiffer (bending weight " + internal::short_number(fold_bending) +
                               ") where a boundary side turned over: " + std::to_string(after) +
                               " patches not certified instead of " + std::to_string(before) + " (before untangling)");
      model.volume = std::move(r);
      volume_options.bending_weight = fold_bending;
      model.bending_weight = fold_bending;
    } else if(r.quality_evaluated) {
      model.warnings.push_back("stiffer faces (bending weight " + internal::short_number(fold_bending) + ") were tried and kept " +
                               std::to_string(after) + " patches uncertified (" + std::to_string(before) + " without), " +
                               std::to_string(folded) + " with a boundary side turned over: not used");
    }
  }
  const bool first_grid_hopeless = model.volume.quality_evaluated && !why_untangling_cannot_validate(model.volume).empty() &&
                                   (!other || !why_untangling_cannot_validate(*other).empty());
  auto untangle_first_grid = [&] {
    if(!(untangle && worth_retrying())) return;
    stage("volume untangling", [&] { untangle_layout_volume(model.layout, model.volume, volume_options); });
    if(worth_retrying() && other) {
      stage("volume untangling, other grids", [&] { untangle_layout_volume(model.layout, *other, volume_options); });
      const std::size_t kept = internal::uncertified_patches(model.volume), alternative = internal::uncertified_patches(*other);
      if(better_than_kept(*other)) {
        model.warnings.push_back("untangled, the " + std::string(other->relaxation.sweeps > 0 ? "relaxed" : "unrelaxed") +
                                 " surface grids leave " + std::to_string(alternative) + " patches uncertified instead of " +
                                 std::to_string(kept) + ": they are used");
        std::swap(model.volume, *other);
        std::swap(model.stretch_rounds, other_stretch_rounds);
        volume_options.sampling.stretch_rounds = model.stretch_rounds;
      }
    }
  };
  if(!first_grid_hopeless) untangle_first_grid();
  // An invalid volume is rebuilt on another grid, kept only if valid. First on grids twice
  // as fine, up to maximum_grid_resolution (by default one doubling): more samples and spans
  // give the faces and the untangling room (the mushroom's cube is valid at 24 and 32
  // samples per side, not at 16). Then on grids half as fine, down to
  // minimum_grid_resolution (by default one halving, if it leaves 8 or more): fewer spans
  // give smoother cuboids with fewer control points to untangle, which is what the many
  // curved cuboids of high genus need (the genus-5 and genus-6 chains of tori in the test
  // data are valid at 8 samples, not at 16 or 32). A missing part of the shape (femur's
  // shaft) is not retried: no grid brings it back.
  // The other grids combine the attempts above that served their ends: relaxed grids if they
  // left no more patches uncertified, stretch-reduced maps if they brought the boundary
  // closer. 27 of the 30 femurs of population/femur are valid so at 32 samples, none with
  // the plain finer grid; the mushroom at 8 samples, whose relaxed grids leave more patches
  // uncertified, is valid at 16 only unrelaxed.
  const int first_grid = volume_options.sampling.grid_segments;
  // Returns false when the grid could not be built (a stage rejects its grids): the retry is
  // a bonus, the first volume stands.
  auto retry_on_grid = [&](int N, int degree) {
    Layout_volume_options other_grid = volume_options;
    other_grid.sampling.grid_segments = N;
    other_grid.degree = degree;
    if(relaxation_helped) other_grid.relaxation = relaxation;
    // Four times the rounds per doubling: the finer grid follows the opened-up map with its
    // finer faces. Of the 30 femurs, 27 are valid at 32 samples with 12 rounds (S005 and S027
    // within 1.92% and 1.99% of the diagonal), 25 with 6, 21 with 3. A coarser grid keeps
    // the first grid's rounds.
    if(stretch_helped || volume_options.sampling.stretch_rounds > 0) {
      const int ratio = std::max(1, N / first_grid);
      other_grid.sampling.stretch_rounds = stretch_rounds * ratio * ratio;
    }
    model.grid_attempts.push_back(N);
    model.degree_attempts.push_back(degree);
    const bool lower = degree != volume_options.degree;
    const std::string at_degree = lower ? "degree " + std::to_string(degree) + ", " : "";
    // What the warnings call this attempt.
    const std::string what = (lower ? "at " + at_degree : "") + "a grid of " + std::to_string(N) + " samples per patch side";
    Layout_volume_result r = attempt("volume construction, " + at_degree + "grid " + std::to_string(N), other_grid, what);
    if(!r.quality_evaluated) return false;
    // Only a valid volume is kept, so it is untangled only if it can become valid: its
    // boundary, which untangling does not move, is near enough and faces the mesh, and no
    // patch is pinned (the untangler stops when it finds one). Twice the spans give 8 times
    // the control points per patch, so the same budget admits an eighth of the patches.
    std::vector<std::string> reasons = internal::invalidity_reasons(r, model.maximum_boundary_distance);
    std::string not_untangled; // why not, for the warning
    if(untangle && !reasons.empty()) {
      not_untangled = why_untangling_cannot_validate(r);
      if(not_untangled.empty()) {
        other_grid.untangling.stop_when_pinned = true;
        stage("volume untangling, " + at_degree + "grid " + std::to_string(N), [&] { untangle_layout_volume(model.layout, r, other_grid); });
        reasons = internal::invalidity_reasons(r, model.maximum_boundary_distance);
        if(r.untangling.skipped)
          not_untangled = std::to_string(r.untangling.patches.size()) +
                          " patches need it, more than the cost guards allow at this grid";
        else if(r.untangling.rounds == 0 && !r.untangling.pinned_patches.empty())
          not_untangled = "patches " + patch_list(r.untangling.pinned_patches) + " are pinned (det J <= 0 where only the fitted boundary sides set it)";
        else if(r.untangling.rounds == 0 && r.untangling.out_of_budget)
          not_untangled = "the untangling budget is spent";
      }
    }
    if(reasons.empty()) {
      if(lower)
        model.warnings.push_back("the volume is built at degree " + std::to_string(degree) + " on a grid of " + std::to_string(N) +
                                 " samples per patch side: at degree " + std::to_string(volume_options.degree) +
                                 " no grid tried was valid");
      else
        model.warnings.push_back("the volume is built on a grid of " + std::to_string(N) + " samples per patch side: at " +
                                 std::to_string(model.volume.samples.segments) + " it was not valid");
      model.volume = std::move(r);
      model.stretch_rounds = other_grid.sampling.stretch_rounds;
    } else {
      model.warnings.push_back(what + " was tried too and is not valid either (" + internal::comma_list(reasons) + ")" +
                               (not_untangled.empty() ? "" : "; not untangled: " + not_untangled));
    }
    return true;
  };
  for(int N = 2 * first_grid; N <= maximum_grid && worth_retrying(); N *= 2)
    if(!retry_on_grid(N, volume_options.degree)) break;
  // Then the smallest step up: one more span per side (4 more samples; spans are N / 4).
  // Validity is not monotone in the grid: where the first grid's faces miss a spike and the
  // doubled grid's, with twice the spans, fold over a crease, one span more may do neither
  // (mech-holes-shark.off after node relocation: valid at 20 samples, not at 16, 24 or 32).
  if(const int N = first_grid + 4; N <= maximum_grid && N != 2 * first_grid && worth_retrying())
    retry_on_grid(N, volume_options.degree);
  for(int N = first_grid / 2; N >= minimum_grid && worth_retrying(); N /= 2)
    if(!retry_on_grid(N, volume_options.degree)) break;
  // Still invalid: lower degrees, down to minimum_spline_degree, on the first grid and the
  // coarser ones. A lower degree has fewer control points per span and follows the grid's
  // samples more loosely, so its faces bend less where the surface creases (ring5.off: at
  // degree 3 a face in its narrow middle hole turns over at every grid, 8 to 32; quadratic
  // on 8 samples it is valid). Finer grids are not tried again: they did not help above.
  for(int degree = volume_options.degree - 1; degree >= minimum_degree && worth_retrying(); --degree)
    for(int N = first_grid; N >= minimum_grid && worth_retrying(); N /= 2)
      if(!retry_on_grid(N, degree)) break;
  if(first_grid_hopeless && worth_retrying()) { // none was valid
    // A boundary too far from the mesh stays so, but a side found turned over against the
    // mesh is a heuristic verdict: a thin part's side can face away from the nearest mesh
    // face and still bound a valid volume. blade.off is so: untangled here it is valid, and
    // it was not when untangle_invalid_result(false) skipped it. So that verdict is put to the test.
    const bool untangle_here = untangle_invalid || !too_far(model.volume);
    const bool deferred = untangle && untangle_here && other_phases_follow && !model.sphere_chain &&
                          model.layout.layout_class == Layout_class::sphere;
    if(untangling_deferred) *untangling_deferred = deferred;
    if(untangle_here && !deferred)
      untangle_first_grid();
    else if(untangle)
      model.warnings.push_back("not untangled (untangle_invalid_result is false): no untangling makes this volume valid: " +
                               why_untangling_cannot_validate(model.volume));
  }
  for(std::size_t p = 0; p < model.volume.samples.flipped_triangles.size(); ++p)
    if(model.volume.samples.flipped_triangles[p] > 0)
      model.warnings.push_back("patch " + std::to_string(p) + ": " + std::to_string(model.volume.samples.flipped_triangles[p]) +
                               " degenerate or flipped triangles in its map to the square");
  const Volume_untangling_result& u = model.volume.untangling;
  if(u.skipped)
    model.warnings.push_back("untangling skipped: " + std::to_string(u.patches.size()) +
                             " patches would be optimised, more than Volume_untangling_options::maximum_patches or "
                             "maximum_control_points allow");
  else if(u.out_of_budget && u.rounds == 0)
    model.warnings.push_back("not untangled: the untangling budget is spent");
  else if(u.reverted)
    model.warnings.push_back("untangling discarded: it did not raise the smallest det J or cost a patch its certificate");
  else if(!u.patches.empty() && !u.positive_at_samples)
    model.warnings.push_back("untangling left a negative det J (smallest relative det " +
                             std::to_string(u.min_relative_determinant_after) + ", was " +
                             std::to_string(u.min_relative_determinant_before) + ")");
  if(!u.skipped && !u.pinned_patches.empty()) {
    model.warnings.push_back("volume patches " + patch_list(u.pinned_patches) +
                             ": det J <= 0 where only fixed control points (the fitted boundary sides) set it; "
                             "untangling cannot reach there");
  }
  if(model.volume.quality_evaluated && !(model.volume.distance.relative <= model.maximum_boundary_distance))
    model.warnings.push_back(internal::boundary_distance_message(model.layout, model.volume.distance, model.maximum_boundary_distance));
  // Untangling moves no control point of a side on the surface: a fitted face that turns over
  // on an uncertified patch keeps its negative det J whatever it does.
  for(const auto& f : internal::folded_uncertified_sides(model.volume))
    model.warnings.push_back("volume patch " + std::to_string(f.side.patch) + ": its boundary side " + std::to_string(f.side.side) +
                             " turns over (" + std::to_string(f.samples) +
                             " samples face against the mesh); untangling cannot repair it, the fitted surface must change");
  // An invalid volume: corners where a patch is nearly flat or a sliver say why (det J of
  // the face fitted there nearly vanishes, and no inner control point changes that).
  if(!model.is_valid()) {
    const std::vector<std::array<double, 4>> angles = internal::surface_corner_angles(model.layout);
    for(std::size_t p = 0; p < angles.size(); ++p)
      for(int i = 0; i < 4; ++i) {
        const double a = angles[p][std::size_t(i)];
        if(model.layout.patches[p].kind != std::decay_t<decltype(model.layout)>::SURFACE || !internal::is_bad_corner(a)) continue;
        const std::size_t n = model.layout.patches[p].corners[std::size_t(i)];
        const Eigen::Vector3d x = internal::to_eigen_point(model.layout.mesh.point(model.layout.nodes[n]));
        model.warnings.push_back("layout patch " + std::to_string(p) + ": its corner at node " + std::to_string(n) + " " +
                                 internal::triple_text(x.x(), x.y(), x.z()) +
                                 " measures " + internal::short_number(a) + " degrees on the mesh: " +
                                 (a > 180. ? "reflex, so a face fitted to it turns over there"
                                           : std::string(a > 90. ? "nearly flat" : "a sliver") + ", so the face fitted there has det J near 0"));
      }
    // And patches too elongated, at any grid the ladder tries (internal::patch_elongation()):
    // where the strip's long sides differ by a width or more, its grid lines across are
    // sheared nearly along it (internal::patch_side_drift()).
    for(const internal::Layout_strip& s : internal::strip_patches(model.layout))
      model.warnings.push_back("layout patch " + std::to_string(s.patch) + " is a strip " + internal::short_number(s.elongation) +
                               " times as long as it is wide" +
                               (s.drift >= 1. ? ", its long sides differing by " + internal::short_number(s.drift) +
                                                    " widths: sampled at equal fractions of each, its grid is sheared nearly flat and turns over"
                                              : std::string(": a face fitted along it turns over where it bends")));
    // And bands (internal::patch_fill()): no sampling opens their grid cells.
    for(const internal::Layout_band& b : internal::band_patches(model.layout))
      model.warnings.push_back("layout patch " + std::to_string(b.patch) + " is a band: its area is " + internal::short_number(b.fill) +
                               " of its mean length times its mean breadth (its sides run close together, or one nearly vanishes), "
                               "so the cells of any grid on it cover about " + internal::short_number(b.fill) +
                               " of the area their sides would span at right angles, and a face fitted there is likely to turn "
                               "over: no sampling opens them, the layout must change there");
  }
  if(model.volume.quality_evaluated)
    for(std::size_t c = 0; c < model.volume.quality.certified.size(); ++c)
      if(!model.volume.quality.certified[c].certified_positive) {
        // Where: the parameters of the bound's lowest Bernstein coefficient, and that point.
        const Jacobian_bound& b = model.volume.quality.certified[c];
        const Eigen::Vector3d x = model.volume.volume.patch(c).evaluate(b.lower_bound_at);
        model.warnings.push_back("volume patch " + std::to_string(c) + ": det J not certified positive (lower bound " +
                                 std::to_string(b.lower_bound) + " near parameters " +
                                 internal::triple_text(b.lower_bound_at[0], b.lower_bound_at[1], b.lower_bound_at[2]) +
                                 ", the point " + internal::triple_text(x.x(), x.y(), x.z()) + ")");
      }
  model.belt_phase = variant.belt_phase;
  model.corners_off_steps = variant.corners_off_steps;
  return model;
}

/// build_trivariate_model() up to the node relocation retry: the first layout and the
/// variants of its class (belt phases, corners off steps).
template <class TriangleMesh, class NamedParameters>
auto build_with_class_variants(const TriangleMesh& tm, const NamedParameters& np,
                               const std::function<void(const std::string&)>& progress, Untangling_budget& budget)
{
  const int phases = int(option(np, internal_np::belt_phases, 4));
  if(phases < 1 || phases > 8) throw Invalid_input_error("invalid_parameter", "belt_phases must be from 1 to 8");
  const bool untangle_invalid = option(np, internal_np::untangle_invalid_result, true);
  // Which cube corners of a closed genus-0 surface land in hollows or on ridges depends on
  // where the belt's zigzag starts, and validity with it: of the 30 femurs of
  // population/femur, 27 are valid at phase 0, and S014, S018, S027 at 1/8, 1/8, 2/8. Any
  // valid one will do; an invalid result is phase 0's, untangled at the end if asked (so
  // built again, only if its untangling was deferred: the other phases do not need it).
  bool deferred = false;
  internal::Layout_variant first;
  first.sphere_chain = option(np, internal_np::sphere_chain, true);
  first.polycube_map = option(np, internal_np::polycube_map, false);
  auto model = *internal::build_on_layout(tm, np, progress, budget, first, untangle_invalid, phases > 1, nullptr, &deferred);
  if(model.is_valid()) return model;
  // A long closed genus-0 surface laid out as a chain of cuboids whose volume is not valid:
  // one cube is tried too, at its belt phases, and kept if valid; else the chain's volume
  // (untangled: build_on_layout() defers a cube's only) is the result. It fits a long shape
  // better: femur.off with its noise handles closed, 9 of 52 patches uncertified and 3.6% of
  // the diagonal off, against 9 of 22 and 20.9% as one cube.
  std::optional<std::decay_t<decltype(model)>> chain;
  std::vector<std::pair<std::string, double>> seconds;
  std::vector<std::string> tried;
  internal::Layout_variant cube;
  cube.sphere_chain = false;
  auto cube_instead_of_chain = [&] {
    return "laid out as one cube: as a chain of " + std::to_string(chain->layout.cuboids.size()) +
           " cuboids the volume was not valid (" + internal::comma_list(chain->invalidity_reasons()) + ")";
  };
  auto chain_result = [&] {
    chain->warnings.push_back("one cube was tried too (belt phases " + internal::comma_list(tried) + ") and gave no valid volume");
    chain->stage_seconds = std::move(seconds);
    return std::move(*chain);
  };
  if(model.sphere_chain) {
    internal::append_stage_seconds(seconds, model.stage_seconds, ", chain");
    chain = std::move(model);
    model = *internal::build_on_layout(tm, np, progress, budget, cube, false, false, nullptr);
    tried.push_back("0");
    if(model.is_valid()) {
      model.warnings.insert(model.warnings.begin(), cube_instead_of_chain());
      seconds.insert(seconds.end(), model.stage_seconds.begin(), model.stage_seconds.end());
      model.stage_seconds = std::move(seconds);
      return model;
    }
    if(phases == 1) {
      internal::append_stage_seconds(seconds, model.stage_seconds, ", belt phase 0");
      return chain_result();
    }
  }
  const auto phase0_nodes = internal::node_points(model.layout);
  // A tube cut at two heights: the seam ends, and a corner with them, at a step's end, whose
  // side turns at once along the step. Off the steps, an elliptic tube 10 by 2 whose ends
  // are stepped by 3 is valid at 16 samples; there, at no grid. Not the first try: blade.off
  // (stepped ends, knife edges) is then further from valid (65 of 105 patches uncertified
  // before untangling at the first grid, against 52).
  if(model.layout.layout_class == Layout_class::cylinder && option(np, internal_np::step_retry, true)) {
    internal::Layout_variant off_steps;
    off_steps.corners_off_steps = true;
    auto other = internal::build_on_layout(tm, np, progress, budget, off_steps, false, false, &phase0_nodes);
    if(!other) return model; // no corner near a step
    if(other->is_valid()) {
      other->warnings.insert(other->warnings.begin(), "the cylinder's section corners are moved off the steps of its cut ends: "
                                                      "with them there the volume was not valid (" +
                                                        internal::comma_list(model.invalidity_reasons()) + ")");
      std::vector<std::pair<std::string, double>> seconds = model.stage_seconds;
      internal::append_stage_seconds(seconds, other->stage_seconds, ", corners off steps");
      other->stage_seconds = std::move(seconds);
      return std::move(*other);
    }
    internal::append_stage_seconds(model.stage_seconds, other->stage_seconds, ", corners off steps");
    model.warnings.push_back("section corners moved off the steps of the cut ends were tried too and gave no valid volume");
    return model;
  }
  if(model.layout.layout_class != Layout_class::sphere || phases == 1) return model;
  internal::append_stage_seconds(seconds, model.stage_seconds, ", belt phase 0");
  for(int k = 1; k < phases; ++k) {
    const std::string phase = std::to_string(k) + "/8";
    internal::Layout_variant at_phase = cube;
    at_phase.belt_phase = k / 8.;
    auto other = internal::build_on_layout(tm, np, progress, budget, at_phase, false, false, &phase0_nodes);
    if(!other) break; // the same layout at every phase
    tried.push_back(phase);
    if(other->is_valid()) {
      const std::string why = internal::comma_list(model.invalidity_reasons());
      if(chain)
        other->warnings.insert(other->warnings.begin(), cube_instead_of_chain());
      other->warnings.insert(other->warnings.begin(), "the layout's belt nodes are moved by " + phase +
                                                         " of the zigzag's period: " +
                                                         (k > 1 ? "at phases 0 to " + std::to_string(k - 1) + "/8 no volume"
                                                                : std::string("at phase 0 the volume")) +
                                                         " was valid (phase 0: " + why + ")");
      seconds.insert(seconds.end(), other->stage_seconds.begin(), other->stage_seconds.end());
      other->stage_seconds = std::move(seconds);
      return std::move(*other);
    }
    internal::append_stage_seconds(seconds, other->stage_seconds, ", belt phase " + phase);
  }
  if(chain) return chain_result();
  if(deferred) { // phase 0 again, untangled; its first build's seconds are already listed
    model = *internal::build_on_layout(tm, np, progress, budget, cube, true, false, nullptr);
    internal::append_stage_seconds(seconds, model.stage_seconds, ", belt phase 0, untangled");
  }
  if(!tried.empty())
    model.warnings.push_back("belt phases " + internal::comma_list(tried) + " of the zigzag's period were tried too and gave no valid volume");
  model.stage_seconds = std::move(seconds);
  return model;
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// Runs the whole chain. `progress`, when set, is told the name of each stage as it starts.
/// Named parameters: those of Surface_topology, Pants_decomposition, Cuboid_decomposition
/// and layout_volume() (grid_resolution, spline_degree, number_of_spans, boundary_layer
/// (default 0.25 here; 0 for one volume patch per cuboid), maximum_cuboid_aspect (2 here),
/// untangle_volume (true here), ...), `maximum_refinements` (the cuboid stage's, default 2),
/// `maximum_boundary_distance` (0.02: the model is
/// not valid when its boundary is farther from the mesh than this fraction of the mesh's
/// bounding-box diagonal) and `maximum_grid_resolution` (twice grid_resolution: an invalid
/// volume is rebuilt on grids twice as fine up to this, then on one with 4 more samples
/// (one more span) if this allows it; equal to grid_resolution, never) and
/// `minimum_grid_resolution` (half grid_resolution if that is 8 or more, else
/// grid_resolution: a volume still invalid is then rebuilt on grids half as fine down to this).
/// `minimum_spline_degree` (2, or spline_degree if lower): a volume still invalid is then
/// rebuilt at each lower degree down to this, on the first grid and the coarser ones down to
/// `minimum_grid_resolution`; equal to spline_degree, never. `degree_attempts` and
/// `volume.degree` say which degree was kept.
/// `grid_relaxation_sweeps` (100) and `stretch_rounds` (3) are those of the second and third
/// attempts: relaxed surface grids when the first volume is invalid, stretch-reduced patch
/// maps when the volume is then too far from the mesh (0: no such attempt);
/// `fold_bending_weight` (1e-4) that of a fourth: the faces fitted with this bending weight
/// (lambda2, 1e-6 otherwise) when a boundary side of an uncertified patch still turns over
/// (not above the fitting's own weight: no such attempt). The finer grids
/// combine those of the two that served their ends (the stretch with four times the rounds
/// per doubling). `untangle_invalid_result` (true): when no grid gives a valid volume and the
/// first one cannot become valid by untangling (boundary too far or turned over), untangle it
/// all the same, for the best invalid result; false returns it as built, sooner, when its
/// boundary is too far from the mesh (the CLI does so unless `--allow-invalid`, since it
/// writes no invalid volume); a side turned over is a heuristic verdict, and it is untangled.
/// `sphere_chain` (true): a closed genus-0 surface long enough for three cube-like cuboids or
/// more is laid out as a chain of them between caps at its two ends (Cuboid_decomposition's
/// `sphere_chain`); if its volume is not valid, one cube is built too, at its belt phases, and
/// kept if valid, else the chain's volume is the result; false: one cube.
/// `orthogonal_blocks` (true): a closed CAD block whose faces are all planar and perpendicular
/// to three axes (an L, a T, a U, a frame), other than a box, is laid out as the boxes between
/// its faces' planes (Cuboid_decomposition's `orthogonal_blocks`); false: by its genus.
/// `polycube_map` (false): lay a closed surface out on the boxes of a polycube map of it
/// (Cuboid_decomposition's `polycube_map`) from the start. `polycube_retry` (true): a closed
/// surface whose layouts above give no valid volume (nor blocks) is built again on a polycube
/// map's boxes, which follow a CAD part's round holes and fillets, and that volume is kept if
/// valid (`t_block_filleted.off`, a T with filleted edges: 5 of 42 patches uncertified and
/// 2.54% of the diagonal off as a chain of 6, valid on 4 boxes at 0.37%); `polycube_retried`
/// of the model says it was tried.
/// `polycube_first_alignment` (0.95): a closed surface that is not a CAD block and whose
/// normals align with three axes at least this much (Cuboid_decomposition::polycube_alignment():
/// the filleted T 0.96, the plate with two round holes 0.99, organic shapes 0.83 to 0.92) is
/// laid out on its polycube map first, and that volume is kept if valid; otherwise the
/// layouts above follow and the retry is not made again. Above 1: never; `polycube_first` of
/// the model says it was tried.
/// `belt_phases` (4, at most 8): a closed genus-0 surface whose volume is not valid is built
/// again on layouts whose belt nodes are moved by 1/8, 2/8, ... of the zigzag's period
/// (Cuboid_decomposition's `belt_phase`), and the first valid one is kept; 1: never.
/// `step_retry` (true): a cylinder whose volume is not valid is built again with its section
/// corners moved off the steps of its cut ends (`corners_off_steps`), when that moves any,
/// and that volume is kept if it is valid.
/// `arc_relaxation_sweeps` (0): sweeps of relax_layout_arcs() on every layout before its
/// volume is built (Layout_arc_relaxation.h): corners nearer right angles (anchor.off: mean
/// deviation 42 -> 33 degrees at 3 sweeps), so far without a volume that becomes valid.
/// `polycube_arc_relaxation_sweeps` (3): the same on a layout of a polycube map, whose arcs
/// follow its charts' borders and zigzag on curved faces (at least `arc_relaxation_sweeps`);
/// plate_two_round_holes.off remeshed: the volume on its 13 boxes becomes valid.
/// `node_relocation_sweeps` (0): sweeps of relocate_layout_nodes() on every layout before its
/// volume is built, and before the arc relaxation (Layout_node_relocation.h): nodes moved in
/// the union of their patches, or along their hole's rim, where their corners come nearer
/// right angles (mean deviation joint.off 52 -> 31 degrees, mech-holes-shark.off 36 -> 21).
/// `node_relocation_retry` (2): when node_relocation_sweeps is 0 and no volume above is
/// valid, the first layout is built again with this many sweeps of node relocation, through
/// the same grids and degrees, and kept if its volume is valid (mech-holes-shark.off: valid
/// at 20 samples); 0: never. `relocation_retried` of the model says it was tried.
/// `cuts_away_retry` (true): a closed surface of genus 2 or more whose volume is not valid on
/// any layout above is built again on pants whose cuts keep away from the holes
/// (Pants_decomposition's `cuts_away_from_holes`, which this function passes on as well), and
/// that volume is kept if valid, else it competes for the nearest to valid (the five-spoke
/// wheel of the benchmark corpus: valid this way); `cuts_away_retried` of the model says it
/// was tried.
/// `missing_part_cubes` (2): when the first volume misses a part of the shape (a mesh point
/// far from it while all of it is near the mesh: a protrusion that a patch's map to the
/// square shrinks), that patch gets a cube of its own, its bottom around the farthest point
/// (Cuboid_decomposition::with_cube_under()), and the volume is built again; kept if its
/// boundary comes closer, up to this many times; 0: never. `missing_part_cubes` of the
/// model counts those kept.
/// `untangling_budget` (default_untangling_budget, 1e10): the Jacobian samples that every
/// untangling of the run, retries included, may visit in all (Untangling_budget); once they
/// are spent, the untangling stops, the model says so (`untangling_budget_exhausted`, a
/// warning) and `untangling_work` counts them. Must be positive; infinity: no limit.
/// Throws the stages' errors; an invalid layout becomes Internal_error("invalid_layout").
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
auto build_trivariate_model(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values(),
                            const std::function<void(const std::string&)>& progress = {})
{
  const int retry_sweeps = int(option(np, internal_np::node_relocation_retry, 2));
  if(retry_sweeps < 0) throw Invalid_input_error("invalid_parameter", "node_relocation_retry must not be negative");
  Untangling_budget budget;
  budget.limit = option(np, internal_np::untangling_budget, default_untangling_budget);
  if(!(budget.limit > 0.)) throw Invalid_input_error("invalid_parameter", "untangling_budget must be positive");
  auto finished = [&budget](auto& m) {
    m.untangling_work = budget.spent;
    m.untangling_budget_exhausted = budget.exhausted();
    if(m.untangling_budget_exhausted && !m.is_valid())
      m.warnings.push_back("the untangling stopped when its budget was spent (" + internal::short_number(budget.spent) +
                           " Jacobian samples visited, untangling_budget " + internal::short_number(budget.limit) +
                           "): a larger one lets it go on, at that cost");
    return std::move(m);
  };
  using Model = std::decay_t<decltype(*internal::build_on_layout(tm, np, progress, budget, internal::Layout_variant(), false, false, nullptr))>;
  // The layout on the boxes of a polycube map, tried first or retried below.
  internal::Layout_variant on_polycube;
  on_polycube.polycube_map = true;
  on_polycube.sphere_chain = false;
  // The volume on the boxes of a polycube map; empty, with the reason, when it makes none.
  auto on_polycube_map = [&](std::string& failure) {
    std::optional<Model> result;
    try {
      result = internal::build_on_layout(tm, np, progress, budget, on_polycube, false, false, nullptr);
    } catch(const Error& e) {
      failure = e.reason() + ": " + e.what();
    }
    return result;
  };
  const bool closed = CGAL::is_closed(tm);
  const bool polycube_given = option(np, internal_np::polycube_map, false);
  // A CAD part with fillets, round holes or slanted faces (its faces mostly along three axes,
  // not all: a CAD block has its own boxes) is laid out on its polycube map first. Its
  // harmonic layouts cross those faces, and on the shipped filleted T and plate with two
  // round holes they were invalid after minutes of retries, where the polycube's boxes are
  // valid at once. Organic shapes (alignment 0.83 to 0.92) never try it first.
  const double first_alignment = option(np, internal_np::polycube_first_alignment, 0.95);
  if(!(first_alignment >= 0.)) throw Invalid_input_error("invalid_parameter", "polycube_first_alignment must not be negative or NaN");
  std::optional<Model> polycube_attempt; // the polycube map's volume, tried first or retried, not valid
  std::string polycube_failure;
  // What the run's other layouts gave (the polycube map tried first or again, the nodes
  // relocated): said by the genus layout's model and, when another attempt is kept, by it.
  std::vector<std::string> run_record;
  if(closed && !polycube_given && first_alignment <= 1.) {
    const auto [alignment, axis_aligned] = Cuboid_decomposition<TriangleMesh>::polycube_alignment(tm);
    if(!axis_aligned && alignment >= first_alignment) {
      std::optional<Model> first = on_polycube_map(polycube_failure);
      if(first && first->is_valid()) {
        first->polycube_first = true;
        first->warnings.insert(first->warnings.begin(), "laid out on a polycube map (" + std::to_string(first->layout.cuboids.size()) +
                                                          " boxes) first: its faces' alignment with three axes is " +
                                                          internal::short_number(alignment) + ", at least polycube_first_alignment " +
                                                          internal::short_number(first_alignment));
        return finished(*first);
      }
      polycube_attempt = std::move(first); // empty only when it threw: polycube_failure says why
    }
  }
  auto model = internal::build_with_class_variants(tm, np, progress, budget);
  // When no attempt is valid the result is the one nearest a valid volume (nearer_valid()):
  // the genus layout's, unless the polycube map's or the relocated nodes' is (a cube with
  // crossing round holes: its pants layout left 13 of 76 patches uncertified and 2.35% off,
  // its polycube map's boxes 2 of 112, 1.61%), with the whole run's record and its own
  // diagnostics, which name its own patches.
  // The retries' volumes that are not valid (below).
  std::optional<Model> relocated, away, away_relocated;
  auto nearest_attempt = [&] {
    Model* kept = &model;
    const std::string genus_layout = "the " + std::string(layout_class_name(model.layout.layout_class)) + " layout";
    std::string kept_name = genus_layout;
    auto address = [](std::optional<Model>& m) { return m ? &*m : nullptr; };
    const std::pair<Model*, std::string> alternatives[] = {
      {address(polycube_attempt), "the polycube map's boxes"},
      {address(relocated), genus_layout + " with its nodes relocated"},
      {address(away), genus_layout + " with the pants cut away from the holes"},
      {address(away_relocated), genus_layout + " with the pants cut away from the holes and its nodes relocated"}};
    for(const auto& [alternative, name] : alternatives)
      if(alternative && internal::nearer_valid(alternative->volume, kept->volume, model.maximum_boundary_distance))
        kept = alternative, kept_name = name;
    if(kept == &model) return finished(model);
    kept->stage_seconds = model.stage_seconds;
    kept->polycube_first = model.polycube_first;
    kept->polycube_retried = model.polycube_retried;
    kept->relocation_retried = model.relocation_retried;
    kept->cuts_away_retried = model.cuts_away_retried;
    kept->warnings.insert(kept->warnings.begin(), run_record.begin(), run_record.end());
    kept->warnings.insert(kept->warnings.begin(), "no attempt gave a valid volume; the one kept is the nearest to valid, on " + kept_name +
                                                      " (" + internal::volume_shortfall(kept->volume) + "); on " + genus_layout + ": " +
                                                      internal::volume_shortfall(model.volume));
    return finished(*kept);
  };
  if(polycube_attempt || !polycube_failure.empty()) {
    model.polycube_first = true;
    if(polycube_attempt) {
      internal::prepend_stage_seconds(model.stage_seconds, polycube_attempt->stage_seconds, ", polycube map first");
      run_record.push_back("a layout on a polycube map (" + std::to_string(polycube_attempt->layout.cuboids.size()) +
                           " boxes) was tried first and gave no valid volume (" +
                           internal::comma_list(polycube_attempt->invalidity_reasons()) + ")");
    } else
      run_record.push_back("a layout on a polycube map was tried first and failed: " + polycube_failure);
    model.warnings.insert(model.warnings.begin(), run_record.back());
  }
  if(model.is_valid()) return finished(model);
  // One more layout after those above gave no valid volume: returned if its volume is valid,
  // its first warning saying what it changed and why; otherwise the run's record says what it
  // gave (so does a retry that throws) and `invalid` holds it for nearest_attempt().
  struct Retry_words
  {
    std::function<std::string(const Model&)> figures; // of the layout built
    std::string tried, valid, before, nothing, failed, own_suffix, suffix;
    std::string tried_verb = "were"; // "was" after a singular `tried`
  };
  using Nodes = std::decay_t<decltype(internal::node_points(model.layout))>;
  auto retry = [&](const internal::Layout_variant& variant, const Nodes* unless_nodes,
                   const Retry_words& words, std::optional<Model>& invalid) -> std::optional<Model> {
    std::optional<Model> other;
    try {
      other = internal::build_on_layout(tm, np, progress, budget, variant, false, false, unless_nodes);
      if(!other) model.warnings.push_back(words.nothing);
    } catch(const Error& e) {
      run_record.push_back(words.failed + ": " + e.reason() + ": " + e.what());
      model.warnings.push_back(run_record.back());
    }
    if(!other) return std::nullopt;
    if(other->is_valid()) {
      other->polycube_retried = model.polycube_retried;
      other->relocation_retried = model.relocation_retried;
      other->cuts_away_retried = model.cuts_away_retried;
      other->warnings.insert(other->warnings.begin(), words.valid + " (" + words.figures(*other) + "): " + words.before + " (" +
                                                        internal::comma_list(model.invalidity_reasons()) + ")");
      internal::prepend_stage_seconds(other->stage_seconds, model.stage_seconds, words.own_suffix);
      return other;
    }
    internal::append_stage_seconds(model.stage_seconds, other->stage_seconds, words.suffix);
    run_record.push_back(words.tried + " (" + words.figures(*other) + ") " + words.tried_verb + " tried too and gave no valid volume (" +
                         internal::comma_list(other->invalidity_reasons()) + ")");
    model.warnings.push_back(run_record.back());
    invalid = std::move(other);
    return std::nullopt;
  };
  auto boxes = [](const Model& m) { return std::to_string(m.layout.cuboids.size()) + " boxes"; };
  auto moves = [](const Model& m) { return std::to_string(m.node_relocation.nodes_moved) + " moves"; };
  auto cuboids = [](const Model& m) { return std::to_string(m.layout.cuboids.size()) + " cuboids"; };
  // A closed surface whose layout crosses the shape's own directions (a CAD part's round
  // holes, fillets and slanted faces under harmonic cuts) may be valid on the boxes of a
  // polycube map, which follow them.
  if(option(np, internal_np::polycube_retry, true) && !polycube_given && !model.polycube_first &&
     model.layout.layout_class != Layout_class::blocks && closed) {
    model.polycube_retried = true;
    const std::string layout_name = layout_class_name(model.layout.layout_class);
    // build_on_layout() gives none for relocation variants alone: `nothing` is never said.
    Retry_words words{boxes, "a layout on a polycube map", "laid out on a polycube map",
                      "the " + layout_name + " layout's volume was not valid", "",
                      "a layout on a polycube map was tried too and failed", ", " + layout_name, ", polycube map"};
    words.tried_verb = "was";
    if(auto valid = retry(on_polycube, nullptr, words, polycube_attempt)) return finished(*valid);
  }
  // The decomposition puts nodes where the harmonic cuts and the conformal map say, blind to
  // the corners they make; a node amid a flat face or a spoke along a rim folds a face
  // (mech-holes-shark.off: 8 of 38 patches uncertified on its own nodes; relocated, valid).
  // After the polycube map, since it moves the nodes of layouts that are valid as they are
  // (blade.off's rim corners sit off the steps of its cut ends on purpose).
  const bool relocate = retry_sweeps > 0 && option(np, internal_np::node_relocation_sweeps, 0) == 0;
  if(relocate) {
    model.relocation_retried = true;
    internal::Layout_variant variant;
    variant.node_relocation_sweeps = retry_sweeps;
    variant.sphere_chain = model.sphere_chain;
    const Retry_words words{moves, "the layout's nodes relocated", "the layout's nodes are relocated",
                            "on the decomposition's own nodes the volume was not valid",
                            "node relocation was tried too and moved no node", "relocating the layout's nodes failed",
                            ", own nodes", ", nodes relocated"};
    if(auto valid = retry(variant, nullptr, words, relocated)) return finished(*valid);
  }
  // Last, a closed surface's pants traced again with their cuts away from the holes
  // (Pants_decomposition's `cuts_away_from_holes`), and that layout's nodes relocated: through
  // the middle of a CAD wheel's spokes and rim rather than beside its junctions. Not first:
  // on smooth shapes those cuts are longer and the volumes worse and slower to certify.
  if(option(np, internal_np::cuts_away_retry, true) && closed && model.layout.layout_class == Layout_class::pants &&
     !option(np, internal_np::cuts_away_from_holes, false)) {
    model.cuts_away_retried = true;
    internal::Layout_variant variant;
    variant.cuts_away_from_holes = true;
    // Nothing is built again when the cuts are where they were (3torus.off).
    const auto own_nodes = internal::node_points(model.layout);
    const Retry_words words{cuboids, "the pants cut away from the holes", "the pants are cut away from the holes",
                            "with the shortest cuts the volume was not valid",
                            "the pants cut away from the holes were tried too and gave the same layout",
                            "cutting the pants away from the holes failed", ", shortest cuts", ", cuts away from holes"};
    if(auto valid = retry(variant, &own_nodes, words, away)) return finished(*valid);
    if(away && relocate) {
      variant.node_relocation_sweeps = retry_sweeps;
      const Retry_words relocated_words{moves, "the pants cut away from the holes with their nodes relocated",
                                        "the pants are cut away from the holes and the layout's nodes relocated",
                                        "with the shortest cuts the volume was not valid",
                                        "the pants cut away from the holes with their nodes relocated were tried too and moved no node",
                                        "relocating the nodes of the pants cut away from the holes failed", ", shortest cuts",
                                        ", cuts away from holes, nodes relocated"};
      if(auto valid = retry(variant, nullptr, relocated_words, away_relocated)) return finished(*valid);
    }
  }
  return nearest_attempt();
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_H
