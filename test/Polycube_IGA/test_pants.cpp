// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Pants_decomposition on genus 1-4 meshes with and without boundary and on generated plates
// (genus 11; genus 5 with 7 boundary loops): counts 2g+b-2 and 3g+b-3, every pants a
// connected genus-0 surface with 3 boundaries, cycles simple and pairwise disjoint,
// neighbours consistent, and every cut cycle of a closed solid bounding inside it (its
// Gauss linking number with every outward push-off of a homology basis is 0). validate()
// names each broken invariant on corrupted decompositions; the VTK writer's file reads back.

#include "test_geometry.h"
#include "test_support.h"
#include "vtu_text.h"

#include <CGAL/Polycube_IGA/IO/pants_vtk.h>
#include <CGAL/Polycube_IGA/Pants_decomposition.h>

#include <algorithm>
#include <cmath>
#include <set>

#include <catch2/catch.hpp>

using namespace test_support;
namespace PI = CGAL::Polycube_IGA;
namespace PIP = CGAL::Polycube_IGA::parameters;
using Pants = PI::Pants_decomposition<Mesh>;

namespace {

void check_pants(const Mesh& input, const Pants::Result& r, int genus, int boundaries)
{
  CHECK(r.genus == genus);
  CHECK(int(r.boundary_loops) == boundaries);
  CHECK(int(r.pants.size()) == 2 * genus + boundaries - 2);
  CHECK(int(r.number_of_cut_cycles()) == 3 * genus + boundaries - 3);
  const PI::Pants_validation v = Pants::validate(input, r);
  for(const auto& p : v.problems) UNSCOPED_INFO(p);
  CHECK(v.is_valid());
  // Neighbours: symmetric across every cycle.
  for(std::size_t p = 0; p < r.pants.size(); ++p)
    for(int s = 0; s < 3; ++s) {
      const int c = r.pants[p].boundaries[s], q = r.pants[p].neighbours[s];
      if(r.cycles[c].kind == PI::Pants_cycle<Mesh>::INPUT_BOUNDARY) { CHECK(q == -1); continue; }
      REQUIRE(q >= 0);
      const auto& other = r.pants[q];
      bool found = false;
      for(int t = 0; t < 3; ++t) found = found || (other.boundaries[t] == c && other.neighbours[t] == int(p));
      CHECK(found);
    }
  // Each cycle appears as a boundary of one pants per side: input boundaries once, others twice.
  std::vector<int> uses(r.cycles.size(), 0);
  for(const auto& p : r.pants) for(int c : p.boundaries) ++uses[c];
  for(std::size_t c = 0; c < r.cycles.size(); ++c)
    CHECK(uses[c] == (r.cycles[c].kind == PI::Pants_cycle<Mesh>::INPUT_BOUNDARY ? 1 : 2));
}

/// On a closed solid, every cut cycle bounds inside: it links no outward push-off.
void check_cycles_bound_inside(const Mesh& input, const Pants::Result& r)
{
  const auto topo = PI::Surface_topology<Mesh>()(input);
  const Mesh& tm = topo.loop_mesh(input);
  const Geometry geo = outward_geometry(tm);
  for(const auto& c : r.cycles) {
    if(c.kind == PI::Pants_cycle<Mesh>::INPUT_BOUNDARY) continue;
    std::vector<V3> pts;
    for(const auto& p : c.points) pts.emplace_back(p[0], p[1], p[2]);
    for(const auto& b : topo.homology_basis)
      CHECK(gauss_linking(pts, points_of(tm, b.vertices, &geo, +1)) == 0);
  }
}

/// True when one of validate()'s problems contains `what`.
bool names(const PI::Pants_validation& v, const std::string& what)
{
  for(const auto& p : v.problems) UNSCOPED_INFO(p);
  return std::any_of(v.problems.begin(), v.problems.end(),
                     [&](const std::string& p) { return p.find(what) != std::string::npos; });
}

/// eight.off (genus 2), its topology with tunnel loops, and its decomposition (valid).
struct Eight
{
  Mesh mesh = load(data("eight.off"));
  PI::Surface_topology_result<Mesh> topology = PI::Surface_topology<Mesh>()(mesh);
  Pants::Result pants = Pants()(mesh, PIP::surface_topology(topology));
  Eight() { REQUIRE(Pants::validate(mesh, pants, topology).is_valid()); }
};

} // namespace

#define PANTS_CASE(FILE, GENUS, BOUNDARIES, LINKING)                                     \
  TEST_CASE("pants decomposition of " FILE, "[pants][corpus]")                          \
  {                                                                                    \
    const Mesh m = load(data(FILE));                                                   \
    const Pants::Result r = Pants()(m);                                                \
    check_pants(m, r, GENUS, BOUNDARIES);                                              \
    if(BOUNDARIES == 0 && LINKING) check_cycles_bound_inside(m, r);                    \
  }

PANTS_CASE("eight.off", 2, 0, true)
PANTS_CASE("double-torus-example.off", 2, 0, true)
PANTS_CASE("joint.off", 2, 0, true)
PANTS_CASE("double-torus-3-holes.off", 2, 3, true)
PANTS_CASE("elephant.off", 3, 0, true)
PANTS_CASE("3holes.obj", 3, 0, true)
// 19 vertices: its vertex normals are no valid push-off directions for the test's own check.
PANTS_CASE("3torus.off", 3, 0, false)
PANTS_CASE("anchor.off", 4, 0, true)
PANTS_CASE("mech-holes-shark.off", 0, 4, true)

TEST_CASE("a refined decomposition is the same decomposition on a finer mesh", "[pants][refine]")
{
  // anchor.off: two of its cycles run one edge apart around a thin handle.
  const Mesh m = load(data("anchor.off"));
  const Pants::Result r = Pants()(m);
  const Pants::Result f = PI::refined_pants_decomposition(m, r);
  check_pants(m, f, 4, 0);
  CHECK(f.refinements == r.refinements + 1);
  const Mesh& coarse = r.mesh(m);
  const Mesh& fine = f.mesh(m);
  CHECK(num_faces(fine) == 4 * num_faces(coarse));
  for(std::size_t k = 0; k < r.pants.size(); ++k) CHECK(f.pants[k].faces.size() == 4 * r.pants[k].faces.size());
  for(std::size_t c = 0; c < r.cycles.size(); ++c) {
    const auto &a = r.cycles[c], &b = f.cycles[c];
    CHECK(b.kind == a.kind);
    REQUIRE(b.vertices.size() == 2 * a.vertices.size());
    // Same course: every other vertex is the old one, the ones between are edge midpoints.
    bool same = true;
    for(std::size_t i = 0; i < a.vertices.size(); ++i) {
      same = same && b.vertices[2 * i] == a.vertices[i];
      const auto p = fine.point(b.vertices[2 * i + 1]);
      const auto q = CGAL::midpoint(coarse.point(a.vertices[i]), coarse.point(a.vertices[(i + 1) % a.vertices.size()]));
      same = same && p == q && b.points[2 * i + 1] == std::array<double, 3>{{p.x(), p.y(), p.z()}};
    }
    CHECK(same);
    CHECK(std::abs(b.length - a.length) <= 1e-12 * a.length);
  }
  check_cycles_bound_inside(m, f);
}

TEST_CASE("a single pants patch passes through unchanged", "[pants][corpus]")
{
  const Mesh m = load(data("head.off"));
  const Pants::Result r = Pants()(m);
  check_pants(m, r, 0, 3);
  REQUIRE(r.pants.size() == 1);
  CHECK(r.pants[0].faces.size() == num_faces(m));
  CHECK(r.refinements == 0);
  for(const auto& c : r.cycles) CHECK(c.kind == PI::Pants_cycle<Mesh>::INPUT_BOUNDARY);
}

TEST_CASE("generated plate of genus 11", "[pants][generated]")
{
  const Mesh m = load(write_text("pants_g11.off", voxel_plate_with(11, 0)));
  const Pants::Result r = Pants()(m);
  check_pants(m, r, 11, 0);
}

TEST_CASE("generated plate of genus 5 with 7 boundary loops", "[pants][generated]")
{
  const Mesh m = load(write_text("pants_g5_b7.off", voxel_plate_with(5, 7)));
  check_pants(m, Pants()(m), 5, 7);
}

TEST_CASE("generated plates of genus 1 with 1 and 2 boundary loops", "[pants][generated]")
{
  const Mesh m1 = load(write_text("pants_g1_b1.off", voxel_plate_with(1, 1)));
  check_pants(m1, Pants()(m1), 1, 1);
  const Mesh m2 = load(write_text("pants_g1_b2.off", voxel_plate_with(1, 2)));
  check_pants(m2, Pants()(m2), 1, 2);
}

namespace {
/// Longest handle loop and longest cut of a decomposition.
std::pair<double, double> longest_handle_and_cut(const Pants::Result& r)
{
  double handle = 0, cut = 0;
  for(const auto& c : r.cycles) {
    if(c.kind == PI::Pants_cycle<Mesh>::HANDLE_LOOP) handle = std::max(handle, c.length);
    if(c.kind == PI::Pants_cycle<Mesh>::CUT) cut = std::max(cut, c.length);
  }
  return {handle, cut};
}
} // namespace

TEST_CASE("the cuts of a plate with holes are meridians of its bars", "[pants][pairs]")
{
  // plate5.off: its handle loops are meridians of bars between holes (2.5 to 2.8 long). The
  // pair with the shortest estimate alone gave cuts around whole junctions (up to 9.1 long),
  // parallel strips of pants between the rows of holes; traced and compared, the pairs' cuts
  // are meridians too (up to 3.6).
  const Mesh m = load(data("plate5.off"));
  const Pants::Result r = Pants()(m);
  check_pants(m, r, 5, 0);
  const auto [handle, cut] = longest_handle_and_cut(r);
  CHECK(cut <= 1.5 * handle);
  const Pants::Result greedy = Pants()(m, PIP::cut_pair_trials(1));
  check_pants(m, greedy, 5, 0);
  CHECK(longest_handle_and_cut(greedy).second > 3 * handle);
}

TEST_CASE("the cycles of a wheel cut its spokes and rim midway between junctions", "[pants][centre]")
{
  // wheel3.off: a rim and a hub joined by three round spokes at 17, 137 and 257 degrees
  // (spokes from radius 0.8 to 2.6, the rim from 2.6 to 3). Shortest cycles ran where the
  // mesh has rings of edges, beside the junctions (the rim's cycles 2, 9 and 17 degrees
  // from a spoke, two spokes' cycles at their rim ends), and the pants there had no room
  // for a centre cuboid; moved to the middle of their tubes, each rim cycle is over 45
  // degrees from every spoke and each spoke's cycle lies along its middle half. The cuts
  // kept away from the holes, with the centring's doubled slope (the build's last retry on
  // closed surfaces), keep this.
  const bool away = GENERATE(false, true);
  INFO("cuts_away_from_holes " << away);
  const Mesh m = load(data("wheel3.off"));
  const Pants::Result r = Pants()(m, PIP::cuts_away_from_holes(away));
  check_pants(m, r, 3, 0);
  check_cycles_bound_inside(m, r);
  int on_rim = 0, on_spokes = 0;
  for(const auto& c : r.cycles) {
    double x = 0, y = 0;
    for(const auto& p : c.points) { x += p[0]; y += p[1]; }
    x /= double(c.points.size());
    y /= double(c.points.size());
    const double radius = std::hypot(x, y), angle = std::atan2(y, x) * 180 / CGAL_PI;
    INFO("cycle at radius " << radius << ", angle " << angle);
    if(radius > 2.6) {
      ++on_rim;
      for(double spoke : {17.19, 137.19, 257.19}) {
        const double d = std::abs(std::remainder(angle - spoke, 360.));
        CHECK(d > 45);
      }
    } else {
      ++on_spokes;
      CHECK(radius > 1.25);
      CHECK(radius < 2.15);
    }
  }
  CHECK(on_rim == 3);
  CHECK(on_spokes == 3);
}

TEST_CASE("cuts away from the holes: a closed surface's cycles bound inside, a surface with boundary keeps its own", "[pants][away]")
{
  // Closed: still a valid decomposition whose cuts bound inside the solid; other cycles on
  // 3holes.obj (eight.off's one cut, between its two handle loops, stays where it was).
  for(const char* file : {"eight.off", "3holes.obj"}) {
    INFO(file);
    const Mesh m = load(data(file));
    const Pants::Result shortest = Pants()(m), away = Pants()(m, PIP::cuts_away_from_holes(true));
    check_pants(m, away, shortest.genus, 0);
    check_cycles_bound_inside(m, away);
    bool other = false;
    for(std::size_t c = 0; c < away.cycles.size(); ++c) other = other || away.cycles[c].vertices != shortest.cycles[c].vertices;
    CHECK(other == (std::string(file) == "3holes.obj"));
  }
  // With boundary loops the caps end the tubes, and a torus with holes has its own rule: the
  // option changes nothing.
  for(const char* file : {"double-torus-3-holes.off", "mech-holes-shark.off"}) {
    INFO(file);
    const Mesh m = load(data(file));
    const Pants::Result shortest = Pants()(m), away = Pants()(m, PIP::cuts_away_from_holes(true));
    REQUIRE(away.cycles.size() == shortest.cycles.size());
    for(std::size_t c = 0; c < away.cycles.size(); ++c) CHECK(away.cycles[c].vertices == shortest.cycles[c].vertices);
  }
}

TEST_CASE("cut_pair_trials below 1 is rejected", "[pants][bad]")
{
  const Mesh m = load(data("eight.off"));
  try {
    Pants()(m, PIP::cut_pair_trials(0));
    FAIL("no error");
  } catch(const PI::Invalid_input_error& e) {
    CHECK(e.reason() == "invalid_parameter");
  }
}

TEST_CASE("surfaces with non-negative Euler characteristic have no pants decomposition", "[pants][bad]")
{
  for(const char* file : {"sphere.off", "mushroom.off", "blade.off", "torus.obj"}) {
    INFO(file);
    const Mesh m = load(data(file));
    try {
      Pants()(m);
      FAIL("no error");
    } catch(const PI::Unsupported_topology_error& e) {
      CHECK(e.reason() == "no_pants_decomposition");
      CHECK(e.exit_code() == 3);
    }
  }
}

TEST_CASE("pants decomposition is deterministic", "[pants][determinism]")
{
  const Mesh m = load(data("elephant.off"));
  const Pants::Result a = Pants()(m), b = Pants()(m);
  REQUIRE(a.cycles.size() == b.cycles.size());
  for(std::size_t c = 0; c < a.cycles.size(); ++c) CHECK(a.cycles[c].vertices == b.cycles[c].vertices);
  for(std::size_t p = 0; p < a.pants.size(); ++p) CHECK(a.pants[p].faces == b.pants[p].faces);
}

TEST_CASE("geometric criteria give valid decompositions", "[pants][criteria]")
{
  const Mesh m = load(data("elephant.off"));
  const Pants::Result minima = Pants()(m, PIP::cut_criterion(PI::Cut_criterion::MINIMA_RULE));
  check_pants(m, minima, 3, 0);
  const Pants::Result sym = Pants()(m, PIP::cut_criterion(PI::Cut_criterion::SYMMETRY)
                                          .symmetry_plane(std::array<double, 4>{0, 0, 1, 0}));
  check_pants(m, sym, 3, 0);
  // A precomputed topology is reused and gives the same result.
  const auto topo = PI::Surface_topology<Mesh>()(m, PIP::compute_tunnel_loops(false));
  const Pants::Result again = Pants()(m, PIP::surface_topology(topo));
  const Pants::Result plain = Pants()(m);
  REQUIRE(again.cycles.size() == plain.cycles.size());
  for(std::size_t c = 0; c < plain.cycles.size(); ++c) CHECK(again.cycles[c].vertices == plain.cycles[c].vertices);
}

TEST_CASE("CLI: pants --json and --write-pants", "[cli][pants]")
{
  const std::string dir = temp_path("pants_out");
  REQUIRE(std::system(("mkdir -p '" + dir + "'").c_str()) == 0);
  Cli_result r = run_cli("pants --json --write-pants '" + dir + "' '" + data("double-torus-3-holes.off") + "'");
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("\"genus\":2,") != std::string::npos);
  CHECK(r.out.find("\"boundary_loops\":3,") != std::string::npos);
  std::size_t pants = 0;
  for(std::size_t at = r.out.find("{\"faces\":"); at != std::string::npos; at = r.out.find("{\"faces\":", at + 1)) ++pants;
  CHECK(pants == 5);
  for(int k = 0; k < 5; ++k) {
    const Mesh p = load(dir + "/pants_" + std::to_string(k) + ".off");
    const auto t = PI::Surface_topology<Mesh>()(p);
    CHECK(t.genus == 0);
    CHECK(t.number_of_boundary_loops() == 3);
  }
  Cli_result sphere = run_cli("pants --json '" + data("sphere.off") + "'");
  CHECK(sphere.exit_code == 3);
  CHECK(sphere.err.rfind("error: no_pants_decomposition: ", 0) == 0);
  CHECK(sphere.out.empty());
  CHECK(run_cli("pants --criterion bogus '" + data("eight.off") + "'").exit_code == 2);
  CHECK(run_cli("pants --write-pants /nonexistent/dir '" + data("eight.off") + "'").exit_code == 2);
}

TEST_CASE("validate names swapped neighbours", "[pants][validate]")
{
  Eight e;
  Pants::Result r = e.pants;
  // Two slots of one pants with different neighbours; if every pants sees a single
  // neighbour, swap the lists of pants 0 and 1 instead.
  bool swapped = false;
  for(auto& p : r.pants)
    for(int s = 0; s < 3 && !swapped; ++s)
      for(int t = s + 1; t < 3 && !swapped; ++t)
        if(p.neighbours[s] != p.neighbours[t]) { std::swap(p.neighbours[s], p.neighbours[t]); swapped = true; }
  if(!swapped) {
    REQUIRE(r.pants.size() >= 2);
    REQUIRE(r.pants[0].neighbours != r.pants[1].neighbours);
    std::swap(r.pants[0].neighbours, r.pants[1].neighbours);
  }
  const PI::Pants_validation v = Pants::validate(e.mesh, r, e.topology);
  CHECK(names(v, "the neighbour across"));
  // A cycle between two pants that only one of them lists: it bounds one slot instead of two.
  Pants::Result once = e.pants;
  bool dropped = false;
  for(int k = 0; k < int(once.pants.size()) && !dropped; ++k)
    for(int t = 0; t < 3 && !dropped; ++t) {
      const int c = once.pants[k].boundaries[t], n = once.pants[k].neighbours[t];
      if(n < 0 || n == k) continue;
      for(int& b : once.pants[n].boundaries)
        if(b == c && !dropped) { b = (c + 1) % int(once.cycles.size()); dropped = true; }
    }
  REQUIRE(dropped);
  const PI::Pants_validation v1 = Pants::validate(e.mesh, once, e.topology);
  CHECK(names(v1, "bounds 1 pants slots instead of 2"));
  CHECK(names(v1, "back across"));
}

TEST_CASE("validate names a cycle that does not bound a disk inside the solid", "[pants][validate]")
{
  Eight e;
  // A handle loop (a meridian of a handle: it bounds inside) replaced by a tunnel loop
  // (around a hole: it bounds outside, and links the outward push-off of a meridian).
  REQUIRE(!e.topology.tunnel_loops.empty());
  REQUIRE(e.pants.refinements == e.topology.refinements);
  Pants::Result r = e.pants;
  auto handle = std::find_if(r.cycles.begin(), r.cycles.end(),
                             [](const auto& c) { return c.kind == PI::Pants_cycle<Mesh>::HANDLE_LOOP; });
  REQUIRE(handle != r.cycles.end());
  CHECK(!names(Pants::validate(e.mesh, r, e.topology), "does not bound a disk inside"));
  handle->vertices = e.topology.tunnel_loops[0].vertices;
  handle->points = e.topology.tunnel_loops[0].points;
  CHECK(names(Pants::validate(e.mesh, r, e.topology), "does not bound a disk inside the solid"));
  // The same without a topology given: validate() computes one.
  CHECK(names(Pants::validate(e.mesh, r), "does not bound a disk inside the solid"));
}

TEST_CASE("validate names a face missing from the pants", "[pants][validate]")
{
  Eight e;
  Pants::Result r = e.pants;
  r.pants[0].faces.pop_back();
  const PI::Pants_validation v = Pants::validate(e.mesh, r, e.topology);
  CHECK(names(v, "the pants do not cover every face"));
}

TEST_CASE("write_pants_vtu: the file reads back", "[pants][vtk]")
{
  Eight e;
  const Mesh& m = e.pants.mesh(e.mesh);
  const std::string path = temp_path("pants_eight.vtu");
  PI::IO::write_pants_vtu(path, e.mesh, e.pants);
  const std::string xml = file_text(path);
  REQUIRE(xml_tags_balance(xml));
  CHECK(attribute(xml, "VTKFile", "type") == "UnstructuredGrid");
  const std::size_t nf = num_faces(m), nc = e.pants.cycles.size();
  CHECK(attribute(xml, "Piece", "NumberOfPoints") == std::to_string(num_vertices(m)));
  CHECK(attribute(xml, "Piece", "NumberOfCells") == std::to_string(nf + nc));
  const std::vector<long> pants = integers(xml, "pants"), cycle = integers(xml, "cycle"), kind = integers(xml, "kind"),
                          types = integers(xml, "types"), offsets = integers(xml, "offsets");
  REQUIRE(pants.size() == nf + nc);
  REQUIRE(cycle.size() == nf + nc);
  REQUIRE(kind.size() == nf + nc);
  REQUIRE(types.size() == nf + nc);
  // Faces: triangles whose pants ids cover 0..P-1; cycles: closed poly lines with their ids and kinds.
  std::set<long> ids(pants.begin(), pants.begin() + long(nf));
  CHECK(ids.size() == e.pants.pants.size());
  CHECK(*ids.begin() == 0);
  CHECK(*ids.rbegin() == long(e.pants.pants.size()) - 1);
  for(std::size_t f = 0; f < nf; ++f) CHECK((types[f] == 5 && cycle[f] == -1 && kind[f] == -1));
  for(std::size_t c = 0; c < nc; ++c) {
    const std::size_t cell = nf + c;
    CHECK(types[cell] == 4);
    CHECK(pants[cell] == -1);
    CHECK(cycle[cell] == long(c));
    CHECK(kind[cell] == long(e.pants.cycles[c].kind));
    CHECK(offsets[cell] - offsets[cell - 1] == long(e.pants.cycles[c].vertices.size()) + 1);
  }
  // Unwritable: the package's error, and no file (nor temporary) left behind.
  const std::string bad = temp_path("no_such_dir") + "/x/pants.vtu";
  try {
    PI::IO::write_pants_vtu(bad, e.mesh, e.pants);
    FAIL("no error");
  } catch(const PI::Invalid_input_error& err) {
    CHECK(err.reason() == "unwritable_output");
  }
  CHECK(!exists(bad));
}

TEST_CASE("CLI: pants --vtk", "[cli][pants][vtk]")
{
  const std::string path = temp_path("cli_pants_3holes.vtu");
  std::remove(path.c_str());
  const Cli_result r = run_cli("pants --vtk '" + path + "' '" + data("3holes.obj") + "'");
  REQUIRE(r.exit_code == 0);
  const std::string xml = file_text(path);
  REQUIRE(xml_tags_balance(xml));
  const std::vector<long> pants = integers(xml, "pants"), kind = integers(xml, "kind");
  CHECK(*std::max_element(pants.begin(), pants.end()) == 3); // genus 3: 4 pants
  CHECK(std::count(kind.begin(), kind.end(), long(PI::Pants_cycle<Mesh>::HANDLE_LOOP)) == 3);
  CHECK(std::count(kind.begin(), kind.end(), long(PI::Pants_cycle<Mesh>::CUT)) == 3);
  // An unwritable path: exit 2 with the package's error, no file, nothing on stdout.
  const std::string bad = temp_path("no_such_dir") + "/pants.vtu";
  const Cli_result b = run_cli("pants --json --vtk '" + bad + "' '" + data("eight.off") + "'");
  CHECK(b.exit_code == 2);
  CHECK(b.err.rfind("error: unwritable_output: ", 0) == 0);
  CHECK(b.out.empty());
  CHECK(!exists(bad));
  CHECK(!exists(bad + ".tmp-polycube-iga"));
}
