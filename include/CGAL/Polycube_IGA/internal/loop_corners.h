// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Four corners for a closed loop that is to be one face of a cuboid: the quad they span
// should be as large and as rectangular as the loop allows.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LOOP_CORNERS_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LOOP_CORNERS_H

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// The smallest sine of the angles of the quad on the 2D points `q[c[0]], ..., q[c[3]]`, in
/// that order; 0 if it is not strictly convex.
inline double smallest_sine(const std::vector<Eigen::Vector2d>& q, const std::array<std::size_t, 4>& c)
{
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  double area = 0.;
  for(int k = 0; k < 4; ++k) area += cross(q[c[std::size_t(k)]], q[c[std::size_t((k + 1) % 4)]]);
  const double orient = area > 0. ? 1. : -1.;
  double smallest = 1.;
  for(int k = 0; k < 4; ++k) {
    const Eigen::Vector2d& a = q[c[std::size_t(k)]];
    const Eigen::Vector2d u = q[c[std::size_t((k + 1) % 4)]] - a, v = q[c[std::size_t((k + 3) % 4)]] - a;
    const double l = u.norm() * v.norm();
    if(!(l > 0.)) return 0.;
    smallest = std::min(smallest, orient * cross(u, v) / l);
  }
  return std::max(smallest, 0.);
}

/// The turn, in degrees, from direction `a` to direction `b` (counter-clockwise positive).
inline double turn_degrees(const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)) * 180. / 3.14159265358979323846;
}

/// Newell's normal of the closed polyline `p`: its area vector, zero if it encloses no area.
inline Eigen::Vector3d newell_normal(const std::vector<Eigen::Vector3d>& p)
{
  const std::size_t n = p.size();
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), N = Eigen::Vector3d::Zero();
  for(const auto& x : p) c += x;
  c /= double(n);
  for(std::size_t i = 0; i < n; ++i) N += (p[i] - c).cross(p[(i + 1) % n] - c);
  return N;
}

/// The axis of a tube at a loop around it, from the area normals `n` of the faces along the
/// loop: the direction they are most nearly normal to (the least eigenvector of the sum of
/// their outer products); empty unless it is clearly the only one (least eigenvalue under a
/// quarter of the next), as on a blade with sharp edges whose faces all face one way.
/// Newell's normal is the loop's plane when the loop is flat, but a stepped end (a blade cut
/// at two heights, 1.9 apart over 0.65 of thickness) encloses more area seen from the side
/// than along the blade, and its normal lay across the tube (73 degrees off on blade.off).
inline std::optional<Eigen::Vector3d> tube_axis(const std::vector<Eigen::Vector3d>& n)
{
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for(const auto& x : n) M += x * x.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(M);
  if(eig.info() != Eigen::Success || !(eig.eigenvalues()(1) > 0.) || eig.eigenvalues()(0) > 0.25 * eig.eigenvalues()(1))
    return std::nullopt;
  return Eigen::Vector3d(eig.eigenvectors().col(0));
}

/// The closed polyline `p` projected on the plane through its centroid normal to `axis`
/// (Newell's normal if `axis` is zero), counter-clockwise in it; empty if it encloses no
/// area there.
inline std::optional<std::vector<Eigen::Vector2d>> in_mean_plane(const std::vector<Eigen::Vector3d>& p,
                                                                 Eigen::Vector3d axis = Eigen::Vector3d::Zero())
{
  const std::size_t n = p.size();
  const Eigen::Vector3d area = newell_normal(p);
  if(axis.isZero()) axis = area;
  const double side = area.dot(axis);
  if(!(std::abs(side) > 0.)) return std::nullopt;
  const Eigen::Vector3d N = (side > 0. ? axis : Eigen::Vector3d(-axis)).normalized();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for(const auto& x : p) c += x;
  c /= double(n);
  const Eigen::Vector3d e1 = N.unitOrthogonal(), e2 = N.cross(e1);
  std::vector<Eigen::Vector2d> q(n);
  for(std::size_t i = 0; i < n; ++i) q[i] = Eigen::Vector2d((p[i] - c).dot(e1), (p[i] - c).dot(e2));
  return q;
}

/// Cumulative arc length (size n + 1, the last the total) of the closed polyline `q`, a loop
/// seen along a tube (in_mean_plane()), where edges along the tube count for nothing.
inline std::vector<double> section_arc_length(const std::vector<Eigen::Vector2d>& q)
{
  const std::size_t n = q.size();
  std::vector<double> s(n + 1, 0.);
  for(std::size_t i = 0; i < n; ++i) s[i + 1] = s[i] + (q[(i + 1) % n] - q[i]).norm();
  return s;
}

/// The vertex of the closed polyline `q` (a loop seen along a tube, in_mean_plane()) within
/// `window` of arc length (`s`, as section_arc_length()) of vertex `c` where `q` turns the
/// most towards its inside, if by more than `min_turn_degrees` (the first such if several);
/// else `c`. A section corner beside a knife edge goes onto it: blade.off's edges turn by 72
/// degrees at one vertex, and a corner 0.25 from one left the patch on one side wrapped round
/// the edge, a sliver corner and a slab that folds.
inline std::size_t sharpest_turn_near(const std::vector<Eigen::Vector2d>& q, const std::vector<double>& s, std::size_t c,
                                      double window, double min_turn_degrees = 60.)
{
  const std::size_t n = q.size();
  std::size_t best = c;
  double most = min_turn_degrees;
  // Points that coincide seen along the tube (a step's ends) share the turn there.
  const double tiny = 1e-9 * s[n];
  auto apart = [&](std::size_t j, std::size_t step) {
    std::size_t k = (j + step) % n;
    for(std::size_t m = 1; m < n && (q[k] - q[j]).norm() <= tiny; ++m) k = (k + step) % n;
    return k;
  };
  for(std::size_t j = 0; j < n; ++j) {
    const double g = std::abs(s[j] - s[c]);
    if(std::min(g, s[n] - g) > window) continue;
    const double t = turn_degrees(q[j] - q[apart(j, n - 1)], q[apart(j, 1)] - q[j]);
    if(t > most) {
      most = t;
      best = j;
    }
  }
  return best;
}

/// The smallest sine of the angles of the quad on the points `c` (any order along the
/// loop) of the closed polyline `p`, seen along `axis` (as in_mean_plane()); 0 if it is not
/// convex.
inline double corner_sine(const std::vector<Eigen::Vector3d>& p, std::array<std::size_t, 4> c,
                          const Eigen::Vector3d& axis = Eigen::Vector3d::Zero())
{
  const auto q = in_mean_plane(p, axis);
  if(!q) return 0.;
  std::sort(c.begin(), c.end());
  return smallest_sine(*q, c);
}

/// Indices, increasing, of four points of the closed polyline `p` that split its turning,
/// seen along `axis` (as in_mean_plane()), into four quarters of 90 degrees: the corners at
/// turnings a, a + 90, a + 180, a + 270, with a the offset (in whole degrees) whose chord
/// quad has the largest smallest sine of its angles. On a circle a square; on a flat lens (a
/// blade's section) corners in the middle of the two rounded ends, where corners at equal
/// arc lengths make a diamond whose two flat corners give a cap a det J of 0. Empty if the
/// loop has fewer than 8 points, does not turn once around, or has no convex chord quad, or
/// if that quad is over 100 times longer than wide: on a thin blade (0.6 by 10) the ends'
/// sides are slivers whose slabs fold (13 of 100 patches not certified, against 4 for corners
/// at equal arc lengths).
inline std::optional<std::array<std::size_t, 4>> quarter_turn_corners(const std::vector<Eigen::Vector3d>& p,
                                                                       const Eigen::Vector3d& axis = Eigen::Vector3d::Zero())
{
  const std::size_t n = p.size();
  if(n < 8) return std::nullopt;
  const auto projected = in_mean_plane(p, axis);
  if(!projected) return std::nullopt;
  const std::vector<Eigen::Vector2d>& q = *projected;
  // turn[i]: the turning, in degrees, from edge 0 to edge i (counter-clockwise about N).
  std::vector<double> turn(n + 1, 0.);
  for(std::size_t i = 1; i <= n; ++i) {
    const Eigen::Vector2d a = q[i % n] - q[i - 1], b = q[(i + 1) % n] - q[i % n];
    turn[i] = turn[i - 1] + turn_degrees(a, b);
  }
  if(std::abs(turn[n] - 360.) > 30.) return std::nullopt;
  std::optional<std::array<std::size_t, 4>> best;
  double best_score = 0.;
  for(int a = 0; a < 90; ++a) {
    std::array<std::size_t, 4> t{};
    std::size_t i = 0;
    for(std::size_t k = 0; k < 4; ++k) {
      while(i < n && turn[i] < double(a) + 90. * double(k)) ++i;
      t[k] = (i + 1) % n; // edge i ends at vertex i + 1
    }
    std::array<std::size_t, 4> sorted = t;
    std::sort(sorted.begin(), sorted.end());
    if(std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) continue;
    const double sc = smallest_sine(q, sorted);
    if(sc > best_score) {
      best_score = sc;
      best = sorted;
    }
  }
  if(best) {
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.;
    for(std::size_t k = 0; k < 4; ++k) {
      const double l = (q[(*best)[(k + 1) % 4]] - q[(*best)[k]]).norm();
      shortest = std::min(shortest, l);
      longest = std::max(longest, l);
    }
    if(shortest < 0.01 * longest) return std::nullopt;
  }
  return best;
}

/// Indices, increasing, of the four sharp corners of the closed polyline `p`: its only
/// vertices where it turns, seen along `axis` (as in_mean_plane()), by more than
/// `min_turn_degrees`, all four the way the loop turns, no two of them neighbours, and the
/// loop turning once around. A loop around a tube of rectangular section from CAD
/// (anchor.off's handle loops: 8 vertices, 4 of them on the tube's sharp edges). Empty
/// otherwise: a smooth loop turns a little at every vertex, and an edge path that zigzags
/// turns both ways.
inline std::optional<std::array<std::size_t, 4>> sharp_corners(const std::vector<Eigen::Vector3d>& p,
                                                                const Eigen::Vector3d& axis = Eigen::Vector3d::Zero(),
                                                                double min_turn_degrees = 60.)
{
  const std::size_t n = p.size();
  if(n < 8) return std::nullopt;
  const auto projected = in_mean_plane(p, axis);
  if(!projected) return std::nullopt;
  const std::vector<Eigen::Vector2d>& q = *projected;
  std::vector<std::size_t> sharp;
  double total = 0.;
  for(std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = q[i] - q[(i + n - 1) % n], b = q[(i + 1) % n] - q[i];
    const double turn = turn_degrees(a, b);
    total += turn;
    if(std::abs(turn) <= min_turn_degrees) continue;
    if(turn < 0.) return std::nullopt;
    sharp.push_back(i);
  }
  if(sharp.size() != 4 || std::abs(total - 360.) > 30.) return std::nullopt;
  for(std::size_t k = 0; k < 4; ++k)
    if((sharp[(k + 1) % 4] + n - sharp[k]) % n < 2) return std::nullopt;
  return std::array<std::size_t, 4>{sharp[0], sharp[1], sharp[2], sharp[3]};
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LOOP_CORNERS_H
