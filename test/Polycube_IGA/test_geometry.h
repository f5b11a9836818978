// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Geometric checks shared by the tests: the tests' own outward push-offs (area-weighted
// normals, independent of the stages' directions) and Gauss-integral linking numbers.

#ifndef POLYCUBE_IGA_TEST_GEOMETRY_H
#define POLYCUBE_IGA_TEST_GEOMETRY_H

#include "test_support.h"

#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Polycube_IGA/internal/linking_number.h>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

namespace test_support {

using V3 = Eigen::Vector3d;
namespace PI = CGAL::Polycube_IGA;

inline V3 pos(const Mesh& m, Mesh::Vertex_index v)
{
  const Point& p = m.point(v);
  return V3(p.x(), p.y(), p.z());
}

/// The independent check: the Gauss double integral (the stage counts projected crossings).
inline int gauss_linking(const std::vector<V3>& a, const std::vector<V3>& b)
{
  const double lk = PI::internal::gauss_linking_number(a, b);
  CHECK(std::abs(lk - std::round(lk)) < 0.05); // an integer for disjoint closed curves
  return int(std::lround(lk));
}

struct Geometry
{
  std::vector<V3> normal; // area-weighted, oriented outwards
  std::vector<double> step;
};

inline Geometry outward_geometry(const Mesh& m)
{
  Geometry g;
  g.normal.assign(num_vertices(m), V3::Zero());
  g.step.assign(num_vertices(m), 1e300);
  double volume = 0;
  for(auto f : faces(m)) {
    std::vector<Mesh::Vertex_index> vs(vertices_around_face(halfedge(f, m), m).begin(),
                                       vertices_around_face(halfedge(f, m), m).end());
    const V3 a = pos(m, vs[0]), b = pos(m, vs[1]), c = pos(m, vs[2]);
    const V3 n = (b - a).cross(c - a);
    volume += a.dot(b.cross(c)) / 6;
    for(auto v : vs) g.normal[v] += n;
  }
  const double sign = volume >= 0 ? 1 : -1;
  for(auto& n : g.normal) n = sign * n.normalized();
  for(auto e : edges(m)) {
    const double l = (pos(m, source(e, m)) - pos(m, target(e, m))).norm();
    for(auto v : {source(e, m), target(e, m)}) g.step[v] = std::min(g.step[v], 1e-3 * l);
  }
  return g;
}

inline std::vector<V3> points_of(const Mesh& m, const std::vector<Mesh::Vertex_index>& loop, const Geometry* g = nullptr, double side = 0)
{
  std::vector<V3> p;
  for(auto v : loop) p.push_back(g ? V3(pos(m, v) + side * g->step[v] * g->normal[v]) : pos(m, v));
  return p;
}

} // namespace test_support

#endif
