// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// JSON summary of a multipatch volume and its quality (reference §4.1): per patch the
// degrees, knot spans, control net size, sampled det J and scaled Jacobian and the
// certified det J bound; the interfaces with their conformity gap; overall figures.
// Deterministic (17 significant digits, fixed key order); written atomically.

#ifndef CGAL_POLYCUBE_IGA_IO_SPLINE_JSON_H
#define CGAL_POLYCUBE_IGA_IO_SPLINE_JSON_H

#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/Quality.h>
#include <CGAL/Polycube_IGA/internal/atomic_file.h>
#include <CGAL/Polycube_IGA/internal/json_writer.h>

#include <ostream>
#include <string>

namespace CGAL {
namespace Polycube_IGA {
namespace IO {

namespace internal_json {

inline void write_sampling(CGAL::Polycube_IGA::internal::Json_writer& w, const Jacobian_sampling& s)
{
  w.begin_object()
    .member("min_det_jacobian", s.min_determinant)
    .member("max_det_jacobian", s.max_determinant)
    .member("min_scaled_jacobian", s.min_scaled_jacobian)
    .member("mean_scaled_jacobian", s.mean_scaled_jacobian)
    .member("samples", static_cast<unsigned long long>(s.samples))
    .member("nonpositive_samples", static_cast<unsigned long long>(s.nonpositive_samples))
    .end_object();
}

inline void write_bound(CGAL::Polycube_IGA::internal::Json_writer& w, const Jacobian_bound& b)
{
  w.begin_object()
    .member("lower_bound", b.lower_bound)
    .member("upper_bound", b.upper_bound)
    .member("smallest_value_found", b.smallest_value_found)
    .member("certified_positive", b.certified_positive)
    .member("has_nonpositive_value", b.has_nonpositive_value)
    .member("bezier_boxes", static_cast<unsigned long long>(b.boxes))
    .member("subdivision_depth", b.depth_reached)
    .end_object();
}

} // namespace internal_json

inline void write_json_summary(std::ostream& os, const Multipatch_volume& mp, const Multipatch_quality& q)
{
  CGAL::Polycube_IGA::internal::Json_writer w(os);
  w.begin_object().member("patches", static_cast<unsigned long long>(mp.number_of_patches()));
  w.key("patch").begin_array();
  for(std::size_t p = 0; p < mp.number_of_patches(); ++p) {
    const Tensor_bspline_volume& v = mp.patch(p);
    w.begin_object().member("id", static_cast<unsigned long long>(p)).member("rational", v.is_rational());
    w.key("degrees").begin_array().value(v.degree(0)).value(v.degree(1)).value(v.degree(2)).end_array();
    w.key("knot_spans").begin_array();
    for(int d = 0; d < 3; ++d) w.value(v.knot_vector(d).number_of_spans());
    w.end_array().key("control_net").begin_array();
    for(int d = 0; d < 3; ++d) w.value(v.number_of_control_points(d));
    w.end_array();
    if(p < q.sampled.size()) {
      w.key("sampled");
      internal_json::write_sampling(w, q.sampled[p]);
    }
    if(p < q.certified.size()) {
      w.key("certified");
      internal_json::write_bound(w, q.certified[p]);
    }
    w.end_object();
  }
  w.end_array();
  w.key("interfaces").begin_array();
  for(std::size_t i = 0; i < mp.interfaces().size(); ++i) {
    const Patch_interface& f = mp.interfaces()[i];
    w.begin_object()
      .member("first", static_cast<unsigned long long>(f.first.patch)).member("first_side", f.first.side)
      .member("second", static_cast<unsigned long long>(f.second.patch)).member("second_side", f.second.side);
    w.key("direction_map").begin_array();
    for(int m : f.direction_map) w.value(m);
    w.end_array().key("direction_orientation").begin_array();
    for(bool o : f.direction_orientation) w.value(o);
    w.end_array();
    if(i < q.interfaces.gaps.size()) w.member("max_gap", q.interfaces.gaps[i]);
    w.end_object();
  }
  w.end_array();
  w.member("boundary_sides", static_cast<unsigned long long>(mp.boundaries().size()));
  w.key("sampled");
  internal_json::write_sampling(w, q.overall_sampled);
  w.key("certified");
  internal_json::write_bound(w, q.overall_certified);
  w.member("interfaces_conforming", q.interfaces.conforming)
    .member("interfaces_max_gap", q.interfaces.max_gap)
    .member("interface_tolerance", q.interfaces.tolerance)
    .member("bounding_box_diagonal", mp.bounding_box_diagonal());
  w.end_object();
  os << '\n';
}

inline void write_json_summary(const std::string& path, const Multipatch_volume& mp, const Multipatch_quality& q)
{
  internal::write_file_atomically(path, [&](std::ostream& os) { write_json_summary(os, mp, q); });
}

} // namespace IO
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_IO_SPLINE_JSON_H
