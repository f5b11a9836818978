// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Lengths, areas and shapes of a layout's arcs and patches, measured on its mesh: the
// layout JSON writes them, and build_trivariate_model() names the patches whose shape
// spoils their grids: strips (a strip whose long sides differ shears its grid until it
// turns over) and bands (sides so close together that no grid's cells open).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_MEASURES_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_MEASURES_H

#include <CGAL/Polycube_IGA/Polycube_layout.h>

#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

template <class P>
std::array<double, 3> layout_point_array(const P& p)
{
  return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
}

/// Sum of the segment lengths along the arc's vertex path.
template <class P>
double layout_arc_length(const Polycube_layout<P>& L, const typename Polycube_layout<P>::Arc& arc)
{
  double s = 0.;
  for(std::size_t i = 0; i + 1 < arc.vertices.size(); ++i) {
    const auto a = layout_point_array(L.mesh.point(arc.vertices[i])), b = layout_point_array(L.mesh.point(arc.vertices[i + 1]));
    s += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  }
  return s;
}

/// Area of the patch's faces (each face by the norm of its vector area; 0 without faces).
template <class P>
double layout_patch_area(const Polycube_layout<P>& L, const typename Polycube_layout<P>::Patch& pa)
{
  double s = 0.;
  for(auto f : pa.faces) {
    std::vector<std::array<double, 3>> q;
    for(auto v : vertices_around_face(halfedge(f, L.mesh), L.mesh)) q.push_back(layout_point_array(L.mesh.point(v)));
    double n[3] = {0., 0., 0.};
    for(std::size_t i = 1; i + 1 < q.size(); ++i) {
      const double u[3] = {q[i][0] - q[0][0], q[i][1] - q[0][1], q[i][2] - q[0][2]};
      const double w[3] = {q[i + 1][0] - q[0][0], q[i + 1][1] - q[0][1], q[i + 1][2] - q[0][2]};
      n[0] += u[1] * w[2] - u[2] * w[1];
      n[1] += u[2] * w[0] - u[0] * w[2];
      n[2] += u[0] * w[1] - u[1] * w[0];
    }
    s += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return s;
}

/// A surface patch longer than this many times its width is a strip (see patch_elongation()).
constexpr double strip_elongation = 8.;

/// A surface patch whose area is less than this fraction of its length times its breadth is
/// a band (see patch_fill()).
constexpr double band_fill = 0.3;

/// The lengths of a patch's two pairs of opposite arcs (the longer pair first), and its area.
struct Patch_extent
{
  double long_side_a = 0., long_side_b = 0., short_side_a = 0., short_side_b = 0., area = 0.;
  double length() const { return 0.5 * (long_side_a + long_side_b); }
  double breadth() const { return 0.5 * (short_side_a + short_side_b); } ///< the mean of the shorter pair
  double width() const { return length() > 0. ? area / length() : 0.; } ///< area over length
  /// See patch_elongation(), patch_side_drift() and patch_fill().
  double elongation() const { return area > 0. ? length() * length() / area : std::numeric_limits<double>::infinity(); }
  double drift() const { return area > 0. ? std::abs(long_side_a - long_side_b) / width() : std::numeric_limits<double>::infinity(); }
  double fill() const { return length() * breadth() > 0. ? area / (length() * breadth()) : 0.; }
};

template <class P>
Patch_extent patch_extent(const Polycube_layout<P>& L, std::size_t p)
{
  const auto& pa = L.patches[p];
  std::array<double, 4> l{};
  for(std::size_t i = 0; i < 4; ++i) l[i] = layout_arc_length(L, L.arcs[pa.arcs[i]]);
  Patch_extent e;
  const bool first = l[0] + l[2] >= l[1] + l[3];
  e.long_side_a = first ? l[0] : l[1];
  e.long_side_b = first ? l[2] : l[3];
  e.short_side_a = first ? l[1] : l[0];
  e.short_side_b = first ? l[3] : l[2];
  e.area = layout_patch_area(L, pa);
  return e;
}

/// Calls f(p, patch_extent(L, p)) for each surface patch p of `L`, in patch order.
template <class P, class F>
void for_each_surface_extent(const Polycube_layout<P>& L, F f)
{
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    if(L.patches[p].kind == Polycube_layout<P>::SURFACE) f(p, patch_extent(L, p));
}

/// How many times a patch is longer than it is wide: its length (the mean of its longer
/// pair of opposite arcs) over its width (its area over that length). 1 for a square, 10
/// for a 10 by 1 rectangle; infinite without area. Of the layouts whose volumes are not
/// valid yet, the surface patches over strip_elongation are those whose fitted faces turn
/// over (at 16 samples, before relaxation: anchor.off 19 of 19, femur.off 6 of 6, joint.off
/// 4 of 4, 3torus.off 4 of 4, elephant.off 11 of 17); valid ones have few (3holes.obj 1, head.off 0).
template <class P>
double patch_elongation(const Polycube_layout<P>& L, std::size_t p)
{
  return patch_extent(L, p).elongation();
}

/// By how many of its widths a patch's two long sides differ in length: 0 for a rectangle,
/// 4 for a trapezoid 20 and 16 long and 1 wide; infinite without area. A patch is sampled at
/// equal fractions of each side's length, so its grid lines across drift along it by up to
/// this many widths: sheared nearly flat, the grid itself turns over (anchor.off at 16
/// samples: the sampled grid, before any fit, turns over on 19 surface patches, and on 26 at
/// 64). The surface patches whose fitted faces turn over have a median drift of 2.9 on
/// anchor.off, 1.9 on femur.off, 3.2 on double-torus-3-holes.off, against 0.8, 0.55 and 1.1
/// on the others.
template <class P>
double patch_side_drift(const Polycube_layout<P>& L, std::size_t p)
{
  return patch_extent(L, p).drift();
}

/// How much of the rectangle its sides span a patch fills: its area over its length times
/// its breadth (the means of its two pairs of opposite arcs). 1 for a rectangle, sin(a) for
/// a parallelogram of angle a, 0 without area. Low when the four sides run close together
/// along much of their length (a band) or one nearly vanishes: the cells of every grid
/// between its sides cover about this fraction of the area their sides would span at right
/// angles, whatever the sampling. At 16 samples (before relaxation), the surface patches of
/// fill under band_fill hold most of the grid quads that face against the mesh: femur.off
/// 258 of 317, double-torus-3-holes.off 155 of 173, anchor.off 133 of 162, elephant.off 126
/// of 155, 3torus.off 92 of 131, joint.off 65 of 78; with the strips (over strip_elongation; many are both), 147 of anchor.off's
/// 162 and 139 of elephant.off's 155. Of the layouts of valid volumes, 3holes.obj has one
/// such patch (no quad facing against the mesh), blade.off and head.off none, and eight.off
/// 4, which hold all 16 of its quads facing against the mesh: it is valid once its grids are
/// relaxed (Grid_relaxation.h).
template <class P>
double patch_fill(const Polycube_layout<P>& L, std::size_t p)
{
  return patch_extent(L, p).fill();
}

/// A band of a layout (band_patches()).
struct Layout_band
{
  std::size_t patch = 0;
  double fill = 0.;       ///< patch_fill()
  double elongation = 0.; ///< patch_elongation()
};

/// The bands of `L`: each surface patch whose patch_fill() is under band_fill, in patch
/// order (the driver's warnings and the CLI report).
template <class P>
std::vector<Layout_band> band_patches(const Polycube_layout<P>& L)
{
  std::vector<Layout_band> out;
  for_each_surface_extent(L, [&](std::size_t p, const Patch_extent& x) {
    if(x.fill() < band_fill) out.push_back({p, x.fill(), x.elongation()});
  });
  return out;
}

/// A strip of a layout (strip_patches()).
struct Layout_strip
{
  std::size_t patch = 0;
  double elongation = 0.; ///< patch_elongation()
  double drift = 0.;      ///< patch_side_drift()
};

/// The strips of `L`: each surface patch whose patch_elongation() is over strip_elongation,
/// in patch order (the driver's warnings and the CLI report).
template <class P>
std::vector<Layout_strip> strip_patches(const Polycube_layout<P>& L)
{
  std::vector<Layout_strip> out;
  for_each_surface_extent(L, [&](std::size_t p, const Patch_extent& x) {
    if(x.elongation() > strip_elongation) out.push_back({p, x.elongation(), x.drift()});
  });
  return out;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_MEASURES_H
