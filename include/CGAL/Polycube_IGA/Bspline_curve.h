// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// B-spline and NURBS curves in R^3 (reference §2.1.2.2, eq. 2.8 and 2.11): the univariate
// instance of Tensor_bspline. Curves are the fixed boundaries of the surface fitting
// (Bspline_surface_fitting.h) and the simplest object refinement is checked on.

#ifndef CGAL_POLYCUBE_IGA_BSPLINE_CURVE_H
#define CGAL_POLYCUBE_IGA_BSPLINE_CURVE_H

#include <CGAL/Polycube_IGA/Tensor_bspline.h>

#include <algorithm>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// `curve.evaluate({t})`, `curve.derivatives({t}, 2)`, control points in order.
using Bspline_curve = Tensor_bspline<1>;

/// The same curve traversed backwards, on the same parameter interval: t -> a + b - t.
inline Bspline_curve reversed(const Bspline_curve& c)
{
  const Knot_vector& kv = c.knot_vector(0);
  const double a = kv.first(), b = kv.last();
  std::vector<double> k(kv.knots().rbegin(), kv.knots().rend());
  for(double& t : k) t = a + b - t;
  std::vector<Eigen::Vector3d> pts(c.control_points().rbegin(), c.control_points().rend());
  std::vector<double> w(c.weights().rbegin(), c.weights().rend());
  return Bspline_curve({Knot_vector(kv.degree(), std::move(k))}, std::move(pts), std::move(w));
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_BSPLINE_CURVE_H
