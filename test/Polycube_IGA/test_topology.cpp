// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Surface_topology on every topological class of the shared corpus and on generated
// surfaces (voxel plates up to genus 11 with up to 7 boundary loops, thin and thick tori):
// exact genus and boundary counts, and the loop invariants — simple, along edges, handle
// loops pairwise disjoint and together non-separating — with handle vs tunnel checked by an
// independent method: Gauss-integral linking numbers (the stage counts projected crossings),
// with push-offs along the test's own area-weighted normals.

#include "test_support.h"
#include "test_geometry.h"

#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Polycube_IGA/internal/linking_number.h>
#include <CGAL/Polycube_IGA/internal/mesh_refinement.h>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <numeric>

using namespace test_support;
namespace PI = CGAL::Polycube_IGA;
namespace PIP = CGAL::Polycube_IGA::parameters;
using Result = PI::Surface_topology_result<Mesh>;

namespace {

/// Simple closed loop along edges of `m`, whose points and length match its vertices.
void check_loop_is_simple_edge_cycle(const Mesh& m, const PI::Surface_loop<Mesh>& loop, bool euclidean = true)
{
  REQUIRE(loop.vertices.size() >= 3);
  REQUIRE(loop.points.size() == loop.vertices.size());
  std::set<Mesh::Vertex_index> distinct(loop.vertices.begin(), loop.vertices.end());
  CHECK(distinct.size() == loop.vertices.size());
  double length = 0;
  for(std::size_t k = 0; k < loop.vertices.size(); ++k) {
    auto a = loop.vertices[k], b = loop.vertices[(k + 1) % loop.vertices.size()];
    CHECK(CGAL::halfedge(a, b, m).second);
    length += (pos(m, a) - pos(m, b)).norm();
    CHECK(loop.points[k][0] == m.point(a).x());
  }
  if(euclidean) CHECK(loop.length == Approx(length).epsilon(1e-9));
}

/// Faces reachable from each other without crossing a loop edge: one component means the
/// loops together do not separate the surface.
std::size_t components_after_cutting(const Mesh& m, const std::vector<PI::Surface_loop<Mesh>>& loops)
{
  std::set<Mesh::Edge_index> cut;
  for(const auto& loop : loops)
    for(std::size_t k = 0; k < loop.vertices.size(); ++k)
      cut.insert(edge(CGAL::halfedge(loop.vertices[k], loop.vertices[(k + 1) % loop.vertices.size()], m).first, m));
  std::map<Mesh::Face_index, int> comp;
  int count = 0;
  for(auto f0 : faces(m)) {
    if(comp.count(f0)) continue;
    ++count;
    std::vector<Mesh::Face_index> stack{f0};
    comp[f0] = count;
    while(!stack.empty()) {
      auto f = stack.back(); stack.pop_back();
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        if(cut.count(edge(h, m)) || is_border(opposite(h, m), m)) continue;
        auto g = face(opposite(h, m), m);
        if(!comp.count(g)) { comp[g] = count; stack.push_back(g); }
      }
    }
  }
  return std::size_t(count);
}

/// Every invariant of the handle and tunnel loops; `independent_linking` also runs the
/// projection-based linking check (needs a mesh whose vertex normals are sane).
void check_topology(const Mesh& input, const Result& r, int genus, int boundaries, bool independent_linking,
                    bool all_tunnels = true, bool euclidean = true)
{
  CHECK(r.genus == genus);
  CHECK(int(r.number_of_boundary_loops()) == boundaries);
  CHECK(r.euler_characteristic == 2 - 2 * genus - boundaries);
  for(const auto& cycle : r.boundary_cycles)
    for(auto h : cycle) CHECK(CGAL::is_border(h, input));
  const Mesh& m = r.loop_mesh(input);
  REQUIRE(int(r.handle_loops.size()) == genus);
  REQUIRE(int(r.homology_basis.size()) == 2 * genus);
  if(all_tunnels) REQUIRE(int(r.tunnel_loops.size()) == genus);
  for(const auto& l : r.handle_loops) check_loop_is_simple_edge_cycle(m, l, euclidean);
  for(const auto& l : r.tunnel_loops) check_loop_is_simple_edge_cycle(m, l, euclidean);
  for(const auto& l : r.homology_basis) check_loop_is_simple_edge_cycle(m, l, euclidean);
  // Handle loops: pairwise disjoint, off the boundary, together non-separating.
  std::set<Mesh::Vertex_index> used;
  for(const auto& l : r.handle_loops)
    for(auto v : l.vertices) {
      CHECK(used.insert(v).second);
      CHECK_FALSE(m.is_border(v));
    }
  CHECK(components_after_cutting(m, r.handle_loops) == 1);
  if(genus == 0 || !independent_linking) return;

  const Geometry geo = outward_geometry(m);
  Eigen::MatrixXd ht(genus, r.tunnel_loops.size());
  for(std::size_t i = 0; i < r.handle_loops.size(); ++i) {
    for(std::size_t j = 0; j < r.handle_loops.size(); ++j) {
      INFO("handle " << i << " links handle " << j << " pushed outwards");
      CHECK(gauss_linking(points_of(m, r.handle_loops[i].vertices), points_of(m, r.handle_loops[j].vertices, &geo, +1)) == 0);
    }
    for(std::size_t j = 0; j < r.tunnel_loops.size(); ++j)
      {
      // A handle bounds a disk inside: it cannot link anything outside.
      CHECK(gauss_linking(points_of(m, r.handle_loops[i].vertices), points_of(m, r.tunnel_loops[j].vertices, &geo, +1)) == 0);
      ht(i, j) = gauss_linking(points_of(m, r.handle_loops[i].vertices), points_of(m, r.tunnel_loops[j].vertices, &geo, -1));
    }
  }
  for(std::size_t i = 0; i < r.tunnel_loops.size(); ++i)
    for(std::size_t j = 0; j < r.tunnel_loops.size(); ++j) {
      INFO("tunnel " << i << " links tunnel " << j << " pushed inwards");
      CHECK(gauss_linking(points_of(m, r.tunnel_loops[i].vertices), points_of(m, r.tunnel_loops[j].vertices, &geo, -1)) == 0);
    }
  if(int(r.tunnel_loops.size()) == genus) {
    // Handles and tunnels are dual bases: their linking matrix is unimodular.
    CHECK(std::abs(std::abs(ht.determinant()) - 1.0) < 1e-9);
    for(int i = 0; i < genus; ++i)
      for(int j = 0; j < genus; ++j) CHECK(std::abs(ht(i, j)) == std::abs(r.handle_tunnel_linking[i][j]));
  }
}

Result topology_of(const Mesh& m) { return PI::Surface_topology<Mesh>()(m); }

} // namespace

// ---------------------------------------------------------------- the shared corpus

#define CORPUS_CASE(FILE, GENUS, BOUNDARIES, LINKING)                                  \
  TEST_CASE("topology of " FILE, "[topology][corpus]")                                 \
  {                                                                                    \
    const Mesh m = load(data(FILE));                                                   \
    check_topology(m, topology_of(m), GENUS, BOUNDARIES, LINKING);                     \
  }

CORPUS_CASE("sphere.off", 0, 0, true)
CORPUS_CASE("mushroom.off", 0, 1, true)
CORPUS_CASE("blade.off", 0, 2, true)
CORPUS_CASE("head.off", 0, 3, true)
CORPUS_CASE("mech-holes-shark.off", 0, 4, true)
CORPUS_CASE("pipe.off", 1, 0, true)
CORPUS_CASE("rotor.off", 1, 0, true)
CORPUS_CASE("torus.obj", 1, 0, true)
CORPUS_CASE("eight.off", 2, 0, true)
CORPUS_CASE("double-torus-example.off", 2, 0, true)
CORPUS_CASE("joint.off", 2, 0, true)
CORPUS_CASE("double-torus-3-holes.off", 2, 3, true)
// 19 vertices: its vertex normals are no valid push-off directions for the test's own check.
CORPUS_CASE("3torus.off", 3, 0, false)
CORPUS_CASE("elephant.off", 3, 0, true)
CORPUS_CASE("3holes.obj", 3, 0, true)
CORPUS_CASE("anchor.off", 4, 0, true)
// Tiny noisy handles: vertex normals there are useless for the test's own push-offs.
CORPUS_CASE("femur.off", 2, 0, false)

TEST_CASE("topology of knot.off: the handle loop is a meridian of the knotted tube", "[topology][corpus]")
{
  const Mesh m = load(data("knot.off"));
  Result r = topology_of(m);
  // A knotted solid torus has no disk outside it: the tunnel loop may be missing, with a warning.
  check_topology(m, r, 1, 0, true, /*all_tunnels*/ false);
  if(r.tunnel_loops.empty()) CHECK_FALSE(r.warnings.empty());
  // The meridian is far shorter than any loop around the knot.
  double bbox = 0;
  for(auto v : vertices(m)) bbox = std::max(bbox, pos(m, v).norm());
  CHECK(r.handle_loops[0].length < bbox);
}

// ---------------------------------------------------------------- generated surfaces

TEST_CASE("thin torus: the handle loop is the meridian and the tunnel loop the inner equator", "[topology][torus]")
{
  const double R = 3, r = 1;
  const Mesh m = load(write_text("thin_torus.off", torus_off(R, r, 64, 24)));
  Result t = topology_of(m);
  check_topology(m, t, 1, 0, true);
  CHECK(t.handle_loops[0].length == Approx(2 * M_PI * r).epsilon(0.02));
  CHECK(t.tunnel_loops[0].length == Approx(2 * M_PI * (R - r)).epsilon(0.02));
}

TEST_CASE("thick torus: the handle loop is the meridian although the tunnel loop is shorter", "[topology][torus]")
{
  // Shortest loops alone would call the short inner equator the handle.
  const double R = 1.25, r = 1;
  const Mesh m = load(write_text("thick_torus.off", torus_off(R, r, 64, 24)));
  Result t = topology_of(m);
  check_topology(m, t, 1, 0, true);
  CHECK(t.handle_loops[0].length == Approx(2 * M_PI * r).epsilon(0.02));
  CHECK(t.tunnel_loops[0].length == Approx(2 * M_PI * (R - r)).epsilon(0.05));
  CHECK(t.tunnel_loops[0].length < t.handle_loops[0].length);
}

TEST_CASE("inward-oriented torus gives the same handle loop", "[topology][torus]")
{
  std::string text = torus_off(1.25, 1, 48, 16);
  // Reverse every triangle: "3 a b c" -> "3 c b a".
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  while(std::getline(in, line)) {
    std::istringstream ls(line);
    int n; std::size_t a, b, c;
    if(line.rfind("3 ", 0) == 0 && (ls >> n >> a >> b >> c) && !(ls >> line)) out << "3 " << c << " " << b << " " << a << "\n";
    else out << line << "\n";
  }
  const Mesh m = load(write_text("inverted_torus.off", out.str()));
  Result t = topology_of(m);
  check_topology(m, t, 1, 0, true);
  CHECK(t.handle_loops[0].length == Approx(2 * 16 * std::sin(M_PI / 16)).epsilon(1e-6));
}

TEST_CASE("voxel plate of genus 11", "[topology][generated]")
{
  const Mesh m = load(write_text("plate_g11.off", voxel_plate_with(11, 0)));
  check_topology(m, topology_of(m), 11, 0, true);
}

TEST_CASE("voxel plate of genus 5 with 7 boundary loops", "[topology][generated]")
{
  const Mesh m = load(write_text("plate_g5_b7.off", voxel_plate_with(5, 7)));
  check_topology(m, topology_of(m), 5, 7, true);
}

TEST_CASE("voxel plate of genus 0 with 7 boundary loops returns at once", "[topology][generated]")
{
  const Mesh m = load(write_text("plate_g0_b7.off", voxel_plate_with(0, 7)));
  Result r = topology_of(m);
  check_topology(m, r, 0, 7, true);
  CHECK(r.homology_basis.empty());
  CHECK(r.refinements == 0);
}

TEST_CASE("voxel plate of genus 2 with 1 boundary loop", "[topology][generated]")
{
  const Mesh m = load(write_text("plate_g2_b1.off", voxel_plate_with(2, 1)));
  check_topology(m, topology_of(m), 2, 1, true);
}

// ---------------------------------------------------------------- options and properties

TEST_CASE("topology is deterministic", "[topology][determinism]")
{
  const Mesh m = load(data("elephant.off"));
  Result a = topology_of(m), b = topology_of(m);
  REQUIRE(a.handle_loops.size() == b.handle_loops.size());
  for(std::size_t i = 0; i < a.handle_loops.size(); ++i) CHECK(a.handle_loops[i].vertices == b.handle_loops[i].vertices);
  for(std::size_t i = 0; i < a.tunnel_loops.size(); ++i) CHECK(a.tunnel_loops[i].vertices == b.tunnel_loops[i].vertices);
}

TEST_CASE("named parameters: edge weights and number of roots", "[topology][parameters]")
{
  Mesh m = load(data("eight.off"));
  // Unit weights: loops minimise the number of edges instead of their length.
  auto unit = m.add_property_map<Mesh::Edge_index, double>("e:unit", 1.0).first;
  Result r = PI::Surface_topology<Mesh>()(m, PIP::loop_edge_weight(unit).number_of_roots(4));
  check_topology(m, r, 2, 0, true, true, /*euclidean*/ false);
  for(const auto& l : r.handle_loops) CHECK(l.length == Approx(double(l.vertices.size())));

  Result no_tunnels = PI::Surface_topology<Mesh>()(m, PIP::compute_tunnel_loops(false));
  CHECK(no_tunnels.tunnel_loops.empty());
  CHECK(no_tunnels.handle_loops.size() == 2);

  auto bad = m.add_property_map<Mesh::Edge_index, double>("e:bad", -1.0).first;
  try {
    PI::Surface_topology<Mesh>()(m, PIP::loop_edge_weight(bad));
    FAIL("negative weights accepted");
  } catch(const PI::Invalid_input_error& e) {
    CHECK(e.reason() == "invalid_edge_weight");
  }
}

TEST_CASE("midpoint refinement keeps the surface and its topology", "[topology][refinement]")
{
  Mesh m = load(data("double-torus-3-holes.off"));
  const std::size_t f = num_faces(m), v = num_vertices(m);
  PI::internal::subdivide_at_edge_midpoints(m, get(CGAL::vertex_point, m));
  CHECK(num_faces(m) == 4 * f);
  CHECK(m.is_valid());
  for(std::size_t i = 0; i < v; ++i) CHECK(m.point(Mesh::Vertex_index(i)) == load(data("double-torus-3-holes.off")).point(Mesh::Vertex_index(i)));
  check_topology(m, topology_of(m), 2, 3, true);
}

TEST_CASE("multiple components are refused by the topology stage", "[topology][bad]")
{
  Mesh m = load(data("sphere.off"));
  Mesh other = load(data("sphere.off"));
  for(auto v : vertices(other)) other.point(v) = Point(other.point(v).x() + 10, other.point(v).y(), other.point(v).z());
  m.join(other);
  try {
    topology_of(m);
    FAIL("two components accepted");
  } catch(const PI::Invalid_input_error& e) {
    CHECK(e.reason() == "multiple_components");
  }
}

TEST_CASE("CLI: info --json reports counts and loops in input indices", "[cli][topology]")
{
  Cli_result r = run_cli("info --json '" + data("eight.off") + "'");
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find("\"genus\":2,") != std::string::npos);
  CHECK(r.out.find("\"boundary_loops\":0,") != std::string::npos);
  CHECK(r.out.find("\"vertices\":315,") != std::string::npos);
  CHECK(r.out.find("\"faces\":634,") != std::string::npos);
  CHECK(r.out.find("\"euler_characteristic\":-2,") != std::string::npos);
  CHECK(r.out.find("\"problems\":[]") != std::string::npos);
  // The first handle loop's first vertex and point agree with the input file.
  const std::size_t at = r.out.find("\"handle_loops\":[{\"vertices\":[");
  REQUIRE(at != std::string::npos);
  const std::size_t index = std::stoul(r.out.substr(at + 29));
  const std::size_t pts = r.out.find("\"points\":[[", at);
  std::istringstream coords(r.out.substr(pts + 11));
  double x; char comma; double y, z;
  coords >> x >> comma >> y >> comma >> z;
  const Mesh m = load(data("eight.off"));
  CHECK(m.point(Mesh::Vertex_index(index)) == Point(x, y, z));
  // Same output twice: deterministic to the byte.
  CHECK(run_cli("info --json '" + data("eight.off") + "'").out == r.out);
}
