// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A CAD block whose faces are all planar and perpendicular to three orthogonal axes (an L,
// a T, a U, a bracket: an orthogonal polyhedron) splits into boxes along the planes of its
// faces: the cells of that grid inside the solid. The boxes meet face to face, so they are
// the cuboids of a polycube layout, and every sharp edge lies on a box edge. Box edges and
// corners may lie inside the solid (a staircase's inner corner line; where the planes of a
// boss and of a hole elsewhere cross): the layout takes them as straight arcs and interior
// nodes (Polycube_layout::is_interior_node()).
// Read by the cuboid decomposition (Cuboid_decomposition::orthogonal_blocks()).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_ORTHOGONAL_GRID_H
#define CGAL_POLYCUBE_IGA_INTERNAL_ORTHOGONAL_GRID_H

#include <CGAL/Polycube_IGA/internal/bbox_diagonal.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>
#include <CGAL/Polycube_IGA/internal/triangle_projection.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// The grid of an orthogonal polyhedron: `frame` rows are its axes (right-handed), `planes[k]`
/// the increasing coordinates along axis k of its faces' planes, `inside` the cells
/// (i, j, l) within the solid, indexed i + n0 (j + n1 l).
struct Orthogonal_grid
{
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  std::array<std::vector<double>, 3> planes;
  std::vector<bool> inside;
  double tolerance = 0.; ///< a coordinate this near a plane is on it

  std::array<int, 3> cells() const
  {
    return {int(planes[0].size()) - 1, int(planes[1].size()) - 1, int(planes[2].size()) - 1};
  }
  /// Whether cell c is in the solid; cells outside the grid are not.
  bool is_inside(const std::array<int, 3>& c) const
  {
    const std::array<int, 3> n = cells();
    for(std::size_t k = 0; k < 3; ++k)
      if(c[k] < 0 || c[k] >= n[k]) return false;
    return inside[std::size_t(c[0] + n[0] * (c[1] + n[1] * c[2]))];
  }
  /// Whether the box edge from grid point `a` one step along axis k runs inside the solid:
  /// the four cells around it are all in it.
  bool edge_inside(const std::array<int, 3>& a, std::size_t k) const
  {
    const std::size_t b = (k + 1) % 3, d = (k + 2) % 3;
    for(int s = 0; s < 4; ++s) {
      std::array<int, 3> c = a;
      c[b] -= s & 1, c[d] -= s >> 1;
      if(!is_inside(c)) return false;
    }
    return true;
  }
  /// Whether grid point `a` lies inside the solid: the eight cells around it are all in it.
  bool point_inside(const std::array<int, 3>& a) const
  {
    for(int s = 0; s < 8; ++s)
      if(!is_inside({a[0] - (s & 1), a[1] - ((s >> 1) & 1), a[2] - (s >> 2)})) return false;
    return true;
  }
  /// The coordinate of `p` along axis k.
  template <class Point>
  double coordinate(const Point& p, std::size_t k) const
  {
    return frame.row(Eigen::Index(k)).dot(Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())));
  }
  /// The index of the plane along axis k at coordinate x, or -1.
  int plane_at(std::size_t k, double x) const
  {
    const auto it = std::lower_bound(planes[k].begin(), planes[k].end(), x - tolerance);
    return it != planes[k].end() && std::abs(*it - x) <= tolerance ? int(it - planes[k].begin()) : -1;
  }
};

/// Each face's unit normal (unit_face_normal()) and area, by face index.
template <class Mesh>
std::pair<std::vector<Eigen::Vector3d>, std::vector<double>> face_normals_and_areas(const Mesh& m)
{
  std::vector<Eigen::Vector3d> normal(num_faces(m));
  std::vector<double> area(num_faces(m));
  for(auto f : faces(m)) {
    normal[std::size_t(f)] = unit_face_normal(m, f);
    area[std::size_t(f)] = CGAL::to_double(CGAL::Polygon_mesh_processing::face_area(f, m));
  }
  return {std::move(normal), std::move(area)};
}

/// The grid of `m` when it is an orthogonal polyhedron (every face's normal within
/// `angle_degrees` of an axis, every face on one of its axis's planes) with at most
/// `maximum_cells` boxes; empty otherwise, and then, for an orthogonal polyhedron, `why`
/// says what is wrong with its boxes.
template <class Mesh>
std::optional<Orthogonal_grid> orthogonal_grid(const Mesh& m, double angle_degrees = 2., std::size_t maximum_cells = 256,
                                               std::string* why = nullptr)
{
  auto refuse = [&](const std::string& reason) -> std::optional<Orthogonal_grid> {
    if(why) *why = reason;
    return std::nullopt;
  };
  using K = typename CGAL::Kernel_traits<typename Mesh::Point>::Kernel;
  if(num_faces(m) == 0) return std::nullopt;
  const auto [normal, area] = face_normals_and_areas(m);
  // Axes: the largest face's normal, then the largest face's perpendicular to it.
  const double radians = angle_degrees * 3.14159265358979323846 / 180., along = std::cos(radians), across = std::sin(radians);
  std::size_t first = 0;
  for(std::size_t f = 1; f < normal.size(); ++f)
    if(area[f] > area[first]) first = f;
  const Eigen::Vector3d a0 = normal[first];
  if(a0.squaredNorm() == 0.) return std::nullopt;
  std::optional<std::size_t> second;
  for(std::size_t f = 0; f < normal.size(); ++f)
    if(normal[f].squaredNorm() > 0. && std::abs(normal[f].dot(a0)) < across && (!second || area[f] > area[*second])) second = f;
  if(!second) return std::nullopt;
  const Eigen::Vector3d a1 = (normal[*second] - normal[*second].dot(a0) * a0).normalized();
  Orthogonal_grid g;
  g.frame.row(0) = a0;
  g.frame.row(1) = a1;
  g.frame.row(2) = a0.cross(a1);
  const double diagonal = mesh_bbox_diagonal(m);
  g.tolerance = 1e-6 * diagonal;
  // Each face on a plane of its axis: the planes are the distinct face coordinates.
  std::array<std::vector<double>, 3> values;
  for(auto f : faces(m)) {
    const Eigen::Vector3d n = g.frame * normal[std::size_t(f)];
    std::size_t k = 0;
    n.cwiseAbs().maxCoeff(&k);
    if(!(std::abs(n[Eigen::Index(k)]) >= along)) return std::nullopt;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for(auto v : vertices_around_face(halfedge(f, m), m)) {
      const double x = g.coordinate(m.point(v), k);
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    if(hi - lo > 2. * g.tolerance) return std::nullopt; // not on a plane of its axis
    values[k].push_back(0.5 * (lo + hi));
  }
  for(std::size_t k = 0; k < 3; ++k) {
    std::sort(values[k].begin(), values[k].end());
    for(double x : values[k])
      if(g.planes[k].empty() || x - g.planes[k].back() > 4. * g.tolerance) g.planes[k].push_back(x);
    if(g.planes[k].size() < 2) return std::nullopt;
  }
  const std::array<int, 3> n = g.cells();
  if(std::size_t(n[0]) * std::size_t(n[1]) * std::size_t(n[2]) > 64 * maximum_cells)
    return refuse("its grid has " + std::to_string(std::size_t(n[0]) * std::size_t(n[1]) * std::size_t(n[2])) + " cells, over " +
                  std::to_string(64 * maximum_cells));
  // The cells inside: their centres, by the exact side-of-mesh test.
  CGAL::Side_of_triangle_mesh<Mesh, K> side(m);
  g.inside.assign(std::size_t(n[0] * n[1] * n[2]), false);
  std::size_t count = 0;
  for(int l = 0; l < n[2]; ++l)
    for(int j = 0; j < n[1]; ++j)
      for(int i = 0; i < n[0]; ++i) {
        const Eigen::Vector3d u(0.5 * (g.planes[0][std::size_t(i)] + g.planes[0][std::size_t(i) + 1]),
                                0.5 * (g.planes[1][std::size_t(j)] + g.planes[1][std::size_t(j) + 1]),
                                0.5 * (g.planes[2][std::size_t(l)] + g.planes[2][std::size_t(l) + 1]));
        const Eigen::Vector3d x = g.frame.transpose() * u;
        const bool in = side(typename K::Point_3(x.x(), x.y(), x.z())) == CGAL::ON_BOUNDED_SIDE;
        g.inside[std::size_t(i + n[0] * (j + n[1] * l))] = in;
        count += in ? 1 : 0;
      }
  if(count == 0) return refuse("no grid cell is inside it");
  if(count > maximum_cells) return refuse(std::to_string(count) + " boxes, over " + std::to_string(maximum_cells));
  return g;
}

/// Splits the edges of `m` that the grid's planes cross, where they cross (the surface does
/// not move), so that every grid line on the surface is a path of mesh edges. A triangle
/// crossed by a plane has the two points of its crossing joined by an edge after its two
/// crossed edges are split (split_edge_at() joins each new vertex to the opposite corner).
template <class P>
void insert_grid_planes(CGAL::Surface_mesh<P>& m, const Orthogonal_grid& g)
{
  using V = typename CGAL::Surface_mesh<P>::Vertex_index;
  for(std::size_t k = 0; k < 3; ++k)
    for(std::size_t i = 1; i + 1 < g.planes[k].size(); ++i) {
      const double c = g.planes[k][i];
      auto offset = [&](V v) {
        const double s = g.coordinate(m.point(v), k) - c;
        return std::abs(s) <= g.tolerance ? 0. : s;
      };
      std::vector<std::pair<std::array<V, 2>, double>> splits;
      for(auto e : edges(m)) {
        const auto h = halfedge(e, m);
        const double a = offset(source(h, m)), b = offset(target(h, m));
        if((a < 0. && b > 0.) || (a > 0. && b < 0.)) splits.push_back({{{source(h, m), target(h, m)}}, a / (a - b)});
      }
      for(const auto& sp : splits) split_edge_at(m, halfedge(sp.first[0], sp.first[1], m).first, sp.second);
    }
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_ORTHOGONAL_GRID_H
