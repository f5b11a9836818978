// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Trivariate tensor-product B-spline and NURBS volumes V(u,v,w) in R^3 (reference §2.1.2.2,
// eq. 2.10-2.11): the patches of the analysis-suitable models of §4.1, control points
// P(i,j,k) stored i (u) fastest as in G+Smo. Sides follow G+Smo's numbering,
// 1 = u0, 2 = u1, 3 = v0, 4 = v1, 5 = w0, 6 = w1; the side surface keeps the two remaining
// directions in increasing order (u,v,w without the normal one).

#ifndef CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_VOLUME_H
#define CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_VOLUME_H

#include <CGAL/Polycube_IGA/Tensor_bspline_surface.h>

#include <Eigen/Dense>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// `volume.evaluate({u, v, w})`, `volume.derivatives({u, v, w}, 2)`, `volume.control_point({i, j, k})`.
using Tensor_bspline_volume = Tensor_bspline<3>;

/// Parametric direction normal to side 1..6 (0 = u, 1 = v, 2 = w).
inline int side_direction(int side) { return (side - 1) / 2; }
/// 0 when side lies at the start of its direction, 1 at the end.
inline int side_parameter(int side) { return (side - 1) % 2; }
/// Side number of (direction, 0|1).
inline int side_number(int direction, int end) { return 2 * direction + end + 1; }

inline void check_volume_side(int side)
{
  if(side < 1 || side > 6)
    throw Invalid_input_error("invalid_side", "a volume side is 1..6 (u0 u1 v0 v1 w0 w1), got " + std::to_string(side));
}

/// Surface of side 1..6 of `v`: exact restriction of the volume.
inline Tensor_bspline_surface side_surface(const Tensor_bspline_volume& v, int side)
{
  check_volume_side(side);
  return boundary_of<3>(v, side_direction(side), side_parameter(side));
}

/// Jacobian matrix [X_u X_v X_w] at (u, v, w).
inline Eigen::Matrix3d jacobian_matrix(const Tensor_bspline_volume& v, double u, double vv, double w)
{
  const auto d = v.derivatives({u, vv, w}, 1);
  Eigen::Matrix3d J;
  J << d.first[0], d.first[1], d.first[2];
  return J;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_TENSOR_BSPLINE_VOLUME_H
