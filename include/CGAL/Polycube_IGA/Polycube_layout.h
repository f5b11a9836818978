// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Polycube_layout: the value every stage after the cuboid decomposition reads (reference
// §1.2.3, §2.2.2). It lives on a (possibly refined) copy of the input surface: nodes are mesh
// vertices, arcs are vertex paths between two nodes, quad patches are either face sets of the
// surface bounded by four arcs or interior quads (caps on input boundary loops, interfaces
// between cuboids) that only have their four arcs, and cuboids list their 8 nodes and 6
// patches. Every arc lies on the surface, except the box edges of a CAD block (or a polycube)
// that run through the solid between two surface nodes: those are straight segments
// (Arc::inside) bounding interfaces only, and the box corners inside the solid where such
// edges cross: interior nodes, vertices of the mesh on no face (is_interior_node()), all of
// whose arcs run inside. validate() checks the properties the later stages rely on.

#ifndef CGAL_POLYCUBE_IGA_POLYCUBE_LAYOUT_H
#define CGAL_POLYCUBE_IGA_POLYCUBE_LAYOUT_H


#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// Which construction produced a layout.
enum class Layout_class
{
  sphere,   ///< one cube
  disk,     ///< one cube capped by the boundary loop
  cylinder, ///< a chain of cuboids between two boundary loops
  torus,    ///< a ring of cuboids cut along meridians
  pants,    ///< 4 cuboids per pants patch (§2.2.2)
  blocks,   ///< a CAD block's boxes between the planes of its faces (any genus, no boundary)
  polycube  ///< the boxes of a polycube map of the surface, carried back to it (any genus, no boundary)
};

inline const char* layout_class_name(Layout_class c)
{
  switch(c) {
  case Layout_class::sphere: return "sphere";
  case Layout_class::disk: return "disk";
  case Layout_class::cylinder: return "cylinder";
  case Layout_class::torus: return "torus";
  case Layout_class::blocks: return "blocks";
  case Layout_class::polycube: return "polycube";
  default: return "pants";
  }
}

/// \ingroup PkgPolycubeIGARef
/// Result of `Polycube_layout::validate()`.
struct Layout_validation
{
  std::vector<std::string> problems;
  int euler_surface = 0; ///< V - E + F over nodes, arcs and surface patches
  int euler_solid = 0;   ///< V - E + F - C over the whole cuboid complex
  int minimum_valence = 0, maximum_valence = 0;
  bool is_valid() const { return problems.empty(); }
};

/// \ingroup PkgPolycubeIGARef
template <class Point_3>
struct Polycube_layout
{
  using Mesh = CGAL::Surface_mesh<Point_3>;
  using vertex_descriptor = typename Mesh::Vertex_index;
  using face_descriptor = typename Mesh::Face_index;

  enum Patch_kind
  {
    SURFACE,  ///< a face set of the surface
    CAP,      ///< spans an input boundary loop: a boundary side of the volume
    INTERFACE ///< between two cuboids, inside the solid
  };

  struct Arc
  {
    std::array<std::size_t, 2> nodes{{0, 0}};
    std::vector<vertex_descriptor> vertices; ///< from nodes[0]'s vertex to nodes[1]'s
    /// A straight segment through the solid between two surface nodes (`vertices` is just
    /// their two vertices), bounding INTERFACE patches only: a box edge of a CAD block inside
    /// it, such as a staircase's inner corner line.
    bool inside = false;
  };

  struct Patch
  {
    Patch_kind kind = SURFACE;
    /// Corners in cyclic order; for surface patches counter-clockwise seen from outside
    /// (the mesh's orientation), so that (corner0->corner1) x (corner0->corner3) points out.
    std::array<std::size_t, 4> corners{{0, 0, 0, 0}};
    /// arcs[i] joins corners[i] and corners[(i+1)%4] (in either direction).
    std::array<std::size_t, 4> arcs{{0, 0, 0, 0}};
    std::vector<face_descriptor> faces; ///< empty unless SURFACE
  };

  /// Corner (i,j,k) in {0,1}^3 of the cuboid's local (u,v,w) axes is nodes[i + 2j + 4k].
  /// Side s = 1..6 (G+Smo order: u=0, u=1, v=0, v=1, w=0, w=1) is patches[s-1].
  struct Cuboid
  {
    std::array<std::size_t, 8> nodes{};
    std::array<std::size_t, 6> patches{};
    int pants = -1; ///< pants patch it belongs to, -1 for the chi >= 0 layouts
  };

  /// Two cuboid sides glued through an INTERFACE patch.
  struct Interface
  {
    std::size_t patch = 0;
    std::size_t cuboid_a = 0, cuboid_b = 0;
    int side_a = 1, side_b = 1;
  };

  Layout_class layout_class = Layout_class::sphere;
  int genus = 0;
  std::size_t boundary_loops = 0;
  std::size_t number_of_pants = 0;
  /// The input's faces pointed into the solid, so `mesh` is the input turned over (surface
  /// patches are counter-clockwise seen from outside whichever way the input points).
  bool turned_outwards = false;
  /// `mesh` is a copy of the input remeshed for its polycube map (a CAD part with 45-degree
  /// features, internal::remeshed_for_labels()): the same surface, none of its vertices
  /// the input's.
  bool remeshed = false;
  /// The surface the layout lives on; carries "v:input_index"/"f:input_index" when built
  /// from an input file (refinement vertices get -1 as input index; all of a remeshed one's).
  Mesh mesh;
  std::vector<vertex_descriptor> nodes;
  std::vector<Arc> arcs;
  std::vector<Patch> patches;
  std::vector<Cuboid> cuboids;

  /// Whether node n lies inside the solid, not on the surface: its vertex is on no face
  /// (a box corner of a polycube where the planes of features far apart cross).
  bool is_interior_node(std::size_t n) const { return mesh.is_isolated(nodes[n]); }

  /// The node indices of side s (1..6) of a cuboid, ordered by the two remaining local
  /// directions increasing: (0,0), (1,0), (0,1), (1,1).
  static std::array<std::size_t, 4> side_nodes(const Cuboid& c, int s)
  {
    const int d = (s - 1) / 2, at = (s - 1) % 2;
    const int a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;
    std::array<std::size_t, 4> out{};
    for(int q = 0; q < 4; ++q) {
      int x[3];
      x[d] = at;
      x[a] = q & 1;
      x[b] = (q >> 1) & 1;
      out[std::size_t(q)] = c.nodes[std::size_t(x[0] + 2 * x[1] + 4 * x[2])];
    }
    return out;
  }

  /// Every INTERFACE patch with the two cuboid sides it glues, in patch order.
  std::vector<Interface> interfaces() const
  {
    std::vector<Interface> out;
    std::vector<std::vector<std::pair<std::size_t, int>>> users(patches.size());
    for(std::size_t c = 0; c < cuboids.size(); ++c)
      for(int s = 1; s <= 6; ++s) users[cuboids[c].patches[std::size_t(s - 1)]].push_back({c, s});
    for(std::size_t p = 0; p < patches.size(); ++p)
      if(patches[p].kind == INTERFACE && users[p].size() == 2)
        out.push_back({p, users[p][0].first, users[p][1].first, users[p][0].second, users[p][1].second});
    return out;
  }

  std::size_t number_of_surface_patches() const
  {
    return std::size_t(std::count_if(patches.begin(), patches.end(), [](const Patch& p) { return p.kind == SURFACE; }));
  }

  /// Checks the layout: arcs are edge paths meeting only at nodes, surface patches are disks
  /// bounded by their four arcs with the corners in order and tile the surface exactly once,
  /// every cuboid has 8 distinct nodes and 6 patches whose corners are its sides' nodes, every
  /// interior patch is used by the right number of cuboids, and the Euler characteristics of
  /// the surface layout (2-2g-b) and of the cuboid complex (1-g, a handlebody) are right.
  Layout_validation validate() const;
};

// ---------------------------------------------------------------------------------------

template <class Point_3>
Layout_validation Polycube_layout<Point_3>::validate() const
{
  Layout_validation r;
  auto problem = [&r](const std::string& s) {
    if(r.problems.size() < 50) r.problems.push_back(s);
  };
  const std::size_t nv = num_vertices(mesh), nf = num_faces(mesh), ne = num_edges(mesh);
  if(nodes.empty() || cuboids.empty()) {
    problem("empty layout");
    return r;
  }
  std::vector<int> node_of(nv, -1);
  for(std::size_t n = 0; n < nodes.size(); ++n) {
    if(std::size_t(nodes[n]) >= nv) {
      problem("node " + std::to_string(n) + " is not a mesh vertex");
      return r;
    }
    if(node_of[nodes[n]] >= 0) problem("nodes " + std::to_string(node_of[nodes[n]]) + " and " + std::to_string(n) + " share a vertex");
    node_of[nodes[n]] = int(n);
  }

  // Arcs: edge paths between their nodes; interior vertices private to one arc.
  std::vector<int> arc_of_edge(ne, -1), arc_of_vertex(nv, -1);
  std::vector<int> valence(nodes.size(), 0);
  for(std::size_t a = 0; a < arcs.size(); ++a) {
    const Arc& arc = arcs[a];
    const std::string name = "arc " + std::to_string(a);
    if(arc.vertices.size() < 2 || arc.nodes[0] >= nodes.size() || arc.nodes[1] >= nodes.size()) {
      problem(name + " is malformed");
      continue;
    }
    if(arc.vertices.front() != nodes[arc.nodes[0]] || arc.vertices.back() != nodes[arc.nodes[1]])
      problem(name + " does not start and end at its nodes");
    ++valence[arc.nodes[0]];
    ++valence[arc.nodes[1]];
    if(!arc.inside && (is_interior_node(arc.nodes[0]) || is_interior_node(arc.nodes[1])))
      problem(name + " ends at an interior node but runs on the surface");
    if(arc.inside) {
      if(arc.vertices.size() != 2) problem(name + " runs inside the solid but is not one segment");
      continue;
    }
    for(std::size_t i = 0; i + 1 < arc.vertices.size(); ++i) {
      auto h = halfedge(arc.vertices[i], arc.vertices[i + 1], mesh);
      if(!h.second) {
        problem(name + " jumps between non-adjacent vertices");
        break;
      }
      const std::size_t e = std::size_t(edge(h.first, mesh));
      if(arc_of_edge[e] >= 0) problem(name + " shares an edge with arc " + std::to_string(arc_of_edge[e]));
      arc_of_edge[e] = int(a);
    }
    for(std::size_t i = 1; i + 1 < arc.vertices.size(); ++i) {
      const auto v = arc.vertices[i];
      if(node_of[v] >= 0) problem(name + " passes through node " + std::to_string(node_of[v]));
      if(arc_of_vertex[v] >= 0) problem(name + " meets arc " + std::to_string(arc_of_vertex[v]) + " away from a node");
      arc_of_vertex[v] = int(a);
    }
  }
  if(!valence.empty()) {
    r.minimum_valence = *std::min_element(valence.begin(), valence.end());
    r.maximum_valence = *std::max_element(valence.begin(), valence.end());
    if(r.minimum_valence < 3) problem("a node has valence " + std::to_string(r.minimum_valence) + " (at least 3 expected)");
  }

  // Surface patches tile the faces; each is a disk whose border is its four arcs in order.
  std::vector<int> patch_of_face(nf, -1);
  std::size_t surface_patches = 0;
  for(std::size_t p = 0; p < patches.size(); ++p) {
    const Patch& pa = patches[p];
    const std::string name = "patch " + std::to_string(p);
    for(int i = 0; i < 4; ++i) {
      const std::size_t a = pa.arcs[std::size_t(i)];
      const std::size_t c0 = pa.corners[std::size_t(i)], c1 = pa.corners[std::size_t((i + 1) % 4)];
      if(a >= arcs.size() || !((arcs[a].nodes[0] == c0 && arcs[a].nodes[1] == c1) || (arcs[a].nodes[0] == c1 && arcs[a].nodes[1] == c0)))
        problem(name + ": arc " + std::to_string(i) + " does not join its corners");
    }
    if(pa.kind != SURFACE) {
      if(!pa.faces.empty()) problem(name + " is interior but has faces");
      if(pa.kind == CAP)
        for(std::size_t a : pa.arcs)
          if(a < arcs.size() && arcs[a].inside) problem(name + " is a cap bounded by an arc inside the solid");
      continue;
    }
    ++surface_patches;
    for(std::size_t a : pa.arcs)
      if(a < arcs.size() && arcs[a].inside) problem(name + " is on the surface but bounded by an arc inside the solid");
    if(pa.faces.empty()) {
      problem(name + " has no faces");
      continue;
    }
    for(face_descriptor f : pa.faces) {
      if(std::size_t(f) >= nf) {
        problem(name + " lists a face that is not in the mesh");
        break;
      }
      if(patch_of_face[f] >= 0) problem(name + " overlaps patch " + std::to_string(patch_of_face[f]));
      patch_of_face[f] = int(p);
    }
  }
  for(std::size_t f = 0; f < nf; ++f)
    if(patch_of_face[f] < 0) {
      problem("face " + std::to_string(f) + " is in no patch");
      break;
    }
  // Edges between two patches (or on the border) must be arc edges, and arc edges must
  // separate patches: then every patch is bounded exactly by arcs.
  for(auto e : edges(mesh)) {
    const auto h = halfedge(e, mesh), o = opposite(h, mesh);
    const int a = is_border(h, mesh) ? -2 : patch_of_face[face(h, mesh)];
    const int b = is_border(o, mesh) ? -2 : patch_of_face[face(o, mesh)];
    if((a != b) != (arc_of_edge[std::size_t(e)] >= 0)) {
      problem(a != b ? "a patch border runs off the arcs" : "an arc runs inside a patch");
      break;
    }
  }
  // Per patch: connected, chi = 1, one border loop meeting the corners in order.
  for(std::size_t p = 0; p < patches.size(); ++p) {
    const Patch& pa = patches[p];
    if(pa.kind != SURFACE || pa.faces.empty()) continue;
    const std::string name = "patch " + std::to_string(p);
    std::vector<vertex_descriptor> vs;
    std::size_t inner_edges2 = 0, border_edges = 0;
    typename Mesh::Halfedge_index start;
    for(face_descriptor f : pa.faces)
      for(auto h : halfedges_around_face(halfedge(f, mesh), mesh)) {
        vs.push_back(target(h, mesh));
        const auto o = opposite(h, mesh);
        if(!is_border(o, mesh) && patch_of_face[face(o, mesh)] == int(p)) ++inner_edges2;
        else {
          ++border_edges;
          if(start == typename Mesh::Halfedge_index() || source(h, mesh) == nodes[pa.corners[0]]) start = h;
        }
      }
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    const long chi = long(vs.size()) - long(inner_edges2 / 2 + border_edges) + long(pa.faces.size());
    if(chi != 1) {
      problem(name + " is not a disk (Euler characteristic " + std::to_string(chi) + ")");
      continue;
    }
    // Walk the border with the patch on the left, from corner 0 (if it is on the border).
    if(source(start, mesh) != nodes[pa.corners[0]]) {
      problem(name + ": corner 0 is not on its border");
      continue;
    }
    std::vector<std::size_t> met;
    std::size_t steps = 0;
    auto h = start;
    do {
      const int n = node_of[source(h, mesh)];
      if(n >= 0) met.push_back(std::size_t(n));
      // Next border halfedge of the patch: turn around target(h) until leaving the patch.
      auto g = next(h, mesh);
      while(true) {
        const auto o = opposite(g, mesh);
        if(is_border(o, mesh) || patch_of_face[face(o, mesh)] != int(p)) break;
        g = next(o, mesh);
      }
      h = g;
    } while(h != start && ++steps <= border_edges);
    if(steps > border_edges || met.size() != 4 || !std::equal(met.begin(), met.end(), pa.corners.begin()))
      problem(name + ": its border does not meet exactly its four corners in order");
  }

  // Cuboids.
  std::vector<int> uses(patches.size(), 0);
  for(std::size_t c = 0; c < cuboids.size(); ++c) {
    const Cuboid& cu = cuboids[c];
    const std::string name = "cuboid " + std::to_string(c);
    std::array<std::size_t, 8> ns = cu.nodes;
    std::sort(ns.begin(), ns.end());
    if(std::adjacent_find(ns.begin(), ns.end()) != ns.end() || ns.back() >= nodes.size()) problem(name + " has repeated or invalid nodes");
    for(int s = 1; s <= 6; ++s) {
      const std::size_t p = cu.patches[std::size_t(s - 1)];
      if(p >= patches.size()) {
        problem(name + " has an invalid patch");
        continue;
      }
      ++uses[p];
      std::array<std::size_t, 4> want = side_nodes(cu, s), have = patches[p].corners;
      std::sort(want.begin(), want.end());
      std::sort(have.begin(), have.end());
      if(want != have) problem(name + ": side " + std::to_string(s) + " is not bounded by its patch's corners");
    }
  }
  for(std::size_t p = 0; p < patches.size(); ++p) {
    const int want = patches[p].kind == INTERFACE ? 2 : 1;
    if(uses[p] != want)
      problem("patch " + std::to_string(p) + " is used by " + std::to_string(uses[p]) + " cuboids (" + std::to_string(want) + " expected)");
  }

  // The surface's own graph: the arcs inside the solid are edges of the cuboid complex only.
  const long inside_arcs = std::count_if(arcs.begin(), arcs.end(), [](const Arc& a) { return a.inside; });
  std::size_t interior_nodes = 0;
  for(std::size_t n = 0; n < nodes.size(); ++n) interior_nodes += is_interior_node(n) ? 1 : 0;
  r.euler_surface = int(nodes.size() - interior_nodes) - int(arcs.size() - std::size_t(inside_arcs)) + int(surface_patches);
  r.euler_solid = int(nodes.size()) - int(arcs.size()) + int(patches.size()) - int(cuboids.size());
  const int chi_surface = 2 - 2 * genus - int(boundary_loops);
  if(r.euler_surface != chi_surface)
    problem("surface layout has Euler characteristic " + std::to_string(r.euler_surface) + ", the surface " + std::to_string(chi_surface));
  if(r.euler_solid != 1 - genus)
    problem("cuboid complex has Euler characteristic " + std::to_string(r.euler_solid) + ", a genus-" + std::to_string(genus) +
            " solid " + std::to_string(1 - genus));
  return r;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_POLYCUBE_LAYOUT_H
