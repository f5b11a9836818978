// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fidelity of a multipatch volume to the triangle mesh it was built from (reference §4.1,
// quality figure "fidelity"): the two-sided Hausdorff distance between the boundary sides
// of the volume and the mesh, estimated on samples with CGAL AABB trees, absolute and
// relative to the diagonal of the mesh's bounding box. The volume side is sampled on a
// regular grid per boundary side (at least `samples_per_direction` points per direction and
// four per knot span) and triangulated; the mesh side uses its vertices and face centroids.
// The spline side's triangulation adds its chord error, so raise the sampling before
// reading a small value as a failure. Kept apart from Quality.h so that Eigen-only users
// do not pull CGAL's AABB tree.

#ifndef CGAL_POLYCUBE_IGA_BOUNDARY_DISTANCE_H
#define CGAL_POLYCUBE_IGA_BOUNDARY_DISTANCE_H

#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/internal/bbox_diagonal.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

struct Boundary_distance
{
  double spline_to_mesh = 0.;  ///< max over volume-boundary samples of the distance to the mesh
  double mesh_to_spline = 0.;  ///< max over mesh samples of the distance to the volume boundary
  double hausdorff = 0.;       ///< max of the two
  double relative = 0.;        ///< hausdorff / mesh bounding-box diagonal
  double mesh_bbox_diagonal = 0.;
  std::size_t spline_samples = 0, mesh_samples = 0, boundary_sides = 0;
  /// Where the two maxima are attained, so a report can say which part of the shape is lost.
  std::array<double, 3> farthest_spline_point{{0., 0., 0.}}, farthest_mesh_point{{0., 0., 0.}};
  /// The mesh face at `farthest_mesh_point` (its face, or a face around it for a vertex).
  std::size_t farthest_mesh_face = 0;
  /// Boundary sides whose fitted face turns over: at `samples` of their sample points (side
  /// corners excluded) the side's outward normal points against the normal of the nearest
  /// mesh face (angle above 120 degrees, the mesh's orientation taken from the majority of
  /// all samples). Moving inner control points cannot repair such a side.
  struct Folded_side
  {
    Patch_side side;
    std::size_t samples = 0;
  };
  std::vector<Folded_side> folded_sides;
};

/// Two-sided Hausdorff distance between the boundary of `mp` (its declared boundary sides,
/// or every side not in an interface when none is declared) and the triangle mesh `mesh`.
template <class TriangleMesh>
Boundary_distance boundary_hausdorff_distance(const Multipatch_volume& mp, const TriangleMesh& mesh,
                                              int samples_per_direction = 64)
{
  using Point_3 = typename boost::property_traits<
    typename boost::property_map<TriangleMesh, boost::vertex_point_t>::const_type>::value_type;
  using K = typename CGAL::Kernel_traits<Point_3>::Kernel;
  using Triangle_3 = typename K::Triangle_3;
  if(faces(mesh).empty()) throw Invalid_input_error("empty_mesh", "the reference triangle mesh has no face");
  if(!CGAL::is_triangle_mesh(mesh)) throw Invalid_input_error("not_triangle_mesh", "the reference mesh must be made of triangles");

  std::vector<Patch_side> sides = mp.boundaries();
  if(sides.empty()) {
    std::set<Patch_side> glued;
    for(const auto& f : mp.interfaces()) {
      glued.insert(f.first);
      glued.insert(f.second);
    }
    for(std::size_t p = 0; p < mp.number_of_patches(); ++p)
      for(int s = 1; s <= 6; ++s)
        if(!glued.count({p, s})) sides.push_back({p, s});
  }
  Boundary_distance r;
  r.boundary_sides = sides.size();
  r.mesh_bbox_diagonal = internal::mesh_bbox_diagonal(mesh);
  if(sides.empty()) throw Invalid_input_error("no_boundary", "the multipatch volume has no boundary side");

  // Sample and triangulate the boundary sides.
  std::vector<Point_3> spline_points;
  std::vector<Eigen::Vector3d> spline_normals; // outward normal of the side at each point
  std::vector<std::size_t> spline_side;        // index in `sides`
  std::vector<bool> spline_corner;             // a corner of its side
  std::vector<Triangle_3> spline_triangles;
  for(const Patch_side& ps : sides) {
    const Tensor_bspline_volume& v = mp.patch(ps.patch);
    const int d = side_direction(ps.side), t0 = d == 0 ? 1 : 0, t1 = d == 2 ? 1 : 2;
    const int n0 = std::max(samples_per_direction, 4 * v.knot_vector(t0).number_of_spans() + 1);
    const int n1 = std::max(samples_per_direction, 4 * v.knot_vector(t1).number_of_spans() + 1);
    const std::size_t base = spline_points.size();
    for(int j = 0; j < n1; ++j)
      for(int i = 0; i < n0; ++i) {
        std::array<double, 3> s{};
        s[std::size_t(d)] = double(side_parameter(ps.side));
        s[std::size_t(t0)] = double(i) / double(n0 - 1);
        s[std::size_t(t1)] = double(j) / double(n1 - 1);
        const auto dv = v.derivatives(v.from_normalized(s), 1);
        spline_points.emplace_back(dv.point.x(), dv.point.y(), dv.point.z());
        // Outward for a patch with det J > 0: (2e-1) d_{d+1} x d_{d+2}, directions cyclic.
        const Eigen::Vector3d n = dv.first[std::size_t((d + 1) % 3)].cross(dv.first[std::size_t((d + 2) % 3)]);
        spline_normals.push_back((side_parameter(ps.side) == 1 ? 1. : -1.) * n);
        spline_side.push_back(std::size_t(&ps - sides.data()));
        spline_corner.push_back((i == 0 || i == n0 - 1) && (j == 0 || j == n1 - 1));
      }
    auto at = [&](int i, int j) { return spline_points[base + std::size_t(i) + std::size_t(n0) * std::size_t(j)]; };
    for(int j = 0; j + 1 < n1; ++j)
      for(int i = 0; i + 1 < n0; ++i) {
        spline_triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        spline_triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
  }
  // Degenerate sample triangles (collapsed sides) are harmless for distance queries but
  // AABB trees reject nothing; keep them.

  using Mesh_primitive = CGAL::AABB_face_graph_triangle_primitive<TriangleMesh>;
  using Mesh_tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Mesh_primitive>>;
  Mesh_tree mesh_tree(faces(mesh).first, faces(mesh).second, mesh);
  mesh_tree.accelerate_distance_queries();
  auto as_array = [](const Point_3& p) {
    return std::array<double, 3>{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  };
  // Cosine between each sample's outward normal and its nearest mesh face's normal.
  std::vector<double> cosine(spline_points.size(), 0.), nearest(spline_points.size(), 0.);
  double orientation = 0.;
  const auto mvpm = get(CGAL::vertex_point, mesh);
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  auto cosine_with = [&](face_descriptor f, std::size_t i) {
    const auto h = halfedge(f, mesh);
    const auto fn = CGAL::cross_product(get(mvpm, target(h, mesh)) - get(mvpm, source(h, mesh)),
                                        get(mvpm, target(next(h, mesh), mesh)) - get(mvpm, target(h, mesh)));
    const Eigen::Vector3d m(CGAL::to_double(fn.x()), CGAL::to_double(fn.y()), CGAL::to_double(fn.z()));
    const double l = m.norm() * spline_normals[i].norm();
    return l > 0. ? m.dot(spline_normals[i]) / l : 0.;
  };
  for(std::size_t i = 0; i < spline_points.size(); ++i) {
    const Point_3& p = spline_points[i];
    const auto hit = mesh_tree.closest_point_and_primitive(p);
    const double d = std::sqrt(CGAL::to_double(CGAL::squared_distance(p, hit.first)));
    nearest[i] = d;
    if(d > r.spline_to_mesh) {
      r.spline_to_mesh = d;
      r.farthest_spline_point = as_array(p);
    }
    cosine[i] = cosine_with(hit.second, i);
    orientation += cosine[i];
  }
  // A fold: more than 120 degrees against the mesh, once the mesh's own orientation (outward
  // or inward, by the majority) is factored out. Corners do not count: there the normal is
  // set by the corner's angle between the two arcs (the layout's), not by the fit, and a
  // valid volume can have a reflex one (sphere.off).
  // Nor does a sample on a part thinner than the fit's distance to the mesh, nearer the far
  // side: a face facing its way lies within twice its nearest distance (blade.off, 0.65
  // thick, its fit up to 0.3 off: 8 sides of patches certified valid were called folded, and
  // its finer and coarser grids were not untangled).
  const double sense = orientation >= 0. ? 1. : -1.;
  auto facing_face_near = [&](std::size_t i) {
    const Point_3& p = spline_points[i];
    const double R = 2. * nearest[i] + 1e-9 * r.mesh_bbox_diagonal;
    const double x = CGAL::to_double(p.x()), y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
    std::vector<face_descriptor> near;
    mesh_tree.all_intersected_primitives(CGAL::Bbox_3(x - R, y - R, z - R, x + R, y + R, z + R), std::back_inserter(near));
    for(face_descriptor f : near) {
      if(!(sense * cosine_with(f, i) > 0.5)) continue;
      const auto h = halfedge(f, mesh);
      const Triangle_3 t(get(mvpm, source(h, mesh)), get(mvpm, target(h, mesh)), get(mvpm, target(next(h, mesh), mesh)));
      if(CGAL::to_double(CGAL::squared_distance(p, t)) <= R * R) return true;
    }
    return false;
  };
  std::vector<std::size_t> folded(sides.size(), 0);
  for(std::size_t i = 0; i < cosine.size(); ++i)
    if(!spline_corner[i] && sense * cosine[i] < -0.5 && !facing_face_near(i)) ++folded[spline_side[i]];
  for(std::size_t k = 0; k < sides.size(); ++k)
    if(folded[k] > 0) r.folded_sides.push_back({sides[k], folded[k]});
  r.spline_samples = spline_points.size();

  using Soup_primitive = CGAL::AABB_triangle_primitive<K, typename std::vector<Triangle_3>::const_iterator>;
  using Soup_tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Soup_primitive>>;
  Soup_tree soup_tree(spline_triangles.cbegin(), spline_triangles.cend());
  soup_tree.accelerate_distance_queries();
  std::vector<std::pair<Point_3, face_descriptor>> mesh_points; // with a face they lie on
  const auto face_index = CGAL::get_initialized_face_index_map(mesh);
  for(auto v : vertices(mesh)) {
    const auto h = halfedge(v, mesh);
    if(h == boost::graph_traits<TriangleMesh>::null_halfedge()) continue; // isolated
    mesh_points.push_back({get(mvpm, v), face(is_border(h, mesh) ? opposite(h, mesh) : h, mesh)});
  }
  for(auto f : faces(mesh)) {
    auto h = halfedge(f, mesh);
    mesh_points.push_back({CGAL::centroid(get(mvpm, source(h, mesh)), get(mvpm, target(h, mesh)),
                                          get(mvpm, target(next(h, mesh), mesh))), f});
  }
  for(const auto& pf : mesh_points) {
    const double d = std::sqrt(CGAL::to_double(soup_tree.squared_distance(pf.first)));
    if(d > r.mesh_to_spline) {
      r.mesh_to_spline = d;
      r.farthest_mesh_point = as_array(pf.first);
      r.farthest_mesh_face = std::size_t(get(face_index, pf.second));
    }
  }
  r.mesh_samples = mesh_points.size();

  r.hausdorff = std::max(r.spline_to_mesh, r.mesh_to_spline);
  r.relative = r.mesh_bbox_diagonal > 0. ? r.hausdorff / r.mesh_bbox_diagonal : 0.;
  return r;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_BOUNDARY_DISTANCE_H
