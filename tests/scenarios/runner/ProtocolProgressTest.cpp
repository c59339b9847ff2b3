// The progress observer of run_packing_protocol (ProtocolSetup::on_progress): it sees the run as it
// goes and changes nothing.
#include <gtest/gtest.h>

#include <vector>

#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"

using namespace laguerre;
using namespace laguerre::scenarios;

TEST(ProtocolProgress, ReportsTheRunAsItGoesAndChangesNothing) {
  const core::GraphInput in = core::random_delaunay_triangulation(400, 7);
  ProtocolSetup setup;
  setup.acceleration = core::Acceleration::chebyshev;
  const ProtocolOutcome plain = run_packing_protocol(in.graph, in.positions, setup);
  std::vector<ProtocolProgress> seen;
  setup.on_progress = [&](const ProtocolProgress& p) { seen.push_back(p); };
  setup.progress_period = 0;  // every 2^16 events
  const ProtocolOutcome watched = run_packing_protocol(in.graph, in.positions, setup);

  ASSERT_TRUE(plain.converged());
  EXPECT_EQ(watched.iterations, plain.iterations);
  EXPECT_EQ(watched.messages, plain.messages);
  EXPECT_EQ(watched.bytes, plain.bytes);
  EXPECT_EQ(watched.events, plain.events);
  EXPECT_EQ(watched.simulated_time, plain.simulated_time);
  ASSERT_EQ(watched.circles.size(), plain.circles.size());
  for (std::size_t v = 0; v < plain.circles.size(); ++v) {
    EXPECT_EQ(watched.circles[v].x, plain.circles[v].x);
    EXPECT_EQ(watched.circles[v].r, plain.circles[v].r);
  }
  // One report per 2^16 events, in order, each within the run's final figures.
  ASSERT_GE(seen.size(), 2u);
  ASSERT_EQ(seen.size(), plain.events >> 16);
  for (std::size_t k = 0; k < seen.size(); ++k) {
    const ProtocolProgress& p = seen[k];
    EXPECT_EQ(p.nodes, in.graph.num_vertices());
    EXPECT_EQ(p.events, (k + 1) << 16);
    EXPECT_LE(p.rounds, plain.rounds);
    EXPECT_LE(p.iterations, plain.iterations);
    EXPECT_LE(p.holds_nodes, p.nodes);
    EXPECT_LE(p.simulated_time, plain.simulated_time);
    if (k > 0) {
      EXPECT_GE(p.phase, seen[k - 1].phase);
      EXPECT_GE(p.rounds, seen[k - 1].rounds);
      EXPECT_GE(p.wall_seconds, seen[k - 1].wall_seconds);
    }
  }
}
