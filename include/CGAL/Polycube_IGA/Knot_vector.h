// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Clamped (open), possibly non-uniform knot vectors of the univariate B-spline bases the
// package builds its curves, surfaces and volumes from (reference §2.1.2.2, eq. 2.5-2.6).
// A Knot_vector is always valid once constructed: degree >= 1, finite non-decreasing knots,
// first and last knot repeated degree+1 times, interior multiplicity at most the degree.
// Bad input throws Invalid_input_error with reason `invalid_knot_vector`.

#ifndef CGAL_POLYCUBE_IGA_KNOT_VECTOR_H
#define CGAL_POLYCUBE_IGA_KNOT_VECTOR_H

#include <CGAL/Polycube_IGA/Errors.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// \ingroup PkgPolycubeIGARef
/// A clamped knot vector `{a,...,a, xi_{p+1}, ..., xi_{m-p-1}, b,...,b}` of degree `p`.
class Knot_vector
{
public:
  /// Largest degree the evaluation routines accept (their scratch arrays are on the stack).
  static constexpr int maximum_degree = 24;

  Knot_vector() = default;

  /// Validates and stores `knots` for degree `degree`.
  Knot_vector(int degree, std::vector<double> knots) : degree_(degree), knots_(std::move(knots))
  {
    validate();
  }

  /// Clamped knot vector on [a,b] with `spans` equal knot spans.
  static Knot_vector uniform(int degree, int spans, double a = 0., double b = 1.)
  {
    if(spans < 1)
      throw Invalid_input_error("invalid_knot_vector", "a knot vector needs at least one knot span, got " +
                                                           std::to_string(spans));
    std::vector<double> breaks(spans + 1);
    for(int i = 0; i <= spans; ++i)
      breaks[i] = (i == spans) ? b : a + (b - a) * double(i) / double(spans);
    return from_breaks(degree, breaks);
  }

  /// Clamped knot vector whose distinct values are `breaks`, each interior one repeated
  /// `interior_multiplicity` times (1 gives maximal smoothness C^{p-1}).
  static Knot_vector from_breaks(int degree, const std::vector<double>& breaks, int interior_multiplicity = 1)
  {
    if(breaks.size() < 2)
      throw Invalid_input_error("invalid_knot_vector", "a knot vector needs at least two distinct break values");
    std::vector<double> k;
    k.insert(k.end(), std::size_t(std::max(degree, 0) + 1), breaks.front());
    for(std::size_t i = 1; i + 1 < breaks.size(); ++i)
      k.insert(k.end(), std::size_t(std::max(interior_multiplicity, 0)), breaks[i]);
    k.insert(k.end(), std::size_t(std::max(degree, 0) + 1), breaks.back());
    return Knot_vector(degree, std::move(k));
  }

  int degree() const { return degree_; }
  const std::vector<double>& knots() const { return knots_; }
  double operator[](std::size_t i) const { return knots_[i]; }
  std::size_t size() const { return knots_.size(); }
  /// Number of basis functions (control points along this direction): m + 1 - (p + 1).
  int number_of_basis_functions() const { return int(knots_.size()) - degree_ - 1; }
  double first() const { return knots_[std::size_t(degree_)]; }
  double last() const { return knots_[knots_.size() - std::size_t(degree_) - 1]; }

  /// Distinct knot values, first to last.
  std::vector<double> breaks() const
  {
    std::vector<double> b;
    for(double t : knots_)
      if(b.empty() || t != b.back()) b.push_back(t);
    return b;
  }
  int number_of_spans() const { return int(breaks().size()) - 1; }

  /// Multiplicity of the value `t` in the knot vector (0 when absent).
  int multiplicity(double t) const
  {
    return int(std::upper_bound(knots_.begin(), knots_.end(), t) - std::lower_bound(knots_.begin(), knots_.end(), t));
  }

  /// Index `i` of the span with `knots[i] <= t < knots[i+1]`, `p <= i <= n-1`; the last
  /// non-empty span is used at t = last(), and values outside the domain are clamped.
  int find_span(double t) const
  {
    const int n = number_of_basis_functions();
    if(!(t < knots_[std::size_t(n)])) return n - 1;
    if(t <= knots_[std::size_t(degree_)]) return degree_;
    auto it = std::upper_bound(knots_.begin() + degree_, knots_.begin() + n + 1, t);
    return int(it - knots_.begin()) - 1;
  }

  /// Greville abscissa of basis function i: the mean of its p interior knots. B-splines
  /// reproduce linear functions with these as control values (linear precision).
  double greville(int i) const
  {
    double s = 0.;
    for(int j = 1; j <= degree_; ++j) s += knots_[std::size_t(i + j)];
    return s / double(degree_);
  }

  /// Greville abscissa mapped to [0,1] over the domain.
  double normalized_greville(int i) const { return (greville(i) - first()) / (last() - first()); }

  friend bool operator==(const Knot_vector& a, const Knot_vector& b)
  {
    return a.degree_ == b.degree_ && a.knots_ == b.knots_;
  }
  friend bool operator!=(const Knot_vector& a, const Knot_vector& b) { return !(a == b); }

private:
  [[noreturn]] static void fail(const std::string& sentence)
  {
    throw Invalid_input_error("invalid_knot_vector", sentence);
  }

  void validate() const
  {
    const std::string p = std::to_string(degree_);
    if(degree_ < 1) fail("the degree must be at least 1, got " + p);
    if(degree_ > maximum_degree)
      fail("the degree must be at most " + std::to_string(maximum_degree) + ", got " + p);
    if(knots_.size() < std::size_t(2 * degree_ + 2))
      fail("a degree-" + p + " knot vector needs at least " + std::to_string(2 * degree_ + 2) + " knots, got " +
           std::to_string(knots_.size()));
    for(std::size_t i = 0; i < knots_.size(); ++i) {
      if(!std::isfinite(knots_[i])) fail("knot " + std::to_string(i) + " is not a finite number");
      if(i > 0 && knots_[i] < knots_[i - 1])
        fail("knots must be non-decreasing; knot " + std::to_string(i) + " is smaller than knot " +
             std::to_string(i - 1));
    }
    const std::size_t m = knots_.size() - 1, q = std::size_t(degree_);
    for(std::size_t i = 1; i <= q; ++i)
      if(knots_[i] != knots_[0] || knots_[m - i] != knots_[m])
        fail("the knot vector must be clamped: first and last knot repeated degree+1 = " +
             std::to_string(degree_ + 1) + " times");
    if(!(knots_[0] < knots_[m])) fail("the parameter domain is empty (first knot equals last knot)");
    for(std::size_t i = q + 1; i + q + 1 <= m; ++i)
      if(multiplicity(knots_[i]) > degree_)
        fail("interior knot " + std::to_string(knots_[i]) + " has multiplicity above the degree " + p +
             " (the basis would be discontinuous)");
  }

  int degree_ = 0;
  std::vector<double> knots_;
};

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_KNOT_VECTOR_H
