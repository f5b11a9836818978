// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Measures of the level sets of a function given at a triangle mesh's vertices and linear
// on its faces: the area where it is below a value and the length of the curve where it
// equals it. The cuboid stage reads them to size the caps of a chain laid along a closed
// genus-0 surface (Cuboid_decomposition, sphere_chain()).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LEVEL_SET_MEASURES_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LEVEL_SET_MEASURES_H

#include <Eigen/Dense>

#include <array>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

struct Level_set_measure
{
  double sublevel_area = 0.; ///< area of {f < value}
  double level_length = 0.;  ///< length of {f = value}
};

/// Area of {f < value} and length of {f = value} on the triangles `faces` (vertex indices
/// into `position` and `f`), f linear on each triangle.
inline Level_set_measure level_set_measure(const std::vector<Eigen::Vector3d>& position,
                                           const std::vector<std::array<int, 3>>& faces, const std::vector<double>& f,
                                           double value)
{
  Level_set_measure out;
  for(const auto& t : faces) {
    // The triangle clipped to f < value (Sutherland-Hodgman against one half-space: at most
    // four corners), and the clip's new edge, which lies on the level curve.
    std::array<Eigen::Vector3d, 4> poly;
    std::array<Eigen::Vector3d, 2> cut;
    int n = 0, cuts = 0;
    for(int i = 0; i < 3; ++i) {
      const int a = t[std::size_t(i)], b = t[std::size_t((i + 1) % 3)];
      const double fa = f[std::size_t(a)] - value, fb = f[std::size_t(b)] - value;
      if(fa < 0.) poly[std::size_t(n++)] = position[std::size_t(a)];
      if((fa < 0.) != (fb < 0.)) {
        const Eigen::Vector3d x = position[std::size_t(a)] + (fa / (fa - fb)) * (position[std::size_t(b)] - position[std::size_t(a)]);
        poly[std::size_t(n++)] = x;
        if(cuts < 2) cut[std::size_t(cuts++)] = x;
      }
    }
    for(int i = 1; i + 1 < n; ++i) out.sublevel_area += 0.5 * (poly[std::size_t(i)] - poly[0]).cross(poly[std::size_t(i + 1)] - poly[0]).norm();
    if(cuts == 2) out.level_length += (cut[1] - cut[0]).norm();
  }
  return out;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LEVEL_SET_MEASURES_H
