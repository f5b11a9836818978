// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Mesh input: OFF, OBJ, PLY and STL (ASCII and binary) through CGAL's polygon-soup
// readers; the soup is validated and oriented (Input_validation.h), its polygons are
// triangulated, and the result is a Surface_mesh whose property maps `v:input_index`
// and `f:input_index` give, for every vertex and triangle, the index in the input file.
// Nothing is built from an invalid input: the report says why.

#ifndef CGAL_POLYCUBE_IGA_IO_READ_TRIANGLE_MESH_H
#define CGAL_POLYCUBE_IGA_IO_READ_TRIANGLE_MESH_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/Input_validation.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Names of the property maps that link a mesh built by the package to its input file.
inline const char* input_vertex_index_property() { return "v:input_index"; }
inline const char* input_face_index_property() { return "f:input_index"; }

namespace internal {

inline std::string lower_extension(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.');
  if(dot == std::string::npos || path.find_first_of("/\\", dot) != std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

/// CGAL's stream readers stop at "nan"/"inf" tokens, which would hide the real problem
/// behind `unreadable`. This permissive second reading of ASCII OFF and OBJ accepts them
/// (strtod does), only to name the problem precisely.
template <class Point>
bool read_ascii_soup_permissively(const std::string& path, const std::string& ext,
                                  std::vector<Point>& points,
                                  std::vector<std::vector<std::size_t>>& polygons)
{
  std::ifstream in(path);
  if(!in) return false;
  auto number = [](const std::string& tok, double& out) {
    char* end = nullptr;
    out = std::strtod(tok.c_str(), &end);
    return end != tok.c_str() && *end == '\0';
  };
  std::string line;
  if(ext == "obj") {
    while(std::getline(in, line)) {
      std::istringstream ls(line);
      std::string tag; ls >> tag;
      if(tag == "v") {
        std::string t[3]; double c[3];
        if(!(ls >> t[0] >> t[1] >> t[2])) return false;
        for(int i = 0; i < 3; ++i) if(!number(t[i], c[i])) return false;
        points.emplace_back(c[0], c[1], c[2]);
      } else if(tag == "f") {
        std::vector<std::size_t> P; std::string tok;
        while(ls >> tok) {
          long i = std::strtol(tok.c_str(), nullptr, 10);
          if(i == 0) return false;
          P.push_back(i > 0 ? std::size_t(i - 1) : std::size_t(long(points.size()) + i));
        }
        polygons.push_back(P);
      }
    }
    return true;
  }
  if(ext != "off") return false;
  std::vector<std::string> tokens;
  while(std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream ls(line); std::string tok;
    while(ls >> tok) tokens.push_back(tok);
  }
  std::size_t k = 0;
  if(k < tokens.size() && tokens[k].find("OFF") != std::string::npos) ++k;
  if(tokens.size() < k + 3) return false;
  const std::size_t nv = std::strtoul(tokens[k].c_str(), nullptr, 10);
  const std::size_t nf = std::strtoul(tokens[k + 1].c_str(), nullptr, 10);
  k += 3;
  if(tokens.size() < k + 3 * nv) return false;
  for(std::size_t v = 0; v < nv; ++v, k += 3) {
    double c[3];
    for(int i = 0; i < 3; ++i) if(!number(tokens[k + i], c[i])) return false;
    points.emplace_back(c[0], c[1], c[2]);
  }
  for(std::size_t f = 0; f < nf; ++f) {
    if(k >= tokens.size()) return false;
    const std::size_t n = std::strtoul(tokens[k++].c_str(), nullptr, 10);
    if(k + n > tokens.size()) return false;
    std::vector<std::size_t> P;
    for(std::size_t i = 0; i < n; ++i) P.push_back(std::strtoul(tokens[k++].c_str(), nullptr, 10));
    polygons.push_back(P);
  }
  return true;
}

} // namespace internal

/*!
 * \ingroup PkgPolycubeIGARef
 * Reads a polygon soup from `path` (`.off`, `.obj`, `.ply`, `.stl`, case-insensitive).
 * Returns false, with `reason` set, when the file cannot be read.
 */
template <class Point>
bool read_polygon_soup_file(const std::string& path, std::vector<Point>& points,
                            std::vector<std::vector<std::size_t>>& polygons, std::string& reason)
{
  points.clear(); polygons.clear();
  const std::string ext = internal::lower_extension(path);
  if(ext != "off" && ext != "obj" && ext != "ply" && ext != "stl") {
    reason = "'" + path + "' has an unsupported extension (expected .off, .obj, .ply or .stl)";
    return false;
  }
  {
    std::ifstream probe(path, std::ios::binary);
    if(!probe) { reason = "cannot open '" + path + "'"; return false; }
    probe.seekg(0, std::ios::end);
    if(probe.tellg() <= 0) { reason = "'" + path + "' is an empty file"; return false; }
  }
  // Dispatch on the lower-cased extension ourselves: CGAL's dispatcher is case-sensitive.
  bool ok = false;
  try {
    if(ext == "off") ok = CGAL::IO::read_OFF(path, points, polygons);
    else if(ext == "obj") ok = CGAL::IO::read_OBJ(path, points, polygons);
    else if(ext == "ply") ok = CGAL::IO::read_PLY(path, points, polygons);
    else ok = CGAL::IO::read_STL(path, points, polygons);
  } catch(const std::exception&) {
    ok = false;
  }
  if(!ok) {
    points.clear(); polygons.clear();
    // Only to name non-finite coordinates precisely; any other failure stays `unreadable`.
    if((ext == "off" || ext == "obj") &&
       internal::read_ascii_soup_permissively(path, ext, points, polygons) && !polygons.empty() &&
       std::any_of(points.begin(), points.end(), [](const Point& p) {
         return !std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
                !std::isfinite(CGAL::to_double(p.z()));
       }))
      return true;
    points.clear(); polygons.clear();
    reason = "'" + path + "' is not a readable " + ext + " file";
    return false;
  }
  return true;
}

/*!
 * \ingroup PkgPolycubeIGARef
 * Builds a triangle mesh from a prepared (valid) soup: polygons are triangulated, and the
 * property maps named by `input_vertex_index_property()` / `input_face_index_property()`
 * record the input indices.
 */
template <class Point>
void build_triangle_mesh(const Prepared_soup<Point>& soup, CGAL::Surface_mesh<Point>& mesh)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  using vertex_descriptor = typename Mesh::Vertex_index;
  using face_descriptor = typename Mesh::Face_index;
  if(!soup.report.is_valid())
    soup.report.require_valid();
  mesh.clear();
  auto vin = mesh.template add_property_map<vertex_descriptor, std::size_t>(input_vertex_index_property(), 0).first;
  auto fin = mesh.template add_property_map<face_descriptor, std::size_t>(input_face_index_property(), 0).first;
  std::vector<vertex_descriptor> vs;
  vs.reserve(soup.points.size());
  for(std::size_t i = 0; i < soup.points.size(); ++i) {
    vs.push_back(mesh.add_vertex(soup.points[i]));
    vin[vs.back()] = soup.input_vertex[i];
  }
  bool polygonal = false;
  std::vector<vertex_descriptor> fv;
  for(std::size_t f = 0; f < soup.polygons.size(); ++f) {
    fv.clear();
    for(std::size_t v : soup.polygons[f]) fv.push_back(vs[v]);
    polygonal = polygonal || fv.size() > 3;
    face_descriptor fd = CGAL::Euler::add_face(fv, mesh);
    if(fd == mesh.null_face())
      throw Internal_error("mesh_construction_failed",
                           "validated face " + std::to_string(soup.input_face[f]) + " could not be added to the mesh");
    fin[fd] = soup.input_face[f];
  }
  if(polygonal) {
    struct Copy_index : public CGAL::Polygon_mesh_processing::Triangulate_faces::Default_visitor<Mesh>
    {
      decltype(fin)* map = nullptr; std::size_t current = 0;
      void before_subface_creations(face_descriptor f) { current = (*map)[f]; }
      void after_subface_created(face_descriptor f) { (*map)[f] = current; }
    } visitor;
    visitor.map = &fin;
    if(!CGAL::Polygon_mesh_processing::triangulate_faces(mesh, CGAL::parameters::visitor(visitor)))
      throw Invalid_input_error("degenerate_face", "a polygonal face could not be triangulated");
  }
}

/*!
 * \ingroup PkgPolycubeIGARef
 * Reads, validates and triangulates the mesh in `path`. On success `mesh` holds the
 * triangle mesh and the returned report lists warnings and repairs; when the report has
 * errors (`!report.is_valid()`), `mesh` is left empty. Named parameters as in
 * `prepare_polygon_soup()`.
 */
template <class Point, class NamedParameters = parameters::Default_named_parameters>
Validation_report read_triangle_mesh(const std::string& path, CGAL::Surface_mesh<Point>& mesh,
                                     const NamedParameters& np = parameters::default_values())
{
  mesh.clear();
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::string reason;
  if(!read_polygon_soup_file(path, points, polygons, reason)) {
    Validation_report report;
    internal::add_problem(report, "unreadable", Input_problem::ERROR, "file",
                          std::vector<std::vector<std::size_t>>{{0}}, 0, reason);
    return report;
  }
  Prepared_soup<Point> soup = prepare_polygon_soup(points, polygons, np);
  if(soup.report.is_valid()) build_triangle_mesh(soup, mesh);
  return soup.report;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_IO_READ_TRIANGLE_MESH_H
