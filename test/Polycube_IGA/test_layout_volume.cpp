// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Patch_sampling.h and Layout_volume.h on box chains whose answer is known by construction:
// arc-compatible grids, the box planes reproduced, valid conforming multipatch volumes close
// to the mesh, any cuboid frame (rotated or left-handed), G+Smo round trip, determinism.

#include "layout_fixtures.h"

#include <CGAL/Polycube_IGA/Cuboid_decomposition.h>
#include <CGAL/Polycube_IGA/IO/gismo_xml.h>
#include <CGAL/Polycube_IGA/Layout_node_relocation.h>
#include <CGAL/Polycube_IGA/Layout_volume.h>
#include <CGAL/Polycube_IGA/Patch_sampling.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

using namespace test_support;
namespace PI = CGAL::Polycube_IGA;

namespace {

const double pi = 3.14159265358979323846;

/// Bent along a quarter circle of radius 3 (about the axis x = 0, y = 3) over the chain's
/// length and twisted by 45 degrees about its axis: orientation-preserving.
std::function<Point(double, double, double)> bend_and_twist(int k)
{
  return [k](double x, double y, double z) {
    const double phi = 0.25 * pi * x / k; // twist about (y, z) = (0.5, 0.5)
    const double yy = 0.5 + std::cos(phi) * (y - 0.5) - std::sin(phi) * (z - 0.5);
    const double zz = 0.5 + std::sin(phi) * (y - 0.5) + std::cos(phi) * (z - 0.5);
    const double R = 3., theta = 0.5 * pi * x / k;
    return Point((R - yy) * std::sin(theta), R - (R - yy) * std::cos(theta), zz);
  };
}

PI::Layout_volume_options small_options(int N)
{
  PI::Layout_volume_options o;
  o.sampling.grid_segments = N;
  o.distance_samples_per_direction = 16;
  return o;
}

/// The interface with first <= second (patch, side), its maps inverted if it had to swap.
PI::Patch_interface canonical(const PI::Patch_interface& f)
{
  if(!(f.second < f.first)) return f;
  PI::Patch_interface g;
  g.first = f.second;
  g.second = f.first;
  for(int i = 0; i < 3; ++i) {
    const int j = f.direction_map[std::size_t(i)];
    g.direction_map[std::size_t(j)] = i;
    g.direction_orientation[std::size_t(j)] = f.direction_orientation[std::size_t(i)];
  }
  return g;
}

auto interface_key(const PI::Patch_interface& f)
{
  return std::make_tuple(f.first.patch, f.first.side, f.second.patch, f.second.side, f.direction_map, f.direction_orientation);
}

/// Declared interfaces equal the geometric ones of compute_topology(), boundaries too.
void check_against_compute_topology(const PI::Multipatch_volume& mp)
{
  PI::Multipatch_volume geo = mp;
  geo.compute_topology();
  std::vector<decltype(interface_key(PI::Patch_interface()))> a, b;
  for(const auto& f : mp.interfaces()) a.push_back(interface_key(canonical(f)));
  for(const auto& f : geo.interfaces()) b.push_back(interface_key(canonical(f)));
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  CHECK(a == b);
  std::vector<PI::Patch_side> ba = mp.boundaries(), bb = geo.boundaries();
  std::sort(ba.begin(), ba.end());
  std::sort(bb.begin(), bb.end());
  CHECK(ba == bb);
}

/// The two sides of every interface have the same control points, bit for bit, under the
/// interface's direction map. Returns the number of control points compared.
std::size_t check_interface_nets_identical(const PI::Multipatch_volume& mp)
{
  std::size_t compared = 0, mismatches = 0;
  for(const auto& f : mp.interfaces()) {
    const auto& a = mp.patch(f.first.patch);
    const auto& b = mp.patch(f.second.patch);
    const auto na = a.control_net_size(), nb = b.control_net_size();
    const int da = PI::side_direction(f.first.side), db = PI::side_direction(f.second.side);
    std::array<int, 3> extent = na;
    extent[std::size_t(da)] = 1;
    PI::internal::for_each_multi_index<3>(extent, [&](const std::array<int, 3>& t) {
      std::array<int, 3> ia = t, ib{};
      ia[std::size_t(da)] = PI::side_parameter(f.first.side) ? na[std::size_t(da)] - 1 : 0;
      for(int d = 0; d < 3; ++d) {
        if(d == da) continue;
        const int e = f.direction_map[std::size_t(d)];
        ib[std::size_t(e)] = f.direction_orientation[std::size_t(d)] ? ia[std::size_t(d)] : nb[std::size_t(e)] - 1 - ia[std::size_t(d)];
      }
      ib[std::size_t(db)] = PI::side_parameter(f.second.side) ? nb[std::size_t(db)] - 1 : 0;
      if(a.control_point(ia) != b.control_point(ib)) ++mismatches;
      ++compared;
    });
  }
  CHECK(mismatches == 0);
  return compared;
}

/// Every arc's samples appear exactly (bit for bit) on the matching side of every patch using it.
void check_arc_compatibility(const Layout& L, const PI::Patch_grids& g)
{
  std::vector<int> uses(L.arcs.size(), 0);
  std::size_t mismatches = 0;
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    for(int i = 0; i < 4; ++i) {
      const std::size_t a = L.patches[p].arcs[std::size_t(i)];
      std::vector<Eigen::Vector3d> side = g.side(p, i);
      if(L.arcs[a].nodes[0] != L.patches[p].corners[std::size_t(i)]) std::reverse(side.begin(), side.end());
      if(side != g.arc_samples[a]) ++mismatches;
      ++uses[a];
    }
  CHECK(mismatches == 0);
  // Every arc borders at least two patches (surface, cap or interface): the test compared something.
  CHECK(*std::min_element(uses.begin(), uses.end()) >= 2);
}

void check_no_flips(const PI::Patch_grids& g)
{
  for(std::size_t p = 0; p < g.grids.size(); ++p) {
    INFO("patch " << p);
    CHECK(g.flipped_triangles[p] == 0);
    CHECK(g.unlocated_points[p] == 0);
  }
}

/// Relabels cuboid c's local frame: new coordinate d is old coordinate perm[d], reversed if flip[d].
void relabel(Layout& L, std::size_t c, const std::array<int, 3>& perm, const std::array<bool, 3>& flip)
{
  const Layout::Cuboid old = L.cuboids[c];
  Layout::Cuboid& cu = L.cuboids[c];
  for(int n = 0; n < 8; ++n) {
    const int x[3] = {n & 1, (n >> 1) & 1, (n >> 2) & 1};
    int y[3];
    for(int d = 0; d < 3; ++d) y[perm[std::size_t(d)]] = flip[std::size_t(d)] ? 1 - x[d] : x[d];
    cu.nodes[std::size_t(n)] = old.nodes[std::size_t(y[0] + 2 * y[1] + 4 * y[2])];
  }
  for(int d = 0; d < 3; ++d)
    for(int at = 0; at < 2; ++at)
      cu.patches[std::size_t(2 * d + at)] = old.patches[std::size_t(2 * perm[std::size_t(d)] + (flip[std::size_t(d)] ? 1 - at : at))];
}

} // namespace

TEST_CASE("patch grids of shared arcs agree bit for bit and no uv triangle flips", "[layout_volume]")
{
  struct Case
  {
    int k;
    bool open, deformed;
  };
  for(const Case& c : {Case{1, false, false}, Case{3, false, false}, Case{2, true, false}, Case{2, true, true}, Case{3, false, true}}) {
    INFO("k " << c.k << " open " << c.open << " deformed " << c.deformed);
    const Layout L = box_chain_layout(c.k, 4, c.open, c.deformed ? bend_and_twist(c.k) : std::function<Point(double, double, double)>());
    REQUIRE(L.validate().is_valid());
    const PI::Patch_grids g = PI::sample_layout_patches(L, PI::parameters::grid_resolution(6));
    REQUIRE(g.segments == 6);
    REQUIRE(g.grids.size() == L.patches.size());
    for(const auto& grid : g.grids) CHECK((grid.size_u == 7 && grid.size_v == 7));
    check_arc_compatibility(L, g);
    check_no_flips(g);
    // Arc samples are equally spaced along the (straight, before deformation) arcs.
    if(!c.deformed)
      for(const auto& s : g.arc_samples)
        for(std::size_t i = 1; i < s.size(); ++i)
          CHECK(std::abs((s[i] - s[i - 1]).norm() - 1. / 6.) < 1e-12);
  }
}

TEST_CASE("an inner edge joining two vertices of one side is split so no triangle maps flat", "[layout_volume]")
{
  // A square patch whose border vertex b has one triangle, (c0, b, c1): the inner edge c0 c1
  // joins two vertices of side 0, and that triangle would map onto the side, flat.
  PI::internal::Surface_patch_map M;
  const std::vector<Eigen::Vector3d> x{{0., 0., 0.}, {0.5, -0.3, 0.}, {1., 0., 0.}, {1., 1., 0.}, {0., 1., 0.}, {0.5, 0.5, 0.1}};
  const std::vector<Eigen::Vector2d> uv{{0., 0.}, {0.5, 0.}, {1., 0.}, {1., 1.}, {0., 1.}, {0., 0.}};
  std::vector<bool> fixed{true, true, true, true, true, false};
  for(std::size_t v = 0; v < x.size(); ++v) {
    M.vertex.push_back(v);
    M.position.push_back(x[v]);
    M.uv.push_back(uv[v]);
  }
  M.triangles = {{{0, 1, 2}}, {{0, 2, 5}}, {{2, 3, 5}}, {{3, 4, 5}}, {{4, 0, 5}}};
  auto area = [&] {
    double a = 0.;
    for(const auto& t : M.triangles)
      a += 0.5 * (M.position[std::size_t(t[1])] - M.position[std::size_t(t[0])]).cross(M.position[std::size_t(t[2])] - M.position[std::size_t(t[0])]).norm();
    return a;
  };
  const double before = area();
  PI::internal::split_side_chords(M, fixed);
  REQUIRE(M.position.size() == 7);
  CHECK(M.triangles.size() == 7);
  CHECK(fixed.size() == 7);
  CHECK_FALSE(fixed[6]);
  CHECK((M.position[6] - Eigen::Vector3d(0.5, 0., 0.)).norm() == 0.);
  CHECK(std::abs(area() - before) < 1e-14);
  // Every triangle now has a free vertex or corners on two sides; every edge is used once
  // per orientation inside and once on the border.
  std::map<std::pair<int, int>, int> directed;
  for(const auto& t : M.triangles) {
    CHECK(std::count_if(t.begin(), t.end(), [&](int v) { return !fixed[std::size_t(v)]; }) >= 1);
    for(int c = 0; c < 3; ++c) ++directed[{t[std::size_t(c)], t[std::size_t((c + 1) % 3)]}];
  }
  for(const auto& e : directed) CHECK(e.second == 1);
  CHECK(directed.count({0, 2}) + directed.count({2, 0}) == 0);
}

TEST_CASE("no uv triangle maps flat or flips on a femur whose corner fans hold single triangles", "[layout_volume]")
{
  // Before inner edges joining two vertices of one side were split, three of its six
  // patches had such a triangle (as had every femur of the population).
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(data("femur_S001.ply")));
  REQUIRE(L.validate().is_valid());
  const PI::Patch_grids g = PI::sample_layout_patches(L, PI::parameters::grid_resolution(16));
  check_no_flips(g);
  check_arc_compatibility(L, g);
}

/// Largest turn (degrees) between consecutive segments of a polyline.
double sharpest_turn(const std::vector<Eigen::Vector3d>& s)
{
  double worst = 0.;
  for(std::size_t i = 1; i + 1 < s.size(); ++i) {
    const Eigen::Vector3d a = s[i] - s[i - 1], b = s[i + 1] - s[i];
    worst = std::max(worst, std::atan2(a.cross(b).norm(), a.dot(b)) * 180. / CGAL_PI);
  }
  return worst;
}

TEST_CASE("a sharp turn inside a boundary arc is rounded within its two edges", "[layout_volume]")
{
  // A V: two edges of length 1 meeting at a right angle, sampled at 16 segments. Its ends
  // are not rounded, so the curve runs along three quarters of each edge.
  const std::vector<Eigen::Vector3d> v{{-1., 0., 0.}, {0., 0., 0.}, {0., 1., 0.}};
  const std::vector<double> cum = PI::internal::cumulative_lengths(v);
  const std::vector<Eigen::Vector3d> plain = PI::internal::sample_polyline(v, cum, 16);
  std::vector<Eigen::Vector3d> r = plain;
  PI::internal::round_sharp_turns(v, cum, 60., r);
  CHECK(sharpest_turn(plain) == Approx(90.));
  CHECK(sharpest_turn(r) < 30.);
  int moved = 0;
  for(std::size_t i = 0; i < r.size(); ++i) {
    const double t = cum.back() * double(i) / 16.;
    if(std::abs(t - 1.) >= 0.75) {
      CHECK(r[i] == plain[i]); // outside the window: untouched, ends included
      continue;
    }
    ++moved;
    // On the quadratic Bezier (-3/4,0) (0,0) (0,3/4): x = -3/4 (1-u)^2, y = 3/4 u^2, inside
    // the corner's triangle and less than half an edge from the polyline's sample.
    CHECK(std::abs(std::sqrt(-r[i].x() / 0.75) + std::sqrt(r[i].y() / 0.75) - 1.) < 1e-12);
    CHECK(r[i].x() <= 0.);
    CHECK(r[i].y() >= 0.);
    CHECK((r[i] - plain[i]).norm() < 0.5);
  }
  CHECK(moved == 11);
  // A turn below the threshold is kept.
  std::vector<Eigen::Vector3d> kept = plain;
  PI::internal::round_sharp_turns(v, cum, 100., kept);
  CHECK(kept == plain);
  // Two sharp vertices one edge apart (a Z) share that edge half and half: every sample
  // moves at most once, and the turns are gone on both.
  const std::vector<Eigen::Vector3d> z{{-1., 0., 0.}, {0., 0., 0.}, {0., 1., 0.}, {1., 1., 0.}};
  const std::vector<double> cz = PI::internal::cumulative_lengths(z);
  std::vector<Eigen::Vector3d> rz = PI::internal::sample_polyline(z, cz, 24);
  PI::internal::round_sharp_turns(z, cz, 60., rz);
  CHECK(sharpest_turn(rz) < 30.);
  CHECK(rz[12] == Eigen::Vector3d(0., 0.5, 0.)); // the shared edge's midpoint stays
  for(std::size_t i = 1; i < rz.size(); ++i) CHECK(rz[i].x() + rz[i].y() > rz[i - 1].x() + rz[i - 1].y()); // no backtracking
}

TEST_CASE("the eye holes' tips are rounded in head.off's arc samples and nowhere else", "[layout_volume]")
{
  // Each eye loop has 10 vertices and turns by about 105 degrees at its two tips, inside
  // its arcs: a reflex crease in the middle of the face of the slab under the surface.
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(data("head.off")));
  REQUIRE(L.validate().is_valid());
  const PI::Patch_grids g = PI::sample_layout_patches(L, PI::parameters::grid_resolution(16));
  const PI::Patch_grids plain = PI::sample_layout_patches(L, PI::parameters::grid_resolution(16).sharp_boundary_turn(0.));
  int rounded = 0, border_arcs = 0;
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    std::vector<Eigen::Vector3d> pts;
    for(auto v : L.arcs[a].vertices) pts.push_back(PI::internal::to_eigen_point(L.mesh.point(v)));
    const bool border = PI::internal::on_mesh_border(L.mesh, L.arcs[a].vertices);
    border_arcs += border;
    if(g.arc_samples[a] == plain.arc_samples[a]) continue;
    ++rounded;
    INFO("arc " << a);
    CHECK(border);
    CHECK(g.arc_samples[a].front() == plain.arc_samples[a].front());
    CHECK(g.arc_samples[a].back() == plain.arc_samples[a].back());
    CHECK(sharpest_turn(pts) > 100.);
    CHECK(sharpest_turn(g.arc_samples[a]) < 60.);
  }
  CHECK(border_arcs == 12); // the neck and the two eyes, 4 arcs each
  CHECK(rounded >= 2);
  check_arc_compatibility(L, g);
  check_no_flips(g);
  CHECK_THROWS_AS(PI::sample_layout_patches(L, PI::parameters::sharp_boundary_turn(-1.)), PI::Invalid_input_error);
}

TEST_CASE("patch grids of an undeformed box lie on the box planes", "[layout_volume]")
{
  for(bool open : {false, true})
    for(bool smooth : {true, false}) {
      INFO("open " << open << " smooth " << smooth);
      const Layout L = box_chain_layout(3, 3, open);
      const PI::Patch_grids g =
        PI::sample_layout_patches(L, PI::parameters::grid_resolution(5).smooth_interior_patches(smooth));
      double worst = 0., outside = 0.;
      for(std::size_t p = 0; p < L.patches.size(); ++p) {
        // The coordinate all four corners share is the patch's plane.
        std::array<Eigen::Vector3d, 4> c;
        for(int i = 0; i < 4; ++i) c[std::size_t(i)] = PI::internal::to_eigen_point(L.mesh.point(L.nodes[L.patches[p].corners[std::size_t(i)]]));
        int d = -1;
        for(int e = 0; e < 3; ++e)
          if(c[0][e] == c[1][e] && c[0][e] == c[2][e] && c[0][e] == c[3][e]) d = e;
        REQUIRE(d >= 0);
        Eigen::Vector3d lo = c[0], hi = c[0];
        for(const auto& x : c) {
          lo = lo.cwiseMin(x);
          hi = hi.cwiseMax(x);
        }
        for(const auto& x : g.grids[p].points) {
          worst = std::max(worst, std::abs(x[d] - c[0][d]));
          outside = std::max(outside, ((lo - x).cwiseMax(x - hi)).maxCoeff());
        }
      }
      CHECK(worst < 1e-12);
      CHECK(outside < 1e-12);
    }
}

TEST_CASE("stretch reduction keeps the patch maps one-to-one and evens out the grid cells of a face mask", "[layout_volume][stretch]")
{
  // maxFace.obj: a face mask (a disk). Its nose lies in one patch, whose mean-value map
  // shrinks it: few grid cells cover it and they are large on the surface.
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(data("maxFace.obj")));
  auto worst_cell_ratio = [&](const PI::Patch_grids& g) {
    // Per surface patch, its largest grid cell (area on the surface) over its mean cell.
    double worst = 0.;
    const int N = g.segments;
    for(std::size_t p = 0; p < L.patches.size(); ++p) {
      if(L.patches[p].kind != Layout::SURFACE) continue;
      double largest = 0., sum = 0.;
      for(int j = 0; j < N; ++j)
        for(int i = 0; i < N; ++i) {
          const PI::Point_grid& x = g.grids[p];
          const double a = 0.5 * ((x(i + 1, j) - x(i, j)).cross(x(i, j + 1) - x(i, j)).norm() +
                                  (x(i + 1, j) - x(i + 1, j + 1)).cross(x(i, j + 1) - x(i + 1, j + 1)).norm());
          largest = std::max(largest, a);
          sum += a;
        }
      worst = std::max(worst, largest / (sum / double(N * N)));
    }
    return worst;
  };
  const PI::Patch_grids plain = PI::sample_layout_patches(L, PI::parameters::grid_resolution(16));
  const PI::Patch_grids stretched = PI::sample_layout_patches(L, PI::parameters::grid_resolution(16).stretch_rounds(3));
  // Positive weights: no triangle of a map turns over that did not before.
  for(std::size_t p = 0; p < L.patches.size(); ++p) CHECK(stretched.flipped_triangles[p] <= plain.flipped_triangles[p]);
  for(int u : stretched.unlocated_points) CHECK(u == 0);
  // Shared arcs are sampled as before, bit for bit; only the patches' insides move.
  CHECK(stretched.arc_samples == plain.arc_samples);
  check_arc_compatibility(L, stretched);
  const double before = worst_cell_ratio(plain), after = worst_cell_ratio(stretched);
  INFO("largest cell over mean cell, worst patch: " << before << " -> " << after);
  CHECK(after < 0.5 * before);
  CHECK_THROWS_AS(PI::sample_layout_patches(L, PI::parameters::stretch_rounds(-1)), PI::Invalid_input_error);
}

TEST_CASE("interior patch grids of a flat square are the same with and without harmonic smoothing", "[layout_volume]")
{
  // On a flat square with uniform border samples the Coons grid is bilinear, hence discrete harmonic.
  const Layout L = box_chain_layout(2, 2, true);
  const PI::Patch_grids a = PI::sample_layout_patches(L, PI::parameters::grid_resolution(6).smooth_interior_patches(true));
  const PI::Patch_grids b = PI::sample_layout_patches(L, PI::parameters::grid_resolution(6).smooth_interior_patches(false));
  double diff = 0.;
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    if(L.patches[p].kind == Layout::SURFACE) {
      CHECK(a.grids[p].points == b.grids[p].points);
      continue;
    }
    for(std::size_t i = 0; i < a.grids[p].points.size(); ++i) diff = std::max(diff, (a.grids[p].points[i] - b.grids[p].points[i]).norm());
  }
  CHECK(diff < 1e-13);
}

TEST_CASE("layout volume of undeformed box chains is valid and conforming and fits the box", "[layout_volume]")
{
  struct Case
  {
    int k;
    bool open;
  };
  for(const Case& c : {Case{1, false}, Case{3, false}, Case{2, true}}) {
    INFO("k " << c.k << " open " << c.open);
    const Layout L = box_chain_layout(c.k, 3, c.open);
    const PI::Layout_volume_result r = PI::layout_volume(L, small_options(8));
    const PI::Multipatch_volume& mp = r.volume;
    CHECK(r.degree == 3);
    CHECK(r.spans == 2);
    CHECK(mp.number_of_patches() == std::size_t(c.k));
    CHECK(mp.interfaces().size() == std::size_t(c.k - 1));
    CHECK(mp.boundaries().size() == std::size_t(6 * c.k - 2 * (c.k - 1)));
    check_against_compute_topology(mp);
    check_no_flips(r.samples);
    REQUIRE(r.quality_evaluated);
    CHECK(r.quality.interfaces.conforming);
    CHECK(r.quality.interfaces.max_gap < 1e-12);
    check_interface_nets_identical(mp);
    for(std::size_t p = 0; p < mp.number_of_patches(); ++p) {
      INFO("patch " << p);
      CHECK(!r.mirrored[p]);
      CHECK(r.enclosed_volume[p] == Approx(1.).epsilon(1e-12));
      CHECK(r.quality.certified[p].certified_positive);
      CHECK(r.quality.certified[p].lower_bound > 0.);
      CHECK(r.quality.sampled[p].min_scaled_jacobian > 0.);
    }
    // Caps span the boundary loops, the mesh has nothing there: only surface sides are measured.
    CHECK(r.distance.boundary_sides == std::size_t(4 * c.k + (c.open ? 0 : 2)));
    CHECK(r.distance.relative < 1e-3);
  }
}

TEST_CASE("a boundary layer tiles the chain with cores and one slab per surface patch", "[layout_volume][boundary_layer]")
{
  struct Case { int k; bool open; bool deformed; };
  for(const Case& c : {Case{1, false, false}, Case{3, false, false}, Case{2, true, false}, Case{3, false, true}}) {
    INFO("k " << c.k << " open " << c.open << " deformed " << c.deformed);
    const Layout L = box_chain_layout(c.k, 3, c.open, c.deformed ? bend_and_twist(c.k) : std::function<Point(double, double, double)>());
    PI::Layout_volume_options o = small_options(8);
    o.boundary_layer = 0.25;
    const PI::Layout_volume_result r = PI::layout_volume(L, o);
    const PI::Multipatch_volume& mp = r.volume;
    const std::size_t C = L.cuboids.size(), S = L.number_of_surface_patches();
    REQUIRE(mp.number_of_patches() == C + S);
    REQUIRE(r.core_of.size() == C + S);
    REQUIRE(r.slab_of.size() == C + S);
    std::vector<int> slabs(L.patches.size(), 0);
    for(std::size_t p = 0; p < C + S; ++p) {
      CHECK((r.core_of[p] >= 0) != (r.slab_of[p] >= 0));
      if(p < C) CHECK(r.core_of[p] == long(p));
      if(r.slab_of[p] >= 0) {
        CHECK(L.patches[std::size_t(r.slab_of[p])].kind == Layout::SURFACE);
        ++slabs[std::size_t(r.slab_of[p])];
      }
    }
    for(std::size_t p = 0; p < L.patches.size(); ++p) CHECK(slabs[p] == (L.patches[p].kind == Layout::SURFACE ? 1 : 0));
    // Interfaces: the layout's (between cores), core-slab, and slab-slab across every arc
    // with two surface patches beside it.
    std::vector<int> surface_sides(L.arcs.size(), 0);
    for(const auto& pa : L.patches)
      if(pa.kind == Layout::SURFACE)
        for(std::size_t a : pa.arcs) ++surface_sides[a];
    const std::size_t shared_arcs = std::size_t(std::count(surface_sides.begin(), surface_sides.end(), 2));
    CHECK(mp.interfaces().size() == L.interfaces().size() + S + shared_arcs);
    check_against_compute_topology(mp);
    REQUIRE(r.quality_evaluated);
    CHECK(r.quality.interfaces.conforming);
    check_interface_nets_identical(mp);
    // Cores and slabs tile the solid: their enclosed volumes add up to the chain's (exactly
    // for flat sides; bent grids are triangulated differently by the two cells of a face).
    const PI::Layout_volume_result plain = PI::layout_volume(L, small_options(8));
    double padded_total = 0., plain_total = 0.;
    for(double v : r.enclosed_volume) padded_total += std::abs(v);
    for(double v : plain.enclosed_volume) plain_total += std::abs(v);
    CHECK(padded_total == Approx(plain_total).epsilon(c.deformed ? 1e-3 : 1e-9));
    for(std::size_t p = 0; p < mp.number_of_patches(); ++p) {
      INFO("patch " << p << " lb " << r.quality.certified[p].lower_bound << " found " << r.quality.certified[p].smallest_value_found << " minSJ " << r.quality.sampled[p].min_scaled_jacobian);
      CHECK(r.quality.certified[p].certified_positive);
    }
    // The slabs' tops are the surface patches' own fits.
    CHECK(r.distance.relative == Approx(plain.distance.relative).epsilon(1e-3).margin(1e-9));
  }
}

TEST_CASE("the boundary layer's depth is capped by the solid's thickness under a node", "[layout_volume][boundary_layer]")
{
  // The unit cube: a corner's normal is the diagonal, whose ray leaves the cube through the
  // opposite corner at distance sqrt(3). A cap of 0.2 of that is 0.2 along every axis.
  const Layout L = box_chain_layout(1, 3);
  PI::Patch_sampling_options so;
  so.grid_segments = 6;
  const PI::Patch_grids g = PI::sample_layout_patches(L, so);
  const std::size_t nn = L.nodes.size(), na = L.arcs.size();
  for(const double fraction : {0.2, 0.}) {
    PI::Padding_options po;
    po.thickness = 0.45;
    po.maximum_thickness_fraction = fraction;
    const PI::Padded_layout<Point> P = PI::pad_layout(L, g, po);
    const double expected = fraction > 0. ? 0.2 : 0.45 / std::sqrt(3.); // per axis
    for(std::size_t n = 0; n < nn; ++n) {
      const auto& radial = P.samples.arc_samples[2 * na + n];
      const Eigen::Vector3d outer = radial.front(), inner = radial.back();
      INFO("fraction " << fraction << " node " << n);
      for(int i = 0; i < 3; ++i)
        CHECK(inner[i] == Approx(outer[i] < 0.5 ? expected : 1. - expected).margin(1e-9));
    }
  }
}

TEST_CASE("the boundary layer stays inside a thin blade", "[layout_volume][boundary_layer]")
{
  // blade.off is a few percent thick: a quarter of its arcs would push every inner node
  // through the opposite face (most of its nodes), building slabs outside the solid.
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(data("blade.off")));
  const PI::Patch_grids g = PI::sample_layout_patches(L, small_options(8).sampling);
  const std::size_t nn = L.nodes.size(), na = L.arcs.size();
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_face_graph_triangle_primitive<Mesh>>>;
  const Tree tree(faces(L.mesh).first, faces(L.mesh).second, L.mesh);
  // Inner nodes whose radial segment (from just below the surface) crosses the mesh.
  auto crossing = [&](const PI::Padded_layout<Point>& P) {
    std::size_t out = 0;
    for(std::size_t n = 0; n < nn; ++n) {
      const auto& radial = P.samples.arc_samples[2 * na + n];
      const Eigen::Vector3d a = radial.front() + 1e-6 * (radial.back() - radial.front()), b = radial.back();
      if(tree.do_intersect(Kernel::Segment_3(Point(a.x(), a.y(), a.z()), Point(b.x(), b.y(), b.z())))) ++out;
    }
    return out;
  };
  PI::Padding_options uncapped;
  uncapped.maximum_thickness_fraction = 0.;
  uncapped.maximum_depth_slope = 0.;
  uncapped.folded_corner_lift = 1.;
  CHECK(crossing(PI::pad_layout(L, g, uncapped)) > nn / 2);

  const PI::Padding_options po;
  const PI::Padded_layout<Point> P = PI::pad_layout(L, g, po);
  CHECK(crossing(P) == 0);
  std::vector<Eigen::Vector3d> outer(nn), normal(nn);
  std::vector<double> depth(nn);
  for(std::size_t n = 0; n < nn; ++n) {
    const auto& radial = P.samples.arc_samples[2 * na + n];
    outer[n] = radial.front();
    depth[n] = (radial.back() - radial.front()).norm();
    normal[n] = (radial.front() - radial.back()) / depth[n];
    CHECK(depth[n] > 0.);
  }
  const std::vector<double> t = PI::internal::inward_thickness(L.mesh, outer, normal);
  for(std::size_t n = 0; n < nn; ++n) CHECK(depth[n] <= po.maximum_thickness_fraction * t[n] * (1. + 1e-9));
  // A node whose ray leaves the solid without a hit (the far end's bottom corner: the step
  // cut the top away above it) keeps to the thickness at the nodes it shares an arc with;
  // it went 0.53 deep into the blade, 0.65 thick, and its core cuboid turned over there.
  std::size_t escaping = 0;
  for(std::size_t n = 0; n < nn; ++n) {
    if(t[n] < std::numeric_limits<double>::infinity()) continue;
    ++escaping;
    for(const auto& arc : L.arcs)
      for(std::size_t e = 0; e < 2; ++e)
        if(arc.nodes[e] == n) CHECK(depth[n] <= po.maximum_thickness_fraction * t[arc.nodes[1 - e]] * (1. + 1e-9));
  }
  CHECK(escaping > 0);
  // Along every arc the depth changes by at most 5% of the arc's length, but at a lifted
  // node (a ridge on purpose).
  auto lifted = [&](std::size_t n) { return std::find(P.lifted_nodes.begin(), P.lifted_nodes.end(), n) != P.lifted_nodes.end(); };
  for(std::size_t a = 0; a < na; ++a) {
    if(lifted(L.arcs[a].nodes[0]) || lifted(L.arcs[a].nodes[1])) continue;
    const double length = PI::internal::cumulative_lengths(g.arc_samples[a]).back();
    CHECK(std::abs(depth[L.arcs[a].nodes[0]] - depth[L.arcs[a].nodes[1]]) <= po.maximum_depth_slope * length * (1. + 1e-9));
  }
}

TEST_CASE("the boundary layer's inner nodes lie inside the solid, reflex corners and inward faces included", "[layout_volume][boundary_layer]")
{
  // joint.off sampled at 32 with its bent tubes split: at a chain node on its flat face
  // y = -0.5, two of the four patch corners are reflex and their grid normals point in, so
  // the four cancel; the node takes the normal of the mesh face it lies on instead.
  // head.off has its faces pointing into the solid; its layout is turned outwards
  // (Cuboid_decomposition), else every inner node would lie outside.
  for(const auto& [name, n] : {std::make_pair("joint.off", 32), std::make_pair("head.off", 16)}) {
    INFO(name);
    const Mesh m = load(data(name));
    const Layout L = PI::Cuboid_decomposition<Mesh>()(m);
    const PI::Patch_sampling_options so = small_options(n).sampling;
    const auto C = PI::split_long_cuboids(L, PI::sample_layout_patches(L, so), so);
    const PI::Padded_layout<Point> P = PI::pad_layout(C.layout, C.samples);
    Mesh closed = m; // the head's neck and eye holes filled, so that it bounds a solid
    std::vector<Mesh::Halfedge_index> borders;
    CGAL::Polygon_mesh_processing::extract_boundary_cycles(closed, std::back_inserter(borders));
    for(auto h : borders) CGAL::Polygon_mesh_processing::triangulate_hole(closed, h, CGAL::Emptyset_iterator());
    REQUIRE(CGAL::is_closed(closed));
    const CGAL::Side_of_triangle_mesh<Mesh, Kernel> inside(closed);
    const std::size_t nn = C.layout.nodes.size(), na = C.layout.arcs.size();
    int tested = 0;
    for(std::size_t k = 0; k < nn; ++k) {
      // A node on a boundary loop moves along the loop's surface, which may flare past the
      // flat triangulation filling the hole: it has no solid to stay in beyond the hole.
      if(CGAL::is_border(C.layout.nodes[k], C.layout.mesh)) continue;
      ++tested;
      const Eigen::Vector3d q = P.samples.arc_samples[2 * na + k].back();
      INFO("node " << k);
      CHECK(inside(Point(q.x(), q.y(), q.z())) == CGAL::ON_BOUNDED_SIDE);
    }
    CHECK(tested >= int(nn) - 12); // the head's three holes carry 12 nodes
  }
}

TEST_CASE("the boundary layer turns inner arc ends to open flat corners of cores and slabs", "[layout_volume][boundary_layer]")
{
  // eight.off (genus 2): nodes on the smooth middle of interface cycles give cores whose
  // corners at the inner node have their three edge tangents nearly coplanar. (On the
  // relaxed grids of build_trivariate_model()'s second attempt, all of them end above 0.05.)
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(data("eight.off")));
  const PI::Patch_sampling_options so = small_options(16).sampling;
  const auto C = PI::split_long_cuboids(L, PI::sample_layout_patches(L, so), so);
  const std::size_t nn = C.layout.nodes.size(), na = C.layout.arcs.size();
  // The opening alone: a node still folded after it would be lifted (tested below).
  PI::Padding_options on;
  on.folded_corner_lift = 1.;
  PI::Padding_options off = on;
  off.corner_threshold = 0.;
  const PI::Padded_layout<Point> before = PI::pad_layout(C.layout, C.samples, off);
  const PI::Padded_layout<Point> after = PI::pad_layout(C.layout, C.samples, on);
  PI::internal::Corner_tangents<Layout> T0(before.layout, before.samples.arc_samples, nn),
    T1(after.layout, after.samples.arc_samples, nn);
  int flat_before = 0, flat_after = 0, raised = 0;
  double worst_before = 1., worst_after = 1.;
  for(std::size_t n = nn; n < 2 * nn; ++n) {
    REQUIRE(T0.has_corners(n));
    const double w0 = T0.worst(n), w1 = T1.worst(n);
    INFO("inner node " << n << ": " << w0 << " -> " << w1);
    CHECK(w1 >= w0 - 1e-12); // a node's corners only improve
    flat_before += int(w0 < 0.05);
    flat_after += int(w1 < 0.05);
    raised += int(w1 > w0 + 1e-9);
    worst_before = std::min(worst_before, w0);
    worst_after = std::min(worst_after, w1);
    if(!(w0 < PI::Padding_options().corner_threshold)) CHECK(w1 == w0); // sound nodes untouched
  }
  // On these unrelaxed grids 11 of the 48 inner nodes have a corner below 0.05 and 5 keep
  // one (their surface corners are folded; a turn of 30 degrees does not undo that).
  CHECK(flat_before >= 8);
  CHECK(2 * flat_after <= flat_before);
  CHECK(worst_after > worst_before + 0.2);
  CHECK(raised >= flat_before);
  // Only inner arcs change, and each only on the half next to a turned end, by a turn of at
  // most maximum_corner_turn degrees; the outer arcs, the radial ones and the nodes stay.
  const int N = before.samples.segments;
  REQUIRE(after.samples.arc_samples.size() == before.samples.arc_samples.size());
  const double max_turn = PI::Padding_options().maximum_corner_turn * 3.14159265358979323846 / 180.;
  for(std::size_t a = 0; a < after.samples.arc_samples.size(); ++a) {
    const auto &s0 = before.samples.arc_samples[a], &s1 = after.samples.arc_samples[a];
    INFO("arc " << a);
    CHECK(s1.front() == s0.front());
    CHECK(s1.back() == s0.back());
    CHECK(s1[std::size_t(N / 2)] == s0[std::size_t(N / 2)]);
    if(a < na || a >= 2 * na) CHECK(s1 == s0);
    for(bool start : {true, false}) {
      const Eigen::Vector3d t0 = PI::internal::end_tangent(s0, start), t1 = PI::internal::end_tangent(s1, start);
      CHECK(std::acos(std::min(1., t0.dot(t1))) <= max_turn + 1e-9);
    }
  }
  // The inner patches are built from the final arcs: every border sample is an arc sample.
  for(std::size_t p = 0; p < after.layout.patches.size(); ++p) {
    const auto& pa = after.layout.patches[p];
    const PI::Point_grid& g = after.samples.grids[p];
    const auto& arc0 = after.samples.arc_samples[pa.arcs[0]];
    const bool forward = after.layout.arcs[pa.arcs[0]].nodes[0] == pa.corners[0];
    for(int i = 0; i <= N; ++i) CHECK(g(i, 0) == arc0[std::size_t(forward ? i : N - i)]);
  }
  // Options out of range are named, not used.
  for(int k = 0; k < 5; ++k) {
    PI::Padding_options bad;
    if(k == 0) bad.inner_relief = std::numeric_limits<double>::quiet_NaN();
    if(k == 1) bad.maximum_corner_turn = 120.;
    if(k == 2) bad.corner_threshold = -1.;
    if(k == 3) bad.folded_corner_lift = 0.;
    if(k == 4) bad.folded_corner_lift = 1.5;
    CHECK_THROWS_AS(PI::pad_layout(C.layout, C.samples, bad), PI::Invalid_input_error);
  }
  // Deterministic.
  const PI::Padded_layout<Point> again = PI::pad_layout(C.layout, C.samples, on);
  CHECK(again.samples.arc_samples == after.samples.arc_samples);
  for(std::size_t p = 0; p < again.samples.grids.size(); ++p) CHECK(again.samples.grids[p].points == after.samples.grids[p].points);
}

TEST_CASE("the boundary layer lifts an inner node whose corner stays folded", "[layout_volume][boundary_layer]")
{
  // mech-holes-shark.off after node relocation, at 20 samples: node 14 sits on the rim of
  // a hole in a flat face, flush with its cap, and the core's corner under it stays folded
  // after the opening; the whole build is valid only with it lifted (--relocate-nodes 2
  // --grid 20).
  const Mesh m = load(data("mech-holes-shark.off"));
  Layout L = PI::Cuboid_decomposition<Mesh>()(m);
  PI::relocate_layout_nodes(L, 2);
  const PI::Patch_sampling_options so = small_options(20).sampling;
  const auto C = PI::split_long_cuboids(L, PI::sample_layout_patches(L, so), so);
  const std::size_t nn = C.layout.nodes.size(), na = C.layout.arcs.size();
  PI::Padding_options unlifted;
  unlifted.folded_corner_lift = 1.;
  const PI::Padded_layout<Point> P0 = PI::pad_layout(C.layout, C.samples, unlifted);
  const PI::Padded_layout<Point> P = PI::pad_layout(C.layout, C.samples);
  CHECK(P0.lifted_nodes.empty());
  REQUIRE(!P.lifted_nodes.empty());
  PI::internal::Corner_tangents<Layout> T0(P0.layout, P0.samples.arc_samples, nn), T(P.layout, P.samples.arc_samples, nn);
  // The radial arc of node n runs from it to its inner node.
  auto depth = [&](const PI::Padded_layout<Point>& X, std::size_t n) {
    const auto& s = X.samples.arc_samples[2 * na + n];
    return (s.back() - s.front()).norm();
  };
  bool rim_node_lifted = false;
  for(std::size_t n = 0; n < nn; ++n) {
    const bool lifted = std::find(P.lifted_nodes.begin(), P.lifted_nodes.end(), n) != P.lifted_nodes.end();
    INFO("node " << n << ": worst corner " << T0.worst(nn + n) << " -> " << T.worst(nn + n) << ", depth " << depth(P0, n) << " -> "
                 << depth(P, n));
    if(lifted) {
      CHECK(T0.worst(nn + n) < 0.);                 // only folded corners
      CHECK(T.worst(nn + n) > T0.worst(nn + n));    // and only where that raises them
      CHECK(depth(P, n) == Approx(PI::Padding_options().folded_corner_lift * depth(P0, n)).epsilon(1e-9));
      rim_node_lifted = rim_node_lifted || bool(CGAL::is_border(C.layout.nodes[n], C.layout.mesh));
    } else
      CHECK(P.samples.arc_samples[2 * na + n] == P0.samples.arc_samples[2 * na + n]);
  }
  CHECK(rim_node_lifted);
  // Deterministic.
  CHECK(PI::pad_layout(C.layout, C.samples).samples.arc_samples == P.samples.arc_samples);
}

TEST_CASE("cuboid handedness read from the mesh's orientation agrees with the geometry of sound cuboids", "[layout_volume][boundary_layer]")
{
  // The padded sphere: slabs (one SURFACE side each) and cores (reached through interfaces)
  // are all sound, so the sign of the volume their side grids enclose must be the handedness
  // frame_handedness() reads off the combinatorics, for every cuboid.
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(data("sphere.off")));
  const PI::Patch_sampling_options so = small_options(8).sampling;
  const auto C = PI::split_long_cuboids(L, PI::sample_layout_patches(L, so), so);
  const PI::Padded_layout<Point> P = PI::pad_layout(C.layout, C.samples);
  const std::vector<int> h = PI::internal::frame_handedness(P.layout);
  REQUIRE(h.size() == P.layout.cuboids.size());
  int left = 0;
  for(std::size_t c = 0; c < h.size(); ++c) {
    std::array<PI::Point_grid, 6> grids;
    for(int s = 1; s <= 6; ++s) grids[std::size_t(s - 1)] = PI::internal::cuboid_side_grid(P.layout, P.samples, P.layout.cuboids[c], s);
    const double vol = PI::internal::enclosed_volume(grids);
    INFO("cuboid " << c << " volume " << vol);
    CHECK(h[c] == (vol > 0. ? 1 : -1));
    left += int(h[c] < 0);
  }
  CHECK(left > 0); // slabs run from the surface inwards on a counter-clockwise patch: left-handed
}

TEST_CASE("a long tube becomes a chain of cube-like cuboids cut at its arc-length fractions", "[layout_volume][chains]")
{
  // One 4 x 1 x 1 box: a tube along x, 4 times as long as wide.
  const Layout L = box_chain_layout(1, 4, false, [](double x, double y, double z) { return Point(4. * x, y, z); });
  const PI::Patch_grids G = PI::sample_layout_patches(L, small_options(8).sampling);
  const auto C = PI::split_long_cuboids(L, G, small_options(8).sampling);
  REQUIRE(C.pieces == std::vector<int>{4});
  const Layout& M = C.layout;
  CHECK(M.cuboids.size() == 4);
  CHECK(M.nodes.size() == 8 + 4 * 3);
  CHECK(M.patches.size() == 4 * 4 + 2 + 3);    // side pieces, ends, cross-sections
  CHECK(M.arcs.size() == 4 * 4 + 8 + 4 * 3);   // long pieces, end arcs, cross arcs
  CHECK(C.cuboid_of == std::vector<long>(4, 0));
  REQUIRE(C.samples.grids.size() == M.patches.size());
  // Cross-section l lies in the plane x = l (arc length fractions of straight arcs) and the
  // side pieces between x = m and m + 1.
  int sections = 0;
  for(std::size_t p = 0; p < M.patches.size(); ++p) {
    const auto& g = C.samples.grids[p];
    if(C.patch_of[p] < 0) {
      ++sections;
      CHECK(M.patches[p].kind == Layout::INTERFACE);
      const double x = g(0, 0).x();
      CHECK(std::abs(x - std::round(x)) < 1e-12); // a node: an arc sample
      // The lattice's map to the square is affine (symmetric stencils), so the whole
      // section is flat.
      for(const auto& q : g.points) CHECK(q.x() == Approx(x).margin(1e-9));
    } else if(M.patches[p].kind == Layout::SURFACE && L.patches[std::size_t(C.patch_of[p])].kind == Layout::SURFACE) {
      double lo = 1e9, hi = -1e9;
      for(const auto& q : g.points) { lo = std::min(lo, q.x()); hi = std::max(hi, q.x()); }
      CHECK(hi - lo <= 1. + 1e-9);
    }
  }
  CHECK(sections == 3);
  // The chain's volume: valid, conforming, and it fills the box.
  PI::Layout_volume_options o = small_options(8);
  o.maximum_cuboid_aspect = 2.;
  const PI::Layout_volume_result r = PI::layout_volume(L, o);
  CHECK(r.volume.number_of_patches() == 4);
  CHECK(r.volume.interfaces().size() == 3);
  CHECK(r.core_of == std::vector<long>(4, 0));
  check_against_compute_topology(r.volume);
  CHECK(r.quality.interfaces.conforming);
  check_interface_nets_identical(r.volume);
  double total = 0.;
  for(double v : r.enclosed_volume) total += v;
  CHECK(total == Approx(4.).epsilon(1e-9));
  for(const auto& b : r.quality.certified) CHECK(b.certified_positive);
  // With the boundary layer: a core per piece and a slab per side piece and end.
  o.boundary_layer = 0.25;
  const PI::Layout_volume_result rl = PI::layout_volume(L, o);
  CHECK(rl.volume.number_of_patches() == 4 + 4 * 4 + 2);
  for(std::size_t p = 0; p < rl.core_of.size(); ++p) {
    if(rl.slab_of[p] >= 0) CHECK(L.patches[std::size_t(rl.slab_of[p])].kind == Layout::SURFACE);
    else CHECK(rl.core_of[p] == 0);
  }
  for(const auto& b : rl.quality.certified) CHECK(b.certified_positive);
}

TEST_CASE("a long bent tube is valid as a chain", "[layout_volume][chains]")
{
  // One cuboid bent through a quarter turn and twisted, 4 times as long as wide.
  const auto bend = bend_and_twist(4);
  const Layout L = box_chain_layout(1, 4, true, [&](double x, double y, double z) { return bend(4. * x, y, z); });
  PI::Layout_volume_options o = small_options(8);
  o.maximum_cuboid_aspect = 2.;
  const PI::Layout_volume_result chain = PI::layout_volume(L, o);
  const PI::Layout_volume_result single = PI::layout_volume(L, small_options(8));
  REQUIRE(chain.volume.number_of_patches() == 4);
  for(const auto& b : chain.quality.certified) CHECK(b.certified_positive);
  CHECK(chain.quality.overall_sampled.min_scaled_jacobian >= single.quality.overall_sampled.min_scaled_jacobian);
  CHECK(chain.distance.relative <= single.distance.relative + 1e-9);
}

TEST_CASE("a short tube bent by 120 degrees becomes a chain of 2", "[layout_volume][chains]")
{
  // The unit cube bent about the axis x = -0.4, y = 0.5 (... z) through 120 degrees: its arcs
  // along the bend are 0.84 to 2.93 long, 1.9 times its width on average, below the aspect
  // rule's 2; their ends' tangents turn by 120 degrees, twice the 60 allowed.
  const double R = 0.9, turn = 2. * pi / 3.;
  const Layout L = box_chain_layout(1, 4, false, [&](double x, double y, double z) {
    const double r = R + (y - 0.5), phi = turn * x;
    return Point(r * std::sin(phi), r * std::cos(phi), z);
  });
  const PI::Patch_grids G = PI::sample_layout_patches(L, small_options(8).sampling);
  PI::Cuboid_chain_options co;
  CHECK(PI::split_long_cuboids(L, G, small_options(8).sampling, co).pieces == std::vector<int>{2});
  co.maximum_bend = 0.;
  CHECK(PI::split_long_cuboids(L, G, small_options(8).sampling, co).pieces == std::vector<int>{1});
  // Unbent, the cube stays one piece.
  const Layout cube = box_chain_layout(1, 4);
  CHECK(PI::split_long_cuboids(cube, PI::sample_layout_patches(cube, small_options(8).sampling), small_options(8).sampling).pieces ==
        std::vector<int>{1});
  // Two pieces of 60 degrees are certified valid; the layer and chains of build's defaults.
  PI::Layout_volume_options o = small_options(8);
  o.maximum_cuboid_aspect = 2.;
  const PI::Layout_volume_result chain = PI::layout_volume(L, o);
  CHECK(chain.volume.number_of_patches() == 2);
  for(const auto& b : chain.quality.certified) CHECK(b.certified_positive);
}

TEST_CASE("layout volume of a bent and twisted chain stays valid and close to the mesh", "[layout_volume]")
{
  for(bool open : {true, false}) {
    const int k = open ? 2 : 3;
    INFO("k " << k << " open " << open);
    const Layout L = box_chain_layout(k, 4, open, bend_and_twist(k));
    REQUIRE(L.validate().is_valid());
    const PI::Layout_volume_result r = PI::layout_volume(L, small_options(8));
    CHECK(r.volume.number_of_patches() == std::size_t(k));
    CHECK(r.volume.interfaces().size() == std::size_t(k - 1));
    check_against_compute_topology(r.volume);
    check_no_flips(r.samples);
    check_arc_compatibility(L, r.samples);
    CHECK(r.quality.interfaces.conforming);
    check_interface_nets_identical(r.volume);
    for(std::size_t p = 0; p < r.volume.number_of_patches(); ++p) {
      INFO("patch " << p);
      CHECK(!r.mirrored[p]);
      CHECK(r.quality.certified[p].lower_bound > 0.);
    }
    CHECK(r.distance.relative < 0.02);
  }
}

TEST_CASE("layout volume orients rotated and left-handed cuboid frames", "[layout_volume]")
{
  const Layout base = box_chain_layout(2, 2, false, bend_and_twist(2));
  const std::array<std::array<int, 3>, 6> perms{{{{0, 1, 2}}, {{1, 0, 2}}, {{0, 2, 1}}, {{2, 1, 0}}, {{1, 2, 0}}, {{2, 0, 1}}}};
  const std::array<bool, 6> odd{{false, true, true, true, false, false}};
  int mirrored = 0, cases = 0;
  for(int t = 0; t < 48; t += 5) { // a spread of the 48 frames, both cuboids relabelled differently
    Layout L = base;
    const int t1 = (t * 7 + 3) % 48;
    bool expect[2];
    int idx = 0;
    for(int tt : {t, t1}) {
      const std::array<int, 3>& perm = perms[std::size_t(tt % 6)];
      const std::array<bool, 3> flip{{(tt / 6 & 1) != 0, (tt / 12 & 1) != 0, (tt / 24 & 1) != 0}};
      relabel(L, std::size_t(idx), perm, flip);
      expect[idx] = odd[std::size_t(tt % 6)] != ((int(flip[0]) + int(flip[1]) + int(flip[2])) % 2 == 1);
      ++idx;
    }
    INFO("frames " << t << " and " << t1);
    REQUIRE(L.validate().is_valid());
    PI::Layout_volume_options o = small_options(6);
    o.distance_samples_per_direction = 8;
    const PI::Layout_volume_result r = PI::layout_volume(L, o);
    for(int c = 0; c < 2; ++c) {
      CHECK(r.mirrored[std::size_t(c)] == expect[c]);
      CHECK(r.quality.certified[std::size_t(c)].lower_bound > 0.);
      mirrored += int(r.mirrored[std::size_t(c)]);
    }
    CHECK(r.volume.interfaces().size() == 1);
    CHECK(r.quality.interfaces.conforming);
    CHECK(r.quality.interfaces.max_gap < 1e-12);
    CHECK(check_interface_nets_identical(r.volume) > 0);
    check_against_compute_topology(r.volume);
    ++cases;
  }
  CHECK(mirrored > 0);
  CHECK(mirrored < 2 * cases);
}

TEST_CASE("per-cuboid fitting agrees with the shared fits to rounding", "[layout_volume]")
{
  Layout L = box_chain_layout(2, 3, true, bend_and_twist(2));
  relabel(L, 1, {{1, 0, 2}}, {{false, false, true}}); // a different frame on each side of the interface
  PI::Layout_volume_options o = small_options(8);
  const PI::Layout_volume_result shared = PI::layout_volume(L, o);
  o.per_cuboid_fit = true;
  const PI::Layout_volume_result own = PI::layout_volume(L, o);
  CHECK(own.quality.interfaces.conforming);
  CHECK(shared.quality.interfaces.max_gap <= own.quality.interfaces.max_gap);
  double diff = 0.;
  for(std::size_t p = 0; p < 2; ++p)
    for(std::size_t i = 0; i < shared.volume.patch(p).control_points().size(); ++i)
      diff = std::max(diff, (shared.volume.patch(p).control_points()[i] - own.volume.patch(p).control_points()[i]).norm());
  CHECK(diff < 1e-12);
  for(std::size_t p = 0; p < 2; ++p) CHECK(own.quality.certified[p].lower_bound > 0.);
}

TEST_CASE("layout volume round-trips through G+Smo XML bit for bit", "[layout_volume]")
{
  const Layout L = box_chain_layout(2, 3, true, bend_and_twist(2));
  PI::Layout_volume_options o = small_options(8);
  o.evaluate_quality = false;
  const PI::Layout_volume_result r = PI::layout_volume(L, o);
  std::stringstream xml;
  PI::IO::write_gismo_xml(xml, r.volume);
  const PI::Multipatch_volume back = PI::IO::read_gismo_xml(xml);
  REQUIRE(back.number_of_patches() == r.volume.number_of_patches());
  for(std::size_t p = 0; p < back.number_of_patches(); ++p) {
    CHECK(back.patch(p).control_points() == r.volume.patch(p).control_points());
    for(int d = 0; d < 3; ++d) CHECK(back.patch(p).knot_vector(d) == r.volume.patch(p).knot_vector(d));
  }
  REQUIRE(back.interfaces().size() == r.volume.interfaces().size());
  for(std::size_t i = 0; i < back.interfaces().size(); ++i)
    CHECK(interface_key(back.interfaces()[i]) == interface_key(r.volume.interfaces()[i]));
  CHECK(back.boundaries() == r.volume.boundaries());
}

TEST_CASE("layout volume is deterministic", "[layout_volume]")
{
  const Layout L = box_chain_layout(3, 3, false, bend_and_twist(3));
  PI::Layout_volume_options o = small_options(8);
  o.evaluate_quality = false;
  const PI::Layout_volume_result a = PI::layout_volume(L, o), b = PI::layout_volume(L, o);
  for(std::size_t p = 0; p < a.samples.grids.size(); ++p) CHECK(a.samples.grids[p].points == b.samples.grids[p].points);
  REQUIRE(a.volume.number_of_patches() == b.volume.number_of_patches());
  for(std::size_t p = 0; p < a.volume.number_of_patches(); ++p)
    CHECK(a.volume.patch(p).control_points() == b.volume.patch(p).control_points());
  std::stringstream xa, xb;
  PI::IO::write_gismo_xml(xa, a.volume);
  PI::IO::write_gismo_xml(xb, b.volume);
  CHECK(xa.str() == xb.str());
}

TEST_CASE("untangling a measured layout volume gives the figures of untangling while building", "[layout_volume][untangling]")
{
  // untangle_layout_volume() reuses what layout_volume() measured (certificates for the
  // untangler's choice, figures of patches it did not move, the boundary distance, which
  // untangling cannot change); the result must be that of layout_volume() untangling itself.
  const Layout L = PI::Cuboid_decomposition<Mesh>()(load(data("sphere.off")));
  PI::Layout_volume_options o = small_options(16);
  o.boundary_layer = 0.25;
  o.maximum_cuboid_aspect = 2.;
  o.untangle = false;
  PI::Layout_volume_result later = PI::layout_volume(L, o);
  REQUIRE(later.quality_evaluated);
  REQUIRE_FALSE(later.quality.overall_certified.certified_positive); // the padded cube folds (test_build)
  PI::untangle_layout_volume(L, later, o);
  o.untangle = true;
  const PI::Layout_volume_result at_once = PI::layout_volume(L, o);
  REQUIRE(later.volume.number_of_patches() == at_once.volume.number_of_patches());
  CHECK_FALSE(later.untangling.patches.empty());
  CHECK(later.untangling.patches == at_once.untangling.patches);
  for(std::size_t p = 0; p < later.volume.number_of_patches(); ++p) {
    CHECK(later.volume.patch(p).control_points() == at_once.volume.patch(p).control_points());
    CHECK(later.quality.certified[p].lower_bound == at_once.quality.certified[p].lower_bound);
    CHECK(later.quality.sampled[p].min_scaled_jacobian == at_once.quality.sampled[p].min_scaled_jacobian);
  }
  CHECK(later.distance.hausdorff == at_once.distance.hausdorff);
  CHECK(later.distance.folded_sides.size() == at_once.distance.folded_sides.size());
  CHECK(later.quality.interfaces.max_gap == at_once.quality.interfaces.max_gap);
}

TEST_CASE("layout volume named parameters match the options struct", "[layout_volume]")
{
  const Layout L = box_chain_layout(1, 3, true);
  PI::Layout_volume_options o;
  o.sampling.grid_segments = 6;
  o.degree = 2;
  o.spans = 3;
  o.bending_weight = 1e-5;
  o.evaluate_quality = false;
  const PI::Layout_volume_result a = PI::layout_volume(L, o);
  PI::Layout_volume_options base;
  base.evaluate_quality = false;
  const PI::Layout_volume_result b =
    PI::layout_volume(L, PI::parameters::grid_resolution(6).spline_degree(2).number_of_spans(3).bending_weight(1e-5), base);
  CHECK(b.degree == 2);
  CHECK(b.spans == 3);
  CHECK(b.samples.segments == 6);
  CHECK(a.volume.patch(0).control_points() == b.volume.patch(0).control_points());
  // Default spans: N / 4, at least 1.
  o.spans = 0;
  o.sampling.grid_segments = 3;
  CHECK(PI::layout_volume(L, o).spans == 1);
  // Options of the untangling.
  CHECK(PI::layout_volume_options(PI::parameters::default_values()).untangling.focused_sample_rounds ==
        PI::Volume_untangling_options().focused_sample_rounds);
  CHECK(PI::layout_volume_options(PI::parameters::focused_sample_rounds(0)).untangling.focused_sample_rounds == 0);
  CHECK_THROWS_AS(PI::layout_volume_options(PI::parameters::focused_sample_rounds(-1)), PI::Invalid_input_error);
}

TEST_CASE("patch sampling rejects bad resolutions and mismatched grids", "[layout_volume]")
{
  const Layout L = box_chain_layout(1, 2);
  CHECK_THROWS_AS(PI::sample_layout_patches(L, PI::parameters::grid_resolution(0)), PI::Invalid_input_error);
  PI::Patch_grids g = PI::sample_layout_patches(L, PI::parameters::grid_resolution(4));
  g.grids.pop_back();
  CHECK_THROWS_AS(PI::layout_volume(L, g), PI::Invalid_input_error);
  Layout bad = L;
  bad.patches[0].arcs[0] = bad.patches[0].arcs[2];
  CHECK_THROWS_AS(PI::sample_layout_patches(bad), PI::Invalid_input_error);
}
