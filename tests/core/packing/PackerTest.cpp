#include <gtest/gtest.h>

#include <cmath>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"

using namespace laguerre::core;

namespace {
PlanarGraph delaunay(std::size_t n, std::uint64_t seed) { return prepare_for_packing(random_delaunay_triangulation(n, seed)); }
PlanarGraph three_connected(std::size_t n, std::uint64_t seed) { return prepare_for_packing(random_three_connected(n, seed)); }
}  // namespace

TEST(Packer, StopRulesParseAndPrint) {
  for (StopRule r : {StopRule::lpd, StopRule::exact, StopRule::angle, StopRule::cap})
    EXPECT_EQ(parse_stop_rule(to_string(r)), r);
  EXPECT_THROW(parse_stop_rule("soon"), std::invalid_argument);
}

TEST(Packer, EachRuleHoldsWhenItFires) {
  const PlanarGraph g = delaunay(80, 5);
  PackOptions opt;
  opt.stop = StopRule::lpd;
  const PackResult lpd = pack(g, opt);
  ASSERT_EQ(lpd.status, PackStatus::converged);
  EXPECT_EQ(lpd.local_ok, g.num_vertices());
  EXPECT_EQ(check_all(g, lpd.circles), lpd.local);
  opt.stop = StopRule::exact;
  const PackResult exact = pack(g, opt);
  ASSERT_EQ(exact.status, PackStatus::converged);
  EXPECT_LE(exact.max_tangency_error, opt.tangency_tolerance);
  EXPECT_LE(max_tangency_error(g, exact.circles), opt.tangency_tolerance);
  opt.stop = StopRule::angle;
  opt.angle_epsilon = 1e-10;
  const PackResult angle = pack(g, opt);
  ASSERT_EQ(angle.status, PackStatus::converged);
  EXPECT_LE(angle.angle_error, 1e-10);
  // The thesis's observation: LPD comes (much) earlier than an exact packing, which comes earlier
  // than a tight angle tolerance.
  EXPECT_LT(lpd.iterations, exact.iterations);
  EXPECT_LE(exact.iterations, angle.iterations);
}

TEST(Packer, TrackedRunRecordsFirstOccurrences) {
  const PlanarGraph g = three_connected(60, 3);
  PackOptions opt;
  opt.stop = StopRule::exact;
  opt.track_all = true;
  const PackResult r = pack(g, opt);
  ASSERT_EQ(r.status, PackStatus::converged);
  EXPECT_EQ(r.first_exact, r.iterations);
  ASSERT_GE(r.first_lpd, 0);
  opt.stop = StopRule::lpd;
  opt.track_all = false;
  EXPECT_EQ(pack(g, opt).iterations, r.first_lpd);  // deterministic: the same run, stopped earlier
}

TEST(Packer, CapIsReportedAsSuch) {
  PackOptions opt;
  opt.stop = StopRule::exact;
  opt.max_iterations = 2;
  const PackResult r = pack(delaunay(200, 1), opt);
  EXPECT_EQ(r.status, PackStatus::iteration_cap);
  EXPECT_EQ(r.iterations, 2);
}

TEST(Packer, StepsPerCheckOnlyCoarsensWhenWeLook) {
  const PlanarGraph g = delaunay(120, 8);
  PackOptions opt;
  const int every = pack(g, opt).iterations;
  opt.steps_per_check = 7;
  const int coarse = pack(g, opt).iterations;
  EXPECT_EQ(coarse % 7, 0);
  EXPECT_GE(coarse, every);
  EXPECT_LT(coarse, every + 7);
}

TEST(Packer, IsDeterministic) {
  const PlanarGraph g = three_connected(50, 11);
  const PackResult a = pack(g), b = pack(g);
  ASSERT_EQ(a.radii.size(), b.radii.size());
  for (std::size_t i = 0; i < a.radii.size(); ++i) EXPECT_EQ(a.radii[i], b.radii[i]);
  for (std::size_t i = 0; i < a.circles.size(); ++i) {
    EXPECT_EQ(a.circles[i].x, b.circles[i].x);
    EXPECT_EQ(a.circles[i].r, b.circles[i].r);
  }
}

TEST(Packer, AccelerationsReachTheSamePackingInFewerSweeps) {
  EXPECT_EQ(parse_acceleration("anderson"), Acceleration::anderson);
  EXPECT_THROW(parse_acceleration("warp"), std::invalid_argument);
  const PlanarGraph g = delaunay(400, 21);
  PackOptions opt;
  opt.stop = StopRule::angle;
  opt.angle_epsilon = 1e-9;
  opt.steps_per_check = 5;
  const PackResult plain = pack(g, opt);
  ASSERT_EQ(plain.status, PackStatus::converged);
  for (Acceleration a : {Acceleration::superstep, Acceleration::anderson}) {
    opt.acceleration = a;
    const PackResult fast = pack(g, opt);
    ASSERT_EQ(fast.status, PackStatus::converged) << to_string(a);
    EXPECT_GT(fast.jumps, 0);
    EXPECT_LT(fast.iterations, plain.iterations / 2) << to_string(a);
    for (std::size_t i = 0; i < plain.radii.size(); ++i)
      if (std::isfinite(plain.radii[i])) EXPECT_NEAR(fast.radii[i], plain.radii[i], 1e-7) << to_string(a);
      else EXPECT_EQ(fast.radii[i], plain.radii[i]);  // a horocycle stays one
  }
}
