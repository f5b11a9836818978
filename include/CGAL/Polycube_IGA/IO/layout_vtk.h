// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// VTK XML unstructured grid (.vtu, ASCII) of a Polycube_layout, for ParaView: the points
// are the vertices of the layout's mesh, the cells its faces, then its arcs as poly lines,
// then its nodes as vertices, with per-cell integer data telling them apart (`kind`) and
// naming the patch, cuboid, arc and node. Layouts that fail validate() are written too;
// indices out of range are rejected (internal_layout_io::check_layout_references).
// Written atomically (internal/atomic_file.h).

#ifndef CGAL_POLYCUBE_IGA_IO_LAYOUT_VTK_H
#define CGAL_POLYCUBE_IGA_IO_LAYOUT_VTK_H

#include <CGAL/Polycube_IGA/IO/layout_json.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/internal/atomic_file.h>
#include <CGAL/Polycube_IGA/internal/vtu_writer.h>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace IO {

/// \ingroup PkgPolycubeIGARef
/// Writes the layout as a VTK XML unstructured grid (ASCII). Points: the mesh vertices,
/// point i being vertex i of `L.mesh`; no point data. Cells, in this order:
/// - every mesh face in face order (VTK_TRIANGLE, VTK_POLYGON if not a triangle): `kind` 0,
///   `patch` the surface patch that lists the face (-1 if none), `cuboid` the cuboid that
///   has this patch as a side (the first one; -1 if none);
/// - every arc in arc order (VTK_POLY_LINE through its vertices): `kind` 1, `arc` its id;
/// - every node in node order (VTK_VERTEX): `kind` 2, `node` its id, `valence` the number
///   of arc ends at it.
/// Cell data `patch`, `cuboid`, `kind`, `arc`, `node`, `valence` (Int32) are -1 where they
/// do not apply. Throws Invalid_input_error `invalid_layout` if an index is out of range.
template <class P>
void write_layout_vtu(std::ostream& os, const Polycube_layout<P>& L)
{
  using Layout = Polycube_layout<P>;
  internal_layout_io::check_layout_references(L);
  const std::size_t nf = num_faces(L.mesh);

  std::vector<int> patch_of_face(nf, -1);
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    if(L.patches[p].kind == Layout::SURFACE)
      for(auto f : L.patches[p].faces)
        if(patch_of_face[std::size_t(f)] < 0) patch_of_face[std::size_t(f)] = int(p);
  const std::vector<int> cuboid_of_patch = internal_layout_io::cuboid_of_patch(L);
  const std::vector<int> valence = internal_layout_io::node_valences(L);

  namespace pii = CGAL::Polycube_IGA::internal;
  pii::Vtu_cells cells{"patch", "cuboid", "kind", "arc", "node", "valence"};
  const auto vim = CGAL::get_initialized_vertex_index_map(L.mesh);
  for(auto f : faces(L.mesh)) {
    const int type = cells.append_face(L.mesh, f, vim);
    const int p = patch_of_face[std::size_t(f)];
    cells.close_cell(type, {p, p >= 0 ? cuboid_of_patch[std::size_t(p)] : -1, 0});
  }
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    for(auto v : L.arcs[a].vertices) cells.connectivity.push_back(std::int64_t(get(vim, v)));
    cells.close_cell(pii::VTK_POLY_LINE, {-1, -1, 1, std::int64_t(a)});
  }
  for(std::size_t n = 0; n < L.nodes.size(); ++n) {
    cells.connectivity.push_back(std::int64_t(get(vim, L.nodes[n])));
    cells.close_cell(pii::VTK_VERTEX, {-1, -1, 2, -1, std::int64_t(n), valence[n]});
  }
  pii::write_vtu(os, pii::vtu_points(L.mesh), cells);
}

/// Writes write_layout_vtu(os, L) to `path` atomically: on any error no file is left
/// (Invalid_input_error `unwritable_output` if the file cannot be created).
template <class P>
void write_layout_vtu(const std::string& path, const Polycube_layout<P>& L)
{
  internal::write_file_atomically(path, [&](std::ostream& os) { write_layout_vtu(os, L); });
}

} // namespace IO
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_IO_LAYOUT_VTK_H
