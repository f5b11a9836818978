// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Reading the mesh argument of a subcommand, with the repair options shared by all.

#ifndef POLYCUBE_IGA_CLI_MESH_INPUT_H
#define POLYCUBE_IGA_CLI_MESH_INPUT_H

#include "arguments.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polycube_IGA/IO/read_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <string>

namespace polycube_iga_cli {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

struct Input_mesh
{
  std::string path;
  Mesh mesh;
  CGAL::Polycube_IGA::Validation_report report;

  bool valid() const { return report.is_valid(); }

  /// Index in the input file of vertex v of the input mesh or of a refinement of it (whose
  /// first vertices are the input mesh's); -1 for a vertex added by refinement.
  long input_index(Mesh::Vertex_index v) const
  {
    if(std::size_t(v) >= num_vertices(mesh)) return -1;
    auto map = mesh.property_map<Mesh::Vertex_index, std::size_t>(
                 CGAL::Polycube_IGA::input_vertex_index_property()).first;
    return long(map[v]);
  }
};

inline Input_mesh read_input_mesh(const std::string& path, const Parsed_arguments& a)
{
  namespace PIP = CGAL::Polycube_IGA::parameters;
  Input_mesh in;
  in.path = path;
  in.report = CGAL::Polycube_IGA::read_triangle_mesh(
    path, in.mesh,
    PIP::merge_duplicate_vertices(a.has("--merge-duplicates"))
      .remove_isolated_vertices(a.has("--drop-isolated"))
      .check_self_intersections(!a.has("--no-self-intersection-test")));
  return in;
}

} // namespace polycube_iga_cli

#endif
