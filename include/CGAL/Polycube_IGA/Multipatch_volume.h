// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A multipatch trivariate model (reference §4.1): tensor B-spline volume patches, the
// interfaces where a side of one patch meets a side of another, and the boundary sides.
// Interfaces carry G+Smo's orientation data: direction i of the first patch corresponds to
// direction `direction_map[i]` of the second, in the same sense iff `direction_orientation[i]`
// (for the normal direction: the flag says whether the two sides lie at different ends).
// Sides are numbered 1 = u0, 2 = u1, 3 = v0, 4 = v1, 5 = w0, 6 = w1, patches from 0.

#ifndef CGAL_POLYCUBE_IGA_MULTIPATCH_VOLUME_H
#define CGAL_POLYCUBE_IGA_MULTIPATCH_VOLUME_H

#include <CGAL/Polycube_IGA/Tensor_bspline_volume.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// One side (1..6) of one patch.
struct Patch_side
{
  std::size_t patch = 0;
  int side = 1;
  friend bool operator<(const Patch_side& a, const Patch_side& b)
  {
    return a.patch != b.patch ? a.patch < b.patch : a.side < b.side;
  }
  friend bool operator==(const Patch_side& a, const Patch_side& b) { return a.patch == b.patch && a.side == b.side; }
};

/// Two sides glued together, with G+Smo's direction map and orientation.
struct Patch_interface
{
  Patch_side first, second;
  std::array<int, 3> direction_map{{0, 1, 2}};
  std::array<bool, 3> direction_orientation{{true, true, true}};

  /// Normalized parameter on `second` of the point with normalized parameter `s` on `first`
  /// (the normal coordinate is set to the side of `second`).
  std::array<double, 3> map_normalized(const std::array<double, 3>& s) const
  {
    std::array<double, 3> t{};
    for(int i = 0; i < 3; ++i) {
      if(i == side_direction(first.side)) continue;
      const int j = direction_map[std::size_t(i)];
      t[std::size_t(j)] = direction_orientation[std::size_t(i)] ? s[std::size_t(i)] : 1. - s[std::size_t(i)];
    }
    t[std::size_t(side_direction(second.side))] = double(side_parameter(second.side));
    return t;
  }
};

/// \ingroup PkgPolycubeIGARef
class Multipatch_volume
{
public:
  std::size_t add_patch(Tensor_bspline_volume v)
  {
    patches_.push_back(std::move(v));
    return patches_.size() - 1;
  }
  const std::vector<Tensor_bspline_volume>& patches() const { return patches_; }
  std::vector<Tensor_bspline_volume>& patches() { return patches_; }
  const Tensor_bspline_volume& patch(std::size_t i) const { return patches_.at(i); }
  Tensor_bspline_volume& patch(std::size_t i) { return patches_.at(i); }
  std::size_t number_of_patches() const { return patches_.size(); }

  const std::vector<Patch_interface>& interfaces() const { return interfaces_; }
  const std::vector<Patch_side>& boundaries() const { return boundaries_; }

  /// Declares an interface; validates patch indices, sides and that the map is a permutation
  /// sending the normal direction of `first` to the normal direction of `second`.
  void add_interface(const Patch_interface& f)
  {
    check_side(f.first);
    check_side(f.second);
    std::array<bool, 3> seen{};
    for(int i = 0; i < 3; ++i) {
      const int j = f.direction_map[std::size_t(i)];
      if(j < 0 || j > 2 || seen[std::size_t(j)])
        throw Invalid_input_error("invalid_interface", "the direction map of an interface must be a permutation of 0 1 2");
      seen[std::size_t(j)] = true;
    }
    if(f.direction_map[std::size_t(side_direction(f.first.side))] != side_direction(f.second.side))
      throw Invalid_input_error("invalid_interface", "the direction map must send the normal direction of the first "
                                                     "side to the normal direction of the second");
    interfaces_.push_back(f);
  }
  void add_boundary(const Patch_side& s)
  {
    check_side(s);
    boundaries_.push_back(s);
  }
  void clear_topology()
  {
    interfaces_.clear();
    boundaries_.clear();
  }

  /// Finds the interfaces geometrically, as G+Smo's computeTopology does: two sides are glued
  /// when their four corners coincide within `tolerance` (relative to the bounding-box
  /// diagonal of all control points). Every other side becomes a boundary. Replaces any
  /// declared topology; deterministic (patches and sides in increasing order).
  void compute_topology(double tolerance = 1e-9)
  {
    clear_topology();
    const double tol = tolerance * std::max(bounding_box_diagonal(), 1e-300);
    std::vector<std::array<Eigen::Vector3d, 4>> corners;
    std::vector<Patch_side> sides;
    for(std::size_t p = 0; p < patches_.size(); ++p)
      for(int s = 1; s <= 6; ++s) {
        sides.push_back({p, s});
        corners.push_back(side_corners(p, s));
      }
    std::vector<bool> used(sides.size(), false);
    for(std::size_t a = 0; a < sides.size(); ++a) {
      if(used[a]) continue;
      for(std::size_t b = a + 1; b < sides.size() && !used[a]; ++b) {
        if(used[b] || sides[b].patch == sides[a].patch) continue;
        for(int sym = 0; sym < 8; ++sym) {
          bool match = true;
          for(int c = 0; c < 4 && match; ++c)
            match = (corners[a][std::size_t(c)] - corners[b][std::size_t(map_corner(sym, c))]).norm() <= tol;
          if(!match) continue;
          interfaces_.push_back(make_interface(sides[a], sides[b], sym));
          used[a] = used[b] = true;
          break;
        }
      }
      if(!used[a]) boundaries_.push_back(sides[a]);
    }
  }

  /// Diagonal of the axis-aligned bounding box of all control points.
  double bounding_box_diagonal() const
  {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
    for(const auto& v : patches_)
      for(const auto& p : v.control_points()) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    return patches_.empty() ? 0. : (hi - lo).norm();
  }

  /// Corners of a side at normalized tangential parameters (0,0), (1,0), (0,1), (1,1), the
  /// first tangential direction being the smaller of the two remaining ones.
  std::array<Eigen::Vector3d, 4> side_corners(std::size_t patch, int side) const
  {
    std::array<Eigen::Vector3d, 4> c;
    const int d = side_direction(side);
    const int t0 = d == 0 ? 1 : 0, t1 = d == 2 ? 1 : 2;
    for(int k = 0; k < 4; ++k) {
      std::array<double, 3> s{};
      s[std::size_t(d)] = double(side_parameter(side));
      s[std::size_t(t0)] = double(k & 1);
      s[std::size_t(t1)] = double(k >> 1);
      const auto& v = patches_[patch];
      c[std::size_t(k)] = v.evaluate(v.from_normalized(s));
    }
    return c;
  }

private:
  void check_side(const Patch_side& s) const
  {
    if(s.patch >= patches_.size())
      throw Invalid_input_error("invalid_interface", "patch " + std::to_string(s.patch) + " does not exist");
    check_volume_side(s.side);
  }

  // Symmetry `sym` of the unit square: bit 0 swaps (s,t), bit 1 flips the first coordinate
  // of the result, bit 2 flips the second. Returns the corner of the second side that
  // corner c (bits: s = c&1, t = c>>1) of the first side maps to.
  static int map_corner(int sym, int c)
  {
    int s = c & 1, t = c >> 1;
    if(sym & 1) std::swap(s, t);
    if(sym & 2) s = 1 - s;
    if(sym & 4) t = 1 - t;
    return s | (t << 1);
  }

  static Patch_interface make_interface(const Patch_side& a, const Patch_side& b, int sym)
  {
    const int da = side_direction(a.side), db = side_direction(b.side);
    const std::array<int, 2> ta{{da == 0 ? 1 : 0, da == 2 ? 1 : 2}}, tb{{db == 0 ? 1 : 0, db == 2 ? 1 : 2}};
    Patch_interface f;
    f.first = a;
    f.second = b;
    // Without swap, tangential direction k of a goes to direction k of b; with swap, crossed.
    const bool swap = sym & 1;
    const int to0 = swap ? tb[1] : tb[0], to1 = swap ? tb[0] : tb[1];
    f.direction_map[std::size_t(ta[0])] = to0;
    f.direction_map[std::size_t(ta[1])] = to1;
    // The flip applies to the coordinate of b that receives a's direction.
    const bool flip_to0 = swap ? (sym & 4) : (sym & 2);
    const bool flip_to1 = swap ? (sym & 2) : (sym & 4);
    f.direction_orientation[std::size_t(ta[0])] = !flip_to0;
    f.direction_orientation[std::size_t(ta[1])] = !flip_to1;
    f.direction_map[std::size_t(da)] = db;
    f.direction_orientation[std::size_t(da)] = side_parameter(a.side) != side_parameter(b.side);
    return f;
  }

  std::vector<Tensor_bspline_volume> patches_;
  std::vector<Patch_interface> interfaces_;
  std::vector<Patch_side> boundaries_;
};

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_MULTIPATCH_VOLUME_H
