// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Linking numbers of two disjoint closed polylines, two ways:
// - `projected_linking_number`: signed crossings of a planar projection along a fixed
//   generic direction, counted where the first curve passes over the second. Crossing
//   decisions use exact 2D orientation predicates on the projected points, so a crossing
//   at a shared segment end is counted once; a uniform grid keeps the cost near linear in
//   the curves' sizes. This is what the stages use.
// - `gauss_linking_number`: the Gauss double integral in closed form per segment pair, the
//   signed solid angle of the quadrilateral they span (Klenin and Langowski 2000): an
//   integer up to round-off, in quadratic time; an independent check for the tests.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LINKING_NUMBER_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LINKING_NUMBER_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// Real-valued linking number of closed polylines a and b (last point joins the first).
inline double gauss_linking_number(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b)
{
  auto clamp_asin = [](double x) { return std::asin(std::max(-1.0, std::min(1.0, x))); };
  auto unit = [](const Eigen::Vector3d& v, bool& ok) {
    const double n = v.norm();
    ok = ok && n > 0;
    return n > 0 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
  };
  double total = 0;
  const std::size_t na = a.size(), nb = b.size();
  for(std::size_t i = 0; i < na; ++i) {
    const Eigen::Vector3d& p1 = a[i];
    const Eigen::Vector3d& p2 = a[(i + 1) % na];
    const Eigen::Vector3d r12 = p2 - p1;
    for(std::size_t j = 0; j < nb; ++j) {
      const Eigen::Vector3d& p3 = b[j];
      const Eigen::Vector3d& p4 = b[(j + 1) % nb];
      const Eigen::Vector3d r13 = p3 - p1, r14 = p4 - p1, r23 = p3 - p2, r24 = p4 - p2, r34 = p4 - p3;
      const double orient = r34.cross(r12).dot(r13);
      if(orient == 0) continue; // coplanar segments subtend no solid angle
      bool ok = true;
      const Eigen::Vector3d n1 = unit(r13.cross(r14), ok), n2 = unit(r14.cross(r24), ok),
                            n3 = unit(r24.cross(r23), ok), n4 = unit(r23.cross(r13), ok);
      if(!ok) continue;
      const double omega = clamp_asin(n1.dot(n2)) + clamp_asin(n2.dot(n3)) +
                           clamp_asin(n3.dot(n4)) + clamp_asin(n4.dot(n1));
      total += orient > 0 ? omega : -omega;
    }
  }
  return total / (4 * M_PI);
}

/// Integer linking number of closed polylines a and b (last point joins the first).
inline int projected_linking_number(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b)
{
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using P2 = K::Point_2;
  // A direction no mesh is likely aligned with.
  const Eigen::Vector3d view = Eigen::Vector3d(0.3176, 0.6283, 0.7103).normalized();
  const Eigen::Vector3d e1 = view.unitOrthogonal(), e2 = view.cross(e1);
  auto project = [&](const std::vector<Eigen::Vector3d>& c) {
    std::vector<P2> p;
    p.reserve(c.size());
    for(const auto& x : c) p.emplace_back(x.dot(e1), x.dot(e2));
    return p;
  };
  const std::vector<P2> pa = project(a), pb = project(b);
  const std::size_t na = a.size(), nb = b.size();
  if(na < 2 || nb < 2) return 0;

  // Grid over b's projected segments.
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300, total = 0;
  for(std::size_t j = 0; j < nb; ++j) {
    xmin = std::min(xmin, pb[j].x()); xmax = std::max(xmax, pb[j].x());
    ymin = std::min(ymin, pb[j].y()); ymax = std::max(ymax, pb[j].y());
    total += std::sqrt(CGAL::squared_distance(pb[j], pb[(j + 1) % nb]));
  }
  const double cell = std::max(total / double(nb), 1e-300) * 2;
  const int gx = std::max(1, std::min(1024, int((xmax - xmin) / cell) + 1));
  const int gy = std::max(1, std::min(1024, int((ymax - ymin) / cell) + 1));
  const double sx = gx / std::max(xmax - xmin, 1e-300), sy = gy / std::max(ymax - ymin, 1e-300);
  auto cx = [&](double x) { return std::max(0, std::min(gx - 1, int((x - xmin) * sx))); };
  auto cy = [&](double y) { return std::max(0, std::min(gy - 1, int((y - ymin) * sy))); };
  std::vector<std::vector<int>> grid(std::size_t(gx) * gy);
  for(std::size_t j = 0; j < nb; ++j) {
    const P2 &p = pb[j], &q = pb[(j + 1) % nb];
    for(int x = cx(std::min(p.x(), q.x())); x <= cx(std::max(p.x(), q.x())); ++x)
      for(int y = cy(std::min(p.y(), q.y())); y <= cy(std::max(p.y(), q.y())); ++y)
        grid[std::size_t(x) * gy + y].push_back(int(j));
  }

  std::vector<std::size_t> stamp(nb, std::size_t(-1));
  int sum = 0;
  for(std::size_t i = 0; i < na; ++i) {
    const P2 &p = pa[i], &q = pa[(i + 1) % na];
    if(q.x() < xmin && p.x() < xmin) continue;
    for(int x = cx(std::min(p.x(), q.x())); x <= cx(std::max(p.x(), q.x())); ++x)
      for(int y = cy(std::min(p.y(), q.y())); y <= cy(std::max(p.y(), q.y())); ++y)
        for(int j : grid[std::size_t(x) * gy + y]) {
          if(stamp[j] == i) continue;
          stamp[j] = i;
          const P2 &r = pb[j], &s = pb[(j + 1) % nb];
          // Crossing of the half-open segments [p, q) and [r, s): a start point lying exactly
          // on the other segment's line counts, an end point does not, so a crossing at a
          // shared segment end is counted once (exact predicates keep the decisions consistent).
          const CGAL::Orientation o_r = CGAL::orientation(p, q, r), o_s = CGAL::orientation(p, q, s);
          const CGAL::Orientation o_p = CGAL::orientation(r, s, p), o_q = CGAL::orientation(r, s, q);
          const bool rs_crosses_line = o_s != CGAL::COLLINEAR && o_r != o_s;
          const bool pq_crosses_line = o_q != CGAL::COLLINEAR && o_p != o_q;
          if(!rs_crosses_line || !pq_crosses_line) continue;
          // Heights at the crossing decide which curve is above.
          const Eigen::Vector2d d1(q.x() - p.x(), q.y() - p.y()), d2(s.x() - r.x(), s.y() - r.y());
          const Eigen::Vector2d w(r.x() - p.x(), r.y() - p.y());
          const double den = d1.x() * d2.y() - d1.y() * d2.x();
          if(den == 0) continue;
          const double t = std::max(0.0, std::min(1.0, (w.x() * d2.y() - w.y() * d2.x()) / den));
          const double u = std::max(0.0, std::min(1.0, (w.x() * d1.y() - w.y() * d1.x()) / den));
          const double ha = (a[i] + t * (a[(i + 1) % na] - a[i])).dot(view);
          const double hb = (b[j] + u * (b[(j + 1) % nb] - b[j])).dot(view);
          if(ha > hb) sum += den > 0 ? 1 : -1;
        }
  }
  return sum;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
