// Heavy sizes of the accelerations the network runs (label slow): 2000-node uniform random maps reach
// LPD/GLPD with Acceleration::chebyshev and Acceleration::newton_krylov, and greedy power routing
// delivers every sampled pair; 500-node maps with Newton–Krylov in the simulated network equal
// core::pack bit for bit.
#include <gtest/gtest.h>

#include <cstdint>

#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"
#include "laguerre/scenarios/Topology.hpp"

using namespace laguerre;

namespace {
core::PlanarGraph uniform(const char* generator, std::int64_t n, std::uint64_t seed) {
  scenarios::TopologyParams p;
  p.set("n", n);
  return scenarios::build_topology(generator, p, seed).graph;
}
}  // namespace

TEST(LocalAccelerationSlow, UniformMapsOf2000NodesReachLpdGlpdAndRouteGreedily) {
  for (const core::Acceleration a : {core::Acceleration::chebyshev, core::Acceleration::newton_krylov})
  for (const char* generator : {"uniform-triangulation", "uniform-three-connected"})
    for (std::uint64_t seed : {1u, 2u}) {
      const core::PlanarGraph g = uniform(generator, 2000, seed);
      core::PackOptions opt;
      opt.acceleration = a;
      opt.max_iterations = 20000;
      const core::PackResult r = core::pack(g, opt);
      SCOPED_TRACE(std::string(core::to_string(a)) + " " + generator + " seed " + std::to_string(seed) + ": " +
                   std::to_string(r.iterations) + " steps");
      EXPECT_EQ(r.status, core::PackStatus::converged);
      EXPECT_EQ(r.local_ok, g.num_vertices());
      const core::RoutingStats m = core::evaluate_routing(g, r.circles, core::Scheme::greedy_power, {2000, 7});
      EXPECT_EQ(m.delivered, m.pairs);
    }
}

TEST(LocalAccelerationSlow, NewtonKrylovInASimulatedNetworkOf500NodesEqualsCoreAndRoutesGreedily) {
  for (const char* generator : {"uniform-triangulation", "uniform-three-connected"}) {
    const core::PlanarGraph g = uniform(generator, 500, 3);
    scenarios::ProtocolSetup setup;
    setup.acceleration = core::Acceleration::newton_krylov;
    const scenarios::ProtocolOutcome o = scenarios::run_packing_protocol(g, {}, setup);
    const core::GraphKind kind = std::string(generator) == "uniform-triangulation" ? core::GraphKind::triangulated_disc
                                                                                    : core::GraphKind::three_connected;
    SCOPED_TRACE(generator);
    EXPECT_EQ(scenarios::verify_against_core(g, kind, setup, o), "identical to core::pack, bit for bit");
    EXPECT_EQ(o.converged_nodes, g.num_vertices());
    const core::RoutingStats m = core::evaluate_routing(g, o.circles, core::Scheme::greedy_power, {2000, 7});
    EXPECT_EQ(m.delivered, m.pairs);
  }
}
