// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Cut_criteria: jet-fitted minimum principal curvature against analytic values (sphere:
// kmin = 1/R; torus R=3, r=1: kmin = -1/(R-r) = -0.5 on the inner equator, 1/(R+r) = 0.25
// on the outer one; fit error shrinks with resolution), its sign under a flipped orientation, scale invariance of r(v), and the
// edge weights of each criterion (positive, LENGTH = edge length, SYMMETRY smallest on the
// plane, MINIMA_RULE cheaper on the concave side), determinism and the error reason codes.

#include "test_support.h"

#include <CGAL/Polycube_IGA/Cut_criteria.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

using namespace test_support;
namespace PI = CGAL::Polycube_IGA;
using Graph = PI::internal::Mesh_graph<Mesh>;

namespace {

Graph graph_of(const Mesh& m) { return Graph(m, get(CGAL::vertex_point, m)); }

/// The torus of torus_off(3, 1, n, m): vertex i * m + j sits at angles u = 2 pi i / n
/// (around the axis) and v = 2 pi j / m (around the tube; j = 0 outer, j = m / 2 inner equator).
const Mesh& torus()
{
  static const Mesh m = load(write_text("cut_criteria_torus.off", torus_off(3, 1, 64, 24)));
  return m;
}
constexpr int torus_m = 24;

template <class F>
std::string reason_of(F&& f)
{
  try { f(); } catch(const PI::Invalid_input_error& e) { return e.reason(); }
  return "no error";
}

double mean(const std::vector<double>& x) { return std::accumulate(x.begin(), x.end(), 0.0) / double(x.size()); }

} // namespace

TEST_CASE("sphere: kmin is 1/R with small spread, r finite")
{
  const Mesh m = load(data("sphere.off"));
  const Graph g = graph_of(m);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for(const auto& p : g.position) c += p;
  c /= double(g.position.size());
  double radius = 0;
  for(const auto& p : g.position) radius += (p - c).norm();
  radius /= double(g.position.size());

  const std::vector<double> k = PI::internal::minimum_principal_curvature(g);
  REQUIRE(k.size() == g.position.size());
  for(double x : k) REQUIRE(std::isfinite(x));
  const double mu = mean(k);
  double var = 0;
  for(double x : k) var += (x - mu) * (x - mu);
  const double sigma = std::sqrt(var / double(k.size()));
  INFO("R = " << radius << ", mean kmin = " << mu << ", 1/R = " << 1 / radius << ", stddev = " << sigma
       << ", min = " << *std::min_element(k.begin(), k.end()) << ", max = " << *std::max_element(k.begin(), k.end()));
  // 162 vertices: a 2-ring spans about 0.7 rad of the sphere, and the quadratic jet absorbs
  // part of the quartic term of the sphere's height function, so kmin comes out ~11 % above
  // 1/R (measured 2.214 for 1/R = 2.000); the finer torus below is within 1.3 %.
  CHECK(mu * radius == Approx(1.0).epsilon(0.15));
  CHECK(sigma * radius < 0.05);
  for(double x : k) CHECK(x > 0);

  const std::vector<double> r = PI::normalized_minimum_curvature(g);
  REQUIRE(r.size() == k.size());
  for(double x : r) REQUIRE(std::isfinite(x));
  CHECK(std::abs(mean(r)) < 1e-9);
}

TEST_CASE("torus: kmin negative on the inner equator, inner side has the lowest r")
{
  const Graph g = graph_of(torus());
  const std::vector<double> k = PI::internal::minimum_principal_curvature(g);
  const std::vector<double> r = PI::normalized_minimum_curvature(g);
  REQUIRE(k.size() == g.position.size());
  std::vector<double> inner_k, outer_k, inner_r, outer_r, inner_half_r, outer_half_r;
  for(int v = 0; v < g.number_of_vertices(); ++v) {
    REQUIRE(std::isfinite(k[v]));
    REQUIRE(std::isfinite(r[v]));
    const int j = v % torus_m;
    if(j == torus_m / 2) { inner_k.push_back(k[v]); inner_r.push_back(r[v]); }
    if(j == 0) { outer_k.push_back(k[v]); outer_r.push_back(r[v]); }
    const double cv = std::cos(2 * M_PI * j / torus_m);
    if(cv < -1e-9) inner_half_r.push_back(r[v]);
    if(cv > 1e-9) outer_half_r.push_back(r[v]);
  }
  INFO("inner equator kmin in [" << *std::min_element(inner_k.begin(), inner_k.end()) << ", "
       << *std::max_element(inner_k.begin(), inner_k.end()) << "] (exact -0.5), outer equator kmin in ["
       << *std::min_element(outer_k.begin(), outer_k.end()) << ", " << *std::max_element(outer_k.begin(), outer_k.end())
       << "] (exact 0.25); r inner " << mean(inner_r) << ", r outer " << mean(outer_r));
  for(double x : inner_k) CHECK(x == Approx(-0.5).epsilon(0.05));
  for(double x : outer_k) CHECK(x == Approx(0.25).epsilon(0.05));
  // The inner equator carries the lowest r of the mesh (up to fitting noise between copies).
  const double r_min = *std::min_element(r.begin(), r.end());
  for(double x : inner_r) CHECK(x <= r_min + 1e-6);
  CHECK(mean(inner_half_r) < mean(outer_half_r));
  CHECK(*std::max_element(inner_r.begin(), inner_r.end()) < *std::min_element(outer_r.begin(), outer_r.end()));
}

TEST_CASE("curvature sign follows the outward normal, r is scale invariant")
{
  Mesh flipped = torus();
  CGAL::Polygon_mesh_processing::reverse_face_orientations(flipped);
  const Graph g = graph_of(torus()), gf = graph_of(flipped);
  REQUIRE(g.capped_signed_volume() * gf.capped_signed_volume() < 0);
  const std::vector<double> k = PI::internal::minimum_principal_curvature(g);
  const std::vector<double> kf = PI::internal::minimum_principal_curvature(gf);
  for(std::size_t v = 0; v < k.size(); ++v) CHECK(kf[v] == Approx(k[v]).margin(1e-9));

  Mesh scaled = torus();
  for(auto v : vertices(scaled)) {
    const Point p = scaled.point(v);
    scaled.point(v) = Point(10 * p.x() + 1, 10 * p.y() - 2, 10 * p.z() + 3);
  }
  const Graph gs = graph_of(scaled);
  const std::vector<double> ks = PI::internal::minimum_principal_curvature(gs);
  const std::vector<double> r = PI::normalized_minimum_curvature(g), rs = PI::normalized_minimum_curvature(gs);
  for(std::size_t v = 0; v < k.size(); ++v) {
    CHECK(10 * ks[v] == Approx(k[v]).margin(1e-9));
    CHECK(rs[v] == Approx(r[v]).margin(1e-7));
  }
}

TEST_CASE("LENGTH weights are the edge lengths, every criterion gives positive finite weights")
{
  const Graph g = graph_of(torus());
  PI::Cut_criterion_options o;
  const std::vector<double> w = PI::cut_edge_weights(g, o);
  REQUIRE(int(w.size()) == g.number_of_edges());
  for(int e = 0; e < g.number_of_edges(); ++e)
    CHECK(w[e] == (g.position[g.edge_vertices[e][0]] - g.position[g.edge_vertices[e][1]]).norm());
  for(auto c : {PI::Cut_criterion::LENGTH, PI::Cut_criterion::SYMMETRY, PI::Cut_criterion::MINIMA_RULE})
    for(double strength : {0.0, 1.0, 1e6}) {
      o.criterion = c;
      o.strength = strength;
      const std::vector<double> x = PI::cut_edge_weights(g, o);
      REQUIRE(int(x.size()) == g.number_of_edges());
      for(double y : x) {
        CHECK(y > 0);
        CHECK(std::isfinite(y));
      }
      if(strength == 1.0) CHECK(x == PI::cut_edge_weights(g, o)); // deterministic
    }
}

TEST_CASE("SYMMETRY weights per unit length are smallest on the plane and grow with distance")
{
  const Graph g = graph_of(torus());
  PI::Cut_criterion_options o;
  o.criterion = PI::Cut_criterion::SYMMETRY; // default plane z = 0
  const std::vector<double> w = PI::cut_edge_weights(g, o);
  o.symmetry_plane = {0, 0, -4, 0}; // same plane, not normalised, opposite normal
  CHECK(PI::cut_edge_weights(g, o) == w);

  double diag = 0;
  {
    Eigen::Vector3d lo = g.position[0], hi = g.position[0];
    for(const auto& p : g.position) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
    diag = (hi - lo).norm();
  }
  double on_plane_max = 0, off_plane_min = std::numeric_limits<double>::max();
  for(int e = 0; e < g.number_of_edges(); ++e) {
    const auto& a = g.position[g.edge_vertices[e][0]];
    const auto& b = g.position[g.edge_vertices[e][1]];
    const double density = w[e] / g.length(e);
    const double d = 0.5 * (std::abs(a.z()) + std::abs(b.z()));
    CHECK(density == Approx(0.01 + d / diag).epsilon(1e-12));
    if(std::abs(a.z()) < 1e-12 && std::abs(b.z()) < 1e-12) on_plane_max = std::max(on_plane_max, density);
    else off_plane_min = std::min(off_plane_min, density);
  }
  CHECK(on_plane_max == Approx(0.01).epsilon(1e-9));
  CHECK(on_plane_max < off_plane_min);

  // The plane x = 1 (offset d = -1): the density is smallest on edges nearest to it.
  o.symmetry_plane = {1, 0, 0, -1};
  const std::vector<double> wx = PI::cut_edge_weights(g, o);
  int best = 0;
  double best_distance = std::numeric_limits<double>::max();
  for(int e = 0; e < g.number_of_edges(); ++e) {
    const double d = 0.5 * (std::abs(g.position[g.edge_vertices[e][0]].x() - 1) +
                            std::abs(g.position[g.edge_vertices[e][1]].x() - 1));
    if(d < best_distance) { best_distance = d; best = e; }
  }
  double min_density = std::numeric_limits<double>::max();
  for(int e = 0; e < g.number_of_edges(); ++e) min_density = std::min(min_density, wx[e] / g.length(e));
  CHECK(wx[best] / g.length(best) == Approx(min_density).epsilon(1e-12));
}

TEST_CASE("MINIMA_RULE weights: length times exp(strength mean r), cheaper on the concave side")
{
  const Graph g = graph_of(torus());
  const std::vector<double> r = PI::normalized_minimum_curvature(g);
  PI::Cut_criterion_options o;
  o.criterion = PI::Cut_criterion::MINIMA_RULE;
  o.strength = 2.0;
  const std::vector<double> w = PI::cut_edge_weights(g, o);
  double inner = 0, outer = 0;
  int n_inner = 0, n_outer = 0;
  for(int e = 0; e < g.number_of_edges(); ++e) {
    const int a = g.edge_vertices[e][0], b = g.edge_vertices[e][1];
    CHECK(w[e] == Approx(g.length(e) * std::exp(std::clamp(2.0 * 0.5 * (r[a] + r[b]), -3.0, 3.0))).epsilon(1e-12));
    if(a % torus_m == torus_m / 2 && b % torus_m == torus_m / 2) { inner += w[e] / g.length(e); ++n_inner; }
    if(a % torus_m == 0 && b % torus_m == 0) { outer += w[e] / g.length(e); ++n_outer; }
  }
  REQUIRE(n_inner == 64);
  REQUIRE(n_outer == 64);
  CHECK(inner / n_inner < 1.0);
  CHECK(outer / n_outer > 1.0);

  o.strength = 0;
  const std::vector<double> w0 = PI::cut_edge_weights(g, o);
  for(int e = 0; e < g.number_of_edges(); ++e) CHECK(w0[e] == Approx(g.length(e)).epsilon(1e-15));
}

TEST_CASE("bad input: reason codes")
{
  CHECK(PI::parse_cut_criterion("length") == PI::Cut_criterion::LENGTH);
  CHECK(PI::parse_cut_criterion("symmetry") == PI::Cut_criterion::SYMMETRY);
  CHECK(PI::parse_cut_criterion("minima") == PI::Cut_criterion::MINIMA_RULE);
  for(auto c : {PI::Cut_criterion::LENGTH, PI::Cut_criterion::SYMMETRY, PI::Cut_criterion::MINIMA_RULE})
    CHECK(PI::parse_cut_criterion(PI::cut_criterion_name(c)) == c);
  CHECK(reason_of([] { PI::parse_cut_criterion("Length"); }) == "bad_arguments");
  CHECK(reason_of([] { PI::parse_cut_criterion(""); }) == "bad_arguments");

  const Graph g = graph_of(torus());
  PI::Cut_criterion_options o;
  o.criterion = PI::Cut_criterion::SYMMETRY;
  o.symmetry_plane = {0, 0, 0, 1};
  CHECK(reason_of([&] { PI::cut_edge_weights(g, o); }) == "degenerate_symmetry_plane");
  o.symmetry_plane = {0, std::nan(""), 1, 0};
  CHECK(reason_of([&] { PI::cut_edge_weights(g, o); }) == "degenerate_symmetry_plane");
  o.symmetry_plane = {0, 0, 1, std::numeric_limits<double>::infinity()};
  CHECK(reason_of([&] { PI::cut_edge_weights(g, o); }) == "degenerate_symmetry_plane");
  o.symmetry_plane = {0, 0, 1, 0};
  o.strength = -1;
  CHECK(reason_of([&] { PI::cut_edge_weights(g, o); }) == "invalid_cut_strength");
  o.strength = std::nan("");
  CHECK(reason_of([&] { PI::cut_edge_weights(g, o); }) == "invalid_cut_strength");

  Mesh bad = torus();
  bad.point(*vertices(bad).begin()) = Point(std::nan(""), 0, 0);
  const Graph gb = graph_of(bad);
  CHECK(reason_of([&] { PI::cut_edge_weights(gb, PI::Cut_criterion_options{}); }) == "non_finite_position");
  CHECK(reason_of([&] { PI::normalized_minimum_curvature(gb); }) == "non_finite_position");
}

// Measured (strength 1): eight kmin in [-11.7, 4.8], r in [-2.1, 1.7], density in [0.13, 5.1];
// anchor kmin in [-23.2, 1.9], r in [-7.3, 1.3], density in [0.019, 3.5]. Off the test (too
// slow here): elephant r in [-8.8, 4.5], mech-holes-shark r in [-23.1, 2.3], density down to
// 9e-9 there, since sharp creases give a heavy-tailed kmin distribution.
TEST_CASE("corpus meshes: every vertex gets a finite fit, weights positive")
{
  for(const char* name : {"eight.off", "anchor.off"}) {
    const Mesh m = load(data(name));
    const Graph g = graph_of(m);
    const std::vector<double> k = PI::internal::minimum_principal_curvature(g);
    const std::vector<double> r = PI::normalized_minimum_curvature(g);
    const auto finite = std::count_if(k.begin(), k.end(), [](double x) { return std::isfinite(x); });
    PI::Cut_criterion_options o;
    o.criterion = PI::Cut_criterion::MINIMA_RULE;
    const std::vector<double> w = PI::cut_edge_weights(g, o);
    double wmin = std::numeric_limits<double>::max(), wmax = 0;
    for(int e = 0; e < g.number_of_edges(); ++e) {
      wmin = std::min(wmin, w[e] / g.length(e)); wmax = std::max(wmax, w[e] / g.length(e));
    }
    INFO(name << ": finite fits " << finite << "/" << k.size() << ", kmin in [" << *std::min_element(k.begin(), k.end())
         << ", " << *std::max_element(k.begin(), k.end()) << "], r in [" << *std::min_element(r.begin(), r.end()) << ", "
         << *std::max_element(r.begin(), r.end()) << "], minima density in [" << wmin << ", " << wmax << "]");
    CHECK(std::size_t(finite) == k.size());
    for(double x : r) CHECK(std::isfinite(x));
    for(double x : w) CHECK((x > 0 && std::isfinite(x)));
  }
}
