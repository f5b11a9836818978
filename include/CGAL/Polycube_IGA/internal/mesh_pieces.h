// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Cutting a surface mesh along edges into separate pieces (each a Surface_mesh with maps back
// to its parent), and gluing refined pieces back together. The layout stages work on disk
// pieces (convex maps, exact segment insertion) and must return one refined surface whose
// first vertices are the parent's; refinement never splits a piece's border edge, so the
// pieces still agree along every cut.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_MESH_PIECES_H
#define CGAL_POLYCUBE_IGA_INTERNAL_MESH_PIECES_H

#include <CGAL/Polycube_IGA/Errors.h>

#include <CGAL/Surface_mesh.h>

#include <algorithm>
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

template <class P>
Vertex_parent_map<P> vertex_parent_map(CGAL::Surface_mesh<P>& m)
{
  return m.template add_property_map<typename CGAL::Surface_mesh<P>::Vertex_index, std::size_t>("v:parent", no_parent).first;
}
template <class P>
Face_parent_map<P> face_parent_map(CGAL::Surface_mesh<P>& m)
{
  return m.template add_property_map<typename CGAL::Surface_mesh<P>::Face_index, std::size_t>("f:parent", no_parent).first;
}

/// Cuts `m` along the edges e with cut_edge[e] (borders are boundaries anyway) and returns
/// the connected components, ordered by their smallest face. Vertices are copied once per
/// fan of faces around them that cut edges and borders separate. Pieces carry "v:parent"
/// and "f:parent" (indices in m).
template <class P>
std::vector<CGAL::Surface_mesh<P>> cut_into_pieces(const CGAL::Surface_mesh<P>& m, const std::vector<bool>& cut_edge)
{
  using Mesh = CGAL::Surface_mesh<P>;
  using V = typename Mesh::Vertex_index;
  const std::size_t nf = num_faces(m);
  std::vector<std::size_t> uf(3 * nf); // corners 3f+k: the k-th vertex of face f
  std::iota(uf.begin(), uf.end(), std::size_t(0));
  auto find = [&uf](std::size_t x) {
    while(uf[x] != x) x = uf[x] = uf[uf[x]];
    return x;
  };
  auto unite = [&](std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if(a != b) uf[std::max(a, b)] = std::min(a, b);
  };
  auto corner = [&m](typename Mesh::Face_index f, V v) {
    std::size_t k = 0;
    for(V w : vertices_around_face(halfedge(f, m), m)) {
      if(w == v) return 3 * std::size_t(f) + k;
      ++k;
    }
    throw Internal_error("not_a_triangle_mesh", "a face does not contain its vertex");
  };
  for(auto f : faces(m))
    if(degree(f, m) != 3) throw Internal_error("not_a_triangle_mesh", "cutting needs a triangle mesh");
  std::vector<std::size_t> face_root(nf);
  std::iota(face_root.begin(), face_root.end(), std::size_t(0));
  auto ffind = [&face_root](std::size_t x) {
    while(face_root[x] != x) x = face_root[x] = face_root[face_root[x]];
    return x;
  };
  for(auto e : edges(m)) {
    if(!cut_edge.empty() && cut_edge[std::size_t(e)]) continue;
    const auto h = halfedge(e, m), o = opposite(h, m);
    if(is_border(h, m) || is_border(o, m)) continue;
    const auto f = face(h, m), g = face(o, m);
    unite(corner(f, source(h, m)), corner(g, target(o, m)));
    unite(corner(f, target(h, m)), corner(g, source(o, m)));
    const std::size_t a = ffind(std::size_t(f)), b = ffind(std::size_t(g));
    if(a != b) face_root[std::max(a, b)] = std::min(a, b);
  }
  // Components in order of their smallest face (the root is the smallest by construction).
  std::vector<std::size_t> component(nf, no_parent);
  std::size_t nc = 0;
  for(std::size_t f = 0; f < nf; ++f) {
    const std::size_t r = ffind(f);
    if(component[r] == no_parent) component[r] = nc++;
    component[f] = component[r];
  }
  std::vector<Mesh> pieces(nc);
  std::vector<std::size_t> new_vertex(3 * nf, no_parent);
  for(std::size_t f = 0; f < nf; ++f) {
    const typename Mesh::Face_index fd(static_cast<std::uint32_t>(f));
    Mesh& piece = pieces[component[f]];
    auto vpar = vertex_parent_map(piece);
    auto fpar = face_parent_map(piece);
    std::vector<V> vs;
    std::size_t k = 0;
    for(V v : vertices_around_face(halfedge(fd, m), m)) {
      const std::size_t r = find(3 * f + k++);
      if(new_vertex[r] == no_parent) {
        const V nv = piece.add_vertex(m.point(v));
        vpar[nv] = std::size_t(v);
        new_vertex[r] = std::size_t(nv);
      }
      vs.push_back(V(static_cast<std::uint32_t>(new_vertex[r])));
    }
    const auto nfc = piece.add_face(vs);
    if(nfc == Mesh::null_face()) throw Internal_error("cut_failed", "a face cannot be added to its piece");
    fpar[nfc] = f;
  }
  return pieces;
}

/// The single border loop of `piece`, faces on the left (counter-clockwise once embedded
/// with positive orientation), from `start` or from the smallest border vertex.
template <class P>
std::vector<typename CGAL::Surface_mesh<P>::Vertex_index> border_loop(const CGAL::Surface_mesh<P>& piece,
                                                                      typename CGAL::Surface_mesh<P>::Vertex_index start = {})
{
  using H = typename CGAL::Surface_mesh<P>::Halfedge_index;
  H first;
  std::size_t loops = 0;
  std::vector<bool> seen(num_halfedges(piece), false);
  for(auto h : halfedges(piece)) {
    if(!is_border(h, piece) || seen[h]) continue;
    ++loops;
    auto g = h;
    do {
      seen[g] = true;
      const bool wanted = start != decltype(start)() ? target(g, piece) == start
                                                     : (first == H() || target(g, piece) < target(first, piece));
      if(wanted) first = g;
      g = next(g, piece);
    } while(g != h);
  }
  if(loops != 1) throw Internal_error("not_a_disk", "a layout piece has " + std::to_string(loops) + " border loops instead of 1");
  if(first == H()) throw Internal_error("not_a_disk", "the start vertex is not on the border");
  std::vector<typename CGAL::Surface_mesh<P>::Vertex_index> loop;
  auto g = first;
  do {
    loop.push_back(target(g, piece)); // border halfedges run clockwise: walk them backwards
    g = prev(g, piece);
  } while(g != first);
  return loop;
}

template <class P>
struct Glued_mesh
{
  CGAL::Surface_mesh<P> mesh;
  std::vector<std::vector<typename CGAL::Surface_mesh<P>::Vertex_index>> piece_to_result;
};

/// Glues pieces of `m` back: the result's first vertices are m's; then the pieces' new
/// vertices (v:parent == no_parent), piece by piece. Faces of all pieces, in piece order,
/// with "f:parent" the face of m they came from. When m itself has "v:parent"/"f:parent"
/// (it is a piece of a larger mesh), the result carries them composed: vertices of m keep
/// m's parent, new ones have none, faces refer to m's parent faces.
template <class P>
Glued_mesh<P> glue_pieces(const CGAL::Surface_mesh<P>& m, const std::vector<CGAL::Surface_mesh<P>>& pieces)
{
  using Mesh = CGAL::Surface_mesh<P>;
  using V = typename Mesh::Vertex_index;
  Glued_mesh<P> out;
  Mesh& r = out.mesh;
  const auto m_vpar = m.template property_map<V, std::size_t>("v:parent");
  const auto m_fpar = m.template property_map<typename Mesh::Face_index, std::size_t>("f:parent");
  auto vpar = vertex_parent_map(r);
  auto fpar = face_parent_map(r);
  for(V v : vertices(m)) {
    const V nv = r.add_vertex(m.point(v));
    vpar[nv] = m_vpar.second ? m_vpar.first[v] : std::size_t(v);
  }
  for(const Mesh& piece : pieces) {
    const auto pv = piece.template property_map<V, std::size_t>("v:parent");
    const auto pf = piece.template property_map<typename Mesh::Face_index, std::size_t>("f:parent");
    if(!pv.second || !pf.second) throw Internal_error("glue_failed", "a piece has no parent maps");
    std::vector<V> map(num_vertices(piece));
    for(V v : vertices(piece)) {
      if(pv.first[v] != no_parent) map[v] = V(static_cast<std::uint32_t>(pv.first[v]));
      else {
        map[v] = r.add_vertex(piece.point(v));
        vpar[map[v]] = no_parent;
      }
    }
    for(auto f : faces(piece)) {
      std::vector<V> vs;
      for(V v : vertices_around_face(halfedge(f, piece), piece)) vs.push_back(map[v]);
      const auto nf = r.add_face(vs);
      if(nf == Mesh::null_face()) throw Internal_error("glue_failed", "glued pieces do not form a valid surface");
      const std::size_t pfi = pf.first[f];
      fpar[nf] = m_fpar.second ? m_fpar.first[typename Mesh::Face_index(static_cast<std::uint32_t>(pfi))] : pfi;
    }
    out.piece_to_result.push_back(std::move(map));
  }
  if(!m_vpar.second) {
    // A top-level glue: parents are the identity on m's vertices; no maps are needed.
    r.remove_property_map(vpar);
  }
  return out;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_MESH_PIECES_H
