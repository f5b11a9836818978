// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Suite `build`: the whole mesh-to-volume chain, build_trivariate_model(mesh) with its default
// parameters (grid 16, degree 3), on sphere, torus and genus-2/3 meshes from the shared data
// and their midpoint subdivisions, from ~600 to ~64k faces. 3holes x2 (63,712 faces, genus 3)
// is the target case ("the whole build on a 50k-face genus-3 mesh under 10 s on one core").
// Timed (best of --repetitions by total wall clock, one core), on the mesh in memory (no I/O):
//   the stages as build_trivariate_model() times them in Trivariate_model::stage_seconds
//   (topology, cuboid decomposition, layout validation, volume construction, ...: whatever
//   it reports, in its order), of the best run, and
//   total     wall clock of the whole build_trivariate_model() call.
// The volume construction is also split into its sampling / fitting / quality parts
// (Layout_volume_result::*_seconds; "quality" is the Jacobian certification and the
// Hausdorff distance, part of the stage).
// Quality of the result: min scaled Jacobian (sampled), certified valid (every patch's det J
// certified positive, Trivariate_model::is_valid()), Hausdorff distance of the volume
// boundary to the mesh over the mesh's bounding-box diagonal.
// A Polycube_IGA::Error makes a row with the stage it failed in and its reason(); the suite
// goes on with the next mesh.
// Baseline, same mesh, same run: one CHOLMOD supernodal factorization and one solve of
// L + 1e-8 M (bench_meshes.h); the ratio total / baseline is the machine-independent figure.
// Each case prints the usual report line and JSON line; a summary table closes the suite.
//
//   build/bin/polycube_iga_benchmark build            # all sizes
//   build/bin/polycube_iga_benchmark --quick build    # small meshes only (< 5k faces)

#include "bench_meshes.h"

#include <CGAL/polycube_iga.h>

#include <cmath>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace polycube_iga_bench {
namespace {

namespace PI = CGAL::Polycube_IGA;
using meshes::Case;
using meshes::Mesh;

// Growing sizes: sphere (genus 0), torus (genus 1, cinolib/torus.obj is the shipped
// test/Polycube_IGA/data/torus.obj), eight (genus 2), 3holes (genus 3).
const Case cases[] = {
  {"cgal/eight.off", 0, true},        //    634 faces, genus 2
  {"cgal/sphere.off", 1, true},       //  1,280, genus 0
  {"cinolib/torus.obj", 0, true},     //  1,536, genus 1
  {"cgal/eight.off", 1, true},        //  2,536, genus 2
  {"cinolib/3holes.obj", 0, true},    //  3,982, genus 3
  {"cinolib/torus.obj", 1, false},    //  6,144, genus 1
  {"cgal/eight.off", 2, false},       // 10,144, genus 2
  {"cinolib/3holes.obj", 1, false},   // 15,928, genus 3
  {"cgal/sphere.off", 3, false},      // 20,480, genus 0
  {"cinolib/torus.obj", 2, false},    // 24,576, genus 1
  {"cinolib/3holes.obj", 2, false},   // 63,712, genus 3 (target case)
};

/// Genus and number of boundary loops from the mesh alone (one connected component assumed),
/// so that a failed build still gets them in its row.
void mesh_topology(const Mesh& m, int& genus, int& boundary_loops)
{
  std::vector<bool> seen(m.num_halfedges(), false); // index range, removed ones included
  boundary_loops = 0;
  for(auto h : halfedges(m)) {
    if(!is_border(h, m) || seen[std::size_t(h)]) continue;
    ++boundary_loops;
    for(auto g = h; !seen[std::size_t(g)]; g = next(g, m)) seen[std::size_t(g)] = true;
  }
  const long chi = long(num_vertices(m)) - long(num_edges(m)) + long(num_faces(m));
  genus = int((2 - boundary_loops - chi) / 2);
}

/// One line of the closing table.
struct Row
{
  std::string name;
  std::size_t faces = 0;
  int genus = 0, boundary_loops = 0;
  bool failed = false;
  std::string failure; ///< "stage: reason (what)"
  std::size_t cuboids = 0, patches = 0;
  std::vector<std::pair<std::string, double>> stages; ///< as stage_seconds
  double sampling = 0, fitting = 0, quality = 0;
  double total = 0, baseline = 0;
  double min_scaled_jacobian = 0, hausdorff_relative = 0;
  bool quality_evaluated = false, certified = false;
};

std::string underscored(std::string s)
{
  for(char& c : s)
    if(c == ' ') c = '_';
  return s;
}

Row run_case(const Options& opt, const Case& c)
{
  Row row;
  const std::string source = opt.data_dir + "/" + c.file;
  row.name = meshes::base_name(c.file) + " x" + std::to_string(c.subdivisions);
  Mesh mesh;
  if(!meshes::read_subdivided(source, c.subdivisions, mesh)) {
    std::cerr << "build: skipping " << source << ": cannot read it\n";
    row.failed = true;
    row.failure = "cannot read " + source;
    return row;
  }
  row.faces = num_faces(mesh);
  mesh_topology(mesh, row.genus, row.boundary_loops);

  // The whole chain, best of N by total wall clock; the stage times are those of that run.
  using Model = decltype(PI::build_trivariate_model(mesh));
  Model best;
  double t_total = std::numeric_limits<double>::infinity(), total_cpu = 0;
  std::string current_stage;
  for(int r = 0; r < std::max(1, opt.repetitions) && !row.failed; ++r) {
    const double cpu0 = meshes::process_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    try {
      Model model = PI::build_trivariate_model(mesh, PI::parameters::default_values(),
                                               [&](const std::string& stage) { current_stage = stage; });
      const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if(t < t_total) {
        t_total = t;
        total_cpu = meshes::process_cpu_seconds() - cpu0;
        best = std::move(model);
      }
    } catch(const PI::Error& e) {
      row.failed = true;
      row.failure = current_stage + ": " + e.reason() + " (" + e.what() + ")";
    } catch(const std::exception& e) {
      row.failed = true;
      row.failure = current_stage + ": exception (" + std::string(e.what()) + ")";
    }
    if(row.failed)
      row.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if(row.failed) std::cerr << "build: " << row.name << ": failed in " << row.failure << "\n";

  double t_assembly = 0, residual = 0;
  row.baseline = meshes::cholmod_laplacian_baseline(mesh, opt.repetitions, t_assembly, residual);
  if(residual > 1e-8) std::cerr << "build: " << row.name << ": baseline residual " << residual << "\n";

  char label[96];
  std::snprintf(label, sizeof(label), "%s (%zuf g%d)", row.name.c_str(), row.faces, row.genus);
  if(row.failed) {
    std::printf("%-10s %-34s FAILED after %.4fs in %s | cholmod=%.4fs\n", "build", label, row.total,
                row.failure.c_str(), row.baseline);
    std::ostringstream os;
    CGAL::Polycube_IGA::internal::Json_writer w(os);
    w.begin_object().member("suite", "build").member("case", std::string(label));
    w.member("faces", double(row.faces)).member("genus", double(row.genus));
    w.member("boundary_loops", double(row.boundary_loops)).member("failed", true);
    w.member("error", row.failure).member("seconds_until_failure", row.total);
    w.key("baseline").begin_object().member("name", "cholmod").member("seconds", row.baseline).end_object();
    w.end_object();
    std::printf("JSON %s\n", os.str().c_str());
    std::fflush(stdout);
    return row;
  }

  const auto& V = best.volume;
  row.cuboids = best.layout.cuboids.size();
  row.patches = V.volume.number_of_patches();
  row.stages = best.stage_seconds;
  row.sampling = V.sampling_seconds;
  row.fitting = V.fitting_seconds;
  row.quality = V.quality_seconds;
  row.total = t_total;
  row.quality_evaluated = V.quality_evaluated;
  row.certified = best.is_valid();
  row.min_scaled_jacobian = V.quality.overall_sampled.min_scaled_jacobian;
  row.hausdorff_relative = V.distance.relative;
  for(std::size_t k = 0; k < best.warnings.size() && k < 3; ++k)
    std::cerr << "build: " << row.name << ": warning: " << best.warnings[k] << "\n";
  if(best.warnings.size() > 3) std::cerr << "build: " << row.name << ": ... " << best.warnings.size() << " warnings\n";

  std::vector<std::pair<std::string, double>> extra = {
    {"faces", double(row.faces)},
    {"vertices", double(num_vertices(mesh))},
    {"genus", double(row.genus)},
    {"boundary_loops", double(row.boundary_loops)},
    {"layout_genus", double(best.layout.genus)},
    {"cuboids", double(row.cuboids)},
    {"volume_patches", double(row.patches)},
    {"interfaces", double(V.volume.interfaces().size())},
    {"degree", double(V.degree)},
    {"spans", double(V.spans)},
    {"volume_sampling_seconds", row.sampling},
    {"volume_fitting_seconds", row.fitting},
    {"volume_untangling_seconds", V.untangling_seconds},
    {"untangled_patches", V.untangling.skipped ? 0. : double(V.untangling.patches.size())},
    {"untangling_skipped", V.untangling.skipped ? 1. : 0.},
    {"untangling_work", best.untangling_work},
    {"volume_quality_seconds", row.quality},
    {"quality_evaluated", row.quality_evaluated ? 1.0 : 0.0},
    {"certified_valid", row.certified ? 1.0 : 0.0},
    {"certified_lower_bound", V.quality.overall_certified.lower_bound},
    {"min_scaled_jacobian", row.min_scaled_jacobian},
    {"mean_scaled_jacobian", V.quality.overall_sampled.mean_scaled_jacobian},
    {"interfaces_conforming", V.quality.interfaces.conforming ? 1.0 : 0.0},
    {"hausdorff_over_diagonal", row.hausdorff_relative},
    {"warnings", double(best.warnings.size())},
    {"total_cpu_over_wall", total_cpu / t_total},
    {"baseline_assembly_seconds", t_assembly},
    {"threads", 1.0},
  };
  std::vector<std::pair<std::string, double>> stages;
  for(const auto& [name, s] : best.stage_seconds) stages.push_back({underscored(name), s});
  stages.push_back({"total", t_total});
  report("build", label, extra, stages, "cholmod", row.baseline);
  return row;
}

/// The closing table: one row per mesh, stage columns in the order the chain reports them.
void print_table(const std::vector<Row>& rows)
{
  std::vector<std::string> stage_names;
  for(const Row& r : rows)
    for(const auto& s : r.stages)
      if(std::find(stage_names.begin(), stage_names.end(), s.first) == stage_names.end()) stage_names.push_back(s.first);

  std::printf("\n# build: seconds per stage (best run), total = whole build_trivariate_model(), "
              "baseline = CHOLMOD factor + solve; vol split = sampling/fitting/quality of the volume stage\n");
  std::printf("%-20s %7s %2s %2s %4s %4s", "mesh", "faces", "g", "b", "cub", "pat");
  for(const std::string& n : stage_names) std::printf(" %*s", int(std::max<std::size_t>(8, n.size())), n.c_str());
  std::printf(" %20s %8s %8s %9s %8s %5s %9s\n", "vol split (s/f/q)", "total", "baseline", "total/bl", "minSJ",
              "cert", "H/diag");
  for(const Row& r : rows) {
    std::printf("%-20s %7zu %2d %2d", r.name.c_str(), r.faces, r.genus, r.boundary_loops);
    if(r.failed) {
      std::printf("    -    -  FAILED after %.3fs (baseline %.4fs) in %s\n", r.total, r.baseline, r.failure.c_str());
      continue;
    }
    std::printf(" %4zu %4zu", r.cuboids, r.patches);
    for(const std::string& n : stage_names) {
      double s = std::numeric_limits<double>::quiet_NaN();
      for(const auto& p : r.stages)
        if(p.first == n) s = p.second;
      std::printf(" %*.3f", int(std::max<std::size_t>(8, n.size())), s);
    }
    char split[64];
    std::snprintf(split, sizeof(split), "%.2f/%.2f/%.2f", r.sampling, r.fitting, r.quality);
    std::printf(" %20s %8.3f %8.4f %9.1f", split, r.total, r.baseline, r.total / r.baseline);
    if(r.quality_evaluated)
      std::printf(" %8.3f %5s %8.2f%%\n", r.min_scaled_jacobian, r.certified ? "yes" : "no", 100 * r.hausdorff_relative);
    else
      std::printf(" %8s %5s %9s\n", "-", "no", "-");
  }
  std::fflush(stdout);
}

void run_suite(const Options& opt)
{
  meshes::One_core core;
  meshes::print_timed_suite_header("build", opt, core, " (by total)");
  std::vector<Row> rows;
  for(const Case& c : cases)
    if(c.quick || !opt.quick) rows.push_back(run_case(opt, c));
  print_table(rows);
}

static Register_suite build_suite("build", run_suite);

} // namespace
} // namespace polycube_iga_bench
