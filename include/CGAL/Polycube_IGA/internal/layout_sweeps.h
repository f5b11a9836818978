// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// What the layout's local improvements share (Layout_arc_relaxation.h moves arcs,
// Layout_node_relocation.h moves nodes): the face sets of the patches between new paths,
// and sweeps over the layout until one changes nothing.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_SWEEPS_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_SWEEPS_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>

#include <algorithm>
#include <cstddef>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// The faces reached from each side's seed halfedges (their faces) by flood fills that cross
/// no edge in `barrier` and no border, each side's sorted. Empty when two sides meet, a side
/// is empty, or the sides do not hold `total` faces together (a region left out).
template <class Mesh>
std::vector<std::vector<typename Mesh::Face_index>>
faces_between_barriers(const Mesh& m, const std::vector<std::vector<typename Mesh::Halfedge_index>>& seeds,
                       const std::set<std::size_t>& barrier, std::size_t total)
{
  using F = typename Mesh::Face_index;
  std::vector<int> side(num_faces(m), -1);
  std::vector<std::vector<F>> out(seeds.size());
  std::size_t covered = 0;
  for(std::size_t s = 0; s < seeds.size(); ++s) {
    std::vector<F> stack;
    auto reach = [&](F f) {
      if(side[std::size_t(f)] == int(s)) return true;
      if(side[std::size_t(f)] >= 0) return false;
      side[std::size_t(f)] = int(s);
      stack.push_back(f);
      return true;
    };
    for(auto h : seeds[s])
      if(!reach(face(h, m))) return {};
    while(!stack.empty()) {
      const F f = stack.back();
      stack.pop_back();
      out[s].push_back(f);
      for(auto h : halfedges_around_face(halfedge(f, m), m))
        if(!barrier.count(std::size_t(edge(h, m))) && !is_border(opposite(h, m), m) && !reach(face(opposite(h, m), m))) return {};
    }
    if(out[s].empty()) return {};
    covered += out[s].size();
    std::sort(out[s].begin(), out[s].end());
  }
  if(covered != total) return {};
  return out;
}

/// Up to `sweeps` sweeps of `step(i)` over i = 0 .. count-1 (true when it changed the
/// layout), until a sweep changes nothing; then `L` is validated if anything changed
/// (Internal_error("invalid_layout") naming `what` otherwise). Returns {changes, sweeps run}.
template <class Point_3, class Step>
std::pair<std::size_t, int> sweep_layout(Polycube_layout<Point_3>& L, int sweeps, std::size_t count, const std::string& what, Step step)
{
  if(sweeps < 0) throw Invalid_input_error("invalid_parameter", "the " + what + "'s sweeps must not be negative");
  std::size_t changes = 0;
  int run = 0;
  for(int s = 0; s < sweeps; ++s) {
    ++run;
    std::size_t changed = 0;
    for(std::size_t i = 0; i < count; ++i)
      if(step(i)) ++changed;
    changes += changed;
    if(changed == 0) break;
  }
  if(changes > 0) {
    const Layout_validation v = L.validate();
    if(!v.is_valid()) throw Internal_error("invalid_layout", "the " + what + " broke the layout: " + v.problems.front());
  }
  return {changes, run};
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LAYOUT_SWEEPS_H
