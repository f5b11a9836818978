// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Polycube labels for faces that lie halfway between two directions of the frame: a CAD
// part's 45-degree features (anchor.off's slanted boss with its bore and groove). Their
// nearest direction is decided by rounding, so on a faceted 45-degree cylinder the labels
// alternate in strips, and smoothing them (graph cuts) gives the whole feature one label,
// which folds it into a neighbouring chart. Here the tied faces are grouped into regions,
// and each region takes one of its two labels, or is cut in two along a plane, by rules a
// polycube must obey at its creases; then the borders on the region's cylinder follow its
// decision, one-face teeth of a chart are given to their neighbours, and small charts are
// merged. The method is ours; the problem is the one PolyCut (Livesu et al. 2013) and
// Evocube (Dumery et al. 2022) attack with global optimisation, read to learn.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_TIED_LABELS_H
#define CGAL_POLYCUBE_IGA_INTERNAL_TIED_LABELS_H

#include <CGAL/Polycube_IGA/internal/label_charts.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>
#include <CGAL/Polycube_IGA/internal/orthogonal_grid.h>

#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// A copy of the closed surface `m` remeshed isotropically to edges of `edge_fraction` of
/// its bounding-box diagonal, its sharp edges (over 30 degrees) kept as constraints, so that
/// its new vertices lie on it. A CAD export's long slivers from a hole's rim to a far corner
/// turn over when the rim is squared (anchor.off: 225 of its faces with ties split, none at
/// 2% of the diagonal). Its vertices are not the input's.
template <class P>
CGAL::Surface_mesh<P> remeshed_for_labels(const CGAL::Surface_mesh<P>& m, double edge_fraction)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  CGAL::Surface_mesh<P> r = m;
  const double diagonal = mesh_bbox_diagonal(r);
  auto sharp = get(CGAL::edge_is_feature, r);
  PMP::detect_sharp_edges(r, 30., sharp);
  PMP::isotropic_remeshing(faces(r), edge_fraction * diagonal, r, CGAL::parameters::edge_is_constrained_map(sharp).number_of_iterations(3));
  r.collect_garbage();
  return r;
}

/// `normal` averaged `iterations` times with the normals of the neighbouring faces across
/// edges under 25 degrees, area-weighted: a remeshed cylinder's faces then change label
/// where its smooth normal does, not where a face's own tilt says.
template <class Mesh>
std::vector<Eigen::Vector3d> smoothed_face_normals(const Mesh& m, std::vector<Eigen::Vector3d> normal,
                                                   const std::vector<double>& area, int iterations)
{
  const double smooth = std::cos(25. * CGAL_PI / 180.);
  for(int it = 0; it < iterations; ++it) {
    std::vector<Eigen::Vector3d> next = normal;
    for(auto f : faces(m)) {
      const std::size_t i = std::size_t(f);
      Eigen::Vector3d sum = normal[i] * area[i];
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        const auto g = face(opposite(h, m), m);
        if(g != Mesh::null_face() && normal[i].dot(normal[std::size_t(g)]) >= smooth) sum += normal[std::size_t(g)] * area[std::size_t(g)];
      }
      if(sum.squaredNorm() > 0.) next[i] = sum.normalized();
    }
    normal = std::move(next);
  }
  return normal;
}

/// The labels of `m` with its tied faces decided (the file's comment), from `nearest` (each
/// face's nearest direction of `frame`, `normal` by face). A face is tied when its two best
/// directions are within `tie` in cosine. `m` is refined where a region is cut by a plane;
/// the labels returned are by face of the refined mesh.
///
/// A region (connected tied faces with one pair {a, b}) is
/// - planar (its normals within 3 degrees): all the planar regions facing the same way take
///   one label, the side of the larger one's cut with more area, largest first (so a face
///   and the bottom of a groove in it agree);
/// - else constrained by its decided neighbours across creases over 30 degrees: a label
///   equal to its neighbour's across a concave crease would fold the feature into the
///   neighbour's chart, the opposite label across a convex crease is a fold, and across a
///   convex crease over 60 degrees (a bore's rim) the neighbour's axis would flatten it: one
///   label left is taken, repeatedly, as decisions spread;
/// - else cut where its relative positions along a and b are equal (the plane
///   (x.a - min)/range = (x.b - min)/range): on a convex region the faces further along a
///   take a, on a concave one (a bore) those further against it, as a box's faces do.
/// A region whose normals span a plane (a cylinder, axis t) then relabels the smooth part of
/// its cylinder (faces with |n.t| < 0.2, across edges under 30 degrees) with the nearest
/// direction off the axis of the label it did not take there.
template <class P>
std::vector<int> tied_labels(CGAL::Surface_mesh<P>& m, const Eigen::Matrix3d& frame, const std::vector<Eigen::Vector3d>& normal,
                             const std::vector<int>& nearest, double tie = 0.05)
{
  using Mesh = CGAL::Surface_mesh<P>;
  using F = typename Mesh::Face_index;
  using V = typename Mesh::Vertex_index;
  const std::size_t nf = num_faces(m);
  const double crease = std::cos(30. * CGAL_PI / 180.), steep = std::cos(60. * CGAL_PI / 180.);
  auto point = [&](V v) {
    const auto& p = m.point(v);
    return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  };
  auto centroid = [&](F f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for(auto v : vertices_around_face(halfedge(f, m), m)) c += point(v) / 3.;
    return c;
  };
  // The tied pair of each face (a * 6 + b, a < b), -1 when not tied.
  std::vector<int> pair(nf, -1);
  for(std::size_t f = 0; f < nf; ++f) {
    std::array<std::pair<double, int>, 6> s;
    for(int l = 0; l < 6; ++l) s[std::size_t(l)] = {normal[f].dot(label_direction(frame, l)), l};
    std::sort(s.begin(), s.end(), [](const auto& x, const auto& y) { return x.first > y.first || (x.first == y.first && x.second < y.second); });
    if(s[0].first - s[1].first < tie) pair[f] = std::min(s[0].second, s[1].second) * 6 + std::max(s[0].second, s[1].second);
  }
  struct Region
  {
    std::array<int, 2> label{};
    std::array<double, 4> range{}; // min and extent of the positions along a, then b
    double area = 0.;
    bool concave = false, planar = false;
    Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis = Eigen::Vector3d::Zero(); // a cylinder's, else zero
    int decided = -2; // -2 open, -1 cut by its plane, else its label
  };
  // The regions: the charts of `pair` among tied faces, numbered in face order, each with
  // its faces in index order.
  std::vector<int> region = label_charts(m, pair);
  std::vector<std::vector<F>> members;
  {
    std::vector<int> number;
    for(auto f : faces(m)) {
      int& r = region[std::size_t(f)];
      if(pair[std::size_t(f)] < 0) {
        r = -1;
        continue;
      }
      if(std::size_t(r) >= number.size()) number.resize(std::size_t(r) + 1, -1);
      if(number[std::size_t(r)] < 0) number[std::size_t(r)] = int(members.size()), members.emplace_back();
      r = number[std::size_t(r)];
      members[std::size_t(r)].push_back(f);
    }
  }
  std::vector<Region> regions;
  for(std::size_t r = 0; r < members.size(); ++r) {
    const F f0 = members[r].front();
    Region R;
    R.label = {pair[std::size_t(f0)] / 6, pair[std::size_t(f0)] % 6};
    const Eigen::Vector3d da = label_direction(frame, R.label[0]), db = label_direction(frame, R.label[1]);
    double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300, turning = 0.;
    Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
    for(F f : members[r]) {
      const std::size_t i = std::size_t(f);
      R.area += CGAL::to_double(CGAL::Polygon_mesh_processing::face_area(f, m));
      R.mean_normal += normal[i];
      tensor += normal[i] * normal[i].transpose();
      for(auto v : vertices_around_face(halfedge(f, m), m)) {
        const Eigen::Vector3d x = point(v);
        a0 = std::min(a0, x.dot(da)), a1 = std::max(a1, x.dot(da)), b0 = std::min(b0, x.dot(db)), b1 = std::max(b1, x.dot(db));
      }
      // Convexity: each edge's signed turning times its length, inner edges once.
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        const F g = face(opposite(h, m), m);
        if(g == Mesh::null_face() || (region[std::size_t(g)] == int(r) && g < f)) continue;
        const Eigen::Vector3d &n1 = normal[i], &n2 = normal[std::size_t(g)], d = point(target(h, m)) - point(source(h, m));
        const double angle = std::acos(std::clamp(n1.dot(n2), -1., 1.));
        turning += (n1.cross(n2).dot(d) > 0. ? angle : -angle) * d.norm();
      }
    }
    R.range = {a0, std::max(a1 - a0, 1e-300), b0, std::max(b1 - b0, 1e-300)};
    R.concave = turning < 0.;
    R.mean_normal.normalize();
    double least = 1.;
    for(F f : members[r]) least = std::min(least, normal[std::size_t(f)].dot(R.mean_normal));
    R.planar = least > std::cos(3. * CGAL_PI / 180.);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(tensor);
    const Eigen::Vector3d ev = eigen.eigenvalues();
    if(!R.planar && ev[0] < 0.02 * ev[2] && ev[1] > 0.05 * ev[2]) R.axis = eigen.eigenvectors().col(0);
    regions.push_back(R);
  }
  const int nr = int(regions.size());
  // > 0 on the side of a region's cut that takes its first label.
  auto side = [&](int r, const Eigen::Vector3d& x) {
    const Region& R = regions[std::size_t(r)];
    const double s = (x.dot(label_direction(frame, R.label[0])) - R.range[0]) / R.range[1] -
                     (x.dot(label_direction(frame, R.label[1])) - R.range[2]) / R.range[3];
    return R.concave ? -s : s;
  };
  auto label_by_cut = [&](int r, const Eigen::Vector3d& x) {
    return regions[std::size_t(r)].label[side(r, x) >= 0. ? 0 : 1];
  };
  // Planar regions, largest first, with all those facing the same way.
  for(;;) {
    int big = -1;
    for(int r = 0; r < nr; ++r)
      if(regions[std::size_t(r)].planar && regions[std::size_t(r)].decided == -2 && (big < 0 || regions[std::size_t(r)].area > regions[std::size_t(big)].area)) big = r;
    if(big < 0) break;
    std::array<double, 2> on{};
    for(F f : members[std::size_t(big)])
      on[side(big, centroid(f)) >= 0. ? 0 : 1] += CGAL::to_double(CGAL::Polygon_mesh_processing::face_area(f, m));
    const int L = regions[std::size_t(big)].label[on[0] >= on[1] ? 0 : 1];
    for(auto& R : regions)
      if(R.planar && R.decided == -2 && R.mean_normal.dot(regions[std::size_t(big)].mean_normal) > std::cos(3. * CGAL_PI / 180.)) R.decided = L;
  }
  // The others, by their decided neighbours across creases, as long as decisions spread.
  auto allowed = [&](int r) {
    const Region& R = regions[std::size_t(r)];
    int ok = 3;
    for(F f : members[std::size_t(r)]) {
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        const F g = face(opposite(h, m), m);
        if(g == Mesh::null_face() || region[std::size_t(g)] == r) continue;
        const int other = region[std::size_t(g)] >= 0 ? regions[std::size_t(region[std::size_t(g)])].decided : nearest[std::size_t(g)];
        const Eigen::Vector3d &n1 = normal[std::size_t(f)], &n2 = normal[std::size_t(g)];
        if(other < 0 || n1.dot(n2) > crease) continue;
        const bool convex = n1.cross(n2).dot(point(target(h, m)) - point(source(h, m))) > 0.;
        for(int i = 0; i < 2; ++i) {
          const int c = R.label[std::size_t(i)];
          const bool excluded = convex ? c / 2 == other / 2 && (n1.dot(n2) < steep || c != other) : c == other;
          if(excluded) ok &= ~(1 << i);
        }
      }
    }
    return ok;
  };
  for(bool spread = true; spread;) {
    spread = false;
    for(int r = 0; r < nr; ++r) {
      if(regions[std::size_t(r)].decided != -2) continue;
      const int ok = allowed(r);
      if(ok == 1 || ok == 2) regions[std::size_t(r)].decided = regions[std::size_t(r)].label[ok == 1 ? 0 : 1], spread = true;
      else if(ok == 0) regions[std::size_t(r)].decided = -1, spread = true;
    }
  }
  for(auto& R : regions)
    if(R.decided == -2) R.decided = -1;
  // Cut the regions left open along their planes: the crossed edges split where the side
  // function is zero (the surface does not move).
  auto parent = m.template add_property_map<F, std::size_t>("f:parent", std::size_t(0)).first;
  for(auto f : faces(m)) parent[f] = std::size_t(f);
  for(int r = 0; r < nr; ++r) {
    if(regions[std::size_t(r)].decided != -1) continue;
    std::vector<std::pair<std::array<V, 2>, double>> splits;
    for(auto e : edges(m)) {
      const auto h = halfedge(e, m);
      const F f1 = face(h, m), f2 = face(opposite(h, m), m);
      if(!((f1 != Mesh::null_face() && region[parent[f1]] == r) || (f2 != Mesh::null_face() && region[parent[f2]] == r))) continue;
      double x = side(r, point(source(h, m))), y = side(r, point(target(h, m)));
      if(std::abs(x) < 1e-3) x = 0.;
      if(std::abs(y) < 1e-3) y = 0.;
      if((x < 0. && y > 0.) || (x > 0. && y < 0.)) splits.push_back({{{source(h, m), target(h, m)}}, x / (x - y)});
    }
    for(const auto& sp : splits) split_edge_at(m, halfedge(sp.first[0], sp.first[1], m).first, sp.second);
  }
  std::vector<int> label(num_faces(m));
  for(auto f : faces(m)) {
    const int r = region[parent[f]];
    label[std::size_t(f)] = r < 0 ? nearest[parent[f]] : regions[std::size_t(r)].decided >= 0 ? regions[std::size_t(r)].decided : label_by_cut(r, centroid(f));
  }
  // Each cylinder's smooth part follows its decision.
  const auto [now_normal, now_area] = face_normals_and_areas(m);
  for(int r = 0; r < nr; ++r) {
    const Region& R = regions[std::size_t(r)];
    if(R.axis.squaredNorm() == 0.) continue;
    std::vector<bool> seen(num_faces(m), false);
    std::vector<F> stack;
    for(auto f : faces(m))
      if(region[parent[f]] == r) stack.push_back(f), seen[std::size_t(f)] = true;
    std::vector<F> cylinder = stack;
    while(!stack.empty()) {
      const F f = stack.back();
      stack.pop_back();
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        const F g = face(opposite(h, m), m);
        if(g == Mesh::null_face() || seen[std::size_t(g)]) continue;
        if(now_normal[std::size_t(f)].dot(now_normal[std::size_t(g)]) < crease || std::abs(now_normal[std::size_t(g)].dot(R.axis)) > 0.2) continue;
        if(region[parent[g]] >= 0 && region[parent[g]] != r) continue;
        seen[std::size_t(g)] = true;
        stack.push_back(g);
        cylinder.push_back(g);
      }
    }
    for(F f : cylinder) {
      const int taken = R.decided >= 0 ? R.decided : label_by_cut(r, centroid(f));
      const int other = taken == R.label[0] ? R.label[1] : R.label[0];
      int best = -1;
      double best_dot = -2.;
      for(int l = 0; l < 6; ++l) {
        const double d = now_normal[std::size_t(f)].dot(label_direction(frame, l));
        if(l / 2 != other / 2 && d > best_dot) best_dot = d, best = l;
      }
      label[std::size_t(f)] = best;
    }
  }
  m.remove_property_map(parent);
  // Teeth: a face with no neighbour of its label, or one only across a crease, goes to the
  // neighbouring label its normal prefers (one that two neighbours share first).
  for(int sweep = 0; sweep < 5; ++sweep) {
    bool changed = false;
    for(auto f : faces(m)) {
      const std::size_t i = std::size_t(f);
      int same = 0;
      bool across_crease = false;
      std::array<int, 6> count{};
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        const F g = face(opposite(h, m), m);
        if(g == Mesh::null_face()) continue;
        if(label[std::size_t(g)] == label[i]) {
          ++same;
          across_crease = across_crease || now_normal[i].dot(now_normal[std::size_t(g)]) < crease;
        } else
          ++count[std::size_t(label[std::size_t(g)])];
      }
      if(same > 1) continue;
      int best = -1;
      double score = -1e300;
      for(int l = 0; l < 6; ++l) {
        if(count[std::size_t(l)] == 0) continue;
        const double s = now_normal[i].dot(label_direction(frame, l)) + (count[std::size_t(l)] > 1 ? 1. : 0.);
        if(s > score) score = s, best = l;
      }
      if(best >= 0 && (same == 0 || across_crease || count[std::size_t(best)] > 1)) label[i] = best, changed = true;
    }
    if(!changed) break;
  }
  return label;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_TIED_LABELS_H
