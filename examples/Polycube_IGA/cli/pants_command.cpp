// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `polycube_iga pants MESH --json [--criterion length|minima|symmetry]
//                   [--symmetry-plane a,b,c,d] [--write-pants DIR] [--vtk OUT.vtu]`:
// the pants decomposition (reference §2.2.1). chi >= 0 inputs: exit 3, no_pants_decomposition.
// Output files are checked for a directory before the work and written atomically.

#include "arguments.h"
#include "command_registry.h"
#include "mesh_input.h"

#include <CGAL/Polycube_IGA/IO/pants_vtk.h>
#include <CGAL/Polycube_IGA/Pants_decomposition.h>
#include <CGAL/Polycube_IGA/internal/atomic_file.h>
#include <CGAL/Polycube_IGA/internal/json_writer.h>

#include <CGAL/IO/OFF.h>

#include <iostream>
#include <sstream>
#include <sys/stat.h>

namespace polycube_iga_cli {
namespace {

namespace PI = CGAL::Polycube_IGA;

std::array<double, 4> parse_plane(const std::string& text)
{
  std::array<double, 4> p{};
  std::istringstream in(text);
  char comma;
  if(!(in >> p[0] >> comma >> p[1] >> comma >> p[2] >> comma >> p[3]) || !(std::abs(p[0]) + std::abs(p[1]) + std::abs(p[2]) > 0))
    throw PI::Invalid_input_error("bad_arguments", "--symmetry-plane expects a,b,c,d of a plane ax+by+cz+d=0, got '" + text + "'");
  return p;
}

void write_off_atomically(const std::string& path, const Mesh& m)
{
  PI::internal::write_file_atomically(path, [&](std::ostream& os) {
    if(!CGAL::IO::write_OFF(os, m, CGAL::parameters::stream_precision(17)))
      throw PI::Internal_error("write_failed", "cannot write '" + path + "'");
  });
}

int run_pants(const Arguments& args)
{
  Parsed_arguments a(args, {"--json", "--merge-duplicates", "--drop-isolated", "--no-self-intersection-test"},
                     {"--criterion", "--symmetry-plane", "--write-pants", "--vtk"});
  a.expect_positional(1, "one mesh file: polycube_iga pants MESH --json");
  PI::Cut_criterion criterion = PI::parse_cut_criterion(a.get("--criterion", "length"));
  std::array<double, 4> plane{0, 0, 1, 0};
  if(a.has("--symmetry-plane")) plane = parse_plane(a.get("--symmetry-plane"));
  else if(criterion == PI::Cut_criterion::SYMMETRY)
    throw PI::Invalid_input_error("bad_arguments", "--criterion symmetry needs --symmetry-plane a,b,c,d");
  auto require_directory = [](const std::string& option, const std::string& dir) {
    struct stat st;
    if(stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
      throw PI::Invalid_input_error("unwritable_output", option + ": '" + dir + "' is not a directory");
  };
  const std::string out_dir = a.get("--write-pants");
  if(!out_dir.empty()) require_directory("--write-pants", out_dir);
  const std::string vtk = a.get("--vtk");
  if(a.has("--vtk")) {
    if(vtk.empty() || vtk.back() == '/') throw PI::Invalid_input_error("bad_arguments", "--vtk expects a file name OUT.vtu");
    const std::size_t slash = vtk.rfind('/');
    require_directory("--vtk", slash == std::string::npos ? "." : (slash == 0 ? "/" : vtk.substr(0, slash)));
  }

  Input_mesh in = read_input_mesh(a.positional()[0], a);
  in.report.require_valid();
  // The topology once, for the decomposition and for validate(); the one build cuts along.
  const auto topology = PI::internal::cutting_topology(in.mesh);
  const auto result = PI::Pants_decomposition<Mesh>()(
    in.mesh, PI::parameters::cut_criterion(criterion).symmetry_plane(plane).surface_topology(topology));
  const PI::Pants_validation check = PI::Pants_decomposition<Mesh>::validate(in.mesh, result, topology);
  if(!check.is_valid())
    throw PI::Internal_error("pants_decomposition_invalid", "the decomposition violates an invariant: " + check.problems.front());
  const Mesh& m = result.mesh(in.mesh);

  // Each file is written atomically (temporary, then rename).
  if(!out_dir.empty()) {
    for(std::size_t k = 0; k < result.pants.size(); ++k) {
      Mesh sub;
      PI::internal::extract_pants_mesh(in.mesh, result, k, sub);
      write_off_atomically(out_dir + "/pants_" + std::to_string(k) + ".off", sub);
    }
    if(result.refinements) write_off_atomically(out_dir + "/refined_mesh.off", m);
  }
  if(a.has("--vtk")) PI::IO::write_pants_vtu(vtk, in.mesh, result);

  // Input vertices by their index in the input file; vertices added by refinement by their
  // index in refined_mesh.off (whose first vertices are the input mesh's).
  auto index_of = [&](Mesh::Vertex_index v) -> long {
    return std::size_t(v) < num_vertices(in.mesh) ? in.input_index(v) : long(std::size_t(v));
  };
  if(a.has("--json")) {
    PI::internal::Json_writer w(std::cout);
    w.begin_object()
      .member("genus", result.genus)
      .member("boundary_loops", result.boundary_loops)
      .member("refinements", result.refinements);
    w.key("pants").begin_array();
    for(const auto& p : result.pants) {
      w.begin_object().member("faces", p.faces.size());
      w.key("boundaries").begin_array();
      for(int c : p.boundaries) w.value(c);
      w.end_array().key("neighbours").begin_array();
      for(int n : p.neighbours) w.value(n);
      w.end_array().end_object();
    }
    w.end_array().key("cycles").begin_array();
    for(const auto& c : result.cycles) {
      w.begin_object().member("kind", PI::Pants_cycle<Mesh>::kind_name(c.kind));
      w.key("vertices").begin_array();
      for(auto v : c.vertices) w.value(index_of(v));
      w.end_array().key("points").begin_array();
      for(const auto& p : c.points) w.begin_array().value(p[0]).value(p[1]).value(p[2]).end_array();
      w.end_array().member("length", c.length).end_object();
    }
    w.end_array().end_object();
    std::cout << "\n";
  } else {
    std::cout << "genus " << result.genus << ", boundary loops " << result.boundary_loops << ": "
              << result.pants.size() << " pants, " << result.number_of_cut_cycles() << " cut cycles";
    if(result.refinements) std::cout << " (mesh refined " << result.refinements << " time(s) at edge midpoints)";
    std::cout << "\n";
    for(std::size_t k = 0; k < result.pants.size(); ++k) {
      const auto& p = result.pants[k];
      std::cout << "  pants " << k << ": " << p.faces.size() << " faces, cycles " << p.boundaries[0] << " "
                << p.boundaries[1] << " " << p.boundaries[2] << ", neighbours " << p.neighbours[0] << " "
                << p.neighbours[1] << " " << p.neighbours[2] << "\n";
    }
  }
  return 0;
}

Register_command pants_command("pants", {
  "cut the surface into pants patches (genus 0, 3 boundaries) along handle loops and cycles",
  "usage: polycube_iga pants MESH [--json] [--criterion length|minima|symmetry]\n"
  "                         [--symmetry-plane a,b,c,d] [--write-pants DIR] [--vtk OUT.vtu]\n"
  "  --json              {genus, boundary_loops, refinements, pants: [{faces,\n"
  "                      boundaries: [cycle ids], neighbours: [pants ids, -1 across an input\n"
  "                      boundary]}], cycles: [{kind, vertices, points, length}]}; cycles list the\n"
  "                      input boundary loops, then the handle loops, then the cuts. Vertices of\n"
  "                      the input have their input-file index; vertices that a refinement added\n"
  "                      have their index in DIR/refined_mesh.off (always with exact points).\n"
  "  --criterion         length (default): shortest cycles; minima: through concave regions\n"
  "                      (minimum curvature); symmetry: near --symmetry-plane\n"
  "  --write-pants DIR   one OFF per pants (DIR/pants_K.off), plus refined_mesh.off if refined\n"
  "  --vtk OUT.vtu       VTK XML unstructured grid for ParaView: the (refined) mesh with cell\n"
  "                      data pants (the pants of each face), then the cycles as closed poly\n"
  "                      lines with cell data cycle (its id) and kind (0 input boundary,\n"
  "                      1 handle, 2 cut); -1 where a field does not apply\n"
  "  exit 3 with no_pants_decomposition for a sphere, disk, cylinder or torus (chi >= 0);\n"
  "  exit 2 with unwritable_output when an output cannot be written (no file is left)\n",
  run_pants});

} // namespace
} // namespace polycube_iga_cli
