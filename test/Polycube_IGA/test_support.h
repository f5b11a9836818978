// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Helpers shared by the test files: data paths, temporary files, small mesh generators
// (voxel plates of any genus and boundary count, parametric tori) and running the CLI.

#ifndef POLYCUBE_IGA_TEST_SUPPORT_H
#define POLYCUBE_IGA_TEST_SUPPORT_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polycube_IGA/IO/read_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace test_support {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

inline std::string data(const std::string& name) { return std::string(POLYCUBE_IGA_TEST_DATA_DIR) + "/" + name; }

/// A fresh temporary directory per test process, removed with its files when the process
/// ends, so that a CTest run (one process per case) leaves nothing behind in /tmp.
inline std::string temp_path(const std::string& name)
{
  struct Temporary_directory
  {
    std::string path;
    Temporary_directory()
    {
      char tmpl[] = "/tmp/polycube_iga_test_XXXXXX";
      if(const char* d = mkdtemp(tmpl)) path = d;
    }
    ~Temporary_directory()
    {
      std::error_code ignored;
      if(!path.empty()) std::filesystem::remove_all(path, ignored);
    }
  };
  static const Temporary_directory dir;
  return (dir.path.empty() ? std::string("/tmp") : dir.path) + "/" + name;
}

inline std::string write_text(const std::string& name, const std::string& text)
{
  const std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// The whole text of a file ("" if it cannot be read).
inline std::string slurp(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Reads a mesh and requires it to be valid.
inline Mesh load(const std::string& path)
{
  Mesh m;
  CGAL::Polycube_IGA::Validation_report r = CGAL::Polycube_IGA::read_triangle_mesh(path, m);
  r.require_valid();
  return m;
}

using Polygon = std::vector<std::size_t>;

inline std::string off_text(const std::vector<std::array<double, 3>>& points, const std::vector<Polygon>& polygons)
{
  std::ostringstream os;
  os.precision(17);
  os << "OFF\n" << points.size() << " " << polygons.size() << " 0\n";
  for(const auto& p : points) os << p[0] << " " << p[1] << " " << p[2] << "\n";
  for(const auto& f : polygons) {
    os << f.size();
    for(std::size_t v : f) os << " " << v;
    os << "\n";
  }
  return os.str();
}

/// Boundary surface of a one-voxel-thick plate of nx x ny cells with the cells in `holes`
/// removed (each hole adds a handle), as quads; `open_tops` lists cells whose top face is
/// left out (each adds a boundary loop). Holes and open tops must not touch each other.
inline std::string voxel_plate_off(int nx, int ny, const std::set<std::pair<int, int>>& holes,
                                   const std::set<std::pair<int, int>>& open_tops)
{
  std::map<std::array<int, 3>, std::size_t> index;
  std::vector<std::array<double, 3>> points;
  std::vector<Polygon> quads;
  auto vid = [&](int x, int y, int z) {
    auto it = index.find({x, y, z});
    if(it != index.end()) return it->second;
    index[{x, y, z}] = points.size();
    points.push_back({double(x), double(y), double(z)});
    return points.size() - 1;
  };
  auto filled = [&](int x, int y) { return x >= 0 && y >= 0 && x < nx && y < ny && !holes.count({x, y}); };
  for(int x = 0; x < nx; ++x)
    for(int y = 0; y < ny; ++y) {
      if(!filled(x, y)) continue;
      // bottom (normal -z) and top (normal +z), counter-clockwise seen from outside
      quads.push_back({vid(x, y, 0), vid(x, y + 1, 0), vid(x + 1, y + 1, 0), vid(x + 1, y, 0)});
      if(!open_tops.count({x, y}))
        quads.push_back({vid(x, y, 1), vid(x + 1, y, 1), vid(x + 1, y + 1, 1), vid(x, y + 1, 1)});
      if(!filled(x - 1, y)) quads.push_back({vid(x, y, 0), vid(x, y, 1), vid(x, y + 1, 1), vid(x, y + 1, 0)});
      if(!filled(x + 1, y)) quads.push_back({vid(x + 1, y, 0), vid(x + 1, y + 1, 0), vid(x + 1, y + 1, 1), vid(x + 1, y, 1)});
      if(!filled(x, y - 1)) quads.push_back({vid(x, y, 0), vid(x + 1, y, 0), vid(x + 1, y, 1), vid(x, y, 1)});
      if(!filled(x, y + 1)) quads.push_back({vid(x, y + 1, 0), vid(x, y + 1, 1), vid(x + 1, y + 1, 1), vid(x + 1, y + 1, 0)});
    }
  return off_text(points, quads);
}

/// Boundary surface of a union of unit cubes (`cells`, by their lowest corners), as quads,
/// each cube split into `split`^3 (finer meshes of the same solid).
inline std::string voxel_solid_off(const std::set<std::array<int, 3>>& cells, int split = 1)
{
  std::set<std::array<int, 3>> fine;
  for(const auto& c : cells)
    for(int i = 0; i < split * split * split; ++i)
      fine.insert({split * c[0] + i % split, split * c[1] + i / split % split, split * c[2] + i / (split * split)});
  std::map<std::array<int, 3>, std::size_t> index;
  std::vector<std::array<double, 3>> points;
  std::vector<Polygon> quads;
  auto vid = [&](std::array<int, 3> p) {
    auto it = index.find(p);
    if(it != index.end()) return it->second;
    index[p] = points.size();
    points.push_back({double(p[0]) / split, double(p[1]) / split, double(p[2]) / split});
    return points.size() - 1;
  };
  for(const auto& c : fine)
    for(int a = 0; a < 3; ++a)
      for(int s : {-1, 1}) {
        std::array<int, 3> n = c;
        n[a] += s;
        if(fine.count(n)) continue;
        // The face across axis a; (u, v) cyclic after a, so u x v points along +a.
        const int u = (a + 1) % 3, v = (a + 2) % 3;
        std::array<int, 3> p = c;
        if(s > 0) ++p[a];
        std::array<std::array<int, 3>, 4> q{p, p, p, p};
        ++q[1][u];
        ++q[2][u], ++q[2][v];
        ++q[3][v];
        if(s > 0) quads.push_back({vid(q[0]), vid(q[1]), vid(q[2]), vid(q[3])});
        else quads.push_back({vid(q[0]), vid(q[3]), vid(q[2]), vid(q[1])});
      }
  return off_text(points, quads);
}

/// An L of unit cubes, 4 by 3 by 1 (a CAD block: the plate without the cells x >= 1, y >= 1).
inline std::string voxel_l_off()
{
  return voxel_plate_off(4, 3, {{1, 1}, {2, 1}, {3, 1}, {1, 2}, {2, 2}, {3, 2}}, {});
}

/// A plate with `genus` holes in a row and `boundaries` open top cells in a second row.
inline std::string voxel_plate_with(int genus, int boundaries)
{
  std::set<std::pair<int, int>> holes, tops;
  for(int i = 0; i < genus; ++i) holes.insert({1 + 2 * i, 1});
  for(int i = 0; i < boundaries; ++i) tops.insert({1 + 2 * i, 3});
  const int nx = 2 * std::max(genus, boundaries) + 1;
  return voxel_plate_off(nx, boundaries > 0 ? 5 : 3, holes, tops);
}

/// Torus of major radius R and minor radius r, n x m vertices.
inline std::string torus_off(double R, double r, int n, int m)
{
  std::vector<std::array<double, 3>> points;
  std::vector<Polygon> tris;
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      points.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto id = [&](int i, int j) { return std::size_t(((i + n) % n) * m + (j + m) % m); };
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < m; ++j) {
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return off_text(points, tris);
}

/// An open straight blade along y, `length` long, `rings` + 1 rings of `around` vertices:
/// each section the ellipse x = a cos t, z = b sin t (a flat blade for b << a), or with
/// `power` p the superellipse |x/a|^p + |z/b|^p = 1 (p = 4: a square with round corners).
/// With `step` > 0 the ends are stepped: the half z < 0 starts `step` rings later than the
/// half z > 0, and the half z > 0 ends `step` rings earlier.
inline std::string blade_off(double a, double b, double length, int around, int rings, double power = 2, int step = 0)
{
  std::vector<std::array<double, 3>> points;
  std::vector<Polygon> tris;
  std::vector<std::size_t> index(std::size_t((rings + 1) * around), std::size_t(-1));
  auto id = [&](int i, int j) {
    const std::size_t k = std::size_t(j * around + (i + around) % around);
    if(index[k] == std::size_t(-1)) {
      const double t = -2 * M_PI * ((i + around) % around) / around; // faces outwards
      const double r = std::pow(std::pow(std::abs(std::cos(t)), power) + std::pow(std::abs(std::sin(t)), power), -1 / power);
      index[k] = points.size();
      points.push_back({a * r * std::cos(t), length * j / rings, b * r * std::sin(t)});
    }
    return index[k];
  };
  for(int j = 0; j < rings; ++j)
    for(int i = 0; i < around; ++i) {
      const bool upper = std::sin(-2 * M_PI * (i + 0.5) / around) > 0;
      if(upper ? j >= rings - step : j < step) continue;
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return off_text(points, tris);
}

/// A closed capsule along z: a tube of radius r, `length` long between the centres of its
/// two hemispherical ends, `around` vertices round it (a multiple of 4) and rings about as
/// far apart as they are round; with `bulb` > 0 each end swells like a bone's, by up to that
/// fraction of r.
inline std::string capsule_off(double r, double length, int around, double bulb = 0.)
{
  std::vector<std::array<double, 3>> points;
  std::vector<Polygon> tris;
  std::vector<std::array<double, 2>> profile; // (radius, z), poles excluded
  const int quarter = around / 4;
  const int rings = std::max(2, int(std::lround(length / (2 * M_PI * r / around))));
  for(int i = 1; i <= quarter; ++i) profile.push_back({r * std::sin(M_PI / 2 * i / quarter), -length / 2 - r * std::cos(M_PI / 2 * i / quarter)});
  for(int i = 1; i < rings; ++i) profile.push_back({r, -length / 2 + length * i / rings});
  for(int i = quarter; i >= 1; --i) profile.push_back({r * std::sin(M_PI / 2 * i / quarter), length / 2 + r * std::cos(M_PI / 2 * i / quarter)});
  points.push_back({0., 0., -length / 2 - r});
  for(const auto& rz : profile) {
    const double swell = 1. + bulb * std::exp(-std::pow((std::abs(rz[1]) - length / 2) / r, 2));
    for(int j = 0; j < around; ++j) {
      const double t = 2 * M_PI * j / around;
      points.push_back({swell * rz[0] * std::cos(t), swell * rz[0] * std::sin(t), rz[1]});
    }
  }
  points.push_back({0., 0., length / 2 + r});
  const std::size_t top = points.size() - 1, n = profile.size();
  auto id = [&](std::size_t k, int j) { return 1 + k * std::size_t(around) + std::size_t((j + around) % around); };
  for(int j = 0; j < around; ++j) {
    tris.push_back({0, id(0, j + 1), id(0, j)});
    tris.push_back({top, id(n - 1, j), id(n - 1, j + 1)});
    for(std::size_t k = 0; k + 1 < n; ++k) {
      tris.push_back({id(k, j), id(k, j + 1), id(k + 1, j + 1)});
      tris.push_back({id(k, j), id(k + 1, j + 1), id(k + 1, j)});
    }
  }
  return off_text(points, tris);
}

struct Cli_result
{
  int exit_code = -1;
  std::string out, err;
};

/// Runs the `polycube_iga` tool with `args` (a shell-quoted string).
inline Cli_result run_cli(const std::string& args)
{
  static int counter = 0;
  const std::string out = temp_path("cli_out_" + std::to_string(counter)), err = temp_path("cli_err_" + std::to_string(counter));
  ++counter;
  const std::string cmd = std::string("'") + POLYCUBE_IGA_CLI + "' " + args + " > '" + out + "' 2> '" + err + "'";
  const int status = std::system(cmd.c_str());
  Cli_result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream o(out), e(err);
  std::stringstream so, se;
  so << o.rdbuf();
  se << e.rdbuf();
  r.out = so.str();
  r.err = se.str();
  return r;
}

} // namespace test_support

#endif
