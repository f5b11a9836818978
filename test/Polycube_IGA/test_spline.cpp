// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Spline back end on analytic solids whose truth is known: unit cube (degree 1 and 3),
// quarter annulus extruded (NURBS), torus sector (NURBS), twisted block, folded volume;
// refinement invariance, fitting convergence rates, Coons reproduction, certified det J
// bounds, interfaces, G+Smo XML round trip, VTU/JSON output, Hausdorff distance, bad input.

#include <CGAL/Polycube_IGA/Boundary_distance.h>
#include <CGAL/Polycube_IGA/Bspline_refinement.h>
#include <CGAL/Polycube_IGA/Bspline_surface_fitting.h>
#include <CGAL/Polycube_IGA/Bspline_volume_construction.h>
#include <CGAL/Polycube_IGA/IO/gismo_xml.h>
#include <CGAL/Polycube_IGA/IO/spline_json.h>
#include <CGAL/Polycube_IGA/IO/vtu.h>
#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/Quality.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/generators.h>

#include <set>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

namespace PI = CGAL::Polycube_IGA;
using PI::Knot_vector;
using PI::Tensor_bspline_volume;
using Vec = Eigen::Vector3d;

namespace {

const double sqrt_half = std::sqrt(0.5);

Tensor_bspline_volume unit_cube(int degree = 1)
{
  const Knot_vector k = Knot_vector::uniform(1, 1);
  std::vector<Vec> P;
  for(int c = 0; c < 2; ++c)
    for(int b = 0; b < 2; ++b)
      for(int a = 0; a < 2; ++a) P.emplace_back(a, b, c);
  return PI::elevate_degree_uniformly<3>(Tensor_bspline_volume({k, k, k}, P), degree - 1);
}

/// Volume whose control points are f(Greville point): exact for affine f.
Tensor_bspline_volume interpolate_at_greville(const std::array<Knot_vector, 3>& k, const std::function<Vec(double, double, double)>& f)
{
  std::vector<Vec> P;
  for(int c = 0; c < k[2].number_of_basis_functions(); ++c)
    for(int b = 0; b < k[1].number_of_basis_functions(); ++b)
      for(int a = 0; a < k[0].number_of_basis_functions(); ++a)
        P.push_back(f(k[0].normalized_greville(a), k[1].normalized_greville(b), k[2].normalized_greville(c)));
  return Tensor_bspline_volume(k, P);
}

/// Quarter annulus r in [1,2], theta in [0, pi/2], extruded z in [0, 1]: exact NURBS,
/// u = angle (quadratic arc), v = radius, w = height.
Tensor_bspline_volume quarter_annulus()
{
  const Knot_vector arc(2, {0, 0, 0, 1, 1, 1}), lin = Knot_vector::uniform(1, 1);
  const Vec C[3] = {Vec(1, 0, 0), Vec(1, 1, 0), Vec(0, 1, 0)};
  const double W[3] = {1, sqrt_half, 1};
  std::vector<Vec> P;
  std::vector<double> w;
  for(int k = 0; k < 2; ++k)
    for(int j = 0; j < 2; ++j)
      for(int i = 0; i < 3; ++i) {
        P.push_back((1. + j) * C[i] + Vec(0, 0, k));
        w.push_back(W[i]);
      }
  return Tensor_bspline_volume({arc, lin, lin}, P, w);
}

/// Sector of a thick torus: major radius R = 3, tube radii rho in [0.5, 1], tube angle phi and
/// revolution angle theta in [0, pi/2]. u = rho (linear), v = phi (arc), w = theta (arc).
Tensor_bspline_volume torus_sector()
{
  const Knot_vector arc(2, {0, 0, 0, 1, 1, 1}), lin = Knot_vector::uniform(1, 1);
  const double C[3][2] = {{1, 0}, {1, 1}, {0, 1}};
  const double W[3] = {1, sqrt_half, 1};
  std::vector<Vec> P;
  std::vector<double> w;
  for(int k = 0; k < 3; ++k)
    for(int j = 0; j < 3; ++j)
      for(int i = 0; i < 2; ++i) {
        const double rho = 0.5 + 0.5 * i;
        // Profile point in the (x, z) half-plane, revolved around z (The NURBS Book 8.5).
        const double px = 3. + rho * C[j][0], pz = rho * C[j][1];
        P.emplace_back(px * C[k][0], px * C[k][1], pz);
        w.push_back(W[j] * W[k]);
      }
  return Tensor_bspline_volume({lin, arc, arc}, P, w);
}

Vec twist(double u, double v, double w, double angle = 1.0)
{
  const double a = angle * w, x = u - 0.5, y = v - 0.5;
  return Vec(0.5 + std::cos(a) * x - std::sin(a) * y, 0.5 + std::sin(a) * x + std::cos(a) * y, 2. * w);
}

/// Twisted block: the interior of a square cross-section rotating with height, fitted as
/// the §4.1 pipeline does (faces from sampled grids, Coons + harmonic interior).
Tensor_bspline_volume twisted_block(int spans = 4, double angle = 1.0)
{
  const auto grids = PI::sample_cuboid_faces([angle](double u, double v, double w) { return twist(u, v, w, angle); }, 17);
  PI::Volume_fitting_options o;
  o.knots = {Knot_vector::uniform(3, spans), Knot_vector::uniform(3, spans), Knot_vector::uniform(3, spans)};
  o.parameterization = PI::Parameterization::uniform;
  o.bending_weight = 0.;
  return PI::fit_bspline_volume(grids, o).volume;
}

double max_difference(const Tensor_bspline_volume& a, const Tensor_bspline_volume& b, int n = 9)
{
  double m = 0.;
  for(int k = 0; k < n; ++k)
    for(int j = 0; j < n; ++j)
      for(int i = 0; i < n; ++i) {
        const std::array<double, 3> s{{i / (n - 1.), j / (n - 1.), k / (n - 1.)}};
        m = std::max(m, (a.evaluate(a.from_normalized(s)) - b.evaluate(b.from_normalized(s))).norm());
      }
  return m;
}

double finite_difference_error(const Tensor_bspline_volume& v)
{
  // First and second derivatives against central differences at interior points.
  const double h = 1e-5;
  double worst = 0.;
  for(double u : {0.23, 0.61})
    for(double vv : {0.37, 0.74})
      for(double w : {0.15, 0.88}) {
        const auto d = v.derivatives({u, vv, w}, 2);
        for(int e = 0; e < 3; ++e) {
          std::array<double, 3> p{{u, vv, w}}, m{{u, vv, w}};
          p[std::size_t(e)] += h;
          m[std::size_t(e)] -= h;
          const auto dp = v.derivatives(p, 1), dm = v.derivatives(m, 1);
          worst = std::max(worst, ((dp.point - dm.point) / (2 * h) - d.first[std::size_t(e)]).norm());
          for(int f = 0; f < 3; ++f)
            worst = std::max(worst, ((dp.first[std::size_t(f)] - dm.first[std::size_t(f)]) / (2 * h) - d.second[std::size_t(e)][std::size_t(f)]).norm());
        }
      }
  return worst;
}

} // namespace

TEST_CASE("knot vectors validate and find spans", "[spline]")
{
  const Knot_vector k(3, {0, 0, 0, 0, 0.25, 0.5, 0.5, 1, 1, 1, 1});
  CHECK(k.number_of_basis_functions() == 7);
  CHECK(k.number_of_spans() == 3);
  CHECK(k.multiplicity(0.5) == 2);
  CHECK(k.find_span(0.) == 3);
  CHECK(k.find_span(0.25) == 4);
  CHECK(k.find_span(0.4) == 4);
  CHECK(k.find_span(0.5) == 6);
  CHECK(k.find_span(1.) == 6);
  auto reason = [](const std::function<void()>& f) {
    try { f(); } catch(const PI::Invalid_input_error& e) { return e.reason(); }
    return std::string("none");
  };
  CHECK(reason([] { Knot_vector(0, {0, 1}); }) == "invalid_knot_vector");
  CHECK(reason([] { Knot_vector(2, {0, 0, 0, 0.7, 0.5, 1, 1, 1}); }) == "invalid_knot_vector");
  CHECK(reason([] { Knot_vector(2, {0, 0, 0.1, 1, 1, 1}); }) == "invalid_knot_vector");
  CHECK(reason([] { Knot_vector(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}); }) == "invalid_knot_vector");
  CHECK(reason([] { Knot_vector(2, {0, 0, 0, std::nan(""), 1, 1, 1}); }) == "invalid_knot_vector");
  CHECK(reason([] { Knot_vector(1, {1, 1, 1, 1}); }) == "invalid_knot_vector");
}

TEST_CASE("basis functions: partition of unity, derivatives against finite differences", "[spline]")
{
  const Knot_vector k(4, {0, 0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 4, 4, 4, 5, 5, 5, 5, 5}); // the reference's Fig. 2.10
  double ders[3 * 5], dp[3 * 5], dm[3 * 5];
  for(double t = 0.; t <= 5.; t += 0.0625) {
    const int s = k.find_span(t);
    PI::basis_function_derivatives(k, s, t, 2, ders);
    double sum = 0., dsum = 0.;
    for(int j = 0; j <= 4; ++j) {
      CHECK(ders[j] >= 0.);
      sum += ders[j];
      dsum += ders[5 + j];
    }
    CHECK(sum == Approx(1.).epsilon(1e-14));
    CHECK(std::abs(dsum) < 1e-12);
    const double h = 1e-6;
    if(t > 0.01 && t < 4.99 && k.find_span(t - h) == s && k.find_span(t + h) == s) {
      PI::basis_function_derivatives(k, s, t + h, 1, dp);
      PI::basis_function_derivatives(k, s, t - h, 1, dm);
      for(int j = 0; j <= 4; ++j) {
        CHECK(std::abs((dp[j] - dm[j]) / (2 * h) - ders[5 + j]) < 1e-6);
        CHECK(std::abs((dp[5 + j] - dm[5 + j]) / (2 * h) - ders[10 + j]) < 1e-4);
      }
    }
  }
}

TEST_CASE("unit cube degree 1 and 3: identity map, det J = 1 certified", "[spline]")
{
  for(int p : {1, 3}) {
    const Tensor_bspline_volume v = unit_cube(p);
    CHECK(v.degree(0) == p);
    for(double u : {0., 0.3, 1.})
      for(double w : {0., 0.55, 1.}) {
        const auto d = v.derivatives({u, 0.7, w}, 2);
        CHECK((d.point - Vec(u, 0.7, w)).norm() < 1e-14);
        CHECK((d.first[0] - Vec(1, 0, 0)).norm() < 1e-13);
        CHECK(d.second[0][1].norm() < 1e-12);
      }
    const auto s = PI::sample_jacobian(v);
    CHECK(s.min_determinant == Approx(1.).epsilon(1e-12));
    CHECK(s.min_scaled_jacobian == Approx(1.).epsilon(1e-12));
    const auto b = PI::certified_jacobian_bound(v);
    CHECK(b.certified_positive);
    CHECK(b.lower_bound == Approx(1.).epsilon(1e-12));
    CHECK(b.upper_bound == Approx(1.).epsilon(1e-12));
  }
}

TEST_CASE("quarter annulus (NURBS): exact radii, analytic det J, certified positive", "[spline]")
{
  const Tensor_bspline_volume v = quarter_annulus();
  CHECK(finite_difference_error(v) < 1e-5);
  for(int i = 0; i <= 10; ++i)
    for(int j = 0; j <= 4; ++j) {
      const double u = i / 10., r = 1. + j / 4.;
      const Vec x = v.evaluate({u, j / 4., 0.3});
      CHECK(std::hypot(x.x(), x.y()) == Approx(r).epsilon(1e-14));
      CHECK(x.z() == Approx(0.3).epsilon(1e-14));
    }
  // Left-handed by construction (angle x radius x height): det J < 0 everywhere.
  const auto s = PI::sample_jacobian(v);
  CHECK(s.max_determinant < 0.);
  // Swap u and v in the net to get the right-handed version, certified positive.
  std::vector<Vec> P;
  std::vector<double> w;
  for(int k = 0; k < 2; ++k)
    for(int i = 0; i < 3; ++i)
      for(int j = 0; j < 2; ++j) {
        P.push_back(v.control_point({i, j, k}));
        w.push_back(v.weights()[v.linear_index({i, j, k})]);
      }
  const Tensor_bspline_volume r({v.knot_vector(1), v.knot_vector(0), v.knot_vector(2)}, P, w);
  const auto sr = PI::sample_jacobian(r, 9);
  const auto br = PI::certified_jacobian_bound(r);
  CHECK(sr.min_determinant > 0.);
  CHECK(br.certified_positive);
  CHECK(br.lower_bound <= sr.min_determinant);
  CHECK(br.upper_bound >= sr.max_determinant);
}

TEST_CASE("torus sector (NURBS): points on the torus, refinement invariance", "[spline]")
{
  const Tensor_bspline_volume v = torus_sector();
  for(int i = 0; i <= 6; ++i)
    for(int j = 0; j <= 6; ++j)
      for(int k = 0; k <= 6; ++k) {
        const Vec x = v.evaluate({i / 6., j / 6., k / 6.});
        const double rho = std::hypot(std::hypot(x.x(), x.y()) - 3., x.z());
        CHECK(rho == Approx(0.5 + 0.5 * i / 6.).epsilon(1e-13));
      }
  const auto b = PI::certified_jacobian_bound(v);
  const auto s = PI::sample_jacobian(v, 7);
  CHECK(b.lower_bound <= s.min_determinant);
  CHECK((b.certified_positive || b.has_nonpositive_value || s.min_determinant > 0.));
  CHECK(s.min_determinant * s.max_determinant > 0.); // one orientation, no fold

  Tensor_bspline_volume r = PI::insert_knot<3>(v, 1, 0.3, 2);
  r = PI::refine_uniformly<3>(r, 2);
  r = PI::elevate_degree<3>(r, 0, 2);
  r = PI::elevate_degree<3>(r, 2, 1);
  CHECK(r.degree(0) == 3);
  CHECK(r.degree(2) == 3);
  CHECK(r.knot_vector(1).multiplicity(0.3) == 2);
  CHECK(max_difference(v, r, 11) < 1e-13);
  // Control points at the same place after refinement of a rational map: weights too.
  CHECK(r.is_rational());
}

TEST_CASE("refinement of curves, surfaces, volumes keeps the geometry to round-off", "[spline]")
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1., 1.);
  // Random cubic curve with a double knot.
  const Knot_vector kc(3, {0, 0, 0, 0, 0.2, 0.5, 0.5, 0.9, 1, 1, 1, 1});
  std::vector<Vec> cp;
  for(int i = 0; i < kc.number_of_basis_functions(); ++i) cp.emplace_back(U(rng), U(rng), U(rng));
  const PI::Bspline_curve c({kc}, cp);
  const PI::Bspline_curve c2 = PI::elevate_degree<1>(PI::refine_knots<1>(c, 0, {0.1, 0.5, 0.77}), 0, 2);
  CHECK(c2.degree(0) == 5);
  CHECK(c2.knot_vector(0).multiplicity(0.5) == 5);
  CHECK(c2.knot_vector(0).multiplicity(0.2) == 3);
  double worst = 0.;
  for(int i = 0; i <= 1000; ++i) {
    const double t = i / 1000.;
    worst = std::max(worst, (c.evaluate({t}) - c2.evaluate({t})).norm());
  }
  CHECK(worst < 1e-13);
  // Random bi-quadratic surface.
  const Knot_vector ks(2, {0, 0, 0, 0.3, 0.6, 1, 1, 1});
  std::vector<Vec> sp;
  for(int i = 0; i < 25; ++i) sp.emplace_back(U(rng), U(rng), U(rng));
  const PI::Tensor_bspline_surface s({ks, ks}, sp);
  const PI::Tensor_bspline_surface s2 = PI::elevate_degree_uniformly<2>(PI::refine_uniformly<2>(s, 3), 1);
  worst = 0.;
  for(int i = 0; i <= 40; ++i)
    for(int j = 0; j <= 40; ++j) worst = std::max(worst, (s.evaluate({i / 40., j / 40.}) - s2.evaluate({i / 40., j / 40.})).norm());
  CHECK(worst < 1e-13);
  // Random trivariate, mixed degrees.
  const Knot_vector k1 = Knot_vector::uniform(1, 2), k2 = Knot_vector::uniform(2, 2), k3(3, {0, 0, 0, 0, 0.4, 1, 1, 1, 1});
  std::vector<Vec> vp;
  for(int i = 0; i < 3 * 4 * 5; ++i) vp.emplace_back(U(rng), U(rng), U(rng));
  const Tensor_bspline_volume v({k1, k2, k3}, vp);
  const Tensor_bspline_volume v2 = PI::elevate_degree_uniformly<3>(PI::refine_uniformly<3>(v, 2), 1);
  CHECK(max_difference(v, v2, 13) < 1e-13);
  // Bezier extraction: every interior knot at multiplicity p.
  const Tensor_bspline_volume b = PI::to_bezier_form<3>(v);
  CHECK(b.knot_vector(2).multiplicity(0.4) == 3);
  CHECK(max_difference(v, b, 13) < 1e-13);
}

TEST_CASE("derivatives of B-spline and NURBS volumes match finite differences", "[spline]")
{
  CHECK(finite_difference_error(torus_sector()) < 1e-5);
  CHECK(finite_difference_error(twisted_block()) < 1e-5);
}

TEST_CASE("surface fitting converges at the expected rate", "[spline]")
{
  // z = sin(2x) cos(3y) over the unit square, given (exact) parameters, no regularization:
  // the least-squares cubic spline error decreases as h^4.
  auto f = [](double x, double y) { return Vec(x, y, std::sin(2 * x) * std::cos(3 * y)); };
  std::vector<double> errors;
  for(int spans : {4, 8, 16}) {
    const int m = 6 * spans + 1;
    PI::Point_grid g(m, m);
    std::vector<double> t(static_cast<std::size_t>(m));
    for(int i = 0; i < m; ++i) t[std::size_t(i)] = double(i) / (m - 1);
    for(int j = 0; j < m; ++j)
      for(int i = 0; i < m; ++i) g(i, j) = f(t[std::size_t(i)], t[std::size_t(j)]);
    PI::Surface_fitting_options o;
    o.spans_u = o.spans_v = spans;
    o.bending_weight = 0.;
    o.parameterization = PI::Parameterization::given;
    o.u_parameters = o.v_parameters = t;
    const auto r = PI::fit_bspline_surface(g, o);
    // Error measured off the data, at the centres between samples.
    double e = 0.;
    for(int j = 0; j + 1 < m; ++j)
      for(int i = 0; i + 1 < m; ++i) {
        const double x = 0.5 * (t[std::size_t(i)] + t[std::size_t(i + 1)]), y = 0.5 * (t[std::size_t(j)] + t[std::size_t(j + 1)]);
        e = std::max(e, (r.spline.evaluate({x, y}) - f(x, y)).norm());
      }
    CHECK(r.max_error <= e * 1.5);
    errors.push_back(e);
  }
  const double rate1 = std::log2(errors[0] / errors[1]), rate2 = std::log2(errors[1] / errors[2]);
  INFO("errors " << errors[0] << " " << errors[1] << " " << errors[2] << " rates " << rate1 << " " << rate2);
  CHECK(rate1 > 3.5);
  CHECK(rate2 > 3.5);
  CHECK(errors[2] < 1e-5);
}

TEST_CASE("named parameters set the fitting weights and the spline space", "[spline]")
{
  const int m = 25;
  PI::Point_grid g(m, m);
  for(int j = 0; j < m; ++j)
    for(int i = 0; i < m; ++i) {
      const double x = double(i) / (m - 1), y = double(j) / (m - 1);
      g(i, j) = Vec(x, y, std::sin(3 * x) * std::cos(2 * y));
    }
  namespace PIP = CGAL::Polycube_IGA::parameters;
  const auto loose = PI::fit_bspline_surface(g, PIP::spline_degree(2).number_of_spans(5).bending_weight(0.0));
  CHECK(loose.spline.degree(0) == 2);
  CHECK(loose.spline.number_of_control_points(1) == 7);
  // Heavy bending regularisation (lambda2) flattens the surface: a larger fitting error.
  const auto stiff = PI::fit_bspline_surface(g, PIP::spline_degree(2).number_of_spans(5).bending_weight(10.0));
  CHECK(stiff.max_error > 10 * loose.max_error);
  // The named form equals the struct form.
  PI::Surface_fitting_options o;
  o.degree_u = o.degree_v = 2;
  o.spans_u = o.spans_v = 5;
  o.bending_weight = 0.0;
  o.stretching_weight = 0.5;
  const auto a = PI::fit_bspline_surface(g, o);
  const auto b = PI::fit_bspline_surface(g, PIP::spline_degree(2).number_of_spans(5).bending_weight(0.0).stretching_weight(0.5));
  CHECK(a.spline.control_points() == b.spline.control_points());
}

TEST_CASE("fitting with chord length and regularization, neighbours share their boundary exactly", "[spline]")
{
  // Two faces of a cylinder-like surface meeting along x = 0, fitted separately.
  auto f = [](double x, double y) { return Vec(x, y, 0.3 * std::sin(3 * x + y) + 0.1 * y * y); };
  const int m = 25;
  PI::Point_grid left(m, m), right(m, m);
  for(int j = 0; j < m; ++j)
    for(int i = 0; i < m; ++i) {
      const double y = double(j) / (m - 1);
      left(i, j) = f(-1. + double(i) / (m - 1), y);
      right(i, j) = f(double(i) / (m - 1), y);
    }
  PI::Curve_fitting_options co;
  co.spans = 6;
  const PI::Bspline_curve common = PI::fit_bspline_curve(right.side(1), co).spline;
  CHECK((common.control_points().front() - right(0, 0)).norm() == 0.);
  PI::Surface_fitting_options o;
  o.spans_u = 5;
  o.spans_v = 6;
  o.stretching_weight = 1e-6;
  o.bending_weight = 1e-6;
  o.fixed_boundaries[1] = common; // u1 of the left face
  const auto a = PI::fit_bspline_surface(left, o);
  o.fixed_boundaries[1].reset();
  o.fixed_boundaries[0] = PI::elevate_degree<1>(PI::Bspline_curve(common), 0, 0); // u0 of the right face
  o.degree_u = 2; // different degree across the boundary is fine
  const auto b = PI::fit_bspline_surface(right, o);
  CHECK(a.max_error < 1e-2); // chord-length parameters, 5 spans, amplitude 0.3
  CHECK(b.max_error < 1e-2);
  for(int j = 0; j < a.spline.number_of_control_points(1); ++j)
    CHECK(a.spline.control_point({a.spline.number_of_control_points(0) - 1, j}) == b.spline.control_point({0, j}));
  for(int j = 0; j <= 50; ++j)
    CHECK((a.spline.evaluate({1., j / 50.}) - b.spline.evaluate({0., j / 50.})).norm() == 0.);
  // Fixing a curve whose knots the surface lacks is refused, not silently altered.
  o.fixed_boundaries[0] = PI::fit_bspline_curve(right.side(1), [] { PI::Curve_fitting_options c; c.spans = 7; return c; }()).spline;
  CHECK_THROWS_AS(PI::fit_bspline_surface(right, o), PI::Invalid_input_error);
}

TEST_CASE("Coons volume reproduces a trilinear block exactly, smoothing variants", "[spline]")
{
  const Vec c[8] = {Vec(0, 0, 0), Vec(2, 0.1, 0), Vec(-0.2, 1, 0.1), Vec(1.7, 1.4, 0.2),
                    Vec(0.1, -0.1, 1), Vec(2.2, 0, 1.3), Vec(0, 1.1, 1.2), Vec(2, 1.5, 1.6)};
  auto tri = [&](double u, double v, double w) {
    Vec r = Vec::Zero();
    for(int k = 0; k < 8; ++k) r += ((k & 1) ? u : 1 - u) * ((k & 2) ? v : 1 - v) * ((k & 4) ? w : 1 - w) * c[k];
    return r;
  };
  const std::array<Knot_vector, 3> k{{Knot_vector(3, {0, 0, 0, 0, 0.2, 0.7, 1, 1, 1, 1}), Knot_vector::uniform(2, 3),
                                      Knot_vector(3, {0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1})}};
  const Tensor_bspline_volume truth = interpolate_at_greville(k, tri);
  std::array<PI::Tensor_bspline_surface, 6> faces;
  for(int s = 1; s <= 6; ++s) faces[std::size_t(s - 1)] = PI::side_surface(truth, s);
  PI::Volume_construction_options o;
  o.smoothing = PI::Interior_smoothing::none;
  const auto coons = PI::build_bspline_volume(faces, o);
  for(std::size_t i = 0; i < truth.number_of_control_points(); ++i)
    CHECK((coons.volume.control_points()[i] - truth.control_points()[i]).norm() < 1e-14);
  for(double u : {0.1, 0.45, 0.9})
    for(double w : {0.05, 0.5, 0.95}) CHECK((coons.volume.evaluate({u, 0.33, w}) - tri(u, 0.33, w)).norm() < 1e-14);

  // Harmonic solve and fixed-point iteration agree, and the boundary does not move.
  const auto harmonic = PI::build_bspline_volume(faces);
  o.smoothing = PI::Interior_smoothing::fixed_point_iteration;
  o.iteration_tolerance = 1e-13;
  const auto iterated = PI::build_bspline_volume(faces, o);
  CHECK(iterated.iterations > 1);
  double diff = 0.;
  for(std::size_t i = 0; i < truth.number_of_control_points(); ++i)
    diff = std::max(diff, (harmonic.volume.control_points()[i] - iterated.volume.control_points()[i]).norm());
  CHECK(diff < 1e-9);
  for(int s = 1; s <= 6; ++s) {
    const auto f = PI::side_surface(harmonic.volume, s);
    CHECK(f.control_points() == faces[std::size_t(s - 1)].control_points());
  }
  // Harmonic interior: each interior control point is the mean of its 6 neighbours.
  const auto& V = harmonic.volume;
  const Vec mean = (V.control_point({0, 2, 2}) + V.control_point({2, 2, 2}) + V.control_point({1, 1, 2}) +
                    V.control_point({1, 3, 2}) + V.control_point({1, 2, 1}) + V.control_point({1, 2, 3})) / 6.;
  CHECK((mean - V.control_point({1, 2, 2})).norm() < 1e-12);
  CHECK(PI::certified_jacobian_bound(V).certified_positive);

  // Incompatible faces are refused.
  auto bad = faces;
  bad[4].control_points()[0] += Vec(0.1, 0, 0);
  CHECK_THROWS_AS(PI::build_bspline_volume(bad), PI::Invalid_input_error);
  bad = faces;
  bad[0] = PI::insert_knot<2>(faces[0], 0, 0.5);
  CHECK_THROWS_AS(PI::build_bspline_volume(bad), PI::Invalid_input_error);
}

TEST_CASE("twisted block from six point grids: faces exact on edges, certified valid", "[spline]")
{
  const Tensor_bspline_volume v = twisted_block(4, 1.0);
  // Close to the analytic twist everywhere on the boundary.
  double e = 0.;
  for(int i = 0; i <= 8; ++i)
    for(int j = 0; j <= 8; ++j) {
      e = std::max(e, (v.evaluate({i / 8., j / 8., 0.}) - twist(i / 8., j / 8., 0.)).norm());
      e = std::max(e, (v.evaluate({0., i / 8., j / 8.}) - twist(0., i / 8., j / 8.)).norm());
    }
  CHECK(e < 1e-3);
  const auto s = PI::sample_jacobian(v);
  const auto b = PI::certified_jacobian_bound(v);
  CHECK(s.min_determinant > 0.);
  CHECK(b.certified_positive);
  CHECK(b.lower_bound <= s.min_determinant);
  CHECK(b.upper_bound >= s.max_determinant);
  CHECK(s.min_scaled_jacobian > 0.5);
}

TEST_CASE("a folded volume is always caught by the certified bound", "[spline]")
{
  // A cubic cube with one interior control point pushed through the opposite face.
  Tensor_bspline_volume v = PI::refine_uniformly<3>(unit_cube(3), 2);
  v.control_point({2, 2, 2}) += Vec(0, 0, 4.);
  const auto b = PI::certified_jacobian_bound(v);
  const auto s = PI::sample_jacobian(v, 9);
  CHECK(s.min_determinant < 0.);
  CHECK(b.lower_bound < 0.);
  CHECK(!b.certified_positive);
  CHECK(b.has_nonpositive_value);
  CHECK(b.lower_bound <= s.min_determinant);
  // The bound says where to look: det J is negative there.
  for(double t : b.lower_bound_at) CHECK((t >= 0. && t <= 1.));
  const auto at = v.derivatives(b.lower_bound_at, 1);
  CHECK(at.first[0].dot(at.first[1].cross(at.first[2])) < 0.);
  // A fold between samples: sampling at span ends only can miss it; the bound cannot.
  Tensor_bspline_volume w = unit_cube(2);
  w.control_point({1, 1, 1}) = Vec(0.5, 0.5, 3.0); // dz/dw = 1 - 1.25 at the top centre
  const auto coarse = PI::sample_jacobian(w, 2);
  const auto fine = PI::sample_jacobian(w, 41);
  const auto bw = PI::certified_jacobian_bound(w);
  INFO("coarse " << coarse.min_determinant << " fine " << fine.min_determinant << " bound " << bw.lower_bound);
  CHECK(coarse.min_determinant > 0.);
  CHECK(fine.min_determinant < 0.);
  CHECK(bw.lower_bound < 0.);
  CHECK(bw.has_nonpositive_value);
  // Valid but with a bound needing subdivision: a mildly distorted cube.
  Tensor_bspline_volume m = unit_cube(2);
  m.control_point({1, 1, 1}) = Vec(0.5, 0.5, 1.2);
  const auto bm = PI::certified_jacobian_bound(m);
  const auto sm = PI::sample_jacobian(m, 21);
  CHECK(bm.lower_bound <= sm.min_determinant);
  CHECK(bm.upper_bound >= sm.max_determinant);
}

TEST_CASE("the Bernstein product behind the bound is the product of the polynomials, at any degree", "[spline]")
{
  namespace PII = PI::internal;
  // Value of a Bernstein polynomial by its definition, sum C(n,i) t^i (1-t)^(n-i) c_ijk.
  auto value = [](const PII::Bernstein3& f, const std::array<double, 3>& t) {
    double sum = 0.;
    for(int k = 0; k <= f.degree[2]; ++k)
      for(int j = 0; j <= f.degree[1]; ++j)
        for(int i = 0; i <= f.degree[0]; ++i) {
          double b = f(i, j, k);
          const std::array<int, 3> n{{i, j, k}};
          for(int d = 0; d < 3; ++d)
            b *= PII::binomial(f.degree[std::size_t(d)], n[std::size_t(d)]) * std::pow(t[std::size_t(d)], n[std::size_t(d)]) *
                 std::pow(1. - t[std::size_t(d)], f.degree[std::size_t(d)] - n[std::size_t(d)]);
          sum += b;
        }
    return sum;
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coefficient(-1., 1.);
  auto random = [&](const std::array<int, 3>& degree) {
    PII::Bernstein3 f(degree);
    for(double& c : f.c) c = coefficient(rng);
    return f;
  };
  // The det J of a cubic span (degrees up to 8), and degrees past the tabulated binomials (64).
  for(const auto& degrees : {std::array<std::array<int, 3>, 2>{{{{2, 3, 3}}, {{6, 5, 5}}}},
                             std::array<std::array<int, 3>, 2>{{{{40, 1, 0}}, {{30, 2, 1}}}}}) {
    const PII::Bernstein3 a = random(degrees[0]), b = random(degrees[1]);
    const PII::Bernstein3 ab = PII::multiply(a, b);
    for(int d = 0; d < 3; ++d) CHECK(ab.degree[std::size_t(d)] == a.degree[std::size_t(d)] + b.degree[std::size_t(d)]);
    for(const std::array<double, 3>& t : {std::array<double, 3>{{0.1, 0.5, 0.9}}, std::array<double, 3>{{0.73, 0.2, 0.35}},
                                          std::array<double, 3>{{0., 1., 0.5}}}) {
      const double expected = value(a, t) * value(b, t);
      INFO("degree " << ab.degree[0] << " at " << t[0] << " " << t[1] << " " << t[2]);
      CHECK(std::abs(value(ab, t) - expected) <= 1e-10 * std::max(1., std::abs(expected)));
    }
  }
  // The tabulated rows are the binomials themselves.
  std::vector<double> spare;
  const double* row = PII::binomial_row(8, spare);
  CHECK(row[0] == 1.);
  CHECK(row[3] == 56.);
  CHECK(row[8] == 1.);
  const double* high = PII::binomial_row(70, spare);
  CHECK(high[1] == 70.);
  CHECK(high[69] == 70.);
}

TEST_CASE("multipatch topology, direction maps, interface conformity", "[spline]")
{
  // Two cubes side by side; the second has its parametric directions permuted and reversed.
  const Tensor_bspline_volume a = PI::refine_uniformly<3>(unit_cube(2), 2);
  std::vector<Vec> P;
  const auto n = a.control_net_size();
  // b(u,v,w) = a-like cube shifted by +1 in x, with parameters (w, 1-u, v) -> x, y, z.
  for(int k = 0; k < n[2]; ++k)
    for(int j = 0; j < n[1]; ++j)
      for(int i = 0; i < n[0]; ++i) {
        const Vec q = a.control_point({n[0] - 1 - j, k, i}); // x from 1-v, y from w, z from u
        P.push_back(q + Vec(1, 0, 0));
      }
  const Tensor_bspline_volume b(a.knot_vectors(), P);
  PI::Multipatch_volume mp;
  mp.add_patch(a);
  mp.add_patch(b);
  mp.compute_topology();
  REQUIRE(mp.interfaces().size() == 1);
  CHECK(mp.boundaries().size() == 10);
  const auto& f = mp.interfaces()[0];
  CHECK(f.first.patch == 0);
  CHECK(f.first.side == 2);   // u1 of a (x = 1)
  CHECK(f.second.side == 4);  // v1 of b (x = 1 when 1-v = 0)
  const auto c = PI::check_interface_conformity(mp, 7);
  CHECK(c.conforming);
  CHECK(c.max_gap < 1e-14);
  // A wrong orientation is detected.
  PI::Multipatch_volume wrong;
  wrong.add_patch(a);
  wrong.add_patch(b);
  PI::Patch_interface g = f;
  g.direction_orientation[f.first.side == 2 ? 1 : 0] = !g.direction_orientation[f.first.side == 2 ? 1 : 0];
  wrong.add_interface(g);
  CHECK(!PI::check_interface_conformity(wrong).conforming);
  PI::Patch_interface h = f;
  h.direction_map = {0, 0, 1};
  CHECK_THROWS_AS(wrong.add_interface(h), PI::Invalid_input_error);
}

TEST_CASE("G+Smo XML round trip is bit for bit, VTU and JSON are written", "[spline]")
{
  PI::Multipatch_volume mp;
  mp.add_patch(PI::insert_knot<3>(twisted_block(3, 0.7), 0, 1. / 3. + 1e-3));
  Tensor_bspline_volume t = torus_sector();
  mp.add_patch(t);
  mp.compute_topology();
  std::ostringstream os;
  PI::IO::write_gismo_xml(os, mp);
  std::istringstream is(os.str());
  const PI::Multipatch_volume r = PI::IO::read_gismo_xml(is);
  REQUIRE(r.number_of_patches() == 2);
  for(std::size_t p = 0; p < 2; ++p) {
    for(int d = 0; d < 3; ++d) CHECK(r.patch(p).knot_vector(d) == mp.patch(p).knot_vector(d));
    CHECK(r.patch(p).control_points() == mp.patch(p).control_points());
    CHECK(r.patch(p).weights() == mp.patch(p).weights());
  }
  CHECK(r.boundaries().size() == mp.boundaries().size());
  std::ostringstream again;
  PI::IO::write_gismo_xml(again, r);
  CHECK(again.str() == os.str());
  CHECK(os.str().find("<Geometry type=\"TensorNurbs3\" id=\"1\">") != std::string::npos);

  // Files: atomic writes, readable back.
  const std::string xml = "test_spline_roundtrip.xml";
  PI::IO::write_gismo_xml(xml, mp);
  CHECK(PI::IO::read_gismo_xml(xml).patch(1).weights() == t.weights());
  std::ostringstream vtu, net, json;
  PI::IO::write_vtu(vtu, mp, 3);
  PI::IO::write_control_net_vtu(net, mp);
  PI::IO::write_json_summary(json, mp, PI::evaluate_quality(mp));
  CHECK(vtu.str().find("Name=\"jacobian\"") != std::string::npos);
  // 3 samples per span: 2 cells per span; patch 0 has 4 x 3 x 3 spans, the torus 1 x 1 x 1.
  CHECK(vtu.str().find("NumberOfCells=\"" + std::to_string(8 * 6 * 6 + 8) + "\"") != std::string::npos);
  CHECK(net.str().find("Name=\"weight\"") != std::string::npos);
  CHECK(json.str().find("\"certified_positive\":") != std::string::npos);
  std::remove(xml.c_str());

  // Malformed input: clear errors.
  auto read = [](const std::string& s) {
    std::istringstream in(s);
    return PI::IO::read_gismo_xml(in);
  };
  CHECK_THROWS_AS(read("<xml><Geometry type=\"TensorBSpline3\" id=\"0\"></xml>"), PI::Invalid_input_error);
  std::string broken = os.str();
  broken.replace(broken.find("degree=\""), 9, "degree=\"0");
  CHECK_THROWS_AS(read(broken), PI::Invalid_input_error);
  CHECK_THROWS_AS(PI::IO::read_gismo_xml(std::string("/nonexistent/file.xml")), PI::Invalid_input_error);
}

namespace {
using Cube_mesh = CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3>;

/// The unit cube [0,1]^3 as 12 outward-oriented triangles: the reference mesh of the
/// boundary distance tests.
Cube_mesh triangulated_unit_cube()
{
  using P = Cube_mesh::Point;
  Cube_mesh cube;
  CGAL::make_hexahedron(P(0, 0, 0), P(1, 0, 0), P(1, 1, 0), P(0, 1, 0), P(0, 1, 1), P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), cube);
  CGAL::Polygon_mesh_processing::triangulate_faces(cube);
  return cube;
}
} // namespace

TEST_CASE("two-sided Hausdorff distance to a triangle mesh", "[spline]")
{
  using Mesh = Cube_mesh;
  const Mesh cube = triangulated_unit_cube();
  PI::Multipatch_volume mp;
  mp.add_patch(unit_cube(3));
  const auto d = PI::boundary_hausdorff_distance(mp, cube, 16);
  CHECK(d.hausdorff < 1e-12);
  CHECK(d.boundary_sides == 6);
  Tensor_bspline_volume moved = unit_cube(1);
  for(auto& p : moved.control_points()) p.x() *= 1.1; // x in [0, 1.1]
  PI::Multipatch_volume mq;
  mq.add_patch(moved);
  const auto e = PI::boundary_hausdorff_distance(mq, cube, 16);
  CHECK(e.spline_to_mesh == Approx(0.1).epsilon(1e-9));
  CHECK(e.mesh_to_spline == Approx(0.1).epsilon(1e-9)); // mesh face x = 1 to spline face x = 1.1
  CHECK(e.relative == Approx(0.1 / std::sqrt(3.)).epsilon(1e-9));
  // A volume covering only x <= 0.5 loses the part x > 0.5: the farthest mesh point is on
  // the face x = 1 and the face it names touches it.
  Tensor_bspline_volume half = unit_cube(1);
  for(auto& p : half.control_points()) p.x() *= 0.5;
  PI::Multipatch_volume mh;
  mh.add_patch(half);
  const auto h = PI::boundary_hausdorff_distance(mh, cube, 16);
  CHECK(h.mesh_to_spline == Approx(0.5).epsilon(1e-9));
  CHECK(h.farthest_mesh_point[0] == Approx(1.));
  REQUIRE(h.farthest_mesh_face < num_faces(cube));
  bool touches = false;
  for(auto v : vertices_around_face(halfedge(Mesh::Face_index(std::uint32_t(h.farthest_mesh_face)), cube), cube))
    touches = touches || cube.point(v).x() == 1.;
  CHECK(touches);
  CHECK(h.farthest_spline_point[0] <= 0.5 + 1e-12);
}

TEST_CASE("boundary sides whose fitted face turns over are named", "[spline]")
{
  using Mesh = Cube_mesh;
  const Mesh cube = triangulated_unit_cube();
  PI::Multipatch_volume plain;
  plain.add_patch(unit_cube(3));
  CHECK(PI::boundary_hausdorff_distance(plain, cube, 16).folded_sides.empty());
  // Swap the two middle columns of the top side (z = 1) in x, past each other: the face
  // doubles back on itself in the middle (dx/du = -0.3 at u = 1/2), its normal points down
  // there, and it stays on the plane z = 1.
  Tensor_bspline_volume folded = unit_cube(3);
  for(int j = 0; j < 4; ++j) {
    folded.control_point({1, j, 3}).x() = 1.2;
    folded.control_point({2, j, 3}).x() = -0.2;
  }
  PI::Multipatch_volume mf;
  mf.add_patch(folded);
  const auto d = PI::boundary_hausdorff_distance(mf, cube, 16);
  CHECK(d.spline_to_mesh < 0.1);
  std::set<int> sides;
  for(const auto& f : d.folded_sides) {
    CHECK(f.side.patch == 0);
    CHECK(f.samples > 0);
    sides.insert(f.side.side);
  }
  CHECK(sides.count(6) == 1);
  CHECK(sides.count(1) == 0); // x = 0, x = 1 and the bottom are untouched
  CHECK(sides.count(2) == 0);
  CHECK(sides.count(5) == 0);
}

TEST_CASE("bad input gives Invalid_input_error, never a crash", "[spline]")
{
  const Knot_vector k = Knot_vector::uniform(2, 2);
  CHECK_THROWS_AS(Tensor_bspline_volume({k, k, k}, std::vector<Vec>(10)), PI::Invalid_input_error);
  std::vector<Vec> P(64, Vec::Zero());
  P[3] = Vec(std::nan(""), 0, 0);
  CHECK_THROWS_AS(Tensor_bspline_volume({k, k, k}, P), PI::Invalid_input_error);
  P[3] = Vec::Zero();
  CHECK_THROWS_AS(Tensor_bspline_volume({k, k, k}, P, std::vector<double>(64, -1.)), PI::Invalid_input_error);
  PI::Point_grid g(5, 5);
  for(int j = 0; j < 5; ++j)
    for(int i = 0; i < 5; ++i) g(i, j) = Vec(i, j, 0);
  PI::Point_grid wrong = g;
  wrong.points.pop_back();
  CHECK_THROWS_AS(PI::fit_bspline_surface(wrong), PI::Invalid_input_error);
  PI::Point_grid nan = g;
  nan(2, 2) = Vec(0, std::nan(""), 0);
  CHECK_THROWS_AS(PI::fit_bspline_surface(nan), PI::Invalid_input_error);
  PI::Surface_fitting_options o;
  o.bending_weight = 0.;
  CHECK_THROWS_AS(PI::fit_bspline_surface(g, o), PI::Invalid_input_error); // 5 points, 11 control points
  o.bending_weight = -1.;
  CHECK_THROWS_AS(PI::fit_bspline_surface(g, o), PI::Invalid_input_error);
  o = PI::Surface_fitting_options();
  o.spans_u = 0;
  CHECK_THROWS_AS(PI::fit_bspline_surface(g, o), PI::Invalid_input_error);
  o = PI::Surface_fitting_options();
  o.parameterization = PI::Parameterization::given;
  o.u_parameters = {0, 0.5, 0.25, 0.75, 1};
  o.v_parameters = {0, 0.25, 0.5, 0.75, 1};
  CHECK_THROWS_AS(PI::fit_bspline_surface(g, o), PI::Invalid_input_error);
  CHECK_THROWS_AS(PI::insert_knot<3>(unit_cube(2), 0, 1.5), PI::Invalid_input_error);
  CHECK_THROWS_AS(PI::insert_knot<3>(unit_cube(2), 0, 0.5, 3), PI::Invalid_input_error);
  CHECK_THROWS_AS(PI::side_surface(unit_cube(1), 7), PI::Invalid_input_error);
  // Fitting regularized by bending works on the same small grid (the plane is reproduced).
  o = PI::Surface_fitting_options();
  const auto r = PI::fit_bspline_surface(g, o);
  CHECK(r.max_error < 1e-6);
}
