// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The vocabulary of polycube labels, shared by the labellings (polycube_map.h,
// tied_labels.h): a label's direction in a frame, and the charts a labelling makes.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LABEL_CHARTS_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LABEL_CHARTS_H

#include <CGAL/boost/graph/iterator.h>

#include <Eigen/Dense>

#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// Labels are 2 k + s: axis k of the frame, s = 0 along it, 1 against it.
inline Eigen::Vector3d label_direction(const Eigen::Matrix3d& frame, int label)
{
  const Eigen::Vector3d a = frame.row(label / 2).transpose();
  return label % 2 ? Eigen::Vector3d(-a) : a;
}

/// The charts of a labelling: connected sets of faces of one label across edges. Returns
/// each face's chart.
template <class Mesh>
std::vector<int> label_charts(const Mesh& m, const std::vector<int>& label, int* count = nullptr)
{
  std::vector<int> chart(num_faces(m), -1);
  int n = 0;
  for(auto f0 : faces(m)) {
    if(chart[std::size_t(f0)] >= 0) continue;
    std::vector<typename Mesh::Face_index> stack{f0};
    chart[std::size_t(f0)] = n;
    while(!stack.empty()) {
      const auto f = stack.back();
      stack.pop_back();
      for(auto h : halfedges_around_face(halfedge(f, m), m)) {
        const auto g = face(opposite(h, m), m);
        if(g == Mesh::null_face() || chart[std::size_t(g)] >= 0 || label[std::size_t(g)] != label[std::size_t(f)]) continue;
        chart[std::size_t(g)] = n;
        stack.push_back(g);
      }
    }
    ++n;
  }
  if(count) *count = n;
  return chart;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LABEL_CHARTS_H
