// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// JSON form of a Polycube_layout (reference §1.2.3): class and topology, the nodes with
// their mesh vertex, input-file vertex and point, the arcs with their vertex paths and
// lengths, the quad patches with corners, arcs, face counts and areas, the cuboids, the
// interfaces between cuboids and the result of validate(). Keys come in a fixed order and
// numbers are written by internal/json_writer.h (17 significant digits, read back bit for
// bit), so equal layouts give byte-identical files; the path overload writes atomically.
//
// Layouts that fail validate() are written too (that is when one wants to look at them),
// but every index must refer to an existing element: a layout whose nodes, arcs, patches
// or cuboids point outside the mesh or outside the layout is rejected with
// Invalid_input_error `invalid_layout`, and nothing is written.

#ifndef CGAL_POLYCUBE_IGA_IO_LAYOUT_JSON_H
#define CGAL_POLYCUBE_IGA_IO_LAYOUT_JSON_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/IO/read_triangle_mesh.h>
#include <CGAL/Polycube_IGA/Polycube_layout.h>
#include <CGAL/Polycube_IGA/internal/atomic_file.h>
#include <CGAL/Polycube_IGA/internal/json_writer.h>
#include <CGAL/Polycube_IGA/internal/layout_measures.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace IO {
namespace internal_layout_io {

/// Throws `invalid_layout` unless every index of the layout refers to an existing element
/// (this is what the writers, and validate(), need to read it without undefined behaviour).
template <class P>
void check_layout_references(const Polycube_layout<P>& L)
{
  auto fail = [](const std::string& s) { throw Invalid_input_error("invalid_layout", "cannot write the layout: " + s); };
  if(L.mesh.has_garbage()) fail("its mesh has removed elements");
  const std::size_t nv = num_vertices(L.mesh), nf = num_faces(L.mesh);
  for(std::size_t n = 0; n < L.nodes.size(); ++n)
    if(std::size_t(L.nodes[n]) >= nv) fail("node " + std::to_string(n) + " is not a mesh vertex");
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    const auto& arc = L.arcs[a];
    if(arc.nodes[0] >= L.nodes.size() || arc.nodes[1] >= L.nodes.size()) fail("arc " + std::to_string(a) + " joins a node that does not exist");
    for(auto v : arc.vertices)
      if(std::size_t(v) >= nv) fail("arc " + std::to_string(a) + " passes through a vertex that is not in the mesh");
  }
  for(std::size_t p = 0; p < L.patches.size(); ++p) {
    const auto& pa = L.patches[p];
    for(int i = 0; i < 4; ++i)
      if(pa.corners[std::size_t(i)] >= L.nodes.size() || pa.arcs[std::size_t(i)] >= L.arcs.size())
        fail("patch " + std::to_string(p) + " has a corner or an arc that does not exist");
    for(auto f : pa.faces)
      if(std::size_t(f) >= nf) fail("patch " + std::to_string(p) + " lists a face that is not in the mesh");
  }
  for(std::size_t c = 0; c < L.cuboids.size(); ++c) {
    for(std::size_t n : L.cuboids[c].nodes)
      if(n >= L.nodes.size()) fail("cuboid " + std::to_string(c) + " has a node that does not exist");
    for(std::size_t p : L.cuboids[c].patches)
      if(p >= L.patches.size()) fail("cuboid " + std::to_string(c) + " has a patch that does not exist");
  }
}

/// The first cuboid (in cuboid and side order) that has patch p as a side, -1 if none.
template <class P>
std::vector<int> cuboid_of_patch(const Polycube_layout<P>& L)
{
  std::vector<int> out(L.patches.size(), -1);
  for(std::size_t c = 0; c < L.cuboids.size(); ++c)
    for(std::size_t p : L.cuboids[c].patches)
      if(p < out.size() && out[p] < 0) out[p] = int(c);
  return out;
}

/// Number of arc ends at every node (a loop arc counts twice, as in validate()).
template <class P>
std::vector<int> node_valences(const Polycube_layout<P>& L)
{
  std::vector<int> out(L.nodes.size(), 0);
  for(const auto& arc : L.arcs)
    for(std::size_t n : arc.nodes)
      if(n < out.size()) ++out[n];
  return out;
}

inline const char* patch_kind_name(int kind)
{
  return kind == 0 ? "surface" : kind == 1 ? "cap" : "interface";
}

/// Re-indents the compact JSON text of internal::Json_writer: objects and arrays that hold
/// objects or arrays get one member per line (two spaces per level), arrays of plain
/// values stay on one line. Only whitespace outside strings is added.
inline void write_indented_json(std::ostream& os, const std::string& s)
{
  // For every '[' or '{': does it hold no '[' or '{' (then it stays on one line)?
  std::vector<char> flat(s.size(), 0);
  {
    std::vector<std::size_t> open;
    bool in_string = false;
    for(std::size_t i = 0; i < s.size(); ++i) {
      const char c = s[i];
      if(in_string) {
        if(c == '\\') ++i;
        else if(c == '"') in_string = false;
        continue;
      }
      if(c == '"') in_string = true;
      else if(c == '[' || c == '{') {
        if(!open.empty()) flat[open.back()] = 2; // holds a container
        open.push_back(i);
      } else if((c == ']' || c == '}') && !open.empty()) {
        const std::size_t o = open.back();
        open.pop_back();
        // Objects break unless empty; arrays break only if they hold containers.
        const bool empty = o + 1 == i;
        flat[o] = (empty || (s[o] == '[' && flat[o] != 2)) ? 1 : 0;
      }
    }
  }
  std::vector<bool> inline_stack; // per open container: written on one line?
  int depth = 0;
  auto newline = [&os](int d) {
    os << '\n';
    for(int k = 0; k < d; ++k) os << "  ";
  };
  bool in_string = false;
  for(std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if(in_string) {
      os << c;
      if(c == '\\' && i + 1 < s.size()) os << s[++i];
      else if(c == '"') in_string = false;
      continue;
    }
    const bool inside_inline = !inline_stack.empty() && inline_stack.back();
    switch(c) {
    case '"': in_string = true; os << c; break;
    case '{':
    case '[':
      os << c;
      inline_stack.push_back(inside_inline || flat[i] == 1);
      ++depth;
      if(!inline_stack.back()) newline(depth);
      break;
    case '}':
    case ']':
      --depth;
      if(!inline_stack.empty()) {
        if(!inline_stack.back()) newline(depth);
        inline_stack.pop_back();
      }
      os << c;
      break;
    case ',':
      os << ',';
      if(inside_inline) os << ' ';
      else newline(depth);
      break;
    case ':': os << ": "; break;
    default: os << c;
    }
  }
}

} // namespace internal_layout_io

/// \ingroup PkgPolycubeIGARef
/// Writes the layout as one JSON object (keys in this order): `class` (layout_class_name),
/// `genus`, `boundary_loops`, `pants`, `turned_outwards` (the input's faces pointed inwards),
/// `remeshed` (the surface a remeshed copy of the input, Polycube_layout::remeshed);
/// `nodes` [{`vertex`, `input_vertex` (from the mesh's
/// "v:input_index" property, -1 without it or for a refinement vertex), `interior` (a box
/// corner inside the solid, Polycube_layout::is_interior_node()), `point` [x,y,z]}];
/// `arcs` [{`nodes` [a,b], `vertices` [...], `inside`, `length`}]; `patches` [{`kind` ("surface",
/// "cap" or "interface"), `corners` [4], `arcs` [4], `faces` (count), `area` (of the faces,
/// 0 for cap and interface patches)}]; `cuboids` [{`nodes` [8], `patches` [6], `pants`}];
/// `interfaces` [{`patch`, `cuboids` [a,b], `sides` [sa,sb]}]; `validation` {`valid`,
/// `problems` [...], `euler_surface`, `euler_solid`, `minimum_valence`, `maximum_valence`}.
/// Vertex indices are those of `L.mesh`. `pretty` indents the text (same content).
/// Throws Invalid_input_error `invalid_layout` if an index of the layout is out of range.
template <class P>
void write_layout_json(std::ostream& os, const Polycube_layout<P>& L, bool pretty = false)
{
  using Layout = Polycube_layout<P>;
  using Ull = unsigned long long;
  internal_layout_io::check_layout_references(L);
  const Layout_validation validation = L.validate();
  const auto input_index =
    L.mesh.template property_map<typename Layout::vertex_descriptor, std::size_t>(input_vertex_index_property());

  std::ostringstream text;
  CGAL::Polycube_IGA::internal::Json_writer w(pretty ? static_cast<std::ostream&>(text) : os);
  w.begin_object()
    .member("class", layout_class_name(L.layout_class))
    .member("genus", L.genus)
    .member("boundary_loops", Ull(L.boundary_loops))
    .member("pants", Ull(L.number_of_pants))
    .member("turned_outwards", L.turned_outwards)
    .member("remeshed", L.remeshed);

  w.key("nodes").begin_array();
  for(auto v : L.nodes) {
    long long input = -1;
    if(input_index.second && input_index.first[v] != std::size_t(-1)) input = (long long)(input_index.first[v]);
    const auto p = Polycube_IGA::internal::layout_point_array(L.mesh.point(v));
    w.begin_object().member("vertex", Ull(std::size_t(v))).member("input_vertex", input).member("interior", L.mesh.is_isolated(v));
    w.key("point").begin_array().value(p[0]).value(p[1]).value(p[2]).end_array();
    w.end_object();
  }
  w.end_array();

  w.key("arcs").begin_array();
  for(const auto& arc : L.arcs) {
    w.begin_object();
    w.key("nodes").begin_array().value(Ull(arc.nodes[0])).value(Ull(arc.nodes[1])).end_array();
    w.key("vertices").begin_array();
    for(auto v : arc.vertices) w.value(Ull(std::size_t(v)));
    w.end_array();
    w.member("inside", arc.inside); // a straight segment through the solid, not a mesh path
    w.member("length", Polycube_IGA::internal::layout_arc_length(L, arc));
    w.end_object();
  }
  w.end_array();

  w.key("patches").begin_array();
  for(const auto& pa : L.patches) {
    w.begin_object().member("kind", internal_layout_io::patch_kind_name(int(pa.kind)));
    w.key("corners").begin_array();
    for(std::size_t c : pa.corners) w.value(Ull(c));
    w.end_array().key("arcs").begin_array();
    for(std::size_t a : pa.arcs) w.value(Ull(a));
    w.end_array();
    w.member("faces", Ull(pa.faces.size())).member("area", Polycube_IGA::internal::layout_patch_area(L, pa));
    w.end_object();
  }
  w.end_array();

  w.key("cuboids").begin_array();
  for(const auto& cu : L.cuboids) {
    w.begin_object();
    w.key("nodes").begin_array();
    for(std::size_t n : cu.nodes) w.value(Ull(n));
    w.end_array().key("patches").begin_array();
    for(std::size_t p : cu.patches) w.value(Ull(p));
    w.end_array();
    w.member("pants", cu.pants);
    w.end_object();
  }
  w.end_array();

  w.key("interfaces").begin_array();
  for(const auto& f : L.interfaces()) {
    w.begin_object().member("patch", Ull(f.patch));
    w.key("cuboids").begin_array().value(Ull(f.cuboid_a)).value(Ull(f.cuboid_b)).end_array();
    w.key("sides").begin_array().value(f.side_a).value(f.side_b).end_array();
    w.end_object();
  }
  w.end_array();

  w.key("validation").begin_object().member("valid", validation.is_valid());
  w.key("problems").begin_array();
  for(const auto& p : validation.problems) w.value(p);
  w.end_array()
    .member("euler_surface", validation.euler_surface)
    .member("euler_solid", validation.euler_solid)
    .member("minimum_valence", validation.minimum_valence)
    .member("maximum_valence", validation.maximum_valence)
    .end_object();
  w.end_object();

  if(pretty) internal_layout_io::write_indented_json(os, text.str());
  os << '\n';
}

/// Writes write_layout_json(os, L, pretty) to `path` atomically: on any error no file is
/// left (Invalid_input_error `unwritable_output` if the file cannot be created).
template <class P>
void write_layout_json(const std::string& path, const Polycube_layout<P>& L, bool pretty = false)
{
  internal::write_file_atomically(path, [&](std::ostream& os) { write_layout_json(os, L, pretty); });
}

} // namespace IO
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_IO_LAYOUT_JSON_H
