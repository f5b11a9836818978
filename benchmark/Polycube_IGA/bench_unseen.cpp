// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Suite `unseen`: issue 5's "done when" measured on meshes the tests and the tuning never
// used. Two kinds of case, each built once with the defaults of `polycube_iga build` (no
// untangling of a result that stays invalid, since the command writes no invalid volume):
//   - shared-data meshes no test reads (a CAD fan disk and a gear, a capped cylinder, a
//     denser anchor, the armadillo, femurs of the population);
//   - CAD blocks that are not boxes, made here as unions of unit cubes (an L, a T, a U, a
//     staircase, a plate with a hole, a boss and a lug whose planes cross inside it;
//     meshes::union_of_cubes(), 6 x 6 squares per cube face): the simplest CAD parts after a
//     box, which `build` lays out on its sharp edges;
//   - the test meshes remeshed (among them two CAD parts with fillets and round holes, which
//     go to their polycube maps first): PMP::isotropic_remeshing to about `target_faces` faces,
//     with the edges whose faces meet at over 50 degrees, the border edges, and the
//     vertices where such edges do not pass straight through kept as constraints, so the
//     shape is the same and every triangle (hence every map, cut and arc) new;
//   - a second corpus of new shapes, benchmark/Polycube_IGA/data (README there): 12 CAD
//     parts (a flange with bolt holes, an L bracket, a mug, a solid tee, a bent thick pipe,
//     a box with three holes, a cube with crossing holes, a stepped shaft, a plate with six
//     holes, and turned parts: a flanged bushing, a grooved pulley, a five-spoke wheel of
//     genus 6) and 8 smooth shapes (a limbed blob, a pretzel, three tori, a twisted torus, a
//     banana, plates with four and six holes, four tori in a square), genus 0 to 6, as
//     they are.
// A remeshed surface is validated as `build` validates a file (a remeshing that makes
// faces intersect gives an input row, not a build). Per case: class, genus, valid (every
// patch's det J certified positive and the boundary within 2% of the diagonal), patches
// left uncertified, Hausdorff distance over the diagonal, the build's wall clock against
// the same-run CHOLMOD baseline of the mesh suites, and the untangling's work in billions of
// Jacobian samples (what Untangling_budget counts: a figure that does not depend on the
// machine, to compare with the default budget of 10). The build is deterministic,
// so one run each. The closing line counts the valid cases.
//
//   build/bin/polycube_iga_benchmark unseen            # every case (about an hour)
//   build/bin/polycube_iga_benchmark --quick unseen    # the cases that build in seconds

#include "bench_meshes.h"

#include <CGAL/polycube_iga.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace polycube_iga_bench {
namespace {

namespace PI = CGAL::Polycube_IGA;
namespace PMP = CGAL::Polygon_mesh_processing;
using meshes::Mesh;

struct Unseen_case
{
  const char* file;      ///< relative to the shared data directory, "test:" + test data name, "bench:" + benchmark data name, or "block:" + blocks[] name
  std::size_t faces;     ///< remeshed to about this many faces; 0: as it is
  bool quick;            ///< part of --quick
};

// Test meshes whose shapes the tests cover, remeshed; then shared meshes no test reads.
const Unseen_case cases[] = {
  {"cgal/sphere.off", 5000, true},           {"cgal/cube-meshed.off", 5000, true},
  {"cgal/mushroom.off", 5000, true},         {"cinolib/maxFace.obj", 5000, true},
  {"test:bent_tube.off", 5000, true},        {"cgal/blade.off", 5000, false},
  {"cinolib/torus.obj", 5000, true},         {"cgal/pipe.off", 5000, true},
  {"cgal/knot.off", 5000, true},             {"test:square_ring.off", 5000, false},
  {"cgal/head.off", 5000, true},             {"test:ybranch.off", 5000, true},
  {"test:ybranch_jagged.off", 5000, true},   {"cgal/mech-holes-shark.off", 5000, false},
  {"cgal/eight.off", 5000, true},            {"cgal/double-torus-example.off", 5000, true},
  {"cgal/double-torus-3-holes.off", 5000, false}, {"cgal/joint.off", 5000, false},
  {"cinolib/3holes.obj", 5000, true},        {"cgal/3torus.off", 5000, false},
  {"cgal/anchor.off", 5000, false},          {"test:ring4.off", 5000, true},
  {"test:ring5.off", 5000, true},            {"test:chain5.off", 5000, true},
  {"test:plate5.off", 5000, true},           {"test:chain6.off", 5000, true},
  {"test:plate6.off", 5000, true},           {"cgal/rotor.off", 5000, false},
  {"test:t_block_filleted.off", 5000, true}, {"test:plate_two_round_holes.off", 5000, true},
  {"cgal/cylinder.off", 0, true},            {"cgal/pinion.off", 0, true},
  {"cgal/fandisk.off", 0, false},            {"cgal/anchor_dense.off", 0, false},
  {"cgal/armadillo.off", 0, false},          {"population/femur/S002_Femur.ply", 0, true},
  {"population/femur/S010_Femur.ply", 0, true},
  {"block:L", 0, true},                      {"block:T", 0, true},
  {"block:U", 0, true},                      {"block:staircase", 0, true},
  {"block:bossed_plate", 0, true},
  {"bench:cad_flange_5holes.off", 0, false}, {"bench:cad_L_bracket_2holes.off", 0, true},
  {"bench:cad_mug_torus_handle.off", 0, true}, {"bench:cad_tee_solid.off", 0, false},
  {"bench:cad_elbow_tube.off", 0, false},    {"bench:cad_box_3holes.off", 0, false},
  {"bench:cad_cube_cross_holes.off", 0, false}, {"bench:cad_stepped_shaft.off", 0, true},
  {"bench:org_blobby_4limbs.off", 0, true},  {"bench:org_pretzel_genus2.off", 0, true},
  {"bench:org_triple_torus_genus3.off", 0, true}, {"bench:org_twisted_torus.off", 0, true},
  {"bench:org_banana.off", 0, true},         {"bench:org_plate_4holes.off", 0, true},
  {"bench:cad_plate_6holes.off", 0, false},  {"bench:org_plate_6holes.off", 0, true},
  {"bench:org_quad_torus_genus4.off", 0, true}, {"bench:cad_flanged_bushing.off", 0, true},
  {"bench:cad_pulley_vgroove.off", 0, true}, {"bench:cad_spoked_wheel.off", 0, false},
};

/// The CAD blocks, as unit cubes (x, y, z): each a plate extruded from an orthogonal polygon.
struct Block
{
  const char* name;
  std::vector<std::array<int, 3>> cells;
};

std::vector<std::array<int, 3>> extruded(const std::vector<std::array<int, 2>>& squares, int height)
{
  std::vector<std::array<int, 3>> cells;
  for(const auto& s : squares)
    for(int z = 0; z < height; ++z) cells.push_back({s[0], s[1], z});
  return cells;
}

const Block blocks[] = {
  {"L", extruded({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {0, 1}, {0, 2}}, 2)},
  {"T", extruded({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {2, 1}, {2, 2}, {2, 3}}, 2)},
  {"U", extruded({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {0, 2}, {2, 1}, {2, 2}}, 1)},
  {"staircase", {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}, {0, 0, 2}, {0, 1, 2}}},
  // A 5 by 3 plate, 2 thick, with a hole at (3, 1), a boss on top at (1, 1) and a lug on its
  // side at (5, 1) one high: the planes of the three cross inside the plate (interior nodes).
  {"bossed_plate", [] {
     std::vector<std::array<int, 3>> c = extruded({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {0, 1}, {1, 1}, {2, 1}, {4, 1},
                                                   {0, 2}, {1, 2}, {2, 2}, {3, 2}, {4, 2}}, 2);
     c.push_back({1, 1, 2});
     c.push_back({5, 1, 0});
     return c;
   }()},
};

/// Isotropic remeshing to about `target_faces` faces of equilateral triangles, sharp edges (dihedral
/// turn over 50 degrees) and border edges constrained: they may be split or collapsed along
/// themselves, never flipped; their corners stay.
void remesh(Mesh& m, std::size_t target_faces)
{
  const double area = CGAL::to_double(PMP::area(m));
  const double edge_length = std::sqrt(4. * area / (std::sqrt(3.) * double(target_faces)));
  auto sharp = m.add_property_map<Mesh::Edge_index, bool>("e:unseen_sharp", false).first;
  PMP::detect_sharp_edges(m, 50., sharp);
  for(auto e : edges(m))
    if(is_border(e, m)) put(sharp, e, true);
  auto corner = m.add_property_map<Mesh::Vertex_index, bool>("v:unseen_corner", false).first;
  for(auto v : vertices(m)) {
    int k = 0;
    for(auto h : CGAL::halfedges_around_target(v, m)) k += get(sharp, edge(h, m)) ? 1 : 0;
    put(corner, v, k != 0 && k != 2);
  }
  PMP::isotropic_remeshing(faces(m), edge_length, m,
                           CGAL::parameters::number_of_iterations(5).edge_is_constrained_map(sharp)
                             .vertex_is_constrained_map(corner).protect_constraints(false).relax_constraints(true));
  m.remove_property_map(sharp);
  m.remove_property_map(corner);
  m.collect_garbage();
}

/// The mesh as `build` would read it from a file: validated, with self-intersections.
bool validated(const Mesh& in, Mesh& out, std::string& problem)
{
  std::vector<meshes::Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  for(auto v : vertices(in)) points.push_back(in.point(v));
  for(auto f : faces(in)) {
    polygons.emplace_back();
    for(auto v : vertices_around_face(halfedge(f, in), in)) polygons.back().push_back(std::size_t(v));
  }
  const auto soup = PI::prepare_polygon_soup(points, polygons);
  try {
    soup.report.require_valid();
  } catch(const PI::Error& e) {
    problem = e.reason();
    return false;
  }
  PI::build_triangle_mesh(soup, out);
  return true;
}

struct Outcome
{
  std::string name, layout_class, error;
  std::size_t faces = 0, patches = 0, uncertified = 0;
  int genus = 0;
  bool valid = false;
  double hausdorff = 0, seconds = 0, baseline = 0;
  double untangling_work = 0; ///< Jacobian samples the untangling visited (Untangling_budget)
};

Outcome run_case(const Options& opt, const Unseen_case& c)
{
  Outcome o;
  const std::string file = c.file;
  const bool in_tests = file.rfind("test:", 0) == 0, in_bench = file.rfind("bench:", 0) == 0, block = file.rfind("block:", 0) == 0;
  const std::string path = in_tests   ? std::string(POLYCUBE_IGA_TEST_DATA_DIR) + "/" + file.substr(5)
                           : in_bench ? std::string(POLYCUBE_IGA_BENCH_DATA_DIR) + "/" + file.substr(6)
                                      : opt.data_dir + "/" + file;
  o.name = block ? file.substr(6) + " block" : meshes::base_name(path) + (c.faces ? " ~" + std::to_string(c.faces) : std::string());
  Mesh read, mesh;
  if(block) {
    for(const Block& b : blocks)
      if(file.substr(6) == b.name) meshes::union_of_cubes(b.cells, 6, read);
  } else if(!meshes::read_subdivided(path, 0, read)) {
    o.error = "cannot read " + path;
    return o;
  }
  if(c.faces) remesh(read, c.faces);
  if(!validated(read, mesh, o.error)) {
    o.error = "input: " + o.error;
    return o;
  }
  o.faces = num_faces(mesh);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const auto model = PI::build_trivariate_model(mesh, PI::parameters::untangle_invalid_result(false));
    o.valid = model.is_valid();
    o.genus = model.layout.genus;
    o.layout_class = PI::layout_class_name(model.layout.layout_class);
    o.patches = model.volume.volume.number_of_patches();
    for(const auto& b : model.volume.quality.certified) o.uncertified += b.certified_positive ? 0 : 1;
    o.hausdorff = model.volume.distance.relative;
    o.untangling_work = model.untangling_work;
  } catch(const PI::Error& e) {
    o.error = e.reason();
  }
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double assembly = 0, residual = 0;
  o.baseline = meshes::cholmod_laplacian_baseline(mesh, opt.repetitions, assembly, residual);

  char label[96];
  std::snprintf(label, sizeof(label), "%s (%zuf)", o.name.c_str(), o.faces);
  report("unseen", label,
         {{"faces", double(o.faces)}, {"genus", double(o.genus)}, {"valid", o.valid ? 1. : 0.},
          {"failed", o.error.empty() ? 0. : 1.}, {"patches", double(o.patches)},
          {"uncertified_patches", double(o.uncertified)}, {"hausdorff_over_diagonal", o.hausdorff},
          {"untangling_work", o.untangling_work}},
         {{"build", o.seconds}}, "cholmod", o.baseline);
  return o;
}

void run_suite(const Options& opt)
{
  meshes::One_core core;
  std::printf("# suite unseen: defaults of polycube_iga build, one run each, %s\n",
              core.description());
  std::vector<Outcome> rows;
  for(const Unseen_case& c : cases)
    if(c.quick || !opt.quick) rows.push_back(run_case(opt, c));
  std::printf("\n# unseen: valid = every det J certified positive and the boundary within 2%% of the diagonal\n");
  std::printf("%-34s %7s %-9s %2s %6s %11s %8s %8s %9s %10s\n", "mesh", "faces", "class", "g", "valid", "uncertified", "H/diag",
              "build s", "build/bl", "untangle G");
  std::size_t valid = 0;
  for(const Outcome& o : rows) {
    valid += o.valid ? 1 : 0;
    if(!o.error.empty()) {
      std::printf("%-34s %7zu  failed: %s\n", o.name.c_str(), o.faces, o.error.c_str());
      continue;
    }
    std::printf("%-34s %7zu %-9s %2d %6s %5zu / %-4zu %7.2f%% %8.1f %9.0f %10.3f\n", o.name.c_str(), o.faces, o.layout_class.c_str(),
                o.genus, o.valid ? "yes" : "no", o.uncertified, o.patches, 100 * o.hausdorff, o.seconds, o.seconds / o.baseline,
                o.untangling_work / 1e9);
  }
  std::printf("# valid: %zu of %zu\n", valid, rows.size());
  std::fflush(stdout);
}

static Register_suite unseen_suite("unseen", run_suite);

} // namespace
} // namespace polycube_iga_bench
