// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Small_handle_removal: femur.off's two handles a few triangles across are closed (genus
// 2 -> 0), the surface stays one closed manifold without self-intersection and within the
// handles' size of the input; a torus' handle is far above any threshold and stays.

#include "test_support.h"

#include <CGAL/Polycube_IGA/Small_handle_removal.h>
#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Polycube_IGA/internal/bbox_diagonal.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <catch2/catch.hpp>

using namespace test_support;
namespace PI = CGAL::Polycube_IGA;
namespace PIP = CGAL::Polycube_IGA::parameters;

namespace {

/// The largest distance from a vertex of `a` to the surface `b`.
double farthest_vertex(const Mesh& a, const Mesh& b)
{
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  Tree tree(faces(b).first, faces(b).second, b);
  double far = 0.;
  for(auto v : vertices(a)) far = std::max(far, std::sqrt(tree.squared_distance(a.point(v))));
  return far;
}

} // namespace

TEST_CASE("small handles: femur.off's two handles a few triangles across are closed", "[small_handles]")
{
  const Mesh input = load(data("femur.off"));
  Mesh m = input;
  const PI::Small_handle_removal_result r = PI::Small_handle_removal<Point>()(m, PIP::small_handle_length(0.01));
  CHECK(r.genus_before == 2);
  CHECK(r.genus_after == 0);
  REQUIRE(r.closed.size() == 2);
  CHECK(r.warnings.empty());
  for(const auto& h : r.closed) {
    CHECK(h.relative < 0.01);
    CHECK(h.loop_edges <= 5);
  }
  CHECK(r.closed[0].length <= r.closed[1].length * 1.0001 + 1e-12); // shortest first, as found
  // A closed manifold surface of genus 0 without self-intersection, the same shape away from
  // the handles: every vertex within 1% of the diagonal of the input, and back.
  const PI::Surface_topology_result<Mesh> topo = PI::Surface_topology<Mesh>()(m);
  CHECK(topo.genus == 0);
  CHECK(topo.number_of_boundary_loops() == 0);
  CHECK_FALSE(CGAL::Polygon_mesh_processing::does_self_intersect(m));
  const double diagonal = PI::internal::mesh_bbox_diagonal(input);
  CHECK(farthest_vertex(m, input) < 0.01 * diagonal);
  CHECK(farthest_vertex(input, m) < 0.01 * diagonal);
  // Only the neighbourhoods of the handles changed.
  CHECK(std::abs(long(num_faces(m)) - long(num_faces(input))) < 200);

  // Deterministic: the same input gives the same mesh.
  Mesh again = input;
  PI::Small_handle_removal<Point>()(again, PIP::small_handle_length(0.01));
  REQUIRE(num_vertices(again) == num_vertices(m));
  bool same = true;
  for(auto v : vertices(m)) same = same && again.point(v) == m.point(v);
  CHECK(same);
}

TEST_CASE("small handles: a threshold below the loops, 0, or a torus' handle closes nothing", "[small_handles]")
{
  const Mesh femur = load(data("femur.off"));
  for(double fraction : {0., 0.001}) {
    Mesh m = femur;
    const PI::Small_handle_removal_result r = PI::Small_handle_removal<Point>()(m, PIP::small_handle_length(fraction));
    CHECK(r.closed.empty());
    CHECK(r.genus_after == 2);
    CHECK(num_faces(m) == num_faces(femur));
  }
  const Mesh torus = load(data("torus.obj"));
  Mesh m = torus;
  const PI::Small_handle_removal_result r = PI::Small_handle_removal<Point>()(m);
  CHECK(r.genus_before == 1);
  CHECK(r.closed.empty());
  CHECK(num_faces(m) == num_faces(torus));
}

TEST_CASE("small handles: a threshold below 0, of 1 or more, or NaN is refused", "[small_handles]")
{
  Mesh m = load(data("torus.obj"));
  for(double fraction : {-0.1, 1.0, std::numeric_limits<double>::quiet_NaN()}) {
    try {
      PI::Small_handle_removal<Point>()(m, PIP::small_handle_length(fraction));
      FAIL("accepted " << fraction);
    } catch(const PI::Invalid_input_error& e) {
      CHECK(std::string(e.reason()) == "invalid_parameter");
    }
  }
}

TEST_CASE("build CLI --small-handle-length closes femur.off's handles and reports them", "[small_handles][cli]")
{
  // A quick build (one grid, no retries): the report is what is checked, not the volume.
  const std::string xml = temp_path("femur_closed.xml"), report = temp_path("femur_closed.json");
  const std::string quick = " --max-grid 16 --min-grid 16 --min-degree 3 --belt-phases 1 --stretch-rounds 0 --relax-sweeps 0"
                            " --missing-part-cubes 0 --no-untangle --allow-invalid --quiet";
  const Cli_result r = run_cli("build '" + data("femur.off") + "' -o '" + xml + "' --report '" + report + "' --small-handle-length 0.01" + quick);
  REQUIRE(r.exit_code == 0);
  const std::string rep = slurp(report);
  CHECK(rep.find("\"input_genus\":2") != std::string::npos);
  CHECK(rep.find("\"genus\":0") != std::string::npos);
  CHECK(rep.find("\"layout_class\":\"sphere\"") != std::string::npos);
  CHECK(rep.find("\"loop\":\"tunnel\"") != std::string::npos);
  CHECK(rep.find("\"loop\":\"handle\"") != std::string::npos);
  CHECK(rep.find("\"hausdorff_to_input\"") != std::string::npos);
  // By default every handle stays.
  const Cli_result kept = run_cli("build '" + data("femur.off") + "' -o '" + xml + "' --report '" + report + "'" + quick);
  REQUIRE(kept.exit_code == 0);
  const std::string rep2 = slurp(report);
  CHECK(rep2.find("\"genus\":2") != std::string::npos);
  CHECK(rep2.find("\"small_handles_closed\":[]") != std::string::npos);
  CHECK(rep2.find("\"hausdorff_to_input\"") == std::string::npos);
  // The volume is invalid and the handles are tiny: the report says what would help.
  CHECK(rep2.find("\"valid\":false") != std::string::npos);
  CHECK(rep2.find("likely topological noise that no grid resolves; --small-handle-length 0.01 closes it") != std::string::npos);
  // Out of range: refused before any work.
  CHECK(run_cli("build '" + data("femur.off") + "' -o '" + xml + "' --small-handle-length 0.7").exit_code == 2);
}
