// Radius-only termination in the protocol (PackingParams::termination, docs/radius-only.md): every
// round ends with one radius exchange and the closing-gap test; the layout wave and the exact check
// run only when the test holds everywhere or at the cap. The synchronous run equals core::pack with
// Termination::radius_only bit for bit (radii, circles, iteration count, local outcomes, outcome),
// under FIFO and shuffled delivery, on triangulations and 3-connected graphs, with a cap, with a
// local acceleration and over lossy links; it claims convergence only on a passed exact check; and
// it sends fewer messages than the layout termination.

#include <gtest/gtest.h>

#include "laguerre/core/Error.hpp"
#include "../LossyCompare.hpp"
#include "../SyncCompare.hpp"
#include "../TestGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {
PackingParams radius_only(int steps = 1, double gap = 1e-2,
                          core::Termination termination = core::Termination::radius_only) {
  PackingParams p;
  p.termination = termination;
  p.steps_per_check = steps;
  p.radius_only_gap = gap;
  return p;
}

std::uint64_t total_sent(DequeHost& host, std::size_t n) {
  std::uint64_t s = 0;
  for (core::Vertex v = 0; v < n; ++v) s += host.node(v).counters().sent;
  return s;
}
// The equivalence cases of both gated terminations: Delaunay triangulations n = 4…200 (seeds 1–2,
// N = 1 and 3, graphs with a root) and 3-connected graphs n = 5…80, each run FIFO with the default
// gap and shuffled with the gap 0.3 (some exact checks then fail). Returns core::pack's results of
// the shuffled triangulation runs.
std::vector<core::PackResult> expect_gated_runs_equal_core(core::Termination t) {
  std::vector<core::PackResult> loose;
  for (std::size_t n : {4, 5, 8, 16, 40, 90, 200})
    for (std::uint64_t seed = 1; seed <= 2; ++seed)
      for (int steps : {1, 3}) {
        const core::PlanarGraph g = delaunay(n, seed);
        if (core::choose_root(core::PackingComplex::from_graph(g), core::RootRule::deepest) == core::none) continue;
        const std::string label = "n=" + std::to_string(n) + " seed=" + std::to_string(seed) + " N=" + std::to_string(steps);
        expect_sync_equals_core(g, radius_only(steps, 1e-2, t), 0, label);
        expect_sync_equals_core(g, radius_only(steps, 0.3, t), seed, label + " gap 0.3 shuffled");
        loose.push_back(core::pack(g, reference_options(radius_only(steps, 0.3, t))));
        if (::testing::Test::HasFailure()) return loose;
      }
  for (std::size_t n : {5, 8, 12, 20, 35, 80})
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const core::PlanarGraph g = three_connected(n, 100 * n + seed);
      expect_sync_equals_core(g, radius_only(static_cast<int>(seed), 1e-2, t), 3 * seed, "n=" + std::to_string(n));
      expect_sync_equals_core(g, radius_only(1, 0.3, t), seed, "n=" + std::to_string(n) + " gap 0.3");
      if (::testing::Test::HasFailure()) return loose;
    }
  return loose;
}
}  // namespace

TEST(RadiusOnlyTermination, TriangulationsAndThreeConnectedGraphsEqualCoreBitForBit) {
  int failed_checks = 0;
  for (const core::PackResult& r : expect_gated_runs_equal_core(core::Termination::radius_only)) failed_checks += r.layouts - 1;
  EXPECT_GT(failed_checks, 0) << "both outcomes of the exact check";
}

TEST(RadiusOnlyTermination, CapAndAccelerationEqualCore) {
  const core::PlanarGraph g = delaunay(120, 7);
  PackingParams p = radius_only();
  p.max_iterations = 5;  // the test never holds this early: the cap's layout still runs
  expect_sync_equals_core(g, p, 0, "cap 5");
  p = radius_only();
  p.acceleration = core::Acceleration::chebyshev;
  expect_sync_equals_core(g, p, 2, "chebyshev");
}

TEST(RadiusOnlyTermination, LossyLinksEqualCore) {
  PackingParams p = radius_only();
  enable_lossy_links(p, 5'000'000);  // the lossy host's latency is 1–5 ms
  expect_lossy_equals_core(delaunay(40, 11), p, lossy_config(0.25, 0.1, 5), "loss 0.25 dup 0.1");
  expect_lossy_equals_core(three_connected(30, 4), p, lossy_config(0.2, 0.05, 9), "3-connected loss 0.2");
}

TEST(RadiusOnlyTermination, ConvergesOnlyOnAPassedExactCheckWithFewerMessages) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const core::PlanarGraph g = delaunay(150, seed);
    DequeHost layout(g, PackingParams{}), radius(g, radius_only(1, 0.5));  // a loose gap: some checks fail
    layout.run(0);
    radius.run(0);
    const core::PackResult r = core::pack(g, reference_options(radius_only(1, 0.5)));
    ASSERT_EQ(r.status, core::PackStatus::converged);
    EXPECT_GT(r.layouts, 1) << "a 0.5 rad gap should trigger a failing exact check first";
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      ASSERT_EQ(radius.node(v).outcome(), PackingOutcome::converged);
      EXPECT_EQ(radius.node(v).local_condition(), core::LocalCondition::holds);
    }
    EXPECT_LT(total_sent(radius, g.num_vertices()), total_sent(layout, g.num_vertices()));
  }
}

// Termination::radius_flood: the gate's AND on the radius exchange (GateRadiusMsg), decided D steps
// after each tested step, no convergecast per round. The synchronous run equals core::pack with
// Termination::radius_flood bit for bit (radii of the laid-out step, circles, iteration count, local
// outcomes, outcome), FIFO and shuffled, with passed and failed exact checks, at the cap, with a local
// acceleration and over lossy links.
PackingParams flood(int steps = 1, double gap = 1e-2) { return radius_only(steps, gap, core::Termination::radius_flood); }

TEST(RadiusFloodTermination, TriangulationsAndThreeConnectedGraphsEqualCoreBitForBit) {
  int failed_checks = 0;
  const std::vector<core::PackResult> loose = expect_gated_runs_equal_core(core::Termination::radius_flood);
  for (const core::PackResult& r : loose) {
    EXPECT_EQ(r.decision_step, r.iterations + r.flood_depth);
    failed_checks += r.layouts - 1;
  }
  EXPECT_GT(failed_checks, 0) << "both outcomes of the exact check, over " << loose.size() << " runs";
}

TEST(RadiusFloodTermination, CapAccelerationAndLossyLinksEqualCore) {
  const core::PlanarGraph g = delaunay(120, 7);
  PackingParams p = flood();
  p.max_iterations = 5;
  expect_sync_equals_core(g, p, 0, "cap 5");
  p = flood();
  p.acceleration = core::Acceleration::chebyshev;
  expect_sync_equals_core(g, p, 2, "chebyshev");
  p = flood();
  enable_lossy_links(p, 5'000'000);
  expect_lossy_equals_core(delaunay(40, 11), p, lossy_config(0.25, 0.1, 5), "loss 0.25 dup 0.1");
  expect_lossy_equals_core(three_connected(30, 4), p, lossy_config(0.2, 0.05, 9), "3-connected loss 0.2");
}

TEST(RadiusFloodTermination, ConvergesOnlyOnAPassedExactCheck) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const core::PlanarGraph g = delaunay(150, seed);
    DequeHost radius(g, flood(1, 0.5));
    radius.run(0);
    const core::PackResult r = core::pack(g, reference_options(flood(1, 0.5)));
    ASSERT_EQ(r.status, core::PackStatus::converged);
    EXPECT_GT(r.layouts, 1) << "a 0.5 rad gap should trigger a failing exact check first";
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      ASSERT_EQ(radius.node(v).outcome(), PackingOutcome::converged);
      EXPECT_EQ(radius.node(v).local_condition(), core::LocalCondition::holds);
    }
  }
}

// D = 2H + 2 comes from the height convergecast on the final layout tree (HeightMsg, once, before
// round 0): one report up and one answer down per tree edge, and every vertex then runs exactly the
// steps 0 … core's decision step (iterations + D), exchanging GateRadiusMsg on every dart at each.
TEST(RadiusFloodTermination, HeightConvergecastGivesCoresDepth) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
    for (std::uint64_t order : {std::uint64_t{0}, 7 * seed}) {
      SCOPED_TRACE("seed " + std::to_string(seed) + " order " + std::to_string(order));
      const core::PlanarGraph g = delaunay(120, seed + 40);
      const core::PackResult r = core::pack(g, reference_options(flood(1, 0.3)));
      ASSERT_EQ(r.status, core::PackStatus::converged);
      ASSERT_EQ(r.flood_depth, static_cast<int>(core::radius_flood_depth(r.layout)));
      DequeHost host(g, flood(1, 0.3));
      host.run(order);
      const std::uint64_t n = g.num_vertices();
      EXPECT_EQ(host.delivered(MessageType::height), 2 * (n - 1));
      EXPECT_EQ(host.delivered(MessageType::gate_radius), 2 * g.num_edges() * (static_cast<std::uint64_t>(r.decision_step) + 1));
      for (core::Vertex v = 0; v < n; ++v) {
        EXPECT_EQ(host.node(v).outcome(), PackingOutcome::converged);
        EXPECT_EQ(host.node(v).steps(), static_cast<std::uint32_t>(r.iterations));
        EXPECT_EQ(host.node(v).counters().unexpected, 0u);
      }
    }
}

TEST(RadiusOnlyTermination, RefusesAsynchronousModeAndBadGap) {
  const core::PlanarGraph g = delaunay(10, 1);
  PackingParams p = radius_only();
  p.asynchronous = true;
  EXPECT_THROW(DequeHost(g, p), core::InternalError);
  p = radius_only(1, 0.0);
  EXPECT_THROW(DequeHost(g, p), core::InternalError);
  p = flood();
  p.asynchronous = true;
  EXPECT_THROW(DequeHost(g, p), core::InternalError);
}
