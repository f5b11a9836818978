// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Embeds a planar layout graph in one disk-shaped piece of the surface: the piece is mapped
// bijectively onto a convex polygon (convex_embedding.h), the graph's interior vertices are
// placed in that polygon (given, or by Tutte's barycentric rule on the graph itself, which
// keeps a 3-connected planar graph with a convex outer face free of crossings), and every
// graph edge is inserted as a straight uv segment, refining the piece with exact predicates
// (segment_insertion.h). The polyedges of §2.2.2.3 are straight lines in a parametric
// domain in the same way; here one convex domain per piece serves all of them.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_PIECE_LAYOUT_H
#define CGAL_POLYCUBE_IGA_INTERNAL_PIECE_LAYOUT_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/internal/convex_embedding.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>
#include <CGAL/Polycube_IGA/internal/piece_graph_corners.h>
#include <CGAL/Polycube_IGA/internal/segment_insertion.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// A planar graph to embed in a piece. Graph vertices 0..border_nodes.size()-1 are border
/// vertices of the piece (indices into its border loop); the following ones are interior,
/// at `interior_uv` (entries with NaN are placed by Tutte's rule).
struct Piece_graph
{
  std::vector<std::pair<std::size_t, Eigen::Vector2d>> anchors; ///< loop index -> polygon vertex (convex, CCW)
  std::vector<std::size_t> border_nodes;                        ///< loop indices
  std::vector<Eigen::Vector2d> interior_uv;
  std::vector<std::array<std::size_t, 2>> segments;             ///< graph vertex pairs
  /// If > 0: the interior vertices, in order a convex polygon around `interior_center`, are
  /// scaled about it (by s in [0.02, 0.9], their given positions being s = 1) so that the
  /// polygon holds this fraction of the piece's area. A convex map squeezes the far parts
  /// of a piece into a small middle: fixed positions put most of a mushroom in one patch.
  double interior_area_fraction = 0.;
  Eigen::Vector2d interior_center = Eigen::Vector2d(0.5, 0.5);
  /// If set: a piece vertex whose place in the polygon becomes `interior_center`, the interior
  /// vertices moved with it (a protrusion's far end, which the map squeezes anywhere).
  std::optional<std::size_t> interior_center_vertex;
  /// If set: the interior vertices, once placed, move to where the edges meet at even
  /// angles on the mesh (balance_piece_graph_corners()).
  bool balance_corners = false;
};

/// The scale about g.interior_center at which the convex polygon of g's interior vertices
/// holds g.interior_area_fraction of the piece's 3D area (triangles counted by their uv
/// centroid), by bisection; the area inside grows with the scale.
template <class P>
double area_balancing_scale(const CGAL::Surface_mesh<P>& piece, const Piece_graph& g)
{
  const auto uv = piece.template property_map<typename CGAL::Surface_mesh<P>::Vertex_index, Eigen::Vector2d>("v:uv").first;
  std::vector<Eigen::Vector2d> centroid;
  std::vector<double> area;
  double total = 0.;
  for(auto f : faces(piece)) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    std::array<Eigen::Vector3d, 3> x;
    int k = 0;
    for(auto v : vertices_around_face(halfedge(f, piece), piece)) {
      c += uv[v] / 3.;
      const auto& p = piece.point(v);
      x[std::size_t(k++)] = Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
    centroid.push_back(c);
    area.push_back(0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm());
    total += area.back();
  }
  const std::size_t n = g.interior_uv.size();
  auto inside_area = [&](double s) {
    double a = 0.;
    for(std::size_t t = 0; t < centroid.size(); ++t) {
      bool in = true;
      for(std::size_t i = 0; i < n && in; ++i) {
        const Eigen::Vector2d p = g.interior_center + s * (g.interior_uv[i] - g.interior_center);
        const Eigen::Vector2d q = g.interior_center + s * (g.interior_uv[(i + 1) % n] - g.interior_center);
        const Eigen::Vector2d e = q - p, d = centroid[t] - p;
        in = e.x() * d.y() - e.y() * d.x() >= 0.;
      }
      if(in) a += area[t];
    }
    return a;
  };
  double lo = 0.02, hi = 0.9;
  const double target = g.interior_area_fraction * total;
  if(inside_area(lo) >= target) return lo;
  if(inside_area(hi) <= target) return hi;
  for(int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (inside_area(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

template <class P>
struct Piece_graph_embedding
{
  using vertex_descriptor = typename CGAL::Surface_mesh<P>::Vertex_index;
  std::vector<vertex_descriptor> vertex;            ///< piece vertex of each graph vertex
  std::vector<std::vector<vertex_descriptor>> path; ///< per segment, from its first to its second vertex
  Piece_corner_balance balance;                     ///< what the corner balance did (Piece_graph::balance_corners)
};

/// Regular polygon positions for loop indices chosen by 3D arc length: vertex i of `loop`
/// at angle 2*pi*s_i/L on the unit circle (s_i the arc length from loop[0]). Every loop
/// vertex becomes an anchor, so the border is a strictly convex polygon and no anchor
/// interpolation is needed.
template <class P>
std::vector<std::pair<std::size_t, Eigen::Vector2d>>
circle_anchors(const CGAL::Surface_mesh<P>& piece, const std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>& loop)
{
  std::vector<double> s(loop.size() + 1, 0.);
  for(std::size_t i = 0; i < loop.size(); ++i)
    s[i + 1] = s[i] + std::sqrt(CGAL::to_double(CGAL::squared_distance(piece.point(loop[i]), piece.point(loop[(i + 1) % loop.size()]))));
  const double total = s.back() > 0 ? s.back() : 1.;
  std::vector<std::pair<std::size_t, Eigen::Vector2d>> out;
  const double two_pi = 6.283185307179586476925286766559;
  for(std::size_t i = 0; i < loop.size(); ++i) {
    const double a = two_pi * s[i] / total;
    out.push_back({i, Eigen::Vector2d(std::cos(a), std::sin(a))});
  }
  return out;
}

/// Maps `piece` onto the polygon, places and inserts the graph. `start` selects the loop's
/// first vertex (the indices in `g` refer to the loop from there).
template <class P>
Piece_graph_embedding<P> embed_piece_graph(CGAL::Surface_mesh<P>& piece,
                                           const std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>& loop,
                                           Piece_graph g)
{
  Piece_graph_embedding<P> out;
  const std::vector<Eigen::Vector2d> loop_uv = place_border(piece, loop, g.anchors);
  const std::size_t flipped = embed_in_convex_polygon(piece, loop, loop_uv);
  if(flipped != 0)
    throw Internal_error("parameterization_failed", "the convex map of a layout piece flips " + std::to_string(flipped) + " triangles");

  const std::size_t nb = g.border_nodes.size(), ni = g.interior_uv.size(), n = nb + ni;
  std::vector<Eigen::Vector2d> uv(n);
  for(std::size_t i = 0; i < nb; ++i) uv[i] = loop_uv[g.border_nodes[i]];
  if(g.interior_center_vertex) {
    const auto uvmap = piece.template property_map<typename CGAL::Surface_mesh<P>::Vertex_index, Eigen::Vector2d>("v:uv").first;
    const Eigen::Vector2d to = uvmap[typename CGAL::Surface_mesh<P>::Vertex_index(std::uint32_t(*g.interior_center_vertex))];
    for(auto& p : g.interior_uv) p += to - g.interior_center;
    g.interior_center = to;
  }
  if(g.interior_area_fraction > 0.) {
    const double scale = area_balancing_scale(piece, g);
    for(auto& p : g.interior_uv) p = g.interior_center + scale * (p - g.interior_center);
  }
  // Around a vertex that the map puts near the polygon's border, the interior nodes would
  // cross it: they are drawn towards the vertex (strictly inside, as every inner vertex)
  // until they are inside.
  if(g.interior_center_vertex) {
    auto inside = [&](const Eigen::Vector2d& p) {
      // NaN: placed by Tutte's rule below, inside.
      return !std::isfinite(p.x()) || strictly_inside_convex_polygon(loop_uv, p);
    };
    for(int k = 0; k < 40 && !std::all_of(g.interior_uv.begin(), g.interior_uv.end(), inside); ++k)
      for(auto& p : g.interior_uv) p = g.interior_center + 0.75 * (p - g.interior_center);
  }
  // Tutte's rule for the interior vertices without a position: each the mean of its
  // graph neighbours (a small dense solve).
  std::vector<int> unknown(n, -1);
  int nu = 0;
  for(std::size_t i = 0; i < ni; ++i) {
    uv[nb + i] = g.interior_uv[i];
    if(!std::isfinite(g.interior_uv[i].x())) unknown[nb + i] = nu++;
  }
  if(nu > 0) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nu, nu);
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(nu, 2);
    for(const auto& s : g.segments)
      for(int k = 0; k < 2; ++k) {
        const std::size_t x = s[std::size_t(k)], y = s[std::size_t(1 - k)];
        if(unknown[x] < 0) continue;
        A(unknown[x], unknown[x]) += 1.;
        if(unknown[y] >= 0) A(unknown[x], unknown[y]) -= 1.;
        else b.row(unknown[x]) += uv[y].transpose();
      }
    const Eigen::MatrixXd x = A.fullPivLu().solve(b);
    for(std::size_t i = 0; i < n; ++i)
      if(unknown[i] >= 0) uv[i] = x.row(unknown[i]).transpose();
  }

  if(g.balance_corners) out.balance = balance_piece_graph_corners(piece, loop_uv, g.border_nodes, g.segments, uv);

  out.vertex.resize(n);
  for(std::size_t i = 0; i < nb; ++i) out.vertex[i] = loop[g.border_nodes[i]];
  for(std::size_t i = nb; i < n; ++i) out.vertex[i] = insert_point(piece, uv[i]);
  for(const auto& s : g.segments) out.path.push_back(insert_segment(piece, out.vertex[s[0]], out.vertex[s[1]]));
  return out;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_PIECE_LAYOUT_H
