// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Writers of Polycube_layout (IO/layout_vtk.h, IO/layout_json.h) on box-chain layouts whose
// content is known by construction: the files are read back with small readers written
// here (a tag-balance check and attribute/array extraction for the VTU, a minimal JSON
// parser), compared element by element with the layout, checked for determinism, and for
// atomicity when writing fails.

#include "layout_fixtures.h"
#include "vtu_text.h"

#include <CGAL/Polycube_IGA/IO/layout_json.h>
#include <CGAL/Polycube_IGA/IO/layout_vtk.h>

#include <catch2/catch.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

using namespace test_support;
namespace PI = CGAL::Polycube_IGA;

namespace {

std::size_t occurrences(const std::string& text, const std::string& what)
{
  std::size_t n = 0;
  for(std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

/// A smooth non-affine map, so that coordinates are not short decimals.
Point bend(double x, double y, double z)
{
  return Point(x + 0.1 * std::sin(3. * y + z), y + 0.05 * std::cos(x * z), z + y * y / 7.);
}

// --- VTU ---------------------------------------------------------------------------------

std::vector<int> expected_patch_of_face(const Layout& L)
{
  std::vector<int> out(num_faces(L.mesh), -1);
  for(std::size_t p = 0; p < L.patches.size(); ++p)
    for(auto f : L.patches[p].faces) out[std::size_t(f)] = int(p);
  return out;
}

// --- JSON --------------------------------------------------------------------------------

struct Json
{
  enum Type { NUL, BOOL, NUMBER, STRING, ARRAY, OBJECT } type = NUL;
  bool boolean = false;
  double number = 0.;
  std::string text; ///< string value, or the number's text as written
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> members;

  const Json& operator[](const std::string& key) const
  {
    for(const auto& m : members)
      if(m.first == key) return m.second;
    FAIL("no key " << key);
    return *this;
  }
  const Json& operator[](std::size_t i) const { return items.at(i); }
  std::size_t size() const { return type == ARRAY ? items.size() : members.size(); }
  long integer() const { return long(number); }
};

/// Strict enough for what the writers emit; throws std::runtime_error on malformed text.
class Json_parser
{
public:
  explicit Json_parser(const std::string& s) : s_(s) {}
  Json parse()
  {
    Json v = value();
    skip();
    if(i_ != s_.size()) error("text after the value");
    return v;
  }

private:
  [[noreturn]] void error(const std::string& what) { throw std::runtime_error("JSON: " + what + " at " + std::to_string(i_)); }
  void skip()
  {
    while(i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\t' || s_[i_] == '\r')) ++i_;
  }
  void expect(char c)
  {
    skip();
    if(i_ >= s_.size() || s_[i_] != c) error(std::string("expected '") + c + "'");
    ++i_;
  }
  bool literal(const char* word)
  {
    const std::string w(word);
    if(s_.compare(i_, w.size(), w) != 0) return false;
    i_ += w.size();
    return true;
  }
  std::string string()
  {
    expect('"');
    std::string out;
    while(i_ < s_.size() && s_[i_] != '"') {
      if(s_[i_] == '\\') {
        ++i_;
        if(i_ >= s_.size()) break;
        const char c = s_[i_];
        out += c == 'n' ? '\n' : c == 't' ? '\t' : c == 'r' ? '\r' : c;
      } else
        out += s_[i_];
      ++i_;
    }
    if(i_ >= s_.size()) error("unterminated string");
    ++i_;
    return out;
  }
  Json value()
  {
    skip();
    if(i_ >= s_.size()) error("missing value");
    Json v;
    const char c = s_[i_];
    if(c == '{') {
      v.type = Json::OBJECT;
      ++i_;
      skip();
      if(s_[i_] == '}') { ++i_; return v; }
      do {
        std::string k = string();
        expect(':');
        v.members.emplace_back(k, value());
        skip();
      } while(i_ < s_.size() && s_[i_] == ',' && ++i_);
      expect('}');
    } else if(c == '[') {
      v.type = Json::ARRAY;
      ++i_;
      skip();
      if(s_[i_] == ']') { ++i_; return v; }
      do {
        v.items.push_back(value());
        skip();
      } while(i_ < s_.size() && s_[i_] == ',' && ++i_);
      expect(']');
    } else if(c == '"') {
      v.type = Json::STRING;
      v.text = string();
    } else if(literal("true") || literal("false")) {
      v.type = Json::BOOL;
      v.boolean = s_[i_ - 1] == 'e' && s_[i_ - 2] == 'u';
    } else if(literal("null")) {
      v.type = Json::NUL;
    } else {
      const char* begin = s_.c_str() + i_;
      char* end = nullptr;
      v.number = std::strtod(begin, &end);
      if(end == begin) error("not a value");
      v.type = Json::NUMBER;
      v.text.assign(begin, std::size_t(end - begin));
      i_ += std::size_t(end - begin);
    }
    return v;
  }

  const std::string& s_;
  std::size_t i_ = 0;
};

/// Brackets and braces balance outside strings.
bool json_brackets_balance(const std::string& s)
{
  std::vector<char> open;
  bool in_string = false;
  for(std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if(in_string) {
      if(c == '\\') ++i;
      else if(c == '"') in_string = false;
    } else if(c == '"') in_string = true;
    else if(c == '{' || c == '[') open.push_back(c);
    else if(c == '}' || c == ']') {
      if(open.empty() || open.back() != (c == '}' ? '{' : '[')) return false;
      open.pop_back();
    }
  }
  return open.empty() && !in_string;
}

/// Every number's text is the canonical text of the double it reads back to: the
/// 17-significant-digit form of internal/number_text.h (or the shortest round-trip form),
/// so writing what was read gives the same bytes.
void check_numbers_round_trip(const Json& v, std::size_t& count)
{
  if(v.type == Json::NUMBER) {
    char digits17[32], shortest[32];
    std::snprintf(digits17, sizeof(digits17), "%.17g", v.number);
    const auto r = std::to_chars(shortest, shortest + sizeof(shortest), v.number);
    CHECK((v.text == digits17 || v.text == std::string(shortest, r.ptr)));
    CHECK(std::strtod(digits17, nullptr) == v.number);
    ++count;
  }
  for(const auto& i : v.items) check_numbers_round_trip(i, count);
  for(const auto& m : v.members) check_numbers_round_trip(m.second, count);
}

std::string without_whitespace_outside_strings(const std::string& s)
{
  std::string out;
  bool in_string = false;
  for(std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if(in_string) {
      out += c;
      if(c == '\\' && i + 1 < s.size()) out += s[++i];
      else if(c == '"') in_string = false;
    } else if(c == '"') {
      in_string = true;
      out += c;
    } else if(c != ' ' && c != '\n' && c != '\t' && c != '\r')
      out += c;
  }
  return out;
}

std::array<double, 3> coordinates(const Point& p) { return {{p.x(), p.y(), p.z()}}; }

} // namespace

TEST_CASE("layout vtu has one cell per face and arc and node", "[layout_io]")
{
  for(bool open : {false, true})
    for(int k : {1, 3}) {
      const Layout L = box_chain_layout(k, 3, open, bend);
      REQUIRE(L.validate().is_valid());
      const std::string path = temp_path("layout_" + std::to_string(k) + (open ? "_open" : "_closed") + ".vtu");
      PI::IO::write_layout_vtu(path, L);
      REQUIRE(exists(path));
      CHECK(!exists(path + ".tmp-polycube-iga"));
      const std::string xml = file_text(path);
      CHECK(xml_tags_balance(xml));
      CHECK(attribute(xml, "VTKFile", "type") == "UnstructuredGrid");

      const std::size_t nv = num_vertices(L.mesh), nf = num_faces(L.mesh);
      const std::size_t cells = nf + L.arcs.size() + L.nodes.size();
      CHECK(attribute(xml, "Piece", "NumberOfPoints") == std::to_string(nv));
      CHECK(attribute(xml, "Piece", "NumberOfCells") == std::to_string(cells));

      const auto types = integers(xml, "types"), kind = integers(xml, "kind"), patch = integers(xml, "patch");
      const auto cuboid = integers(xml, "cuboid"), arc = integers(xml, "arc"), node = integers(xml, "node");
      const auto valence = integers(xml, "valence"), offsets = integers(xml, "offsets");
      const auto connectivity = integers(xml, "connectivity");
      for(const auto* a : {&types, &kind, &patch, &cuboid, &arc, &node, &valence, &offsets}) REQUIRE(a->size() == cells);
      CHECK(std::count(types.begin(), types.end(), 5L) == long(nf)); // VTK_TRIANGLE
      CHECK(std::count(types.begin(), types.end(), 4L) == long(L.arcs.size())); // VTK_POLY_LINE
      CHECK(std::count(types.begin(), types.end(), 1L) == long(L.nodes.size())); // VTK_VERTEX
      CHECK(std::count(kind.begin(), kind.end(), 0L) == long(nf));
      CHECK(std::count(kind.begin(), kind.end(), 1L) == long(L.arcs.size()));
      CHECK(std::count(kind.begin(), kind.end(), 2L) == long(L.nodes.size()));
      REQUIRE(std::size_t(offsets.back()) == connectivity.size());

      // Triangles: face i of the mesh, in the patch that lists it, of the cuboid that has it.
      const std::vector<int> patch_of_face = expected_patch_of_face(L);
      std::vector<int> cuboid_of(L.patches.size(), -1), users(L.patches.size(), 0);
      for(std::size_t c = 0; c < L.cuboids.size(); ++c)
        for(std::size_t p : L.cuboids[c].patches) {
          cuboid_of[p] = int(c);
          ++users[p];
        }
      std::vector<std::size_t> triangles_of_patch(L.patches.size(), 0);
      std::size_t cell = 0, mismatches = 0;
      long begin = 0;
      for(auto f : faces(L.mesh)) {
        std::vector<long> want;
        for(auto v : vertices_around_face(halfedge(f, L.mesh), L.mesh)) want.push_back(long(std::size_t(v)));
        const std::vector<long> have(connectivity.begin() + begin, connectivity.begin() + offsets[cell]);
        const int p = patch_of_face[std::size_t(f)];
        REQUIRE(p >= 0);
        CHECK(users[std::size_t(p)] == 1);
        if(have != want || kind[cell] != 0 || patch[cell] != p || cuboid[cell] != cuboid_of[std::size_t(p)] || arc[cell] != -1 ||
           node[cell] != -1 || valence[cell] != -1)
          ++mismatches;
        ++triangles_of_patch[std::size_t(p)];
        begin = offsets[cell++];
      }
      CHECK(mismatches == 0);
      for(std::size_t p = 0; p < L.patches.size(); ++p) CHECK(triangles_of_patch[p] == L.patches[p].faces.size());

      // Arcs: their vertex paths. Nodes: their vertex and the number of arcs there.
      std::vector<long> arcs_at(L.nodes.size(), 0);
      for(std::size_t a = 0; a < L.arcs.size(); ++a, ++cell) {
        std::vector<long> want;
        for(auto v : L.arcs[a].vertices) want.push_back(long(std::size_t(v)));
        CHECK(std::vector<long>(connectivity.begin() + begin, connectivity.begin() + offsets[cell]) == want);
        CHECK(kind[cell] == 1);
        CHECK(patch[cell] == -1);
        CHECK(arc[cell] == long(a));
        ++arcs_at[L.arcs[a].nodes[0]];
        ++arcs_at[L.arcs[a].nodes[1]];
        begin = offsets[cell];
      }
      for(std::size_t n = 0; n < L.nodes.size(); ++n, ++cell) {
        CHECK(offsets[cell] - begin == 1);
        CHECK(connectivity[std::size_t(begin)] == long(std::size_t(L.nodes[n])));
        CHECK(kind[cell] == 2);
        CHECK(node[cell] == long(n));
        CHECK(valence[cell] == arcs_at[n]);
        CHECK((valence[cell] == 3 || valence[cell] == 4)); // corners of the chain and the squares between cuboids
        begin = offsets[cell];
      }

      // Points: exactly the mesh points (17 significant digits read back bit for bit).
      const auto xyz = PI::internal::parse_doubles(data_array(xml, "", "<Points>"), "points");
      REQUIRE(xyz.size() == 3 * nv);
      std::size_t exact = 0;
      for(auto v : vertices(L.mesh)) {
        const auto c = coordinates(L.mesh.point(v));
        for(int d = 0; d < 3; ++d) exact += xyz[3 * std::size_t(v) + std::size_t(d)] == c[std::size_t(d)] ? 1 : 0;
      }
      CHECK(exact == 3 * nv);
    }
}

TEST_CASE("layout vtu loads in vtkXMLUnstructuredGridReader when python3-vtk is installed", "[layout_io]")
{
  const std::string probe = temp_path("vtk_python");
  const std::string find = "for p in python3 /usr/bin/python3; do if $p -c 'import vtk' >/dev/null 2>&1; then printf %s $p > '" + probe +
                           "'; break; fi; done";
  CHECK(std::system(find.c_str()) == 0);
  const std::string python = file_text(probe);
  if(python.empty()) {
    WARN("no python3 with the vtk module: python3-vtk9 check skipped");
    return;
  }
  const std::string script = write_text("read_vtu.py",
    "import sys, vtk\n"
    "errors = []\n"
    "r = vtk.vtkXMLUnstructuredGridReader()\n"
    "r.AddObserver('ErrorEvent', lambda o, e: errors.append(e))\n"
    "r.SetFileName(sys.argv[1])\n"
    "r.Update()\n"
    "g = r.GetOutput()\n"
    "types = [g.GetCellType(i) for i in range(g.GetNumberOfCells())]\n"
    "kind = g.GetCellData().GetArray('kind')\n"
    "kinds = [int(kind.GetValue(i)) for i in range(kind.GetNumberOfTuples())] if kind else []\n"
    "patch = g.GetCellData().GetArray('patch')\n"
    "ps = sum(int(patch.GetValue(i)) for i in range(patch.GetNumberOfTuples())) if patch else -999\n"
    "print(len(errors) + r.GetErrorCode(), g.GetNumberOfPoints(), g.GetNumberOfCells(), types.count(5), types.count(4), types.count(1),"
    " kinds.count(0), kinds.count(1), kinds.count(2), ps)\n");
  for(bool open : {false, true}) {
    const Layout L = box_chain_layout(2, 2, open, bend);
    const std::string path = temp_path(std::string("vtk_read_") + (open ? "open" : "closed") + ".vtu"), out = temp_path("vtk_read.out");
    PI::IO::write_layout_vtu(path, L);
    const std::string cmd = python + " '" + script + "' '" + path + "' > '" + out + "' 2>&1";
    CHECK(std::system(cmd.c_str()) == 0);
    const std::string got = file_text(out);
    INFO(got);
    const std::size_t nf = num_faces(L.mesh);
    long patch_sum = 0;
    for(std::size_t p = 0; p < L.patches.size(); ++p) patch_sum += long(p * L.patches[p].faces.size());
    patch_sum -= long(L.arcs.size() + L.nodes.size());
    std::ostringstream want;
    want << 0 << ' ' << num_vertices(L.mesh) << ' ' << nf + L.arcs.size() + L.nodes.size() << ' ' << nf << ' ' << L.arcs.size() << ' '
         << L.nodes.size() << ' ' << nf << ' ' << L.arcs.size() << ' ' << L.nodes.size() << ' ' << patch_sum << '\n';
    CHECK(got == want.str());
  }
}

TEST_CASE("layout json lists every element of the layout", "[layout_io]")
{
  for(bool open : {false, true})
    for(int k : {1, 3}) {
      const Layout L = box_chain_layout(k, 3, open); // unit cuboids: known lengths and areas
      const std::string path = temp_path("layout_" + std::to_string(k) + (open ? "_open" : "_closed") + ".json");
      PI::IO::write_layout_json(path, L);
      REQUIRE(exists(path));
      CHECK(!exists(path + ".tmp-polycube-iga"));
      const std::string text = file_text(path);
      CHECK(json_brackets_balance(text));
      CHECK(text.find('\n') == text.size() - 1); // compact: one line
      CHECK(occurrences(text, "\"corners\"") == L.patches.size());
      CHECK(occurrences(text, "\"input_vertex\"") == L.nodes.size());
      CHECK(occurrences(text, "\"length\"") == L.arcs.size());
      CHECK(occurrences(text, "\"area\"") == L.patches.size());
      CHECK(occurrences(text, "\"pants\"") == 1 + L.cuboids.size());
      CHECK(occurrences(text, "\"sides\"") == std::size_t(k - 1));

      const Json j = Json_parser(text).parse();
      std::size_t numbers = 0;
      check_numbers_round_trip(j, numbers);
      CHECK(numbers > 0);
      CHECK(j["class"].text == (open ? "cylinder" : "sphere"));
      CHECK(j["genus"].integer() == 0);
      CHECK(j["boundary_loops"].integer() == (open ? 2 : 0));
      CHECK(j["pants"].integer() == 0);
      CHECK(j["remeshed"].type == Json::BOOL);
      CHECK(!j["remeshed"].boolean); // the fixture's own mesh

      REQUIRE(j["nodes"].size() == L.nodes.size());
      for(std::size_t n = 0; n < L.nodes.size(); ++n) {
        const Json& node = j["nodes"][n];
        CHECK(node["vertex"].integer() == long(std::size_t(L.nodes[n])));
        CHECK(node["input_vertex"].integer() == -1); // the fixture has no "v:input_index"
        CHECK(node["interior"].type == Json::BOOL);
        CHECK(!node["interior"].boolean); // every node of a sphere's or a tube's cube is on it
        const auto c = coordinates(L.mesh.point(L.nodes[n]));
        for(std::size_t d = 0; d < 3; ++d) CHECK(node["point"][d].number == c[d]);
      }
      REQUIRE(j["arcs"].size() == L.arcs.size());
      for(std::size_t a = 0; a < L.arcs.size(); ++a) {
        const Json& arc = j["arcs"][a];
        CHECK(std::size_t(arc["nodes"][0].integer()) == L.arcs[a].nodes[0]);
        CHECK(std::size_t(arc["nodes"][1].integer()) == L.arcs[a].nodes[1]);
        REQUIRE(arc["vertices"].size() == L.arcs[a].vertices.size());
        for(std::size_t i = 0; i < L.arcs[a].vertices.size(); ++i)
          CHECK(std::size_t(arc["vertices"][i].integer()) == std::size_t(L.arcs[a].vertices[i]));
        CHECK(arc["length"].number == Approx(1.).epsilon(1e-14)); // every arc of the chain is a unit edge
      }
      REQUIRE(j["patches"].size() == L.patches.size());
      std::map<std::string, int> kinds;
      double total_area = 0.;
      for(std::size_t p = 0; p < L.patches.size(); ++p) {
        const Json& pa = j["patches"][p];
        const std::string kind = pa["kind"].text;
        ++kinds[kind];
        CHECK(kind == (L.patches[p].kind == Layout::SURFACE ? "surface" : L.patches[p].kind == Layout::CAP ? "cap" : "interface"));
        for(std::size_t i = 0; i < 4; ++i) {
          CHECK(std::size_t(pa["corners"][i].integer()) == L.patches[p].corners[i]);
          CHECK(std::size_t(pa["arcs"][i].integer()) == L.patches[p].arcs[i]);
        }
        CHECK(std::size_t(pa["faces"].integer()) == L.patches[p].faces.size());
        CHECK(pa["area"].number == Approx(kind == "surface" ? 1. : 0.).margin(1e-14));
        total_area += pa["area"].number;
      }
      CHECK(kinds["surface"] == 4 * k + (open ? 0 : 2));
      CHECK(kinds["cap"] == (open ? 2 : 0));
      CHECK(kinds["interface"] == k - 1);
      CHECK(total_area == Approx(4. * k + (open ? 0. : 2.)));
      REQUIRE(j["cuboids"].size() == L.cuboids.size());
      for(std::size_t c = 0; c < L.cuboids.size(); ++c) {
        for(std::size_t i = 0; i < 8; ++i) CHECK(std::size_t(j["cuboids"][c]["nodes"][i].integer()) == L.cuboids[c].nodes[i]);
        for(std::size_t i = 0; i < 6; ++i) CHECK(std::size_t(j["cuboids"][c]["patches"][i].integer()) == L.cuboids[c].patches[i]);
        CHECK(j["cuboids"][c]["pants"].integer() == -1);
      }
      REQUIRE(j["interfaces"].size() == std::size_t(k - 1));
      for(std::size_t i = 0; i + 1 < std::size_t(k); ++i) {
        const Json& f = j["interfaces"][i];
        // Cuboid i's side u=1 (2) is glued to cuboid i+1's side u=0 (1).
        CHECK(std::size_t(f["patch"].integer()) == L.cuboids[i].patches[1]);
        CHECK(f["cuboids"][0].integer() == long(i));
        CHECK(f["cuboids"][1].integer() == long(i + 1));
        CHECK(f["sides"][0].integer() == 2);
        CHECK(f["sides"][1].integer() == 1);
      }
      const Json& v = j["validation"];
      CHECK(v["valid"].type == Json::BOOL);
      CHECK(v["valid"].boolean);
      CHECK(v["problems"].size() == 0);
      CHECK(v["euler_surface"].integer() == (open ? 0 : 2));
      CHECK(v["euler_solid"].integer() == 1);
      CHECK(v["minimum_valence"].integer() == 3);
    }
}

TEST_CASE("layout json pretty form has the same content and exact numbers", "[layout_io]")
{
  const Layout L = box_chain_layout(2, 3, true, bend);
  std::ostringstream compact, pretty;
  PI::IO::write_layout_json(compact, L, false);
  PI::IO::write_layout_json(pretty, L, true);
  CHECK(json_brackets_balance(pretty.str()));
  CHECK(occurrences(pretty.str(), "\n") > L.nodes.size() + L.arcs.size() + L.patches.size());
  CHECK(without_whitespace_outside_strings(pretty.str()) == without_whitespace_outside_strings(compact.str()));
  CHECK(without_whitespace_outside_strings(compact.str()) + "\n" == compact.str());
  // Arrays of plain values stay on one line.
  const std::size_t point = pretty.str().find("\"point\": [");
  REQUIRE(point != std::string::npos);
  CHECK(pretty.str().find(']', point) < pretty.str().find('\n', point));

  const Json j = Json_parser(pretty.str()).parse();
  std::size_t numbers = 0;
  check_numbers_round_trip(j, numbers);
  // Node points and arc lengths of a bent chain: not short decimals, read back exactly.
  for(std::size_t n = 0; n < L.nodes.size(); ++n) {
    const auto c = coordinates(L.mesh.point(L.nodes[n]));
    for(std::size_t d = 0; d < 3; ++d) CHECK(j["nodes"][n]["point"][d].number == c[d]);
  }
  for(std::size_t a = 0; a < L.arcs.size(); ++a) {
    double length = 0.;
    for(std::size_t i = 0; i + 1 < L.arcs[a].vertices.size(); ++i)
      length += std::sqrt(CGAL::squared_distance(L.mesh.point(L.arcs[a].vertices[i]), L.mesh.point(L.arcs[a].vertices[i + 1])));
    CHECK(j["arcs"][a]["length"].number == Approx(length).epsilon(1e-15));
  }
}

TEST_CASE("layout json reports input vertices and validation problems", "[layout_io]")
{
  Layout L = box_chain_layout(2, 2);
  auto input = L.mesh.add_property_map<Mesh::Vertex_index, std::size_t>(PI::input_vertex_index_property(), std::size_t(-1)).first;
  for(auto v : vertices(L.mesh)) input[v] = 1000 + std::size_t(v);
  input[L.nodes[3]] = std::size_t(-1); // a vertex that a refinement added
  L.patches[0].faces.pop_back();       // leaves a face in no patch
  std::ostringstream os;
  PI::IO::write_layout_json(os, L, true);
  const Json j = Json_parser(os.str()).parse();
  for(std::size_t n = 0; n < L.nodes.size(); ++n)
    CHECK(j["nodes"][n]["input_vertex"].integer() == (n == 3 ? -1 : long(1000 + std::size_t(L.nodes[n]))));
  const Json& v = j["validation"];
  CHECK(!v["valid"].boolean);
  REQUIRE(v["problems"].size() > 0);
  bool named = false;
  for(const auto& p : v["problems"].items) named = named || p.text.find("in no patch") != std::string::npos;
  CHECK(named);

  // The VTU of that layout shows the orphan face with patch -1.
  std::ostringstream vtu;
  PI::IO::write_layout_vtu(vtu, L);
  const auto patch = integers(vtu.str(), "patch");
  REQUIRE(patch.size() == num_faces(L.mesh) + L.arcs.size() + L.nodes.size());
  CHECK(std::count(patch.begin(), patch.begin() + long(num_faces(L.mesh)), -1L) == 1);
}

TEST_CASE("layout writers give byte-identical files", "[layout_io]")
{
  for(bool open : {false, true}) {
    const std::string tag = open ? "open" : "closed";
    const Layout a = box_chain_layout(3, 2, open, bend), b = box_chain_layout(3, 2, open, bend);
    PI::IO::write_layout_vtu(temp_path("twice_1_" + tag + ".vtu"), a);
    PI::IO::write_layout_vtu(temp_path("twice_2_" + tag + ".vtu"), a);
    PI::IO::write_layout_vtu(temp_path("twice_3_" + tag + ".vtu"), b);
    for(bool pretty : {false, true}) {
      const std::string t = tag + (pretty ? "_pretty" : "");
      PI::IO::write_layout_json(temp_path("twice_1_" + t + ".json"), a, pretty);
      PI::IO::write_layout_json(temp_path("twice_2_" + t + ".json"), a, pretty);
      PI::IO::write_layout_json(temp_path("twice_3_" + t + ".json"), b, pretty);
      const std::string first = file_text(temp_path("twice_1_" + t + ".json"));
      CHECK(!first.empty());
      CHECK(first == file_text(temp_path("twice_2_" + t + ".json")));
      CHECK(first == file_text(temp_path("twice_3_" + t + ".json")));
      std::ostringstream os;
      PI::IO::write_layout_json(os, a, pretty);
      CHECK(os.str() == first);
    }
    const std::string first = file_text(temp_path("twice_1_" + tag + ".vtu"));
    CHECK(!first.empty());
    CHECK(first == file_text(temp_path("twice_2_" + tag + ".vtu")));
    CHECK(first == file_text(temp_path("twice_3_" + tag + ".vtu")));
  }
}

TEST_CASE("layout writers throw into a missing directory and leave no file", "[layout_io]")
{
  const Layout L = box_chain_layout(1, 2, true);
  const std::string dir = temp_path("no_such_directory");
  REQUIRE(!exists(dir));
  for(const std::string name : {"layout.vtu", "layout.json", "layout_pretty.json"}) {
    const std::string path = dir + "/" + name;
    std::string reason;
    try {
      if(name == "layout.vtu") PI::IO::write_layout_vtu(path, L);
      else PI::IO::write_layout_json(path, L, name == "layout_pretty.json");
    } catch(const PI::Invalid_input_error& e) {
      reason = e.reason();
    }
    CHECK(reason == "unwritable_output");
    CHECK(!exists(path));
    CHECK(!exists(path + ".tmp-polycube-iga"));
  }
  CHECK(!exists(dir));
}

TEST_CASE("layout writers reject indices out of range and keep the previous file", "[layout_io]")
{
  const Layout good = box_chain_layout(2, 2);
  std::vector<Layout> broken(4, good);
  broken[0].arcs[1].vertices.push_back(Mesh::Vertex_index(std::uint32_t(num_vertices(good.mesh) + 5)));
  broken[1].patches[2].faces.push_back(Mesh::Face_index(std::uint32_t(num_faces(good.mesh))));
  broken[2].cuboids[1].patches[3] = good.patches.size();
  broken[3].patches[0].corners[2] = good.nodes.size();
  const std::string vtu = temp_path("kept.vtu"), json = temp_path("kept.json");
  PI::IO::write_layout_vtu(vtu, good);
  PI::IO::write_layout_json(json, good);
  const std::string vtu_text = file_text(vtu), json_text = file_text(json);
  for(const Layout& L : broken) {
    std::string reason_vtu, reason_json;
    try { PI::IO::write_layout_vtu(vtu, L); } catch(const PI::Invalid_input_error& e) { reason_vtu = e.reason(); }
    try { PI::IO::write_layout_json(json, L, true); } catch(const PI::Invalid_input_error& e) { reason_json = e.reason(); }
    CHECK(reason_vtu == "invalid_layout");
    CHECK(reason_json == "invalid_layout");
    CHECK(file_text(vtu) == vtu_text);
    CHECK(file_text(json) == json_text);
    CHECK(!exists(vtu + ".tmp-polycube-iga"));
    CHECK(!exists(json + ".tmp-polycube-iga"));
  }
}
