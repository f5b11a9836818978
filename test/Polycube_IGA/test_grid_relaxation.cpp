// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Grid_relaxation.h on real layouts: eight.off's squeezed grids unfold and stay on the mesh,
// shared borders stay bit-identical, boundary loops stay put, and build_trivariate_model()
// uses the relaxed grids as its second attempt only when they are better.

#include "test_support.h"

#include <CGAL/Polycube_IGA/Cuboid_decomposition.h>
#include <CGAL/Polycube_IGA/Grid_relaxation.h>
#include <CGAL/Polycube_IGA/Patch_sampling.h>
#include <CGAL/Polycube_IGA/internal/triangle_projection.h>
#include <CGAL/polycube_iga.h>

#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/generators.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

using namespace test_support;
namespace PI = CGAL::Polycube_IGA;

namespace {

using Layout = PI::Polycube_layout<Point>;

struct Cell_figures
{
  int facing_against = 0;   ///< cells whose normal points against the mesh's
  int sheared = 0;          ///< cells whose two directions meet at less than 20 degrees
};

Cell_figures cell_figures(const Layout& L, const PI::Patch_grids& G)
{
  const PI::internal::Mesh_probe<Layout::Mesh> probe(L.mesh);
  Cell_figures f;
  const int N = G.segments;
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    if(L.patches[p].kind != Layout::SURFACE) continue;
    const PI::Point_grid& g = G.grids[p];
    for(int j = 0; j < N; ++j)
      for(int i = 0; i < N; ++i) {
        const Eigen::Vector3d du = g(i + 1, j) - g(i, j) + g(i + 1, j + 1) - g(i, j + 1);
        const Eigen::Vector3d dv = g(i, j + 1) - g(i, j) + g(i + 1, j + 1) - g(i + 1, j);
        const Eigen::Vector3d n = du.cross(dv);
        const Eigen::Vector3d c = 0.25 * (g(i, j) + g(i + 1, j) + g(i, j + 1) + g(i + 1, j + 1));
        if(n.dot(probe.closest_point(c).normal) < 0.) ++f.facing_against;
        if(n.norm() < std::sin(20. * 3.14159265358979323846 / 180.) * du.norm() * dv.norm()) ++f.sheared;
      }
  }
  return f;
}

/// Every grid's border rows are its arcs' samples, bit for bit.
bool borders_are_arc_samples(const Layout& L, const PI::Patch_grids& G)
{
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    PI::Point_grid b = G.grids[p];
    PI::internal::set_patch_border(b, G.segments, L, L.patches[p], G.arc_samples);
    if(b.points != G.grids[p].points) return false;
  }
  return true;
}

double largest_distance_to_mesh(const Layout& L, const PI::Patch_grids& G)
{
  const PI::internal::Mesh_probe<Layout::Mesh> probe(L.mesh);
  double d = 0.;
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    if(L.patches[p].kind == Layout::SURFACE)
      for(const auto& x : G.grids[p].points) d = std::max(d, (probe.closest_point(x).point - x).norm());
  return d;
}

/// A test mesh's layout, its grids at N samples per side, and those grids relaxed.
struct Relaxed
{
  Layout layout;
  PI::Patch_grids before, after;
  PI::Grid_relaxation_result result;
};

Relaxed relaxed(const std::string& name, int N)
{
  Relaxed x;
  x.layout = PI::Cuboid_decomposition<Mesh>()(load(data(name)));
  x.before = PI::sample_layout_patches(x.layout, PI::parameters::grid_resolution(N));
  x.after = x.before;
  x.result = PI::relax_surface_grids(x.layout, x.after, PI::Grid_relaxation_options());
  return x;
}

} // namespace

TEST_CASE("relaxed surface grids of eight.off unfold, widen their cells and stay on the mesh", "[grid_relaxation]")
{
  const Relaxed x = relaxed("eight.off", 16);
  const Layout& L = x.layout;
  const PI::Patch_grids &before = x.before, &after = x.after;
  const PI::Grid_relaxation_result& r = x.result;
  // Distinct points: nodes, N-1 per surface arc, (N-1)^2 per surface patch.
  std::size_t surface_arcs = 0, surface_patches = 0;
  std::vector<bool> seen(L.arcs.size(), false);
  for(const auto& pa : L.patches)
    if(pa.kind == Layout::SURFACE) {
      ++surface_patches;
      for(std::size_t a : pa.arcs)
        if(!seen[a]) seen[a] = true, ++surface_arcs;
    }
  CHECK(std::size_t(r.points) == L.nodes.size() + 15 * surface_arcs + 225 * surface_patches);
  CHECK(r.fixed_points == 0); // no boundary loop
  CHECK(r.sweeps >= 1);
  CHECK(r.sweeps <= 100);
  const Cell_figures f0 = cell_figures(L, before), f1 = cell_figures(L, after);
  INFO("cells facing against the mesh " << f0.facing_against << " -> " << f1.facing_against << ", sheared "
                                        << f0.sheared << " -> " << f1.sheared);
  // Measured: 16 -> 1 cells facing against the mesh, 415 -> 86 sheared.
  CHECK(f0.facing_against >= 8);
  CHECK(8 * f1.facing_against <= f0.facing_against);
  CHECK(4 * f1.sheared < f0.sheared);
  // On the mesh (closest points), and still one quad mesh: borders shared bit for bit.
  CHECK(largest_distance_to_mesh(L, after) < 1e-9);
  CHECK(borders_are_arc_samples(L, after));
  // The points did move, nodes included.
  CHECK(after.arc_samples != before.arc_samples);
  // Deterministic.
  PI::Patch_grids again = before;
  PI::relax_surface_grids(L, again, PI::Grid_relaxation_options());
  for(std::size_t p = 0; p < L.patches.size(); ++p) CHECK(again.grids[p].points == after.grids[p].points);
}

TEST_CASE("grid relaxation keeps boundary loops and, if asked, nodes in place", "[grid_relaxation]")
{
  // mushroom.off is a disk: its cap spans the boundary loop.
  const Relaxed x = relaxed("mushroom.off", 8);
  const Layout& L = x.layout;
  const PI::Patch_grids &before = x.before, &after = x.after;
  const PI::Grid_relaxation_result& r = x.result;
  CHECK(r.fixed_points > 0);
  std::size_t caps = 0;
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    if(L.patches[p].kind != Layout::CAP) continue;
    ++caps;
    CHECK(after.grids[p].points == before.grids[p].points);
    for(std::size_t a : L.patches[p].arcs) CHECK(after.arc_samples[a] == before.arc_samples[a]);
  }
  CHECK(caps == 1);
  CHECK(borders_are_arc_samples(L, after));
  // Nodes kept: every node's position is unchanged, the rest may move.
  PI::Grid_relaxation_options o;
  o.move_nodes = false;
  PI::Patch_grids pinned = before;
  PI::relax_surface_grids(L, pinned, o);
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    CHECK(pinned.arc_samples[a].front() == before.arc_samples[a].front());
    CHECK(pinned.arc_samples[a].back() == before.arc_samples[a].back());
  }
  CHECK(borders_are_arc_samples(L, pinned));
  // No sweep: nothing changes.
  PI::Patch_grids same = before;
  const auto none = PI::relax_surface_grids(L, same, PI::Grid_relaxation_options::none());
  CHECK(none.sweeps == 0);
  for(std::size_t p = 0; p < L.patches.size(); ++p) CHECK(same.grids[p].points == before.grids[p].points);
}

TEST_CASE("build relaxes the grids of an invalid volume and keeps them only when fewer patches fail", "[grid_relaxation][build]")
{
  const Mesh m = load(data("eight.off"));
  const auto plain = PI::build_trivariate_model(
    m, PI::parameters::maximum_grid_resolution(16).minimum_grid_resolution(16).minimum_spline_degree(3).grid_relaxation_sweeps(0));
  REQUIRE_FALSE(plain.is_valid());
  CHECK(plain.grid_attempts == std::vector<int>{16}); // no other grid, no lower degree
  CHECK_FALSE(plain.relaxation_attempted);
  CHECK(plain.volume.relaxation.sweeps == 0);
  const auto relaxed = PI::build_trivariate_model(m, PI::parameters::maximum_grid_resolution(16));
  CHECK(relaxed.relaxation_attempted);
  REQUIRE(relaxed.volume.relaxation.sweeps > 0);
  auto uncertified = [](const auto& model) {
    return std::count_if(model.volume.quality.certified.begin(), model.volume.quality.certified.end(),
                         [](const auto& b) { return !b.certified_positive; });
  };
  INFO("uncertified patches " << uncertified(plain) << " -> " << uncertified(relaxed));
  CHECK(2 * uncertified(relaxed) < uncertified(plain));
  CHECK(relaxed.volume.distance.folded_sides.empty());
  CHECK(relaxed.volume.distance.relative < 0.02);
  CHECK(relaxed.volume.quality.interfaces.max_gap < 1e-9);
  // A valid first volume is never relaxed (the torus).
  const auto torus = PI::build_trivariate_model(load(data("torus.obj")));
  REQUIRE(torus.is_valid());
  CHECK_FALSE(torus.relaxation_attempted);
}

TEST_CASE("a triangle's closest point and the feature holding it agree with a dense search", "[grid_relaxation][probe]")
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1., 1.);
  auto random_point = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for(int k = 0; k < 300; ++k) {
    std::array<Eigen::Vector3d, 3> t{random_point(), random_point(), random_point()};
    if(k % 10 == 0) t[2] = t[0] + 0.3 * (t[1] - t[0]); // no area: a segment
    const Eigen::Vector3d p = 2. * random_point();
    const PI::internal::Triangle_projection q = PI::internal::project_on_triangle(p, t);
    // No point of a fine barycentric grid is closer.
    double dense = std::numeric_limits<double>::infinity();
    const int n = 200;
    for(int i = 0; i <= n; ++i)
      for(int j = 0; i + j <= n; ++j) {
        const Eigen::Vector3d x = t[0] + (double(i) / n) * (t[1] - t[0]) + (double(j) / n) * (t[2] - t[0]);
        dense = std::min(dense, (x - p).norm());
      }
    const double d = (q.point - p).norm();
    INFO("triangle " << k);
    CHECK(d <= dense + 1e-12);
    CHECK(d >= dense - 0.02); // the grid's spacing
    // The feature named holds the point.
    if(q.vertex >= 0) {
      CHECK(q.edge == -1);
      CHECK(q.point == t[std::size_t(q.vertex)]);
    } else if(q.edge >= 0) {
      const Eigen::Vector3d a = t[std::size_t(q.edge)], b = t[std::size_t((q.edge + 1) % 3)];
      CHECK((q.point - a).cross(b - a).norm() <= 1e-12 * (1. + (b - a).squaredNorm()));
      CHECK((p - q.point).dot(b - a) == Approx(0.).margin(1e-12));
    } else {
      // Inside: p projects along the triangle's normal.
      const Eigen::Vector3d normal = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
      CHECK((p - q.point).cross(normal).norm() == Approx(0.).margin(1e-9));
    }
  }
}

TEST_CASE("a walk to the closest point on sphere.off finds the point the whole tree finds", "[grid_relaxation][probe]")
{
  const Mesh mesh = load(data("sphere.off"));
  const PI::internal::Mesh_probe<Mesh> probe(mesh);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1., 1.);
  // From a point of the mesh, targets outside the convex mesh, up to a tenth of the radius
  // away: there the closest point is the only local minimum near the start, which the walk
  // must reach. (From inside, a convex mesh has one local minimum per face near the point.)
  int walked = 0;
  for(auto v : vertices(mesh)) {
    const Point& c = mesh.point(v);
    const Eigen::Vector3d x(c.x(), c.y(), c.z());
    const auto from = probe.closest_point(x + 0.01 * Eigen::Vector3d(u(rng), u(rng), u(rng)));
    Eigen::Vector3d sideways(u(rng), u(rng), u(rng));
    sideways -= sideways.dot(x) / x.squaredNorm() * x;
    const Eigen::Vector3d target = x * (1. + 0.05 * (u(rng) + 1.2)) + 0.1 * x.norm() * sideways;
    const auto walk = probe.closest_point(target, from);
    const auto tree = probe.closest_point(target);
    CHECK((walk.point - target).norm() == Approx((tree.point - target).norm()).epsilon(1e-12));
    CHECK((walk.point - tree.point).norm() < 1e-9);
    CHECK(walk.normal.dot(tree.normal) > 0.);
    walked += walk.hint.second != from.hint.second;
  }
  CHECK(walked > int(num_vertices(mesh)) / 2); // most walks left their first face
}

TEST_CASE("a walk to the closest point stays on its side of a thin wall", "[grid_relaxation][probe]")
{
  // A plate 0.02 thick: a target just below its middle plane is closest to the bottom face,
  // but a point moving there from the top face must stay on the top.
  using P = Point;
  Mesh plate;
  CGAL::make_hexahedron(P(0, 0, 0), P(1, 0, 0), P(1, 1, 0), P(0, 1, 0), P(0, 1, 0.02), P(0, 0, 0.02), P(1, 0, 0.02),
                        P(1, 1, 0.02), plate);
  CGAL::Polygon_mesh_processing::triangulate_faces(plate);
  const PI::internal::Mesh_probe<Mesh> probe(plate);
  const auto top = probe.closest_point(Eigen::Vector3d(0.4, 0.4, 0.05));
  REQUIRE(top.normal.z() > 0.99);
  const Eigen::Vector3d target(0.6, 0.5, 0.008);
  const auto walk = probe.closest_point(target, top);
  CHECK(walk.normal.z() > 0.99);
  CHECK(walk.point.z() == Approx(0.02));
  CHECK(walk.point.x() == Approx(0.6));
  CHECK(walk.point.y() == Approx(0.5));
  CHECK(probe.closest_point(target).normal.z() < -0.99); // the whole tree's answer: the bottom
}

TEST_CASE("grid relaxation keeps a CAD block's arcs inside the solid straight between their moved nodes", "[grid_relaxation][blocks]")
{
  // A 4 by 4 plate without two opposite corner cells: two box edges run through it from its
  // bottom to its top (Polycube_layout::Arc::inside). The relaxation may move their nodes
  // within the flat faces; the segments must follow, or the interfaces along them would not
  // meet the surface patches' corners.
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(write_text("notched.off", voxel_plate_off(4, 4, {{0, 0}, {3, 3}}, {}))));
  REQUIRE(L.layout_class == PI::Layout_class::blocks);
  const int N = 8;
  const PI::Patch_grids before = PI::sample_layout_patches(L, PI::parameters::grid_resolution(N));
  PI::Patch_grids after = before;
  PI::relax_surface_grids(L, after, PI::Grid_relaxation_options());
  CHECK(borders_are_arc_samples(L, after));
  int inside = 0;
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    if(!L.arcs[a].inside) continue;
    ++inside;
    const auto& s = after.arc_samples[a];
    // Its ends where every other arc at its nodes now starts or ends.
    for(std::size_t b = 0; b < L.arcs.size(); ++b)
      for(int e = 0; e < 2; ++e)
        for(int f = 0; f < 2; ++f)
          if(b != a && L.arcs[b].nodes[std::size_t(e)] == L.arcs[a].nodes[std::size_t(f)])
            CHECK((f == 0 ? s.front() : s.back()) == (e == 0 ? after.arc_samples[b].front() : after.arc_samples[b].back()));
    // Straight, evenly sampled.
    for(int k = 0; k <= N; ++k)
      CHECK((s[std::size_t(k)] - (s.front() + (double(k) / N) * (s.back() - s.front()))).norm() < 1e-12);
  }
  CHECK(inside == 2);
}

TEST_CASE("a crease network locates points on sharp edges and slides them along, stopping at corners", "[grid_relaxation][creases]")
{
  // A unit cube of two triangles per face: every crease is one mesh edge between two
  // corners (three sharp edges each), a crease all the same although so short.
  const Mesh m = load(write_text("unit_cube.off", voxel_plate_off(1, 1, {}, {})));
  const PI::internal::Crease_network<Mesh> creases(m, 45.);
  const PI::internal::Mesh_probe<Mesh> probe(m);
  auto at = [&](const Eigen::Vector3d& p) {
    const auto s = probe.closest_point(p);
    return creases.locate(s.point, std::size_t(s.hint.second), 1e-9);
  };
  const PI::internal::Crease_position mid = at(Eigen::Vector3d(0.5, 0., 0.));
  REQUIRE(mid.kind == PI::internal::Crease_position::on_edge);
  CHECK(at(Eigen::Vector3d(0., 0., 0.)).kind == PI::internal::Crease_position::at_corner);
  CHECK(at(Eigen::Vector3d(1., 1., 1.)).kind == PI::internal::Crease_position::at_corner);
  CHECK(at(Eigen::Vector3d(0.5, 0.5, 0.)).kind == PI::internal::Crease_position::off); // a face's middle
  CHECK(at(Eigen::Vector3d(0.3, 0.3, 0.)).kind == PI::internal::Crease_position::off); // on a face's diagonal
  // Along the edge, its nearest point; beyond the corner, the corner: paths end there.
  std::size_t e = mid.edge;
  CHECK((creases.slide(Eigen::Vector3d(0.25, 0.1, -0.2), &e) - Eigen::Vector3d(0.25, 0., 0.)).norm() < 1e-15);
  CHECK(e == mid.edge);
  CHECK((creases.slide(Eigen::Vector3d(3., 0.2, 0.5), &e) - Eigen::Vector3d(1., 0., 0.)).norm() < 1e-15);

  // Creases without corners (pipe.off's four run round its ring, 160 sharp edges, each vertex
  // on two) are closed paths: a point slides along them and stays on them.
  const Mesh c = load(data("pipe.off"));
  const PI::internal::Crease_network<Mesh> rims(c, 45.);
  const PI::internal::Mesh_probe<Mesh> cp(c);
  std::size_t found = 0;
  for(auto h : halfedges(c)) {
    const auto& a = c.point(source(h, c));
    const auto& b = c.point(target(h, c));
    const Eigen::Vector3d p(0.5 * (a.x() + b.x()), 0.5 * (a.y() + b.y()), 0.5 * (a.z() + b.z()));
    const auto s = cp.closest_point(p);
    const PI::internal::Crease_position q = rims.locate(s.point, std::size_t(s.hint.second), 1e-9);
    if(q.kind != PI::internal::Crease_position::on_edge) continue;
    ++found;
    // Slid towards a point off the mesh, it stays on sharp edges: sliding again stays put.
    std::size_t f = q.edge;
    const Eigen::Vector3d y = rims.slide(p + Eigen::Vector3d(0.3, -0.2, 0.1), &f);
    std::size_t g = f;
    CHECK((rims.slide(y, &g) - y).norm() < 1e-12);
    // A rim is a regular 40-gon round the y axis: the point across it is half the rim away,
    // 20 edges either way, where the two walks from the edge meet. Within reach it is found;
    // 10 edges either way stop short of it.
    const Eigen::Vector3d across(-p.x(), p.y(), -p.z());
    std::size_t far = q.edge, near = q.edge;
    CHECK((rims.slide(across, &far) - across).norm() < 1e-5); // the mesh is symmetric to 2e-6
    CHECK((rims.slide(across, &near, 10) - across).norm() > 0.1);
    if(found == 20) break;
  }
  CHECK(found == 20);
}

TEST_CASE("grid relaxation slides points on a crease along it and keeps the creases' corners", "[grid_relaxation][creases]")
{
  // The L block: its arcs along the box's sharp edges are sampled on them, its corner nodes
  // sit at the creases' corners. Relaxed, the corners stay and the samples stay on the
  // creases (moved freely, a node on a hole's rim went down the hole's wall).
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(write_text("l_block.off", voxel_l_off())));
  REQUIRE(L.layout_class == PI::Layout_class::blocks);
  const int N = 8;
  const PI::Patch_grids before = PI::sample_layout_patches(L, PI::parameters::grid_resolution(N));
  PI::Patch_grids after = before;
  const PI::Grid_relaxation_result r = PI::relax_surface_grids(L, after, PI::Grid_relaxation_options());
  REQUIRE(r.sweeps > 0);
  CHECK(borders_are_arc_samples(L, after));
  const PI::internal::Crease_network<Layout::Mesh> creases(L.mesh, 45.);
  const PI::internal::Mesh_probe<Layout::Mesh> probe(L.mesh);
  int corners = 0, on_creases = 0, slid = 0;
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    if(L.arcs[a].inside) continue;
    for(int k = 0; k <= N; ++k) {
      const Eigen::Vector3d &p = before.arc_samples[a][std::size_t(k)], &q = after.arc_samples[a][std::size_t(k)];
      const auto s = probe.closest_point(p);
      const PI::internal::Crease_position c = creases.locate(s.point, std::size_t(s.hint.second), 1e-9);
      if(c.kind == PI::internal::Crease_position::at_corner) {
        ++corners;
        CHECK(q == p);
      } else if(c.kind == PI::internal::Crease_position::on_edge) {
        ++on_creases;
        std::size_t e = c.edge;
        CHECK((creases.slide(q, &e) - q).norm() < 1e-12);
        slid += int((q - p).norm() > 1e-6);
      }
    }
  }
  CHECK(corners > 0);
  CHECK(on_creases > 0);
  INFO("slid " << slid);
  CHECK(slid > 0);
}
