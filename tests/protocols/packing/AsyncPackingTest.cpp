// The asynchronous mode (docs/protocol.md, "Asynchronous mode"): under arbitrary delivery orders, and
// under loss and duplication with the reliability layer, every node ends converged after the same
// number of updates, and core's own LPD/GLPD check holds at every vertex of the embedding the nodes
// hold.

#include <gtest/gtest.h>

#include "../LossyCompare.hpp"
#include "../TestGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {

// Checks the end state of an asynchronous run; returns its iteration-equivalents.
template <class Host>
std::uint32_t expect_async_converged(const core::PlanarGraph& g, Host& host) {
  core::CircleEmbedding phi(g.num_vertices());
  const std::uint32_t steps = host.node(0).steps();
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    const PackingNode& n = host.node(v);
    EXPECT_EQ(n.outcome(), PackingOutcome::converged) << "vertex " << v;
    EXPECT_EQ(n.steps(), steps) << "vertex " << v;
    EXPECT_EQ(n.local_condition(), core::LocalCondition::holds) << "vertex " << v;
    EXPECT_EQ(n.counters().unexpected, 0u) << "vertex " << v;
    phi[v] = n.placement().circle;
  }
  const auto checks = core::check_all(g, phi);
  for (core::Vertex v = 0; v < g.num_vertices(); ++v)
    EXPECT_EQ(checks[v], core::LocalCondition::holds) << "core's check at vertex " << v;
  return steps;
}

PackingParams async_params(int steps) {
  PackingParams p;
  p.steps_per_check = steps;
  p.asynchronous = true;
  p.max_iterations = 20000;
  return p;
}

}  // namespace

TEST(AsyncPacking, ConvergesUnderArbitraryDeliveryOrders) {
  std::uint64_t async_total = 0, sync_total = 0;
  for (std::size_t n : {20, 40, 60})
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const bool tri = seed % 2 == 1;
      const core::PlanarGraph g = tri ? delaunay(n, 100 * n + seed) : three_connected(n, 100 * n + seed);
      const PackingParams p = async_params(1 + static_cast<int>(seed % 3));
      SCOPED_TRACE("n=" + std::to_string(n) + " seed " + std::to_string(seed));
      DequeHost host(g, p);
      host.run(seed % 2 == 0 ? 0 : seed);  // FIFO or shuffled
      async_total += expect_async_converged(g, host);
      sync_total += static_cast<std::uint64_t>(core::pack(g, reference_options(p)).iterations);
      if (HasFailure()) return;
    }
  RecordProperty("async_iterations", static_cast<int>(async_total));
  RecordProperty("sync_iterations", static_cast<int>(sync_total));
  EXPECT_GT(async_total, 0u);
}

TEST(AsyncPacking, ConvergesUnderLossAndDuplicationWithTheReliabilityLayer) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const bool tri = seed % 2 == 0;
    const core::PlanarGraph g = tri ? delaunay(40, seed) : three_connected(40, seed);
    PackingParams p = async_params(2);
    enable_lossy_links(p, 5'000'000);
    const LossyConfig c = lossy_config(0.2, 0.05, seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    LossyHost host(g, p, c);
    ASSERT_TRUE(host.run().drained);
    expect_async_converged(g, host);
  }
}
