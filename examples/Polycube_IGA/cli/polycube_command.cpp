// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `polycube_iga polycube MESH [--json] [--vtk OUT.vtu] [--deformed OUT.vtu]`: the polycube
// map of a closed surface as the cuboid decomposition makes it (internal/polycube_map.h),
// and where and why it is refused: its frame, alignment, labels and charts, the faces the
// deformation leaves turned over, the boxes' layout or what is wrong with them. The files
// are written atomically, also for a refused map (that is what they are for); the exit code
// is then that of build --polycube (1, no_polycube_map).

#include "arguments.h"
#include "command_registry.h"
#include "mesh_input.h"

#include <CGAL/Polycube_IGA/Cuboid_decomposition.h>
#include <CGAL/Polycube_IGA/internal/atomic_file.h>
#include <CGAL/Polycube_IGA/internal/json_writer.h>
#include <CGAL/Polycube_IGA/internal/polycube_map.h>
#include <CGAL/Polycube_IGA/internal/vtu_writer.h>

#include <cmath>
#include <iostream>
#include <optional>

namespace polycube_iga_cli {
namespace {

namespace PI = CGAL::Polycube_IGA;

/// The surface at `points` (by vertex) with cell data label (0 to 5: axis 2k along, 2k + 1
/// against), chart and turned (1 for a face the deformation left turned over or flat).
void write_map_vtu(const std::string& path, const PI::internal::Polycube_map_attempt<Point>& a,
                   const std::vector<std::array<double, 3>>& points)
{
  namespace pii = PI::internal;
  const Mesh& m = a.mesh;
  const std::vector<int> chart = pii::label_charts(m, a.label);
  pii::Vtu_cells cells{"label", "chart", "turned"};
  const auto vim = CGAL::get_initialized_vertex_index_map(m);
  for(auto f : faces(m)) {
    const std::size_t i = std::size_t(f);
    const int type = cells.append_face(m, f, vim);
    cells.close_cell(type, {a.label[i], chart[i], !a.turned.empty() && a.turned[i] ? 1 : 0});
  }
  pii::write_file_atomically(path, [&](std::ostream& os) { pii::write_vtu(os, points, cells); });
}

int run_polycube(const Arguments& args)
{
  Parsed_arguments a(args, {"--json", "--merge-duplicates", "--drop-isolated", "--no-self-intersection-test"},
                     {"--vtk", "--deformed"});
  a.expect_positional(1, "one mesh file: polycube_iga polycube MESH");
  for(const char* option : {"--vtk", "--deformed"})
    if(a.has(option) && (a.get(option).empty() || a.get(option).back() == '/'))
      throw PI::Invalid_input_error("bad_arguments", std::string(option) + " expects a file name OUT.vtu");
  Input_mesh in = read_input_mesh(a.positional()[0], a);
  in.report.require_valid();
  if(!CGAL::is_closed(in.mesh))
    throw PI::Invalid_input_error("wrong_topology", "a polycube map needs a closed surface; this one has boundary edges");

  const PI::internal::Polycube_map_attempt<Point> map = PI::internal::polycube_map_attempt(in.mesh);
  // The boxes, as the build lays them out. The map is made again there, up to the attempt's
  // time once more (3holes.obj, a polycube on graph-cut labels: 0.13 s); only this command
  // pays it, and a refused map is not made again.
  std::optional<PI::Polycube_layout<Point>> layout;
  std::string refusal = map.position ? "" : "the surface deformed to its labels is not a polycube: " + map.why;
  if(map.position) {
    try {
      layout = PI::Cuboid_decomposition<Mesh>()(in.mesh, PI::parameters::polycube_map(true));
    } catch(const PI::Error& e) {
      refusal = e.what();
    }
  }
  std::size_t interior_nodes = 0;
  for(std::size_t n = 0; layout && n < layout->nodes.size(); ++n) interior_nodes += layout->is_interior_node(n) ? 1 : 0;
  if(a.has("--vtk")) write_map_vtu(a.get("--vtk"), map, PI::internal::vtu_points(map.mesh));
  if(a.has("--deformed")) {
    const std::vector<Eigen::Vector3d>& deformed = map.position ? *map.position : map.refused_position;
    if(deformed.size() == num_vertices(map.mesh)) {
      std::vector<std::array<double, 3>> points(deformed.size());
      for(std::size_t v = 0; v < deformed.size(); ++v) points[v] = {{deformed[v].x(), deformed[v].y(), deformed[v].z()}};
      write_map_vtu(a.get("--deformed"), map, points);
    } else
      std::cerr << "warning: --deformed not written: the deformation's solve failed\n";
  }

  if(a.has("--json")) {
    PI::internal::Json_writer w(std::cout);
    w.begin_object().key("frame").begin_array();
    for(int r = 0; r < 3; ++r) w.begin_array().value(map.frame(r, 0)).value(map.frame(r, 1)).value(map.frame(r, 2)).end_array();
    w.end_array()
      .member("alignment", map.alignment)
      .member("faces", num_faces(map.mesh))
      .member("charts", map.charts)
      .member("label_border_weight", map.border_weight)
      .member("remeshed_edge", map.remeshed_edge)
      .member("normal_smoothing", map.normal_smoothing)
      .member("polycube", bool(map.position))
      .member("faces_turned", map.faces_turned())
      .member("boxes", layout ? layout->cuboids.size() : std::size_t(0))
      .member("interior_nodes", interior_nodes)
      .member("refusal", refusal)
      .end_object();
    std::cout << "\n";
  } else {
    // Six decimals: the rounding residues of an axis-aligned frame (1e-17) read as 0.
    auto shown = [](double x) {
      const double r = std::round(x * 1e6) / 1e6;
      return r == 0. ? 0. : r;
    };
    std::cout << "frame axes";
    for(int r = 0; r < 3; ++r)
      std::cout << (r ? ", (" : " (") << shown(map.frame(r, 0)) << " " << shown(map.frame(r, 1)) << " " << shown(map.frame(r, 2)) << ")";
    std::cout << "; alignment " << map.alignment << "\n" << num_faces(map.mesh) << " faces (edges between chart borders split), "
              << map.charts << " charts, ";
    if(map.border_weight > 0.) std::cout << "graph-cut labels at border weight " << map.border_weight << "\n";
    else if(map.remeshed_edge > 0.)
      std::cout << "tied faces decided, on a copy remeshed to edges of " << 100. * map.remeshed_edge << "% of the diagonal"
                << (map.normal_smoothing ? ", normals smoothed" : "") << "\n";
    else std::cout << "the nearest labels\n";
    if(layout)
      std::cout << "a polycube: " << layout->cuboids.size() << " boxes, " << interior_nodes << " of their corners inside the solid, "
                << layout->patches.size() << " patches\n";
    else if(map.position) std::cout << "a polycube, but " << refusal << "\n";
    else std::cout << "not a polycube: " << map.why << "\n";
  }
  if(!layout) throw PI::Internal_error("no_polycube_map", refusal);
  return 0;
}

Register_command polycube_command("polycube", {
  "the polycube map of a closed surface, and where and why it is refused",
  "usage: polycube_iga polycube MESH [--json] [--vtk OUT.vtu] [--deformed OUT.vtu]\n"
  "  The map the build tries (--polycube, its first attempt for CAD parts, its retry):\n"
  "  faces labelled with the nearest of the six directions of a frame, small charts merged,\n"
  "  the surface deformed until each chart is planar, the polycube split into boxes; when\n"
  "  those labels make no polycube, graph-cut labels at border weights 0.01 and 0.02, then\n"
  "  faces halfway between two directions (45-degree features) decided by the creases round\n"
  "  them, on copies remeshed to edges of 2 to 3% of the diagonal.\n"
  "  --json        {frame: [3 axes], alignment, faces, charts, label_border_weight (0: the\n"
  "                nearest labels), remeshed_edge (0: the input's mesh; else the tied\n"
  "                faces' labels on a copy remeshed to edges of this fraction of the\n"
  "                diagonal), normal_smoothing, polycube, faces_turned, boxes,\n"
  "                interior_nodes (box corners inside the solid), refusal}: polycube\n"
  "                says whether the deformation is one; refusal is empty when the boxes\n"
  "                make a layout; a refused map shows the nearest labels\n"
  "  --vtk OUT.vtu the surface (edges between chart borders split) with cell data label\n"
  "                (0 to 5: axis k along 2k, against 2k + 1), chart, and turned (1: a face\n"
  "                the deformation left turned over or flat)\n"
  "  --deformed OUT.vtu  the same cells at the deformed positions (the polycube, or what\n"
  "                the deformation left when it is none)\n"
  "  exit 1 with no_polycube_map when the map or its boxes are refused (the files are\n"
  "  written first); exit 2 with wrong_topology for a surface with a boundary\n",
  run_polycube});

} // namespace
} // namespace polycube_iga_cli
