// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Moves the interior vertices of a layout graph drawn in a piece's convex map
// (piece_layout.h) to where its straight edges meet at even angles on the surface.
//
// Tutte's rule places a graph's interior vertices by the graph alone; the convex map then
// shears and squeezes the piece unevenly, so on the mesh the arcs leave a node at 10 and
// 170 degrees where they leave at 90 and 90 in the map, and a patch between two such arcs
// becomes a band no sampling opens. The reference moves its layout's nodes to lower the
// distortion after the global parameterization (§3.3, after [Cam14]); here the same idea is
// applied where the arcs are drawn: the corners at the interior vertices are measured on
// the mesh through the map, and a pattern search moves each interior vertex while the sum
// of their squared deviations from even angles falls. The graph's embedding is kept (no vertex leaves the polygon, no two
// edges cross, the cyclic order around every vertex is unchanged), so the arcs inserted
// afterwards are crossing-free as before.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_PIECE_GRAPH_CORNERS_H
#define CGAL_POLYCUBE_IGA_INTERNAL_PIECE_GRAPH_CORNERS_H

#include <CGAL/Polycube_IGA/internal/convex_embedding.h>
#include <CGAL/Polycube_IGA/internal/layout_corner_angles.h>

#include <CGAL/Surface_mesh.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// What balance_piece_graph_corners() did: the sum over the corners of squared deviations
/// (degrees^2) from even angles before and after, and the moves kept.
struct Piece_corner_balance
{
  double before = 0., after = 0.;
  int moves = 0;
};

/// The piece graph's corners as the map draws them on the mesh (see the file comment).
/// Graph vertices 0..border_nodes.size()-1 sit on the piece's border loop, whose map is
/// `loop_uv`, at loop indices `border_nodes`; the others are interior. `uv`: every graph
/// vertex's position in the map.
template <class P>
class Piece_graph_corners
{
  using Mesh = CGAL::Surface_mesh<P>;
  using V = typename Mesh::Vertex_index;

public:
  Piece_graph_corners(const Mesh& piece, const std::vector<Eigen::Vector2d>& loop_uv,
                      const std::vector<std::size_t>& border_nodes, const std::vector<std::array<std::size_t, 2>>& segments,
                      const std::vector<Eigen::Vector2d>& uv)
      : uv_map_(piece.template property_map<V, Eigen::Vector2d>("v:uv").first), locate_(piece, uv_map_),
        loop_uv_(loop_uv), nb_(border_nodes.size()), neighbours_(uv.size()), segments_(segments)
  {
    for(const auto& s : segments)
      for(int k = 0; k < 2; ++k) neighbours_[s[std::size_t(k)]].push_back(s[std::size_t(1 - k)]);
    // A border vertex's edges are ordered from the border's direction ahead in the map.
    for(std::size_t i : border_nodes) ahead_uv_.push_back(loop_uv[(i + 1) % loop_uv.size()] - loop_uv[i]);
    order_ = rotation(uv);
  }
  // The locator holds a reference to uv_map_: not copyable. loop_uv and segments are the
  // caller's and must outlive the object.
  Piece_graph_corners(const Piece_graph_corners&) = delete;
  Piece_graph_corners& operator=(const Piece_graph_corners&) = delete;

  /// Sum over the interior vertices of squared deviations from even angles (a vertex of
  /// valence k should have k corners of 360/k degrees), or infinity when a direction cannot
  /// be located in the map. The border vertices' corners are left out: splitting the angle
  /// between a border vertex's border directions evenly among its edges as well left more
  /// patches uncertified (3torus.off 73 -> 88 at one grid of 16), and alone it made
  /// anchor.off's bands 20 -> 34.
  double deviation(const std::vector<Eigen::Vector2d>& uv) const
  {
    double sum = 0.;
    for(std::size_t v = nb_; v < uv.size(); ++v) {
      Eigen::Vector3d x, normal;
      if(!locate_.point_at(uv[v], x, normal)) return std::numeric_limits<double>::infinity();
      std::vector<Eigen::Vector3d> dirs;
      for(std::size_t w : order_[v]) {
        Eigen::Vector3d q;
        if(!locate_.point_at(uv[v] + 0.25 * (uv[w] - uv[v]), q)) return std::numeric_limits<double>::infinity();
        dirs.push_back(q - x);
      }
      const double even = 360. / double(dirs.size());
      for(std::size_t c = 0; c < dirs.size(); ++c) {
        const double a = corner_angle_between(normal, dirs[c], dirs[(c + 1) % dirs.size()]) - even;
        sum += a * a;
      }
    }
    return sum;
  }

  /// True when interior vertex v may move to uv[v]: strictly inside the polygon, no edge at
  /// v crossing another, and the cyclic orders around v and its neighbours as they were.
  bool keeps_embedding(const std::vector<Eigen::Vector2d>& uv, std::size_t v) const
  {
    if(!strictly_inside_convex_polygon(loop_uv_, uv[v])) return false;
    for(const auto& s : segments_) {
      if(s[0] != v && s[1] != v) continue;
      for(const auto& t : segments_)
        if(t[0] != s[0] && t[0] != s[1] && t[1] != s[0] && t[1] != s[1] && segments_cross(uv[s[0]], uv[s[1]], uv[t[0]], uv[t[1]]))
          return false;
    }
    if(rotation_at(uv, v) != order_[v]) return false;
    for(std::size_t w : neighbours_[v])
      if(rotation_at(uv, w) != order_[w]) return false;
    return true;
  }

private:
  static bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d)
  {
    const auto o1 = uv_orientation(a, b, c), o2 = uv_orientation(a, b, d), o3 = uv_orientation(c, d, a), o4 = uv_orientation(c, d, b);
    return o1 != o2 && o3 != o4; // touching counts as crossing
  }

  /// The neighbours of v counter-clockwise in the map: from its border direction ahead on the
  /// loop for a border vertex, from the smallest polar angle for an interior one.
  std::vector<std::size_t> rotation_at(const std::vector<Eigen::Vector2d>& uv, std::size_t v) const
  {
    const double from = v < nb_ ? std::atan2(ahead_uv_[v].y(), ahead_uv_[v].x()) : 0.;
    std::vector<std::pair<double, std::size_t>> by_angle;
    for(std::size_t w : neighbours_[v]) {
      double a = std::atan2(uv[w].y() - uv[v].y(), uv[w].x() - uv[v].x()) - from;
      while(a < 0.) a += 2. * CGAL_PI;
      by_angle.push_back({a, w});
    }
    std::sort(by_angle.begin(), by_angle.end());
    std::vector<std::size_t> out;
    for(const auto& x : by_angle) out.push_back(x.second);
    if(v >= nb_ && !out.empty()) std::rotate(out.begin(), std::min_element(out.begin(), out.end()), out.end());
    return out;
  }

  std::vector<std::vector<std::size_t>> rotation(const std::vector<Eigen::Vector2d>& uv) const
  {
    std::vector<std::vector<std::size_t>> out(uv.size());
    for(std::size_t v = 0; v < uv.size(); ++v) out[v] = rotation_at(uv, v);
    return out;
  }

  typename Mesh::template Property_map<V, Eigen::Vector2d> uv_map_;
  Uv_locator<P> locate_;
  const std::vector<Eigen::Vector2d>& loop_uv_;
  std::size_t nb_;
  std::vector<std::vector<std::size_t>> neighbours_;
  const std::vector<std::array<std::size_t, 2>>& segments_;
  std::vector<Eigen::Vector2d> ahead_uv_;
  std::vector<std::vector<std::size_t>> order_;
};

/// Pattern search over the interior vertices of a piece graph (see the file comment): each
/// in turn tries 8 steps of length h around it and takes the best one that lowers
/// Piece_graph_corners::deviation() and keeps the embedding; h halves when a round moves
/// nothing, from a tenth of the mean edge length in the map down to 1/64 of that (at most
/// 200 rounds). Deterministic.
template <class P>
Piece_corner_balance balance_piece_graph_corners(const CGAL::Surface_mesh<P>& piece, const std::vector<Eigen::Vector2d>& loop_uv, const std::vector<std::size_t>& border_nodes,
                                                 const std::vector<std::array<std::size_t, 2>>& segments, std::vector<Eigen::Vector2d>& uv)
{
  Piece_corner_balance out;
  const Piece_graph_corners<P> corners(piece, loop_uv, border_nodes, segments, uv);
  double current = out.before = out.after = corners.deviation(uv);
  if(!std::isfinite(current) || segments.empty()) return out;
  double mean = 0.;
  for(const auto& s : segments) mean += (uv[s[0]] - uv[s[1]]).norm() / double(segments.size());
  const double h0 = 0.1 * mean;
  int rounds = 0;
  for(double h = h0; h > h0 / 64. && rounds < 200; ++rounds) {
    bool moved = false;
    for(std::size_t v = border_nodes.size(); v < uv.size(); ++v) {
      const Eigen::Vector2d at = uv[v];
      Eigen::Vector2d best = at;
      double best_value = current;
      for(int k = 0; k < 8; ++k) {
        const double a = CGAL_PI * k / 4.;
        uv[v] = at + h * Eigen::Vector2d(std::cos(a), std::sin(a));
        if(!corners.keeps_embedding(uv, v)) continue;
        const double value = corners.deviation(uv);
        if(value < best_value) {
          best_value = value;
          best = uv[v];
        }
      }
      uv[v] = best;
      if(best_value < current) {
        current = best_value;
        moved = true;
        ++out.moves;
      }
    }
    if(!moved) h /= 2.;
  }
  out.after = current;
  return out;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_PIECE_GRAPH_CORNERS_H
