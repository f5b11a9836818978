// Copyright (c) 2026 The Polycube_IGA authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The length of a bounding box's diagonal: the scale every relative tolerance and distance
// of the package refers to (boundary distance, protrusion depth, small handles).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_BBOX_DIAGONAL_H
#define CGAL_POLYCUBE_IGA_INTERNAL_BBOX_DIAGONAL_H

#include <CGAL/Bbox_3.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>

#include <cmath>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

inline double bbox_diagonal(const CGAL::Bbox_3& b)
{
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) + CGAL::square(b.zmax() - b.zmin()));
}

/// The diagonal of the bounding box of a face graph's points.
template <class TriangleMesh>
double mesh_bbox_diagonal(const TriangleMesh& tm)
{
  return bbox_diagonal(CGAL::Polygon_mesh_processing::bbox(tm));
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_BBOX_DIAGONAL_H
