// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Polycube_layout::validate() on layouts known by construction, and on broken copies of
// them: every check must be able to fail.

#include "layout_fixtures.h"

#include <CGAL/Polycube_IGA/internal/layout_measures.h>

#include <catch2/catch.hpp>

#include <array>

using namespace test_support;

namespace {
bool mentions(const CGAL::Polycube_IGA::Layout_validation& v, const std::string& what)
{
  for(const auto& p : v.problems)
    if(p.find(what) != std::string::npos) return true;
  return false;
}
} // namespace

TEST_CASE("layout validate accepts closed and open box chains", "[layout]")
{
  for(bool open : {false, true})
    for(int k : {1, 3}) {
      const Layout L = box_chain_layout(k, 3, open);
      const auto v = L.validate();
      INFO((v.problems.empty() ? std::string() : v.problems.front()));
      CHECK(v.is_valid());
      CHECK(v.euler_surface == (open ? 0 : 2));
      CHECK(v.euler_solid == 1);
      CHECK(v.minimum_valence == 3);
      CHECK(L.cuboids.size() == std::size_t(k));
      CHECK(L.interfaces().size() == std::size_t(k - 1));
    }
}

TEST_CASE("layout validate names broken layouts", "[layout]")
{
  const Layout good = box_chain_layout(2, 3);
  {
    Layout L = good; // a face in two patches
    L.patches[1].faces.push_back(L.patches[0].faces.front());
    CHECK(mentions(L.validate(), "overlaps"));
  }
  {
    Layout L = good; // a face in no patch
    L.patches[0].faces.pop_back();
    CHECK(mentions(L.validate(), "in no patch"));
  }
  {
    Layout L = good; // corners out of order
    std::swap(L.patches[0].corners[1], L.patches[0].corners[3]);
    CHECK(!L.validate().is_valid());
  }
  {
    Layout L = good; // an arc with a gap
    L.arcs[0].vertices.erase(L.arcs[0].vertices.begin() + 1);
    CHECK(mentions(L.validate(), "non-adjacent"));
  }
  {
    Layout L = good; // a cuboid pointing at the wrong patch
    L.cuboids[0].patches[1] = L.cuboids[1].patches[1];
    CHECK(mentions(L.validate(), "not bounded by its patch"));
  }
  {
    Layout L = good; // the interface made a cap: used by two cuboids, and wrong Euler count
    for(auto& p : L.patches)
      if(p.kind == Layout::INTERFACE) p.kind = Layout::CAP;
    CHECK(mentions(L.validate(), "used by 2 cuboids"));
  }
  {
    Layout L = good; // claims the wrong genus
    L.genus = 1;
    CHECK(mentions(L.validate(), "Euler characteristic"));
  }
}

#include <CGAL/Polycube_IGA/internal/layout_assembly.h>

TEST_CASE("layout assembly rebuilds patches and cuboids from nodes and arcs", "[layout]")
{
  for(bool open : {false, true}) {
    const Layout ref = box_chain_layout(3, 2, open);
    Layout L = ref;
    L.patches.clear();
    L.cuboids.clear();
    std::vector<CGAL::Polycube_IGA::internal::Interior_quad> interior;
    for(const auto& p : ref.patches)
      if(p.kind != Layout::SURFACE) interior.push_back({int(p.kind), p.corners});
    std::vector<std::array<std::size_t, 8>> cuboids;
    for(const auto& c : ref.cuboids) cuboids.push_back(c.nodes);
    CGAL::Polycube_IGA::internal::assemble_layout(L, interior, cuboids, {});
    const auto v = L.validate();
    INFO((v.problems.empty() ? std::string() : v.problems.front()));
    CHECK(v.is_valid());
    CHECK(L.patches.size() == ref.patches.size());
    CHECK(L.number_of_surface_patches() == ref.number_of_surface_patches());
    CHECK(L.cuboids.size() == ref.cuboids.size());
    // An arc removed: two patches merge and the assembly must refuse.
    Layout broken = ref;
    broken.arcs.erase(broken.arcs.begin());
    broken.patches.clear();
    CHECK_THROWS_AS(CGAL::Polycube_IGA::internal::assemble_layout(broken, interior, cuboids, {}), CGAL::Polycube_IGA::Internal_error);
  }
}

// How many patches of L measure below `split` and how many above; each must measure `low`
// or `high` (to 1e-12).
template <class Measure>
std::array<std::size_t, 2> split_patches(const Layout& L, Measure measure, double split, double low, double high)
{
  std::array<std::size_t, 2> n{{0, 0}};
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    const double x = measure(L, p);
    const bool above = x > split;
    CHECK(x == Approx(above ? high : low).epsilon(1e-12));
    ++n[above ? 1 : 0];
  }
  return n;
}

TEST_CASE("patch elongation is length over width and names strips", "[layout]")
{
  using CGAL::Polycube_IGA::internal::patch_elongation;
  using CGAL::Polycube_IGA::internal::patch_side_drift;
  using CGAL::Polycube_IGA::internal::strip_elongation;
  // One cuboid 10 by 1 by 1: its four long sides are 10 by 1 strips, its ends unit squares.
  const Layout L = box_chain_layout(1, 4, false, [](double x, double y, double z) { return Point(10. * x, y, z); });
  REQUIRE(L.validate().is_valid());
  const auto squares_strips = split_patches(L, patch_elongation<Point>, strip_elongation, 1., 10.);
  CHECK(squares_strips[0] == 2);
  CHECK(squares_strips[1] == 4);
  // A unit cube has none.
  const Layout cube = box_chain_layout(1, 3);
  for(std::size_t p = 0; p < cube.patches.size(); ++p) CHECK(patch_elongation(cube, p) == Approx(1.).epsilon(1e-12));
  // Equal long sides do not drift.
  for(std::size_t p = 0; p < L.patches.size(); ++p) CHECK(patch_side_drift(L, p) == Approx(0.).margin(1e-12));
}

TEST_CASE("patch fill is the area over length times breadth and names bands", "[layout]")
{
  using CGAL::Polycube_IGA::internal::band_fill;
  using CGAL::Polycube_IGA::internal::band_patches;
  using CGAL::Polycube_IGA::internal::patch_elongation;
  using CGAL::Polycube_IGA::internal::patch_fill;
  // A unit cube sheared along x by s times y: its sides z = 0 and z = 1 are parallelograms
  // with sides 1 and sqrt(1 + s^2) and area 1, so they fill 1 / sqrt(1 + s^2) of the
  // rectangle their sides span; the other four sides are rectangles (fill 1).
  for(const double shear : {3., 4.}) {
    const Layout L = box_chain_layout(1, 4, false, [&](double x, double y, double z) { return Point(x + shear * y, y, z); });
    REQUIRE(L.validate().is_valid());
    const double sine = 1. / std::sqrt(1. + shear * shear);
    const auto parallelograms_rectangles = split_patches(L, patch_fill<Point>, 0.5, sine, 1.);
    CHECK(parallelograms_rectangles[0] == 2);
    CHECK(parallelograms_rectangles[1] == 4);
    // Sheared by 3 they fill 0.316 (no band), by 4 0.243 (bands), and are as elongated as
    // the square of their long side over their area.
    const auto bands = band_patches(L);
    CHECK(bands.size() == (sine < band_fill ? 2u : 0u));
    for(const auto& b : bands) {
      CHECK(b.fill == Approx(sine).epsilon(1e-12));
      CHECK(b.elongation == Approx(patch_elongation(L, b.patch)).epsilon(1e-15));
      CHECK(b.elongation == Approx(1. + shear * shear).epsilon(1e-9));
    }
  }
  // Long rectangles are strips, not bands.
  const Layout bar = box_chain_layout(1, 4, false, [](double x, double y, double z) { return Point(10. * x, y, z); });
  for(std::size_t p = 0; p < bar.patches.size(); ++p) CHECK(patch_fill(bar, p) == Approx(1.).epsilon(1e-12));
  CHECK(band_patches(bar).empty());
}

TEST_CASE("patch side drift is the difference of the long sides over the width", "[layout]")
{
  using CGAL::Polycube_IGA::internal::patch_elongation;
  using CGAL::Polycube_IGA::internal::patch_side_drift;
  using CGAL::Polycube_IGA::internal::strip_patches;
  // A cuboid whose x extent shrinks from 20 at y = 0 to 16 at y = 1 (height 1 in z): its
  // sides z = 0 and z = 1 are trapezoids with long sides 20 and 16 a width 1 apart (drift 4,
  // elongation 18); its sides y = 0 and y = 1 are 20 by 1 and 16 by 1 rectangles (drift 0);
  // its ends x = 0 (a unit square) and x = 1 (4.12 by 1) are no strips.
  const Layout L = box_chain_layout(1, 4, false, [](double x, double y, double z) { return Point((20. - 4. * y) * x, y, z); });
  REQUIRE(L.validate().is_valid());
  std::size_t trapezoids = 0, rectangles = 0;
  for(const auto& s : strip_patches(L)) {
    CHECK(s.elongation == Approx(patch_elongation(L, s.patch)).epsilon(1e-15));
    CHECK(s.drift == Approx(patch_side_drift(L, s.patch)).epsilon(1e-15));
    if(s.drift > 1.) {
      CHECK(s.drift == Approx(4.).epsilon(1e-9));
      CHECK(s.elongation == Approx(18.).epsilon(1e-9));
      ++trapezoids;
    } else {
      CHECK(s.drift == Approx(0.).margin(1e-9));
      CHECK((s.elongation == Approx(20.).epsilon(1e-9) || s.elongation == Approx(16.).epsilon(1e-9)));
      ++rectangles;
    }
  }
  CHECK(trapezoids == 2);
  CHECK(rectangles == 2);
}
