// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// VTK XML unstructured grids (.vtu, ASCII) of multipatch volumes, for ParaView: the
// volumes sampled on a grid of points per knot span as linear hexahedra, with det J and the
// scaled Jacobian as point data and, per cell, the patch id and det J and scaled Jacobian
// at the cell centre; and, separately, the control nets as hexahedra of control points
// with the weights as point data. Writing is atomic (internal/atomic_file.h).

#ifndef CGAL_POLYCUBE_IGA_IO_VTU_H
#define CGAL_POLYCUBE_IGA_IO_VTU_H

#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/Quality.h>
#include <CGAL/Polycube_IGA/internal/atomic_file.h>
#include <CGAL/Polycube_IGA/internal/number_text.h>

#include <array>
#include <ostream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace IO {
namespace internal_vtu {

struct Grid
{
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<std::int64_t, 8>> cells;
  std::vector<std::pair<std::string, std::vector<double>>> point_data, cell_data;
  std::vector<int> cell_patch;
};

inline void write_array(std::ostream& os, const std::string& name, const std::vector<double>& v)
{
  os << "    <DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
  for(double x : v) {
    CGAL::Polycube_IGA::internal::write_double(os, x);
    os << '\n';
  }
  os << "    </DataArray>\n";
}

inline void write_grid(std::ostream& os, const Grid& g)
{
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
     << " <UnstructuredGrid>\n  <Piece NumberOfPoints=\"" << g.points.size() << "\" NumberOfCells=\"" << g.cells.size() << "\">\n";
  os << "   <PointData>\n";
  for(const auto& [name, v] : g.point_data) write_array(os, name, v);
  os << "   </PointData>\n   <CellData Scalars=\"patch\">\n    <DataArray type=\"Int32\" Name=\"patch\" format=\"ascii\">\n";
  for(int p : g.cell_patch) os << p << '\n';
  os << "    </DataArray>\n";
  for(const auto& [name, v] : g.cell_data) write_array(os, name, v);
  os << "   </CellData>\n   <Points>\n    <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for(const auto& p : g.points) {
    for(int c = 0; c < 3; ++c) {
      if(c) os << ' ';
      CGAL::Polycube_IGA::internal::write_double(os, p[c]);
    }
    os << '\n';
  }
  os << "    </DataArray>\n   </Points>\n   <Cells>\n    <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for(const auto& c : g.cells) {
    for(int k = 0; k < 8; ++k) os << (k ? " " : "") << c[std::size_t(k)];
    os << '\n';
  }
  os << "    </DataArray>\n    <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for(std::size_t i = 0; i < g.cells.size(); ++i) os << 8 * (i + 1) << '\n';
  os << "    </DataArray>\n    <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for(std::size_t i = 0; i < g.cells.size(); ++i) os << "12\n"; // VTK_HEXAHEDRON
  os << "    </DataArray>\n   </Cells>\n  </Piece>\n </UnstructuredGrid>\n</VTKFile>\n";
}

/// Adds the hexahedra of an n0 x n1 x n2 lattice whose first point has index `base`.
inline void add_lattice_cells(Grid& g, std::int64_t base, const std::array<int, 3>& n, int patch)
{
  auto id = [&](int i, int j, int k) { return base + i + std::int64_t(n[0]) * (j + std::int64_t(n[1]) * k); };
  for(int k = 0; k + 1 < n[2]; ++k)
    for(int j = 0; j + 1 < n[1]; ++j)
      for(int i = 0; i + 1 < n[0]; ++i) {
        g.cells.push_back({{id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                            id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)}});
        g.cell_patch.push_back(patch);
      }
}

inline std::pair<double, double> jacobian_figures(const Tensor_bspline_volume& v, const std::array<double, 3>& t)
{
  const auto d = v.derivatives(t, 1);
  const double det = d.first[0].dot(d.first[1].cross(d.first[2]));
  const double len = d.first[0].norm() * d.first[1].norm() * d.first[2].norm();
  return {det, len > 0. ? det / len : 0.};
}

} // namespace internal_vtu

/// The volumes sampled with `samples_per_span` points per knot span and direction (>= 2).
inline void write_vtu(std::ostream& os, const Multipatch_volume& mp, int samples_per_span = 4)
{
  internal_vtu::Grid g;
  g.point_data = {{"jacobian", {}}, {"scaled_jacobian", {}}};
  g.cell_data = {{"jacobian", {}}, {"scaled_jacobian", {}}};
  for(std::size_t p = 0; p < mp.number_of_patches(); ++p) {
    const Tensor_bspline_volume& v = mp.patch(p);
    std::array<std::vector<double>, 3> t;
    std::array<int, 3> n;
    for(int d = 0; d < 3; ++d) {
      t[std::size_t(d)] = internal::span_samples(v.knot_vector(d), samples_per_span);
      n[std::size_t(d)] = int(t[std::size_t(d)].size());
    }
    const std::int64_t base = std::int64_t(g.points.size());
    for(double w : t[2])
      for(double vv : t[1])
        for(double u : t[0]) {
          g.points.push_back(v.evaluate({u, vv, w}));
          const auto [det, sj] = internal_vtu::jacobian_figures(v, {u, vv, w});
          g.point_data[0].second.push_back(det);
          g.point_data[1].second.push_back(sj);
        }
    internal_vtu::add_lattice_cells(g, base, n, int(p));
    for(int k = 0; k + 1 < n[2]; ++k)
      for(int j = 0; j + 1 < n[1]; ++j)
        for(int i = 0; i + 1 < n[0]; ++i) {
          const std::array<double, 3> c{{0.5 * (t[0][std::size_t(i)] + t[0][std::size_t(i + 1)]),
                                         0.5 * (t[1][std::size_t(j)] + t[1][std::size_t(j + 1)]),
                                         0.5 * (t[2][std::size_t(k)] + t[2][std::size_t(k + 1)])}};
          const auto [det, sj] = internal_vtu::jacobian_figures(v, c);
          g.cell_data[0].second.push_back(det);
          g.cell_data[1].second.push_back(sj);
        }
  }
  internal_vtu::write_grid(os, g);
}

inline void write_vtu(const std::string& path, const Multipatch_volume& mp, int samples_per_span = 4)
{
  internal::write_file_atomically(path, [&](std::ostream& os) { write_vtu(os, mp, samples_per_span); });
}

/// The control nets: control points joined as hexahedra, weights as point data.
inline void write_control_net_vtu(std::ostream& os, const Multipatch_volume& mp)
{
  internal_vtu::Grid g;
  g.point_data = {{"weight", {}}};
  for(std::size_t p = 0; p < mp.number_of_patches(); ++p) {
    const Tensor_bspline_volume& v = mp.patch(p);
    const std::int64_t base = std::int64_t(g.points.size());
    for(std::size_t i = 0; i < v.number_of_control_points(); ++i) {
      g.points.push_back(v.control_points()[i]);
      g.point_data[0].second.push_back(v.weight(i));
    }
    internal_vtu::add_lattice_cells(g, base, v.control_net_size(), int(p));
  }
  internal_vtu::write_grid(os, g);
}

inline void write_control_net_vtu(const std::string& path, const Multipatch_volume& mp)
{
  internal::write_file_atomically(path, [&](std::ostream& os) { write_control_net_vtu(os, mp); });
}

} // namespace IO
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_IO_VTU_H
