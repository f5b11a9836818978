// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Reads a triangle mesh, cuts it into pairs of pants, checks every invariant of the
// decomposition, and writes one OFF file per pants.
//
//   pants_decomposition_example [MESH [OUTPUT_DIR]]
//       (defaults: the shared elephant.off, genus 3; the current directory)

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polycube_IGA/IO/read_triangle_mesh.h>
#include <CGAL/Polycube_IGA/Pants_decomposition.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/OFF.h>

#include <iostream>
#include <string>
#include <vector>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PI = CGAL::Polycube_IGA;
namespace PIP = CGAL::Polycube_IGA::parameters;

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : std::string(POLYCUBE_IGA_EXAMPLE_DATA_DIR "/cgal/elephant.off");
  const std::string out_dir = argc > 2 ? argv[2] : std::string(".");

  Mesh mesh;
  const PI::Validation_report report = PI::read_triangle_mesh(path, mesh);
  if(!report.is_valid()) {
    for(const PI::Input_problem& p : report.problems) std::cerr << p.code << ": " << p.sentence << "\n";
    return 2;
  }

  try {
    // Default criterion: shortest cycles. Others: PIP::cut_criterion(PI::Cut_criterion::MINIMA_RULE),
    // or SYMMETRY with PIP::symmetry_plane(std::array<double,4>{a, b, c, d}).
    const PI::Pants_decomposition_result<Mesh> r = PI::Pants_decomposition<Mesh>()(mesh);

    std::cout << path << ": genus " << r.genus << ", " << r.boundary_loops << " boundary loops -> "
              << r.pants.size() << " pants, " << r.number_of_cut_cycles() << " cut cycles"
              << (r.refinements ? " (on a refined mesh)" : "") << "\n";
    for(std::size_t c = 0; c < r.cycles.size(); ++c)
      std::cout << "cycle " << c << " (" << PI::Pants_cycle<Mesh>::kind_name(r.cycles[c].kind) << "): "
                << r.cycles[c].vertices.size() << " vertices, length " << r.cycles[c].length << "\n";

    // Counts, connectivity, genus 0 and three boundaries per pants, disjoint simple cycles.
    const PI::Pants_validation v = PI::Pants_decomposition<Mesh>::validate(mesh, r);
    for(const std::string& p : v.problems) std::cerr << "invalid: " << p << "\n";
    if(!v.is_valid()) return 1;

    // Each pants as a mesh of its own; `to_source[i]` is the vertex of r.mesh(mesh) behind vertex i.
    for(std::size_t k = 0; k < r.pants.size(); ++k) {
      Mesh pants;
      std::vector<Mesh::Vertex_index> to_source;
      PI::internal::extract_pants_mesh(mesh, r, k, pants, &to_source);
      const std::string file = out_dir + "/pants_" + std::to_string(k) + ".off";
      if(!CGAL::IO::write_OFF(file, pants, CGAL::parameters::stream_precision(17))) {
        std::cerr << "cannot write " << file << "\n";
        return 1;
      }
      const auto& p = r.pants[k];
      std::cout << file << ": " << num_faces(pants) << " faces, boundary cycles " << p.boundaries[0] << " "
                << p.boundaries[1] << " " << p.boundaries[2] << ", neighbours " << p.neighbours[0] << " "
                << p.neighbours[1] << " " << p.neighbours[2] << "\n";
    }
  } catch(const PI::Error& e) {
    // chi >= 0 (sphere, disk, cylinder, torus): reason no_pants_decomposition, exit code 3.
    std::cerr << "error: " << e.reason() << ": " << e.what() << "\n";
    return e.exit_code();
  }
  return 0;
}
