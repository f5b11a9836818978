// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// How a cuboid's local frame sits on its layout: which symmetry of the square sends a
// cuboid side onto its patch's grid, the sense of a side's normal in that grid, and whether
// the frame is right- or left-handed (decided from the mesh's orientation). Read by
// layout_volume() (to index and mirror side grids) and by pad_layout() (to orient the
// corners of cores and slabs).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_CUBOID_FRAMES_H
#define CGAL_POLYCUBE_IGA_INTERNAL_CUBOID_FRAMES_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Tensor_bspline_volume.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// Grid index (a, b) of a cuboid side -> grid index of the patch, for symmetry `sym` of the
/// square: bit 0 swaps, bit 1 reverses the first resulting index, bit 2 the second.
inline std::array<int, 2> square_symmetry(int sym, int a, int b, int N)
{
  int x = a, y = b;
  if(sym & 1) std::swap(x, y);
  if(sym & 2) x = N - x;
  if(sym & 4) y = N - y;
  return {{x, y}};
}

/// Patch corner (0..3) at the unit-square grid corner (i, j) in {0,1}^2.
inline int patch_corner_at(int i, int j) { return i == 0 ? (j == 0 ? 0 : 3) : (j == 0 ? 1 : 2); }

/// The symmetry of the square (see square_symmetry()) that sends the index (a, b) of side s
/// of cuboid `cu` (its two remaining local directions, increasing) to the index of its
/// patch's grid: the one matching the patch's corners to Polycube_layout::side_nodes().
template <class Layout>
int side_symmetry(const Layout& L, const typename Layout::Cuboid& cu, int s)
{
  const std::array<std::size_t, 4> sn = Layout::side_nodes(cu, s);
  const std::size_t p = cu.patches[std::size_t(s - 1)];
  if(p >= L.patches.size()) throw Invalid_input_error("invalid_layout", "a cuboid lists a patch that does not exist");
  const auto& corners = L.patches[p].corners;
  for(int sym = 0; sym < 8; ++sym) {
    bool ok = true;
    for(int q = 0; q < 4 && ok; ++q) {
      const std::array<int, 2> ij = square_symmetry(sym, q & 1, q >> 1, 1);
      ok = corners[std::size_t(patch_corner_at(ij[0], ij[1]))] == sn[std::size_t(q)];
    }
    if(ok) return sym;
  }
  throw Invalid_input_error("invalid_layout", "side " + std::to_string(s) + " of a cuboid is not bounded by the corners of patch " +
                                                  std::to_string(p) + " in a compatible order");
}

/// +1 or -1: whether the frame-outward normal of side s of a cuboid, +-(X_a x X_b) as in
/// enclosed_volume(), has the sense of its patch grid's u x v when the side is indexed
/// through symmetry `sym` (each of its three bits is a reflection of the square).
inline int side_sense(int s, int sym)
{
  const int frame = (side_parameter(s) ? 1 : -1) * (side_direction(s) == 1 ? -1 : 1);
  const int bits = (sym & 1) + ((sym >> 1) & 1) + ((sym >> 2) & 1);
  return bits % 2 == 0 ? frame : -frame;
}

/// Per cuboid: +1 if its local frame is right-handed, -1 if left-handed, 0 if undecided.
/// Decided from the mesh's orientation, not from the geometry: a SURFACE patch's grid has
/// u x v pointing out of the solid (Patch_sampling.h), which fixes the handedness of every
/// cuboid with a SURFACE side; across an INTERFACE the two frame-outward normals must be
/// opposite, which carries it to cuboids inside (cores). The signed volume enclosed by the
/// side grids gives the same answer on a sound cuboid but turns over with the cuboid: a
/// slab whose inner side crosses its outer one was mirrored and so faced its surface
/// against the mesh, which no untangling of its interior can repair. Cuboids no SURFACE
/// side reaches (a layout without surface patches) stay 0; the first decision wins.
template <class Layout>
std::vector<int> frame_handedness(const Layout& L)
{
  std::vector<int> h(L.cuboids.size(), 0);
  std::vector<std::vector<std::array<std::size_t, 2>>> sides_of(L.patches.size()); // (cuboid, side)
  std::vector<std::size_t> queue;
  for(std::size_t c = 0; c < L.cuboids.size(); ++c)
    for(int s = 1; s <= 6; ++s) {
      const std::size_t p = L.cuboids[c].patches[std::size_t(s - 1)];
      if(p >= L.patches.size()) continue;
      sides_of[p].push_back({{c, std::size_t(s)}});
      if(h[c] == 0 && L.patches[p].kind == Layout::SURFACE) {
        h[c] = side_sense(s, side_symmetry(L, L.cuboids[c], s));
        queue.push_back(c);
      }
    }
  for(std::size_t q = 0; q < queue.size(); ++q) {
    const std::size_t a = queue[q];
    for(int sa = 1; sa <= 6; ++sa) {
      const std::size_t p = L.cuboids[a].patches[std::size_t(sa - 1)];
      if(p >= L.patches.size() || L.patches[p].kind != Layout::INTERFACE) continue;
      const int na = h[a] * side_sense(sa, side_symmetry(L, L.cuboids[a], sa)); // true outward, in grid u x v
      for(const auto& bs : sides_of[p]) {
        const std::size_t b = bs[0];
        if(b == a || h[b] != 0) continue;
        const int sb = int(bs[1]);
        h[b] = -na * side_sense(sb, side_symmetry(L, L.cuboids[b], sb));
        queue.push_back(b);
      }
    }
  }
  return h;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_CUBOID_FRAMES_H
