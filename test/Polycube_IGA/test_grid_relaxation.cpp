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
#include <CGAL/polycube_iga.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

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
  const auto plain = PI::build_trivariate_model(m, PI::parameters::maximum_grid_resolution(16).grid_relaxation_sweeps(0));
  REQUIRE_FALSE(plain.is_valid());
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
