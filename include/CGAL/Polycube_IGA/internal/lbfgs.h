// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Limited-memory BFGS (Nocedal & Wright, Numerical Optimization, Alg. 7.4 and 7.5) with a
// backtracking Armijo line search. Small and dependency-free: Eigen 3.4 has no quasi-Newton
// solver and the energies minimised here are smooth and finite everywhere (regularised), so
// no Wolfe conditions are needed. Deterministic.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_LBFGS_H
#define CGAL_POLYCUBE_IGA_INTERNAL_LBFGS_H

#include <Eigen/Core>

#include <cmath>
#include <deque>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

struct Lbfgs_options
{
  int memory = 8;
  int maximum_iterations = 200;
  double relative_decrease = 1e-9; ///< stop when an iteration lowers f by less than this times |f|
  double gradient_tolerance = 1e-12; ///< stop when |g|_inf falls below this
};

struct Lbfgs_result
{
  int iterations = 0;
  int evaluations = 0;
  double value = 0.;
};

/// Minimises f from `x` (updated in place). `fg(x, g)` returns f(x) and writes its gradient.
template <class Function>
Lbfgs_result lbfgs_minimize(Function&& fg, Eigen::VectorXd& x, const Lbfgs_options& o = Lbfgs_options())
{
  Lbfgs_result r;
  const Eigen::Index n = x.size();
  Eigen::VectorXd g(n), g_new(n), d(n), x_new(n);
  double f = fg(x, g);
  ++r.evaluations;
  std::deque<Eigen::VectorXd> S, Y;
  std::deque<double> rho;
  for(; r.iterations < o.maximum_iterations; ++r.iterations) {
    if(n == 0 || g.lpNorm<Eigen::Infinity>() < o.gradient_tolerance) break;
    // Two-loop recursion: d = -H g.
    d = -g;
    std::vector<double> alpha(S.size());
    for(std::size_t i = S.size(); i-- > 0;) {
      alpha[i] = rho[i] * S[i].dot(d);
      d -= alpha[i] * Y[i];
    }
    if(!S.empty()) d *= S.back().dot(Y.back()) / Y.back().squaredNorm();
    else d *= 1. / std::max(1., g.norm()); // first step: a short steepest descent
    for(std::size_t i = 0; i < S.size(); ++i) {
      const double beta = rho[i] * Y[i].dot(d);
      d += (alpha[i] - beta) * S[i];
    }
    double slope = g.dot(d);
    if(!(slope < 0.)) { // not a descent direction (curvature lost): restart
      S.clear(), Y.clear(), rho.clear();
      d = -g / std::max(1., g.norm());
      slope = g.dot(d);
    }
    double step = 1., f_new = f;
    bool accepted = false;
    for(int k = 0; k < 40; ++k, step *= 0.5) {
      x_new = x + step * d;
      f_new = fg(x_new, g_new);
      ++r.evaluations;
      if(std::isfinite(f_new) && f_new <= f + 1e-4 * step * slope) {
        accepted = true;
        break;
      }
    }
    if(!accepted) break;
    const Eigen::VectorXd s = x_new - x, y = g_new - g;
    const double sy = s.dot(y);
    const double decrease = f - f_new;
    x.swap(x_new);
    g.swap(g_new);
    f = f_new;
    if(sy > 1e-16 * s.norm() * y.norm()) {
      S.push_back(s), Y.push_back(y), rho.push_back(1. / sy);
      if(int(S.size()) > o.memory) S.pop_front(), Y.pop_front(), rho.pop_front();
    }
    if(decrease <= o.relative_decrease * std::abs(f)) {
      ++r.iterations;
      break;
    }
  }
  r.value = f;
  return r;
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_LBFGS_H
