// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Layouts whose right answer is known by construction, for the tests of everything that
// reads a Polycube_layout: a chain of k unit cuboids along x, its surface triangulated on a
// lattice of n segments per unit, optionally open at both ends (cylinder class, the ends
// become CAP patches) and optionally deformed by a map of R^3.

#ifndef POLYCUBE_IGA_LAYOUT_FIXTURES_H
#define POLYCUBE_IGA_LAYOUT_FIXTURES_H

#include "test_support.h"

#include <CGAL/Polycube_IGA/Polycube_layout.h>

#include <array>
#include <functional>
#include <map>
#include <vector>

namespace test_support {

using Layout = CGAL::Polycube_IGA::Polycube_layout<Point>;

/// Chain of `k` cuboids [c, c+1] x [0,1] x [0,1], n lattice segments per unit. `open`
/// removes the two end squares (they become caps). `deform` maps every lattice point.
inline Layout box_chain_layout(int k, int n, bool open = false,
                               const std::function<Point(double, double, double)>& deform = {})
{
  Layout L;
  L.layout_class = open ? CGAL::Polycube_IGA::Layout_class::cylinder : CGAL::Polycube_IGA::Layout_class::sphere;
  L.genus = 0;
  L.boundary_loops = open ? 2 : 0;
  Mesh& m = L.mesh;
  const int nx = k * n;
  std::map<std::array<int, 3>, Mesh::Vertex_index> vid;
  auto vertex = [&](int x, int y, int z) {
    auto it = vid.find({x, y, z});
    if(it != vid.end()) return it->second;
    const double X = double(x) / n, Y = double(y) / n, Z = double(z) / n;
    const auto v = m.add_vertex(deform ? deform(X, Y, Z) : Point(X, Y, Z));
    vid.emplace(std::array<int, 3>{{x, y, z}}, v);
    return v;
  };
  // Lattice faces of one box side: fixed coordinate d = value, the other two (a, b) spanning
  // [0, size_a] x [0, size_b]; `flip` reverses the orientation so that normals point out.
  std::map<Mesh::Face_index, std::array<int, 3>> face_cell; // face -> (side key, cell a, cell b)
  auto add_side = [&](int d, int value, int size_a, int size_b, bool flip, int key) {
    const int a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;
    for(int j = 0; j < size_b; ++j)
      for(int i = 0; i < size_a; ++i) {
        std::array<Mesh::Vertex_index, 4> q;
        const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
        for(int c = 0; c < 4; ++c) {
          int x[3];
          x[d] = value;
          x[a] = i + di[c];
          x[b] = j + dj[c];
          q[std::size_t(c)] = vertex(x[0], x[1], x[2]);
        }
        if(flip) std::swap(q[1], q[3]);
        const auto f0 = m.add_face(q[0], q[1], q[2]);
        const auto f1 = m.add_face(q[0], q[2], q[3]);
        face_cell[f0] = {{key, i, j}};
        face_cell[f1] = {{key, i, j}};
      }
  };
  // Outward orientation: (a x b) = +d axis for d=0 (y,z), d=1 (x,z) is -y, d=2 (x,y) is +z.
  add_side(1, 0, nx, n, false, 0); // y = 0, outward -y: (x,z) order gives -y
  add_side(1, n, nx, n, true, 1);
  add_side(2, 0, nx, n, true, 2);
  add_side(2, n, nx, n, false, 3);
  if(!open) {
    add_side(0, 0, n, n, true, 4);
    add_side(0, nx, n, n, false, 5);
  }

  // Nodes (c, j, l) for c = 0..k and (j, l) in {0,1}^2.
  auto node = [&](int c, int j, int l) { return std::size_t(4 * c + j + 2 * l); };
  for(int c = 0; c <= k; ++c)
    for(int l = 0; l < 2; ++l)
      for(int j = 0; j < 2; ++j) L.nodes.push_back(vertex(c * n, j * n, l * n));
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> arc_id;
  auto add_arc = [&](std::size_t a, std::size_t b, const std::vector<Mesh::Vertex_index>& path) {
    arc_id[{std::min(a, b), std::max(a, b)}] = L.arcs.size();
    L.arcs.push_back({{{a, b}}, path});
  };
  for(int c = 0; c < k; ++c)
    for(int l = 0; l < 2; ++l)
      for(int j = 0; j < 2; ++j) {
        std::vector<Mesh::Vertex_index> p;
        for(int x = c * n; x <= (c + 1) * n; ++x) p.push_back(vertex(x, j * n, l * n));
        add_arc(node(c, j, l), node(c + 1, j, l), p);
      }
  for(int c = 0; c <= k; ++c) {
    // Square x = c: (0,0)-(1,0)-(1,1)-(0,1) in (y, z).
    const int cy[4] = {0, 1, 1, 0}, cz[4] = {0, 0, 1, 1};
    for(int e = 0; e < 4; ++e) {
      std::vector<Mesh::Vertex_index> p;
      for(int t = 0; t <= n; ++t) {
        const int y = cy[e] * n + (cy[(e + 1) % 4] - cy[e]) * t, z = cz[e] * n + (cz[(e + 1) % 4] - cz[e]) * t;
        p.push_back(vertex(c * n, y, z));
      }
      add_arc(node(c, cy[e], cz[e]), node(c, cy[(e + 1) % 4], cz[(e + 1) % 4]), p);
    }
  }
  auto arc = [&](std::size_t a, std::size_t b) { return arc_id.at({std::min(a, b), std::max(a, b)}); };
  auto add_patch = [&](Layout::Patch_kind kind, std::array<std::size_t, 4> corners) {
    Layout::Patch p;
    p.kind = kind;
    p.corners = corners;
    for(int i = 0; i < 4; ++i) p.arcs[std::size_t(i)] = arc(corners[std::size_t(i)], corners[std::size_t((i + 1) % 4)]);
    L.patches.push_back(p);
    return L.patches.size() - 1;
  };
  // Surface patches, corners counter-clockwise seen from outside; faces by lattice cell.
  auto collect = [&](std::size_t patch, int key, int c_lo) {
    for(const auto& fc : face_cell)
      if(fc.second[0] == key && (key >= 4 || fc.second[1] / n == c_lo)) L.patches[patch].faces.push_back(fc.first);
    std::sort(L.patches[patch].faces.begin(), L.patches[patch].faces.end());
  };
  std::vector<std::array<std::size_t, 6>> sides(static_cast<std::size_t>(k));
  for(int c = 0; c < k; ++c) {
    auto& s = sides[std::size_t(c)];
    // Local axes: u = x, v = y, w = z, so cuboid node (i,j,l) = node(c+i, j, l).
    s[2] = add_patch(Layout::SURFACE, {{node(c, 0, 0), node(c + 1, 0, 0), node(c + 1, 0, 1), node(c, 0, 1)}}); // y=0
    collect(s[2], 0, c);
    s[3] = add_patch(Layout::SURFACE, {{node(c, 1, 0), node(c, 1, 1), node(c + 1, 1, 1), node(c + 1, 1, 0)}}); // y=1
    collect(s[3], 1, c);
    s[4] = add_patch(Layout::SURFACE, {{node(c, 0, 0), node(c, 1, 0), node(c + 1, 1, 0), node(c + 1, 0, 0)}}); // z=0
    collect(s[4], 2, c);
    s[5] = add_patch(Layout::SURFACE, {{node(c, 0, 1), node(c + 1, 0, 1), node(c + 1, 1, 1), node(c, 1, 1)}}); // z=1
    collect(s[5], 3, c);
  }
  for(int c = 0; c <= k; ++c) {
    const bool end = c == 0 || c == k;
    const Layout::Patch_kind kind = !end ? Layout::INTERFACE : (open ? Layout::CAP : Layout::SURFACE);
    std::array<std::size_t, 4> q{{node(c, 0, 0), node(c, 0, 1), node(c, 1, 1), node(c, 1, 0)}}; // outward at x = 0
    if(c == k) std::swap(q[1], q[3]);
    const std::size_t p = add_patch(kind, q);
    if(kind == Layout::SURFACE) collect(p, c == 0 ? 4 : 5, 0);
    if(c < k) sides[std::size_t(c)][0] = p;
    if(c > 0) sides[std::size_t(c - 1)][1] = p;
  }
  for(int c = 0; c < k; ++c) {
    Layout::Cuboid cu;
    for(int l = 0; l < 2; ++l)
      for(int j = 0; j < 2; ++j)
        for(int i = 0; i < 2; ++i) cu.nodes[std::size_t(i + 2 * j + 4 * l)] = node(c + i, j, l);
    cu.patches = sides[std::size_t(c)];
    L.cuboids.push_back(cu);
  }
  return L;
}

} // namespace test_support

#endif // POLYCUBE_IGA_LAYOUT_FIXTURES_H
