// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Gauss linking number of two disjoint closed polylines, evaluated in closed form per
// segment pair as the signed solid angle of the quadrilateral the two segments span
// (Klenin and Langowski 2000). The sum is an integer up to round-off for disjoint curves.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LINKING_NUMBER_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LINKING_NUMBER_H

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

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif
