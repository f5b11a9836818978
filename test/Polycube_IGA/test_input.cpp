// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Mesh input and validation: every reason code on a small file the test writes itself,
// the repairs, the formats (OFF, OBJ, PLY, binary and ASCII STL, polygons), and the CLI's
// exit codes and error lines.

#include "test_support.h"

#include <CGAL/Polycube_IGA/Input_validation.h>
#include <CGAL/Polycube_IGA/IO/read_triangle_mesh.h>
#include <CGAL/Polycube_IGA/parameters.h>

#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>

using namespace test_support;
namespace PI = CGAL::Polycube_IGA;
namespace PIP = CGAL::Polycube_IGA::parameters;

namespace {

const char* tetrahedron =
  "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

PI::Validation_report report_of(const std::string& name, const std::string& text)
{
  Mesh m;
  PI::Validation_report r = PI::read_triangle_mesh(write_text(name, text), m);
  if(!r.is_valid()) CHECK(num_faces(m) == 0); // nothing is built from an invalid input
  return r;
}

/// The report names `code` as an error, and the CLI fails with exit code 2 and one line
/// `error: <code>: ...` on stderr, printing nothing else there.
void require_rejected(const std::string& name, const std::string& text, const std::string& code)
{
  PI::Validation_report r = report_of(name, text);
  INFO(name);
  REQUIRE_FALSE(r.is_valid());
  const PI::Input_problem* p = r.find(code);
  REQUIRE(p != nullptr);
  CHECK(p->severity == PI::Input_problem::ERROR);
  CHECK(p->count >= 1);
  CHECK_FALSE(p->sentence.empty());
  Cli_result cli = run_cli("info '" + temp_path(name) + "'");
  CHECK(cli.exit_code == 2);
  bool found = false;
  std::istringstream lines(cli.err);
  std::string line;
  int count = 0;
  while(std::getline(lines, line)) {
    ++count;
    found = found || line.rfind("error: ", 0) == 0;
  }
  CHECK(found);
  CHECK(count == 1);
  CHECK(cli.err.find("error: ") != std::string::npos);
}

} // namespace

TEST_CASE("valid tetrahedron reads with no problem and keeps input indices", "[input]")
{
  Mesh m;
  PI::Validation_report r = PI::read_triangle_mesh(write_text("tet.off", tetrahedron), m);
  REQUIRE(r.is_valid());
  CHECK(r.problems.empty());
  CHECK(num_vertices(m) == 4);
  CHECK(num_faces(m) == 4);
  auto vin = m.property_map<Mesh::Vertex_index, std::size_t>(PI::input_vertex_index_property()).first;
  for(auto v : vertices(m)) CHECK(vin[v] == std::size_t(v));
}

TEST_CASE("empty input", "[input][bad]")
{
  require_rejected("empty.off", "OFF\n0 0 0\n", "empty");
  require_rejected("no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "empty");
}

TEST_CASE("unreadable input", "[input][bad]")
{
  require_rejected("garbage.off", "this is not a mesh\n", "unreadable");
  require_rejected("zero_bytes.obj", "", "unreadable");
  require_rejected("mesh.xyz", tetrahedron, "unreadable");
  Mesh m;
  PI::Validation_report r = PI::read_triangle_mesh(temp_path("does_not_exist.off"), m);
  CHECK(r.has("unreadable"));
  CHECK(run_cli("info '" + temp_path("does_not_exist.off") + "'").exit_code == 2);
}

TEST_CASE("non-finite coordinates", "[input][bad]")
{
  require_rejected("nan.off", "OFF\n4 4 0\n0 0 0\n1 0 nan\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
                   "non_finite_coordinates");
  require_rejected("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
                   "non_finite_coordinates");
  PI::Validation_report r = report_of("nan2.off", "OFF\n4 4 0\n0 0 0\n1 0 nan\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  REQUIRE(r.find("non_finite_coordinates"));
  CHECK(r.find("non_finite_coordinates")->examples.at(0).at(0) == 1);
}

TEST_CASE("non-manifold edge", "[input][bad]")
{
  // Three triangles around edge (0,1).
  require_rejected("nm_edge.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n",
                   "non_manifold_edge");
  PI::Validation_report r = report_of("nm_edge2.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  const PI::Input_problem* p = r.find("non_manifold_edge");
  REQUIRE(p);
  CHECK(p->count == 1);
  CHECK(p->examples.at(0) == std::vector<std::size_t>{0, 1});
}

TEST_CASE("non-manifold vertex", "[input][bad]")
{
  // Two tetrahedra sharing vertex 0 only.
  require_rejected("nm_vertex.off",
                   "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n"
                   "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 5\n3 0 6 4\n3 0 5 6\n3 4 6 5\n",
                   "non_manifold_vertex");
}

TEST_CASE("non-orientable surface", "[input][bad]")
{
  // A Moebius strip of 5 quads, split into triangles.
  std::vector<std::array<double, 3>> pts;
  const int n = 5;
  for(int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n, c = std::cos(t), s = std::sin(t), h = std::cos(t / 2) * 0.3, z = std::sin(t / 2) * 0.3;
    pts.push_back({(1 + h) * c, (1 + h) * s, z});
    pts.push_back({(1 - h) * c, (1 - h) * s, -z});
  }
  std::vector<Polygon> tris;
  for(int i = 0; i < n; ++i) {
    std::size_t a = 2 * i, b = 2 * i + 1, c = 2 * ((i + 1) % n), d = 2 * ((i + 1) % n) + 1;
    if(i == n - 1) std::swap(c, d); // the half twist
    tris.push_back({a, b, d});
    tris.push_back({a, d, c});
  }
  require_rejected("moebius.off", off_text(pts, tris), "non_orientable");
}

TEST_CASE("self-intersecting surface", "[input][bad]")
{
  // An octahedron whose top vertex is pulled down and sideways through the bottom half.
  require_rejected("self_intersecting.off",
                   "OFF\n6 8 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n0 0 -2\n1.5 0 -0.5\n"
                   "3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n3 1 0 5\n3 2 1 5\n3 3 2 5\n3 0 3 5\n",
                   "self_intersecting");
}

TEST_CASE("degenerate face", "[input][bad]")
{
  require_rejected("degenerate.off",
                   "OFF\n5 5 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.5 0 0\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 1\n",
                   "degenerate_face");
  require_rejected("repeated_index.off",
                   "OFF\n4 5 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 1 1 2\n",
                   "degenerate_face");
}

TEST_CASE("duplicate face", "[input][bad]")
{
  require_rejected("duplicate_face.off",
                   "OFF\n4 5 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 2 1 0\n",
                   "duplicate_face");
}

TEST_CASE("multiple components", "[input][bad]")
{
  PI::Validation_report r = report_of("two_parts.off",
    "OFF\n8 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n5 0 0\n6 0 0\n5 1 0\n5 0 1\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 4 6 5\n3 4 5 7\n3 4 7 6\n3 5 6 7\n");
  CHECK(r.components == 2);
  require_rejected("two_parts.off",
    "OFF\n8 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n5 0 0\n6 0 0\n5 1 0\n5 0 1\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 4 6 5\n3 4 5 7\n3 4 7 6\n3 5 6 7\n",
    "multiple_components");
}

TEST_CASE("invalid vertex index", "[input][bad]")
{
  // CGAL's readers already refuse such files (unreadable); the soup check names it.
  const std::vector<Point> points{Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
  PI::Prepared_soup<Point> soup = PI::prepare_polygon_soup(points, std::vector<Polygon>{{0, 1, 9}});
  REQUIRE(soup.report.find("invalid_vertex_index"));
  CHECK(soup.report.find("invalid_vertex_index")->examples.at(0).at(0) == 0);
  Cli_result cli = run_cli("info '" + write_text("bad_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n") + "'");
  CHECK(cli.exit_code == 2);
  CHECK(cli.err.rfind("error: ", 0) == 0);
}

TEST_CASE("every problem is listed and not only the first", "[input][bad]")
{
  // A degenerate face and a separate component at once.
  PI::Validation_report r = report_of("many.off",
    "OFF\n9 9 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n5 0 0\n6 0 0\n5 1 0\n5 0 1\n0.5 0 0\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 4 6 5\n3 4 5 7\n3 4 7 6\n3 5 6 7\n3 0 8 1\n");
  CHECK(r.has("degenerate_face"));
  CHECK(r.has("multiple_components"));
}

TEST_CASE("isolated and duplicate vertices are warnings or repairs on request", "[input][repair]")
{
  // Vertex 4 is isolated; vertex 5 duplicates vertex 3 and is used by one face.
  const std::string text = "OFF\n6 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n9 9 9\n0 0 1\n"
                           "3 0 2 1\n3 0 1 3\n3 0 5 2\n3 1 2 3\n";
  const std::string path = write_text("repairs.off", text);
  Mesh plain;
  PI::Validation_report r = PI::read_triangle_mesh(path, plain);
  REQUIRE(r.find("isolated_vertices"));
  CHECK(r.find("isolated_vertices")->severity == PI::Input_problem::WARNING);
  REQUIRE(r.find("duplicate_vertices"));
  CHECK(r.find("duplicate_vertices")->severity == PI::Input_problem::WARNING);
  // Without merging, vertices 3 and 5 touch: the surface meets itself there.
  CHECK(r.has("self_intersecting"));
  CHECK(num_faces(plain) == 0);

  Mesh repaired;
  r = PI::read_triangle_mesh(path, repaired, PIP::merge_duplicate_vertices(true).remove_isolated_vertices(true));
  REQUIRE(r.is_valid());
  CHECK(r.find("duplicate_vertices")->severity == PI::Input_problem::REPAIRED);
  CHECK(r.find("isolated_vertices")->severity == PI::Input_problem::REPAIRED);
  CHECK(num_vertices(repaired) == 4);
  CHECK(CGAL::is_closed(repaired));
  auto vin = repaired.property_map<Mesh::Vertex_index, std::size_t>(PI::input_vertex_index_property()).first;
  std::set<std::size_t> inputs;
  for(auto v : vertices(repaired)) inputs.insert(vin[v]);
  CHECK(inputs == std::set<std::size_t>{0, 1, 2, 3});
}

TEST_CASE("inconsistently oriented soup is oriented", "[input][repair]")
{
  Mesh m;
  PI::Validation_report r = PI::read_triangle_mesh(
    write_text("flipped.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 3 1\n3 0 3 2\n3 1 2 3\n"), m);
  REQUIRE(r.is_valid());
  REQUIRE(r.find("reoriented_faces"));
  CHECK(r.find("reoriented_faces")->count == 1); // face 1 disagreed with the others
  CHECK(CGAL::is_closed(m));
}

TEST_CASE("formats: OBJ polygons and ASCII STL and binary STL and PLY", "[input][formats]")
{
  // A cube of quads in OBJ, with texture/normal indices.
  Mesh cube = load(write_text("cube.obj",
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nvt 0 0\nvn 0 0 1\n"
    "f 1/1/1 4/1/1 3/1/1 2/1/1\nf 5/1/1 6/1/1 7/1/1 8/1/1\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"));
  CHECK(num_vertices(cube) == 8);
  CHECK(num_faces(cube) == 12);
  CHECK(CGAL::is_closed(cube));

  Mesh ascii = load(write_text("tet.stl",
    "solid t\n"
    "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
    "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
    "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "endsolid t\n"));
  CHECK(num_vertices(ascii) == 4);
  CHECK(CGAL::is_closed(ascii));

  // Binary STL: 80-byte header, count, then 50 bytes per facet.
  std::string bin(80, ' ');
  auto put32 = [&](std::uint32_t x) { bin.append(reinterpret_cast<const char*>(&x), 4); };
  auto putf = [&](float x) { bin.append(reinterpret_cast<const char*>(&x), 4); };
  const float tri[4][3][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
                              {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  put32(4);
  for(const auto& t : tri) {
    for(int k = 0; k < 3; ++k) putf(0);
    for(const auto& p : t) for(float c : p) putf(c);
    bin.append(2, '\0');
  }
  Mesh binary = load(write_text("tet_binary.STL", bin));
  CHECK(num_vertices(binary) == 4);
  CHECK(num_faces(binary) == 4);
  CHECK(CGAL::is_closed(binary));

  Mesh ply = load(data("femur_S001.ply"));
  CHECK(num_vertices(ply) == 7313);
  CHECK(num_faces(ply) == 14622);
}

TEST_CASE("CLI: usage errors and help", "[cli]")
{
  CHECK(run_cli("").exit_code == 2);
  CHECK(run_cli("--help").exit_code == 0);
  Cli_result unknown = run_cli("no-such-command");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.rfind("error: bad_arguments: ", 0) == 0);
  Cli_result missing = run_cli("info");
  CHECK(missing.exit_code == 2);
  CHECK(missing.err.rfind("error: bad_arguments: ", 0) == 0);
  CHECK(run_cli("info --frobnicate x.off").exit_code == 2);
  CHECK(run_cli("info --help").exit_code == 0);
}

TEST_CASE("CLI: info --json prints the problems of an invalid mesh and then fails", "[cli]")
{
  const std::string path = write_text("cli_nm.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  Cli_result r = run_cli("info --json '" + path + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("\"code\":\"non_manifold_edge\"") != std::string::npos);
  CHECK(r.err.rfind("error: non_manifold_edge: ", 0) == 0);
}
