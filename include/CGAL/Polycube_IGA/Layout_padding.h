// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A boundary layer ("padding") for the layout volume.
//
// Why: where two SURFACE sides of one cuboid meet along an arc of a smooth surface, their
// tangent planes agree, so the three partial derivatives of the cuboid's map lie in one
// plane along that arc and det J -> 0 there; any fitting error makes it negative. This is
// what spoils the volumes of the sphere's cube and of the pants' arms (reference §4.1 and
// its §Limitations show the same symptom). The cure, as in polycube hexahedral meshing
// ("pillowing", a layer of cells under the surface), is to move the polycube inward and to
// fill the gap with one slab per SURFACE patch:
//
//   * every node n gets an inner node n' = n - d_n N_n (N_n the outward unit normal averaged
//     over the surface patches at n, d_n = thickness x the shortest arc at n, but at most a
//     third of the solid's thickness under n (or at its arc neighbours where a ray from n
//     leaves through a cut end), so thin parts keep a core between two layers,
//     and changing by at most 5% of an arc's length along it, so inner arcs stay nearly
//     parallel to their outer arcs);
//   * every arc a gets an inner arc a' (the chord of its inner nodes plus half the arc's
//     deviation from its own chord: straight arcs and flat faces stay so, round ones get
//     half as round; an arc that bulges into the solid by more than the layer's depth,
//     around a hole, keeps enough of it to stay inside) and a wall: the quad between a and
//     a', closed by the straight radial segments n -> n';
//   * where a core or slab corner at an inner node is flat or folded (its three edge
//     tangents nearly coplanar: a node on the smooth middle of an interface's cycle), the
//     inner arcs' ends there are turned towards their chords (open_inner_corners()); one
//     still folded (a node amid a flat face, whose inner arcs all leave in one plane) is
//     lifted to half its depth, so that its faces meet at a ridge there;
//   * every patch p gets an inner patch p' spanned by the inner arcs of its sides (the
//     discrete Coons patch of its border plus a quarter of p's own relief over its Coons
//     patch);
//   * the core cuboids are the layout's cuboids on the inner nodes, arcs and patches; the
//     slab of a SURFACE patch p has p on top, p' below and the walls of p's arcs around.
//
// Every slab touches the surface with one side only and its walls leave the surface at
// about a right angle; the core's edges are inner arcs whose faces are Coons patches, which
// meet at a crease rather than tangentially. The result is again a Polycube_layout (nodes
// 0..n-1 outer, n..2n-1 inner) with its Patch_grids, so layout_volume() builds, glues and
// measures it like any other; inner nodes reuse their outer node's vertex as a placeholder
// (the geometry of the padded layout is in its grids, not on the mesh).

#ifndef CGAL_POLYCUBE_IGA_LAYOUT_PADDING_H
#define CGAL_POLYCUBE_IGA_LAYOUT_PADDING_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Patch_sampling.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/internal/bbox_diagonal.h>
#include <CGAL/Polycube_IGA/internal/cuboid_frames.h>
#include <CGAL/Polycube_IGA/internal/triangle_projection.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Dense>

#include <cmath>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Options of pad_layout().
struct Padding_options
{
  /// Depth of the layer at a node, as a fraction of the shortest arc at that node.
  double thickness = 0.25;
  /// At most this fraction of the solid's thickness below the node (the distance to the
  /// mesh along the inward normal); 0 disables the cap.
  double maximum_thickness_fraction = 1. / 3.;
  /// Along an arc, the depth changes by at most this fraction of the arc's length (but at
  /// a node lifted by folded_corner_lift).
  double maximum_depth_slope = 0.05;
  /// Where a core or slab corner at an inner node has a scaled det (of its three edge
  /// tangents) below this, the inner arcs' end tangents there are turned to raise the
  /// smallest one (internal::open_inner_corners()); 0 keeps the inner arcs as built.
  double corner_threshold = 0.3;
  /// The largest turn (degrees) of an inner arc's end tangent by open_inner_corners().
  double maximum_corner_turn = 30.;
  /// An inner patch is the Coons patch of its inner arcs plus this fraction of its outer
  /// patch's relief (the outer grid minus the Coons patch of its own border).
  double inner_relief = 0.25;
  /// An inner node whose worst corner is still folded after the corners are opened is placed
  /// at this fraction of its depth, where that raises the corner (pad_layout()); 1: never.
  double folded_corner_lift = 0.5;
};

/// A padded layout: the layout of cores and slabs, its grids, and where each cuboid came from.
template <class Point_3>
struct Padded_layout
{
  Polycube_layout<Point_3> layout;
  Patch_grids samples;
  /// Per cuboid of `layout`: the cuboid of the original layout it is the core of, or -1.
  std::vector<long> core_of;
  /// Per cuboid of `layout`: the SURFACE patch of the original layout it is the slab of, or -1.
  std::vector<long> slab_of;
  /// The nodes whose inner node was lifted (Padding_options::folded_corner_lift), in order.
  std::vector<std::size_t> lifted_nodes;
};

namespace internal {

/// Unit normal grid u x grid v at (i, j), by central differences (one-sided on the border);
/// zero where the grid is degenerate.
inline Eigen::Vector3d grid_normal(const Point_grid& g, int i, int j)
{
  const int nu = g.size_u - 1, nv = g.size_v - 1;
  const Eigen::Vector3d du = g(std::min(i + 1, nu), j) - g(std::max(i - 1, 0), j);
  const Eigen::Vector3d dv = g(i, std::min(j + 1, nv)) - g(i, std::max(j - 1, 0));
  const Eigen::Vector3d n = du.cross(dv);
  const double l = n.norm();
  return l > 0. ? Eigen::Vector3d(n / l) : Eigen::Vector3d::Zero();
}

/// Ray casts and closest faces on the surface mesh, for the inner nodes (one AABB tree), and
/// closest points for the grid relaxation (Grid_relaxation.h) on a plain-double copy of the
/// mesh (a second tree, and walks over the copy), built unless `closest_points` is false.
template <class Mesh>
class Mesh_probe
{
  using Point = typename boost::property_traits<typename boost::property_map<Mesh, CGAL::vertex_point_t>::const_type>::value_type;
  using K = typename CGAL::Kernel_traits<Point>::Kernel;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>>;
  // Closest points are constructions, in doubles with either kernel. A tree search's pruning
  // test (sphere against box) is a filtered exact predicate in K whose filter fails for small
  // spheres; with plain doubles a box within rounding of the sphere may be skipped, which can
  // only lose a face as close as the best one to within rounding. The walks of
  // closest_point(p, from) run on the same plain copy.
  using Fast_kernel = CGAL::Simple_cartesian<double>;
  using Fast_mesh = CGAL::Surface_mesh<Fast_kernel::Point_3>;
  using Fast_tree = CGAL::AABB_tree<CGAL::AABB_traits<Fast_kernel, CGAL::AABB_face_graph_triangle_primitive<Fast_mesh>>>;

public:
  explicit Mesh_probe(const Mesh& mesh, bool closest_points = true)
    : mesh_(mesh), tree_(faces(mesh).first, faces(mesh).second, mesh)
  {
    if(faces(mesh).empty()) return;
    offset_ = 1e-7 * internal::bbox_diagonal(tree_.bbox());
    tree_.accelerate_distance_queries();
    if(!closest_points) return;
    // A copy whose face k is the k-th face of `mesh` (its normal is normals_[k]).
    std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, typename Fast_mesh::Vertex_index> copy;
    for(auto v : vertices(mesh)) {
      const Point& q = get(CGAL::vertex_point, mesh, v);
      copy[v] = fast_mesh_.add_vertex(Fast_kernel::Point_3(CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())));
    }
    for(auto f : faces(mesh)) {
      std::vector<typename Fast_mesh::Vertex_index> vs;
      for(auto v : vertices_around_face(halfedge(f, mesh), mesh)) vs.push_back(copy[v]);
      if(fast_mesh_.add_face(vs) == Fast_mesh::null_face()) throw Internal_error("probe_copy_failed", "the surface mesh could not be copied for closest points");
      normals_.push_back(unit_face_normal(mesh, f));
    }
    fast_tree_ = std::make_unique<Fast_tree>(faces(fast_mesh_).first, faces(fast_mesh_).second, fast_mesh_);
    fast_tree_->accelerate_distance_queries();
  }

  /// The distance along -normal from `p` to the first face (a ray cast from just below `p`,
  /// which skips the faces at `p` itself); infinity where the ray leaves without a hit.
  double thickness(const Eigen::Vector3d& p, const Eigen::Vector3d& normal) const
  {
    if(faces(mesh_).empty()) return std::numeric_limits<double>::infinity();
    const Eigen::Vector3d o = p - offset_ * normal;
    const typename K::Ray_3 ray(Point(o.x(), o.y(), o.z()), typename K::Vector_3(-normal.x(), -normal.y(), -normal.z()));
    const auto hit = tree_.first_intersection(ray);
    if(hit)
      if(const Point* q = boost::get<Point>(&hit->first)) return offset_ + std::sqrt(CGAL::to_double(CGAL::squared_distance(*q, ray.source())));
    return std::numeric_limits<double>::infinity();
  }

  /// The unit normal (the mesh's orientation) of the face closest to `p`.
  Eigen::Vector3d closest_face_normal(const Eigen::Vector3d& p) const
  {
    if(faces(mesh_).empty()) return Eigen::Vector3d::Zero();
    return unit_face_normal(mesh_, tree_.closest_point_and_primitive(Point(p.x(), p.y(), p.z())).second);
  }

  using Hint = typename Fast_tree::Point_and_primitive_id;
  /// A point of the mesh, the unit normal of its face, and itself as a hint for the next query.
  struct Surface_point
  {
    Eigen::Vector3d point, normal;
    Hint hint;
  };

  /// The point of the mesh closest to `p` (the mesh must have faces; the probe built with
  /// `closest_points`).
  Surface_point closest_point(const Eigen::Vector3d& p) const
  {
    CGAL_precondition(fast_tree_ != nullptr);
    return surface_point(fast_tree_->closest_point_and_primitive(as_fast_point(p)));
  }

  /// The point of the mesh closest to `p` found by walking from `from` (an earlier answer,
  /// for a point that moved a little) across the edge or around the vertex that holds the
  /// current closest point, while a face there is closer: a local closest point, which stays
  /// on `from`'s side of a thin wall. One to a few faces are tested where a tree search
  /// visits dozens of boxes (the grid relaxation asks millions of these). A walk longer than
  /// the mesh's face count ends in a search of the whole tree.
  Surface_point closest_point(const Eigen::Vector3d& p, const Surface_point& from) const
  {
    CGAL_precondition(fast_tree_ != nullptr);
    using Face = typename Fast_mesh::Face_index;
    using Halfedge = typename Fast_mesh::Halfedge_index;
    auto project = [&](Face f, std::array<Halfedge, 3>& h) {
      h[0] = fast_mesh_.halfedge(f);
      h[1] = fast_mesh_.next(h[0]);
      h[2] = fast_mesh_.next(h[1]);
      std::array<Eigen::Vector3d, 3> t;
      for(std::size_t k = 0; k < 3; ++k) {
        const auto& q = fast_mesh_.point(fast_mesh_.source(h[k]));
        t[k] = Eigen::Vector3d(q.x(), q.y(), q.z());
      }
      return project_on_triangle(p, t);
    };
    Face f = from.hint.second;
    std::array<Halfedge, 3> h;
    Triangle_projection best = project(f, h);
    double d = (best.point - p).squaredNorm();
    const std::size_t longest = fast_mesh_.number_of_faces();
    for(std::size_t step = 0; best.vertex >= 0 || best.edge >= 0; ++step) {
      if(step > longest) return closest_point(p);
      Face next = Fast_mesh::null_face();
      Triangle_projection next_best;
      std::array<Halfedge, 3> next_h;
      auto consider = [&](Face g) {
        if(g == Fast_mesh::null_face() || g == f) return;
        std::array<Halfedge, 3> hg;
        const Triangle_projection q = project(g, hg);
        const double dg = (q.point - p).squaredNorm();
        if(dg < d) {
          d = dg;
          next = g;
          next_best = q;
          next_h = hg;
        }
      };
      if(best.edge >= 0)
        consider(fast_mesh_.face(fast_mesh_.opposite(h[std::size_t(best.edge)])));
      else
        for(Face g : CGAL::faces_around_target(fast_mesh_.prev(h[std::size_t(best.vertex)]), fast_mesh_)) consider(g);
      if(next == Fast_mesh::null_face()) break;
      f = next;
      best = next_best;
      h = next_h;
    }
    const Eigen::Vector3d& x = best.point;
    return {x, normals_[std::size_t(f)], Hint(Fast_kernel::Point_3(x.x(), x.y(), x.z()), f)};
  }

private:
  static Fast_kernel::Point_3 as_fast_point(const Eigen::Vector3d& p) { return Fast_kernel::Point_3(p.x(), p.y(), p.z()); }

  Surface_point surface_point(const Hint& h) const
  {
    const auto& q = h.first;
    return {Eigen::Vector3d(q.x(), q.y(), q.z()), normals_[std::size_t(h.second)], h};
  }

  const Mesh& mesh_;
  Tree tree_;
  double offset_ = 0.;
  Fast_mesh fast_mesh_;
  std::unique_ptr<Fast_tree> fast_tree_;
  std::vector<Eigen::Vector3d> normals_; ///< per face, with fast_tree_
};

/// A corner of a cuboid of a padded layout at an inner node: its three edge arcs.
struct Inner_corner
{
  std::array<std::size_t, 3> arcs{}; ///< edge arcs along u, v, w from the corner's node
  int sign = 1;                      ///< +1 where (u, v, w) is right-handed in a sound cuboid
};

/// Per node of a padded layout (inner nodes nn..2nn-1 only), the cuboid corners there.
template <class Layout>
std::vector<std::vector<Inner_corner>> inner_corners(const Layout& L, std::size_t nn)
{
  const std::vector<int> handed = frame_handedness(L);
  std::vector<std::vector<Inner_corner>> corners(L.nodes.size());
  for(std::size_t c = 0; c < L.cuboids.size(); ++c) {
    const auto& cu = L.cuboids[c];
    if(handed[c] == 0) continue;
    std::vector<std::size_t> own; // the cuboid's arcs, to tell apart arcs with the same ends
    for(std::size_t p : cu.patches)
      for(std::size_t a : L.patches[p].arcs) own.push_back(a);
    auto arc_between = [&](std::size_t n0, std::size_t n1) -> long {
      for(std::size_t a : own) {
        const auto& e = L.arcs[a].nodes;
        if(e[0] != e[1] && ((e[0] == n0 && e[1] == n1) || (e[0] == n1 && e[1] == n0))) return long(a);
      }
      return -1;
    };
    for(int q = 0; q < 8; ++q) {
      const std::size_t n = cu.nodes[std::size_t(q)];
      if(n < nn) continue;
      Inner_corner ic;
      ic.sign = handed[c] * (((q & 1) + ((q >> 1) & 1) + (q >> 2)) % 2 ? -1 : 1);
      bool ok = true;
      for(int d = 0; d < 3 && ok; ++d) {
        const long a = arc_between(n, cu.nodes[std::size_t(q ^ (1 << d))]);
        ok = a >= 0;
        if(ok) ic.arcs[std::size_t(d)] = std::size_t(a);
      }
      if(ok) corners[n].push_back(ic);
    }
  }
  return corners;
}

/// The end tangents of a padded layout's arcs, and the worst corner at a node: the smallest
/// signed det of its corners' three unit edge tangents (1 for a cube's corner, <= 0 folded).
template <class Layout>
class Corner_tangents
{
public:
  Corner_tangents(const Layout& L, const std::vector<std::vector<Eigen::Vector3d>>& arc_samples, std::size_t nn)
    : L_(L), corners_(inner_corners(L, nn)), tangent_(L.arcs.size())
  {
    for(std::size_t a = 0; a < L.arcs.size(); ++a)
      for(int e = 0; e < 2; ++e) tangent_[a][std::size_t(e)] = end_tangent(arc_samples[a], e == 0);
  }
  Eigen::Vector3d& at(std::size_t a, std::size_t n) { return tangent_[a][L_.arcs[a].nodes[0] == n ? 0 : 1]; }
  bool has_corners(std::size_t n) const { return !corners_[n].empty(); }
  double worst(std::size_t n)
  {
    double w = std::numeric_limits<double>::infinity();
    for(const Inner_corner& ic : corners_[n])
      w = std::min(w, ic.sign * at(ic.arcs[0], n).dot(at(ic.arcs[1], n).cross(at(ic.arcs[2], n))));
    return w;
  }

private:
  const Layout& L_;
  std::vector<std::vector<Inner_corner>> corners_;
  std::vector<std::array<Eigen::Vector3d, 2>> tangent_;
};

/// Turns the end tangents of inner arcs (na..2na-1, between inner nodes nn..2nn-1) so that
/// the cuboid corners at inner nodes open up. Why: an inner arc is its chord plus half the
/// outer arc's bulge (pad_layout()), so it leaves its node about as the outer arc leaves the
/// surface; where the layout puts a node on the smooth middle of an interface's cycle, the
/// two arcs of that cycle leave the inner node in almost opposite directions, the core's
/// corner there is flat (a face angle near 180 degrees) and its det J <= 0 (eight.off: 5
/// cores, although the chords there make sound corners). Per inner node whose worst corner
/// (Corner_tangents) is below `threshold`, each incident inner arc's end tangent d is moved,
/// one arc at a time, along the pencil towards (and past) its chord c,
/// t = normalise(d + beta (c - d)), beta in [-0.5, 1.5] by 0.25, turning by at most
/// `maximum_turn` degrees, to the value that most raises the node's worst corner; three passes.
/// The turn is bounded because the bend below is not seen by the corners: on mushroom.off's
/// thin rim, larger turns fold a slab. The samples are then bent near that end by a Hermite
/// bump over half the arc, so the first sample step points along t and the arc's other half
/// is unchanged. Deterministic (nodes, arcs and betas in index order).
template <class Layout>
void open_inner_corners(const Layout& L, std::vector<std::vector<Eigen::Vector3d>>& arc_samples, std::size_t na, std::size_t nn,
                        double threshold, double maximum_turn)
{
  if(arc_samples.empty() || arc_samples.front().size() < 3) return;
  Corner_tangents<Layout> T(L, arc_samples, nn);
  const int N = int(arc_samples.front().size()) - 1;
  const int half = std::max(1, N / 2);
  const double cos_turn = std::cos(maximum_turn * 3.14159265358979323846 / 180.);
  for(std::size_t n = nn; n < L.nodes.size(); ++n) {
    if(!T.has_corners(n) || !(T.worst(n) < threshold)) continue;
    std::vector<std::size_t> free; // inner arcs at n
    for(std::size_t a = na; a < 2 * na && a < L.arcs.size(); ++a)
      if((L.arcs[a].nodes[0] == n) != (L.arcs[a].nodes[1] == n)) free.push_back(a);
    std::vector<Eigen::Vector3d> start, chord;
    for(std::size_t a : free) {
      start.push_back(T.at(a, n));
      const auto& s = arc_samples[a];
      const Eigen::Vector3d c = L.arcs[a].nodes[0] == n ? Eigen::Vector3d(s.back() - s.front()) : Eigen::Vector3d(s.front() - s.back());
      chord.push_back(c.norm() > 0. ? Eigen::Vector3d(c.normalized()) : start.back());
    }
    double best = T.worst(n);
    for(int pass = 0; pass < 3; ++pass)
      for(std::size_t f = 0; f < free.size(); ++f) {
        Eigen::Vector3d keep = T.at(free[f], n);
        for(int b = -2; b <= 6; ++b) {
          const Eigen::Vector3d t = start[f] + 0.25 * b * (chord[f] - start[f]);
          if(!(t.norm() > 1e-9) || t.normalized().dot(start[f]) < cos_turn) continue;
          T.at(free[f], n) = t.normalized();
          const double w = T.worst(n);
          if(w > best + 1e-12) best = w, keep = T.at(free[f], n);
        }
        T.at(free[f], n) = keep;
      }
    // Bend each turned arc near this end: s_k += phi(k) (|e| t - e), e its first step, with
    // phi(0) = 0, phi(1) = 1 and phi and its slope vanishing at k = half (a Hermite bump).
    for(std::size_t f = 0; f < free.size(); ++f) {
      const std::size_t a = free[f];
      if((T.at(a, n) - start[f]).norm() < 1e-12) continue;
      auto& s = arc_samples[a];
      const bool from_start = L.arcs[a].nodes[0] == n;
      auto idx = [&](int k) { return std::size_t(from_start ? k : N - k); };
      const Eigen::Vector3d e = s[idx(1)] - s[idx(0)];
      const Eigen::Vector3d delta = e.norm() * T.at(a, n) - e;
      const double x1 = 1. / half, phi1 = x1 * (1. - x1) * (1. - x1);
      for(int k = 1; k < half; ++k) {
        const double x = double(k) / half;
        s[idx(k)] += (x * (1. - x) * (1. - x) / phi1) * delta;
      }
    }
  }
}

/// Per point, Mesh_probe::thickness() along its normal.
template <class Mesh>
std::vector<double> inward_thickness(const Mesh& mesh, const std::vector<Eigen::Vector3d>& points,
                                     const std::vector<Eigen::Vector3d>& normals)
{
  const Mesh_probe<Mesh> probe(mesh, false); // rays only
  std::vector<double> out(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) out[i] = probe.thickness(points[i], normals[i]);
  return out;
}

} // namespace internal

/*!
 * \ingroup PkgPolycubeIGARef
 * The layout of cores and slabs described in this header, with its grids, from `layout`
 * and its patch grids `samples` (sample_layout_patches()). Cuboid c < layout.cuboids.size()
 * of the result is the core of cuboid c; the slabs follow in the order of the SURFACE
 * patches. Throws Invalid_input_error("invalid_grid") if the grids do not belong to the
 * layout or are too coarse (N < 2), and Invalid_input_error("invalid_layout") if a node
 * lies on no surface patch or has no usable normal.
 */
template <class Point_3>
Padded_layout<Point_3> pad_layout(const Polycube_layout<Point_3>& layout, const Patch_grids& samples,
                                  const Padding_options& o = Padding_options())
{
  using Layout = Polycube_layout<Point_3>;
  const int N = samples.segments;
  const std::size_t nn = layout.nodes.size(), na = layout.arcs.size(), np = layout.patches.size();
  if(N < 2 || samples.arc_samples.size() != na || samples.grids.size() != np)
    throw Invalid_input_error("invalid_grid", "padding needs the layout's patch grids with at least 2 segments");
  if(!(o.thickness > 0. && o.thickness < 0.5))
    throw Invalid_input_error("invalid_parameter", "the boundary layer thickness must lie in (0, 0.5)");
  if(!(o.corner_threshold >= 0. && o.corner_threshold <= 1.) || !(o.maximum_corner_turn >= 0. && o.maximum_corner_turn <= 90.) ||
     !(o.inner_relief >= 0. && o.inner_relief <= 1.) || !(o.folded_corner_lift > 0. && o.folded_corner_lift <= 1.))
    throw Invalid_input_error("invalid_parameter", "the boundary layer's corner_threshold and inner_relief must lie in [0, 1], its "
                                                   "folded_corner_lift in (0, 1], its maximum_corner_turn in [0, 90] degrees");

  // Outward normals at the nodes, from the SURFACE grids (their u x v points out of the
  // solid, Patch_sampling.h): sums of the unit normals at the corners of the surface
  // patches around each node.
  std::vector<Eigen::Vector3d> node_normal(nn, Eigen::Vector3d::Zero());
  std::vector<int> surface_corners(nn, 0);
  std::vector<int> surface_sides(na, 0);
  for(std::size_t p = 0; p < np; ++p) {
    const auto& pa = layout.patches[p];
    if(pa.kind != Layout::SURFACE) continue;
    for(int i = 0; i < 4; ++i) {
      ++surface_sides[pa.arcs[std::size_t(i)]];
      const std::array<int, 2> c = internal::border_index(i, 0, N);
      node_normal[pa.corners[std::size_t(i)]] += internal::grid_normal(samples.grids[p], c[0], c[1]);
      ++surface_corners[pa.corners[std::size_t(i)]];
    }
  }

  // Depth per node, and the nodes' positions taken from the arc samples (bit-identical to
  // the grids' corners).
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<double> depth(nn, infinity);
  std::vector<Eigen::Vector3d> outer(nn, Eigen::Vector3d::Zero());
  std::vector<double> length(na);
  for(std::size_t a = 0; a < na; ++a) {
    const auto& s = samples.arc_samples[a];
    length[a] = internal::cumulative_lengths(s).back();
    const double l = o.thickness * length[a];
    for(int e = 0; e < 2; ++e) {
      const std::size_t n = layout.arcs[a].nodes[std::size_t(e)];
      depth[n] = std::min(depth[n], l);
      outer[n] = e == 0 ? s.front() : s.back();
    }
  }
  // A patch corner whose angle is reflex turns its grid's corner normal over; where that
  // cancels the others (a chain node of joint.off, two of four normals reversed) the node
  // takes the normal of the mesh face it lies on.
  const internal::Mesh_probe<typename Layout::Mesh> probe(layout.mesh, false); // rays and face normals only
  for(std::size_t n = 0; n < nn; ++n)
    if(surface_corners[n] > 0 && node_normal[n].norm() < 0.25 * surface_corners[n] && depth[n] < infinity)
      node_normal[n] = probe.closest_face_normal(outer[n]);
  // An interior node (a box corner inside the solid) is on no slab: its inner node is itself.
  std::vector<bool> interior(nn, false);
  for(std::size_t n = 0; n < nn; ++n) interior[n] = layout.is_interior_node(n);
  std::vector<Eigen::Vector3d> inner(nn);
  for(std::size_t n = 0; n < nn; ++n) {
    if(interior[n]) {
      depth[n] = 0.;
      continue;
    }
    const double l = node_normal[n].norm();
    if(!(l > 0.) || !(depth[n] < infinity))
      throw Invalid_input_error("invalid_layout", "node " + std::to_string(n) + " has no surface normal to pad along");
    node_normal[n] /= l;
  }
  // Where the solid is thinner than the layers on its two faces (a mushroom's rim, a
  // blade), the inner node would pass the opposite face: the layer keeps to a fraction of
  // the thickness under the node.
  // A ray that leaves without a hit starts on a cut end whose opposite face the cut took
  // away (blade.off's far end, stepped: under the bottom corner the top ends 1.9 earlier,
  // and the inner node went 0.53 deep into a blade 0.65 thick, past the top's inner node);
  // there the solid is as thin as at the nodes it shares an arc with.
  if(o.maximum_thickness_fraction > 0.) {
    std::vector<double> under(nn);
    for(std::size_t n = 0; n < nn; ++n) under[n] = interior[n] ? infinity : probe.thickness(outer[n], node_normal[n]);
    std::vector<double> seen = under;
    for(const auto& arc : layout.arcs)
      for(std::size_t e = 0; e < 2; ++e) {
        const std::size_t n = arc.nodes[e], other = arc.nodes[1 - e];
        if(!interior[n] && !(under[n] < infinity)) seen[n] = std::min(seen[n], under[other]);
      }
    for(std::size_t n = 0; n < nn; ++n)
      if(!interior[n]) depth[n] = std::min(depth[n], o.maximum_thickness_fraction * seen[n]);
  }
  // A node capped by the thickness would tilt the inner arcs and walls around it: the depth
  // may change along an arc by at most maximum_depth_slope times its length (depths only
  // decrease, so this ends; each pass lowers at least one node to its final value).
  if(o.maximum_depth_slope > 0.) {
    for(bool changed = true; changed;) {
      changed = false;
      for(std::size_t a = 0; a < na; ++a) {
        const std::size_t n0 = layout.arcs[a].nodes[0], n1 = layout.arcs[a].nodes[1];
        if(interior[n0] || interior[n1]) continue; // no slab along this arc
        const double slack = o.maximum_depth_slope * length[a];
        for(const auto& e : {std::make_pair(n0, n1), std::make_pair(n1, n0)})
          if(depth[e.first] > depth[e.second] + slack) {
            depth[e.first] = depth[e.second] + slack;
            changed = true;
          }
      }
    }
  }

  Padded_layout<Point_3> r;
  Layout& L = r.layout;
  L.layout_class = layout.layout_class;
  L.genus = layout.genus;
  L.boundary_loops = layout.boundary_loops;
  L.number_of_pants = layout.number_of_pants;
  L.mesh = layout.mesh; // for the distance of the slabs' tops to the surface
  Patch_grids& G = r.samples;
  G.segments = N;

  // Nodes: outer 0..nn-1, inner nn..2nn-1.
  L.nodes = layout.nodes;
  L.nodes.insert(L.nodes.end(), layout.nodes.begin(), layout.nodes.end());

  // Arcs: the layout's (0..na-1), inner (na + a), radial n -> n' (2na + n); their samples
  // are placed below, once the cuboids are known.
  L.arcs = layout.arcs;
  for(std::size_t a = 0; a < na; ++a) {
    typename Layout::Arc in;
    in.nodes = {{nn + layout.arcs[a].nodes[0], nn + layout.arcs[a].nodes[1]}};
    L.arcs.push_back(in);
  }
  for(std::size_t n = 0; n < nn; ++n) {
    typename Layout::Arc radial;
    radial.nodes = {{n, nn + n}};
    L.arcs.push_back(radial);
  }
  // The samples of every arc for the inner nodes at `d` below their outer nodes, the
  // corners at inner nodes opened (open_inner_corners()).
  auto place_arcs = [&](const std::vector<double>& d) {
    for(std::size_t n = 0; n < nn; ++n) inner[n] = outer[n] - d[n] * node_normal[n];
    G.arc_samples = samples.arc_samples;
    for(std::size_t a = 0; a < na; ++a) {
      const auto& arc = layout.arcs[a];
      // The inner arc is the chord of its inner nodes plus half the outer arc's deviation from
      // its own chord: straight arcs stay straight (a flat face stays flat), and a round
      // cross-section's inner arcs are half as round, so the core gets real corners there.
      // (Offsetting each sample along its normal makes a box's core edges reflex; keeping the
      // full curvature, as an offset circle does, leaves the core's cross-section corners at
      // about 180 degrees: the torus turned invalid on a finer mesh of the same shape.)
      // An arc that bulges into the solid (around a hole) by more than the layer is deep would,
      // with half its bulge, have an inner arc that cuts across the hole, and the slab under it
      // would lie outside the solid. It keeps enough of its bulge (sagitta s, depth d: a
      // fraction 1 - d / 2s) for its inner arc to stay at least d/2 below it; shallow
      // bulges keep half, like convex arcs (all of a shallow one spoils the torus' core).
      const Eigen::Vector3d arc_normal =
        (node_normal[arc.nodes[0]].normalized() + node_normal[arc.nodes[1]].normalized()).normalized();
      double sagitta = 0.;
      for(int k = 1; k < N; ++k) {
        const double t = double(k) / N;
        const Eigen::Vector3d chord_out = (1. - t) * outer[arc.nodes[0]] + t * outer[arc.nodes[1]];
        sagitta = std::max(sagitta, -(samples.arc_samples[a][std::size_t(k)] - chord_out).dot(arc_normal));
      }
      const double arc_depth = std::min(d[arc.nodes[0]], d[arc.nodes[1]]);
      const double kept = sagitta > arc_depth ? 1. - arc_depth / (2. * sagitta) : 0.5;
      std::vector<Eigen::Vector3d> s(samples.arc_samples[a]);
      for(int k = 1; k < N; ++k) {
        const double t = double(k) / N;
        const Eigen::Vector3d chord_out = (1. - t) * outer[arc.nodes[0]] + t * outer[arc.nodes[1]];
        const Eigen::Vector3d chord_in = (1. - t) * inner[arc.nodes[0]] + t * inner[arc.nodes[1]];
        s[std::size_t(k)] = chord_in + kept * (samples.arc_samples[a][std::size_t(k)] - chord_out);
      }
      s.front() = inner[arc.nodes[0]];
      s.back() = inner[arc.nodes[1]];
      G.arc_samples.push_back(std::move(s));
    }
    for(std::size_t n = 0; n < nn; ++n) {
      std::vector<Eigen::Vector3d> s(std::size_t(N + 1));
      for(int k = 0; k <= N; ++k) s[std::size_t(k)] = outer[n] + (double(k) / N) * (inner[n] - outer[n]);
      s.front() = outer[n];
      s.back() = inner[n];
      G.arc_samples.push_back(std::move(s));
    }
    if(o.corner_threshold > 0.) internal::open_inner_corners(L, G.arc_samples, na, nn, o.corner_threshold, o.maximum_corner_turn);
  };

  // Patches: the layout's (0..np-1, only the SURFACE ones stay in use), inner (np + p),
  // walls (2np + a); the grids of the new ones are filled once their arcs are final (below).
  L.patches = layout.patches;
  G.grids = samples.grids;
  for(std::size_t p = 0; p < np; ++p) {
    const auto& pa = layout.patches[p];
    typename Layout::Patch in;
    in.kind = pa.kind == Layout::CAP ? Layout::CAP : Layout::INTERFACE;
    for(int i = 0; i < 4; ++i) {
      in.corners[std::size_t(i)] = nn + pa.corners[std::size_t(i)];
      in.arcs[std::size_t(i)] = na + pa.arcs[std::size_t(i)];
    }
    L.patches.push_back(in);
  }
  for(std::size_t a = 0; a < na; ++a) {
    const std::size_t n0 = layout.arcs[a].nodes[0], n1 = layout.arcs[a].nodes[1];
    typename Layout::Patch wall;
    // Between two surface patches the wall lies inside; beside a cap it continues the cap.
    // An arc inside the solid has no slab beside it, and its wall no cuboid.
    wall.kind = surface_sides[a] >= 2 || layout.arcs[a].inside ? Layout::INTERFACE : Layout::CAP;
    wall.corners = {{n0, n1, nn + n1, nn + n0}};
    wall.arcs = {{a, 2 * na + n1, na + a, 2 * na + n0}};
    L.patches.push_back(wall);
  }
  G.flipped_triangles = samples.flipped_triangles;
  G.flipped_triangles.resize(L.patches.size(), 0);
  G.unlocated_points = samples.unlocated_points;
  G.unlocated_points.resize(L.patches.size(), 0);

  // Cuboids: the cores, then one slab per SURFACE patch with (u, v) along the patch's grid
  // and w from p' (w = 0) to p (w = 1); u x v points out, so the slab is right-handed.
  for(std::size_t c = 0; c < layout.cuboids.size(); ++c) {
    typename Layout::Cuboid core = layout.cuboids[c];
    for(auto& n : core.nodes) n += nn;
    for(auto& p : core.patches) p += np;
    L.cuboids.push_back(core);
    r.core_of.push_back(long(c));
    r.slab_of.push_back(-1);
  }
  for(std::size_t p = 0; p < np; ++p) {
    const auto& pa = layout.patches[p];
    if(pa.kind != Layout::SURFACE) continue;
    typename Layout::Cuboid slab;
    // Corner (i, j) of the square is patch corner 0, 1, 3, 2 for (0,0), (1,0), (0,1), (1,1).
    const std::array<std::size_t, 4> at{{pa.corners[0], pa.corners[1], pa.corners[3], pa.corners[2]}};
    for(int q = 0; q < 4; ++q) {
      slab.nodes[std::size_t(q)] = nn + at[std::size_t(q)];
      slab.nodes[std::size_t(q + 4)] = at[std::size_t(q)];
    }
    slab.patches = {{2 * np + pa.arcs[3], 2 * np + pa.arcs[1], 2 * np + pa.arcs[0], 2 * np + pa.arcs[2], np + p, p}};
    L.cuboids.push_back(slab);
    r.core_of.push_back(-1);
    r.slab_of.push_back(long(p));
  }

  place_arcs(depth);
  // An inner node whose corner stays folded after opening (shark: a rim node amid a flat
  // face, flush with its hole's cap, so the core's cap and side faces are coplanar there and
  // its three inner arcs leave in one plane) is lifted: at a fraction of its depth it becomes
  // a ridge between those faces. Kept per node only where its worst corner rises.
  if(o.folded_corner_lift < 1.) {
    internal::Corner_tangents<Layout> opened(L, G.arc_samples, nn);
    std::vector<std::pair<std::size_t, double>> folded; // node, its worst corner as opened
    std::vector<double> lifted = depth;
    for(std::size_t n = 0; n < nn; ++n)
      if(opened.has_corners(nn + n)) {
        const double w = opened.worst(nn + n);
        if(w < 0.) {
          folded.emplace_back(n, w);
          lifted[n] *= o.folded_corner_lift;
        }
      }
    if(!folded.empty()) {
      place_arcs(lifted);
      internal::Corner_tangents<Layout> after(L, G.arc_samples, nn);
      for(const auto& [n, w] : folded)
        if(after.worst(nn + n) > w)
          r.lifted_nodes.push_back(n);
        else
          lifted[n] = depth[n];
      if(r.lifted_nodes.size() < folded.size()) place_arcs(lifted);
    }
  }
  // Inner patches and walls: the Coons patches of their (final) border samples. Not
  // harmonic: a uniform grid Laplacian treats a long thin wall as a square and pulls its
  // middle towards the chord, out of the layer. An inner patch adds a fraction of its outer
  // patch's relief, so a slab under a saddle or a dome keeps some of its depth in the middle
  // instead of thinning towards the chords' patch.
  for(std::size_t p = np; p < L.patches.size(); ++p) {
    Point_grid g(N + 1, N + 1);
    internal::set_patch_border(g, N, L, L.patches[p], G.arc_samples);
    internal::coons_grid_interior(g, N);
    if(p < 2 * np && o.inner_relief != 0.) {
      const Point_grid& outer_grid = samples.grids[p - np];
      Point_grid flat = outer_grid;
      internal::coons_grid_interior(flat, N);
      for(int j = 1; j < N; ++j)
        for(int i = 1; i < N; ++i) g(i, j) += o.inner_relief * (outer_grid(i, j) - flat(i, j));
    }
    G.grids.push_back(std::move(g));
  }
  return r;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_LAYOUT_PADDING_H
