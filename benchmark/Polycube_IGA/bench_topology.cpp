// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Suite `topology`: the first stage of the pipeline over meshes of growing size, from the
// shared test data and from midpoint subdivisions of genus-2/3/4 meshes up to ~160k faces.
// Stages timed (best of --repetitions, wall clock, one core):
//   read      read_triangle_mesh(path, mesh, check_self_intersections(false)): file I/O,
//             combinatorial validation, orientation, mesh construction
//   validate  prepare_polygon_soup(points, polygons) on the soup already in memory, with the
//             exact self-intersection test (validation alone, no I/O)
//   topology  Surface_topology<Mesh>()(mesh): genus, boundary loops, homology basis,
//             handle and tunnel loops (defaults: 16 roots, tunnels on)
// Baseline, same mesh, same run: one CHOLMOD supernodal factorization and one solve of
// L + 1e-8 M (cotangent Laplacian plus a scale-free mass shift, SPD), matrix assembled
// beforehand (its assembly time is an extra field).
//
// The suite pins the process to one core while it runs (Linux) and reports the CPU/wall
// ratio of the topology stage, so the figures are one-core figures.
//
//   build/bin/polycube_iga_benchmark topology            # all sizes
//   build/bin/polycube_iga_benchmark --quick topology    # small meshes only

#include "bench_meshes.h"

#include <CGAL/Polycube_IGA/Input_validation.h>
#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/boost/graph/IO/OFF.h>

#include <chrono>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace polycube_iga_bench {
namespace {

namespace PI = CGAL::Polycube_IGA;
namespace PIP = CGAL::Polycube_IGA::parameters;
using meshes::Point;
using meshes::Mesh;
using meshes::One_core;
using meshes::base_name;
using meshes::process_cpu_seconds;

using meshes::Case;

// Growing sizes; the genus-3 3holes x2 (63,712 faces) is the target case of the issue
// ("a 50k-face genus-3 mesh under 1 s on one core").
const Case cases[] = {
  {"cgal/eight.off", 0, true},          //    634 faces, genus 2
  {"cinolib/3holes.obj", 0, true},      //  3,982, genus 3
  {"cgal/elephant.off", 0, true},       //  5,558, genus 3
  {"cgal/anchor_dense.off", 0, false},  //  7,598, genus 4
  {"cinolib/3holes.obj", 1, false},     // 15,928, genus 3
  {"cgal/elephant.off", 1, false},      // 22,232, genus 3
  {"cgal/anchor_dense.off", 1, false},  // 30,392, genus 4
  {"cgal/armadillo.off", 0, false},     // 52,000, genus 0
  {"cinolib/3holes.obj", 2, false},     // 63,712, genus 3
  {"cgal/elephant.off", 2, false},      // 88,928, genus 3
  {"cgal/anchor_dense.off", 2, false},  //121,568, genus 4
  {"cgal/eight.off", 4, false},         //162,304, genus 2
};

void run_case(const Options& opt, const Case& c, const std::filesystem::path& scratch)
{
  const std::string source = opt.data_dir + "/" + c.file;
  std::string name = base_name(c.file);
  if(c.subdivisions) name += " x" + std::to_string(c.subdivisions);

  // The file the stages read: the data file, or its subdivision written to a scratch .off.
  std::string path = source;
  if(c.subdivisions > 0) {
    Mesh m;
    if(!meshes::read_subdivided(source, c.subdivisions, m)) {
      std::cerr << "topology: skipping " << source << ": cannot read it\n";
      return;
    }
    path = (scratch / (std::filesystem::path(c.file).stem().string() + "_x" + std::to_string(c.subdivisions) + ".off")).string();
    if(!CGAL::IO::write_OFF(path, m, CGAL::parameters::stream_precision(17))) {
      std::cerr << "topology: cannot write " << path << "\n";
      return;
    }
  }

  // read
  Mesh mesh;
  PI::Validation_report read_report;
  const double t_read = best_time(opt.repetitions, [&] {
    read_report = PI::read_triangle_mesh(path, mesh, PIP::check_self_intersections(false));
  });
  if(!read_report.is_valid()) { std::cerr << "topology: skipping " << path << ": invalid input\n"; return; }

  // validate (soup in memory, with the self-intersection test)
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::string reason;
  PI::read_polygon_soup_file(path, points, polygons, reason);
  bool self_intersecting = false;
  const double t_validate = best_time(opt.repetitions, [&] {
    const PI::Prepared_soup<Point> soup = PI::prepare_polygon_soup(points, polygons);
    self_intersecting = soup.report.has("self_intersecting");
  });

  // topology, with the CPU time of the best run to show it is single-threaded
  PI::Surface_topology_result<Mesh> topo;
  double topo_cpu = std::numeric_limits<double>::infinity(), t_topology = std::numeric_limits<double>::infinity();
  bool topology_failed = false;
  for(int r = 0; r < std::max(1, opt.repetitions) && !topology_failed; ++r) {
    const double cpu0 = process_cpu_seconds();
    try {
      const double t = best_time(1, [&] { topo = PI::Surface_topology<Mesh>()(mesh); });
      if(t < t_topology) { t_topology = t; topo_cpu = process_cpu_seconds() - cpu0; }
    } catch(const PI::Error& e) {
      std::cerr << "topology: " << name << ": error: " << e.reason() << ": " << e.what() << "\n";
      topology_failed = true;
    }
  }

  // baseline: one CHOLMOD factorization + solve of the cotangent Laplacian (+ mass shift)
  double t_assembly = 0, residual = 0;
  const double t_baseline = meshes::cholmod_laplacian_baseline(mesh, opt.repetitions, t_assembly, residual);
  if(residual > 1e-8) std::cerr << "topology: " << name << ": baseline residual " << residual << "\n";

  std::vector<std::pair<std::string, double>> extra = {
    {"faces", double(num_faces(mesh))},
    {"vertices", double(num_vertices(mesh))},
    {"genus", topology_failed ? -1.0 : double(topo.genus)},
    {"boundary_loops", topology_failed ? -1.0 : double(topo.number_of_boundary_loops())},
    {"handle_loops", topology_failed ? -1.0 : double(topo.handle_loops.size())},
    {"tunnel_loops", topology_failed ? -1.0 : double(topo.tunnel_loops.size())},
    {"refinements", topology_failed ? -1.0 : double(topo.refinements)},
    {"self_intersecting", self_intersecting ? 1.0 : 0.0},
    {"topology_cpu_over_wall", topo_cpu / t_topology},
    {"baseline_assembly_seconds", t_assembly},
    {"threads", 1.0},
  };
  std::vector<std::pair<std::string, double>> stages = {{"read", t_read}, {"validate", t_validate}};
  if(!topology_failed) stages.push_back({"topology", t_topology});
  char label[96];
  std::snprintf(label, sizeof(label), "%s (%zuf g%d)", name.c_str(), std::size_t(num_faces(mesh)),
                topology_failed ? -1 : topo.genus);
  report("topology", label, extra, stages, "cholmod", t_baseline);
}

void run_suite(const Options& opt)
{
  One_core core;
  meshes::print_timed_suite_header("topology", opt, core);
  std::error_code ec;
  const std::filesystem::path scratch =
    std::filesystem::temp_directory_path() / ("polycube_iga_bench_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  std::filesystem::create_directories(scratch, ec);
  for(const Case& c : cases)
    if(c.quick || !opt.quick) run_case(opt, c, scratch);
  std::filesystem::remove_all(scratch, ec);
}

static Register_suite topology_suite("topology", run_suite);

} // namespace
} // namespace polycube_iga_bench
