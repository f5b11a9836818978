// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Untangling and improving a multipatch volume by moving its free control points: those not
// on a boundary side (the solid's surface and caps stay exactly where §4.1 fitted them).
// Coons interpolation plus Laplacian smoothing (§4.1) cannot guarantee det J > 0 once the
// cuboids are curved; like the Jacobian-constrained parameterizations of the IGA literature
// (Xu et al. 2013), this minimises a distortion energy of the Jacobian at Gauss points of
// every span. The energy is the regularised one of Garanzha et al., "Foldover-free maps in
// 50 lines of code" (2021): with K = J W^-1 (W the patch's mean Jacobian, so a thin slab
// is measured against a thin reference), D = det K and chi(D, e) = (D + sqrt(e^2 + D^2)) / 2,
//   f = (1 - theta) |K|^2 / (3 chi^(2/3)) + theta (D^2 + 1) / (2 chi),
// finite for inverted samples, so L-BFGS can pull them through; e shrinks round by round by
// their rule until every sample is positive, and the energy then acts as a barrier.
// Control points shared across interfaces are one unknown, so conformity is kept exactly.

#ifndef CGAL_POLYCUBE_IGA_VOLUME_UNTANGLING_H
#define CGAL_POLYCUBE_IGA_VOLUME_UNTANGLING_H

#include <CGAL/Polycube_IGA/Bspline_basis.h>
#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/internal/lbfgs.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Options of untangle_volume().
struct Volume_untangling_options
{
  int points_per_span = 3; ///< Gauss-Lobatto points per span and direction, ends included (2..4)
  double volume_weight = 0.25; ///< theta: weight of the volume term against the shape term
  /// Patches with a sampled scaled Jacobian below this (at Gauss points and span corners)
  /// are optimised, together with their interface neighbours.
  double scaled_jacobian_threshold = 0.05;
  /// Cost guard: with more patches to optimise than this, nothing is done (`skipped`).
  /// Each L-BFGS iteration costs about (2 spans + 1)^3 samples x (p + 1)^3 per patch:
  /// about 8 s for the 7 patches of the sphere at the default grid, 74 s for 25.
  std::size_t maximum_patches = 12;
  int maximum_rounds = 12;          ///< epsilon updates
  int iterations_per_round = 100;   ///< L-BFGS iterations per round
};

/// What untangle_volume() did.
struct Volume_untangling_result
{
  std::vector<std::size_t> patches; ///< patches whose samples entered the energy
  std::size_t free_points = 0;      ///< control points moved (shared ones counted once)
  int rounds = 0, iterations = 0;
  /// Smallest det(J W^-1) over the samples of those patches, before and after.
  double min_relative_determinant_before = 0., min_relative_determinant_after = 0.;
  bool positive_at_samples = false; ///< every sample has det J > 0 afterwards
  bool skipped = false; ///< more patches needed it than Volume_untangling_options::maximum_patches
};

namespace internal {

/// Basis values and first derivatives of one direction at a list of parameters.
struct Direction_samples
{
  int p = 0;
  std::vector<double> weight;
  std::vector<int> first;          // index of the first non-zero basis function
  std::vector<double> value, slope; // (p + 1) per sample
};

inline Direction_samples direction_samples(const Knot_vector& kv, const std::vector<double>& t, const std::vector<double>& w)
{
  Direction_samples s;
  s.p = kv.degree();
  const int P = s.p + 1;
  std::vector<double> ders(std::size_t(2 * P));
  for(std::size_t i = 0; i < t.size(); ++i) {
    const int span = kv.find_span(t[i]);
    basis_function_derivatives(kv, span, t[i], 1, ders.data());
    s.weight.push_back(w[i]);
    s.first.push_back(span - s.p);
    for(int j = 0; j < P; ++j) s.value.push_back(ders[std::size_t(j)]), s.slope.push_back(ders[std::size_t(P + j)]);
  }
  return s;
}

/// Samples of one direction: Gauss-Lobatto points of every span (its ends and q - 2 inner
/// points; weights sum to the span lengths). The ends matter: det J is often smallest on
/// the boundary sides and at span joints.
inline Direction_samples span_samples_with_ends(const Knot_vector& kv, int q)
{
  q = std::min(std::max(q, 2), 4);
  const double a = std::sqrt(0.2);
  const std::vector<double> gx = q == 2 ? std::vector<double>{-1., 1.} : q == 3 ? std::vector<double>{-1., 0., 1.} : std::vector<double>{-1., -a, a, 1.};
  const std::vector<double> gw = q == 2 ? std::vector<double>{1., 1.} : q == 3 ? std::vector<double>{1. / 3., 4. / 3., 1. / 3.} : std::vector<double>{1. / 6., 5. / 6., 5. / 6., 1. / 6.};
  std::vector<double> t, w;
  const std::vector<double> b = kv.breaks();
  for(std::size_t s = 0; s + 1 < b.size(); ++s) {
    const double mid = 0.5 * (b[s] + b[s + 1]), half = 0.5 * (b[s + 1] - b[s]);
    if(!(half > 0.)) continue;
    for(std::size_t k = 0; k < gx.size(); ++k) {
      if(k == 0 && !t.empty()) { w.back() += half * gw[k]; continue; } // shared span end
      t.push_back(k + 1 == gx.size() ? b[s + 1] : k == 0 ? b[s] : mid + half * gx[k]);
      w.push_back(half * gw[k]);
    }
  }
  return direction_samples(kv, t, w);
}

/// Calls f(J, weight, first index, basis gradients) at every sample of patch v, where the
/// gradients are listed for the (p0+1)(p1+1)(p2+1) non-zero functions, u fastest.
template <class F>
void for_each_jacobian_sample(const Tensor_bspline_volume& v, const std::array<Direction_samples, 3>& S,
                              const std::vector<Eigen::Vector3d>& points, F&& f)
{
  const int P0 = S[0].p + 1, P1 = S[1].p + 1, P2 = S[2].p + 1;
  const int n0 = v.number_of_control_points(0), n1 = v.number_of_control_points(1);
  std::vector<Eigen::Vector3d> grad(std::size_t(P0 * P1 * P2));
  std::vector<std::size_t> index(grad.size());
  for(std::size_t c = 0; c < S[2].weight.size(); ++c)
    for(std::size_t b = 0; b < S[1].weight.size(); ++b)
      for(std::size_t a = 0; a < S[0].weight.size(); ++a) {
        Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
        std::size_t l = 0;
        for(int k = 0; k < P2; ++k)
          for(int j = 0; j < P1; ++j)
            for(int i = 0; i < P0; ++i, ++l) {
              const double Nu = S[0].value[a * std::size_t(P0) + std::size_t(i)], Du = S[0].slope[a * std::size_t(P0) + std::size_t(i)];
              const double Nv = S[1].value[b * std::size_t(P1) + std::size_t(j)], Dv = S[1].slope[b * std::size_t(P1) + std::size_t(j)];
              const double Nw = S[2].value[c * std::size_t(P2) + std::size_t(k)], Dw = S[2].slope[c * std::size_t(P2) + std::size_t(k)];
              grad[l] = Eigen::Vector3d(Du * Nv * Nw, Nu * Dv * Nw, Nu * Nv * Dw);
              index[l] = std::size_t(S[0].first[a] + i) +
                         std::size_t(n0) * (std::size_t(S[1].first[b] + j) + std::size_t(n1) * std::size_t(S[2].first[c] + k));
              J += points[index[l]] * grad[l].transpose();
            }
        f(J, S[0].weight[a] * S[1].weight[b] * S[2].weight[c], index, grad);
      }
}

/// chi(D, e) = (D + sqrt(e^2 + D^2)) / 2, written without cancellation for D < 0.
inline double regularised_determinant(double D, double e)
{
  const double root = std::sqrt(e * e + D * D);
  return D >= 0. ? 0.5 * (D + root) : 0.5 * e * e / (root - D);
}

/// Columns of the cofactor matrix of K: the derivative of det K with respect to K.
inline Eigen::Matrix3d cofactor(const Eigen::Matrix3d& K)
{
  Eigen::Matrix3d C;
  C.col(0) = K.col(1).cross(K.col(2));
  C.col(1) = K.col(2).cross(K.col(0));
  C.col(2) = K.col(0).cross(K.col(1));
  return C;
}

/// Minimum scaled Jacobian of v at its Gauss points and span corners.
inline double sampled_scaled_jacobian(const Tensor_bspline_volume& v, const std::array<Direction_samples, 3>& samples)
{
  double m = std::numeric_limits<double>::infinity();
  auto scaled = [&](const Eigen::Matrix3d& J, double, const std::vector<std::size_t>&, const std::vector<Eigen::Vector3d>&) {
    const double len = J.col(0).norm() * J.col(1).norm() * J.col(2).norm();
    m = std::min(m, len > 0. ? J.determinant() / len : -1.);
  };
  for_each_jacobian_sample(v, samples, v.control_points(), scaled);
  std::array<Direction_samples, 3> corners;
  for(int d = 0; d < 3; ++d) {
    const std::vector<double> b = v.knot_vector(d).breaks();
    corners[std::size_t(d)] = direction_samples(v.knot_vector(d), b, std::vector<double>(b.size(), 1.));
  }
  for_each_jacobian_sample(v, corners, v.control_points(), scaled);
  return m;
}

/// Control points of one patch lying on side s.
template <class F>
void for_each_side_point(const Tensor_bspline_volume& v, int s, F&& f)
{
  const int d = side_direction(s);
  std::array<int, 3> n{{v.number_of_control_points(0), v.number_of_control_points(1), v.number_of_control_points(2)}};
  std::array<int, 3> i{};
  i[std::size_t(d)] = side_parameter(s) ? n[std::size_t(d)] - 1 : 0;
  const int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
  for(i[std::size_t(d2)] = 0; i[std::size_t(d2)] < n[std::size_t(d2)]; ++i[std::size_t(d2)])
    for(i[std::size_t(d1)] = 0; i[std::size_t(d1)] < n[std::size_t(d1)]; ++i[std::size_t(d1)]) f(i);
}

} // namespace internal

/*!
 * \ingroup PkgPolycubeIGARef
 * Moves the free control points of the patches of `mv` whose sampled scaled Jacobian is
 * below `o.scaled_jacobian_threshold`, and of their interface neighbours, to minimise the
 * regularised distortion energy described at the top of this file. Points on boundary
 * sides, points of other patches and rational patches stay fixed; a point shared by an
 * interface moves on both sides at once, so interfaces stay conforming. Returns what was
 * done; `mv` is left unchanged if no patch is below the threshold, if more than
 * `o.maximum_patches` would be optimised (`skipped`), or if the smallest sampled det J does
 * not improve. Deterministic.
 */
inline Volume_untangling_result untangle_volume(Multipatch_volume& mv,
                                                const Volume_untangling_options& o = Volume_untangling_options())
{
  using Eigen::Vector3d;
  Volume_untangling_result r;
  const std::size_t np = mv.number_of_patches();
  std::vector<std::array<internal::Direction_samples, 3>> samples(np);
  std::vector<bool> active(np, false);
  bool any = false;
  for(std::size_t c = 0; c < np; ++c) {
    const Tensor_bspline_volume& v = mv.patch(c);
    for(int d = 0; d < 3; ++d) samples[c][std::size_t(d)] = internal::span_samples_with_ends(v.knot_vector(d), o.points_per_span);
    if(!v.is_rational() && internal::sampled_scaled_jacobian(v, samples[c]) < o.scaled_jacobian_threshold) active[c] = any = true;
  }
  if(!any) {
    r.positive_at_samples = true;
    return r;
  }
  std::vector<bool> seed = active;
  for(const Patch_interface& I : mv.interfaces())
    if(seed[I.first.patch] || seed[I.second.patch]) active[I.first.patch] = active[I.second.patch] = true;
  for(std::size_t c = 0; c < np; ++c)
    if(mv.patch(c).is_rational()) active[c] = false;
  if(std::size_t(std::count(active.begin(), active.end(), true)) > o.maximum_patches) {
    for(std::size_t c = 0; c < np; ++c)
      if(active[c]) r.patches.push_back(c);
    r.skipped = true;
    return r;
  }

  // Control points as classes of a union-find over (patch, linear index); a class is fixed
  // if any member lies on a boundary side or in a patch that is not optimised.
  std::vector<std::size_t> offset(np + 1, 0);
  for(std::size_t c = 0; c < np; ++c) offset[c + 1] = offset[c] + mv.patch(c).number_of_control_points();
  std::vector<std::size_t> parent(offset[np]);
  std::iota(parent.begin(), parent.end(), std::size_t(0));
  auto find = [&](std::size_t a) {
    while(parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<bool> fixed(offset[np], false);
  auto linear = [&](std::size_t c, const std::array<int, 3>& i) { return offset[c] + mv.patch(c).linear_index(i); };
  for(const Patch_interface& I : mv.interfaces()) {
    const Tensor_bspline_volume &a = mv.patch(I.first.patch), &b = mv.patch(I.second.patch);
    bool same = true;
    for(int d = 0; d < 3; ++d)
      if(d != side_direction(I.first.side))
        same = same && a.number_of_control_points(d) == b.number_of_control_points(I.direction_map[std::size_t(d)]);
    internal::for_each_side_point(a, I.first.side, [&](const std::array<int, 3>& i) {
      if(!same) {
        fixed[linear(I.first.patch, i)] = true;
        return;
      }
      std::array<double, 3> s{};
      for(int d = 0; d < 3; ++d) s[std::size_t(d)] = double(i[std::size_t(d)]) / double(std::max(1, a.number_of_control_points(d) - 1));
      const std::array<double, 3> t = I.map_normalized(s);
      std::array<int, 3> j{};
      for(int d = 0; d < 3; ++d)
        j[std::size_t(d)] = int(std::lround(t[std::size_t(d)] * double(std::max(1, b.number_of_control_points(d) - 1))));
      parent[find(linear(I.first.patch, i))] = find(linear(I.second.patch, j));
    });
    if(!same)
      internal::for_each_side_point(b, I.second.side, [&](const std::array<int, 3>& j) { fixed[linear(I.second.patch, j)] = true; });
  }
  for(const Patch_side& s : mv.boundaries())
    internal::for_each_side_point(mv.patch(s.patch), s.side, [&](const std::array<int, 3>& i) { fixed[linear(s.patch, i)] = true; });
  for(std::size_t c = 0; c < np; ++c)
    if(!active[c])
      for(std::size_t k = offset[c]; k < offset[c + 1]; ++k) fixed[k] = true;
  for(std::size_t k = 0; k < fixed.size(); ++k)
    if(fixed[k]) fixed[find(k)] = true;

  // Unknowns: one per free class, numbered in first-member order (deterministic).
  std::vector<long> unknown_of_root(offset[np], -1), unknown(offset[np], -1);
  Eigen::VectorXd x;
  std::vector<Vector3d> start;
  for(std::size_t k = 0; k < offset[np]; ++k) {
    const std::size_t root = find(k);
    if(fixed[root]) continue;
    if(unknown_of_root[root] < 0) {
      unknown_of_root[root] = long(start.size());
      std::size_t c = std::size_t(std::upper_bound(offset.begin(), offset.end(), k) - offset.begin()) - 1;
      start.push_back(mv.patch(c).control_points()[k - offset[c]]);
    }
    unknown[k] = unknown_of_root[root];
  }
  r.free_points = start.size();
  for(std::size_t c = 0; c < np; ++c)
    if(active[c]) r.patches.push_back(c);

  // Per patch: the reference W (mean Jacobian over the unit cube of parameters) and W^-1.
  std::vector<Eigen::Matrix3d> Winv(np, Eigen::Matrix3d::Identity());
  for(std::size_t c : r.patches) {
    Eigen::Matrix3d W = Eigen::Matrix3d::Zero();
    double total = 0.;
    internal::for_each_jacobian_sample(mv.patch(c), samples[c], mv.patch(c).control_points(),
                                       [&](const Eigen::Matrix3d& J, double w, const std::vector<std::size_t>&,
                                           const std::vector<Vector3d>&) { W += w * J, total += w; });
    W /= std::max(total, 1e-300);
    const double scale = std::max(W.norm() / std::sqrt(3.), 1e-300);
    if(!(W.determinant() > 1e-3 * scale * scale * scale)) W = scale * Eigen::Matrix3d::Identity();
    Winv[c] = W.inverse();
  }

  x.resize(Eigen::Index(3 * start.size()));
  for(std::size_t k = 0; k < start.size(); ++k) x.segment<3>(Eigen::Index(3 * k)) = start[k];
  std::vector<std::vector<Vector3d>> points(np);
  for(std::size_t c : r.patches) points[c] = mv.patch(c).control_points();
  auto load = [&](const Eigen::VectorXd& y) {
    for(std::size_t c : r.patches)
      for(std::size_t k = 0; k < points[c].size(); ++k) {
        const long u = unknown[offset[c] + k];
        if(u >= 0) points[c][k] = y.segment<3>(Eigen::Index(3 * u));
      }
  };
  double min_det = 0.;
  auto measure_min = [&](const Eigen::VectorXd& y) {
    load(y);
    double m = std::numeric_limits<double>::infinity();
    for(std::size_t c : r.patches)
      internal::for_each_jacobian_sample(mv.patch(c), samples[c], points[c],
                                         [&](const Eigen::Matrix3d& J, double, const std::vector<std::size_t>&,
                                             const std::vector<Vector3d>&) { m = std::min(m, (J * Winv[c]).determinant()); });
    return m;
  };
  const double theta = o.volume_weight;
  double eps = 1.;
  auto energy = [&](const Eigen::VectorXd& y, Eigen::VectorXd& g) {
    load(y);
    g.setZero(y.size());
    double E = 0.;
    for(std::size_t c : r.patches) {
      const std::size_t base = offset[c];
      const Eigen::Matrix3d& Wi = Winv[c];
      internal::for_each_jacobian_sample(
        mv.patch(c), samples[c], points[c],
        [&](const Eigen::Matrix3d& J, double w, const std::vector<std::size_t>& index, const std::vector<Vector3d>& grad) {
          const Eigen::Matrix3d K = J * Wi;
          const double D = K.determinant(), root = std::sqrt(eps * eps + D * D), chi = internal::regularised_determinant(D, eps);
          const double dchi = chi / root, tr = K.squaredNorm(), c23 = std::cbrt(chi * chi);
          const double shape = tr / (3. * c23), volume = (D * D + 1.) / (2. * chi);
          E += w * ((1. - theta) * shape + theta * volume);
          const Eigen::Matrix3d C = internal::cofactor(K);
          const Eigen::Matrix3d GK = (1. - theta) * (2. / (3. * c23) * K - (2. / 9.) * tr / (c23 * chi) * dchi * C) +
                                     theta * (D / chi - (D * D + 1.) * dchi / (2. * chi * chi)) * C;
          const Eigen::Matrix3d GJ = w * GK * Wi.transpose();
          for(std::size_t l = 0; l < index.size(); ++l) {
            const long u = unknown[base + index[l]];
            if(u >= 0) g.segment<3>(Eigen::Index(3 * u)) += GJ * grad[l];
          }
        });
    }
    return E;
  };

  r.min_relative_determinant_before = min_det = measure_min(x);
  internal::Lbfgs_options lo;
  lo.maximum_iterations = o.iterations_per_round;
  if(!start.empty()) {
    eps = min_det > 0. ? 1e-9 : std::max(1e-6, std::min(1., 2. * std::abs(min_det)));
    Eigen::VectorXd g;
    double E_prev = energy(x, g);
    for(int round = 0; round < o.maximum_rounds; ++round) {
      const internal::Lbfgs_result lr = internal::lbfgs_minimize(energy, x, lo);
      ++r.rounds;
      r.iterations += lr.iterations;
      min_det = measure_min(x);
      const double E = lr.value;
      const double sigma = std::max(1. - E / E_prev, 0.1);
      const double chi_min = internal::regularised_determinant(min_det, eps);
      const double mu = (1. - sigma) * chi_min;
      const bool settled = std::abs(E_prev - E) <= 1e-5 * std::abs(E);
      eps = min_det < mu ? 2. * std::sqrt(mu * (mu - min_det)) : 1e-9;
      E_prev = energy(x, g); // with the new epsilon
      if(min_det > 0. && settled) break;
    }
  }
  r.min_relative_determinant_after = min_det = measure_min(x);
  if(!(min_det > r.min_relative_determinant_before)) { // no better: keep the construction
    for(std::size_t k = 0; k < start.size(); ++k) x.segment<3>(Eigen::Index(3 * k)) = start[k];
    r.min_relative_determinant_after = min_det = r.min_relative_determinant_before;
  }
  r.positive_at_samples = min_det > 0.;
  load(x);
  for(std::size_t c : r.patches) mv.patch(c).control_points() = points[c];
  return r;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_VOLUME_UNTANGLING_H
