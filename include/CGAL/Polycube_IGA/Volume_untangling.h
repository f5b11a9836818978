// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Untangling and improving a multipatch volume by moving its free control points: those not
// on a boundary side (the solid's surface and caps stay exactly where §4.1 fitted them).
// Coons interpolation plus Laplacian smoothing (§4.1) cannot guarantee det J > 0 once the
// cuboids are curved; like the Jacobian-constrained parameterizations of the IGA literature
// (Xu et al. 2013), this minimises a distortion energy of the Jacobian at Gauss points of
// every span. The energy is the regularised one of Garanzha et al., "Foldover-free maps in
// 50 lines of code" (2021): with K = J W^-1 (W the patch's mean Jacobian, so a thin slab
// is measured against a thin reference), D = det K and chi(D, e) = (D + sqrt(e^2 + D^2)) / 2,
//   f = (1 - theta) |K|^2 / (3 chi^(2/3)) + theta (D^2 + 1) / (2 chi),
// finite for inverted samples, so L-BFGS can pull them through; e shrinks round by round by
// their rule until every sample is positive, and the energy then acts as a barrier.
// Control points shared across interfaces are one unknown, so conformity is kept exactly.
// Jacobians and their adjoint are evaluated by sum factorisation over the tensor grid of
// samples (one direction contracted at a time), several times cheaper than per sample.

#ifndef CGAL_POLYCUBE_IGA_VOLUME_UNTANGLING_H
#define CGAL_POLYCUBE_IGA_VOLUME_UNTANGLING_H

#include <CGAL/Polycube_IGA/Bspline_basis.h>
#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/Quality.h>
#include <CGAL/Polycube_IGA/internal/lbfgs.h>
#include <CGAL/Polycube_IGA/internal/parallel_for.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Polycube_IGA {

/// Work that the untangle_volume() calls of one run share: the Jacobian samples their
/// energy evaluations visit. It bounds a run that cannot succeed (a CAD ring remeshed to
/// 5,796 faces spent 13 minutes untangling grids no rounds made valid) by a count, not by
/// seconds, so the result is the same on every machine and thread count.
struct Untangling_budget
{
  double limit = std::numeric_limits<double>::infinity(); ///< samples the calls may visit in all
  double spent = 0.;                                      ///< samples visited so far
  bool exhausted() const { return !(spent < limit); }
};

/// Options of untangle_volume().
struct Volume_untangling_options
{
  /// Gauss-Lobatto points per span and direction, ends included (2..5). det J can be
  /// positive at every sample and negative between, so patches the Bernstein bound does not
  /// certify take part too, and those still uncertified get more points (up to
  /// maximum_points_per_span), then focused samples, at the end. With 4 from the start,
  /// every round costs (13/9)^3 = 3 times as much: eight.off, double-torus-example.off and
  /// 3holes.obj untangle 2 to 3 times slower, and no better.
  int points_per_span = 3;
  /// The most Gauss-Lobatto points per span the patches still uncertified get (up to 5).
  int maximum_points_per_span = 5;
  /// Rounds of focused samples once the densest Gauss-Lobatto samples are not enough: each
  /// adds, to every patch still not certified, one sample per direction where the Bernstein
  /// bound of its det J is lowest (Jacobian_bound::lower_bound_at), and the rounds go on.
  /// A fold between the Gauss-Lobatto points is then seen by the energy: the CAD plate with
  /// six holes of the unseen corpus, left with one such patch at degree 3 (det J -0.0076
  /// between samples), is then valid at its first grid (247 s instead of 698 s for a
  /// quadratic volume at 8 samples). 0: none.
  int focused_sample_rounds = 4;
  /// Focusing stops, before its rounds, when a new sample has det(J W^-1) below this (W the
  /// patch's mean Jacobian): not a shallow dip between samples but a fold they missed
  /// outright. Such rounds certified nothing in our runs and were most of the focusing's
  /// cost (pinion.off: 25 patches, -3.98 at the new samples, still -0.20 and 26 patches
  /// after 0.58 billion samples, the run 1.46 times as long; a femur's and mushroom.off's
  /// failing grids of the tests began at -0.6 to -1); every round that helped began above
  /// -0.35. Focusing also stops after two rounds in a row that did not leave fewer patches
  /// uncertified than any round before (it can take one such round: the plate above goes
  /// 1, 1, 0).
  double focused_sample_floor = -0.5;
  double volume_weight = 0.25; ///< theta: weight of the volume term against the shape term
  /// Patches with a sampled scaled Jacobian below this (at Gauss points and span corners),
  /// or with det J not certified positive, are optimised, with their interface neighbours.
  double scaled_jacobian_threshold = 0.05;
  /// Cost guards: with more patches to optimise than this, or more control points in them
  /// than maximum_control_points, nothing is done (`skipped`). Cost grows with the control
  /// points and the rounds: at the default grid (4 spans, 343 points per patch) about 3 s
  /// for eight.off's 31 patches, 5.5 s for 3holes.obj's 52, 86 s for blade.off's 105. The
  /// point guard is 1024 such patches, so at the default grid both bind together; at twice
  /// the samples (8 spans, 1331 points per patch) it admits 264. The run's time is
  /// bounded by build_trivariate_model()'s untangling_budget, so these only keep a run
  /// from starting on a volume far beyond it. At 128 patches and 256 * 343 points, the
  /// genus-5 flange of the unseen corpus (220 patches to optimise) was not untangled and
  /// its pants layout left 66 of 167 patches uncertified; untangled, 8 (2 with its nodes
  /// relocated), with no more memory (343 MB at the peak either way), in 479 s instead of
  /// 122. At 128 * 343 points a CAD square ring (40 patches) stayed invalid; untangled at
  /// 32 samples it is valid.
  std::size_t maximum_patches = 1024;
  std::size_t maximum_control_points = 1024 * 343;
  /// Epsilon updates per sample density. With minimum_decrease 0.5, every test mesh whose
  /// samples turn positive does so within 22 rounds (blade.off: 17, 21 and 22 at 3, 4 and
  /// 5 points per span); rotor.off, which never does, crawls from -5 to -1.4 in 60.
  int maximum_rounds = 30;
  /// Floor of sigma, the energy decrease a round is credited with in the epsilon update
  /// (Garanzha et al. use 0.1): the larger, the faster epsilon shrinks while an inverted
  /// sample resists. At 0.5, eight.off untangles in 8 rounds instead of 29 and blade.off's
  /// samples turn positive in 17 instead of 81, with larger smallest scaled Jacobians
  /// (eight: 0.071 against 0.039); 0.7 and 0.9 save one or two more rounds.
  double minimum_decrease = 0.5;
  int iterations_per_round = 100;   ///< L-BFGS iterations per round
  /// Rounds stop early, as stalled, when a sample is still inverted and the best smallest
  /// det of the last `stall_window` rounds rose by less than `stall_rise` of its magnitude
  /// over the best before them. Where untangling succeeds it rises at every round (eight.off
  /// -0.55, -0.37, -0.32, -0.19, -0.05, +0.02; blade.off's slowest run by 0.05 to 0.1 a
  /// round); where it cannot, epsilon keeps shrinking, the energy doubles a round and the
  /// det stays put: rotor.off at 32 samples (45 patches) sits at -0.53 from its 12th round
  /// to its 30th, about 10 s a round; it now stops after its 17th.
  int stall_window = 5;
  double stall_rise = 0.1;
  /// For a caller that keeps the volume only if every patch ends certified (the finer grids
  /// of build_trivariate_model()): a pinned patch rules that out, so with this set
  /// untangle_volume() stops before its rounds, `reverted`, the volume unchanged.
  bool stop_when_pinned = false;
  /// Shared with other calls (nullptr: no limit). A call that finds it exhausted moves
  /// nothing (`out_of_budget`, `reverted`); rounds stop once it is (the last one has as many
  /// L-BFGS iterations as it has evaluations left, and its line searches may overrun it a
  /// little), and what they reached is kept on the usual terms.
  Untangling_budget* budget = nullptr;
  /// Threads for the per-patch work (energies, gradients, certificates); 0: one per core the
  /// process may run on (internal::worker_count()). The result does not depend on it:
  /// per-patch sums are combined in patch order.
  unsigned threads = 0;
};

/// What untangle_volume() did.
struct Volume_untangling_result
{
  std::vector<std::size_t> patches; ///< patches whose samples entered the energy
  std::size_t free_points = 0;      ///< control points moved (shared ones counted once)
  std::size_t sliding_points = 0;   ///< of those, points of sliding sides, moved in their tangent plane
  int rounds = 0, iterations = 0;
  /// Smallest det(J W^-1) over the samples of those patches, before and after.
  double min_relative_determinant_before = 0., min_relative_determinant_after = 0.;
  bool positive_at_samples = false; ///< every sample has det J > 0 afterwards
  /// Optimised patches with det J <= 0 at a sample that only fixed control points (the
  /// boundary sides, other patches) determine: untangling cannot certify them.
  std::vector<std::size_t> pinned_patches;
  bool skipped = false; ///< more patches or control points needed it than the options' cost guards allow
  /// The optimised points were discarded: the smallest sampled det J did not improve, or a
  /// patch whose det J was certified positive lost its certificate.
  bool reverted = false;
  /// Rounds ended early: a sample stayed inverted and the smallest det stopped rising
  /// (Volume_untangling_options::stall_window).
  bool stalled = false;
  /// The budget (Volume_untangling_options::budget) was exhausted before the call or ended
  /// its rounds.
  bool out_of_budget = false;
  /// Jacobian samples the energy evaluations of this call visited (what it took of the budget).
  double work = 0.;
  /// Optimised patches whose det J is not certified positive afterwards.
  std::vector<std::size_t> uncertified_patches;
  /// Samples added where the certificate's bound was lowest
  /// (Volume_untangling_options::focused_sample_rounds).
  std::size_t focused_samples = 0;
  int passes = 1; ///< untangle_volume() calls merged here (add_pass())

  /// Merges `next`, a later call on the same volume that was not skipped nor reverted.
  void add_pass(const Volume_untangling_result& next)
  {
    std::vector<std::size_t> all = patches;
    all.insert(all.end(), next.patches.begin(), next.patches.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    patches = std::move(all);
    free_points = std::max(free_points, next.free_points);
    sliding_points = std::max(sliding_points, next.sliding_points);
    rounds += next.rounds, iterations += next.iterations;
    stalled = stalled || next.stalled;
    out_of_budget = out_of_budget || next.out_of_budget;
    work += next.work;
    focused_samples += next.focused_samples;
    min_relative_determinant_after = next.min_relative_determinant_after;
    positive_at_samples = next.positive_at_samples;
    pinned_patches = next.pinned_patches;
    uncertified_patches = next.uncertified_patches;
    passes += next.passes;
    reverted = false; // the volume moved
  }
};

namespace internal {

/// Basis values and first derivatives of one direction at a list of parameters.
struct Direction_samples
{
  int p = 0;
  std::vector<double> weight;
  std::vector<int> first;          // index of the first non-zero basis function
  std::vector<double> value, slope; // (p + 1) per sample
};

inline Direction_samples direction_samples(const Knot_vector& kv, const std::vector<double>& t, const std::vector<double>& w)
{
  Direction_samples s;
  s.p = kv.degree();
  const int P = s.p + 1;
  std::vector<double> ders(std::size_t(2 * P));
  for(std::size_t i = 0; i < t.size(); ++i) {
    const int span = kv.find_span(t[i]);
    basis_function_derivatives(kv, span, t[i], 1, ders.data());
    s.weight.push_back(w[i]);
    s.first.push_back(span - s.p);
    for(int j = 0; j < P; ++j) s.value.push_back(ders[std::size_t(j)]), s.slope.push_back(ders[std::size_t(P + j)]);
  }
  return s;
}

/// Parameters of one direction's samples, ascending, and their quadrature weights.
struct Span_points
{
  std::vector<double> t, w;
};

/// Gauss-Lobatto points of every span (its ends and q - 2 inner points; weights sum to the
/// span lengths). The ends matter: det J is often smallest on the boundary sides and at
/// span joints.
inline Span_points span_points_with_ends(const Knot_vector& kv, int q)
{
  q = std::min(std::max(q, 2), 5);
  const double a = std::sqrt(0.2), b = std::sqrt(3. / 7.);
  static const std::vector<double> gx[4] = {{-1., 1.}, {-1., 0., 1.}, {-1., -a, a, 1.}, {-1., -b, 0., b, 1.}};
  static const std::vector<double> gw[4] = {{1., 1.}, {1. / 3., 4. / 3., 1. / 3.}, {1. / 6., 5. / 6., 5. / 6., 1. / 6.},
                                            {0.1, 49. / 90., 32. / 45., 49. / 90., 0.1}};
  const std::vector<double>&x = gx[q - 2], &xw = gw[q - 2];
  Span_points p;
  const std::vector<double> br = kv.breaks();
  for(std::size_t s = 0; s + 1 < br.size(); ++s) {
    const double mid = 0.5 * (br[s] + br[s + 1]), half = 0.5 * (br[s + 1] - br[s]);
    if(!(half > 0.)) continue;
    for(std::size_t k = 0; k < x.size(); ++k) {
      if(k == 0 && !p.t.empty()) { p.w.back() += half * xw[k]; continue; } // shared span end
      p.t.push_back(k + 1 == x.size() ? br[s + 1] : k == 0 ? br[s] : mid + half * x[k]);
      p.w.push_back(half * xw[k]);
    }
  }
  return p;
}

/// Adds a sample at `u` weighing a quarter of the lightest one, unless one lies within
/// 1e-9: a point the energy must see, not a quadrature node (the weights then no longer
/// sum to the span lengths, by a small share). Returns whether it was added.
inline bool add_focused_point(Span_points& p, double u)
{
  const auto at = std::lower_bound(p.t.begin(), p.t.end(), u);
  if((at != p.t.end() && *at - u < 1e-9) || (at != p.t.begin() && u - *(at - 1) < 1e-9)) return false;
  const double weight = 0.25 * *std::min_element(p.w.begin(), p.w.end());
  p.w.insert(p.w.begin() + (at - p.t.begin()), weight);
  p.t.insert(at, u);
  return true;
}

/// Samples of one direction at Gauss-Lobatto points (span_points_with_ends()).
inline Direction_samples span_samples_with_ends(const Knot_vector& kv, int q)
{
  const Span_points p = span_points_with_ends(kv, q);
  return direction_samples(kv, p.t, p.w);
}

/// Sizes shared by patch_jacobians() and its adjoint: samples q and non-zero functions P per
/// direction, the net's n1, n2 and n0 n1.
struct Grid_sizes
{
  std::size_t q0, q1, q2;
  int P0, P1, P2;
  std::size_t n1, n2, n01;
};

inline Grid_sizes grid_sizes(const std::array<int, 3>& n, const std::array<Direction_samples, 3>& S)
{
  return {S[0].weight.size(), S[1].weight.size(), S[2].weight.size(), S[0].p + 1, S[1].p + 1, S[2].p + 1,
          std::size_t(n[1]), std::size_t(n[2]), std::size_t(n[0]) * std::size_t(n[1])};
}

/// Jacobians J[s] (columns d/du, d/dv, d/dw) of a patch with control points P at all samples
/// s = a + q0 (b + q1 c) of the tensor grid S[0] x S[1] x S[2], by sum factorisation (one
/// direction contracted at a time): O(q n^2 p) work instead of O(q^3 p^3).
inline void patch_jacobians(const std::array<int, 3>& n, const std::array<Direction_samples, 3>& S,
                            const std::vector<Eigen::Vector3d>& P, std::vector<Eigen::Matrix3d>& J)
{
  using Eigen::Vector3d;
  const auto [q0, q1, q2, P0, P1, P2, n1, n2, n01] = grid_sizes(n, S);
  // u contracted: A[(a, j, k)] = sum_i {N, N'}_u(a, i) P(i, j, k).
  std::vector<Vector3d> A0(q0 * n1 * n2, Vector3d::Zero()), A1(A0.size(), Vector3d::Zero());
  for(std::size_t k = 0; k < n2; ++k)
    for(std::size_t j = 0; j < n1; ++j)
      for(std::size_t a = 0; a < q0; ++a) {
        Vector3d s0 = Vector3d::Zero(), s1 = Vector3d::Zero();
        for(int i = 0; i < P0; ++i) {
          const Vector3d& x = P[std::size_t(S[0].first[a] + i) + std::size_t(n[0]) * j + n01 * k];
          s0 += S[0].value[a * std::size_t(P0) + std::size_t(i)] * x;
          s1 += S[0].slope[a * std::size_t(P0) + std::size_t(i)] * x;
        }
        A0[a + q0 * (j + n1 * k)] = s0, A1[a + q0 * (j + n1 * k)] = s1;
      }
  // v contracted: B00 = N_v A0 (for d/dw), B10 = N_v A1 (d/du), B01 = N'_v A0 (d/dv).
  std::vector<Vector3d> B00(q0 * q1 * n2), B10(B00.size()), B01(B00.size());
  for(std::size_t k = 0; k < n2; ++k)
    for(std::size_t b = 0; b < q1; ++b)
      for(std::size_t a = 0; a < q0; ++a) {
        Vector3d s00 = Vector3d::Zero(), s10 = Vector3d::Zero(), s01 = Vector3d::Zero();
        for(int j = 0; j < P1; ++j) {
          const std::size_t at = a + q0 * (std::size_t(S[1].first[b] + j) + n1 * k);
          const double N = S[1].value[b * std::size_t(P1) + std::size_t(j)], D = S[1].slope[b * std::size_t(P1) + std::size_t(j)];
          s00 += N * A0[at], s10 += N * A1[at], s01 += D * A0[at];
        }
        const std::size_t out = a + q0 * (b + q1 * k);
        B00[out] = s00, B10[out] = s10, B01[out] = s01;
      }
  // w contracted.
  J.assign(q0 * q1 * q2, Eigen::Matrix3d::Zero());
  for(std::size_t c = 0; c < q2; ++c)
    for(std::size_t b = 0; b < q1; ++b)
      for(std::size_t a = 0; a < q0; ++a) {
        Eigen::Matrix3d& M = J[a + q0 * (b + q1 * c)];
        for(int k = 0; k < P2; ++k) {
          const std::size_t at = a + q0 * (b + q1 * std::size_t(S[2].first[c] + k));
          const double N = S[2].value[c * std::size_t(P2) + std::size_t(k)], D = S[2].slope[c * std::size_t(P2) + std::size_t(k)];
          M.col(0) += N * B10[at], M.col(1) += N * B01[at], M.col(2) += D * B00[at];
        }
      }
}

/// Adjoint of patch_jacobians(): given G[s] = dE/dJ[s], returns dE/dP for every control
/// point (the same three contractions in reverse order).
inline void patch_jacobians_adjoint(const std::array<int, 3>& n, const std::array<Direction_samples, 3>& S,
                                    const std::vector<Eigen::Matrix3d>& G, std::vector<Eigen::Vector3d>& dP)
{
  using Eigen::Vector3d;
  const auto [q0, q1, q2, P0, P1, P2, n1, n2, n01] = grid_sizes(n, S);
  std::vector<Vector3d> B00(q0 * q1 * n2, Vector3d::Zero()), B10(B00.size(), Vector3d::Zero()), B01(B00.size(), Vector3d::Zero());
  for(std::size_t c = 0; c < q2; ++c)
    for(std::size_t b = 0; b < q1; ++b)
      for(std::size_t a = 0; a < q0; ++a) {
        const Eigen::Matrix3d& M = G[a + q0 * (b + q1 * c)];
        for(int k = 0; k < P2; ++k) {
          const std::size_t at = a + q0 * (b + q1 * std::size_t(S[2].first[c] + k));
          const double N = S[2].value[c * std::size_t(P2) + std::size_t(k)], D = S[2].slope[c * std::size_t(P2) + std::size_t(k)];
          B10[at] += N * M.col(0), B01[at] += N * M.col(1), B00[at] += D * M.col(2);
        }
      }
  std::vector<Vector3d> A0(q0 * n1 * n2, Vector3d::Zero()), A1(A0.size(), Vector3d::Zero());
  for(std::size_t k = 0; k < n2; ++k)
    for(std::size_t b = 0; b < q1; ++b)
      for(std::size_t a = 0; a < q0; ++a) {
        const std::size_t from = a + q0 * (b + q1 * k);
        for(int j = 0; j < P1; ++j) {
          const std::size_t at = a + q0 * (std::size_t(S[1].first[b] + j) + n1 * k);
          const double N = S[1].value[b * std::size_t(P1) + std::size_t(j)], D = S[1].slope[b * std::size_t(P1) + std::size_t(j)];
          A0[at] += N * B00[from] + D * B01[from], A1[at] += N * B10[from];
        }
      }
  dP.assign(n01 * n2, Vector3d::Zero());
  for(std::size_t k = 0; k < n2; ++k)
    for(std::size_t j = 0; j < n1; ++j)
      for(std::size_t a = 0; a < q0; ++a) {
        const std::size_t from = a + q0 * (j + n1 * k);
        for(int i = 0; i < P0; ++i)
          dP[std::size_t(S[0].first[a] + i) + std::size_t(n[0]) * j + n01 * k] +=
            S[0].value[a * std::size_t(P0) + std::size_t(i)] * A0[from] + S[0].slope[a * std::size_t(P0) + std::size_t(i)] * A1[from];
      }
}

/// Per sample s = a + q0 (b + q1 c) of the grid S: whether some control point k with
/// is_free(k) moves J[s], i.e. has a non-zero coefficient in one of its columns. The others'
/// det J is set by the fixed points alone (two boundary sides meeting at an edge fix all
/// three columns there), and no untangling can change it.
template <class IsFree>
std::vector<bool> movable_samples(const std::array<int, 3>& n, const std::array<Direction_samples, 3>& S, IsFree&& is_free)
{
  const auto [q0, q1, q2, P0, P1, P2, n1, n2, n01] = grid_sizes(n, S);
  std::vector<bool> movable(q0 * q1 * q2, false);
  for(std::size_t c = 0; c < q2; ++c)
    for(std::size_t b = 0; b < q1; ++b)
      for(std::size_t a = 0; a < q0; ++a) {
        bool m = false;
        for(int k = 0; k < P2 && !m; ++k)
          for(int j = 0; j < P1 && !m; ++j)
            for(int i = 0; i < P0 && !m; ++i) {
              const std::size_t ia = a * std::size_t(P0) + std::size_t(i), jb = b * std::size_t(P1) + std::size_t(j),
                                kc = c * std::size_t(P2) + std::size_t(k);
              const double Nu = S[0].value[ia], Du = S[0].slope[ia], Nv = S[1].value[jb], Dv = S[1].slope[jb],
                           Nw = S[2].value[kc], Dw = S[2].slope[kc];
              if(Du * Nv * Nw == 0. && Nu * Dv * Nw == 0. && Nu * Nv * Dw == 0.) continue;
              m = is_free(std::size_t(S[0].first[a] + i) + std::size_t(n[0]) * (std::size_t(S[1].first[b] + j) + n1 * std::size_t(S[2].first[c] + k)));
            }
        movable[a + q0 * (b + q1 * c)] = m;
      }
  return movable;
}

/// Weight of sample s = a + q0 (b + q1 c).
inline double sample_weight(const std::array<Direction_samples, 3>& S, std::size_t s)
{
  const std::size_t q0 = S[0].weight.size(), q1 = S[1].weight.size();
  return S[0].weight[s % q0] * S[1].weight[(s / q0) % q1] * S[2].weight[s / (q0 * q1)];
}

/// chi(D, e) = (D + sqrt(e^2 + D^2)) / 2, written without cancellation for D < 0.
inline double regularised_determinant(double D, double e)
{
  const double root = std::sqrt(e * e + D * D);
  return D >= 0. ? 0.5 * (D + root) : 0.5 * e * e / (root - D);
}

/// Columns of the cofactor matrix of K: the derivative of det K with respect to K.
inline Eigen::Matrix3d cofactor(const Eigen::Matrix3d& K)
{
  Eigen::Matrix3d C;
  C.col(0) = K.col(1).cross(K.col(2));
  C.col(1) = K.col(2).cross(K.col(0));
  C.col(2) = K.col(0).cross(K.col(1));
  return C;
}

/// Minimum scaled Jacobian of v at the samples S.
inline double sampled_scaled_jacobian(const Tensor_bspline_volume& v, const std::array<Direction_samples, 3>& S)
{
  std::vector<Eigen::Matrix3d> J;
  patch_jacobians(v.control_net_size(), S, v.control_points(), J);
  double m = std::numeric_limits<double>::infinity();
  for(const Eigen::Matrix3d& M : J) {
    const double len = M.col(0).norm() * M.col(1).norm() * M.col(2).norm();
    m = std::min(m, len > 0. ? M.determinant() / len : -1.);
  }
  return m;
}

/// Control points of one patch lying on side s.
template <class F>
void for_each_side_point(const Tensor_bspline_volume& v, int s, F&& f)
{
  const int d = side_direction(s);
  const std::array<int, 3> n = v.control_net_size();
  std::array<int, 3> i{};
  i[std::size_t(d)] = side_parameter(s) ? n[std::size_t(d)] - 1 : 0;
  const int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
  for(i[std::size_t(d2)] = 0; i[std::size_t(d2)] < n[std::size_t(d2)]; ++i[std::size_t(d2)])
    for(i[std::size_t(d1)] = 0; i[std::size_t(d1)] < n[std::size_t(d1)]; ++i[std::size_t(d1)]) f(i);
}

/// Normal of side s of v at its control point i, from the control net: the cross product of
/// the net's differences along the side's two directions (one-sided at its edges). Not
/// normalised; zero where the net is degenerate.
inline Eigen::Vector3d side_point_normal(const Tensor_bspline_volume& v, int s, const std::array<int, 3>& i)
{
  const int d = side_direction(s);
  const std::array<int, 3> n = v.control_net_size();
  Eigen::Vector3d t[2];
  for(int e = 1; e <= 2; ++e) {
    const std::size_t a = std::size_t((d + e) % 3);
    std::array<int, 3> lo = i, hi = i;
    lo[a] = std::max(0, i[a] - 1), hi[a] = std::min(n[a] - 1, i[a] + 1);
    t[e - 1] = v.control_points()[v.linear_index(hi)] - v.control_points()[v.linear_index(lo)];
  }
  return t[0].cross(t[1]);
}

} // namespace internal

/*!
 * \ingroup PkgPolycubeIGARef
 * Moves the free control points of the patches of `mv` whose sampled scaled Jacobian is
 * below `o.scaled_jacobian_threshold` or whose det J is not certified positive
 * (certified_jacobian_bound()), and of their interface neighbours, to minimise the
 * regularised distortion energy described at the top of this file. Points on boundary
 * sides, points of other patches and rational patches stay fixed; a point shared by an
 * interface moves on both sides at once, so interfaces stay conforming. Returns what was
 * done; `mv` is left unchanged if no patch is below the threshold, if more than
 * `o.maximum_patches` patches or `o.maximum_control_points` control points would be
 * optimised (`skipped`), or (`reverted`) if the smallest
 * sampled det J does not improve or a patch certified valid before is not afterwards.
 * `certified`, if given, holds certified_jacobian_bound() of every patch of `mv` with
 * default options (from evaluate_quality()), which is then not computed again.
 * `sliding_sides`, boundary sides of `mv` (caps: layout_volume()'s `slide_caps`), are not
 * fixed: their control points move in the plane through each normal to the side, except
 * those also on a fixed side, on an edge between two of them at more than 30 degrees, or
 * where the control net is degenerate (no normal). Deterministic.
 */
inline Volume_untangling_result untangle_volume(Multipatch_volume& mv,
                                                const Volume_untangling_options& o = Volume_untangling_options(),
                                                const std::vector<Jacobian_bound>* certified = nullptr,
                                                const std::vector<Patch_side>& sliding_sides = {})
{
  using Eigen::Vector3d;
  Volume_untangling_result r;
  const std::size_t np = mv.number_of_patches();
  std::vector<std::array<internal::Direction_samples, 3>> samples(np);
  std::vector<bool> active(np, false);
  std::vector<double> sampled(np, 0.); // smallest sampled scaled Jacobian (polynomial patches)
  const unsigned threads = internal::worker_count(o.threads);
  // Written by the threads, one entry each, so not vector<bool> (whose entries share words).
  std::vector<char> certified_before(np, 0), low(np, 0);
  internal::parallel_for(np, threads, [&](std::size_t c, unsigned) {
    const Tensor_bspline_volume& v = mv.patch(c);
    for(int d = 0; d < 3; ++d) samples[c][std::size_t(d)] = internal::span_samples_with_ends(v.knot_vector(d), o.points_per_span);
    if(v.is_rational()) return;
    sampled[c] = internal::sampled_scaled_jacobian(v, samples[c]);
    // A patch positive at every sample can still fold between them (double-torus-example.off:
    // next to a corner, where only its neighbours' free points can help), so the certificate
    // picks patches too. A non-positive sample rules it out (and the bound is costly there).
    certified_before[c] = sampled[c] > 0. &&
                          (certified && certified->size() == np ? (*certified)[c].certified_positive : certified_jacobian_bound(v).certified_positive);
    low[c] = sampled[c] < o.scaled_jacobian_threshold || !certified_before[c];
  });
  bool any = false;
  for(std::size_t c = 0; c < np; ++c)
    if(low[c]) active[c] = any = true;
  if(!any) {
    r.positive_at_samples = true;
    return r;
  }
  std::vector<bool> seed = active;
  for(const Patch_interface& I : mv.interfaces())
    if(seed[I.first.patch] || seed[I.second.patch]) active[I.first.patch] = active[I.second.patch] = true;
  for(std::size_t c = 0; c < np; ++c)
    if(mv.patch(c).is_rational()) active[c] = false;
  std::size_t active_points = 0;
  for(std::size_t c = 0; c < np; ++c)
    if(active[c]) active_points += mv.patch(c).number_of_control_points();
  if(std::size_t(std::count(active.begin(), active.end(), true)) > o.maximum_patches || active_points > o.maximum_control_points) {
    for(std::size_t c = 0; c < np; ++c)
      if(active[c]) r.patches.push_back(c);
    r.skipped = true;
    return r;
  }

  // Control points as classes of a union-find over (patch, linear index); a class is fixed
  // if any member lies on a boundary side or in a patch that is not optimised.
  std::vector<std::size_t> offset(np + 1, 0);
  for(std::size_t c = 0; c < np; ++c) offset[c + 1] = offset[c] + mv.patch(c).number_of_control_points();
  std::vector<std::size_t> parent(offset[np]);
  std::iota(parent.begin(), parent.end(), std::size_t(0));
  auto find = [&](std::size_t a) {
    while(parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<bool> fixed(offset[np], false);
  auto linear = [&](std::size_t c, const std::array<int, 3>& i) { return offset[c] + mv.patch(c).linear_index(i); };
  for(const Patch_interface& I : mv.interfaces()) {
    const Tensor_bspline_volume &a = mv.patch(I.first.patch), &b = mv.patch(I.second.patch);
    bool same = true;
    for(int d = 0; d < 3; ++d)
      if(d != side_direction(I.first.side))
        same = same && a.number_of_control_points(d) == b.number_of_control_points(I.direction_map[std::size_t(d)]);
    internal::for_each_side_point(a, I.first.side, [&](const std::array<int, 3>& i) {
      if(!same) {
        fixed[linear(I.first.patch, i)] = true;
        return;
      }
      std::array<double, 3> s{};
      for(int d = 0; d < 3; ++d) s[std::size_t(d)] = double(i[std::size_t(d)]) / double(std::max(1, a.number_of_control_points(d) - 1));
      const std::array<double, 3> t = I.map_normalized(s);
      std::array<int, 3> j{};
      for(int d = 0; d < 3; ++d)
        j[std::size_t(d)] = int(std::lround(t[std::size_t(d)] * double(std::max(1, b.number_of_control_points(d) - 1))));
      parent[find(linear(I.first.patch, i))] = find(linear(I.second.patch, j));
    });
    if(!same)
      internal::for_each_side_point(b, I.second.side, [&](const std::array<int, 3>& j) { fixed[linear(I.second.patch, j)] = true; });
  }
  // Points of a sliding side keep to the plane through them normal to the side (summed over
  // the members of their class, each turned to agree with the first); the other boundary
  // sides fix theirs. A class whose members' normals disagree by more than 30 degrees (an
  // edge where two sliding sides meet at an angle) is fixed too.
  std::vector<Vector3d> side_normal(offset[np], Vector3d::Zero());
  for(const Patch_side& s : mv.boundaries()) {
    const bool slides = std::find(sliding_sides.begin(), sliding_sides.end(), s) != sliding_sides.end();
    internal::for_each_side_point(mv.patch(s.patch), s.side, [&](const std::array<int, 3>& i) {
      const std::size_t k = linear(s.patch, i);
      // Fixed if on a fixed side, on two sliding sides (an edge between them: its normal set,
      // or the point already fixed), or where the net is degenerate: with no normal it would
      // move freely, off its side. A fixed point's normal is never read.
      if(!slides || fixed[k] || !side_normal[k].isZero()) fixed[k] = true;
      else {
        side_normal[k] = internal::side_point_normal(mv.patch(s.patch), s.side, i);
        fixed[k] = side_normal[k].isZero();
      }
    });
  }
  for(std::size_t c = 0; c < np; ++c)
    if(!active[c])
      for(std::size_t k = offset[c]; k < offset[c + 1]; ++k) fixed[k] = true;
  std::vector<Vector3d> class_normal(offset[np], Vector3d::Zero());
  for(std::size_t k = 0; k < fixed.size(); ++k) {
    const std::size_t root = find(k);
    if(fixed[k]) fixed[root] = true;
    const double len = side_normal[k].norm();
    if(!(len > 0.) || fixed[root]) continue;
    const Vector3d m = side_normal[k] / len;
    Vector3d& sum = class_normal[root];
    const double agree = sum.isZero() ? 1. : m.dot(sum.normalized());
    if(std::abs(agree) < std::sqrt(3.) / 2.) fixed[root] = true; // over 30 degrees apart
    else sum += agree > 0. ? m : Vector3d(-m);
  }

  // Unknowns: one per free class, numbered in first-member order (deterministic).
  // A sliding unknown has a unit normal: it moves in the plane through its start normal to it.
  std::vector<long> unknown_of_root(offset[np], -1), unknown(offset[np], -1);
  Eigen::VectorXd x;
  std::vector<Vector3d> start, slide;
  for(std::size_t k = 0; k < offset[np]; ++k) {
    const std::size_t root = find(k);
    if(fixed[root]) continue;
    if(unknown_of_root[root] < 0) {
      unknown_of_root[root] = long(start.size());
      std::size_t c = std::size_t(std::upper_bound(offset.begin(), offset.end(), k) - offset.begin()) - 1;
      start.push_back(mv.patch(c).control_points()[k - offset[c]]);
      slide.push_back(class_normal[root].isZero() ? Vector3d::Zero() : Vector3d(class_normal[root].normalized()));
    }
    unknown[k] = unknown_of_root[root];
  }
  r.sliding_points = std::size_t(std::count_if(slide.begin(), slide.end(), [](const Vector3d& n) { return !n.isZero(); }));
  r.free_points = start.size();
  for(std::size_t c = 0; c < np; ++c)
    if(active[c]) r.patches.push_back(c);
  const std::vector<std::array<internal::Direction_samples, 3>> first_samples = samples;

  // Per patch: the reference W (mean Jacobian over the unit cube of parameters) and W^-1.
  std::vector<Eigen::Matrix3d> Winv(np, Eigen::Matrix3d::Identity());
  for(std::size_t c : r.patches) {
    Eigen::Matrix3d W = Eigen::Matrix3d::Zero();
    double total = 0.;
    std::vector<Eigen::Matrix3d> J;
    internal::patch_jacobians(mv.patch(c).control_net_size(), samples[c], mv.patch(c).control_points(), J);
    for(std::size_t s = 0; s < J.size(); ++s) {
      const double w = internal::sample_weight(samples[c], s);
      W += w * J[s], total += w;
    }
    W /= std::max(total, 1e-300);
    const double scale = std::max(W.norm() / std::sqrt(3.), 1e-300);
    if(!(W.determinant() > 1e-3 * scale * scale * scale)) W = scale * Eigen::Matrix3d::Identity();
    Winv[c] = W.inverse();
  }

  x.resize(Eigen::Index(3 * start.size()));
  for(std::size_t k = 0; k < start.size(); ++k) x.segment<3>(Eigen::Index(3 * k)) = start[k];
  std::vector<std::vector<Vector3d>> points(np);
  for(std::size_t c : r.patches) points[c] = mv.patch(c).control_points();
  auto position = [&](const Eigen::VectorXd& y, long u) -> Vector3d {
    const Vector3d p = y.segment<3>(Eigen::Index(3 * u));
    const Vector3d& n = slide[std::size_t(u)];
    return n.isZero() ? p : Vector3d(p - n * n.dot(p - start[std::size_t(u)]));
  };
  auto load = [&](const Eigen::VectorXd& y) {
    for(std::size_t c : r.patches)
      for(std::size_t k = 0; k < points[c].size(); ++k) {
        const long u = unknown[offset[c] + k];
        if(u >= 0) points[c][k] = position(y, u);
      }
  };
  // Samples whose det J the free points cannot change (set by the fixed boundary alone) are
  // left out of the smallest det that drives epsilon and the stopping test: a folded
  // boundary edge would otherwise hold epsilon up for all the rounds in vain
  // (double-torus-3-holes.off: -13.0 for 60 rounds, 10 minutes).
  std::vector<std::vector<bool>> movable(np);
  auto update_movable = [&](std::size_t c) {
    movable[c] = internal::movable_samples(mv.patch(c).control_net_size(), samples[c],
                                           [&](std::size_t k) { return unknown[offset[c] + k] >= 0; });
  };
  for(std::size_t c : r.patches) update_movable(c);
  double min_det = 0.;
  // One pass over the samples' Jacobians: the smallest det(J W^-1) over all samples and over
  // the movable ones, and (if asked) the patches with a non-positive det at a sample no free
  // point moves: no round can certify those, so they get no denser samples either. det W > 0,
  // so det(J W^-1) and det J share their sign.
  struct Smallest
  {
    double all, movable;
  };
  struct Scratch
  {
    std::vector<Eigen::Matrix3d> J, G;
  };
  std::vector<Scratch> scratch(threads);
  auto measure = [&](const Eigen::VectorXd& y, std::vector<std::size_t>* pinned = nullptr) {
    load(y);
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<Smallest> per_patch(r.patches.size(), Smallest{inf, inf});
    std::vector<char> pin(r.patches.size(), 0);
    internal::parallel_for(r.patches.size(), threads, [&](std::size_t t, unsigned worker) {
      const std::size_t c = r.patches[t];
      std::vector<Eigen::Matrix3d>& J = scratch[worker].J;
      internal::patch_jacobians(mv.patch(c).control_net_size(), samples[c], points[c], J);
      Smallest& m = per_patch[t];
      for(std::size_t s = 0; s < J.size(); ++s) {
        const double D = (J[s] * Winv[c]).determinant();
        m.all = std::min(m.all, D);
        if(movable[c][s]) m.movable = std::min(m.movable, D);
        else pin[t] = pin[t] || !(D > 0.);
      }
    });
    Smallest m{inf, inf};
    for(std::size_t t = 0; t < r.patches.size(); ++t) {
      m.all = std::min(m.all, per_patch[t].all), m.movable = std::min(m.movable, per_patch[t].movable);
      if(pin[t] && pinned) pinned->push_back(r.patches[t]);
    }
    return m;
  };
  const double theta = o.volume_weight;
  double eps = 1.;
  // Per optimised patch: its terms of the energy, sample by sample, and its gradient.
  std::vector<std::vector<double>> terms(r.patches.size());
  std::vector<std::vector<Vector3d>> patch_gradient(r.patches.size());
  double evaluation_samples = 0.; // of the last energy evaluation
  auto energy = [&](const Eigen::VectorXd& y, Eigen::VectorXd& g) {
    load(y);
    evaluation_samples = 0.;
    internal::parallel_for(r.patches.size(), threads, [&](std::size_t t, unsigned worker) {
      const std::size_t c = r.patches[t];
      std::vector<Eigen::Matrix3d>&J = scratch[worker].J, &G = scratch[worker].G;
      const std::array<int, 3> n = mv.patch(c).control_net_size();
      const Eigen::Matrix3d& Wi = Winv[c];
      internal::patch_jacobians(n, samples[c], points[c], J);
      G.resize(J.size());
      terms[t].resize(J.size());
      for(std::size_t s = 0; s < J.size(); ++s) {
        const double w = internal::sample_weight(samples[c], s);
        const Eigen::Matrix3d K = J[s] * Wi;
        const double D = K.determinant(), root = std::sqrt(eps * eps + D * D), chi = internal::regularised_determinant(D, eps);
        const double dchi = chi / root, tr = K.squaredNorm(), c23 = std::cbrt(chi * chi);
        const double shape = tr / (3. * c23), volume = (D * D + 1.) / (2. * chi);
        terms[t][s] = w * ((1. - theta) * shape + theta * volume);
        const Eigen::Matrix3d C = internal::cofactor(K);
        const Eigen::Matrix3d GK = (1. - theta) * (2. / (3. * c23) * K - (2. / 9.) * tr / (c23 * chi) * dchi * C) +
                                   theta * (D / chi - (D * D + 1.) * dchi / (2. * chi * chi)) * C;
        G[s] = w * GK * Wi.transpose(); // dE/dJ, since K = J W^-1
      }
      internal::patch_jacobians_adjoint(n, samples[c], G, patch_gradient[t]);
    });
    // Summed in patch and sample order, term by term: the sums one thread forms.
    g.setZero(y.size());
    double E = 0.;
    for(std::size_t t = 0; t < r.patches.size(); ++t) {
      const std::size_t c = r.patches[t];
      for(double e : terms[t]) E += e;
      evaluation_samples += double(terms[t].size());
      for(std::size_t k = 0; k < patch_gradient[t].size(); ++k) {
        const long u = unknown[offset[c] + k];
        if(u >= 0) g.segment<3>(Eigen::Index(3 * u)) += patch_gradient[t][k];
      }
    }
    for(std::size_t u = 0; u < slide.size(); ++u)
      if(!slide[u].isZero()) {
        const Vector3d gu = g.segment<3>(Eigen::Index(3 * u));
        g.segment<3>(Eigen::Index(3 * u)) = gu - slide[u] * slide[u].dot(gu);
      }
    r.work += evaluation_samples;
    if(o.budget) o.budget->spent += evaluation_samples;
    return E;
  };

  // Garanzha et al.'s loop: L-BFGS at a fixed epsilon, then a smaller epsilon from the
  // energy's decrease and the smallest det, until every sample is positive and the energy
  // has settled. With the options' sigma floor of 0.5, epsilon shrinks by about a third a
  // round while an inverted sample resists (by 5% with Garanzha et al.'s 0.1): a model with
  // a few folded cores needs 5 to 20 rounds.
  internal::Lbfgs_options lo;
  lo.maximum_iterations = o.iterations_per_round;
  auto run_rounds = [&] {
    if(start.empty()) return;
    eps = min_det > 0. ? 1e-9 : std::max(1e-6, std::min(1., 2. * std::abs(min_det)));
    Eigen::VectorXd g;
    double E_prev = energy(x, g);
    std::vector<double> smallest; // min_det after each round
    const std::size_t window = std::size_t(std::max(1, o.stall_window));
    for(int round = 0; round < o.maximum_rounds; ++round) {
      if(o.budget && o.budget->exhausted()) {
        r.out_of_budget = true;
        break;
      }
      // The last round the budget allows: as many iterations as evaluations it has left.
      lo.maximum_iterations = o.iterations_per_round;
      if(o.budget && evaluation_samples > 0.)
        lo.maximum_iterations = int(std::max(1., std::min(double(lo.maximum_iterations), (o.budget->limit - o.budget->spent) / evaluation_samples)));
      const internal::Lbfgs_result lr = internal::lbfgs_minimize(energy, x, lo);
      ++r.rounds;
      r.iterations += lr.iterations;
      min_det = measure(x).movable;
      const double E = lr.value;
      const double sigma = std::max(1. - E / E_prev, o.minimum_decrease);
      const double chi_min = internal::regularised_determinant(min_det, eps);
      const double mu = (1. - sigma) * chi_min;
      const bool settled = std::abs(E_prev - E) <= 1e-5 * std::abs(E);
      eps = min_det < mu ? 2. * std::sqrt(mu * (mu - min_det)) : 1e-9;
      E_prev = energy(x, g); // with the new epsilon
      if(min_det > 0. && settled) break;
      smallest.push_back(min_det);
      if(min_det <= 0. && smallest.size() >= 2 * window) {
        const double before = *std::max_element(smallest.begin(), smallest.end() - std::ptrdiff_t(window));
        const double recent = *std::max_element(smallest.end() - std::ptrdiff_t(window), smallest.end());
        if(recent - before < o.stall_rise * std::abs(before)) {
          r.stalled = true;
          break;
        }
      }
    }
  };
  auto moved_patch = [&](std::size_t c) { // patch c with its current points (after load())
    const Tensor_bspline_volume& v = mv.patch(c);
    return Tensor_bspline_volume({{v.knot_vector(0), v.knot_vector(1), v.knot_vector(2)}}, points[c]);
  };
  // Per optimised patch: certified det J > 0 with the current points (a non-positive
  // sample on the first sample grid rules a certificate out, and the bound is costly there).
  auto certified_now = [&](std::size_t c) {
    const Tensor_bspline_volume w = moved_patch(c);
    return internal::sampled_scaled_jacobian(w, first_samples[c]) > 0. && certified_jacobian_bound(w).certified_positive;
  };
  auto uncertified_patches = [&] {
    load(x);
    std::vector<char> ok(r.patches.size(), 0);
    internal::parallel_for(r.patches.size(), threads, [&](std::size_t t, unsigned) { ok[t] = certified_now(r.patches[t]); });
    std::vector<std::size_t> u;
    for(std::size_t t = 0; t < r.patches.size(); ++t)
      if(!ok[t]) u.push_back(r.patches[t]);
    return u;
  };

  auto uncertified_before = [&] {
    for(std::size_t c : r.patches)
      if(!certified_before[c]) r.uncertified_patches.push_back(c);
  };
  const Smallest before_rounds = measure(x, &r.pinned_patches);
  r.min_relative_determinant_before = before_rounds.all;
  r.out_of_budget = o.budget && o.budget->exhausted();
  if((o.stop_when_pinned && !r.pinned_patches.empty()) || r.out_of_budget) {
    r.min_relative_determinant_after = before_rounds.all;
    r.reverted = true;
    uncertified_before();
    return r;
  }
  min_det = before_rounds.movable;
  run_rounds();
  // Samples are not a certificate: det J can dip below 0 between them (3holes.obj: one core
  // positive at every sample, negative between). Once every sample is positive, the patches
  // still not certified get one more Gauss-Lobatto point per span (up to
  // maximum_points_per_span, 5) and the rounds go on from there.
  std::vector<std::size_t> uncertified = uncertified_patches();
  auto not_pinned = [&](const std::vector<std::size_t>& patches) {
    std::vector<std::size_t> u;
    for(std::size_t c : patches)
      if(std::find(r.pinned_patches.begin(), r.pinned_patches.end(), c) == r.pinned_patches.end()) u.push_back(c);
    return u;
  };
  // Per patch and direction, the parameters it is sampled at from here on (empty: the
  // first samples; a patch first uncertified at focusing starts from the densest ones).
  std::vector<std::array<internal::Span_points, 3>> points_at(np);
  const int densest = std::min(std::max(o.points_per_span, o.maximum_points_per_span), 5);
  for(int q = o.points_per_span + 1; q <= densest && min_det > 0. && !r.out_of_budget; ++q) {
    const std::vector<std::size_t> denser = not_pinned(uncertified);
    if(denser.empty()) break;
    for(std::size_t c : denser) {
      for(std::size_t d = 0; d < 3; ++d) {
        const Knot_vector& kv = mv.patch(c).knot_vector(int(d));
        points_at[c][d] = internal::span_points_with_ends(kv, q);
        samples[c][d] = internal::direction_samples(kv, points_at[c][d].t, points_at[c][d].w);
      }
      update_movable(c);
    }
    min_det = measure(x).movable;
    run_rounds();
    uncertified = uncertified_patches();
  }
  // A fold can hide between even 5 points per span (cad_plate_6holes.off at degree 3: one
  // patch, every sample positive, det J -0.0076 between). The certificate names the point
  // near which its bound is lowest; one more sample there per direction lets the energy see
  // the fold.
  std::size_t fewest = uncertified.size();
  for(int round = 0, idle = 0; round < o.focused_sample_rounds && idle < 2 && min_det > 0. && !r.out_of_budget; ++round) {
    const std::vector<std::size_t> focus = not_pinned(uncertified);
    if(focus.empty()) break;
    load(x);
    std::vector<Jacobian_bound> bound(focus.size());
    internal::parallel_for(focus.size(), threads, [&](std::size_t t, unsigned) { bound[t] = certified_jacobian_bound(moved_patch(focus[t])); });
    std::size_t added = 0;
    for(std::size_t t = 0; t < focus.size(); ++t) {
      const std::size_t c = focus[t];
      for(std::size_t d = 0; d < 3; ++d) {
        const Knot_vector& kv = mv.patch(c).knot_vector(int(d));
        if(points_at[c][d].t.empty()) points_at[c][d] = internal::span_points_with_ends(kv, densest);
        if(!internal::add_focused_point(points_at[c][d], bound[t].lower_bound_at[d])) continue;
        samples[c][d] = internal::direction_samples(kv, points_at[c][d].t, points_at[c][d].w);
        ++added;
      }
      update_movable(c);
    }
    if(added == 0) break; // every lowest point is sampled already
    r.focused_samples += added;
    min_det = measure(x).movable;
    if(min_det < o.focused_sample_floor) break;
    run_rounds();
    uncertified = uncertified_patches();
    idle = uncertified.size() < fewest ? 0 : idle + 1;
    fewest = std::min(fewest, uncertified.size());
  }
  samples = first_samples; // the figures below compare like with like
  for(std::size_t c : r.patches) update_movable(c);
  const Smallest after_rounds = measure(x);
  r.min_relative_determinant_after = after_rounds.all;
  min_det = after_rounds.movable;
  // Kept if fewer patches are left uncertified; with as many, only if the smallest det J
  // the free points can move rose and no patch certified before lost its certificate.
  bool lost = false;
  for(std::size_t c : r.patches)
    lost = lost || (certified_before[c] && std::find(uncertified.begin(), uncertified.end(), c) != uncertified.end());
  const std::size_t before = std::size_t(std::count_if(r.patches.begin(), r.patches.end(), [&](std::size_t c) { return !certified_before[c]; }));
  const bool better = uncertified.size() < before || (uncertified.size() == before && min_det > before_rounds.movable && !lost);
  if(!better) { // no better: keep the construction
    for(std::size_t k = 0; k < start.size(); ++k) x.segment<3>(Eigen::Index(3 * k)) = start[k];
    r.min_relative_determinant_after = r.min_relative_determinant_before;
    r.reverted = true;
    uncertified_before();
  } else
    r.uncertified_patches = uncertified;
  r.positive_at_samples = r.min_relative_determinant_after > 0.;
  load(x);
  for(std::size_t c : r.patches) mv.patch(c).control_points() = points[c];
  return r;
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_VOLUME_UNTANGLING_H
