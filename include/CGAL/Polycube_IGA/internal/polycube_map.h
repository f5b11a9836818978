// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A polycube map of a closed surface: every face labelled with the nearest of the six
// directions of a frame, the labels cleaned into charts, and the surface deformed so that
// each chart lies on one plane perpendicular to its direction. The deformed surface is an
// orthogonal polyhedron, whose boxes (orthogonal_grid.h), carried back to the surface, make
// a layout that follows the shape's own directions: a CAD part's round holes, fillets and
// slanted faces, which no harmonic cut of the pants path follows. The method is that of the
// L1 polycube family (Gregson, Sheffer and Zhang 2011; Huang et al. 2014), read to learn;
// here the labelling is smoothed by iterated conditional modes and the deformation is one
// linear least-squares solve per axis, which keeps every edge's offset along that axis
// while each chart's vertices share one coordinate. Read by the cuboid decomposition
// (Cuboid_decomposition::polycube_blocks()).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_POLYCUBE_MAP_H
#define CGAL_POLYCUBE_IGA_INTERNAL_POLYCUBE_MAP_H

#include <CGAL/Polycube_IGA/internal/bbox_diagonal.h>
#include <CGAL/Polycube_IGA/internal/edge_length.h>
#include <CGAL/Polycube_IGA/internal/label_charts.h>
#include <CGAL/Polycube_IGA/internal/mesh_pieces.h>
#include <CGAL/Polycube_IGA/internal/min_cut.h>
#include <CGAL/Polycube_IGA/internal/orthogonal_grid.h>
#include <CGAL/Polycube_IGA/internal/tied_labels.h>
#include <CGAL/Polycube_IGA/internal/triangle_projection.h>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// A frame's fit to a surface: the area-weighted mean of each normal's largest component
/// (1 for an orthogonal polyhedron, about 0.83 for a sphere in any frame).
inline double frame_alignment(const Eigen::Matrix3d& frame, const std::vector<Eigen::Vector3d>& normal,
                              const std::vector<double>& area)
{
  double s = 0., a = 0.;
  for(std::size_t f = 0; f < normal.size(); ++f) s += area[f] * (frame * normal[f]).cwiseAbs().maxCoeff(), a += area[f];
  return a > 0. ? s / a : 0.;
}

/// A CAD part's own axes (rows, right-handed). The first: of the 64 largest faces' normals,
/// the one (up to its sign) with the most area within 2 degrees, not the largest face's,
/// which on a part with fillets can be one of theirs, a few degrees off the flat faces. The
/// second: of the faces perpendicular to the first, the direction (modulo a quarter turn)
/// that holds the most area, unless no direction holds a fifth of it (round sides: a
/// cylinder's faceting makes the peak) and `spread` (the surface's second moments) is given:
/// then the direction, across the first, in which the surface extends furthest. Empty for a
/// surface without area.
inline std::optional<Eigen::Matrix3d> flat_faces_frame(const std::vector<Eigen::Vector3d>& normal, const std::vector<double>& area,
                                                       const Eigen::Matrix3d* spread = nullptr)
{
  const double pi = 3.14159265358979323846;
  std::vector<std::size_t> order(normal.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  const std::size_t tried = std::min<std::size_t>(64, order.size());
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(tried), order.end(),
                    [&](std::size_t a, std::size_t b) { return area[a] > area[b] || (area[a] == area[b] && a < b); });
  std::optional<Eigen::Vector3d> first;
  double most = 0.;
  for(std::size_t c = 0; c < tried; ++c) {
    const Eigen::Vector3d& n = normal[order[c]];
    if(n.squaredNorm() == 0.) continue;
    double held = 0.;
    for(std::size_t i = 0; i < normal.size(); ++i)
      if(std::abs(normal[i].dot(n)) > std::cos(2. * pi / 180.)) held += area[i];
    if(held > most) most = held, first = n;
  }
  if(!first) return std::nullopt;
  const Eigen::Vector3d a0 = *first, u = a0.unitOrthogonal(), w = a0.cross(u);
  {
    const int bins = 180; // half a degree each
    std::vector<double> held(bins, 0.);
    std::vector<double> angle(normal.size(), -1.);
    for(std::size_t i = 0; i < normal.size(); ++i) {
      if(!(std::abs(normal[i].dot(a0)) < std::sin(2. * pi / 180.)) || normal[i].squaredNorm() == 0.) continue;
      double t = std::atan2(normal[i].dot(w), normal[i].dot(u));
      t = std::fmod(t + 2. * pi, 0.5 * pi);
      angle[i] = t;
      held[std::size_t(std::min(bins - 1, int(t / (0.5 * pi) * bins)))] += area[i];
    }
    const int peak = int(std::max_element(held.begin(), held.end()) - held.begin());
    const double centre = (peak + 0.5) * 0.5 * pi / bins;
    double sum = 0., weight = 0., across = 0.;
    for(std::size_t i = 0; i < normal.size(); ++i) {
      if(angle[i] < 0.) continue;
      across += area[i];
      double d = angle[i] - centre;
      d -= 0.5 * pi * std::round(d / (0.5 * pi));
      if(std::abs(d) <= 1.5 * 0.5 * pi / bins) sum += area[i] * d, weight += area[i];
    }
    double t = centre + (weight > 0. ? sum / weight : 0.);
    // A mug's body: its side's facets make the peak (3% of the side's area), 20 degrees off
    // the plane of its handle, whose labels then meet at a corner no polycube has. Flat sides
    // hold 68% (a box with three holes) to 99.5% (a cube with crossing holes).
    if(spread && weight < 0.2 * across) {
      const Eigen::Matrix2d s{{u.dot(*spread * u), u.dot(*spread * w)}, {w.dot(*spread * u), w.dot(*spread * w)}};
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(s);
      const Eigen::Vector2d e = eig.eigenvectors().col(1);
      // A spread nearly round across a0 (a plain cylinder) has no furthest direction: its
      // eigenvector is rounding noise, so the facets' peak stays.
      if(eig.eigenvalues()[1] > 1.1 * eig.eigenvalues()[0]) t = std::atan2(e.y(), e.x());
    }
    Eigen::Matrix3d g;
    g.row(0) = a0.transpose();
    g.row(1) = (std::cos(t) * u + std::sin(t) * w).transpose();
    g.row(2) = a0.cross(g.row(1).transpose()).transpose();
    return g;
  }
}

/// The frame for the labels, of three candidates: flat_faces_frame(), unless the eigenvectors
/// of the area-weighted normal tensor (the directions the surface mostly faces) or the
/// principal axes of the surface (an organic shape's length, width and depth) have a
/// frame_alignment() better by 0.02.
template <class Mesh>
Eigen::Matrix3d polycube_frame(const Mesh& m, const std::vector<Eigen::Vector3d>& normal, const std::vector<double>& area)
{
  std::vector<Eigen::Matrix3d> candidates;
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero(), spread = Eigen::Matrix3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double total = 0.;
  std::vector<Eigen::Vector3d> centroid(normal.size());
  for(auto f : faces(m)) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for(auto v : vertices_around_face(halfedge(f, m), m)) {
      const auto& p = m.point(v);
      c += Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())) / 3.;
    }
    centroid[std::size_t(f)] = c;
    centre += area[std::size_t(f)] * c, total += area[std::size_t(f)];
  }
  if(!(total > 0.)) return Eigen::Matrix3d::Identity();
  centre /= total;
  for(std::size_t f = 0; f < normal.size(); ++f) {
    tensor += area[f] * normal[f] * normal[f].transpose();
    const Eigen::Vector3d d = centroid[f] - centre;
    spread += area[f] * d * d.transpose();
  }
  if(std::optional<Eigen::Matrix3d> f = flat_faces_frame(normal, area, &spread)) candidates.push_back(*f);
  for(const Eigen::Matrix3d& s : {tensor, spread}) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(s);
    Eigen::Matrix3d f = eig.eigenvectors().transpose();
    if(f.determinant() < 0.) f.row(2) *= -1.;
    candidates.push_back(f);
  }
  // The flat faces' frame unless another fits clearly better: on a CAD part with fillets
  // the normal tensor's axes can lean a few degrees off its flat faces.
  std::size_t best = 0;
  for(std::size_t c = 1; c < candidates.size(); ++c)
    if(frame_alignment(candidates[c], normal, area) > frame_alignment(candidates[best], normal, area) + 0.02) best = c;
  return candidates[best];
}

/// How nearly `m` is an orthogonal polyhedron: the frame_alignment() of its polycube_frame()
/// (over 0.95 for a CAD part with fillets or round holes, about 0.83 to 0.9 for an organic
/// shape), and whether every face's normal is within `angle_degrees` of one of the frame's
/// axes (a CAD block, which orthogonal_blocks() splits as it is).
template <class Mesh>
std::pair<double, bool> polycube_alignment(const Mesh& m, double angle_degrees = 2.)
{
  const auto [normal, area] = face_normals_and_areas(m);
  const Eigen::Matrix3d frame = polycube_frame(m, normal, area);
  const double along = std::cos(angle_degrees * 3.14159265358979323846 / 180.);
  bool aligned = true;
  for(const Eigen::Vector3d& n : normal) aligned = aligned && (n.squaredNorm() == 0. || (frame * n).cwiseAbs().maxCoeff() >= along);
  return {frame_alignment(frame, normal, area), aligned};
}

/// Gives each chart of `label` smaller than `minimum_chart` of the surface's area to the
/// neighbouring label it shares the longest border with, smallest first, until none is left.
template <class Mesh>
void merge_small_charts(const Mesh& m, const std::vector<double>& area, std::vector<int>& label, double minimum_chart)
{
  const std::size_t nf = num_faces(m);
  const double total_area = std::accumulate(area.begin(), area.end(), 0.);
  for(int round = 0; round < 100; ++round) {
    int n = 0;
    const std::vector<int> chart = label_charts(m, label, &n);
    std::vector<double> chart_area(std::size_t(n), 0.);
    for(std::size_t f = 0; f < nf; ++f) chart_area[std::size_t(chart[f])] += area[f];
    int smallest = -1;
    for(int c = 0; c < n; ++c)
      if(chart_area[std::size_t(c)] < minimum_chart * total_area && (smallest < 0 || chart_area[std::size_t(c)] < chart_area[std::size_t(smallest)]))
        smallest = c;
    if(smallest < 0) break;
    std::array<double, 6> border{};
    for(auto f : faces(m)) {
      if(chart[std::size_t(f)] != smallest) continue;
      for(auto hh : halfedges_around_face(halfedge(f, m), m)) {
        const auto g = face(opposite(hh, m), m);
        if(g != Mesh::null_face() && chart[std::size_t(g)] != smallest) border[std::size_t(label[std::size_t(g)])] += edge_length(m, hh);
      }
    }
    int to = -1;
    for(int l = 0; l < 6; ++l)
      if(border[std::size_t(l)] > 0. && (to < 0 || border[std::size_t(l)] > border[std::size_t(to)])) to = l;
    if(to < 0) break; // the whole surface is one chart
    for(std::size_t f = 0; f < nf; ++f)
      if(chart[f] == smallest) label[f] = to;
  }
}

/// The labels of the faces of `m` in `frame`: each face's nearest direction, smoothed by
/// iterated conditional modes when `border_weight` is positive (a face takes the label of
/// least area-weighted normal deviation plus `border_weight` times its border length times
/// the mean edge length, opposite labels side by side three times that, until no face
/// changes), then charts smaller than `minimum_chart` of the area given to the neighbouring
/// label they share the longest border with. Faces are visited in index order: the result
/// is deterministic.
template <class Mesh>
std::vector<int> polycube_labels(const Mesh& m, const Eigen::Matrix3d& frame, const std::vector<Eigen::Vector3d>& normal,
                                 const std::vector<double>& area, double border_weight = 0., double minimum_chart = 2e-3)
{
  const std::size_t nf = num_faces(m);
  std::vector<int> label(nf, 0);
  double total_length = 0.;
  for(auto e : edges(m)) total_length += edge_length(m, halfedge(e, m));
  const double h = total_length / double(std::max<std::size_t>(1, num_edges(m)));
  for(std::size_t f = 0; f < nf; ++f) {
    double best = -2.;
    for(int l = 0; l < 6; ++l) {
      const double d = normal[f].dot(label_direction(frame, l));
      if(d > best + 1e-12) best = d, label[f] = l;
    }
  }
  // A border between two labels costs its length times the mean edge length (an area);
  // between opposite labels three times that, a fold the polycube cannot have.
  auto pair_cost = [](int a, int b) { return a == b ? 0. : (a / 2 == b / 2 ? 3. : 1.); };
  for(int sweep = 0; sweep < 50 && border_weight > 0.; ++sweep) {
    bool changed = false;
    for(auto f : faces(m)) {
      const std::size_t i = std::size_t(f);
      auto energy = [&](int l) {
        double e = area[i] * (1. - normal[i].dot(label_direction(frame, l)));
        for(auto hh : halfedges_around_face(halfedge(f, m), m)) {
          const auto g = face(opposite(hh, m), m);
          if(g != Mesh::null_face()) e += border_weight * h * edge_length(m, hh) * pair_cost(l, label[std::size_t(g)]);
        }
        return e;
      };
      // The face's own label sets the bar, so a tie never changes it (against infinity, as
      // once, the tolerance was NaN and no face ever changed).
      double best = energy(label[i]);
      int chosen = label[i];
      for(int l = 0; l < 6; ++l) {
        if(l == label[i]) continue;
        const double e = energy(l);
        if(e < best - 1e-15 * (1. + std::abs(best))) best = e, chosen = l;
      }
      if(chosen != label[i]) label[i] = chosen, changed = true;
    }
    if(!changed) break;
  }
  merge_small_charts(m, area, label, minimum_chart);
  return label;
}

/// Labels of the faces of `m` in `frame` of least energy by alpha-expansion graph cuts
/// (Boykov, Veksler and Zabih, PAMI 2001; the labelling of PolyCut, Livesu et al. 2013, read
/// to learn), from the nearest labels: each face's area-weighted normal deviation from its
/// label plus, for each border edge, its length times `border_weight` times the square root
/// of the surface's area, twice that between opposite labels (the most that keeps the
/// border cost a metric, so that each expansion move is an exact minimum cut). Against
/// polycube_labels()' sweeps, a move re-labels a whole region at once, so a chart can change
/// sides where face by face every step would cost. The scale is the surface's, not its
/// edges': on a coarse mesh (joint.off, 446 faces) the mean edge length made every border
/// dearer than any chart and left one label. Charts smaller than `minimum_chart` of the area
/// are then merged (merge_small_charts()). Deterministic: moves in label order, cycles until
/// none lowers the energy (at most 10).
template <class Mesh>
std::vector<int> expansion_labels(const Mesh& m, const Eigen::Matrix3d& frame, const std::vector<Eigen::Vector3d>& normal,
                                  const std::vector<double>& area, double border_weight, double minimum_chart = 2e-3)
{
  const int nf = int(num_faces(m));
  std::vector<int> label = polycube_labels(m, frame, normal, area, 0., 0.);
  const double scale = border_weight * std::sqrt(std::accumulate(area.begin(), area.end(), 0.));
  auto pair_cost = [](int a, int b) { return a == b ? 0. : (a / 2 == b / 2 ? 2. : 1.); };
  auto deviation = [&](int f, int l) { return area[std::size_t(f)] * (1. - normal[std::size_t(f)].dot(label_direction(frame, l))); };
  struct Dual_edge { int p, q; double w; };
  std::vector<Dual_edge> dual;
  for(auto e : edges(m)) {
    const auto h = halfedge(e, m);
    const auto f = face(h, m), g = face(opposite(h, m), m);
    if(f != Mesh::null_face() && g != Mesh::null_face()) dual.push_back({int(f), int(g), scale * edge_length(m, h)});
  }
  auto energy = [&](const std::vector<int>& l) {
    double E = 0.;
    for(int f = 0; f < nf; ++f) E += deviation(f, l[std::size_t(f)]);
    for(const Dual_edge& d : dual) E += d.w * pair_cost(l[std::size_t(d.p)], l[std::size_t(d.q)]);
    return E;
  };
  double E = energy(label);
  for(int cycle = 0; cycle < 10; ++cycle) {
    bool lowered = false;
    for(int alpha = 0; alpha < 6; ++alpha) {
      // Node f on the source side keeps its label, on the sink side takes alpha. Per edge, the
      // cost is A (both keep), B (p keeps, q takes), C (p takes, q keeps), D = 0 (both take):
      // A + (C - A) [p takes] + (D - C) [q takes] + (B + C - A - D) [p keeps, q takes].
      Min_cut cut(nf + 2);
      const int s = nf, t = nf + 1;
      std::vector<double> keep(static_cast<std::size_t>(nf)), take(static_cast<std::size_t>(nf));
      for(int f = 0; f < nf; ++f) keep[std::size_t(f)] = deviation(f, label[std::size_t(f)]), take[std::size_t(f)] = deviation(f, alpha);
      for(const Dual_edge& d : dual) {
        const int a = label[std::size_t(d.p)], b = label[std::size_t(d.q)];
        const double A = d.w * pair_cost(a, b), B = d.w * pair_cost(a, alpha), C = d.w * pair_cost(alpha, b);
        take[std::size_t(d.p)] += C - A;
        take[std::size_t(d.q)] -= C;
        const double W = B + C - A; // >= 0: the cost is a metric
        if(W > 0.) cut.add_directed(d.p, d.q, W);
      }
      for(int f = 0; f < nf; ++f) {
        const double x = take[std::size_t(f)] - keep[std::size_t(f)];
        if(x > 0.) cut.add_directed(s, f, x);
        else if(x < 0.) cut.add_directed(f, t, -x);
      }
      cut.max_flow(s, t);
      const std::vector<char> side = cut.source_side(s);
      std::vector<int> moved = label;
      for(int f = 0; f < nf; ++f)
        if(!side[std::size_t(f)]) moved[std::size_t(f)] = alpha;
      const double E_moved = energy(moved);
      if(E_moved < E - 1e-12 * std::abs(E)) E = E_moved, label = std::move(moved), lowered = true;
    }
    if(!lowered) break;
  }
  merge_small_charts(m, area, label, minimum_chart);
  return label;
}

/// Splits each edge whose two faces share a label but whose two ends both lie on chart
/// borders, at its middle: a triangle with its three corners on one border would otherwise
/// be flattened onto that border's line. `label` follows the split faces.
template <class P>
void split_edges_between_borders(CGAL::Surface_mesh<P>& m, std::vector<int>& label)
{
  using Mesh = CGAL::Surface_mesh<P>;
  using F = typename Mesh::Face_index;
  auto parent = m.template add_property_map<F, std::size_t>("f:parent", std::size_t(0)).first;
  for(auto f : faces(m)) parent[f] = std::size_t(label[std::size_t(f)]);
  std::vector<bool> on_border(num_vertices(m), false);
  for(auto e : edges(m)) {
    const auto h = halfedge(e, m);
    if(label[std::size_t(face(h, m))] != label[std::size_t(face(opposite(h, m), m))])
      on_border[std::size_t(source(h, m))] = on_border[std::size_t(target(h, m))] = true;
  }
  std::vector<typename Mesh::Halfedge_index> splits;
  for(auto e : edges(m)) {
    const auto h = halfedge(e, m);
    if(label[std::size_t(face(h, m))] == label[std::size_t(face(opposite(h, m), m))] && on_border[std::size_t(source(h, m))] &&
       on_border[std::size_t(target(h, m))])
      splits.push_back(h);
  }
  for(auto h : splits) split_edge_at(m, h, 0.5);
  label.assign(num_faces(m), 0);
  for(auto f : faces(m)) label[std::size_t(f)] = int(parent[f]);
  m.remove_property_map(parent);
}

/// The coordinates along axis `k` of the vertices of `m` (`x0`: their original ones in the
/// frame) that give every edge (source to target) its `offset` along it best in the
/// least-squares sense while the
/// vertices of each chart facing along that axis share one coordinate (charts meeting at a
/// vertex share it too), and so do the charts whose coordinates `snap` (as solved without
/// it, when given) puts within `snap_distance` of each other and that face the same way
/// (either way, with `across_ways`).
template <class P>
std::optional<std::vector<double>> polycube_axis(const CGAL::Surface_mesh<P>& m, const std::vector<Eigen::Vector3d>& x0,
                                                 const std::vector<Eigen::Vector3d>& offset, const std::vector<int>& label, int k,
                                                 const std::vector<double>* snap = nullptr, double snap_distance = 0.,
                                                 bool across_ways = false)
{
  const std::size_t nv = num_vertices(m);
  std::vector<std::size_t> root(nv);
  std::iota(root.begin(), root.end(), std::size_t(0));
  auto find = [&](std::size_t a) {
    while(root[a] != a) a = root[a] = root[root[a]];
    return a;
  };
  auto unite = [&](std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if(a != b) root[std::max(a, b)] = std::min(a, b);
  };
  std::vector<int> faces_way(nv, 0); // per vertex: 1 along the axis, 2 against it
  for(auto f : faces(m)) {
    const int l = label[std::size_t(f)];
    if(l / 2 != k) continue;
    const auto h = halfedge(f, m);
    for(auto v : vertices_around_face(h, m)) unite(std::size_t(v), std::size_t(target(h, m))), faces_way[std::size_t(v)] |= 1 << (l % 2);
  }
  if(snap) {
    // Charts one way, nearly level: one plane (two walls of two holes in a row, the two
    // halves of a bar on either side of a stem), or the planes between them cut thin boxes
    // and run through the solid.
    std::map<std::size_t, int> way;
    for(std::size_t v = 0; v < nv; ++v)
      if(faces_way[v]) way[find(v)] |= faces_way[v];
    std::vector<std::pair<double, std::size_t>> level;
    for(const auto& c : way)
      if(c.second != 3) level.push_back({(*snap)[c.first], c.first});
    std::sort(level.begin(), level.end());
    for(int w = 1; w <= (across_ways ? 1 : 2); ++w) {
      std::optional<std::pair<double, std::size_t>> last;
      for(const auto& c : level) {
        if(!across_ways && way[c.second] != w) continue;
        if(last && c.first - last->first <= snap_distance) unite(last->second, c.second);
        last = c;
      }
    }
  }
  std::vector<int> unknown(nv, -1);
  int n = 0;
  for(std::size_t v = 0; v < nv; ++v)
    if(unknown[find(v)] < 0) unknown[find(v)] = n++;
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for(auto e : edges(m)) {
    const auto h = halfedge(e, m);
    const std::size_t a = std::size_t(source(h, m)), b = std::size_t(target(h, m));
    const int i = unknown[find(a)], j = unknown[find(b)];
    if(i == j) continue;
    const double d = -offset[std::size_t(e)][k];
    t.emplace_back(i, i, 1.), t.emplace_back(j, j, 1.), t.emplace_back(i, j, -1.), t.emplace_back(j, i, -1.);
    rhs[i] += d, rhs[j] -= d;
  }
  // A faint pull to the original coordinates fixes the translation.
  std::vector<double> count(std::size_t(n), 0.), sum(std::size_t(n), 0.);
  for(std::size_t v = 0; v < nv; ++v) count[std::size_t(unknown[find(v)])] += 1., sum[std::size_t(unknown[find(v)])] += x0[v][k];
  const double weak = 1e-6;
  for(int i = 0; i < n; ++i) t.emplace_back(i, i, weak * count[std::size_t(i)]), rhs[i] += weak * sum[std::size_t(i)];
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if(solver.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXd x = solver.solve(rhs);
  if(solver.info() != Eigen::Success || !x.allFinite()) return std::nullopt;
  std::vector<double> out(nv);
  for(std::size_t v = 0; v < nv; ++v) out[v] = x[unknown[find(v)]];
  return out;
}

/// The faces of `m` that `q` (positions in the frame, by vertex) does not make face their
/// label's way with an area that is not negligible.
template <class P>
std::vector<typename CGAL::Surface_mesh<P>::Face_index> turned_faces(const CGAL::Surface_mesh<P>& m, const std::vector<int>& label,
                                                                     const std::vector<Eigen::Vector3d>& q)
{
  Eigen::Vector3d lo = q.empty() ? Eigen::Vector3d::Zero() : q[0], hi = lo;
  for(const auto& p : q) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double diagonal = (hi - lo).norm();
  std::vector<typename CGAL::Surface_mesh<P>::Face_index> out;
  for(auto f : faces(m)) {
    std::array<Eigen::Vector3d, 3> x;
    std::size_t i = 0;
    for(auto v : vertices_around_face(halfedge(f, m), m)) x[i++] = q[std::size_t(v)];
    const Eigen::Vector3d n = (x[1] - x[0]).cross(x[2] - x[0]);
    const int l = label[std::size_t(f)];
    if(!((l % 2 ? -1. : 1.) * n[l / 2] > 1e-12 * diagonal * diagonal)) out.push_back(f);
  }
  return out;
}

/// By vertex of `m`: bit k set when a face of it has a label on axis k, so that its
/// coordinate along k is its chart's (fixed); the others are free.
template <class P>
std::vector<int> chart_fixed_axes(const CGAL::Surface_mesh<P>& m, const std::vector<int>& label)
{
  std::vector<int> fixed(num_vertices(m), 0);
  for(auto f : faces(m))
    for(auto v : vertices_around_face(halfedge(f, m), m)) fixed[std::size_t(v)] |= 1 << (label[std::size_t(f)] / 2);
  return fixed;
}

/// By vertex of `m`: its ring round the faces `around` (0: a corner of one of them, r: r
/// edges from the nearest), up to `rings`; -1 beyond.
template <class P>
std::vector<int> rings_round_faces(const CGAL::Surface_mesh<P>& m, const std::vector<typename CGAL::Surface_mesh<P>::Face_index>& around,
                                   int rings)
{
  using V = typename CGAL::Surface_mesh<P>::Vertex_index;
  std::vector<int> ring_of(num_vertices(m), -1);
  std::vector<V> ring;
  for(auto f : around)
    for(auto v : vertices_around_face(halfedge(f, m), m))
      if(ring_of[std::size_t(v)] < 0) ring_of[std::size_t(v)] = 0, ring.push_back(v);
  for(int r = 1; r <= rings; ++r) {
    std::vector<V> next_ring;
    for(V v : ring)
      for(V w : vertices_around_target(halfedge(v, m), m))
        if(ring_of[std::size_t(w)] < 0) ring_of[std::size_t(w)] = r, next_ring.push_back(w);
    ring = std::move(next_ring);
  }
  return ring_of;
}

/// Smooths the free coordinates (those of the axes that none of its faces' labels is on) of
/// the vertices near the turned faces of `q` towards the mean of their neighbours', a few
/// rings at a time, until no face is turned or `sweeps` are done: a reflex corner of a
/// chart, where a fillet was, otherwise keeps the triangles that spanned the fillet across
/// the corner. Returns whether no face is turned.
template <class P>
bool unfold_polycube(const CGAL::Surface_mesh<P>& m, const std::vector<int>& label, std::vector<Eigen::Vector3d>& q, int sweeps = 200)
{
  using V = typename CGAL::Surface_mesh<P>::Vertex_index;
  const std::vector<int> fixed = chart_fixed_axes(m, label);
  for(int sweep = 0; sweep < sweeps; ++sweep) {
    const auto turned = turned_faces(m, label, q);
    if(turned.empty()) return true;
    const std::vector<int> ring_of = rings_round_faces(m, turned, 2);
    for(V v : vertices(m)) {
      if(ring_of[std::size_t(v)] < 0 || fixed[std::size_t(v)] == 7) continue;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      double count = 0.;
      for(V w : vertices_around_target(halfedge(v, m), m)) mean += q[std::size_t(w)], count += 1.;
      for(int k = 0; k < 3; ++k)
        if(!(fixed[std::size_t(v)] & (1 << k))) q[std::size_t(v)][k] = mean[k] / count;
    }
  }
  return turned_faces(m, label, q).empty();
}

/// The heights of vertex `v` of `m` over the opposite sides of its faces, as functions of its
/// free coordinates (bit k of `fixed`: axis k is a chart's, not free): one row (c, d) per
/// face, height c . x + d > 0 when the face faces its label's way, x its free coordinates
/// in axis order (one or two). Rows whose face `v` cannot turn (c = 0) are left out.
template <class P>
std::vector<std::pair<Eigen::Vector2d, double>> star_heights(const CGAL::Surface_mesh<P>& m, const std::vector<int>& label,
                                                            const std::vector<Eigen::Vector3d>& q,
                                                            typename CGAL::Surface_mesh<P>::Vertex_index v, int fixed)
{
  std::vector<std::pair<Eigen::Vector2d, double>> rows;
  for(auto h : halfedges_around_target(halfedge(v, m), m)) {
    const auto f = face(h, m);
    if(f == CGAL::Surface_mesh<P>::null_face()) continue;
    // (a - v) x (b - v) = a x b + v x (a - b), v a b the face's corners in order.
    const Eigen::Vector3d& a = q[std::size_t(target(next(h, m), m))];
    const Eigen::Vector3d& b = q[std::size_t(source(h, m))];
    const int l = label[std::size_t(f)], k = l / 2, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const double s = l % 2 ? -1. : 1.;
    const Eigen::Vector3d w = a - b;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    c[k1] = s * w[k2], c[k2] = -s * w[k1];
    double d = s * a.cross(b)[k];
    Eigen::Vector2d free = Eigen::Vector2d::Zero();
    int n = 0;
    for(int i = 0; i < 3; ++i) {
      if(fixed & (1 << i)) d += c[i] * q[std::size_t(v)][i];
      else if(n < 2) free[n++] = c[i];
    }
    const double norm = free.norm();
    if(norm > 0.) rows.push_back({free / norm, d / norm});
  }
  return rows;
}

/// Moves each free coordinate of the vertices near the faces that `q` turns over to the
/// point deepest inside its star's kernel (the Chebyshev centre of the half-planes of
/// star_heights(), bounded softly by its neighbours' box), when that is deeper than where
/// it is: a vertex whose neighbours all lie on a chart's reflex border (the middle of an
/// edge that cut a fillet's corner) is then set inside the corner, where averaging puts it
/// on the border. A move never turns more faces of its star over. Returns whether no face
/// is turned.
template <class P>
bool untangle_polycube(const CGAL::Surface_mesh<P>& m, const std::vector<int>& label, std::vector<Eigen::Vector3d>& q, int sweeps = 50)
{
  using V = typename CGAL::Surface_mesh<P>::Vertex_index;
  const std::vector<int> fixed = chart_fixed_axes(m, label);
  // A labelling that no moves untangle (a smooth shape's) stops after 20 sweeps without
  // fewer faces turned: its sweeps cost a linear program per vertex near each turned face.
  std::size_t fewest = std::numeric_limits<std::size_t>::max();
  int stalled = 0;
  for(int sweep = 0; sweep < sweeps; ++sweep) {
    const auto turned = turned_faces(m, label, q);
    if(turned.empty()) return true;
    if(turned.size() < fewest) fewest = turned.size(), stalled = 0;
    else if(++stalled == 20) break;
    // Ring 0: the corners of turned faces, moved only while their stars are turned. Every
    // ten sweeps one more ring round them is centred too, to make room.
    const std::vector<int> ring_of = rings_round_faces(m, turned, sweep / 10);
    bool moved = false;
    for(V v : vertices(m)) {
      const int fx = fixed[std::size_t(v)];
      if(ring_of[std::size_t(v)] < 0 || fx == 7) continue;
      std::vector<int> axis;
      for(int i = 0; i < 3; ++i)
        if(!(fx & (1 << i))) axis.push_back(i);
      const int dim = int(axis.size());
      Eigen::Vector2d x = Eigen::Vector2d::Zero();
      for(int i = 0; i < dim; ++i) x[i] = q[std::size_t(v)][axis[std::size_t(i)]];
      auto rows = star_heights(m, label, q, v, fx);
      if(rows.empty()) continue;
      double now = std::numeric_limits<double>::infinity();
      for(const auto& r : rows) now = std::min(now, r.first.dot(x) + r.second);
      const std::size_t faces = rows.size();
      // The neighbours' box keeps an unbounded kernel (a convex corner) from sending it off.
      // Its sides are rows like the faces' (x - lo >= t): a star still turned (t < 0) may
      // leave the box by its depth, and sweeps can carry a vertex far off (a probe's labels
      // on a remeshed anchor.off: ten times the part's size), which is_polycube() refuses.
      // A hard box (x >= lo) left more faces turned on 13 of the 17 refused maps of the test
      // and benchmark meshes (anchor.off 438 -> 531; fewer only on cad_spoked_wheel.off,
      // 5871 -> 139, and cad_tee_solid.off, 32 -> 18; none became a polycube) and moved the
      // vertices of 3 of the 17 polycubes, so the box stays soft.
      Eigen::Vector2d lo = x, hi = x;
      for(V w : vertices_around_target(halfedge(v, m), m))
        for(int i = 0; i < dim; ++i)
          lo[i] = std::min(lo[i], q[std::size_t(w)][axis[std::size_t(i)]]), hi[i] = std::max(hi[i], q[std::size_t(w)][axis[std::size_t(i)]]);
      if(ring_of[std::size_t(v)] == 0 && now > 1e-9 * (hi - lo).norm()) continue; // its star is not turned (any more)
      for(int i = 0; i < dim; ++i) {
        Eigen::Vector2d e = Eigen::Vector2d::Zero();
        e[i] = 1.;
        rows.push_back({e, -lo[i]}), rows.push_back({-e, hi[i]});
      }
      // The centre is a vertex of the (dim + 1)-dimensional problem max t, c . x + d >= t:
      // dim + 1 rows active.
      double best = now;
      Eigen::Vector2d best_x = x;
      const std::size_t n = rows.size();
      auto consider = [&](const Eigen::Vector2d& y, double t) {
        if(!(t > best) || !y.allFinite()) return;
        for(const auto& r : rows)
          if(r.first.dot(y) + r.second < t - 1e-12 * (1. + std::abs(t))) return;
        best = t, best_x = y;
      };
      if(dim == 1) {
        for(std::size_t i = 0; i < n; ++i)
          for(std::size_t j = i + 1; j < n; ++j) {
            const double a = rows[i].first[0], b = rows[j].first[0];
            if(std::abs(a - b) < 1e-12) continue;
            const double y = (rows[j].second - rows[i].second) / (a - b);
            consider(Eigen::Vector2d(y, 0.), a * y + rows[i].second);
          }
      } else {
        for(std::size_t i = 0; i < n; ++i)
          for(std::size_t j = i + 1; j < n; ++j)
            for(std::size_t k = j + 1; k < n; ++k) {
              Eigen::Matrix3d A;
              Eigen::Vector3d rhs;
              std::size_t row = 0;
              for(std::size_t r : {i, j, k}) {
                A.row(row) << rows[r].first.x(), rows[r].first.y(), -1.;
                rhs[row++] = -rows[r].second;
              }
              const Eigen::FullPivLU<Eigen::Matrix3d> lu(A);
              if(!lu.isInvertible()) continue;
              const Eigen::Vector3d y = lu.solve(rhs);
              consider(y.head<2>(), y[2]);
            }
      }
      // A star that no point untangles may still get deeper, if no more of its faces turn.
      auto turned_in_star = [&](const Eigen::Vector2d& y) {
        return std::count_if(rows.begin(), rows.begin() + std::ptrdiff_t(faces), [&](const auto& r) { return !(r.first.dot(y) + r.second > 0.); });
      };
      if(best > now && best_x != x && (best > 0. || turned_in_star(best_x) <= turned_in_star(x))) {
        for(int i = 0; i < dim; ++i) q[std::size_t(v)][axis[std::size_t(i)]] = best_x[i];
        moved = true;
      }
    }
    if(!moved) break;
  }
  return turned_faces(m, label, q).empty();
}

/// Whether `q` (positions in the frame, by vertex) makes `m` a polycube for its labels
/// after untangle_polycube() (or, if that leaves faces turned, unfold_polycube() and
/// untangle_polycube() again), which may move `q`: no face turned, the surface not through
/// itself.
template <class P>
bool is_polycube(const CGAL::Surface_mesh<P>& m, const std::vector<int>& label, std::vector<Eigen::Vector3d>& q,
                 std::string* why = nullptr)
{
  if(!untangle_polycube(m, label, q) && !(unfold_polycube(m, label, q) || untangle_polycube(m, label, q))) {
    if(why) *why = std::to_string(turned_faces(m, label, q).size()) + " of its faces turned over or flat";
    return false;
  }
  CGAL::Surface_mesh<P> deformed = m;
  for(auto v : vertices(deformed)) deformed.point(v) = P(q[std::size_t(v)].x(), q[std::size_t(v)].y(), q[std::size_t(v)].z());
  if(!CGAL::Polygon_mesh_processing::does_self_intersect(deformed)) return true;
  if(why) *why = "it passes through itself";
  return false;
}

/// The polycube positions (world coordinates, by vertex) of `m` with labels `label` in
/// `frame`: polycube_axis() for each axis, then again with the charts that face one way
/// within `snap` of the polycube's extent along their axis on one plane, if that is still a
/// polycube (else axis by axis, within `snap`, a quarter and a sixteenth of it), then, axis
/// by axis, charts facing either way within half, a quarter or an eighth of `snap`, where
/// that is still one. Empty when the unsnapped positions are no polycube (is_polycube(),
/// whose reason goes to `why`, and the positions, in the frame, to `refused`).
template <class P>
std::optional<std::vector<Eigen::Vector3d>> polycube_positions(const CGAL::Surface_mesh<P>& m, const Eigen::Matrix3d& frame,
                                                               const std::vector<int>& label, double snap = 0.05,
                                                               std::string* why = nullptr,
                                                               std::vector<Eigen::Vector3d>* refused = nullptr)
{
  const std::size_t nv = num_vertices(m);
  std::vector<Eigen::Vector3d> x0(nv);
  for(auto v : vertices(m)) {
    const auto& p = m.point(v);
    x0[std::size_t(v)] = frame * Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  // Each edge's offset turned with its faces: each face by the least rotation that takes its
  // normal to its label's direction, the two turned edges averaged. The charts are then flat
  // in the offsets already, and the solve has less to bend (a fillet's faces, 45 degrees
  // off, would otherwise pull the vertices of its two charts across each other).
  std::vector<Eigen::Matrix3d> turn(num_faces(m), Eigen::Matrix3d::Identity());
  for(auto f : faces(m)) {
    std::array<Eigen::Vector3d, 3> x;
    std::size_t i = 0;
    for(auto v : vertices_around_face(halfedge(f, m), m)) x[i++] = x0[std::size_t(v)];
    const Eigen::Vector3d n = (x[1] - x[0]).cross(x[2] - x[0]);
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d[label[std::size_t(f)] / 2] = label[std::size_t(f)] % 2 ? -1. : 1.;
    if(n.squaredNorm() > 0.) turn[std::size_t(f)] = Eigen::Quaterniond::FromTwoVectors(n.normalized(), d).toRotationMatrix();
  }
  std::vector<Eigen::Vector3d> offset(num_edges(m));
  for(auto e : edges(m)) {
    const auto h = halfedge(e, m);
    const Eigen::Vector3d x = x0[std::size_t(target(h, m))] - x0[std::size_t(source(h, m))];
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for(auto g : {face(h, m), face(opposite(h, m), m)})
      if(g != CGAL::Surface_mesh<P>::null_face()) sum += turn[std::size_t(g)] * x, ++count;
    offset[std::size_t(e)] = count ? Eigen::Vector3d(sum / count) : x;
  }
  std::array<std::vector<double>, 3> free;
  for(int k = 0; k < 3; ++k) {
    std::optional<std::vector<double>> x = polycube_axis(m, x0, offset, label, k);
    if(!x) return std::nullopt;
    free[std::size_t(k)] = std::move(*x);
  }
  auto positions = [&](const std::array<std::vector<double>, 3>& c) {
    std::vector<Eigen::Vector3d> q(nv);
    for(std::size_t v = 0; v < nv; ++v) q[v] = Eigen::Vector3d(c[0][v], c[1][v], c[2][v]);
    return q;
  };
  auto extent = [&](int k) {
    const auto range = std::minmax_element(free[std::size_t(k)].begin(), free[std::size_t(k)].end());
    return *range.second - *range.first;
  };
  std::array<std::vector<double>, 3> snapped;
  for(int k = 0; k < 3; ++k) {
    std::optional<std::vector<double>> x = polycube_axis(m, x0, offset, label, k, &free[std::size_t(k)], snap * extent(k));
    if(x) snapped[std::size_t(k)] = std::move(*x);
  }
  std::vector<Eigen::Vector3d> q;
  if(!snapped[0].empty() && !snapped[1].empty() && !snapped[2].empty()) q = positions(snapped);
  // Axis k of `c` snapped again (its levels as `c` has them) at the first of `fractions` of
  // `snap` that leaves a polycube, `q` its positions; else both unchanged. `c` is always a
  // polycube and `q` its positions, so a snap that merges nothing more needs no check.
  auto snap_axis = [&](std::array<std::vector<double>, 3>& c, int k, std::initializer_list<double> fractions, bool across_ways) {
    for(double fraction : fractions) {
      std::optional<std::vector<double>> x = polycube_axis(m, x0, offset, label, k, &c[std::size_t(k)], fraction * snap * extent(k), across_ways);
      if(!x) continue;
      if(*x == c[std::size_t(k)]) return;
      std::array<std::vector<double>, 3> t = c;
      t[std::size_t(k)] = std::move(*x);
      std::vector<Eigen::Vector3d> p = positions(t);
      if(is_polycube(m, label, p)) {
        c = std::move(t), q = std::move(p);
        return;
      }
    }
  };
  std::array<std::vector<double>, 3> levels = snapped;
  if(q.empty() || !is_polycube(m, label, q)) {
    q = positions(free);
    if(!is_polycube(m, label, q, why)) {
      if(refused) *refused = std::move(q);
      return std::nullopt;
    }
    // One axis at a time, nearer levels if need be: one axis's snap can fold what another's
    // would not (a probe on anchor.off whose groove's walls all took their crease rules'
    // labels, not kept: 351 boxes unsnapped, 146 so).
    levels = free;
    for(int k = 0; k < 3; ++k) snap_axis(levels, k, {1., 0.25, 0.0625}, false);
  }
  // Charts facing opposite ways, nearly level, on one plane too, if that leaves a polycube:
  // otherwise the slab between them is a strip of boxes through the solid (anchor.off: its
  // bore's wall 0.6% of the extent from its groove's floor, a strip patch with a reflex
  // corner at the groove's bottom; 95 boxes, 21 of 325 volume patches uncertified; 85 boxes
  // so, and all 297 patches certified).
  for(int k = 0; k < 3; ++k) snap_axis(levels, k, {0.5, 0.25, 0.125}, true);
  for(auto& p : q) p = frame.transpose() * p;
  return q;
}

/// A polycube map of the closed surface `mesh` as the cuboid decomposition makes it, step by
/// step, for Cuboid_decomposition::polycube_blocks() and for showing why a map is refused
/// (`polycube_iga polycube`): the frame and the faces' alignment with it, the labels, the
/// mesh with the edges between chart borders split, and the polycube positions, or the
/// reason there are none and the faces the deformation left turned over or flat.
///
/// The labels are the nearest directions with small charts merged, not smoothed (see
/// polycube_blocks()); when those make no polycube, expansion_labels() at border weights
/// 0.01 and then 0.02, and the first polycube is kept, else the nearest labels' refusal
/// with the others' reasons after it. No map that is a polycube on the nearest labels
/// changes. On the 49 closed test, benchmark and shared CAD meshes, 18 were polycubes on
/// the nearest labels; 5 of the other 31 are on graph-cut labels (3holes.obj and
/// double-torus-example.off at 0.01, the benchmark's solid T and banana at 0.01, its blobby
/// shape with four limbs at 0.02); faces turned on the 26 still refused, nearest -> 0.01 ->
/// 0.02: eight.off 39 -> 10 -> 3, ring4.off 25 -> 10 -> 5, chain5.off 22 -> 3 -> 13,
/// rotor.off 34 -> 14 -> 65, anchor.off 438 -> 239 -> 265, fandisk.off 25 -> 169 -> 190,
/// femur.off 4468 -> 228 -> 203 (weights 0.03 to 0.06, on five of them, made one more:
/// torus.obj at 0.06). Last, tied_labels() on remeshed copies (remeshed_for_labels(), at
/// edges of 2%, 2.5% and 3% of the diagonal, the normals as they are and smoothed twice,
/// smoothed_face_normals()), made for a CAD part's 45-degree features: 10 more of the 49
/// are polycubes so (anchor.off, 438 faces turned on its nearest labels, on its copy at 2.5%
/// with smoothed normals; chain5, chain6, plate5, plate6, and five benchmark shapes). A
/// refused map costs more, by 3 to 57 times the nearest labels' alone (wheel3.off 0.07 ->
/// 3.6 s; 3torus.off, 46 faces, 0.01 -> 21 s, remeshed five times;
/// `polycube_iga_benchmark polycube`); a map that is a polycube on them costs the same.
template <class P>
struct Polycube_map_attempt
{
  CGAL::Surface_mesh<P> mesh; ///< the input (or its remeshed copy) with the edges between borders split
  Eigen::Matrix3d frame;      ///< rows: the axes
  double alignment = 0.;      ///< frame_alignment() of the input's faces
  std::vector<int> label;     ///< by face of `mesh`: axis 2k (+) or 2k + 1 (-)
  double border_weight = 0.;  ///< 0: the nearest labels; else expansion_labels()' weight
  /// 0: `mesh` is the input's; else tied_labels() on its copy remeshed to edges of this
  /// fraction of the diagonal (its vertices are not the input's)
  double remeshed_edge = 0.;
  int normal_smoothing = 0; ///< smoothed_face_normals() iterations for tied_labels()
  int charts = 0;             ///< label_charts() count
  std::optional<std::vector<Eigen::Vector3d>> position; ///< world coordinates, by vertex
  std::vector<Eigen::Vector3d> refused_position; ///< world coordinates, when `position` is empty
  std::vector<bool> turned; ///< by face, of `refused_position`
  std::string why;          ///< when `position` is empty: the nearest labels' reason, then the others'

  /// The faces the refused deformation left turned over or flat (0 for a polycube).
  std::size_t faces_turned() const { return std::size_t(std::count(turned.begin(), turned.end(), true)); }
};

/// The rest of an attempt once its labels are set: the edges between borders split, the
/// charts counted, the polycube positions or the refusal with its turned faces.
template <class P>
void deform_to_labels(Polycube_map_attempt<P>& a)
{
  const Eigen::Matrix3d& frame = a.frame;
  split_edges_between_borders(a.mesh, a.label);
  label_charts(a.mesh, a.label, &a.charts);
  std::vector<Eigen::Vector3d> refused;
  a.position = polycube_positions(a.mesh, frame, a.label, 0.05, &a.why, &refused);
  if(!a.position && !refused.empty()) {
    a.turned.assign(num_faces(a.mesh), false);
    for(auto f : turned_faces(a.mesh, a.label, refused)) a.turned[std::size_t(f)] = true;
    for(auto& p : refused) p = frame.transpose() * p;
    a.refused_position = std::move(refused);
  }
}

/// One polycube map of `input` in `frame` (its faces' `normal` and `area` given): the nearest
/// labels when `border_weight` is 0, else expansion_labels() at that weight.
template <class P>
Polycube_map_attempt<P> polycube_map_on_labels(const CGAL::Surface_mesh<P>& input, const Eigen::Matrix3d& frame,
                                               const std::vector<Eigen::Vector3d>& normal, const std::vector<double>& area,
                                               double border_weight)
{
  Polycube_map_attempt<P> a;
  a.frame = frame;
  a.alignment = frame_alignment(frame, normal, area);
  a.border_weight = border_weight;
  a.mesh = input;
  a.label = border_weight > 0. ? expansion_labels(a.mesh, frame, normal, area, border_weight)
                               : polycube_labels(a.mesh, frame, normal, area, 0.);
  deform_to_labels(a);
  return a;
}

/// The map on a copy of `input` remeshed to edges of `edge_fraction` of its diagonal, its
/// tied faces decided by tied_labels() (normals smoothed `smoothing` times for that), small
/// charts merged as for the nearest labels.
template <class P>
Polycube_map_attempt<P> polycube_map_on_tied_labels(const CGAL::Surface_mesh<P>& input, const Eigen::Matrix3d& frame,
                                                    double alignment, double edge_fraction, int smoothing)
{
  Polycube_map_attempt<P> a;
  a.frame = frame;
  a.alignment = alignment;
  a.remeshed_edge = edge_fraction;
  a.normal_smoothing = smoothing;
  a.mesh = remeshed_for_labels(input, edge_fraction);
  {
    const auto [normal, area] = face_normals_and_areas(a.mesh);
    const std::vector<Eigen::Vector3d> smooth = smoothed_face_normals(a.mesh, normal, area, smoothing);
    a.label = tied_labels(a.mesh, frame, smooth, polycube_labels(a.mesh, frame, smooth, area, 0., 0.));
  }
  const auto [normal, area] = face_normals_and_areas(a.mesh);
  merge_small_charts(a.mesh, area, a.label, 2e-3);
  deform_to_labels(a);
  return a;
}

template <class P>
Polycube_map_attempt<P> polycube_map_attempt(const CGAL::Surface_mesh<P>& input)
{
  const auto [normal, area] = face_normals_and_areas(input);
  const Eigen::Matrix3d frame = polycube_frame(input, normal, area);
  Polycube_map_attempt<P> nearest = polycube_map_on_labels(input, frame, normal, area, 0.);
  for(double w : {0.01, 0.02}) {
    if(nearest.position) break;
    Polycube_map_attempt<P> smoothed = polycube_map_on_labels(input, frame, normal, area, w);
    if(smoothed.position) return smoothed;
    std::ostringstream said;
    said << "; with graph-cut labels at border weight " << w << ": " << smoothed.why;
    nearest.why += said.str();
  }
  if(nearest.position) return nearest;
  for(const auto& [edge, smoothing] : {std::pair<double, int>{0.02, 0}, {0.025, 2}, {0.02, 2}, {0.025, 0}, {0.03, 2}}) {
    Polycube_map_attempt<P> tied = polycube_map_on_tied_labels(input, frame, nearest.alignment, edge, smoothing);
    if(tied.position) return tied;
    std::ostringstream said;
    said << "; with tied faces decided on a copy remeshed to " << 100. * edge << "% of the diagonal" << (smoothing ? ", normals smoothed" : "")
         << ": " << tied.why;
    nearest.why += said.str();
  }
  return nearest;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_POLYCUBE_MAP_H
