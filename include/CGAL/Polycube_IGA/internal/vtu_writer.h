// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// VTK XML unstructured grid (.vtu, ASCII) of a surface mesh with curves and points on it:
// cells of mixed types (faces, poly lines, vertices) with integer cell data, shared by the
// writers of layouts (IO/layout_vtk.h) and of pants decompositions (IO/pants_vtk.h).
// Coordinates are written with 17 significant digits (internal/number_text.h).

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_VTU_WRITER_H
#define CGAL_POLYCUBE_IGA_INTERNAL_VTU_WRITER_H

#include <CGAL/Polycube_IGA/internal/number_text.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

enum Vtk_cell_type { VTK_VERTEX = 1, VTK_POLY_LINE = 4, VTK_TRIANGLE = 5, VTK_POLYGON = 7 };

/// Cells with one Int32 value per cell for each named array (-1 where it does not apply).
struct Vtu_cells
{
  std::vector<std::int64_t> connectivity, offsets, types;
  std::vector<std::pair<std::string, std::vector<std::int64_t>>> data;

  explicit Vtu_cells(std::initializer_list<const char*> names)
  {
    for(const char* n : names) data.emplace_back(n, std::vector<std::int64_t>());
  }

  /// Closes the cell whose points were appended to `connectivity`; one value per array.
  void close_cell(int type, std::initializer_list<std::int64_t> values)
  {
    offsets.push_back(std::int64_t(connectivity.size()));
    types.push_back(type);
    auto it = values.begin();
    for(auto& d : data) d.second.push_back(it != values.end() ? *it++ : -1);
  }

  /// Appends face `f` of `tm` (points: vertex indices) and returns its cell type.
  template <class TriangleMesh, class VertexIndexMap>
  int append_face(const TriangleMesh& tm, typename boost::graph_traits<TriangleMesh>::face_descriptor f, VertexIndexMap vim)
  {
    std::size_t corners = 0;
    for(auto v : vertices_around_face(halfedge(f, tm), tm)) {
      connectivity.push_back(std::int64_t(get(vim, v)));
      ++corners;
    }
    return corners == 3 ? VTK_TRIANGLE : VTK_POLYGON;
  }
};

inline void write_vtk_int_array(std::ostream& os, const char* type, const std::string& name, const std::vector<std::int64_t>& v)
{
  os << "    <DataArray type=\"" << type << "\" Name=\"" << name << "\" format=\"ascii\">\n";
  for(std::int64_t x : v) os << x << '\n';
  os << "    </DataArray>\n";
}

/// The points of a mesh in vertex index order.
template <class TriangleMesh>
std::vector<std::array<double, 3>> vtu_points(const TriangleMesh& tm)
{
  const auto vim = CGAL::get_initialized_vertex_index_map(tm);
  const auto vpm = get(CGAL::vertex_point, tm);
  std::vector<std::array<double, 3>> p(num_vertices(tm));
  for(auto v : vertices(tm)) {
    const auto& q = get(vpm, v);
    p[std::size_t(get(vim, v))] = {{CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())}};
  }
  return p;
}

/// The grid: no point data, the cells' arrays as cell data (the first as active scalars).
inline void write_vtu(std::ostream& os, const std::vector<std::array<double, 3>>& points, const Vtu_cells& cells)
{
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
     << " <UnstructuredGrid>\n  <Piece NumberOfPoints=\"" << points.size() << "\" NumberOfCells=\"" << cells.types.size()
     << "\">\n";
  os << "   <PointData>\n   </PointData>\n   <CellData Scalars=\"" << (cells.data.empty() ? "" : cells.data[0].first)
     << "\">\n";
  for(const auto& [name, values] : cells.data) write_vtk_int_array(os, "Int32", name, values);
  os << "   </CellData>\n   <Points>\n    <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for(const auto& p : points) {
    for(std::size_t c = 0; c < 3; ++c) {
      if(c) os << ' ';
      write_double(os, p[c]);
    }
    os << '\n';
  }
  os << "    </DataArray>\n   </Points>\n   <Cells>\n";
  write_vtk_int_array(os, "Int64", "connectivity", cells.connectivity);
  write_vtk_int_array(os, "Int64", "offsets", cells.offsets);
  write_vtk_int_array(os, "UInt8", "types", cells.types);
  os << "   </Cells>\n  </Piece>\n </UnstructuredGrid>\n</VTKFile>\n";
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_VTU_WRITER_H
