// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Edge weights that steer the cutting cycles of the pants decomposition (reference §2.2.1.2):
// the cycles are traced with Dijkstra and min-cut on these weights, so a cheaper edge is one
// a cut prefers.
//
// Three criteria, for an edge e = (v_i, v_j) of length l(e) = |v_j - v_i|:
//
//   LENGTH       w(e) = l(e)
//   SYMMETRY     w(e) = l(e) * (eps + strength * 0.5 [d(v_i) + d(v_j)] / D),   eps = 0.01
//                d(v) = distance of v to the plane a x + b y + c z + d = 0, D = diagonal of
//                the bounding box of the vertices.
//   MINIMA_RULE  w(e) = l(e) * exp(clamp(strength * 0.5 [r(v_i) + r(v_j)], -3, 3))
//                r(v) = (kmin(v) - mu) / sigma, the normalised minimum principal curvature
//                (see normalized_minimum_curvature below).
//
// Why these deviate from the reference's raw weights omega_l = |v_j - v_i|^2,
// omega_s = 0.5 [d(v_i) + d(v_j)] and omega_m = 0.5 [r(v_i) + r(v_j)]:
//  - The weights are min-cut capacities and Dijkstra lengths, so they must be strictly
//    positive. omega_m is negative on concave regions (r < 0), which breaks Dijkstra (and
//    would make an arbitrarily long detour through a concave region "shorter"); omega_s is
//    zero on the plane, so any path wandering along the plane would cost nothing.
//  - Units: a path's cost should approximate an integral along the curve, independent of how
//    finely the mesh is tessellated. omega_s and omega_m are per-edge values (a path of many
//    short edges costs more than one of a few long edges over the same distance), and the
//    squared length omega_l favours many short edges over a straight run. Here each criterion
//    is a positive, dimensionless density multiplied by the edge length, so the cost of a
//    path is a weighted curve length. LENGTH uses the length itself (a geodesic surrogate).
//  - SYMMETRY: the density eps + strength * d / D is smallest (eps) on the plane and grows
//    linearly with the distance; eps > 0 keeps the weights positive and makes the cut still
//    measure length on the plane (among cuts on the plane, the shortest one wins). The
//    distance is divided by the bounding-box diagonal so the density is scale invariant.
//  - MINIMA_RULE: exp(strength * r) is positive, equals 1 for an average curvature, is < 1 on
//    concave regions (r < 0, the cuts the minima rule asks for) and > 1 on convex ones;
//    r is already dimensionless. The exponent is clamped to [-3, 3] (weights within a factor
//    e^6 of each other): on CAD meshes with sharp creases r reaches -20 and unclamped
//    weights spanning 1e9 would make cuts follow creases whatever their length.
//  - Every weight is at last raised to at least 1e-12 * D (or 1e-300 for a mesh of one
//    point), so a zero-length edge does not get a zero capacity.
//
// `strength` must be finite and >= 0; strength = 0 turns SYMMETRY and MINIMA_RULE into pure
// length (up to the constant factor eps for SYMMETRY).
//
// Curvature: CGAL::Monge_via_jet_fitting (degree-2 jet, degree-2 Monge form) fitted at every
// vertex to its 2-ring, grown ring by ring (up to the 6-ring) until it holds at least 10
// points. The fitted normal is oriented along the outward vertex normal (angle-weighted
// normal, flipped when the surface's capped signed volume is negative), and curvature is
// counted positive where the surface bends away from the outward normal (convex), so a
// sphere of radius R has kmin = kmax = 1/R and the inner equator of a torus has kmin < 0.
// kmin is the smaller principal curvature in that convention.
//
// Deterministic: no randomness, fixed traversal orders.
// Errors (Invalid_input_error): `non_finite_position`, `degenerate_symmetry_plane`,
// `invalid_cut_strength`, `bad_arguments` (parse_cut_criterion).

#ifndef CGAL_POLYCUBE_IGA_CUT_CRITERIA_H
#define CGAL_POLYCUBE_IGA_CUT_CRITERIA_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/internal/mesh_graph.h>

#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// Geometric criterion of the pants decomposition's cutting cycles (reference §2.2.1.2).
enum class Cut_criterion
{
  LENGTH,      ///< shortest cycles (default)
  SYMMETRY,    ///< cycles close to a user-given plane
  MINIMA_RULE  ///< cycles through concave regions (low minimum principal curvature)
};

/// \ingroup PkgPolycubeIGARef
struct Cut_criterion_options
{
  Cut_criterion criterion = Cut_criterion::LENGTH;
  std::array<double, 4> symmetry_plane{0, 0, 1, 0}; ///< a x + b y + c z + d = 0 (need not be normalised)
  double strength = 1.0; ///< how strongly the criterion bends cuts away from pure length (finite, >= 0)
};

/// "length" | "symmetry" | "minima"; anything else throws Invalid_input_error("bad_arguments").
inline Cut_criterion parse_cut_criterion(const std::string& name)
{
  if(name == "length") return Cut_criterion::LENGTH;
  if(name == "symmetry") return Cut_criterion::SYMMETRY;
  if(name == "minima") return Cut_criterion::MINIMA_RULE;
  throw Invalid_input_error("bad_arguments",
                            "unknown cut criterion '" + name + "' (expected length, symmetry or minima)");
}

/// The name parse_cut_criterion() accepts for `c`.
inline const char* cut_criterion_name(Cut_criterion c)
{
  switch(c) {
  case Cut_criterion::LENGTH: return "length";
  case Cut_criterion::SYMMETRY: return "symmetry";
  case Cut_criterion::MINIMA_RULE: return "minima";
  }
  return "length";
}

namespace internal {

template <class TriangleMesh>
void require_finite_positions(const Mesh_graph<TriangleMesh>& g)
{
  for(std::size_t v = 0; v < g.position.size(); ++v)
    if(!g.position[v].allFinite())
      throw Invalid_input_error("non_finite_position",
                                "vertex " + std::to_string(v) + " has a non-finite coordinate");
}

template <class TriangleMesh>
double bounding_box_diagonal(const Mesh_graph<TriangleMesh>& g)
{
  if(g.position.empty()) return 0;
  Eigen::Vector3d lo = g.position[0], hi = g.position[0];
  for(const auto& p : g.position) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
  return (hi - lo).norm();
}

/// Signed minimum principal curvature per vertex (positive = convex w.r.t. the outward
/// normal); NaN where no fit was possible (too few points, no normal, failed fit).
template <class TriangleMesh>
std::vector<double> minimum_principal_curvature(const Mesh_graph<TriangleMesh>& g)
{
  using K = CGAL::Simple_cartesian<double>;
  using Monge = CGAL::Monge_via_jet_fitting<K>;
  constexpr std::size_t d_fitting = 2, d_monge = 2, min_points = 10, max_rings = 6;
  constexpr std::size_t min_fit_points = (d_fitting + 1) * (d_fitting + 2) / 2;

  const int nv = g.number_of_vertices();
  const double orientation = g.capped_signed_volume() < 0 ? -1.0 : 1.0;
  const std::vector<Eigen::Vector3d> normals = g.vertex_normals();
  std::vector<double> kmin(nv, std::numeric_limits<double>::quiet_NaN());

  std::vector<int> mark(nv, -1), ring;
  std::vector<K::Point_3> pts;
  for(int v = 0; v < nv; ++v) {
    // Breadth-first rings around v; v itself first (the jet's origin).
    ring.assign(1, v);
    mark[v] = v;
    std::size_t begin = 0;
    for(std::size_t r = 0; r < max_rings; ++r) {
      const std::size_t end = ring.size();
      if(begin == end) break; // component exhausted
      for(std::size_t k = begin; k < end; ++k) {
        const int u = ring[k];
        for(int a = g.offset[u]; a < g.offset[u + 1]; ++a) {
          const int w = g.adjacent_vertex[a];
          if(mark[w] != v) { mark[w] = v; ring.push_back(w); }
        }
      }
      begin = end;
      if(r + 1 >= 2 && ring.size() >= min_points) break;
    }
    const Eigen::Vector3d n = orientation * normals[v];
    if(ring.size() < min_fit_points || n.squaredNorm() == 0) continue;
    pts.clear();
    for(int u : ring) pts.emplace_back(g.position[u].x(), g.position[u].y(), g.position[u].z());
    Monge fit;
    typename Monge::Monge_form form = fit(pts.begin(), pts.end(), d_fitting, d_monge);
    // CGAL's Monge form is z = (k1 x^2 + k2 y^2)/2 over (d1, d2, normal), k1 >= k2. Oriented
    // along the inward normal, a convex bump has z > 0 there, i.e. positive curvature.
    form.comply_wrt_given_normal(K::Vector_3(-n.x(), -n.y(), -n.z()));
    const double k = form.principal_curvatures(1);
    if(std::isfinite(k)) kmin[v] = k;
  }
  return kmin;
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// Per-vertex normalised minimum principal curvature r(v) = (kmin(v) - mu) / sigma
/// (reference §2.2.1.2), mu and sigma the mean and (population) standard deviation of kmin
/// over the vertices where the jet fit succeeded. kmin is signed w.r.t. the outward normal
/// (convex > 0); see the file comment for the fit. Vertices without a fit get r = 0 (the
/// average), and so does every vertex when sigma is 0 or not finite.
template <class TriangleMesh>
std::vector<double> normalized_minimum_curvature(const internal::Mesh_graph<TriangleMesh>& g)
{
  internal::require_finite_positions(g);
  std::vector<double> k = internal::minimum_principal_curvature(g);
  double sum = 0;
  std::size_t n = 0;
  for(double x : k) if(std::isfinite(x)) { sum += x; ++n; }
  std::vector<double> r(k.size(), 0.0);
  if(n == 0) return r;
  const double mean = sum / double(n);
  double var = 0;
  for(double x : k) if(std::isfinite(x)) var += (x - mean) * (x - mean);
  const double sigma = std::sqrt(var / double(n));
  if(!(sigma > 0) || !std::isfinite(sigma)) return r;
  for(std::size_t v = 0; v < k.size(); ++v)
    if(std::isfinite(k[v])) r[v] = (k[v] - mean) / sigma;
  return r;
}

/// \ingroup PkgPolycubeIGARef
/// Positive, finite weight of every edge of `g` (indexed like `g.edge_vertices`) under the
/// criterion `o`; formulas in the file comment.
template <class TriangleMesh>
std::vector<double> cut_edge_weights(const internal::Mesh_graph<TriangleMesh>& g, const Cut_criterion_options& o)
{
  internal::require_finite_positions(g);
  if(!std::isfinite(o.strength) || o.strength < 0)
    throw Invalid_input_error("invalid_cut_strength", "the cut criterion strength must be finite and non-negative");
  const int ne = g.number_of_edges();
  const double diagonal = internal::bounding_box_diagonal(g);
  const double floor = diagonal > 0 ? 1e-12 * diagonal : 1e-300;
  std::vector<double> w(ne);
  for(int e = 0; e < ne; ++e) w[e] = g.length(e);

  switch(o.criterion) {
  case Cut_criterion::LENGTH: break;
  case Cut_criterion::SYMMETRY: {
    const Eigen::Vector3d normal(o.symmetry_plane[0], o.symmetry_plane[1], o.symmetry_plane[2]);
    const double norm = normal.norm();
    if(!normal.allFinite() || !std::isfinite(o.symmetry_plane[3]) || !(norm > 0) || !std::isfinite(norm))
      throw Invalid_input_error("degenerate_symmetry_plane",
                                "the symmetry plane needs a finite offset and a finite, non-zero normal (a, b, c)");
    const double eps = 0.01, scale = diagonal > 0 ? diagonal : 1.0;
    std::vector<double> dist(g.position.size());
    for(std::size_t v = 0; v < g.position.size(); ++v)
      dist[v] = std::abs(normal.dot(g.position[v]) + o.symmetry_plane[3]) / norm;
    for(int e = 0; e < ne; ++e) {
      const double d = 0.5 * (dist[g.edge_vertices[e][0]] + dist[g.edge_vertices[e][1]]);
      w[e] *= eps + o.strength * d / scale;
    }
    break;
  }
  case Cut_criterion::MINIMA_RULE: {
    const std::vector<double> r = normalized_minimum_curvature(g);
    for(int e = 0; e < ne; ++e) {
      const double x = o.strength * 0.5 * (r[g.edge_vertices[e][0]] + r[g.edge_vertices[e][1]]);
      w[e] *= std::exp(std::clamp(x, -3.0, 3.0));
    }
    break;
  }
  }
  for(double& x : w) {
    if(!(x >= floor)) x = floor; // zero-length edges (and underflow)
    if(!std::isfinite(x)) x = std::numeric_limits<double>::max();
  }
  return w;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_CUT_CRITERIA_H
