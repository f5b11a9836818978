// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tensor-product B-spline and NURBS surfaces S(u,v) in R^3 (reference §2.1.2.2, eq. 2.9):
// the bivariate instance of Tensor_bspline, with control points P(i,j) stored i (u) fastest.
// They are the faces fitted in §4.1.1 and the boundary conditions of the volumes of §4.1.2.
// Surface sides are numbered as G+Smo numbers them: 1 = u0, 2 = u1, 3 = v0, 4 = v1.

#ifndef CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_SURFACE_H
#define CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_SURFACE_H

#include <CGAL/Polycube_IGA/Bspline_curve.h>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// `surface.evaluate({u, v})`, `surface.derivatives({u, v}, 2)`, `surface.control_point({i, j})`.
using Tensor_bspline_surface = Tensor_bspline<2>;

/// Boundary curve of side 1..4 (1 = u0, 2 = u1, 3 = v0, 4 = v1), oriented along the
/// increasing remaining parameter.
inline Bspline_curve boundary_curve(const Tensor_bspline_surface& s, int side)
{
  if(side < 1 || side > 4)
    throw Invalid_input_error("invalid_side", "a surface side is 1..4, got " + std::to_string(side));
  return boundary_of<2>(s, (side - 1) / 2, (side - 1) % 2);
}

/// Unnormalized normal S_u x S_v at (u, v).
inline Eigen::Vector3d normal_vector(const Tensor_bspline_surface& s, double u, double v)
{
  const auto d = s.derivatives({u, v}, 1);
  return d.first[0].cross(d.first[1]);
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_SURFACE_H
