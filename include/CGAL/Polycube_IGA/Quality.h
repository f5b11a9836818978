// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Quality measures of trivariate patches and multipatch models (reference §4.1; the
// validity test follows the Bernstein sufficient condition for injectivity discussed by
// Xu et al. 2013): sampled Jacobian determinant and scaled Jacobian on a grid per knot span,
// a certified lower bound of det J per patch, and interface conformity. det J is a
// polynomial on each knot span: after Bezier extraction, the derivative nets give X_u, X_v,
// X_w in Bernstein form, their triple product is formed exactly in the Bernstein basis of
// degree (3p-1, 3q-1, 3r-1) (NURBS: the numerator of det J over w^6), and its smallest
// coefficient bounds det J from below. Where that bound is not positive while the exact
// corner values are, the span is subdivided (de Casteljau) up to a depth limit.

#ifndef CGAL_POLYCUBE_IGA_QUALITY_H
#define CGAL_POLYCUBE_IGA_QUALITY_H

#include <CGAL/Polycube_IGA/Bspline_refinement.h>
#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/internal/bernstein.h>
#include <CGAL/Polycube_IGA/internal/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Jacobian figures sampled on a grid of `samples_per_span` points per knot span and direction.
struct Jacobian_sampling
{
  double min_determinant = std::numeric_limits<double>::infinity();
  double max_determinant = -std::numeric_limits<double>::infinity();
  /// det J / (|X_u| |X_v| |X_w|), in [-1, 1]; 1 for orthogonal parameter lines.
  double min_scaled_jacobian = std::numeric_limits<double>::infinity();
  double mean_scaled_jacobian = 0.;
  std::size_t samples = 0;
  std::size_t nonpositive_samples = 0;
};

/// A certified enclosure of det J over a whole patch.
struct Jacobian_bound
{
  double lower_bound = std::numeric_limits<double>::infinity(); ///< det J >= lower_bound everywhere (certified)
  double upper_bound = -std::numeric_limits<double>::infinity(); ///< det J <= upper_bound everywhere (certified)
  /// Smallest exact value met (corner values of the boxes): the true minimum is <= this.
  double smallest_value_found = std::numeric_limits<double>::infinity();
  bool certified_positive = false;      ///< lower_bound > 0: the patch is a valid (injective) parameterization
  bool has_nonpositive_value = false;   ///< a point with det J <= 0 was found: certainly invalid
  /// Parameters (u, v, w) near which det J is smallest: where the box giving lower_bound has
  /// its smallest Bernstein coefficient, where to look first when a patch
  /// is not certified positive (build_trivariate_model() names it in its warning).
  std::array<double, 3> lower_bound_at{{0., 0., 0.}};
  std::size_t boxes = 0;                ///< Bernstein boxes examined (spans and sub-boxes)
  int depth_reached = 0;
};

struct Jacobian_bound_options
{
  int maximum_depth = 6;              ///< subdivision levels per inconclusive span
  std::size_t maximum_boxes = 200000; ///< overall budget per patch
};

/// Options giving the same bounds.
inline bool operator==(const Jacobian_bound_options& a, const Jacobian_bound_options& b)
{
  return a.maximum_depth == b.maximum_depth && a.maximum_boxes == b.maximum_boxes;
}

namespace internal {

/// Sample values over [first, last]: `n` per knot span, span ends shared.
inline std::vector<double> span_samples(const Knot_vector& kv, int n)
{
  const std::vector<double> b = kv.breaks();
  std::vector<double> t;
  n = std::max(n, 2);
  for(std::size_t s = 0; s + 1 < b.size(); ++s)
    for(int i = (s == 0 ? 0 : 1); i < n; ++i)
      t.push_back(i == n - 1 ? b[s + 1] : b[s] + (b[s + 1] - b[s]) * double(i) / double(n - 1));
  return t;
}

inline void accumulate(Jacobian_bound& into, const Jacobian_bound& b)
{
  if(b.lower_bound < into.lower_bound) into.lower_bound_at = b.lower_bound_at;
  into.lower_bound = std::min(into.lower_bound, b.lower_bound);
  into.upper_bound = std::max(into.upper_bound, b.upper_bound);
  into.smallest_value_found = std::min(into.smallest_value_found, b.smallest_value_found);
  into.boxes += b.boxes;
  into.depth_reached = std::max(into.depth_reached, b.depth_reached);
}

} // namespace internal

/// det J and scaled Jacobian at `samples_per_span` points per knot span and direction.
inline Jacobian_sampling sample_jacobian(const Tensor_bspline_volume& v, int samples_per_span = 5)
{
  Jacobian_sampling r;
  const std::array<std::vector<double>, 3> t{{internal::span_samples(v.knot_vector(0), samples_per_span),
                                              internal::span_samples(v.knot_vector(1), samples_per_span),
                                              internal::span_samples(v.knot_vector(2), samples_per_span)}};
  double sum = 0.;
  for(double w : t[2])
    for(double vv : t[1])
      for(double u : t[0]) {
        const auto d = v.derivatives({u, vv, w}, 1);
        const double det = d.first[0].dot(d.first[1].cross(d.first[2]));
        const double len = d.first[0].norm() * d.first[1].norm() * d.first[2].norm();
        const double sj = len > 0. ? det / len : 0.;
        r.min_determinant = std::min(r.min_determinant, det);
        r.max_determinant = std::max(r.max_determinant, det);
        r.min_scaled_jacobian = std::min(r.min_scaled_jacobian, sj);
        sum += sj;
        ++r.samples;
        if(!(det > 0.)) ++r.nonpositive_samples;
      }
  r.mean_scaled_jacobian = r.samples ? sum / double(r.samples) : 0.;
  return r;
}

/// Certified lower (and upper) bound of det J over the patch.
inline Jacobian_bound certified_jacobian_bound(const Tensor_bspline_volume& v,
                                               const Jacobian_bound_options& o = Jacobian_bound_options())
{
  using namespace internal;
  const Tensor_bspline_volume bez = to_bezier_form<3>(v);
  const std::array<int, 3> p{{v.degree(0), v.degree(1), v.degree(2)}};
  std::array<std::vector<double>, 3> br;
  for(int d = 0; d < 3; ++d) br[std::size_t(d)] = v.knot_vector(d).breaks();
  const bool rational = v.is_rational();
  const std::vector<Eigen::Vector4d> H = bez.homogeneous_control_points();
  Jacobian_bound total;
  for(std::size_t sk = 0; sk + 1 < br[2].size(); ++sk)
    for(std::size_t sj = 0; sj + 1 < br[1].size(); ++sj)
      for(std::size_t si = 0; si + 1 < br[0].size(); ++si) {
        const std::array<std::size_t, 3> s{{si, sj, sk}};
        std::array<double, 3> h;
        for(int d = 0; d < 3; ++d) h[std::size_t(d)] = br[std::size_t(d)][s[std::size_t(d)] + 1] - br[std::size_t(d)][s[std::size_t(d)]];
        // Bezier net of the span: homogeneous components, degree p.
        std::array<Bernstein3, 4> X;
        for(auto& x : X) x = Bernstein3(p);
        for(int k = 0; k <= p[2]; ++k)
          for(int j = 0; j <= p[1]; ++j)
            for(int i = 0; i <= p[0]; ++i) {
              const std::array<int, 3> g{{int(si) * p[0] + i, int(sj) * p[1] + j, int(sk) * p[2] + k}};
              const Eigen::Vector4d& q = H[bez.linear_index(g)];
              for(int c = 0; c < 4; ++c) X[std::size_t(c)](i, j, k) = q[c];
            }
        // Columns of the Jacobian (numerators w X_d - w_d X for NURBS).
        std::array<std::array<Bernstein3, 3>, 3> col;
        for(int d = 0; d < 3; ++d)
          for(int c = 0; c < 3; ++c) {
            const Bernstein3 Xd = derivative(X[std::size_t(c)], d, h[std::size_t(d)]);
            if(!rational) col[std::size_t(d)][std::size_t(c)] = Xd;
            else
              col[std::size_t(d)][std::size_t(c)] =
                add(multiply(X[3], Xd), multiply(derivative(X[3], d, h[std::size_t(d)]), X[std::size_t(c)]), -1.);
          }
        // det = col_u . (col_v x col_w)
        Bernstein3 det;
        for(int c = 0; c < 3; ++c) {
          const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
          const Bernstein3 cross = add(multiply(col[1][std::size_t(c1)], col[2][std::size_t(c2)]),
                                       multiply(col[1][std::size_t(c2)], col[2][std::size_t(c1)]), -1.);
          const Bernstein3 term = multiply(col[0][std::size_t(c)], cross);
          det = c == 0 ? term : add(det, term);
        }
        double wmin = 1., wmax = 1.;
        if(rational) {
          wmin = X[3].min_coefficient();
          wmax = X[3].max_coefficient();
        }
        auto lower = [&](double m) { return m >= 0. ? m / std::pow(wmax, 6) : m / std::pow(wmin, 6); };
        auto upper = [&](double m) { return m >= 0. ? m / std::pow(wmin, 6) : m / std::pow(wmax, 6); };
        // Subdivide where the coefficients straddle zero but every exact value met is positive.
        Jacobian_bound b;
        // Boxes: the polynomial on [lo, lo + size]^3 of the span's unit box, and their depth.
        struct Box
        {
          Bernstein3 f;
          int depth;
          std::array<double, 3> lo;
          double size;
        };
        std::vector<Box> stack{{det, 0, {{0., 0., 0.}}, 1.}};
        while(!stack.empty()) {
          Box box = std::move(stack.back());
          stack.pop_back();
          const Bernstein3& f = box.f;
          const int depth = box.depth;
          ++b.boxes;
          b.depth_reached = std::max(b.depth_reached, depth);
          const double mn = f.min_coefficient(), corner = f.min_corner_value();
          b.smallest_value_found = std::min(b.smallest_value_found, rational ? lower(corner) : corner);
          if(mn <= 0. && corner > 0. && depth < o.maximum_depth && total.boxes + b.boxes + stack.size() < o.maximum_boxes) {
            // Octant k of the box has bit d of k set where it is the upper half in direction d.
            std::vector<Bernstein3> parts{f};
            for(int d = 0; d < 3; ++d) {
              std::vector<Bernstein3> next;
              for(const auto& g : parts) {
                auto lr = split_half(g, d);
                next.push_back(std::move(lr.first));
                next.push_back(std::move(lr.second));
              }
              parts.swap(next);
            }
            const double half = 0.5 * box.size;
            for(std::size_t k = 0; k < parts.size(); ++k) {
              std::array<double, 3> lo = box.lo;
              for(int d = 0; d < 3; ++d)
                if((k >> (2 - d)) & 1u) lo[std::size_t(d)] += half;
              stack.push_back({std::move(parts[k]), depth + 1, lo, half});
            }
            continue;
          }
          if(lower(mn) < b.lower_bound) {
            const std::array<double, 3> t = f.min_coefficient_point();
            for(int d = 0; d < 3; ++d)
              b.lower_bound_at[std::size_t(d)] =
                br[std::size_t(d)][s[std::size_t(d)]] + (box.lo[std::size_t(d)] + box.size * t[std::size_t(d)]) * h[std::size_t(d)];
          }
          b.lower_bound = std::min(b.lower_bound, lower(mn));
          b.upper_bound = std::max(b.upper_bound, upper(f.max_coefficient()));
        }
        accumulate(total, b);
      }
  total.certified_positive = total.lower_bound > 0.;
  total.has_nonpositive_value = total.smallest_value_found <= 0.;
  return total;
}

/// Gaps between the two sides of each interface, sampled at `samples_per_span` points per
/// knot span of the first side, at parameters related by the interface's direction map.
struct Interface_conformity
{
  std::vector<double> gaps;  ///< largest sampled gap per interface
  double max_gap = 0.;
  double tolerance = 0.;     ///< absolute tolerance used
  bool conforming = true;    ///< every gap <= tolerance
};

inline Interface_conformity check_interface_conformity(const Multipatch_volume& mp, int samples_per_span = 5,
                                                       double relative_tolerance = 1e-9)
{
  Interface_conformity r;
  r.tolerance = relative_tolerance * mp.bounding_box_diagonal();
  for(const Patch_interface& f : mp.interfaces()) {
    const Tensor_bspline_volume& a = mp.patch(f.first.patch);
    const Tensor_bspline_volume& b = mp.patch(f.second.patch);
    const int d = side_direction(f.first.side);
    const int t0 = d == 0 ? 1 : 0, t1 = d == 2 ? 1 : 2;
    auto normalized = [&](int dir) {
      std::vector<double> s = internal::span_samples(a.knot_vector(dir), samples_per_span);
      const double lo = a.knot_vector(dir).first(), hi = a.knot_vector(dir).last();
      for(double& x : s) x = x == hi ? 1. : (x - lo) / (hi - lo);
      return s;
    };
    const std::vector<double> s0 = normalized(t0), s1 = normalized(t1);
    double gap = 0.;
    for(double y : s1)
      for(double x : s0) {
        std::array<double, 3> s{};
        s[std::size_t(d)] = double(side_parameter(f.first.side));
        s[std::size_t(t0)] = x;
        s[std::size_t(t1)] = y;
        const Eigen::Vector3d pa = a.evaluate(a.from_normalized(s));
        const Eigen::Vector3d pb = b.evaluate(b.from_normalized(f.map_normalized(s)));
        gap = std::max(gap, (pa - pb).norm());
      }
    r.gaps.push_back(gap);
    r.max_gap = std::max(r.max_gap, gap);
    if(!(gap <= r.tolerance)) r.conforming = false;
  }
  return r;
}

/// Per-patch and overall quality of a multipatch model.
struct Multipatch_quality
{
  std::vector<Jacobian_sampling> sampled;
  std::vector<Jacobian_bound> certified;
  Jacobian_sampling overall_sampled;
  Jacobian_bound overall_certified;
  Interface_conformity interfaces;
};

/// Quality of `mp`. With `known` (measured on `mp` with the same settings before some of its
/// patches changed), the per-patch figures of the patches not flagged in `changed` are
/// copied from it instead of measured again.
inline Multipatch_quality evaluate_quality(const Multipatch_volume& mp, int samples_per_span = 5,
                                           const Jacobian_bound_options& o = Jacobian_bound_options(),
                                           const Multipatch_quality* known = nullptr, const std::vector<bool>& changed = {})
{
  Multipatch_quality q;
  double sum = 0.;
  const std::size_t np = mp.number_of_patches();
  const bool reuse = known && known->sampled.size() == np && known->certified.size() == np && changed.size() == np;
  // Per patch on every core (the bound subdivides uncertified patches deeply), then
  // accumulated in patch order.
  q.sampled.resize(np);
  q.certified.resize(np);
  internal::parallel_for(np, 0, [&](std::size_t c, unsigned) {
    const Tensor_bspline_volume& v = mp.patch(c);
    q.sampled[c] = reuse && !changed[c] ? known->sampled[c] : sample_jacobian(v, samples_per_span);
    q.certified[c] = reuse && !changed[c] ? known->certified[c] : certified_jacobian_bound(v, o);
  });
  for(std::size_t c = 0; c < np; ++c) {
    const Jacobian_sampling& s = q.sampled[c];
    Jacobian_sampling& a = q.overall_sampled;
    a.min_determinant = std::min(a.min_determinant, s.min_determinant);
    a.max_determinant = std::max(a.max_determinant, s.max_determinant);
    a.min_scaled_jacobian = std::min(a.min_scaled_jacobian, s.min_scaled_jacobian);
    sum += s.mean_scaled_jacobian * double(s.samples);
    a.samples += s.samples;
    a.nonpositive_samples += s.nonpositive_samples;
    internal::accumulate(q.overall_certified, q.certified[c]);
  }
  q.overall_sampled.mean_scaled_jacobian = q.overall_sampled.samples ? sum / double(q.overall_sampled.samples) : 0.;
  q.overall_certified.certified_positive = !mp.patches().empty() && q.overall_certified.lower_bound > 0.;
  q.overall_certified.has_nonpositive_value = q.overall_certified.smallest_value_found <= 0.;
  q.interfaces = check_interface_conformity(mp, samples_per_span);
  return q;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_QUALITY_H
