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
#include <CGAL/Polycube_IGA/internal/number_text.h>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace IO {
namespace internal_layout_io {

inline void write_int_array(std::ostream& os, const char* type, const char* name, const std::vector<std::int64_t>& v)
{
  os << "    <DataArray type=\"" << type << "\" Name=\"" << name << "\" format=\"ascii\">\n";
  for(std::int64_t x : v) os << x << '\n';
  os << "    </DataArray>\n";
}

} // namespace internal_layout_io

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
  const std::size_t nv = num_vertices(L.mesh), nf = num_faces(L.mesh);

  std::vector<int> patch_of_face(nf, -1);
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    if(L.patches[p].kind == Layout::SURFACE)
      for(auto f : L.patches[p].faces)
        if(patch_of_face[std::size_t(f)] < 0) patch_of_face[std::size_t(f)] = int(p);
  const std::vector<int> cuboid_of_patch = internal_layout_io::cuboid_of_patch(L);
  const std::vector<int> valence = internal_layout_io::node_valences(L);

  std::vector<std::int64_t> connectivity, offsets, types, patch, cuboid, kind, arc, node, valences;
  // Called after the cell's points were appended to `connectivity`.
  auto add_cell = [&](int type, int k, int p, int c, int a, int n, int val) {
    offsets.push_back(std::int64_t(connectivity.size()));
    types.push_back(type);
    kind.push_back(k);
    patch.push_back(p);
    cuboid.push_back(c);
    arc.push_back(a);
    node.push_back(n);
    valences.push_back(val);
  };
  for(auto f : faces(L.mesh)) {
    std::size_t corners = 0;
    for(auto v : vertices_around_face(halfedge(f, L.mesh), L.mesh)) {
      connectivity.push_back(std::int64_t(std::size_t(v)));
      ++corners;
    }
    const int p = patch_of_face[std::size_t(f)];
    // VTK_TRIANGLE = 5, VTK_POLYGON = 7
    add_cell(corners == 3 ? 5 : 7, 0, p, p >= 0 ? cuboid_of_patch[std::size_t(p)] : -1, -1, -1, -1);
  }
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    for(auto v : L.arcs[a].vertices) connectivity.push_back(std::int64_t(std::size_t(v)));
    add_cell(4, 1, -1, -1, int(a), -1, -1); // VTK_POLY_LINE
  }
  for(std::size_t n = 0; n < L.nodes.size(); ++n) {
    connectivity.push_back(std::int64_t(std::size_t(L.nodes[n])));
    add_cell(1, 2, -1, -1, -1, int(n), valence[n]); // VTK_VERTEX
  }

  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
     << " <UnstructuredGrid>\n  <Piece NumberOfPoints=\"" << nv << "\" NumberOfCells=\"" << types.size() << "\">\n";
  os << "   <PointData>\n   </PointData>\n   <CellData Scalars=\"patch\">\n";
  internal_layout_io::write_int_array(os, "Int32", "patch", patch);
  internal_layout_io::write_int_array(os, "Int32", "cuboid", cuboid);
  internal_layout_io::write_int_array(os, "Int32", "kind", kind);
  internal_layout_io::write_int_array(os, "Int32", "arc", arc);
  internal_layout_io::write_int_array(os, "Int32", "node", node);
  internal_layout_io::write_int_array(os, "Int32", "valence", valences);
  os << "   </CellData>\n   <Points>\n    <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for(auto v : vertices(L.mesh)) {
    const auto p = internal_layout_io::to_array(L.mesh.point(v));
    for(int c = 0; c < 3; ++c) {
      if(c) os << ' ';
      CGAL::Polycube_IGA::internal::write_double(os, p[std::size_t(c)]);
    }
    os << '\n';
  }
  os << "    </DataArray>\n   </Points>\n   <Cells>\n";
  internal_layout_io::write_int_array(os, "Int64", "connectivity", connectivity);
  internal_layout_io::write_int_array(os, "Int64", "offsets", offsets);
  internal_layout_io::write_int_array(os, "UInt8", "types", types);
  os << "   </Cells>\n  </Piece>\n </UnstructuredGrid>\n</VTKFile>\n";
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
