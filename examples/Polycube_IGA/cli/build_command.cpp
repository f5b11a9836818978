// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `polycube_iga build MESH -o OUT.xml [--vtu OUT.vtu] [--layout-vtu L.vtu]
//                  [--layout-json L.json] [--report R.json] [--grid N] [--degree P]`:
// the whole chain, mesh to multipatch B-spline volume (G+Smo XML). When some patch's
// Jacobian is not certified positive, or the boundary is farther from the mesh than
// --max-distance, the volume files are not written (exit 1, reason nonpositive_jacobian or
// boundary_distance) unless --allow-invalid; the report is always written.

#include "arguments.h"
#include "command_registry.h"
#include "mesh_input.h"

#include <CGAL/Polycube_IGA/IO/gismo_xml.h>
#include <CGAL/Polycube_IGA/IO/layout_json.h>
#include <CGAL/Polycube_IGA/IO/layout_vtk.h>
#include <CGAL/Polycube_IGA/IO/vtu.h>
#include <CGAL/Polycube_IGA/Small_handle_removal.h>
#include <CGAL/Polycube_IGA/internal/atomic_file.h>
#include <CGAL/Polycube_IGA/internal/json_writer.h>
#include <CGAL/polycube_iga.h>

#include <array>
#include <algorithm>
#include <chrono>
#include <optional>
#include <iostream>
#include <limits>
#include <unistd.h>

namespace polycube_iga_cli {
namespace {

namespace PI = CGAL::Polycube_IGA;

int positive_option(const Parsed_arguments& a, const std::string& name, int fallback, int lo, int hi)
{
  if(!a.has(name)) return fallback;
  const std::string text = a.get(name);
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if(end == text.c_str() || *end != '\0' || v < lo || v > hi)
    throw PI::Invalid_input_error("bad_arguments", name + " expects an integer in [" + std::to_string(lo) + ", " +
                                                     std::to_string(hi) + "], got '" + text + "'");
  return int(v);
}

double fraction_option(const Parsed_arguments& a, const std::string& name, double fallback, double lo, double hi)
{
  if(!a.has(name)) return fallback;
  const std::string text = a.get(name);
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if(end == text.c_str() || *end != '\0' || !(v >= lo && v < hi))
    throw PI::Invalid_input_error("bad_arguments", name + " expects a number in [" + std::to_string(lo) + ", " +
                                                     std::to_string(hi) + "), got '" + text + "'");
  return v;
}

/// What closing small handles did before the build (Small_handle_removal), and the volume's
/// distance to the mesh as read (the build measures it to the closed one).
struct Handle_closing
{
  bool ran = false;  ///< --small-handle-length > 0; otherwise the mesh built is the mesh read
  PI::Small_handle_removal_result result;
  std::optional<PI::Boundary_distance> to_input;
  /// The stage's own warnings, and a hint when a kept handle is that small and the volume invalid.
  std::vector<std::string> warnings;
  bool too_far(double max_distance) const { return to_input && to_input->relative > max_distance; }
};

/// `reasons`: why the volume is not valid (the model's, and the distance to the mesh as read).
template <class Model>
void write_report(const std::string& path, const Input_mesh& in, const Model& model, const Handle_closing& closing,
                  const std::vector<std::string>& reasons, double read_seconds, bool written)
{
  PI::internal::write_file_atomically(path, [&](std::ostream& os) {
    const auto& L = model.layout;
    const auto& V = model.volume;
    PI::internal::Json_writer w(os);
    w.begin_object()
      .member("input_vertices", num_vertices(in.mesh))
      .member("input_faces", num_faces(in.mesh))
      .member("genus", L.genus)
      .member("input_genus", closing.ran ? closing.result.genus_before : L.genus)
      .member("boundary_loops", L.boundary_loops)
      .member("layout_class", PI::layout_class_name(L.layout_class))
      .member("pants", L.number_of_pants)
      .member("cuboids", L.cuboids.size())
      .member("patches", V.volume.number_of_patches())
      .member("layout_patches", L.patches.size())
      .member("surface_patches", L.number_of_surface_patches())
      .member("layout_nodes", L.nodes.size())
      .member("layout_arcs", L.arcs.size())
      .member("grid", V.samples.segments)
      .member("degree", V.degree)
      .member("spans", V.spans)
      .member("boundary_layer", !V.slab_of.empty())
      .member("untangled_patches", V.untangling.skipped ? 0 : V.untangling.patches.size())
      .member("untangling_skipped", V.untangling.skipped)
      .member("untangling_reverted", V.untangling.reverted)
      .member("untangling_min_relative_det_before", V.untangling.min_relative_determinant_before)
      .member("untangling_min_relative_det_after", V.untangling.min_relative_determinant_after)
      .member("untangling_pinned_patches", V.untangling.pinned_patches.size())
      .member("untangling_passes", V.untangling.passes)
      .member("untangling_stalled", V.untangling.stalled)
      .member("untangling_sliding_points", V.untangling.sliding_points)
      .member("untangling_focused_samples", V.untangling.focused_samples)
      .member("untangling_work", model.untangling_work)
      .member("untangling_budget_exhausted", model.untangling_budget_exhausted)
      .member("relaxation_attempted", model.relaxation_attempted)
      .member("relaxed_grids", V.relaxation.sweeps > 0)
      .member("stretch_attempted", model.stretch_attempted)
      .member("stretch_rounds", model.stretch_rounds)
      .member("stiffer_faces_attempted", model.stiffer_faces_attempted)
      .member("bending_weight", model.bending_weight)
      .member("belt_phase", model.belt_phase)
      .member("sphere_chain", model.sphere_chain)
      .member("corners_off_steps", model.corners_off_steps)
      .member("arcs_relaxed", model.arc_relaxation.arcs_moved)
      .member("nodes_relocated", model.node_relocation.nodes_moved)
      .member("relocation_retried", model.relocation_retried)
      .member("polycube_retried", model.polycube_retried)
      .member("cuts_away_retried", model.cuts_away_retried)
      .member("polycube_first", model.polycube_first)
      .member("relaxation_sweeps", V.relaxation.sweeps)
      .member("relaxation_last_move", V.relaxation.last_move)
      .member("valid", reasons.empty())
      .member("volume_written", written);
    const PI::internal::Layout_corner_statistics corners = PI::internal::layout_corner_statistics(L);
    w.key("layout_corners").begin_object()
      .member("corners", corners.corners)
      .member("mean_deviation_degrees", corners.mean_deviation)
      .member("max_deviation_degrees", corners.max_deviation)
      .member("slivers", corners.slivers)
      .member("nearly_flat", corners.nearly_flat)
      .member("reflex", corners.reflex)
      .end_object();
    // Every corner the statistics count as a sliver, nearly flat or reflex, by patch and
    // node: where a user (or the next stage's author) looks first when det J is not positive.
    w.key("bad_corners").begin_array();
    const std::vector<std::array<double, 4>> angles = PI::internal::surface_corner_angles(L);
    for(std::size_t p = 0; p < angles.size(); ++p)
      for(std::size_t i = 0; i < 4; ++i)
        if(L.patches[p].kind == std::decay_t<decltype(L)>::SURFACE && PI::internal::is_bad_corner(angles[p][i]))
          w.begin_object().member("patch", p).member("node", L.patches[p].corners[i]).member("degrees", angles[p][i]).end_object();
    w.end_array();
    // Surface patches longer than internal::strip_elongation times their width, and by how
    // many widths their long sides differ (their grids shear by as much).
    w.key("strip_patches").begin_array();
    for(const auto& s : PI::internal::strip_patches(L))
      w.begin_object().member("patch", s.patch).member("elongation", s.elongation).member("drift", s.drift).end_object();
    w.end_array();
    // Surface patches whose area is under internal::band_fill of their length times breadth:
    // their grid cells are squeezed whatever the sampling.
    w.key("band_patches").begin_array();
    for(const auto& b : PI::internal::band_patches(L))
      w.begin_object().member("patch", b.patch).member("fill", b.fill).member("elongation", b.elongation).end_object();
    w.end_array();
    w.key("grid_attempts").begin_array();
    for(int g : model.grid_attempts) w.value(g);
    w.end_array();
    w.key("missing_part_cubes").value(model.missing_part_cubes);
    w.key("degree_attempts").begin_array();
    for(int d : model.degree_attempts) w.value(d);
    w.end_array();
    w.key("invalidity_reasons").begin_array();
    for(const auto& r : reasons) w.value(r);
    w.end_array();
    w.key("patch_quality").begin_array();
    for(std::size_t c = 0; c < V.quality.sampled.size(); ++c) {
      const auto& s = V.quality.sampled[c];
      const auto& b = V.quality.certified[c];
      w.begin_object()
        .member("patch", c)
        .member("core_of_cuboid", V.core_of.empty() ? long(c) : V.core_of[c])
        .member("slab_of_surface_patch", V.slab_of.empty() ? -1L : V.slab_of[c])
        .member("min_scaled_jacobian", s.min_scaled_jacobian)
        .member("mean_scaled_jacobian", s.mean_scaled_jacobian)
        .member("min_sampled_jacobian", s.min_determinant)
        .member("certified_jacobian_lower_bound", b.lower_bound)
        .member("certified_positive", b.certified_positive)
        .end_object();
    }
    w.end_array();
    w.key("hausdorff").begin_object()
      .member("absolute", V.distance.hausdorff)
      .member("relative_to_bbox_diagonal", V.distance.relative)
      .member("spline_to_mesh", V.distance.spline_to_mesh)
      .member("mesh_to_spline", V.distance.mesh_to_spline)
      .member("bbox_diagonal", V.distance.mesh_bbox_diagonal)
      .member("maximum_relative", model.maximum_boundary_distance);
    auto point = [&](const char* name, const std::array<double, 3>& p) {
      w.key(name).begin_array().value(p[0]).value(p[1]).value(p[2]).end_array();
    };
    point("farthest_mesh_point", V.distance.farthest_mesh_point);
    point("farthest_spline_point", V.distance.farthest_spline_point);
    w.end_object();
    w.key("small_handles_closed").begin_array();
    for(const auto& h : closing.result.closed) {
      w.begin_object().member("loop", h.loop_kind).member("length", h.length).member("relative_to_bbox_diagonal", h.relative)
        .member("loop_edges", h.loop_edges);
      point("near", h.point);
      w.end_object();
    }
    w.end_array();
    if(closing.to_input)
      w.key("hausdorff_to_input").begin_object()
        .member("absolute", closing.to_input->hausdorff)
        .member("relative_to_bbox_diagonal", closing.to_input->relative)
        .end_object();
    w.key("folded_boundary_sides").begin_array();
    for(const auto& f : V.distance.folded_sides)
      w.begin_object().member("patch", f.side.patch).member("side", f.side.side).member("samples", f.samples).end_object();
    w.end_array();
    w.key("interfaces").begin_object()
      .member("count", V.volume.interfaces().size())
      .member("max_gap", V.quality.interfaces.max_gap)
      .end_object();
    w.key("stage_seconds").begin_object().member("read_and_validate", read_seconds);
    for(const auto& st : model.stage_seconds) w.member(st.first, st.second);
    w.member("sampling", V.sampling_seconds).member("fitting", V.fitting_seconds).member("untangling", V.untangling_seconds)
      .member("quality", V.quality_seconds);
    w.end_object();
    w.key("warnings").begin_array();
    for(const auto& s : closing.warnings) w.value(s);
    for(const auto& s : model.warnings) w.value(s);
    w.end_array().end_object();
    os << "\n";
  });
}

int run_build(const Arguments& args)
{
  Parsed_arguments a(args, {"--merge-duplicates", "--drop-isolated", "--no-self-intersection-test", "--allow-invalid", "--quiet",
                      "--no-untangle", "--no-step-retry", "--balance-corners", "--no-chain", "--no-blocks", "--polycube", "--no-polycube-retry",
                      "--cuts-away-from-holes", "--no-cuts-away-retry"},
                     {"-o", "--vtu", "--layout-vtu", "--layout-json", "--report", "--grid", "--degree", "--criterion",
                      "--boundary-layer", "--max-distance", "--max-refinements", "--max-grid", "--min-grid", "--min-degree", "--relax-sweeps", "--stretch-rounds", "--fold-bending",
                      "--sharp-boundary-turn", "--belt-phases", "--relax-arcs", "--relocate-nodes", "--relocation-retry", "--cut-pair-trials", "--missing-part-cubes",
                      "--small-handle-length", "--untangling-budget", "--focused-samples", "--polycube-first-alignment", "--polycube-relax-arcs"});
  a.expect_positional(1, "one mesh file: polycube_iga build MESH -o OUT.xml");
  const std::string out = a.get("-o");
  if(out.empty()) throw PI::Invalid_input_error("bad_arguments", "build needs -o OUT.xml");
  const int grid = positive_option(a, "--grid", 16, 2, 512);
  const int degree = positive_option(a, "--degree", 3, 1, 7);
  const PI::Cut_criterion criterion = PI::parse_cut_criterion(a.get("--criterion", "length"));
  const double layer = fraction_option(a, "--boundary-layer", 0.25, 0., 0.5);
  const double max_distance = fraction_option(a, "--max-distance", 0.02, 0., 1.);
  const int refinements = positive_option(a, "--max-refinements", 2, 0, 5);
  const int max_grid = positive_option(a, "--max-grid", std::min(2 * grid, 512), grid, 512);
  const int min_grid = positive_option(a, "--min-grid", PI::default_minimum_grid_resolution(grid), 2, grid);
  const int min_degree = positive_option(a, "--min-degree", PI::default_minimum_spline_degree(degree), 1, degree);
  const int sweeps = positive_option(a, "--relax-sweeps", 100, 0, 100000);
  const int stretch = positive_option(a, "--stretch-rounds", 3, 0, 100);
  const double fold_bending = fraction_option(a, "--fold-bending", 1e-4, 0., 1.);
  const double sharp_turn = fraction_option(a, "--sharp-boundary-turn", 60., 0., 180.);
  const int belt_phases = positive_option(a, "--belt-phases", 4, 1, 8);
  const int arc_sweeps = positive_option(a, "--relax-arcs", 0, 0, 100);
  const int polycube_arc_sweeps = positive_option(a, "--polycube-relax-arcs", 3, 0, 100);
  const int node_sweeps = positive_option(a, "--relocate-nodes", 0, 0, 100);
  const int retry_sweeps = positive_option(a, "--relocation-retry", 2, 0, 100);
  const int pair_trials = positive_option(a, "--cut-pair-trials", PI::default_cut_pair_trials, 1, 1000);
  const int missing_part_cubes = positive_option(a, "--missing-part-cubes", 2, 0, 16);
  const double small_handle_length = fraction_option(a, "--small-handle-length", 0., 0., 0.5);
  const double polycube_first = fraction_option(a, "--polycube-first-alignment", 0.95, 0., 2.);
  // In billions of Jacobian samples (Untangling_budget); "inf": no limit.
  const double untangling_budget =
    a.get("--untangling-budget", "") == "inf"
      ? std::numeric_limits<double>::infinity()
      : 1e9 * fraction_option(a, "--untangling-budget", PI::default_untangling_budget / 1e9, 1e-6, 1e12);
  const int focused_rounds = positive_option(a, "--focused-samples", PI::Volume_untangling_options().focused_sample_rounds, 0, 100);
  const bool verbose = !a.has("--quiet") && isatty(2);
  auto progress = [&](const std::string& stage) {
    if(verbose) std::cerr << "polycube_iga: " << stage << "...\n";
  };

  const auto t0 = std::chrono::steady_clock::now();
  progress("reading " + a.positional()[0]);
  Input_mesh in = read_input_mesh(a.positional()[0], a);
  in.report.require_valid();
  const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Handles a few triangles across (topological noise of a scan) are closed first: the
  // volume could not resolve them (Small_handle_removal.h).
  Handle_closing closing;
  Mesh mesh = in.mesh;
  if(small_handle_length > 0.) {
    progress("closing small handles");
    closing.ran = true;
    closing.result = PI::Small_handle_removal<Mesh::Point>()(mesh, PI::parameters::small_handle_length(small_handle_length));
    closing.warnings = closing.result.warnings;
  }
  const auto model = PI::build_trivariate_model(
    mesh, PI::parameters::grid_resolution(grid).spline_degree(degree).cut_criterion(criterion).boundary_layer(layer)
      .untangle_volume(!a.has("--no-untangle")).maximum_boundary_distance(max_distance)
      .maximum_refinements(refinements).maximum_grid_resolution(max_grid).minimum_grid_resolution(min_grid).minimum_spline_degree(min_degree)
      .grid_relaxation_sweeps(sweeps).stretch_rounds(stretch).fold_bending_weight(fold_bending).sharp_boundary_turn(sharp_turn).belt_phases(belt_phases)
      .step_retry(!a.has("--no-step-retry")).sphere_chain(!a.has("--no-chain")).orthogonal_blocks(!a.has("--no-blocks")).polycube_map(a.has("--polycube")).polycube_retry(!a.has("--no-polycube-retry")).polycube_first_alignment(polycube_first).arc_relaxation_sweeps(arc_sweeps).polycube_arc_relaxation_sweeps(polycube_arc_sweeps).node_relocation_sweeps(node_sweeps).node_relocation_retry(retry_sweeps).cut_pair_trials(pair_trials)
      .cuts_away_from_holes(a.has("--cuts-away-from-holes")).cuts_away_retry(!a.has("--no-cuts-away-retry"))
      .missing_part_cubes(missing_part_cubes).balance_pants_corners(a.has("--balance-corners")).untangling_budget(untangling_budget).focused_sample_rounds(focused_rounds)
      // An invalid volume is not written without --allow-invalid: no time spent improving it.
      .untangle_invalid_result(a.has("--allow-invalid")),
    progress);

  // The volume must also be near the mesh as read, not only near the one with handles closed.
  if(!closing.result.closed.empty() && model.volume.quality_evaluated)
    closing.to_input = PI::boundary_hausdorff_distance(model.volume.volume, in.mesh);
  std::vector<std::string> reasons = model.invalidity_reasons();
  const std::string too_far_from_input =
    closing.too_far(max_distance)
      ? "boundary distance to the mesh as read (small handles open) is " + PI::internal::percent_text(closing.to_input->relative) +
          " of the diagonal, over " + PI::internal::percent_text(max_distance)
      : "";
  if(!too_far_from_input.empty() && std::find(reasons.begin(), reasons.end(), "boundary_distance") == reasons.end())
    reasons.push_back("boundary_distance");
  const bool valid = reasons.empty();
  if(!valid && !(small_handle_length > 0.) && model.layout.genus > 0) {
    // Handles a few triangles across are a common reason for an invalid volume; say so.
    using Closing = PI::Small_handle_removal<Mesh::Point>;
    const auto topo = PI::Surface_topology<Mesh>()(in.mesh);
    const double diagonal = PI::internal::mesh_bbox_diagonal(in.mesh);
    for(const auto& s : Closing::small_loops(topo, 0.01 * diagonal)) {
      const auto& l = *s.loop;
      closing.warnings.push_back("a handle near " + PI::internal::triple_text(l.points[0][0], l.points[0][1], l.points[0][2]) +
                                 " has a " + s.kind + " loop of " + std::to_string(l.vertices.size()) + " edges, " +
                                 PI::internal::percent_text(l.length / diagonal) +
                                 " of the diagonal: likely topological noise that no grid resolves; --small-handle-length 0.01 closes it");
    }
  }
  const bool write_volume = valid || a.has("--allow-invalid");
  if(a.has("--layout-vtu")) PI::IO::write_layout_vtu(a.get("--layout-vtu"), model.layout);
  if(a.has("--layout-json")) PI::IO::write_layout_json(a.get("--layout-json"), model.layout);
  if(a.has("--report")) write_report(a.get("--report"), in, model, closing, reasons, read_seconds, write_volume);
  if(!valid) {
    // The first reason is the error's; the message says, for each, what is wrong and where.
    const std::string reason = reasons.front();
    std::string all;
    for(const auto& r : reasons) {
      const std::string topic = r == "boundary_distance" ? "boundary distance" : "det J";
      std::string detail;
      for(const auto& w : model.warnings)
        if(w.find(topic) != std::string::npos) { detail = w; break; }
      if(detail.empty() && r == "boundary_distance") detail = too_far_from_input;
      all += (all.empty() ? "" : "; ") + r + (detail.empty() ? "" : ": " + detail);
    }
    if(!write_volume)
      throw PI::Internal_error(reason, "the volume is not valid (" + all + "); nothing written (--allow-invalid writes it anyway)");
    // Written on request, but a script that only reads the exit code must still be told:
    // one line on stderr, --quiet or not.
    std::cerr << "warning: " << reason << ": the volume is not valid (" << all << "); written anyway (--allow-invalid)" << std::endl;
  }
  progress("writing " + out);
  PI::IO::write_gismo_xml(out, model.volume.volume);
  if(a.has("--vtu")) PI::IO::write_vtu(a.get("--vtu"), model.volume.volume);
  if(!a.has("--quiet")) {
    const auto& V = model.volume;
    std::cout << out << ": " << V.volume.number_of_patches() << " patches (" << PI::layout_class_name(model.layout.layout_class)
              << " layout, genus " << model.layout.genus << ", " << model.layout.boundary_loops << " boundary loops), degree "
              << V.degree << ", certified det J >= " << V.quality.overall_certified.lower_bound
              << ", min scaled Jacobian " << V.quality.overall_sampled.min_scaled_jacobian << ", Hausdorff "
              << V.distance.relative * 100 << "% of the bbox diagonal\n";
  }
  return 0;
}

Register_command build_command("build", {
  "the whole chain: mesh -> polycube layout -> multipatch B-spline volume (G+Smo XML)",
  "usage: polycube_iga build MESH -o OUT.xml [--vtu OUT.vtu] [--layout-vtu L.vtu] [--layout-json L.json]\n"
  "                          [--report R.json] [--grid N] [--degree P] [--criterion length|minima|symmetry]\n"
  "                          [--boundary-layer T] [--max-distance F] [--max-refinements R] [--max-grid M]\n"
  "                          [--min-grid M] [--min-degree D] [--relax-sweeps S] [--stretch-rounds R] [--fold-bending W]\n"
  "                          [--sharp-boundary-turn D] [--no-chain] [--no-blocks] [--polycube] [--no-polycube-retry]\n"
  "                          [--polycube-first-alignment A] [--belt-phases K] [--no-step-retry] [--relax-arcs K]\n"
  "                          [--polycube-relax-arcs K]\n"
  "                          [--relocate-nodes K] [--relocation-retry K] [--cut-pair-trials K]\n"
  "                          [--cuts-away-from-holes] [--no-cuts-away-retry]\n"
  "                          [--missing-part-cubes K] [--small-handle-length F] [--no-untangle]\n"
  "                          [--untangling-budget G] [--focused-samples K] [--balance-corners]\n"
  "                          [--allow-invalid]\n"
  "  -o OUT.xml        the multipatch volume in G+Smo XML (patches, interfaces, boundaries)\n"
  "  --vtu OUT.vtu     sampled hexahedra with det J and patch id, for ParaView\n"
  "  --layout-vtu L    the polycube layout on the surface: patches, arcs, nodes\n"
  "  --layout-json L   the layout as JSON\n"
  "  --report R.json   counts, per-patch scaled and certified Jacobians, Hausdorff distance,\n"
  "                    seconds per stage, warnings (written even when the volume is not)\n"
  "  --grid N          samples per patch side (default 16)   --degree P  spline degree (default 3)\n"
  "  --max-grid M      if the volume is not valid, rebuild it with 2N, 4N, ... samples up to M,\n"
  "                    then N + 4 (one more span) if M allows (default 2N; M = N never\n"
  "                    retries); the first valid one is written\n"
  "  --min-grid M      if it is still not valid, rebuild it with N/2, N/4, ... samples down to M\n"
  "                    (default N/2 when that is 8 or more, else N: never); fewer spans give\n"
  "                    smoother cuboids with fewer control points to untangle (high genus)\n"
  "  --min-degree D    if it is still not valid, rebuild it at degree P-1, ... down to D, on the\n"
  "                    first grid and the coarser ones (default 2, or P if lower; D = P never)\n"
  "  --relax-sweeps S  if the volume is not valid, build it again with the surface grids relaxed\n"
  "                    as one quad mesh on the surface (S sweeps, default 100; 0: never) and keep\n"
  "                    it if fewer patches are left uncertified (the other grids are relaxed if\n"
  "                    it left no more patches uncertified)\n"
  "  --stretch-rounds R  if the boundary is then farther from the mesh than --max-distance, build\n"
  "                    it again from patch maps with R rounds of stretch reduction (default 3;\n"
  "                    0: never), which give protrusions their share of the grid; kept if better\n"
  "  --fold-bending W  if a boundary side of an uncertified patch then turns over, fit the faces\n"
  "                    again with bending weight W (default 1e-4, against 1e-6; 0: never), whose\n"
  "                    stiffer faces keep their inner control points inside along a crease; kept\n"
  "                    if better and no side turns over any more, and the other grids follow\n"
  "  --sharp-boundary-turn D  where an input boundary loop turns by more than D degrees at a\n"
  "                    vertex inside a layout arc, round the arc there within the vertex's two\n"
  "                    edges (default 60; 0: never): a sharp tip inside a patch side folds the\n"
  "                    slab under it\n"
  "  --no-chain        a closed genus-0 surface long enough for three cube-like cuboids or more is\n"
  "                    by default laid out as a chain of them between caps at its two ends, and\n"
  "                    as one cube if that volume is not valid; this lays it out as one cube\n"
  "  --no-blocks       a closed CAD block whose faces are all planar and perpendicular to three\n"
  "                    axes (an L, a T, a U, a frame) is by default split into the boxes between\n"
  "                    its faces' planes, its sharp edges on their edges; this lays it out by its\n"
  "                    genus as any other surface\n"
  "  --polycube        lay a closed surface out on the boxes of a polycube map of it (faces\n"
  "                    labelled by their nearest axis direction, the surface deformed until each\n"
  "                    label's charts are planar, the polycube split into boxes along its faces'\n"
  "                    planes, the boxes carried back to the surface)\n"
  "  --no-polycube-retry  a closed surface whose layout by its genus gives no valid volume is\n"
  "                    by default built again on a polycube map's boxes, kept if valid; this\n"
  "                    never does\n"
  "  --polycube-first-alignment A  a closed surface other than a CAD block whose faces align\n"
  "                    with three axes at least this much (area-weighted, 1 for a CAD block:\n"
  "                    a part with fillets or round holes is over 0.95, an organic shape 0.83\n"
  "                    to 0.92) is laid out on its polycube map first, the layout by its genus\n"
  "                    following only if that volume is not valid (default 0.95; above 1: never)\n"
  "  --belt-phases K   a closed genus-0 surface (one cube) whose volume is not valid is built\n"
  "                    again with the cube's six belt nodes moved along the belt by 1/8, ...,\n"
  "                    (K-1)/8 of the zigzag's period; the first valid one is written\n"
  "                    (default 4, at most 8; 1: never)\n"
  "  --no-step-retry   a cylinder (two boundary loops) whose volume is not valid is by default built\n"
  "                    again with its section corners moved off the steps of its cut ends, if any\n"
  "                    is near one; this never does\n"
  "  --relax-arcs K    before the volume is built, up to K sweeps re-trace each arc between two\n"
  "                    surface patches as the middle of their union where that brings the\n"
  "                    corners at its ends nearer right angles (default 0: never)\n"
  "  --polycube-relax-arcs K  the same on a layout of a polycube map, whose arcs follow its\n"
  "                    charts' borders and zigzag on curved faces (default 3; at least --relax-arcs)\n"
  "  --relocate-nodes K  before the volume is built (and before --relax-arcs), up to K sweeps move\n"
  "                    each node whose corners are over 30 degrees from right angles inside the\n"
  "                    union of its patches, re-tracing its arcs, where that brings the corners\n"
  "                    nearer right angles; a node on a boundary loop slides along it\n"
  "                    (default 0: never)\n"
  "  --relocation-retry K  when --relocate-nodes is 0 and no volume is valid, build the layout\n"
  "                    again with K sweeps of node relocation and keep it if valid (default 2;\n"
  "                    0: never)\n"
  "  --balance-corners  move each pants half's four centre nodes in its convex map to where their\n"
  "                    arcs meet at even angles on the mesh (default: where Tutte's rule puts\n"
  "                    them); the layout's corners improve, its volumes are not more often valid\n"
  "  --cuts-away-from-holes  a closed surface's pants cuts keep away from the holes of the region\n"
  "                    they cut, and its cycles are moved nearer the middle of their tubes:\n"
  "                    through a CAD wheel's spokes and rim midway rather than at a junction;\n"
  "                    on smooth shapes longer cuts and worse volumes (default: shortest cuts)\n"
  "  --no-cuts-away-retry  a closed surface of genus 2 or more whose volume is not valid on any\n"
  "                    layout above is by default built again with --cuts-away-from-holes,\n"
  "                    kept if valid; this never does\n"
  "  --cut-pair-trials K  the pants stage traces the cuts around the K most promising pairs of\n"
  "                    holes at each step and takes the most promising one whose cut is within\n"
  "                    10% of the lightest (default 16; 1: the most promising pair alone)\n"
  "  --missing-part-cubes K  when the volume misses a part of the shape (a mesh point far\n"
  "                    from it while all of it is near the mesh: a protrusion the patch's map\n"
  "                    shrinks), give that patch a cube of its own with its bottom there and\n"
  "                    build again, up to K times while it helps (default 2; 0: never)\n"
  "  --untangling-budget G  billions of Jacobian samples that all the untangling of the run,\n"
  "                    retries included, may visit (default 10, about 12 minutes on 2 cores;\n"
  "                    inf: no limit); once spent it stops, and the report says so\n"
  "                    (untangling_work, untangling_budget_exhausted)\n"
  "  --focused-samples K  rounds in which a patch whose det J is positive at every sample but\n"
  "                    not certified gets a sample where its certificate's bound is lowest\n"
  "                    (default 4; 0: none); the report counts them\n"
  "                    (untangling_focused_samples)\n"
  "  --small-handle-length F  close first every handle whose shortest handle or tunnel loop is\n"
  "                    shorter than F times the bounding-box diagonal (topological noise of a\n"
  "                    scan: no grid resolves it); the volume must still be within --max-distance\n"
  "                    of the mesh as read (default 0: keep every handle; e.g. 0.01)\n"
  "  --boundary-layer T  depth of the layer of slabs under the surface, as a fraction of the\n"
  "                    shortest arc at each node (default 0.25; 0: one patch per cuboid)\n"
  "  --no-untangle     keep the constructed inner control points; by default those of patches\n"
  "                    with poor or negative det J are moved to untangle them (surface kept)\n"
  "  --max-distance F  largest Hausdorff distance between the volume's boundary and the mesh,\n"
  "                    as a fraction of the bounding-box diagonal (default 0.02)\n"
  "  --max-refinements R  midpoint subdivisions of the whole mesh the cuboid stage may add when\n"
  "                    a cutting curve or arc finds no room (default 2; each multiplies the faces by 4)\n"
  "  --allow-invalid   write the volume even if it is not valid (exit 0; one line on stderr,\n"
  "                    warning: <reason_code>: ..., says why it is not); without it, a first\n"
  "                    volume that no untangling makes valid is not untangled when no other\n"
  "                    grid is valid either (sooner to the error; the report has its figures)\n"
  "  exit 1 with nonpositive_jacobian when some det J is not certified positive, or with\n"
  "  boundary_distance when the boundary is farther than --max-distance (nothing written)\n",
  run_build});

} // namespace
} // namespace polycube_iga_cli
