// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The length of a mesh edge, by its two end vertices or by one of its halfedges: what the
// cuboid decomposition's arc lengths and the polycube labels' border costs measure.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_EDGE_LENGTH_H
#define CGAL_POLYCUBE_IGA_INTERNAL_EDGE_LENGTH_H

#include <CGAL/number_utils.h>

#include <cmath>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// The distance between vertices `a` and `b` of `m`.
template <class Mesh>
double edge_length(const Mesh& m, typename Mesh::Vertex_index a, typename Mesh::Vertex_index b)
{
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(m.point(a), m.point(b))));
}

/// The length of the edge of halfedge `h` of `m`.
template <class Mesh>
double edge_length(const Mesh& m, typename Mesh::Halfedge_index h)
{
  return edge_length(m, source(h, m), target(h, m));
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_EDGE_LENGTH_H
