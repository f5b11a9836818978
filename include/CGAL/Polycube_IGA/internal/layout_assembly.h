// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Completes a Polycube_layout once its nodes and arcs are embedded in the mesh: the surface
// patches are the face sets the arcs cut the surface into (flood fill), their corners are
// the nodes met walking each patch's border, and every cuboid finds its six sides among the
// surface patches and the interior quads (caps, interfaces) by their corner sets. Every
// construction of Cuboid_decomposition.h ends here, so the bookkeeping exists once.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_ASSEMBLY_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_ASSEMBLY_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// An interior quad to add: its kind and corner nodes in cyclic order.
struct Interior_quad
{
  int kind = 2; ///< Polycube_layout::Patch_kind (CAP or INTERFACE)
  std::array<std::size_t, 4> corners{};
};

/// +1 when the corners `patch` (cyclic, counter-clockwise about the surface's outward normal)
/// run around side `s` of `cu` counter-clockwise about the side's outward normal in the
/// cuboid's (i,j,k) frame, -1 when they run the other way, 0 when they are not its corners
/// in a cycle. Equal on every surface side of a cuboid whose frame is laid out consistently:
/// the cuboid's handedness.
template <class Layout>
int side_orientation(const typename Layout::Cuboid& cu, int s, const std::array<std::size_t, 4>& patch)
{
  const int d = (s - 1) / 2, at = (s - 1) % 2;
  // Layout::side_nodes() lists (a,b) = (0,0), (1,0), (0,1), (1,1); e_a x e_b is +e_d for
  // d = 0 and 2, -e_d for d = 1, and the outward normal is -e_d at 0, +e_d at 1.
  const int frame = (d == 1 ? -1 : 1) * (at == 1 ? 1 : -1);
  const std::array<std::size_t, 4> n = Layout::side_nodes(cu, s);
  const std::array<std::size_t, 4> cycle{{n[0], n[1], n[3], n[2]}};
  const std::size_t i = std::size_t(std::find(patch.begin(), patch.end(), cycle[0]) - patch.begin());
  if(i == 4) return 0;
  int turn = 0;
  if(patch[(i + 1) % 4] == cycle[1] && patch[(i + 2) % 4] == cycle[2] && patch[(i + 3) % 4] == cycle[3]) turn = 1;
  if(patch[(i + 3) % 4] == cycle[1] && patch[(i + 2) % 4] == cycle[2] && patch[(i + 1) % 4] == cycle[3]) turn = -1;
  return turn * frame;
}

/// Builds `L.patches` and `L.cuboids` from `L.nodes`, `L.arcs`, the interior quads and the
/// cuboids' nodes (corner (i,j,k) at i+2j+4k). Throws Internal_error("layout_assembly")
/// when the arcs do not cut the surface into quads matching the cuboids.
template <class P>
void assemble_layout(Polycube_layout<P>& L, const std::vector<Interior_quad>& interior,
                     const std::vector<std::array<std::size_t, 8>>& cuboid_nodes, const std::vector<int>& cuboid_pants)
{
  using Layout = Polycube_layout<P>;
  using Mesh = typename Layout::Mesh;
  const Mesh& m = L.mesh;
  auto fail = [](const std::string& s) { throw Internal_error("layout_assembly", s); };
  const std::size_t nf = num_faces(m);
  std::vector<int> node_of(num_vertices(m), -1);
  for(std::size_t n = 0; n < L.nodes.size(); ++n) node_of[L.nodes[n]] = int(n);
  std::vector<int> arc_of_edge(num_edges(m), -1);
  std::map<std::pair<std::size_t, std::size_t>, int> arc_of_pair; // -2 when ambiguous
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    const auto& path = L.arcs[a].vertices;
    for(std::size_t i = 0; !L.arcs[a].inside && i + 1 < path.size(); ++i) {
      const auto h = halfedge(path[i], path[i + 1], m);
      if(!h.second) fail("arc " + std::to_string(a) + " is not an edge path");
      arc_of_edge[std::size_t(edge(h.first, m))] = int(a);
    }
    auto key = std::make_pair(std::min(L.arcs[a].nodes[0], L.arcs[a].nodes[1]), std::max(L.arcs[a].nodes[0], L.arcs[a].nodes[1]));
    auto ins = arc_of_pair.emplace(key, int(a));
    if(!ins.second) ins.first->second = -2;
  }

  // Flood fill faces across non-arc edges; components numbered by their smallest face.
  L.patches.clear();
  std::vector<int> patch_of_face(nf, -1);
  std::vector<typename Mesh::Face_index> stack;
  for(auto f0 : faces(m)) {
    if(patch_of_face[f0] >= 0) continue;
    const int id = int(L.patches.size());
    typename Layout::Patch patch;
    patch.kind = Layout::SURFACE;
    patch_of_face[f0] = id;
    stack.assign(1, f0);
    while(!stack.empty()) {
      const auto f = stack.back();
      stack.pop_back();
      patch.faces.push_back(f);
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        const auto o = opposite(h, m);
        if(is_border(o, m) || arc_of_edge[std::size_t(edge(h, m))] >= 0) continue;
        const auto g = face(o, m);
        if(patch_of_face[g] < 0) {
          patch_of_face[g] = id;
          stack.push_back(g);
        }
      }
    }
    std::sort(patch.faces.begin(), patch.faces.end());
    // Border walk with the patch on the left, from the border halfedge leaving the
    // smallest node, collecting corners and the arcs between them.
    typename Mesh::Halfedge_index start;
    int best = -1;
    std::size_t border = 0;
    for(auto f : patch.faces)
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        const auto o = opposite(h, m);
        if(!is_border(o, m) && patch_of_face[face(o, m)] == id) continue;
        ++border;
        const int n = node_of[source(h, m)];
        if(n >= 0 && (best < 0 || n < best)) {
          best = n;
          start = h;
        }
      }
    if(best < 0) fail("surface patch " + std::to_string(id) + " has no corner");
    std::vector<std::size_t> corners, arcs;
    auto h = start;
    std::size_t steps = 0;
    do {
      const int n = node_of[source(h, m)];
      if(n >= 0) {
        corners.push_back(std::size_t(n));
        const int a = arc_of_edge[std::size_t(edge(h, m))];
        if(a < 0) fail("surface patch " + std::to_string(id) + " has a border edge off the arcs");
        arcs.push_back(std::size_t(a));
      }
      auto g = next(h, m);
      while(true) {
        const auto o = opposite(g, m);
        if(is_border(o, m) || patch_of_face[face(o, m)] != id) break;
        g = next(o, m);
      }
      h = g;
    } while(h != start && ++steps <= border);
    if(corners.size() != 4)
      fail("surface patch " + std::to_string(id) + " has " + std::to_string(corners.size()) + " corners instead of 4");
    std::copy(corners.begin(), corners.end(), patch.corners.begin());
    std::copy(arcs.begin(), arcs.end(), patch.arcs.begin());
    L.patches.push_back(std::move(patch));
  }

  for(const Interior_quad& q : interior) {
    typename Layout::Patch patch;
    patch.kind = typename Layout::Patch_kind(q.kind);
    patch.corners = q.corners;
    for(int i = 0; i < 4; ++i) {
      const std::size_t a = q.corners[std::size_t(i)], b = q.corners[std::size_t((i + 1) % 4)];
      auto it = arc_of_pair.find({std::min(a, b), std::max(a, b)});
      if(it == arc_of_pair.end() || it->second < 0) fail("an interior quad side is not a unique arc");
      patch.arcs[std::size_t(i)] = std::size_t(it->second);
    }
    L.patches.push_back(patch);
  }

  // Cuboid sides by corner set. Two surface patches can share one: a pants whose two
  // boundaries are one cycle (a handle) has two crotch patches on the same four nodes, one
  // on each side, walked in opposite directions. The cuboid's other surface sides tell its
  // handedness (side_orientation()), and that picks the patch turning the right way.
  std::map<std::array<std::size_t, 4>, std::vector<std::size_t>> patches_of_corners;
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    auto c = L.patches[p].corners;
    std::sort(c.begin(), c.end());
    patches_of_corners[c].push_back(p);
  }
  auto candidates = [&](const typename Layout::Cuboid& cu, int s) -> const std::vector<std::size_t>& {
    static const std::vector<std::size_t> none;
    auto key = Layout::side_nodes(cu, s);
    std::sort(key.begin(), key.end());
    const auto it = patches_of_corners.find(key);
    return it == patches_of_corners.end() ? none : it->second;
  };
  L.cuboids.clear();
  for(std::size_t c = 0; c < cuboid_nodes.size(); ++c) {
    typename Layout::Cuboid cu;
    cu.nodes = cuboid_nodes[c];
    cu.pants = cuboid_pants.empty() ? -1 : cuboid_pants[c];
    int handedness = 0; // 2: the sides disagree
    for(int s = 1; s <= 6; ++s) {
      const auto& cand = candidates(cu, s);
      if(cand.size() != 1 || L.patches[cand.front()].kind != Layout::SURFACE) continue;
      const int o = side_orientation<Layout>(cu, s, L.patches[cand.front()].corners);
      handedness = handedness == 0 || handedness == o ? o : 2;
    }
    for(int s = 1; s <= 6; ++s) {
      std::vector<std::size_t> cand = candidates(cu, s);
      if(cand.size() > 1 && handedness != 0)
        cand.erase(std::remove_if(cand.begin(), cand.end(), [&](std::size_t p) {
          return L.patches[p].kind != Layout::SURFACE || side_orientation<Layout>(cu, s, L.patches[p].corners) != handedness;
        }), cand.end());
      if(cand.size() != 1)
        fail("side " + std::to_string(s) + " of cuboid " + std::to_string(c) + " matches " +
             (cand.empty() ? std::string("no patch") : std::to_string(cand.size()) + " patches"));
      cu.patches[std::size_t(s - 1)] = cand.front();
    }
    L.cuboids.push_back(cu);
  }
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_ASSEMBLY_H
