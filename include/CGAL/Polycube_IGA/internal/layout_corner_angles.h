// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The angles of a layout's surface patches at their corners, measured on the mesh, and
// their statistics. The driver reports them (a sliver or reflex corner is why a fitted face degenerates there)
// and the arc relaxation (Layout_arc_relaxation.h) moves arcs to bring them nearer 90; the
// pants halves' corner balance (piece_graph_corners.h) measures its corners the same way.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_CORNER_ANGLES_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_CORNER_ANGLES_H

#include <CGAL/Polycube_IGA/Patch_sampling.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// Outward unit normal of the layout's mesh at vertex v.
template <class Point_3>
Eigen::Vector3d layout_vertex_normal(const Polycube_layout<Point_3>& L, typename Polycube_layout<Point_3>::vertex_descriptor v)
{
  const auto n = CGAL::Polygon_mesh_processing::compute_vertex_normal(v, L.mesh);
  return Eigen::Vector3d(CGAL::to_double(n.x()), CGAL::to_double(n.y()), CGAL::to_double(n.z())).normalized();
}

/// The direction in which `path` (a vertex path from a node whose outward normal is
/// `normal`) leaves the node: to its first vertex past a quarter of its length (the path's
/// shape there, not the teeth or hooks of a vertex path on a coarse mesh, which an eighth
/// still sees on sphere.off), or to the last before the surface turns more than 60 degrees
/// away from `normal` (past a sharp edge, around a thin blade's edge, the chord would point
/// through the solid, and a blade's every corner read reflex).
template <class Point_3>
Eigen::Vector3d leaving_direction(const Polycube_layout<Point_3>& L,
                                  const std::vector<typename Polycube_layout<Point_3>::vertex_descriptor>& path,
                                  const Eigen::Vector3d& normal)
{
  std::vector<Eigen::Vector3d> points;
  points.reserve(path.size());
  for(auto v : path) points.push_back(to_eigen_point(L.mesh.point(v)));
  const std::vector<double> length = cumulative_lengths(points);
  const double turned_away = 0.5; // the cosine of 60 degrees
  std::size_t k = 1;
  while(k + 1 < points.size() && length[k - 1] < length.back() / 4. && layout_vertex_normal(L, path[k + 1]).dot(normal) > turned_away) ++k;
  return Eigen::Vector3d(points[std::min(k, points.size() - 1)] - points[0]);
}

/// Angle (degrees, in [0, 360)) at a corner whose two arcs leave in directions `next` and
/// `previous`: reflex (360 minus it) where they turn clockwise about the outward `normal`.
inline double corner_angle_between(const Eigen::Vector3d& normal, const Eigen::Vector3d& next, const Eigen::Vector3d& previous)
{
  const double a = std::atan2(next.cross(previous).norm(), next.dot(previous)) * 180. / CGAL_PI;
  return normal.dot(next.cross(previous)) >= 0. ? a : 360. - a;
}

/// The interior angle (degrees, in [0, 360)) of SURFACE patch p at its corner i: between the
/// directions in which its two arcs leave the corner (leaving_direction()), reflex (360
/// minus it) where they turn clockwise about the node's outward normal (patches are
/// counter-clockwise seen from outside). A box's corners measure 90 degrees.
template <class Point_3>
double surface_corner_angle(const Polycube_layout<Point_3>& L, std::size_t p, int i)
{
  const auto& pa = L.patches[p];
  const std::size_t n = pa.corners[std::size_t(i)];
  const Eigen::Vector3d normal = layout_vertex_normal(L, L.nodes[n]);
  auto from_node = [&](std::size_t a) {
    auto vs = L.arcs[a].vertices;
    if(L.arcs[a].nodes[0] != n) std::reverse(vs.begin(), vs.end());
    return leaving_direction(L, vs, normal);
  };
  const Eigen::Vector3d next = from_node(pa.arcs[std::size_t(i)]);
  const Eigen::Vector3d previous = from_node(pa.arcs[std::size_t((i + 3) % 4)]);
  return corner_angle_between(normal, next, previous);
}

/// Sum over the SURFACE patch corners `corners` ({patch, corner index}) of (angle - 90)^2,
/// and in `*largest` (if given) the largest |angle - 90| met (not below its value on entry).
template <class Point_3>
double squared_corner_deviation(const Polycube_layout<Point_3>& L, const std::vector<std::array<std::size_t, 2>>& corners,
                                double* largest = nullptr)
{
  double sum = 0.;
  for(const auto& c : corners) {
    const double d = surface_corner_angle(L, c[0], int(c[1])) - 90.;
    sum += d * d;
    if(largest) *largest = std::max(*largest, std::abs(d));
  }
  return sum;
}

/// surface_corner_angle() of every SURFACE patch at its four corners (zeros for the others).
template <class Point_3>
std::vector<std::array<double, 4>> surface_corner_angles(const Polycube_layout<Point_3>& L)
{
  std::vector<std::array<double, 4>> angles(L.patches.size(), {{0., 0., 0., 0.}});
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    if(L.patches[p].kind == Polycube_layout<Point_3>::SURFACE)
      for(int i = 0; i < 4; ++i) angles[p][std::size_t(i)] = surface_corner_angle(L, p, i);
  return angles;
}

/// A surface patch corner below this many degrees, or above 180 minus it, is reported when
/// the volume is not valid.
constexpr double sliver_corner_degrees = 25.;

/// A corner angle (degrees) that lets a fitted face degenerate or turn over: a sliver,
/// nearly flat or reflex.
inline bool is_bad_corner(double degrees)
{
  return degrees < sliver_corner_degrees || degrees > 180. - sliver_corner_degrees;
}

/// The corners of a layout's surface patches as surface_corner_angles() measures them on the
/// mesh: how far they are from right angles, and how many would let a fitted face degenerate
/// (under `sliver_corner_degrees` or over 180 minus it) or turn over (reflex). Over the test
/// meshes' layouts the mean deviation is 16 to 33 degrees on those that give valid volumes
/// and 36 to 49 on those that do not yet (anchor, joint, ring5, double-torus-3-holes).
struct Layout_corner_statistics
{
  std::size_t corners = 0, slivers = 0, nearly_flat = 0, reflex = 0;
  double mean_deviation = 0., max_deviation = 0.; ///< |angle - 90| in degrees
};

template <class Point_3>
Layout_corner_statistics layout_corner_statistics(const Polycube_layout<Point_3>& L)
{
  Layout_corner_statistics s;
  const std::vector<std::array<double, 4>> angles = surface_corner_angles(L);
  for(std::size_t p = 0; p < angles.size(); ++p) {
    if(L.patches[p].kind != Polycube_layout<Point_3>::SURFACE) continue;
    for(double a : angles[p]) {
      ++s.corners;
      s.mean_deviation += std::abs(a - 90.);
      s.max_deviation = std::max(s.max_deviation, std::abs(a - 90.));
      s.slivers += a < sliver_corner_degrees;
      s.nearly_flat += a > 180. - sliver_corner_degrees && a <= 180.;
      s.reflex += a > 180.;
    }
  }
  if(s.corners > 0) s.mean_deviation /= double(s.corners);
  return s;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_CORNER_ANGLES_H
