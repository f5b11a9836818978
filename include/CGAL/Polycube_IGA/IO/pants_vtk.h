// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// VTK XML unstructured grid (.vtu, ASCII) of a pants decomposition, for ParaView: the
// decomposition's mesh with every face coloured by its pants, and the cycles as closed poly
// lines telling input boundary loops, handle loops and cuts apart. Written atomically
// (internal/atomic_file.h).

#ifndef CGAL_POLYCUBE_IGA_IO_PANTS_VTK_H
#define CGAL_POLYCUBE_IGA_IO_PANTS_VTK_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Pants_decomposition.h>
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
/// Writes the pants decomposition `r` of `tm` as a VTK XML unstructured grid (ASCII).
/// Points: the vertices of `r.mesh(tm)` (the refined mesh when the decomposition refined
/// it), point i being the vertex of index i; no point data. Cells, in this order:
/// - every face in face order (VTK_TRIANGLE, VTK_POLYGON if not a triangle): `pants` the
///   pants that lists it (-1 if none);
/// - every cycle in cycle order (VTK_POLY_LINE through its vertices, closed by repeating
///   the first): `cycle` its id, `kind` 0 input boundary loop, 1 handle loop, 2 cut
///   (`Pants_cycle::Kind`).
/// Cell data `pants`, `cycle`, `kind` (Int32) are -1 where they do not apply. Throws
/// Invalid_input_error `invalid_pants` if a face or vertex of `r` is not in the mesh.
template <class TriangleMesh>
void write_pants_vtu(std::ostream& os, const TriangleMesh& tm, const Pants_decomposition_result<TriangleMesh>& r)
{
  namespace pii = CGAL::Polycube_IGA::internal;
  const TriangleMesh& m = r.mesh(tm);
  const auto vim = CGAL::get_initialized_vertex_index_map(m);
  const auto fim = CGAL::get_initialized_face_index_map(m);
  const std::size_t nv = num_vertices(m), nf = num_faces(m);
  std::vector<int> pants_of_face(nf, -1);
  for(std::size_t k = 0; k < r.pants.size(); ++k)
    for(auto f : r.pants[k].faces) {
      const std::size_t i = std::size_t(get(fim, f));
      if(i >= nf) throw Invalid_input_error("invalid_pants", "pants " + std::to_string(k) + " lists a face not in the mesh");
      pants_of_face[i] = int(k);
    }
  pii::Vtu_cells cells{"pants", "cycle", "kind"};
  for(auto f : faces(m)) {
    const int type = cells.append_face(m, f, vim);
    cells.close_cell(type, {pants_of_face[std::size_t(get(fim, f))]});
  }
  for(std::size_t c = 0; c < r.cycles.size(); ++c) {
    const auto& vs = r.cycles[c].vertices;
    for(std::size_t i = 0; i <= vs.size() && !vs.empty(); ++i) {
      const std::size_t x = std::size_t(get(vim, vs[i % vs.size()]));
      if(x >= nv) throw Invalid_input_error("invalid_pants", "cycle " + std::to_string(c) + " passes a vertex not in the mesh");
      cells.connectivity.push_back(std::int64_t(x));
    }
    cells.close_cell(pii::VTK_POLY_LINE, {-1, std::int64_t(c), std::int64_t(r.cycles[c].kind)});
  }
  pii::write_vtu(os, pii::vtu_points(m), cells);
}

/// Writes write_pants_vtu(os, tm, r) to `path` atomically: on any error no file is left
/// (Invalid_input_error `unwritable_output` if the file cannot be created).
template <class TriangleMesh>
void write_pants_vtu(const std::string& path, const TriangleMesh& tm, const Pants_decomposition_result<TriangleMesh>& r)
{
  internal::write_file_atomically(path, [&](std::ostream& os) { write_pants_vtu(os, tm, r); });
}

} // namespace IO
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_IO_PANTS_VTK_H
