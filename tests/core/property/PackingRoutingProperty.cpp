// Property: on thousands of random small triangulations and 3-connected planar graphs, the packing
// reaches LPD/GLPD, greedy power routing then delivers on every ordered pair (thesis Corollaries of
// §5.2), and greedy-face-greedy delivers on every pair of the straight-line layout.
#include <gtest/gtest.h>

#include <cstdlib>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"

using namespace laguerre::core;

namespace {
// LAGUERRE_PROPERTY_CASES scales the number of random graphs (default 1000 per family).
int cases() {
  const char* env = std::getenv("LAGUERRE_PROPERTY_CASES");
  return env ? std::atoi(env) : 1000;
}

void check_family(bool three_connected) {
  const int count = cases();
  int lpd_iterations = 0;
  for (int i = 0; i < count; ++i) {
    const std::uint64_t seed = 0x5eed0000u + static_cast<std::uint64_t>(i);
    const std::size_t n = 4 + static_cast<std::size_t>(i % 37);  // 4 … 40 vertices
    const GraphInput in = three_connected ? random_three_connected(n < 5 ? 5 : n, seed) : random_delaunay_triangulation(n, seed);
    GraphKind kind{};
    const PlanarGraph g = prepare_for_packing(in, &kind);
    PackOptions opt;
    opt.max_iterations = 20000;
    const PackResult r = pack(g, opt);
    ASSERT_EQ(r.status, PackStatus::converged) << in.name << " seed " << seed << " n " << n;
    ASSERT_EQ(r.local_ok, g.num_vertices());
    lpd_iterations += r.iterations;
    const RoutingStats power = evaluate_routing(g, r.circles, Scheme::greedy_power, {});
    ASSERT_EQ(power.delivered, power.pairs) << "greedy power failed on an LPD embedding: " << in.name << " seed " << seed;
    const RoutingStats gfg = evaluate_routing(g, r.circles, Scheme::gfg, {});
    ASSERT_EQ(gfg.delivered, gfg.pairs) << "GFG failed: " << in.name << " seed " << seed;
  }
  ::testing::Test::RecordProperty("mean_iterations_to_lpd", lpd_iterations / std::max(1, count));
}
}  // namespace

TEST(PackingRoutingProperty, TriangulationsReachLpdAndGreedyPowerDelivers) { check_family(false); }

TEST(PackingRoutingProperty, ThreeConnectedGraphsReachGlpdAndGreedyPowerDelivers) { check_family(true); }
