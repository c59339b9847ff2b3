#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Newton.hpp"
#include "laguerre/core/packing/Packer.hpp"

using namespace laguerre::core;

namespace {
PlanarGraph delaunay(std::size_t n, std::uint64_t seed) { return prepare_for_packing(random_delaunay_triangulation(n, seed)); }
PlanarGraph three_connected(std::size_t n, std::uint64_t seed) { return prepare_for_packing(random_three_connected(n, seed)); }
}  // namespace

TEST(Packer, StopRulesParseAndPrint) {
  for (StopRule r : {StopRule::lpd, StopRule::exact, StopRule::angle, StopRule::cap})
    EXPECT_EQ(parse_stop_rule(to_string(r)), r);
  EXPECT_THROW(parse_stop_rule("soon"), InputError);
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
  EXPECT_THROW(parse_acceleration("warp"), InputError);
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

TEST(Packer, NewtonReachesThePackingOfThurstonsIterationInFewSteps) {
  // Newton's method solves the same equations θ(v) = 2π: same packing as plain sweeps to rounding,
  // quadratic convergence (a few tens of steps at most), on triangulations and on G′ of 3-connected
  // graphs, and every step it takes decreases the residual.
  EXPECT_EQ(parse_acceleration("newton"), Acceleration::newton);
  for (const PlanarGraph& g : {delaunay(300, 5), three_connected(300, 6)}) {
    PackOptions opt;
    opt.stop = StopRule::angle;
    opt.angle_epsilon = 1e-11;
    const PackResult plain = pack(g, opt);
    ASSERT_EQ(plain.status, PackStatus::converged);
    opt.acceleration = Acceleration::newton;
    const PackResult fast = pack(g, opt);
    ASSERT_EQ(fast.status, PackStatus::converged);
    EXPECT_LE(fast.iterations, 30);
    EXPECT_GE(fast.jumps, fast.iterations - 2);  // nearly every iteration is an improving Newton step
    EXPECT_LT(20 * fast.iterations, plain.iterations);
    for (std::size_t i = 0; i < plain.radii.size(); ++i)
      if (std::isfinite(plain.radii[i])) EXPECT_NEAR(fast.radii[i] / plain.radii[i], 1.0, 1e-8);
      else EXPECT_EQ(fast.radii[i], plain.radii[i]);
    // Stopped at LPD/GLPD instead, Newton's layout passes the same exact local checks.
    opt.stop = StopRule::lpd;
    const PackResult lpd = pack(g, opt);
    ASSERT_EQ(lpd.status, PackStatus::converged);
    EXPECT_EQ(lpd.local_ok, g.num_vertices());
  }
}

TEST(Packer, NewtonStepNeverIncreasesTheAngleError) {
  const PlanarGraph g = three_connected(200, 9);
  const PackingComplex k = PackingComplex::from_graph(g);
  Radii h = initial_radii(k);
  double previous = angle_error(k, h);
  for (int s = 0; s < 40; ++s) {
    const Radii before = h;
    const NewtonStep step = newton_step(k, h);
    EXPECT_EQ(step.error_before, previous);
    if (!step.improved) {
      EXPECT_EQ(h, before);  // a failed step changes nothing
      break;
    }
    previous = step.error_after;
  }
  EXPECT_LT(previous, 1e-10);
}

TEST(Packer, TimeLimitStopsAfterTheStepInProgressAndChecksTheLastLayout) {
  // A limit far below one sweep: the run stops after its first sweep (plain) or Newton step, lays the
  // radii out and checks them like at the cap, and says time_limit.
  const PlanarGraph g = delaunay(300, 4);
  for (const Acceleration a : {Acceleration::plain, Acceleration::newton}) {
    PackOptions opt;
    opt.acceleration = a;
    opt.steps_per_check = 5;
    opt.time_limit = 1e-9;
    const PackResult r = pack(g, opt);
    EXPECT_EQ(r.status, PackStatus::time_limit) << to_string(a);
    EXPECT_EQ(r.iterations, 1) << to_string(a);
    EXPECT_EQ(r.layouts, 2) << to_string(a);  // iteration 0 and the final one
    EXPECT_EQ(r.local, check_all(g, r.circles)) << to_string(a);
    EXPECT_EQ(to_string(r.status), "time_limit");
  }
  // A generous limit changes nothing: the same run as without it.
  PackOptions opt;
  opt.acceleration = Acceleration::newton;
  const PackResult free_run = pack(g, opt);
  opt.time_limit = 3600;
  const PackResult limited = pack(g, opt);
  ASSERT_EQ(limited.status, PackStatus::converged);
  EXPECT_EQ(limited.iterations, free_run.iterations);
  EXPECT_EQ(limited.radii, free_run.radii);
}

TEST(Packer, PhaseSecondsAccountForTheRunAndNameNewtonsParts) {
  const PlanarGraph g = delaunay(2000, 8);
  for (const Acceleration a : {Acceleration::plain, Acceleration::newton}) {
    PackOptions opt;
    opt.acceleration = a;
    const auto t0 = std::chrono::steady_clock::now();
    const PackResult r = pack(g, opt);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(r.status, PackStatus::converged);
    const PackPhaseSeconds& p = r.phase_seconds;
    for (double x : {p.setup, p.sweeps, p.jacobian, p.solve, p.line_search, p.layout, p.checks, p.final}) EXPECT_GE(x, 0.0);
    const double sum = p.setup + p.sweeps + p.jacobian + p.solve + p.line_search + p.layout + p.checks + p.final;
    EXPECT_LE(sum, wall * 1.0001 + 1e-6);  // disjoint laps of the same clock
    EXPECT_GE(sum, 0.9 * wall);            // and nothing large outside them
    EXPECT_GT(p.layout, 0.0);
    EXPECT_GT(p.checks, 0.0);
    if (a == Acceleration::newton) {
      EXPECT_GT(p.jacobian, 0.0);
      EXPECT_GT(p.solve, 0.0);
      EXPECT_GT(p.line_search, 0.0);
    } else {
      EXPECT_GT(p.sweeps, 0.0);
      EXPECT_EQ(p.jacobian + p.solve + p.line_search, 0.0);
    }
  }
}
