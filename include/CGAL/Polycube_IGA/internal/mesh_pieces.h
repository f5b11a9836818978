// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Cutting a surface mesh along edges into separate pieces (each a Surface_mesh with maps back
// to its parent), and gluing refined pieces back together. The layout stages work on disk
// pieces (convex maps, exact segment insertion) and must return one refined surface whose
// first vertices are the parent's; refinement never splits a piece's border edge, so the
// pieces still agree along every cut.
//
// Parent maps: "v:parent" and "f:parent" (std::size_t) give the index of the vertex / face
// of the parent mesh an element copies or was split from; no_parent marks vertices created
// by refinement. Meshes must be free of garbage (removed elements), since indices are the
// link between a piece and its parent.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_MESH_PIECES_H
#define CGAL_POLYCUBE_IGA_INTERNAL_MESH_PIECES_H

#include <CGAL/Polycube_IGA/Errors.h>

#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

constexpr std::size_t no_parent = std::size_t(-1);

template <class P>
using Vertex_parent_map = typename CGAL::Surface_mesh<P>::template Property_map<typename CGAL::Surface_mesh<P>::Vertex_index, std::size_t>;
template <class P>
using Face_parent_map = typename CGAL::Surface_mesh<P>::template Property_map<typename CGAL::Surface_mesh<P>::Face_index, std::size_t>;

/// "v:parent" of `m`, added (all no_parent) when missing.
template <class P>
Vertex_parent_map<P> vertex_parent_map(CGAL::Surface_mesh<P>& m)
{
  return m.template add_property_map<typename CGAL::Surface_mesh<P>::Vertex_index, std::size_t>("v:parent", no_parent).first;
}
/// "f:parent" of `m`, added (all no_parent) when missing.
template <class P>
Face_parent_map<P> face_parent_map(CGAL::Surface_mesh<P>& m)
{
  return m.template add_property_map<typename CGAL::Surface_mesh<P>::Face_index, std::size_t>("f:parent", no_parent).first;
}

template <class P>
typename CGAL::Surface_mesh<P>::Vertex_index vertex_at(std::size_t i)
{
  return typename CGAL::Surface_mesh<P>::Vertex_index(static_cast<std::uint32_t>(i));
}
template <class P>
typename CGAL::Surface_mesh<P>::Face_index face_at(std::size_t i)
{
  return typename CGAL::Surface_mesh<P>::Face_index(static_cast<std::uint32_t>(i));
}

/// Splits the edge of `h` at parameter t (0 at source(h), 1 at target(h)) and joins the new
/// vertex to the opposite corner of each incident triangle, so the mesh stays triangulated.
/// The new point is the linear interpolation of the edge's ends (the surface does not move).
/// Keeps the parent maps when they exist: the new vertex gets no_parent, the faces cut off
/// inherit the "f:parent" of the face they were split from; a "v:original_point" map (the
/// points of a surface the mesh is a deformation of) is interpolated as the points are. Returns the halfedge from
/// source(h) to the new vertex (h itself now runs from the new vertex to its old target).
template <class P>
typename CGAL::Surface_mesh<P>::Halfedge_index split_edge_at(CGAL::Surface_mesh<P>& m,
                                                             typename CGAL::Surface_mesh<P>::Halfedge_index h, double t)
{
  using Mesh = CGAL::Surface_mesh<P>;
  using F = typename Mesh::Face_index;
  const auto vpar = m.template property_map<typename Mesh::Vertex_index, std::size_t>("v:parent");
  const auto fpar = m.template property_map<F, std::size_t>("f:parent");
  const auto original = m.template property_map<typename Mesh::Vertex_index, P>("v:original_point");
  const double s = 1. - t;
  auto between = [&](const P& a, const P& b) {
    return P(s * CGAL::to_double(a.x()) + t * CGAL::to_double(b.x()), s * CGAL::to_double(a.y()) + t * CGAL::to_double(b.y()),
             s * CGAL::to_double(a.z()) + t * CGAL::to_double(b.z()));
  };
  const P x = between(m.point(source(h, m)), m.point(target(h, m)));
  const P x0 = original.second ? between(original.first[source(h, m)], original.first[target(h, m)]) : x;
  const bool left = !is_border(h, m), right = !is_border(opposite(h, m), m);
  const F fl = left ? face(h, m) : F(), fr = right ? face(opposite(h, m), m) : F();
  const auto hn = CGAL::Euler::split_edge(h, m); // source(h) -> new, next(hn) == h
  const auto nv = target(hn, m);
  m.point(nv) = x;
  if(original.second) original.first[nv] = x0;
  if(vpar.second) vpar.first[nv] = no_parent;
  if(left) {
    const auto g = CGAL::Euler::split_face(hn, next(h, m), m);
    if(fpar.second) fpar.first[face(opposite(g, m), m)] = fpar.first[fl];
  }
  if(right) {
    const auto on = opposite(hn, m); // new -> source(h)
    const auto g = CGAL::Euler::split_face(opposite(h, m), next(on, m), m);
    if(fpar.second) fpar.first[face(opposite(g, m), m)] = fpar.first[fr];
  }
  return hn;
}

/// Cuts `m` along the edges e with cut_edge[e.idx()] == true (border edges of m are
/// boundaries anyway; an empty vector cuts nothing) and returns the connected components as
/// separate meshes, ordered by their smallest face of m. A vertex is copied once per fan of
/// faces around it that cut edges and borders separate. Pieces carry "v:parent" and
/// "f:parent" (indices in m) and keep m's face orientation; a piece's vertices come in the
/// order its faces (by index in m) first use them. With `only` (flags by face of m), the
/// faces without the flag are left out, as if cut off: the pieces of a face set, without
/// copying the rest of m.
template <class P>
std::vector<CGAL::Surface_mesh<P>> cut_into_pieces(const CGAL::Surface_mesh<P>& m, const std::vector<bool>& cut_edge,
                                                   const std::vector<bool>& only = {})
{
  using Mesh = CGAL::Surface_mesh<P>;
  using V = typename Mesh::Vertex_index;
  if(m.has_garbage()) throw Internal_error("cut_failed", "cannot cut a mesh with removed elements (collect its garbage first)");
  if(!cut_edge.empty() && cut_edge.size() < num_edges(m)) throw Internal_error("cut_failed", "the cut edge flags do not cover every edge");
  const std::size_t nf = num_faces(m);
  if(!only.empty() && only.size() < nf) throw Internal_error("cut_failed", "the face flags do not cover every face");
  auto kept = [&](typename Mesh::Face_index f) { return only.empty() || only[std::size_t(f)]; };
  for(auto f : faces(m))
    if(degree(f, m) != 3) throw Internal_error("not_a_triangle_mesh", "cutting needs a triangle mesh");
  // Union-find over face corners 3f+k (the k-th vertex of face f): corners of one vertex
  // joined across every uncut interior edge form one copy of it.
  std::vector<std::size_t> uf(3 * nf);
  std::iota(uf.begin(), uf.end(), std::size_t(0));
  auto find = [&uf](std::size_t x) {
    while(uf[x] != x) x = uf[x] = uf[uf[x]];
    return x;
  };
  auto unite = [&](std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if(a != b) uf[std::max(a, b)] = std::min(a, b); // the smallest is the root: components start at their smallest face
  };
  auto corner = [&m](typename Mesh::Halfedge_index h) { // corner of target(h) in face(h)
    const auto f = face(h, m);
    std::size_t k = 0;
    for(auto g = halfedge(f, m); g != h; g = next(g, m)) ++k;
    return 3 * std::size_t(f) + k; // corner k: the target of the k-th halfedge from halfedge(f)
  };
  for(auto e : edges(m)) {
    if(!cut_edge.empty() && cut_edge[std::size_t(e)]) continue;
    const auto h = halfedge(e, m), o = opposite(h, m);
    if(is_border(h, m) || is_border(o, m) || !kept(face(h, m)) || !kept(face(o, m))) continue;
    // h: a -> b in f, o: b -> a in g. Corner of b in f = target(h); of b in g = source(o)
    // = target(prev(o)); of a in f = target(prev(h)); of a in g = target(o).
    unite(corner(h), corner(prev(o, m)));
    unite(corner(prev(h, m)), corner(o));
  }
  // Components: faces joined across uncut interior edges.
  std::vector<std::size_t> face_root(nf);
  std::iota(face_root.begin(), face_root.end(), std::size_t(0));
  auto ffind = [&face_root](std::size_t x) {
    while(face_root[x] != x) x = face_root[x] = face_root[face_root[x]];
    return x;
  };
  for(auto e : edges(m)) {
    if(!cut_edge.empty() && cut_edge[std::size_t(e)]) continue;
    const auto h = halfedge(e, m), o = opposite(h, m);
    if(is_border(h, m) || is_border(o, m) || !kept(face(h, m)) || !kept(face(o, m))) continue;
    const std::size_t a = ffind(std::size_t(face(h, m))), b = ffind(std::size_t(face(o, m)));
    if(a != b) face_root[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::size_t> component(nf, no_parent);
  std::size_t nc = 0;
  for(std::size_t f = 0; f < nf; ++f) {
    if(!kept(face_at<P>(f))) continue;
    const std::size_t r = ffind(f);
    if(component[r] == no_parent) component[r] = nc++;
    component[f] = component[r];
  }
  std::vector<Mesh> pieces(nc);
  std::vector<Vertex_parent_map<P>> vpar;
  std::vector<Face_parent_map<P>> fpar;
  for(Mesh& piece : pieces) {
    vpar.push_back(vertex_parent_map(piece));
    fpar.push_back(face_parent_map(piece));
  }
  std::vector<std::uint32_t> copy(3 * nf, std::uint32_t(-1)); // corner root -> piece vertex
  for(std::size_t f = 0; f < nf; ++f) {
    const auto fd = face_at<P>(f);
    if(!kept(fd)) continue;
    const std::size_t c = component[f];
    Mesh& piece = pieces[c];
    std::array<V, 3> vs;
    auto h = halfedge(fd, m);
    for(std::size_t k = 0; k < 3; ++k, h = next(h, m)) {
      const std::size_t r = find(3 * f + k);
      if(copy[r] == std::uint32_t(-1)) {
        const V nv = piece.add_vertex(m.point(target(h, m)));
        vpar[c][nv] = std::size_t(target(h, m));
        copy[r] = std::uint32_t(nv);
      }
      vs[k] = V(copy[r]);
    }
    const auto nfc = piece.add_face(vs[0], vs[1], vs[2]);
    if(nfc == Mesh::null_face()) throw Internal_error("cut_failed", "a face cannot be added to its piece");
    fpar[c][nfc] = f;
  }
  return pieces;
}

/// The vertices of the single border loop of `piece`, faces on the left (counter-clockwise
/// once the piece is embedded with positive orientation), from `start` (a border vertex) or
/// from the smallest border vertex. Throws Internal_error("not_a_disk") when the piece has no
/// border or more than one border loop, or `start` is not on the border.
template <class P>
std::vector<typename CGAL::Surface_mesh<P>::Vertex_index> border_loop(const CGAL::Surface_mesh<P>& piece,
                                                                      typename CGAL::Surface_mesh<P>::Vertex_index start = {})
{
  using H = typename CGAL::Surface_mesh<P>::Halfedge_index;
  using V = typename CGAL::Surface_mesh<P>::Vertex_index;
  H first;
  std::size_t loops = 0;
  std::vector<bool> seen(piece.number_of_halfedges() + piece.number_of_removed_halfedges(), false);
  for(auto h : halfedges(piece)) {
    if(!is_border(h, piece) || seen[h]) continue;
    ++loops;
    auto g = h;
    do {
      seen[g] = true;
      const bool wanted = start != V() ? target(g, piece) == start : (first == H() || target(g, piece) < target(first, piece));
      if(wanted) first = g;
      g = next(g, piece);
    } while(g != h);
  }
  if(loops != 1) throw Internal_error("not_a_disk", "a layout piece has " + std::to_string(loops) + " border loops instead of 1");
  if(first == H()) throw Internal_error("not_a_disk", "the start vertex is not on the border of the piece");
  std::vector<V> loop;
  auto g = first;
  do {
    loop.push_back(target(g, piece)); // border halfedges run against the faces: walk them backwards
    g = prev(g, piece);
  } while(g != first);
  return loop;
}

template <class P>
struct Glued_mesh
{
  CGAL::Surface_mesh<P> mesh;
  /// piece_to_result[k][v.idx()]: the result vertex of vertex v of piece k.
  std::vector<std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>> piece_to_result;
  /// The face of m each result face came from (never composed; "f:parent" may be, see glue_pieces).
  std::vector<std::size_t> face_in_m;
};

/// Glues the (refined) pieces of `m` back together. Result vertices: m's first (same indices,
/// same points), then the pieces' new vertices (v:parent == no_parent), piece by piece, in
/// index order. Faces: those of every piece, piece by piece, in index order.
/// Parent maps of the result:
///  - m without "f:parent" (a top-level mesh): "f:parent" = the face of m; no "v:parent".
///  - m with "f:parent"/"v:parent" (itself a piece of a larger mesh M): the result replaces m
///    as a piece of M, so its maps refer to M: "f:parent" = m's f:parent of the face of m it
///    came from, "v:parent" = m's v:parent for the first num_vertices(m) vertices and
///    no_parent for the new ones. The uncomposed face of m is in Glued_mesh::face_in_m.
/// Throws Internal_error("glue_failed") when a piece lacks its parent maps or the pieces do
/// not close up into a surface with m's border (e.g. a cut edge was split on one side only).
template <class P>
Glued_mesh<P> glue_pieces(const CGAL::Surface_mesh<P>& m, const std::vector<CGAL::Surface_mesh<P>>& pieces)
{
  using Mesh = CGAL::Surface_mesh<P>;
  using V = typename Mesh::Vertex_index;
  using F = typename Mesh::Face_index;
  if(m.has_garbage()) throw Internal_error("glue_failed", "cannot glue onto a mesh with removed elements");
  Glued_mesh<P> out;
  Mesh& r = out.mesh;
  const auto m_vpar = m.template property_map<V, std::size_t>("v:parent");
  const auto m_fpar = m.template property_map<F, std::size_t>("f:parent");
  const std::size_t nvm = num_vertices(m), nfm = num_faces(m);
  std::size_t total_v = nvm, total_f = 0;
  for(const Mesh& piece : pieces) {
    total_f += num_faces(piece);
    const auto pv = piece.template property_map<V, std::size_t>("v:parent");
    if(!pv.second) throw Internal_error("glue_failed", "a piece has no \"v:parent\" map");
    for(V v : vertices(piece))
      if(pv.first[v] == no_parent) ++total_v;
  }
  r.reserve(total_v, total_f + num_edges(m) + total_v, total_f);
  for(V v : vertices(m)) r.add_vertex(m.point(v));
  auto fpar = face_parent_map(r);
  Vertex_parent_map<P> vpar;
  if(m_vpar.second) {
    vpar = vertex_parent_map(r);
    for(V v : vertices(m)) vpar[v] = m_vpar.first[v];
  }
  out.face_in_m.reserve(total_f);
  for(const Mesh& piece : pieces) {
    const auto pv = piece.template property_map<V, std::size_t>("v:parent");
    const auto pf = piece.template property_map<F, std::size_t>("f:parent");
    if(!pf.second) throw Internal_error("glue_failed", "a piece has no \"f:parent\" map");
    if(piece.has_garbage()) throw Internal_error("glue_failed", "a piece has removed elements");
    std::vector<V> map(num_vertices(piece));
    for(V v : vertices(piece)) {
      const std::size_t p = pv.first[v];
      if(p == no_parent) map[v] = r.add_vertex(piece.point(v)); // v:parent of r (if any) defaults to no_parent
      else if(p < nvm) map[v] = V(static_cast<std::uint32_t>(p));
      else throw Internal_error("glue_failed", "a piece refers to a vertex its parent does not have");
    }
    for(auto f : faces(piece)) {
      std::array<V, 3> vs;
      std::size_t k = 0;
      for(V v : vertices_around_face(halfedge(f, piece), piece)) {
        if(k == 3) throw Internal_error("glue_failed", "gluing needs triangle pieces");
        vs[k++] = map[v];
      }
      if(k != 3) throw Internal_error("glue_failed", "gluing needs triangle pieces");
      const F nf = r.add_face(vs[0], vs[1], vs[2]);
      if(nf == Mesh::null_face()) throw Internal_error("glue_failed", "the glued pieces do not form a valid surface");
      const std::size_t pfi = pf.first[f];
      if(pfi >= nfm) throw Internal_error("glue_failed", "a piece face refers to a face its parent does not have");
      fpar[nf] = m_fpar.second ? m_fpar.first[face_at<P>(pfi)] : pfi;
      out.face_in_m.push_back(pfi);
    }
    out.piece_to_result.push_back(std::move(map));
  }
  // The pieces must close up along every cut: the result's border is exactly m's border.
  std::size_t border_r = 0, border_m = 0;
  for(auto h : halfedges(m))
    if(is_border(h, m)) ++border_m;
  for(auto h : halfedges(r)) {
    if(!is_border(h, r)) continue;
    ++border_r;
    const V a = source(h, r), b = target(h, r);
    bool ok = std::size_t(a) < nvm && std::size_t(b) < nvm;
    if(ok) {
      const auto hm = halfedge(a, b, m);
      ok = hm.second && is_border(hm.first, m);
    }
    if(!ok) throw Internal_error("glue_failed", "the glued pieces leave an open seam (pieces disagree along a cut)");
  }
  if(border_r != border_m) throw Internal_error("glue_failed", "the glued pieces do not cover the parent's border");
  return out;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_MESH_PIECES_H
