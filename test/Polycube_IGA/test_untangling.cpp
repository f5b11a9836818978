// Volume_untangling.h: folded volumes are repaired by moving free control points only;
// boundary sides stay bit-identical, shared interface points move together, valid models
// are left alone.

#include <CGAL/Polycube_IGA/Multipatch_volume.h>
#include <CGAL/Polycube_IGA/Quality.h>
#include <CGAL/Polycube_IGA/Volume_untangling.h>
#include <CGAL/Polycube_IGA/internal/lbfgs.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

namespace PI = CGAL::Polycube_IGA;

namespace {

// Identity map of the box [x0, x0 + 1] x [0, 1]^2: degree 3, 2 spans by default, control
// points at the Greville abscissae (5 x 5 x 5).
PI::Tensor_bspline_volume box(double x0, int spans = 2)
{
  const PI::Knot_vector kv = PI::Knot_vector::uniform(3, spans);
  const int n = kv.number_of_basis_functions();
  std::vector<Eigen::Vector3d> P;
  for(int k = 0; k < n; ++k)
    for(int j = 0; j < n; ++j)
      for(int i = 0; i < n; ++i) P.push_back(Eigen::Vector3d(x0 + kv.greville(i), kv.greville(j), kv.greville(k)));
  return PI::Tensor_bspline_volume({{kv, kv, kv}}, std::move(P));
}

// Pushes the control points (i, j, k), j and k in 1..3 (or k = 4 only with `on_w1`), along
// x: past their neighbours, the map folds.
void fold(PI::Tensor_bspline_volume& v, int i, double dx, bool on_w1 = false)
{
  for(int k = on_w1 ? 4 : 1; k <= (on_w1 ? 4 : 3); ++k)
    for(int j = 1; j <= 3; ++j) v.control_point({{i, j, k}}).x() += dx;
}

void add_all_boundaries(PI::Multipatch_volume& mv, std::size_t p, const std::vector<int>& except = {})
{
  for(int s = 1; s <= 6; ++s)
    if(std::find(except.begin(), except.end(), s) == except.end()) mv.add_boundary({p, s});
}

// The box with its points (1, j, 4) pushed along x within side w1 (z = 1): the side folds.
PI::Tensor_bspline_volume box_folded_on_w1()
{
  PI::Tensor_bspline_volume v = box(0.);
  fold(v, 1, 0.9, true);
  return v;
}

// One patch, all six sides boundaries.
PI::Multipatch_volume closed(const PI::Tensor_bspline_volume& v)
{
  PI::Multipatch_volume mv;
  mv.add_patch(v);
  add_all_boundaries(mv, 0);
  return mv;
}

bool boundary_points_equal(const PI::Tensor_bspline_volume& a, const PI::Tensor_bspline_volume& b, int side)
{
  bool same = true;
  PI::internal::for_each_side_point(a, side, [&](const std::array<int, 3>& i) {
    same = same && a.control_point(i) == b.control_point(i);
  });
  return same;
}

} // namespace

TEST_CASE("L-BFGS minimises the Rosenbrock function", "[untangling]")
{
  auto rosenbrock = [](const Eigen::VectorXd& x, Eigen::VectorXd& g) {
    g.resize(2);
    g[0] = -2. * (1. - x[0]) - 400. * x[0] * (x[1] - x[0] * x[0]);
    g[1] = 200. * (x[1] - x[0] * x[0]);
    return (1. - x[0]) * (1. - x[0]) + 100. * (x[1] - x[0] * x[0]) * (x[1] - x[0] * x[0]);
  };
  Eigen::VectorXd x(2);
  x << -1.2, 1.;
  PI::internal::Lbfgs_options o;
  o.maximum_iterations = 500;
  o.relative_decrease = 0.;
  const auto r = PI::internal::lbfgs_minimize(rosenbrock, x, o);
  CHECK(r.value < 1e-10);
  CHECK(std::abs(x[0] - 1.) < 1e-5);
  CHECK(std::abs(x[1] - 1.) < 1e-5);
}

TEST_CASE("untangling repairs a folded box and keeps its boundary exactly", "[untangling]")
{
  PI::Multipatch_volume mv;
  PI::Tensor_bspline_volume v = box(0.);
  fold(v, 1, 0.9); // x = 1/6 + 0.9: beyond the next two planes
  mv.add_patch(v);
  add_all_boundaries(mv, 0);
  REQUIRE(PI::sample_jacobian(mv.patch(0)).min_determinant < 0.);
  REQUIRE_FALSE(PI::certified_jacobian_bound(mv.patch(0)).certified_positive);

  const PI::Volume_untangling_result r = PI::untangle_volume(mv);
  REQUIRE(r.patches == std::vector<std::size_t>{0});
  CHECK(r.free_points == 27); // the 3 x 3 x 3 inner points
  CHECK_FALSE(r.reverted);
  CHECK(r.min_relative_determinant_before < 0.);
  CHECK(r.positive_at_samples);
  CHECK(r.min_relative_determinant_after > 0.);
  const PI::Jacobian_bound b = PI::certified_jacobian_bound(mv.patch(0));
  CHECK(b.certified_positive);
  CHECK(PI::sample_jacobian(mv.patch(0)).min_scaled_jacobian > 0.1);
  for(int s = 1; s <= 6; ++s) CHECK(boundary_points_equal(mv.patch(0), v, s));

  SECTION("deterministic")
  {
    PI::Multipatch_volume again;
    again.add_patch(v);
    add_all_boundaries(again, 0);
    PI::untangle_volume(again);
    CHECK(again.patch(0).control_points() == mv.patch(0).control_points());
  }
}

TEST_CASE("a larger floor of the energy decrease shrinks epsilon faster and untangles in fewer rounds", "[untangling]")
{
  // A fold on the free side w = 1 of a 4-span box: the pushed points pass the next planes.
  // Garanzha et al.'s floor of 0.1 shrinks epsilon by about 5% a round while the fold
  // resists; the default 0.5 by about a third (6 rounds against 3). Both must certify the
  // box; the default in fewer rounds.
  PI::Tensor_bspline_volume v = box(0., 4);
  fold(v, 1, 1.4, true);
  auto untangled = [&](double floor, PI::Volume_untangling_result& r) {
    PI::Multipatch_volume mv;
    mv.add_patch(v);
    add_all_boundaries(mv, 0, {6});
    PI::Volume_untangling_options o;
    o.minimum_decrease = floor;
    r = PI::untangle_volume(mv, o);
    return mv;
  };
  PI::Volume_untangling_result slow, fast;
  const PI::Multipatch_volume a = untangled(0.1, slow), b = untangled(PI::Volume_untangling_options().minimum_decrease, fast);
  REQUIRE(slow.min_relative_determinant_before < 0.);
  INFO("rounds " << slow.rounds << " (0.1) against " << fast.rounds << " (default)");
  CHECK(PI::certified_jacobian_bound(a.patch(0)).certified_positive);
  CHECK(PI::certified_jacobian_bound(b.patch(0)).certified_positive);
  CHECK(fast.rounds < slow.rounds);
  for(int s = 1; s <= 5; ++s) CHECK(boundary_points_equal(b.patch(0), v, s));
}

TEST_CASE("untangling moves a shared interface point on both sides and keeps the interface conforming", "[untangling]")
{
  // Two boxes glued along x = 1 (side u1 of patch 0, side u0 of patch 1); the fold sits next
  // to the interface so that its inner points must move.
  PI::Multipatch_volume mv;
  PI::Tensor_bspline_volume a = box(0.), b = box(1.);
  fold(a, 3, -0.9);
  mv.add_patch(a);
  mv.add_patch(b);
  PI::Patch_interface f;
  f.first = {0, 2};
  f.second = {1, 1};
  // direction map and orientation: the identity (u1 meets u0: different ends, same senses)
  mv.add_interface(f);
  add_all_boundaries(mv, 0, {2});
  add_all_boundaries(mv, 1, {1});
  REQUIRE(PI::sample_jacobian(mv.patch(0)).min_determinant < 0.);

  const PI::Volume_untangling_result r = PI::untangle_volume(mv);
  CHECK(r.patches == std::vector<std::size_t>{0, 1}); // the folded patch and its neighbour
  CHECK(r.free_points == 2 * 27 + 9);                 // inner points of both, plus the 3 x 3 shared ones
  CHECK_FALSE(r.reverted); // the neighbour, certified before, still is
  CHECK(r.positive_at_samples);
  for(std::size_t p = 0; p < 2; ++p) CHECK(PI::certified_jacobian_bound(mv.patch(p)).certified_positive);
  // Shared points identical (bitwise) on both sides, and some of them moved.
  bool moved = false;
  for(int k = 0; k < 5; ++k)
    for(int j = 0; j < 5; ++j) {
      CHECK(mv.patch(0).control_point({{4, j, k}}) == mv.patch(1).control_point({{0, j, k}}));
      moved = moved || mv.patch(0).control_point({{4, j, k}}) != a.control_point({{4, j, k}});
    }
  CHECK(moved);
  CHECK(PI::check_interface_conformity(mv).max_gap < 1e-12);
  for(int s : {1, 3, 4, 5, 6}) CHECK(boundary_points_equal(mv.patch(0), a, s));
  for(int s : {2, 3, 4, 5, 6}) CHECK(boundary_points_equal(mv.patch(1), b, s));
}

TEST_CASE("untangling gives the same points bit for bit on any number of threads", "[untangling]")
{
  // Four boxes in a row glued along x, two of them folded: shared interface points collect
  // gradient terms from two patches, which threads compute apart and the energy sums in
  // patch order.
  PI::Multipatch_volume mv;
  for(int p = 0; p < 4; ++p) {
    PI::Tensor_bspline_volume v = box(double(p));
    if(p == 1 || p == 2) fold(v, p == 1 ? 3 : 1, p == 1 ? -0.9 : 0.9);
    mv.add_patch(v);
  }
  for(std::size_t p = 0; p + 1 < 4; ++p) {
    PI::Patch_interface f;
    f.first = {p, 2};
    f.second = {p + 1, 1};
    mv.add_interface(f);
  }
  for(std::size_t p = 0; p < 4; ++p) {
    std::vector<int> glued;
    if(p > 0) glued.push_back(1);
    if(p < 3) glued.push_back(2);
    add_all_boundaries(mv, p, glued);
  }
  std::vector<PI::Multipatch_volume> out;
  std::vector<PI::Volume_untangling_result> result;
  for(unsigned threads : {1u, 2u, 3u}) {
    PI::Multipatch_volume copy = mv;
    PI::Volume_untangling_options o;
    o.threads = threads;
    result.push_back(PI::untangle_volume(copy, o));
    out.push_back(copy);
  }
  REQUIRE(result[0].positive_at_samples);
  CHECK(result[0].patches.size() == 4);
  for(std::size_t t = 1; t < out.size(); ++t) {
    INFO(t + 1 << " threads");
    CHECK(result[t].rounds == result[0].rounds);
    CHECK(result[t].iterations == result[0].iterations);
    CHECK(result[t].min_relative_determinant_after == result[0].min_relative_determinant_after);
    for(std::size_t p = 0; p < 4; ++p) CHECK(out[t].patch(p).control_points() == out[0].patch(p).control_points());
  }
  // The quality evaluation, per patch on every core, certifies the result.
  const PI::Multipatch_quality q = PI::evaluate_quality(out[0]);
  CHECK(q.overall_certified.certified_positive);
}

TEST_CASE("quality measured again only where patches changed equals a fresh evaluation", "[untangling][quality]")
{
  // Three separate boxes; the middle one is then folded. evaluate_quality() told that only it
  // changed copies the others' figures and must agree with measuring everything again.
  PI::Multipatch_volume mv;
  for(int p = 0; p < 3; ++p) mv.add_patch(box(2. * p));
  const PI::Multipatch_quality before = PI::evaluate_quality(mv);
  REQUIRE(before.overall_certified.certified_positive);
  fold(mv.patch(1), 1, 0.9);
  const PI::Multipatch_quality fresh = PI::evaluate_quality(mv);
  const PI::Multipatch_quality reused = PI::evaluate_quality(mv, 5, PI::Jacobian_bound_options(), &before, {false, true, false});
  CHECK_FALSE(fresh.certified[1].certified_positive);
  for(std::size_t p = 0; p < 3; ++p) {
    CHECK(reused.certified[p].lower_bound == fresh.certified[p].lower_bound);
    CHECK(reused.certified[p].certified_positive == fresh.certified[p].certified_positive);
    CHECK(reused.sampled[p].min_determinant == fresh.sampled[p].min_determinant);
    CHECK(reused.sampled[p].mean_scaled_jacobian == fresh.sampled[p].mean_scaled_jacobian);
  }
  CHECK(reused.overall_certified.lower_bound == fresh.overall_certified.lower_bound);
  CHECK(reused.overall_sampled.min_scaled_jacobian == fresh.overall_sampled.min_scaled_jacobian);
  // Known figures with a wrong patch count are ignored, not misread.
  PI::Multipatch_quality short_known = before;
  short_known.certified.pop_back();
  CHECK(PI::evaluate_quality(mv, 5, PI::Jacobian_bound_options(), &short_known, {false, false, false}).certified[1].lower_bound ==
        fresh.certified[1].lower_bound);
}

TEST_CASE("untangling leaves a valid model untouched", "[untangling]")
{
  PI::Multipatch_volume mv;
  PI::Tensor_bspline_volume v = box(0.);
  fold(v, 2, 0.05); // a mild, valid distortion
  mv.add_patch(v);
  add_all_boundaries(mv, 0);
  const PI::Volume_untangling_result r = PI::untangle_volume(mv);
  CHECK(r.patches.empty());
  CHECK(r.free_points == 0);
  CHECK(r.positive_at_samples);
  CHECK(mv.patch(0).control_points() == v.control_points());
}

TEST_CASE("untangling cannot move a fixed boundary and says so", "[untangling]")
{
  // The fold is on side w1 (a boundary): nothing may move there, so det J stays negative.
  const PI::Tensor_bspline_volume v = box_folded_on_w1();
  PI::Multipatch_volume mv = closed(v);
  const PI::Volume_untangling_result r = PI::untangle_volume(mv);
  // The samples may end positive (3 to 5 per span miss the fold's narrow negative part), but no
  // certificate: the folded side's parameterization keeps det J <= 0 somewhere.
  CHECK_FALSE(PI::certified_jacobian_bound(mv.patch(0)).certified_positive);
  CHECK(r.min_relative_determinant_after >= r.min_relative_determinant_before);
  for(int s = 1; s <= 6; ++s) CHECK(boundary_points_equal(mv.patch(0), v, s));
}

TEST_CASE("untangling slides the points of a sliding side in its plane and repairs a fold there", "[untangling]")
{
  // The fold of the test above, on side w1, with w1 a sliding side (as a cap spanning a
  // boundary loop is): its inner points move in the plane z = 1, its edge points stay.
  const PI::Tensor_bspline_volume v = box_folded_on_w1();
  PI::Multipatch_volume mv = closed(v);
  const PI::Volume_untangling_result r = PI::untangle_volume(mv, PI::Volume_untangling_options(), nullptr, {{0, 6}});
  CHECK(r.free_points == 27 + 9);
  CHECK(r.sliding_points == 9); // the 3 x 3 inner points of w1
  CHECK_FALSE(r.reverted);
  CHECK(r.uncertified_patches.empty());
  CHECK(PI::certified_jacobian_bound(mv.patch(0)).certified_positive);
  bool in_plane = true, edge_kept = true, moved = false;
  PI::internal::for_each_side_point(mv.patch(0), 6, [&](const std::array<int, 3>& i) {
    const Eigen::Vector3d &now = mv.patch(0).control_point(i), &was = v.control_point(i);
    in_plane = in_plane && now.z() == 1.;
    const bool edge = i[0] == 0 || i[0] == 4 || i[1] == 0 || i[1] == 4;
    if(edge) edge_kept = edge_kept && now == was;
    else moved = moved || now != was;
  });
  CHECK(in_plane);
  CHECK(edge_kept);
  CHECK(moved);
  for(int s = 1; s <= 5; ++s) CHECK(boundary_points_equal(mv.patch(0), v, s));
}

TEST_CASE("a point of a sliding side where its control net is degenerate stays fixed", "[untangling]")
{
  // Side w1's points (1, 2, 4) and (3, 2, 4) made to coincide: the net's difference along u
  // at (2, 2, 4) is zero, so that point has no normal to slide in, and would move freely.
  PI::Tensor_bspline_volume v = box_folded_on_w1();
  v.control_point({{3, 2, 4}}) = v.control_point({{1, 2, 4}});
  PI::Multipatch_volume mv = closed(v);
  const PI::Volume_untangling_result r = PI::untangle_volume(mv, PI::Volume_untangling_options(), nullptr, {{0, 6}});
  CHECK_FALSE(r.skipped);
  CHECK(r.free_points == 27 + 8);
  CHECK(r.sliding_points == 8);
  CHECK(mv.patch(0).control_point({{2, 2, 4}}) == v.control_point({{2, 2, 4}}));
  bool in_plane = true;
  PI::internal::for_each_side_point(mv.patch(0), 6, [&](const std::array<int, 3>& i) { in_plane = in_plane && mv.patch(0).control_point(i).z() == 1.; });
  CHECK(in_plane);
}

TEST_CASE("untangling spends no rounds on a fold that only fixed points determine", "[untangling]")
{
  // Edge point (1, 0, 0) pushed past its neighbour along x: det J < 0 on the edge where sides
  // v0 and w0 (both boundaries) meet, and all three columns of J there come from those two
  // sides. No free point moves those samples, so they must not hold the rounds up.
  PI::Multipatch_volume mv;
  PI::Tensor_bspline_volume v = box(0.);
  v.control_point({{1, 0, 0}}).x() += 0.8;
  REQUIRE(PI::certified_jacobian_bound(v).smallest_value_found < 0.);
  mv.add_patch(v);
  add_all_boundaries(mv, 0);
  const PI::Volume_untangling_options o;
  const PI::Volume_untangling_result r = PI::untangle_volume(mv, o);
  CHECK(r.patches == std::vector<std::size_t>{0});
  CHECK(r.pinned_patches == std::vector<std::size_t>{0});
  CHECK(r.rounds <= 2);
  CHECK(r.min_relative_determinant_before < 0.);
  CHECK(r.min_relative_determinant_after == r.min_relative_determinant_before);
  CHECK_FALSE(r.positive_at_samples);
  CHECK_FALSE(PI::certified_jacobian_bound(mv.patch(0)).certified_positive);
  for(int s = 1; s <= 6; ++s) CHECK(boundary_points_equal(mv.patch(0), v, s));
}

TEST_CASE("untangling asked to stop when a patch is pinned moves nothing, even where it could repair", "[untangling]")
{
  // Patch 0 is pinned (its fold is on an edge of two boundary sides, as above); patch 1 has
  // an inner fold that untangling repairs. A caller that keeps the volume only if every patch
  // ends certified (build's finer grids) loses nothing by stopping at the pinned one.
  PI::Multipatch_volume mv;
  PI::Tensor_bspline_volume pinned = box(0.), folded = box(2.);
  pinned.control_point({{1, 0, 0}}).x() += 0.8;
  fold(folded, 1, 0.9);
  mv.add_patch(pinned);
  mv.add_patch(folded);
  add_all_boundaries(mv, 0);
  add_all_boundaries(mv, 1);
  PI::Multipatch_volume repaired = mv;
  const PI::Volume_untangling_result go_on = PI::untangle_volume(repaired);
  CHECK(go_on.pinned_patches == std::vector<std::size_t>{0});
  CHECK(go_on.rounds > 0);
  CHECK(PI::certified_jacobian_bound(repaired.patch(1)).certified_positive);
  PI::Volume_untangling_options o;
  o.stop_when_pinned = true;
  const PI::Volume_untangling_result r = PI::untangle_volume(mv, o);
  CHECK(r.patches == std::vector<std::size_t>{0, 1});
  CHECK(r.pinned_patches == std::vector<std::size_t>{0});
  CHECK(r.rounds == 0);
  CHECK(r.reverted);
  CHECK_FALSE(r.positive_at_samples);
  CHECK(r.min_relative_determinant_after == r.min_relative_determinant_before);
  CHECK(mv.patch(0).control_points() == pinned.control_points());
  CHECK(mv.patch(1).control_points() == folded.control_points());
}

TEST_CASE("a shared untangling budget stops the rounds, counts the samples visited and then moves nothing", "[untangling]")
{
  // The folded box of the first case, untangled with no limit, gives the work a full run
  // takes; a budget of a tenth of it stops the rounds early (the last one overruns it by at
  // most a round's evaluations), and a second call finds it spent and moves nothing.
  PI::Tensor_bspline_volume v = box(0.);
  fold(v, 1, 0.9);
  PI::Multipatch_volume full = closed(v);
  const PI::Volume_untangling_result unlimited = PI::untangle_volume(full);
  REQUIRE(unlimited.positive_at_samples);
  REQUIRE(unlimited.rounds > 1);
  REQUIRE(unlimited.work > 0.);
  CHECK_FALSE(unlimited.out_of_budget);
  // Every energy evaluation visits every sample of the patch, at least 5^3 (3 Gauss-Lobatto
  // points per span and direction, 2 spans, ends shared), at least once a round.
  CHECK(unlimited.work >= 125. * unlimited.rounds);

  PI::Untangling_budget budget;
  budget.limit = unlimited.work / 10.;
  PI::Volume_untangling_options o;
  o.budget = &budget;
  PI::Multipatch_volume cut_short = closed(v);
  const PI::Volume_untangling_result first = PI::untangle_volume(cut_short, o);
  CHECK(first.out_of_budget);
  CHECK(budget.exhausted());
  CHECK(first.work == budget.spent);
  CHECK(first.rounds < unlimited.rounds);
  CHECK(budget.spent < unlimited.work);
  for(int s = 1; s <= 6; ++s) CHECK(boundary_points_equal(cut_short.patch(0), v, s));

  const PI::Multipatch_volume before = cut_short;
  const PI::Volume_untangling_result second = PI::untangle_volume(cut_short, o);
  CHECK(second.out_of_budget);
  CHECK(second.rounds == 0);
  CHECK(second.reverted);
  CHECK(second.work == 0.);
  CHECK(second.min_relative_determinant_after == second.min_relative_determinant_before);
  CHECK(cut_short.patch(0).control_points() == before.patch(0).control_points());

  SECTION("the same budget stops at the same point")
  {
    PI::Untangling_budget again;
    again.limit = budget.limit;
    o.budget = &again;
    PI::Multipatch_volume twin = closed(v);
    PI::untangle_volume(twin, o);
    CHECK(again.spent == budget.spent);
    CHECK(twin.patch(0).control_points() == before.patch(0).control_points());
  }
}

TEST_CASE("untangling takes a patch positive at every sample but folded between them", "[untangling]")
{
  // One span: the inner point (1, 1, 1) pushed 1.8 along -x folds the map near that corner,
  // between the samples: the scaled Jacobian is well above the threshold at the 3 default
  // Gauss-Lobatto points per span (and at 5), yet det J < 0 somewhere. The certificate, not
  // the samples, must bring the patch in.
  PI::Multipatch_volume mv;
  PI::Tensor_bspline_volume v = box(0., 1);
  v.control_point({{1, 1, 1}}).x() -= 1.8;
  std::array<PI::internal::Direction_samples, 3> S;
  for(int d = 0; d < 3; ++d) S[std::size_t(d)] = PI::internal::span_samples_with_ends(v.knot_vector(d), 3);
  const PI::Volume_untangling_options o;
  REQUIRE(o.points_per_span == 3);
  REQUIRE(PI::internal::sampled_scaled_jacobian(v, S) > o.scaled_jacobian_threshold);
  REQUIRE(PI::sample_jacobian(v, 5).min_scaled_jacobian > 0.5);
  const PI::Jacobian_bound folded = PI::certified_jacobian_bound(v);
  REQUIRE(folded.has_nonpositive_value);
  REQUIRE(folded.smallest_value_found < 0.);
  mv.add_patch(v);
  add_all_boundaries(mv, 0);
  const PI::Volume_untangling_result r = PI::untangle_volume(mv, o);
  CHECK(r.patches == std::vector<std::size_t>{0});
  CHECK_FALSE(r.reverted);
  CHECK(r.positive_at_samples);
  CHECK(PI::certified_jacobian_bound(mv.patch(0)).certified_positive);
  for(int s = 1; s <= 6; ++s) CHECK(boundary_points_equal(mv.patch(0), v, s));
}

TEST_CASE("a fold no sample sees is found by samples where the certificate's bound is lowest", "[untangling]")
{
  // The folded box of the test above, sampled at its span ends only (2 points per span, no
  // denser): its 8 samples are the corners, whose det J the fixed boundary alone sets, so the
  // energy cannot see the fold. The certificate names where its bound is lowest; one sample
  // there per direction brings the fold into the energy.
  PI::Tensor_bspline_volume v = box(0., 1);
  v.control_point({{1, 1, 1}}).x() -= 1.8;
  const PI::Jacobian_bound folded = PI::certified_jacobian_bound(v);
  REQUIRE(folded.has_nonpositive_value);
  PI::Volume_untangling_options o;
  o.points_per_span = o.maximum_points_per_span = 2;
  SECTION("without focused samples the fold stays")
  {
    o.focused_sample_rounds = 0;
    PI::Multipatch_volume mv = closed(v);
    const PI::Volume_untangling_result r = PI::untangle_volume(mv, o);
    CHECK(r.focused_samples == 0);
    CHECK(r.uncertified_patches == std::vector<std::size_t>{0});
    CHECK_FALSE(PI::certified_jacobian_bound(mv.patch(0)).certified_positive);
  }
  SECTION("a focused sample below the floor stops the focusing before its rounds")
  {
    o.focused_sample_floor = 0.; // the fold's sample is negative
    PI::Multipatch_volume mv = closed(v);
    const PI::Volume_untangling_result r = PI::untangle_volume(mv, o);
    CHECK(r.focused_samples > 0);
    CHECK(r.uncertified_patches == std::vector<std::size_t>{0});
  }
  SECTION("with them the patch is certified and its boundary unmoved")
  {
    REQUIRE(o.focused_sample_rounds > 0);
    PI::Multipatch_volume mv = closed(v);
    const PI::Volume_untangling_result r = PI::untangle_volume(mv, o);
    CHECK(r.focused_samples > 0);
    CHECK(r.focused_samples <= std::size_t(3 * o.focused_sample_rounds));
    CHECK_FALSE(r.reverted);
    CHECK(r.uncertified_patches.empty());
    CHECK(PI::certified_jacobian_bound(mv.patch(0)).certified_positive);
    for(int s = 1; s <= 6; ++s) CHECK(boundary_points_equal(mv.patch(0), v, s));
  }
}

TEST_CASE("a focused sample is added in order, lighter than every Gauss-Lobatto weight, and only once", "[untangling]")
{
  const PI::Knot_vector kv = PI::Knot_vector::uniform(3, 2);
  PI::internal::Span_points p = PI::internal::span_points_with_ends(kv, 3); // 0, 1/4, 1/2, 3/4, 1
  REQUIRE(p.t.size() == 5);
  const double lightest = *std::min_element(p.w.begin(), p.w.end());
  const double total = std::accumulate(p.w.begin(), p.w.end(), 0.);
  CHECK(total == Approx(1.));
  CHECK(PI::internal::add_focused_point(p, 0.3));
  REQUIRE(p.t.size() == 6);
  CHECK(std::is_sorted(p.t.begin(), p.t.end()));
  CHECK(p.t[2] == 0.3);
  CHECK(p.w[2] == 0.25 * lightest);
  CHECK_FALSE(PI::internal::add_focused_point(p, 0.3 + 1e-12)); // already sampled
  CHECK_FALSE(PI::internal::add_focused_point(p, 0.5 - 1e-12));
  CHECK_FALSE(PI::internal::add_focused_point(p, 1.));
  CHECK(p.t.size() == 6);
  CHECK_FALSE(PI::internal::add_focused_point(p, 0.));
}

TEST_CASE("untangling skips models with more patches or control points to optimise than allowed", "[untangling]")
{
  PI::Multipatch_volume mv;
  PI::Tensor_bspline_volume v = box(0.);
  fold(v, 1, 0.9);
  mv.add_patch(v);
  mv.add_patch(v);
  add_all_boundaries(mv, 0);
  add_all_boundaries(mv, 1);
  PI::Volume_untangling_options by_patches, by_points;
  by_patches.maximum_patches = 1;
  by_points.maximum_control_points = 2 * v.number_of_control_points() - 1; // one point short
  for(const auto& o : {by_patches, by_points}) {
    PI::Multipatch_volume m = mv;
    const PI::Volume_untangling_result r = PI::untangle_volume(m, o);
    CHECK(r.skipped);
    CHECK(r.patches == std::vector<std::size_t>{0, 1});
    CHECK_FALSE(r.positive_at_samples);
    for(std::size_t p = 0; p < 2; ++p) CHECK(m.patch(p).control_points() == v.control_points());
  }
  // With room for both patches' points, it runs.
  PI::Volume_untangling_options enough;
  enough.maximum_control_points = 2 * v.number_of_control_points();
  CHECK_FALSE(PI::untangle_volume(mv, enough).skipped);
}

TEST_CASE("Gauss-Lobatto samples of 2 to 5 points per span integrate polynomials exactly and include span ends", "[untangling]")
{
  // q points with both ends integrate degree 2q - 3 exactly; the untangler goes to denser
  // samples (up to 5) for patches that stay uncertified.
  const PI::Knot_vector kv = PI::Knot_vector::uniform(3, 3); // spans [0, 1/3], [1/3, 2/3], [2/3, 1]
  for(int q = 2; q <= 5; ++q) {
    INFO(q);
    const PI::internal::Direction_samples s = PI::internal::span_samples_with_ends(kv, q);
    REQUIRE(s.weight.size() == std::size_t(3 * (q - 1) + 1)); // span ends shared
    std::vector<double> t;
    for(std::size_t i = 0; i < s.first.size(); ++i) {
      // Recover the parameter from the basis: the partition of unity of the linear
      // combination of Greville abscissae is the parameter itself.
      double x = 0.;
      for(int j = 0; j <= s.p; ++j) x += s.value[i * std::size_t(s.p + 1) + std::size_t(j)] * kv.greville(s.first[i] + j);
      t.push_back(x);
    }
    CHECK(t.front() == Approx(0.).margin(1e-14));
    CHECK(t.back() == Approx(1.));
    CHECK(std::find_if(t.begin(), t.end(), [](double x) { return std::abs(x - 1. / 3.) < 1e-12; }) != t.end());
    for(int k = 0; k <= 2 * q - 3; ++k) {
      double integral = 0.;
      for(std::size_t i = 0; i < t.size(); ++i) integral += s.weight[i] * std::pow(t[i], k);
      CHECK(integral == Approx(1. / double(k + 1)).epsilon(1e-12));
    }
  }
}

TEST_CASE("the regularised determinant stays positive and accurate for inverted samples", "[untangling]")
{
  // chi(D, e) = (D + sqrt(e^2 + D^2)) / 2 ~ e^2 / (4 |D|) for D << 0: the naive sum cancels to 0.
  const double e = 1e-3, D = -1e6;
  const double chi = PI::internal::regularised_determinant(D, e);
  CHECK(chi > 0.);
  CHECK(chi == Approx(e * e / (4. * -D)).epsilon(1e-9));
  CHECK(PI::internal::regularised_determinant(2., 0.) == 2.);
  CHECK(PI::internal::regularised_determinant(0., e) == Approx(e / 2.));
  CHECK(PI::internal::regularised_determinant(-3., 4.) == Approx((-3. + 5.) / 2.));
}

TEST_CASE("sum-factorised Jacobians match the spline's derivatives and their adjoint is exact", "[untangling]")
{
  PI::Tensor_bspline_volume v = box(0.);
  fold(v, 1, 0.4);
  fold(v, 3, -0.2);
  v.control_point({{2, 1, 3}}).z() += 0.3;
  std::array<PI::internal::Direction_samples, 3> S;
  for(int d = 0; d < 3; ++d) S[std::size_t(d)] = PI::internal::span_samples_with_ends(v.knot_vector(d), 3);
  const std::array<int, 3> n = v.control_net_size();
  std::vector<Eigen::Matrix3d> J;
  PI::internal::patch_jacobians(n, S, v.control_points(), J);
  const std::size_t q = S[0].weight.size();
  REQUIRE(J.size() == q * q * q);
  // Samples at span ends and middles: 0, 1/4, 1/2, 3/4, 1 for 2 spans.
  const std::vector<double> t{0., 0.25, 0.5, 0.75, 1.};
  REQUIRE(q == t.size());
  double worst = 0.;
  for(std::size_t c = 0; c < q; ++c)
    for(std::size_t b = 0; b < q; ++b)
      for(std::size_t a = 0; a < q; ++a) {
        const auto d = v.derivatives({{t[a], t[b], t[c]}}, 1);
        for(int k = 0; k < 3; ++k) worst = std::max(worst, (J[a + q * (b + q * c)].col(k) - d.first[std::size_t(k)]).norm());
      }
  CHECK(worst < 1e-12);
  // J is linear in P, so sum_s G_s : J_s = sum_i dP_i . P_i for any G.
  std::vector<Eigen::Matrix3d> G(J.size());
  double lhs = 0.;
  for(std::size_t s = 0; s < G.size(); ++s) {
    for(int r = 0; r < 3; ++r)
      for(int k = 0; k < 3; ++k) G[s](r, k) = std::sin(double(7 * s + 3 * r + k));
    lhs += (G[s].array() * J[s].array()).sum();
  }
  std::vector<Eigen::Vector3d> dP;
  PI::internal::patch_jacobians_adjoint(n, S, G, dP);
  double rhs = 0.;
  for(std::size_t i = 0; i < dP.size(); ++i) rhs += dP[i].dot(v.control_points()[i]);
  CHECK(rhs == Approx(lhs).epsilon(1e-12));
}
