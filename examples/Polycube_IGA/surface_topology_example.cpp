// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Reads a triangle mesh (validated on the way in) and prints its topology: genus,
// boundary loops, and the handle and tunnel loops found by Surface_topology.
//
//   surface_topology_example [MESH]      (default: the shared elephant.off, genus 3)

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polycube_IGA/IO/read_triangle_mesh.h>
#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>
#include <string>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PI = CGAL::Polycube_IGA;
namespace PIP = CGAL::Polycube_IGA::parameters;

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : std::string(POLYCUBE_IGA_EXAMPLE_DATA_DIR "/cgal/elephant.off");

  // Read and validate; the report lists every problem with its reason code.
  Mesh mesh;
  const PI::Validation_report report = PI::read_triangle_mesh(path, mesh, PIP::merge_duplicate_vertices(true));
  for(const PI::Input_problem& p : report.problems)
    std::cout << PI::Input_problem::severity_name(p.severity) << " " << p.code << ": " << p.sentence << "\n";
  if(!report.is_valid()) return 2;

  try {
    // Named parameters: more roots give more candidate loops (shorter loops, more time).
    const PI::Surface_topology_result<Mesh> topo =
      PI::Surface_topology<Mesh>()(mesh, PIP::number_of_roots(24).maximum_refinements(2));

    std::cout << path << ": " << num_vertices(mesh) << " vertices, " << num_faces(mesh) << " faces\n"
              << "genus " << topo.genus << ", boundary loops " << topo.number_of_boundary_loops()
              << ", Euler characteristic " << topo.euler_characteristic << "\n";
    const Mesh& loop_mesh = topo.loop_mesh(mesh); // the input, or its refinement when one was needed
    auto print = [&](const char* kind, const auto& loops) {
      for(std::size_t i = 0; i < loops.size(); ++i)
        std::cout << kind << " loop " << i << ": " << loops[i].vertices.size() << " vertices, length "
                  << loops[i].length << ", starts at " << loop_mesh.point(loops[i].vertices.front()) << "\n";
    };
    print("handle", topo.handle_loops); // bound disks inside the solid: where pants are cut
    print("tunnel", topo.tunnel_loops); // bound disks outside the solid
    for(const std::string& w : topo.warnings) std::cout << "warning: " << w << "\n";
  } catch(const PI::Error& e) {
    std::cerr << "error: " << e.reason() << ": " << e.what() << "\n";
    return e.exit_code();
  }
  return 0;
}
