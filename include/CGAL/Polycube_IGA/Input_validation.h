// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Input validation: finds every problem of a polygon soup or triangle mesh that would make
// the later stages meaningless, and reports each with a reason code, a count and a few
// example element indices (indices of the input, never of an internal copy). Safe repairs
// (merging coincident vertices, dropping isolated vertices) are options, off by default,
// and are reported when applied. Combinatorial checks are exact; geometric ones
// (degenerate faces, self-intersections) use the kernel's exact predicates.
//
// Reason codes: empty, unreadable, non_finite_coordinates, invalid_vertex_index,
// degenerate_face, duplicate_face, non_manifold_edge, non_manifold_vertex,
// non_orientable, self_intersecting, multiple_components (errors);
// duplicate_vertices, isolated_vertices (warnings, or repairs when the option is set);
// reoriented_faces (a repair always applied: soups are oriented consistently).

#ifndef CGAL_POLYCUBE_IGA_INPUT_VALIDATION_H
#define CGAL_POLYCUBE_IGA_INPUT_VALIDATION_H

#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/parameters.h>
#include <CGAL/Polycube_IGA/internal/json_writer.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// One problem found in the input.
struct Input_problem
{
  enum Severity { ERROR, WARNING, REPAIRED };
  std::string code;      ///< reason code, e.g. `non_manifold_edge`
  Severity severity = ERROR;
  std::string element;   ///< what the examples index: `vertex`, `face`, `edge` (vertex pairs) or `file`
  std::size_t count = 0; ///< how many such elements
  std::vector<std::vector<std::size_t>> examples; ///< a few of them, as input indices
  std::string sentence;  ///< what it means, for a person

  static const char* severity_name(Severity s)
  {
    return s == ERROR ? "error" : (s == WARNING ? "warning" : "repaired");
  }
};

/// \ingroup PkgPolycubeIGARef
/// Everything validation found; `is_valid()` when no problem is an error.
struct Validation_report
{
  std::vector<Input_problem> problems;
  std::size_t input_vertices = 0;
  std::size_t input_faces = 0;
  std::size_t components = 0;

  bool is_valid() const
  {
    return std::none_of(problems.begin(), problems.end(),
                        [](const Input_problem& p) { return p.severity == Input_problem::ERROR; });
  }
  bool has(const std::string& code) const { return find(code) != nullptr; }
  const Input_problem* find(const std::string& code) const
  {
    for(const Input_problem& p : problems) if(p.code == code) return &p;
    return nullptr;
  }
  /// Throws Invalid_input_error naming the first error, and the other error codes.
  void require_valid() const
  {
    const Input_problem* first = nullptr;
    std::string others;
    for(const Input_problem& p : problems) {
      if(p.severity != Input_problem::ERROR) continue;
      if(!first) first = &p;
      else others += (others.empty() ? "" : ", ") + p.code;
    }
    if(!first) return;
    std::string s = first->sentence;
    if(!others.empty()) s += " (also: " + others + ")";
    throw Invalid_input_error(first->code, s);
  }
  /// Writes the problems as a JSON array of objects.
  void write_problems_json(internal::Json_writer& w) const
  {
    w.begin_array();
    for(const Input_problem& p : problems) {
      w.begin_object()
        .member("code", p.code)
        .member("severity", Input_problem::severity_name(p.severity))
        .member("element", p.element)
        .member("count", p.count)
        .member("message", p.sentence);
      w.key("examples").begin_array();
      for(const auto& e : p.examples) {
        if(e.size() == 1) w.value(e[0]);
        else w.array(e);
      }
      w.end_array().end_object();
    }
    w.end_array();
  }
};

namespace internal {

/// Adds a problem with up to `max_examples` examples taken from `elements`.
inline void add_problem(Validation_report& report, const std::string& code,
                        Input_problem::Severity severity, const std::string& element,
                        const std::vector<std::vector<std::size_t>>& elements,
                        std::size_t max_examples, const std::string& what)
{
  if(elements.empty()) return;
  Input_problem p;
  p.code = code;
  p.severity = severity;
  p.element = element;
  p.count = elements.size();
  p.examples.assign(elements.begin(), elements.begin() + std::min(max_examples, elements.size()));
  std::ostringstream s;
  if(element == "file") { // a problem of the whole input: no count, no examples
    p.examples.clear();
    p.sentence = what;
    report.problems.push_back(std::move(p));
    return;
  }
  s << elements.size() << " " << what;
  if(!p.examples.empty() && element != "file") {
    s << " (e.g. " << element << (p.examples.size() > 1 ? "s" : "");
    for(std::size_t i = 0; i < p.examples.size(); ++i) {
      s << (i ? ", " : " ");
      if(p.examples[i].size() == 1) s << p.examples[i][0];
      else { s << '(' << p.examples[i][0] << ' ' << p.examples[i][1] << ')'; }
    }
    s << ")";
  }
  p.sentence = s.str();
  report.problems.push_back(std::move(p));
}

/// Union-find with path halving; used for components and coincident vertices.
class Union_find
{
public:
  explicit Union_find(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t x)
  {
    while(parent_[x] != x) { parent_[x] = parent_[parent_[x]]; x = parent_[x]; }
    return x;
  }
  void unite(std::size_t a, std::size_t b)
  {
    a = find(a); b = find(b);
    if(a != b) parent_[std::max(a, b)] = std::min(a, b); // smallest index represents: deterministic
  }
private:
  std::vector<std::size_t> parent_;
};

inline std::uint64_t edge_key(std::size_t a, std::size_t b)
{
  if(a > b) std::swap(a, b);
  return (std::uint64_t(a) << 32) | std::uint64_t(b);
}

} // namespace internal

/// \ingroup PkgPolycubeIGARef
/// A validated, consistently oriented polygon soup ready to become a triangle mesh.
/// `polygons` index `points`; `input_vertex[i]` / `input_face[f]` give the index in the
/// original input of point i and polygon f (after repairs, several inputs may map to one).
template <class Point>
struct Prepared_soup
{
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::vector<std::size_t> input_vertex;
  std::vector<std::size_t> input_face;
  Validation_report report;
};

/*!
 * \ingroup PkgPolycubeIGARef
 * Validates a polygon soup and prepares it for mesh construction: applies the optional
 * repairs, orients the polygons consistently, and reports every problem.
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{merge_duplicate_vertices}
 *     \cgalParamDescription{merge vertices with identical coordinates (first index kept)}
 *     \cgalParamDefault{`false`: reported as the warning `duplicate_vertices`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{remove_isolated_vertices}
 *     \cgalParamDescription{drop vertices used by no face}
 *     \cgalParamDefault{`false`: reported as the warning `isolated_vertices`; such
 *                       vertices never enter the mesh either way}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{check_self_intersections}
 *     \cgalParamDescription{run the (exact) self-intersection test}
 *     \cgalParamDefault{`true`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{maximum_examples}
 *     \cgalParamDescription{how many example indices each problem lists}
 *     \cgalParamDefault{`5`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 */
template <class Point, class NamedParameters = parameters::Default_named_parameters>
Prepared_soup<Point>
prepare_polygon_soup(const std::vector<Point>& input_points,
                     const std::vector<std::vector<std::size_t>>& input_polygons,
                     const NamedParameters& np = parameters::default_values())
{
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  const bool merge = option(np, internal_np::merge_duplicate_vertices, false);
  const bool drop_isolated = option(np, internal_np::remove_isolated_vertices, false);
  const bool check_si = option(np, internal_np::check_self_intersections, true);
  const std::size_t max_ex = option(np, internal_np::maximum_examples, std::size_t(5));
  using E = std::vector<std::vector<std::size_t>>;
  const auto ERR = Input_problem::ERROR;

  Prepared_soup<Point> out;
  Validation_report& report = out.report;
  const std::size_t nv = input_points.size(), nf = input_polygons.size();
  report.input_vertices = nv;
  report.input_faces = nf;

  if(nf == 0 || nv == 0) {
    internal::add_problem(report, "empty", ERR, "file", E{{0}}, 0,
                          "the input has no faces: nothing to process");
    return out;
  }

  // Indices and coordinates first: nothing else can be trusted without them.
  E bad_index, non_finite;
  for(std::size_t f = 0; f < nf; ++f)
    for(std::size_t v : input_polygons[f])
      if(v >= nv) { bad_index.push_back({f}); break; }
  for(std::size_t v = 0; v < nv; ++v) {
    const Point& p = input_points[v];
    if(!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
       !std::isfinite(CGAL::to_double(p.z())))
      non_finite.push_back({v});
  }
  internal::add_problem(report, "invalid_vertex_index", ERR, "face", bad_index, max_ex,
                        "faces refer to vertices that do not exist");
  internal::add_problem(report, "non_finite_coordinates", ERR, "vertex", non_finite, max_ex,
                        "vertices have NaN or infinite coordinates");
  if(!bad_index.empty() || !non_finite.empty()) return out;

  // Coincident vertices: merged (repair) or reported (warning).
  std::vector<std::size_t> representative(nv);
  std::iota(representative.begin(), representative.end(), 0);
  {
    std::vector<std::size_t> order(nv);
    std::iota(order.begin(), order.end(), 0);
    auto coords = [&](std::size_t i) {
      const Point& p = input_points[i];
      return std::array<double, 3>{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return coords(a) < coords(b); });
    E duplicates;
    for(std::size_t k = 1; k < nv; ++k)
      if(coords(order[k]) == coords(order[k - 1])) {
        const std::size_t first = representative[order[k - 1]];
        representative[order[k]] = first;
        duplicates.push_back({order[k]});
      }
    std::sort(duplicates.begin(), duplicates.end());
    if(merge)
      internal::add_problem(report, "duplicate_vertices", Input_problem::REPAIRED, "vertex", duplicates, max_ex,
                            "vertices coincided with an earlier vertex and were merged into it");
    else {
      std::iota(representative.begin(), representative.end(), 0);
      internal::add_problem(report, "duplicate_vertices", Input_problem::WARNING, "vertex", duplicates, max_ex,
                            "vertices coincide with another vertex (option merge_duplicate_vertices merges them)");
    }
  }

  // Polygons on representatives; degenerate ones are reported and left out of later checks.
  std::vector<std::vector<std::size_t>> polys(nf);
  std::vector<bool> degenerate(nf, false);
  E degenerate_faces;
  for(std::size_t f = 0; f < nf; ++f) {
    std::vector<std::size_t>& P = polys[f];
    for(std::size_t v : input_polygons[f]) P.push_back(representative[v]);
    std::vector<std::size_t> sorted = P;
    std::sort(sorted.begin(), sorted.end());
    bool bad = P.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    if(!bad) {
      // Zero area: every vertex collinear with the first two distinct ones (exact predicate).
      bool all_collinear = true;
      for(std::size_t i = 2; i < P.size() && all_collinear; ++i)
        all_collinear = CGAL::collinear(input_points[P[0]], input_points[P[1]], input_points[P[i]]);
      bad = all_collinear;
    }
    if(bad) { degenerate[f] = true; degenerate_faces.push_back({f}); }
  }
  internal::add_problem(report, "degenerate_face", ERR, "face", degenerate_faces, max_ex,
                        "faces have zero area (repeated or collinear vertices)");

  // Duplicate faces: the same vertex set as an earlier face.
  {
    std::map<std::vector<std::size_t>, std::size_t> seen;
    E dup;
    for(std::size_t f = 0; f < nf; ++f) {
      if(degenerate[f]) continue;
      std::vector<std::size_t> key = polys[f];
      std::sort(key.begin(), key.end());
      if(!seen.emplace(key, f).second) { dup.push_back({f}); degenerate[f] = true; }
    }
    internal::add_problem(report, "duplicate_face", ERR, "face", dup, max_ex,
                          "faces repeat the vertices of an earlier face");
  }

  // Edge incidences.
  struct Incidence { std::size_t face; bool forward; };
  std::unordered_map<std::uint64_t, std::vector<Incidence>> edges;
  edges.reserve(3 * nf);
  for(std::size_t f = 0; f < nf; ++f) {
    if(degenerate[f]) continue;
    const auto& P = polys[f];
    for(std::size_t i = 0; i < P.size(); ++i) {
      std::size_t a = P[i], b = P[(i + 1) % P.size()];
      edges[internal::edge_key(a, b)].push_back({f, a < b});
    }
  }
  E non_manifold_edges;
  for(const auto& [key, inc] : edges)
    if(inc.size() > 2) non_manifold_edges.push_back({std::size_t(key >> 32), std::size_t(key & 0xffffffffu)});
  std::sort(non_manifold_edges.begin(), non_manifold_edges.end());
  internal::add_problem(report, "non_manifold_edge", ERR, "edge", non_manifold_edges, max_ex,
                        "edges are shared by more than two faces");

  // Orientation: propagate across manifold edges; a conflict means non-orientable.
  std::vector<int> flip(nf, -1);
  E non_orientable;
  std::size_t reoriented = 0;
  {
    std::vector<std::vector<std::pair<std::size_t, bool>>> adjacency(nf); // neighbour, same direction?
    for(const auto& [key, inc] : edges)
      if(inc.size() == 2) {
        const bool same = inc[0].forward == inc[1].forward; // same direction: inconsistent pair
        adjacency[inc[0].face].push_back({inc[1].face, same});
        adjacency[inc[1].face].push_back({inc[0].face, same});
      }
    std::vector<std::size_t> stack;
    for(std::size_t seed = 0; seed < nf; ++seed) {
      if(degenerate[seed] || flip[seed] != -1) continue;
      flip[seed] = 0;
      stack.push_back(seed);
      bool conflict = false;
      while(!stack.empty()) {
        std::size_t f = stack.back(); stack.pop_back();
        for(auto [g, same] : adjacency[f]) {
          const int want = flip[f] ^ int(same);
          if(flip[g] == -1) { flip[g] = want; stack.push_back(g); }
          else if(flip[g] != want && !conflict) { conflict = true; non_orientable.push_back({g}); }
        }
      }
    }
    for(std::size_t f = 0; f < nf; ++f) if(flip[f] == 1) ++reoriented;
  }
  internal::add_problem(report, "non_orientable", ERR, "face", non_orientable, max_ex,
                        "connected parts cannot be oriented consistently (Moebius-like)");

  // Non-manifold vertices: the faces around a vertex must form one fan.
  {
    std::vector<std::vector<std::size_t>> faces_of(nv);
    for(std::size_t f = 0; f < nf; ++f)
      if(!degenerate[f]) for(std::size_t v : polys[f]) faces_of[v].push_back(f);
    E nm;
    std::unordered_map<std::size_t, std::size_t> local;
    for(std::size_t v = 0; v < nv; ++v) {
      const auto& F = faces_of[v];
      if(F.size() < 2) continue;
      local.clear();
      for(std::size_t i = 0; i < F.size(); ++i) local[F[i]] = i;
      internal::Union_find uf(F.size());
      for(std::size_t f : F) {
        const auto& P = polys[f];
        for(std::size_t i = 0; i < P.size(); ++i) {
          std::size_t a = P[i], b = P[(i + 1) % P.size()];
          if(a != v && b != v) continue;
          const auto& inc = edges[internal::edge_key(a, b)];
          for(const Incidence& x : inc) uf.unite(local[f], local[x.face]);
        }
      }
      std::size_t fans = 0;
      for(std::size_t i = 0; i < F.size(); ++i) if(uf.find(i) == i) ++fans;
      if(fans > 1) nm.push_back({v});
    }
    internal::add_problem(report, "non_manifold_vertex", ERR, "vertex", nm, max_ex,
                          "vertices join several fans of faces that share no edge (pinched)");
  }

  // Components, through shared vertices.
  {
    internal::Union_find uf(nv);
    for(std::size_t f = 0; f < nf; ++f)
      for(std::size_t i = 1; i < polys[f].size(); ++i) uf.unite(polys[f][0], polys[f][i]);
    std::map<std::size_t, std::size_t> first_face; // component root -> first face
    for(std::size_t f = 0; f < nf; ++f)
      if(!polys[f].empty()) first_face.emplace(uf.find(polys[f][0]), f);
    report.components = first_face.size();
    if(first_face.size() > 1) {
      E ex;
      for(const auto& [root, f] : first_face) ex.push_back({f});
      std::sort(ex.begin(), ex.end());
      ex.erase(ex.begin()); // the first component is the reference
      internal::add_problem(report, "multiple_components", ERR, "face", ex, max_ex,
                            "further connected components besides the first "
                            "(one solid is expected; first faces listed)");
    }
  }

  // Isolated vertices (never enter the mesh; reported, or repaired on request).
  std::vector<bool> used(nv, false);
  for(const auto& P : polys) for(std::size_t v : P) used[v] = true;
  {
    E isolated;
    for(std::size_t v = 0; v < nv; ++v)
      if(!used[v] && representative[v] == v) isolated.push_back({v});
    if(drop_isolated)
      internal::add_problem(report, "isolated_vertices", Input_problem::REPAIRED, "vertex", isolated, max_ex,
                            "vertices used by no face were removed");
    else
      internal::add_problem(report, "isolated_vertices", Input_problem::WARNING, "vertex", isolated, max_ex,
                            "vertices are used by no face and are ignored "
                            "(option remove_isolated_vertices drops them)");
  }

  const bool combinatorially_valid = report.is_valid();
  // The prepared soup: used vertices in input order, oriented polygons.
  std::vector<std::size_t> new_index(nv, std::size_t(-1));
  for(std::size_t v = 0; v < nv; ++v)
    if(used[v]) {
      new_index[v] = out.points.size();
      out.points.push_back(input_points[v]);
      out.input_vertex.push_back(v);
    }
  for(std::size_t f = 0; f < nf; ++f) {
    if(degenerate[f]) continue;
    std::vector<std::size_t> P;
    for(std::size_t v : polys[f]) P.push_back(new_index[v]);
    if(flip[f] == 1) std::reverse(P.begin(), P.end());
    out.polygons.push_back(std::move(P));
    out.input_face.push_back(f);
  }
  if(combinatorially_valid && reoriented > 0) {
    E flipped;
    for(std::size_t f = 0; f < nf; ++f) if(flip[f] == 1) flipped.push_back({f});
    internal::add_problem(report, "reoriented_faces", Input_problem::REPAIRED, "face", flipped, max_ex,
                          "faces were reversed to orient the surface consistently");
  }

  // Self-intersections need a valid mesh to be meaningful; test a triangulated copy.
  if(combinatorially_valid && check_si) {
    CGAL::Surface_mesh<typename Kernel::Point_3> tm;
    std::vector<typename CGAL::Surface_mesh<typename Kernel::Point_3>::Vertex_index> vs;
    for(const Point& p : out.points) vs.push_back(tm.add_vertex(p));
    auto face_input = tm.template add_property_map<typename CGAL::Surface_mesh<typename Kernel::Point_3>::Face_index,
                                                   std::size_t>("f:input", 0).first;
    for(std::size_t f = 0; f < out.polygons.size(); ++f) {
      std::vector<typename CGAL::Surface_mesh<typename Kernel::Point_3>::Vertex_index> fv;
      for(std::size_t v : out.polygons[f]) fv.push_back(vs[v]);
      auto fd = CGAL::Euler::add_face(fv, tm);
      if(fd == tm.null_face())
        throw Internal_error("mesh_construction_failed", "a validated polygon could not be added to the mesh");
      face_input[fd] = out.input_face[f];
    }
    struct Copy_index : public CGAL::Polygon_mesh_processing::Triangulate_faces::Default_visitor<decltype(tm)>
    {
      decltype(face_input)* map; std::size_t current = 0;
      void before_subface_creations(typename decltype(tm)::Face_index f) { current = (*map)[f]; }
      void after_subface_created(typename decltype(tm)::Face_index f) { (*map)[f] = current; }
    } visitor;
    visitor.map = &face_input;
    CGAL::Polygon_mesh_processing::triangulate_faces(tm, CGAL::parameters::visitor(visitor));
    std::vector<std::pair<typename decltype(tm)::Face_index, typename decltype(tm)::Face_index>> pairs;
    CGAL::Polygon_mesh_processing::self_intersections(tm, std::back_inserter(pairs));
    std::vector<std::size_t> faces;
    for(const auto& pr : pairs) {
      std::size_t a = face_input[pr.first], b = face_input[pr.second];
      if(a != b) { faces.push_back(a); faces.push_back(b); } // a non-planar polygon may fold on itself
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    E ex;
    for(std::size_t f : faces) ex.push_back({f});
    internal::add_problem(report, "self_intersecting", ERR, "face", ex, max_ex,
                          "faces intersect other faces of the surface");
  }
  return out;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INPUT_VALIDATION_H
