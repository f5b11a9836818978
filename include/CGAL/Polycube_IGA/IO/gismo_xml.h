// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// G+Smo XML for multipatch trivariate B-splines and NURBS (the format IGA tools load,
// reference §4.1): `<Geometry type="TensorBSpline3">` with a `TensorBSplineBasis3` of three
// `BSplineBasis`/`KnotVector degree=..`, `<coefs geoDim="3">` with u fastest, `TensorNurbs3`
// with `<weights>` when rational, and `<MultiPatch parDim="3">` with `<patches
// type="id_range">`, `<interfaces>` lines `p s q t dirMap(3) dirOrient(3)` and `<boundary>`
// pairs `patch side`. Doubles are written with %.17g, so write -> read is bit for bit.
// Writing is atomic. The reader accepts this subset (and `id_index` patch lists, files
// without MultiPatch); anything else is Invalid_input_error `unreadable`.

#ifndef CGAL_POLYCUBE_IGA_IO_GISMO_XML_H
#define CGAL_POLYCUBE_IGA_IO_GISMO_XML_H

#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/internal/atomic_file.h>
#include <CGAL/Polycube_IGA/internal/number_text.h>

#include <fstream>
#include <istream>
#include <iterator>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace IO {

/// Writes `mp` as G+Smo XML: geometries with ids 0..n-1, the MultiPatch with id n.
inline void write_gismo_xml(std::ostream& os, const Multipatch_volume& mp)
{
  using internal::write_double;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml>\n";
  for(std::size_t p = 0; p < mp.number_of_patches(); ++p) {
    const Tensor_bspline_volume& v = mp.patch(p);
    const bool nurbs = v.is_rational();
    os << " <Geometry type=\"" << (nurbs ? "TensorNurbs3" : "TensorBSpline3") << "\" id=\"" << p << "\">\n";
    if(nurbs) os << "  <Basis type=\"TensorNurbsBasis3\">\n";
    os << "  <Basis type=\"TensorBSplineBasis3\">\n";
    for(int d = 0; d < 3; ++d) {
      os << "   <Basis type=\"BSplineBasis\" index=\"" << d << "\">\n    <KnotVector degree=\"" << v.degree(d) << "\">";
      const auto& k = v.knot_vector(d).knots();
      for(std::size_t i = 0; i < k.size(); ++i) {
        if(i) os << ' ';
        write_double(os, k[i]);
      }
      os << "</KnotVector>\n   </Basis>\n";
    }
    os << "  </Basis>\n";
    if(nurbs) {
      os << "  <weights>\n";
      for(double w : v.weights()) {
        write_double(os, w);
        os << '\n';
      }
      os << "  </weights>\n  </Basis>\n";
    }
    os << "  <coefs geoDim=\"3\">\n";
    for(const auto& c : v.control_points()) {
      write_double(os, c.x());
      os << ' ';
      write_double(os, c.y());
      os << ' ';
      write_double(os, c.z());
      os << '\n';
    }
    os << "  </coefs>\n </Geometry>\n";
  }
  const std::size_t n = mp.number_of_patches();
  os << " <MultiPatch parDim=\"3\" id=\"" << n << "\">\n";
  if(n > 0) os << "  <patches type=\"id_range\">0 " << n - 1 << "</patches>\n";
  else os << "  <patches type=\"id_index\"></patches>\n";
  if(!mp.interfaces().empty()) {
    os << "  <interfaces>\n";
    for(const auto& f : mp.interfaces()) {
      os << "   " << f.first.patch << ' ' << f.first.side << ' ' << f.second.patch << ' ' << f.second.side;
      for(int m : f.direction_map) os << ' ' << m;
      for(bool o : f.direction_orientation) os << ' ' << (o ? 1 : 0);
      os << '\n';
    }
    os << "  </interfaces>\n";
  }
  if(!mp.boundaries().empty()) {
    os << "  <boundary>\n";
    for(const auto& b : mp.boundaries()) os << "   " << b.patch << ' ' << b.side << '\n';
    os << "  </boundary>\n";
  }
  os << " </MultiPatch>\n</xml>\n";
}

inline void write_gismo_xml(const std::string& path, const Multipatch_volume& mp)
{
  internal::write_file_atomically(path, [&](std::ostream& os) { write_gismo_xml(os, mp); });
}

namespace internal_xml {

/// Minimal XML element tree: enough for G+Smo's files (no entities, no namespaces).
struct Element
{
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<std::unique_ptr<Element>> children;

  const Element* child(const std::string& n) const
  {
    for(const auto& c : children)
      if(c->name == n) return c.get();
    return nullptr;
  }
  std::vector<const Element*> all(const std::string& n) const
  {
    std::vector<const Element*> r;
    for(const auto& c : children)
      if(c->name == n) r.push_back(c.get());
    return r;
  }
  std::string attribute(const std::string& a, const std::string& fallback = "") const
  {
    auto it = attributes.find(a);
    return it == attributes.end() ? fallback : it->second;
  }
};

[[noreturn]] inline void fail(const std::string& s) { throw Invalid_input_error("unreadable", "G+Smo XML: " + s); }

inline std::unique_ptr<Element> parse(const std::string& s)
{
  auto root = std::make_unique<Element>();
  root->name = "#document";
  std::vector<Element*> stack{root.get()};
  std::size_t i = 0;
  auto is_space = [](char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r'; };
  while(i < s.size()) {
    if(s[i] != '<') {
      const std::size_t j = s.find('<', i);
      stack.back()->text.append(s, i, (j == std::string::npos ? s.size() : j) - i);
      i = j == std::string::npos ? s.size() : j;
      continue;
    }
    if(s.compare(i, 4, "<!--") == 0) {
      const std::size_t j = s.find("-->", i);
      if(j == std::string::npos) fail("unterminated comment");
      i = j + 3;
      continue;
    }
    if(s.compare(i, 2, "<?") == 0 || s.compare(i, 2, "<!") == 0) {
      const std::size_t j = s.find('>', i);
      if(j == std::string::npos) fail("unterminated declaration");
      i = j + 1;
      continue;
    }
    const std::size_t j = s.find('>', i);
    if(j == std::string::npos) fail("unterminated tag");
    std::string tag = s.substr(i + 1, j - i - 1);
    i = j + 1;
    if(!tag.empty() && tag[0] == '/') {
      std::string name = tag.substr(1);
      while(!name.empty() && is_space(name.back())) name.pop_back();
      if(stack.size() < 2 || stack.back()->name != name) fail("unexpected closing tag </" + name + ">");
      stack.pop_back();
      continue;
    }
    bool self_closing = false;
    if(!tag.empty() && tag.back() == '/') {
      self_closing = true;
      tag.pop_back();
    }
    auto e = std::make_unique<Element>();
    std::size_t k = 0;
    while(k < tag.size() && !is_space(tag[k])) ++k;
    e->name = tag.substr(0, k);
    if(e->name.empty()) fail("empty tag name");
    for(;;) {
      while(k < tag.size() && is_space(tag[k])) ++k;
      if(k >= tag.size()) break;
      const std::size_t eq = tag.find('=', k);
      if(eq == std::string::npos) fail("malformed attribute in <" + e->name + ">");
      std::string key = tag.substr(k, eq - k);
      while(!key.empty() && is_space(key.back())) key.pop_back();
      std::size_t q = eq + 1;
      while(q < tag.size() && is_space(tag[q])) ++q;
      if(q >= tag.size() || (tag[q] != '"' && tag[q] != '\'')) fail("unquoted attribute in <" + e->name + ">");
      const std::size_t close = tag.find(tag[q], q + 1);
      if(close == std::string::npos) fail("unterminated attribute in <" + e->name + ">");
      e->attributes[key] = tag.substr(q + 1, close - q - 1);
      k = close + 1;
    }
    Element* raw = e.get();
    stack.back()->children.push_back(std::move(e));
    if(!self_closing) stack.push_back(raw);
  }
  if(stack.size() != 1) fail("element <" + stack.back()->name + "> is not closed");
  return root;
}

inline void collect(const Element& e, const std::string& name, std::vector<const Element*>& out)
{
  for(const auto& c : e.children) {
    if(c->name == name) out.push_back(c.get());
    collect(*c, name, out);
  }
}

inline int to_int(const std::string& s, const std::string& what)
{
  const auto v = CGAL::Polycube_IGA::internal::parse_integers(s, what);
  if(v.size() != 1) fail(what + ": expected one integer");
  return int(v[0]);
}

inline Tensor_bspline_volume read_geometry(const Element& g)
{
  const std::string type = g.attribute("type"), id = g.attribute("id", "?");
  const Element* basis = g.child("Basis");
  if(!basis) fail("Geometry " + id + " has no <Basis>");
  std::vector<double> weights;
  if(type == "TensorNurbs3") {
    if(basis->attribute("type") != "TensorNurbsBasis3") fail("Geometry " + id + ": expected a TensorNurbsBasis3");
    const Element* w = basis->child("weights");
    if(!w) fail("Geometry " + id + ": NURBS without <weights>");
    weights = CGAL::Polycube_IGA::internal::parse_doubles(w->text, "weights");
    basis = basis->child("Basis");
    if(!basis) fail("Geometry " + id + ": NURBS basis without its B-spline basis");
  }
  if(basis->attribute("type") != "TensorBSplineBasis3") fail("Geometry " + id + ": expected a TensorBSplineBasis3");
  const auto subs = basis->all("Basis");
  if(subs.size() != 3) fail("Geometry " + id + ": expected three univariate bases");
  std::array<Knot_vector, 3> knots;
  std::array<bool, 3> seen{};
  for(std::size_t k = 0; k < 3; ++k) {
    const Element* b = subs[k];
    const int index = b->attributes.count("index") ? to_int(b->attribute("index"), "basis index") : int(k);
    if(index < 0 || index > 2 || seen[std::size_t(index)]) fail("Geometry " + id + ": bad basis index");
    seen[std::size_t(index)] = true;
    const Element* kv = b->child("KnotVector");
    if(!kv) fail("Geometry " + id + ": basis without <KnotVector>");
    knots[std::size_t(index)] = Knot_vector(to_int(kv->attribute("degree"), "degree"),
                                            CGAL::Polycube_IGA::internal::parse_doubles(kv->text, "knot vector"));
  }
  const Element* c = g.child("coefs");
  if(!c) fail("Geometry " + id + " has no <coefs>");
  if(c->attribute("geoDim", "3") != "3") fail("Geometry " + id + ": only geoDim 3 is supported");
  const std::vector<double> x = CGAL::Polycube_IGA::internal::parse_doubles(c->text, "coefs");
  if(x.size() % 3) fail("Geometry " + id + ": the number of coefficients is not a multiple of 3");
  std::vector<Eigen::Vector3d> pts;
  for(std::size_t i = 0; i < x.size(); i += 3) pts.emplace_back(x[i], x[i + 1], x[i + 2]);
  return Tensor_bspline_volume(knots, std::move(pts), std::move(weights));
}

} // namespace internal_xml

/// Reads the trivariate patches (and the first MultiPatch's topology) of a G+Smo XML text.
inline Multipatch_volume read_gismo_xml(std::istream& is)
{
  using namespace internal_xml;
  const std::string text((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  const auto root = parse(text);
  std::vector<const Element*> geometries, multipatches;
  collect(*root, "Geometry", geometries);
  collect(*root, "MultiPatch", multipatches);
  std::map<long, Tensor_bspline_volume> by_id;
  std::vector<Tensor_bspline_volume> in_order;
  for(const Element* g : geometries) {
    const std::string type = g->attribute("type");
    if(type != "TensorBSpline3" && type != "TensorNurbs3") continue;
    Tensor_bspline_volume v = read_geometry(*g);
    in_order.push_back(v);
    if(g->attributes.count("id")) {
      const long id = to_int(g->attribute("id"), "Geometry id");
      if(by_id.count(id)) fail("duplicate Geometry id " + std::to_string(id));
      by_id.emplace(id, std::move(v));
    }
  }
  Multipatch_volume mp;
  if(multipatches.empty()) {
    for(auto& v : in_order) mp.add_patch(std::move(v));
    return mp;
  }
  const Element& m = *multipatches.front();
  if(m.attribute("parDim", "3") != "3") fail("only MultiPatch parDim=\"3\" is supported");
  const Element* pe = m.child("patches");
  if(!pe) fail("<MultiPatch> without <patches>");
  const std::vector<long> vals = CGAL::Polycube_IGA::internal::parse_integers(pe->text, "patches");
  std::vector<long> ids;
  const std::string ptype = pe->attribute("type");
  if(ptype == "id_range") {
    if(vals.size() != 2 || vals[1] < vals[0]) fail("<patches type=\"id_range\"> needs 'first last'");
    for(long i = vals[0]; i <= vals[1]; ++i) ids.push_back(i);
  } else if(ptype == "id_index") ids = vals;
  else fail("<patches type=\"" + ptype + "\"> is not supported");
  std::map<long, std::size_t> position;
  for(long id : ids) {
    auto it = by_id.find(id);
    if(it == by_id.end()) fail("the MultiPatch refers to a missing trivariate Geometry id " + std::to_string(id));
    if(position.count(id)) fail("the MultiPatch lists Geometry id " + std::to_string(id) + " twice");
    position[id] = mp.add_patch(it->second);
  }
  auto patch_of = [&](long id) {
    auto it = position.find(id);
    if(it == position.end()) fail("patch id " + std::to_string(id) + " is not in the MultiPatch");
    return it->second;
  };
  for(const Element* e : m.all("interfaces")) {
    const auto a = CGAL::Polycube_IGA::internal::parse_integers(e->text, "interfaces");
    if(a.size() % 10) fail("<interfaces>: expected 10 integers per interface (p s q t dirMap(3) dirOrient(3))");
    for(std::size_t i = 0; i < a.size(); i += 10) {
      Patch_interface f;
      f.first = {patch_of(a[i]), int(a[i + 1])};
      f.second = {patch_of(a[i + 2]), int(a[i + 3])};
      for(int k = 0; k < 3; ++k) {
        f.direction_map[std::size_t(k)] = int(a[i + 4 + std::size_t(k)]);
        f.direction_orientation[std::size_t(k)] = a[i + 7 + std::size_t(k)] != 0;
      }
      mp.add_interface(f);
    }
  }
  for(const Element* e : m.all("boundary")) {
    const auto a = CGAL::Polycube_IGA::internal::parse_integers(e->text, "boundary");
    if(a.size() % 2) fail("<boundary> has an odd number of integers");
    for(std::size_t i = 0; i < a.size(); i += 2) mp.add_boundary({patch_of(a[i]), int(a[i + 1])});
  }
  return mp;
}

inline Multipatch_volume read_gismo_xml(const std::string& path)
{
  std::ifstream in(path);
  if(!in) throw Invalid_input_error("unreadable", "cannot open '" + path + "'");
  return read_gismo_xml(in);
}

} // namespace IO
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_IO_GISMO_XML_H
