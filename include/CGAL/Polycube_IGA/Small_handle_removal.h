// Copyright (c) 2026 The Polycube_IGA authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Closing handles that are topological noise. A scanned or remeshed surface can carry
// handles a few triangles across (femur.off: two handles whose shortest loops have 3 and 5
// edges, 0.3% and 1.6% of the bounding box's diagonal around, at the knee). The pants and
// cuboid stages lay cuboids around every handle however small, and no grid that the rest of
// the shape needs resolves them: femur.off's volume had 115 of 158 patches uncertified, most
// of them where those two handles are. A handle whose shortest handle or tunnel loop is
// shorter than a fraction of the diagonal is closed instead: the faces near the loop are
// removed and both holes are filled by CGAL's triangulate_refine_and_fair_hole(), which
// moves the surface by about the loop's size, far less than a volume may be off it.
// This is the reference's input (a surface of the genus the user means) made explicit; it
// goes beyond it (the reference assumes clean meshes).

#ifndef CGAL_POLYCUBE_IGA_SMALL_HANDLE_REMOVAL_H
#define CGAL_POLYCUBE_IGA_SMALL_HANDLE_REMOVAL_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Surface_topology.h>
#include <CGAL/Polycube_IGA/parameters.h>
#include <CGAL/Polycube_IGA/internal/bbox_diagonal.h>
#include <CGAL/Polycube_IGA/internal/mesh_graph.h>
#include <CGAL/Polycube_IGA/internal/shortest_path_tree.h>

#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <optional>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// One handle closed by `Small_handle_removal`.
struct Closed_handle
{
  std::string loop_kind;       ///< "handle" or "tunnel": the kind of the shortest loop around it
  double length = 0;           ///< that loop's length
  double relative = 0;         ///< the length over the bounding box's diagonal
  std::size_t loop_edges = 0;  ///< its number of edges
  std::array<double, 3> point{}; ///< a vertex of the loop, to find the handle
};

/// \ingroup PkgPolycubeIGARef
/// Result of `Small_handle_removal`.
struct Small_handle_removal_result
{
  int genus_before = 0, genus_after = 0;
  std::vector<Closed_handle> closed;
  /// A small handle that could not be closed (no removal radius left the surface with two
  /// fillable holes and no self-intersection); the surface keeps it.
  std::vector<std::string> warnings;
};

/*!
 * \ingroup PkgPolycubeIGARef
 * Function object closing the handles of a closed or bordered surface whose shortest handle
 * or tunnel loop (`Surface_topology`) is shorter than `small_handle_length` (named
 * parameter, a fraction of the bounding box's diagonal, default 0.01; 0: none), one at a
 * time, shortest first, until none is left. A handle is closed by removing the faces within
 * r of its loop (along the edges; r = 1, 2, 4, 8 times the loop's length until it works)
 * and filling the two holes with CGAL::Polygon_mesh_processing::triangulate_refine_and_fair_hole();
 * the result must be one manifold component with the same boundary loops, genus one less,
 * and no self-intersection, else the handle stays and a warning says so. The mesh is a
 * `CGAL::Surface_mesh` (garbage is collected; vertex and face indices change where a handle
 * is closed). Throws `Invalid_input_error` (`invalid_parameter`) for a fraction outside [0, 1).
 */
template <class Point>
class Small_handle_removal
{
public:
  using Mesh = CGAL::Surface_mesh<Point>;

  template <class NamedParameters = parameters::Default_named_parameters>
  Small_handle_removal_result operator()(Mesh& tm, const NamedParameters& np = parameters::default_values()) const
  {
    const double fraction = double(option(np, internal_np::small_handle_length, 0.01));
    if(!(fraction >= 0. && fraction < 1.)) throw Invalid_input_error("invalid_parameter", "small_handle_length must be in [0, 1)");
    const double diagonal = internal::mesh_bbox_diagonal(tm);
    Small_handle_removal_result r;
    for(bool first = true;; first = false) {
      const Surface_topology_result<Mesh> topo = Surface_topology<Mesh>()(tm);
      if(first) r.genus_before = topo.genus;
      r.genus_after = topo.genus;
      if(topo.genus == 0 || !(fraction > 0.)) break;
      // The shortest loop around any handle: a thin handle's handle loop, a small hole's tunnel loop.
      const std::vector<Small_loop> small = small_loops(topo, fraction * diagonal);
      if(small.empty()) break;
      const Small_loop& first_small = *std::min_element(small.begin(), small.end(), [](const Small_loop& a, const Small_loop& b) {
        return a.loop->length < b.loop->length;
      });
      const Surface_loop<Mesh>* shortest = first_small.loop;
      const std::string kind = first_small.kind;
      std::optional<Mesh> closed = closed_along(topo.loop_mesh(tm), *shortest, topo.genus, topo.number_of_boundary_loops());
      const Closed_handle h{kind, shortest->length, shortest->length / diagonal, shortest->vertices.size(), shortest->points.front()};
      if(!closed) {
        std::ostringstream os;
        os << std::setprecision(3) << "a handle whose " << kind << " loop is " << 100. * h.relative
           << "% of the diagonal around could not be closed (near " << h.point[0] << ", " << h.point[1] << ", " << h.point[2]
           << "); the surface keeps it";
        r.warnings.push_back(os.str());
        break;
      }
      tm = std::move(*closed);
      r.closed.push_back(h);
    }
    return r;
  }

  /// A handle or tunnel loop of a topology, with its kind ("handle" or "tunnel").
  struct Small_loop
  {
    const char* kind;
    const Surface_loop<Mesh>* loop;
  };

  /// The handle and tunnel loops of `topo` shorter than `limit`, handle loops first: what the
  /// operator() closes (the shortest first), and what a caller can name when it closes nothing.
  static std::vector<Small_loop> small_loops(const Surface_topology_result<Mesh>& topo, double limit)
  {
    std::vector<Small_loop> out;
    for(const auto& l : topo.handle_loops)
      if(l.length < limit) out.push_back({"handle", &l});
    for(const auto& l : topo.tunnel_loops)
      if(l.length < limit) out.push_back({"tunnel", &l});
    return out;
  }

private:
  /// Euler's formula for one connected surface: 2 - 2g - b = V - E + F.
  static int genus_of(const Mesh& m, std::size_t borders)
  {
    const long chi = long(num_vertices(m)) - long(num_edges(m)) + long(num_faces(m));
    return int((2 - chi - long(borders)) / 2);
  }

  static std::size_t border_count(const Mesh& m)
  {
    std::vector<typename Mesh::Halfedge_index> cycles;
    CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(cycles));
    return cycles.size();
  }

  /// `mesh` with the handle around `loop` closed, or nothing if no radius works.
  static std::optional<Mesh> closed_along(const Mesh& mesh, const Surface_loop<Mesh>& loop, int genus, std::size_t borders)
  {
    namespace PMP = CGAL::Polygon_mesh_processing;
    const internal::Mesh_graph<Mesh> g(mesh, get(CGAL::vertex_point, mesh));
    std::vector<int> index(num_vertices(mesh), -1);
    for(int i = 0; i < g.number_of_vertices(); ++i) index[std::size_t(g.vertex[std::size_t(i)])] = i;
    std::vector<int> roots;
    for(auto v : loop.vertices) roots.push_back(index[std::size_t(v)]);
    std::vector<double> w(std::size_t(g.number_of_edges()));
    for(int e = 0; e < g.number_of_edges(); ++e) w[std::size_t(e)] = g.length(e);
    const std::vector<double> d = internal::shortest_path_tree(g, roots, w).distance;
    for(double factor : {1., 2., 4., 8.}) {
      Mesh m = mesh;
      const double radius = factor * loop.length;
      // Vertices that lose a face: the new holes' borders run through them.
      auto touched = m.template add_property_map<typename Mesh::Vertex_index, bool>("v:shr_touched", false).first;
      std::vector<typename Mesh::Face_index> doomed;
      for(auto f : faces(m))
        for(auto v : vertices_around_face(halfedge(f, m), m))
          if(index[std::size_t(v)] >= 0 && d[std::size_t(index[std::size_t(v)])] <= radius) {
            doomed.push_back(f);
            for(auto u : vertices_around_face(halfedge(f, m), m)) touched[u] = true;
            break;
          }
      for(auto f : doomed) CGAL::Euler::remove_face(halfedge(f, m), m);
      PMP::remove_isolated_vertices(m);
      m.collect_garbage();
      if(num_faces(m) == 0 || !CGAL::is_valid_polygon_mesh(m)) continue;
      // One manifold piece with one handle less and two more holes (the loop's neighbourhood
      // was an annulus) or one (it held the whole handle: femur.off's second one); else a
      // larger radius.
      auto fcc = m.template add_property_map<typename Mesh::Face_index, std::size_t>("f:shr_cc", 0).first;
      const std::size_t pieces = PMP::connected_components(m, fcc);
      m.remove_property_map(fcc);
      std::vector<typename Mesh::Halfedge_index> pinched;
      PMP::non_manifold_vertices(m, std::back_inserter(pinched));
      std::vector<typename Mesh::Halfedge_index> cycles;
      PMP::extract_boundary_cycles(m, std::back_inserter(cycles));
      const std::size_t opened = cycles.size();
      if(pieces != 1 || !pinched.empty() || opened < borders + 1 || opened > borders + 2 || genus_of(m, opened) != genus - 1) continue;
      // The new holes are the borders through vertices that lost a face; the input's own
      // boundary loops lie elsewhere (a radius reaching one changes the counts).
      bool filled = true;
      std::size_t holes = 0;
      for(auto h : cycles) {
        // An input boundary loop is a hole the user meant: only the new ones are filled.
        if(!touched[target(h, m)]) continue;
        std::vector<typename Mesh::Face_index> new_faces;
        std::vector<typename Mesh::Vertex_index> new_vertices;
        const bool ok = std::get<0>(PMP::triangulate_refine_and_fair_hole(m, h, std::back_inserter(new_faces), std::back_inserter(new_vertices)));
        filled = filled && ok;
        ++holes;
      }
      m.remove_property_map(touched);
      if(!filled || holes != opened - borders || border_count(m) != borders || genus_of(m, borders) != genus - 1 || PMP::does_self_intersect(m)) continue;
      return m;
    }
    return std::nullopt;
  }
};

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_SMALL_HANDLE_REMOVAL_H
