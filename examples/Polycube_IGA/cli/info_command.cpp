// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `polycube_iga info MESH [--json] [--merge-duplicates] [--drop-isolated]`:
// what the mesh is (counts, genus, boundary loops, handle and tunnel loops) and what is
// wrong with it. Invalid input: the problems are still printed, then exit code 2.

#include "arguments.h"
#include "command_registry.h"
#include "mesh_input.h"

#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Polycube_IGA/internal/json_writer.h>

#include <iostream>

namespace polycube_iga_cli {
namespace {

namespace PI = CGAL::Polycube_IGA;

template <class Loops>
void write_loops(PI::internal::Json_writer& w, const Loops& loops, const Input_mesh& input)
{
  w.begin_array();
  for(const auto& loop : loops) {
    w.begin_object().key("vertices").begin_array();
    for(auto v : loop.vertices) w.value(input.input_index(v));
    w.end_array().key("points").begin_array();
    for(const auto& p : loop.points) w.begin_array().value(p[0]).value(p[1]).value(p[2]).end_array();
    w.end_array().member("length", loop.length).end_object();
  }
  w.end_array();
}

void print_text(const Input_mesh& in, const PI::Surface_topology_result<Mesh>* topo)
{
  std::cout << "mesh: " << in.path << "\n"
            << "  input vertices " << in.report.input_vertices << ", input faces " << in.report.input_faces;
  if(in.valid()) std::cout << ", triangles " << num_faces(in.mesh);
  std::cout << ", components " << in.report.components << "\n";
  if(topo) {
    std::cout << "  genus " << topo->genus << ", boundary loops " << topo->number_of_boundary_loops()
              << ", Euler characteristic " << topo->euler_characteristic << "\n";
    auto lengths = [](const char* name, const auto& loops) {
      std::cout << "  " << name << " loops: " << loops.size();
      for(const auto& l : loops) std::cout << " [" << l.vertices.size() << " vertices, length " << l.length << "]";
      std::cout << "\n";
    };
    lengths("handle", topo->handle_loops);
    lengths("tunnel", topo->tunnel_loops);
    for(const auto& warning : topo->warnings) std::cout << "  warning: " << warning << "\n";
    if(topo->refinements)
      std::cout << "  loops traced on the mesh refined " << topo->refinements << " time(s) at edge midpoints\n";
  }
  for(const auto& p : in.report.problems)
    std::cout << "  " << PI::Input_problem::severity_name(p.severity) << " " << p.code << ": " << p.sentence << "\n";
}

int run_info(const Arguments& args)
{
  Parsed_arguments a(args, {"--json", "--merge-duplicates", "--drop-isolated", "--no-self-intersection-test"}, {});
  a.expect_positional(1, "one mesh file: polycube_iga info MESH [--json]");
  Input_mesh in = read_input_mesh(a.positional()[0], a);
  std::unique_ptr<PI::Surface_topology_result<Mesh>> topo;
  if(in.valid())
    topo.reset(new PI::Surface_topology_result<Mesh>(PI::Surface_topology<Mesh>()(in.mesh)));

  if(a.has("--json")) {
    PI::internal::Json_writer w(std::cout);
    w.begin_object()
      .member("file", in.path)
      .member("input_vertices", in.report.input_vertices)
      .member("input_faces", in.report.input_faces);
    if(topo) {
      w.member("vertices", topo->number_of_vertices)
        .member("faces", topo->number_of_faces)
        .member("edges", topo->number_of_edges)
        .member("components", in.report.components)
        .member("boundary_loops", topo->number_of_boundary_loops())
        .member("genus", topo->genus)
        .member("euler_characteristic", topo->euler_characteristic)
        .member("refinements", topo->refinements);
      w.key("handle_loops"); write_loops(w, topo->handle_loops, in);
      w.key("tunnel_loops"); write_loops(w, topo->tunnel_loops, in);
      w.key("warnings").array(topo->warnings);
      w.key("handle_tunnel_linking").begin_array();
      for(const auto& row : topo->handle_tunnel_linking) w.array(row);
      w.end_array();
    } else {
      w.member("components", in.report.components);
    }
    w.key("problems");
    in.report.write_problems_json(w);
    w.end_object();
    std::cout << "\n";
  } else {
    print_text(in, topo.get());
  }
  std::cout.flush();
  in.report.require_valid(); // invalid input: the report above, then error line and exit 2
  return 0;
}

Register_command info_command("info", {
  "report a mesh's counts, genus, boundary loops, handle/tunnel loops and problems",
  "usage: polycube_iga info MESH [--json] [--merge-duplicates] [--drop-isolated]\n"
  "                            [--no-self-intersection-test]\n"
  "  MESH                        .off .obj .ply .stl (ASCII or binary); polygons are triangulated\n"
  "  --json                      one JSON object on stdout: vertices, faces, components,\n"
  "                              boundary_loops, genus, euler_characteristic, handle_loops,\n"
  "                              tunnel_loops (each {vertices, points, length}), problems.\n"
  "                              Loop vertex indices refer to the input file; -1 marks a vertex\n"
  "                              added by refinement (its point is exact).\n"
  "  --merge-duplicates          merge vertices with identical coordinates\n"
  "  --drop-isolated             drop vertices used by no face\n"
  "  --no-self-intersection-test skip the (exact, O(n log n)) self-intersection test\n",
  run_info});

} // namespace
} // namespace polycube_iga_cli
