// Heavy sizes of the local acceleration (label slow): 2000-node uniform random maps reach LPD/GLPD with
// Acceleration::chebyshev, and greedy power routing delivers every sampled pair.
#include <gtest/gtest.h>

#include <cstdint>

#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/Topology.hpp"

using namespace laguerre;

TEST(LocalAccelerationSlow, UniformMapsOf2000NodesReachLpdGlpdAndRouteGreedily) {
  for (const char* generator : {"uniform-triangulation", "uniform-three-connected"})
    for (std::uint64_t seed : {1u, 2u}) {
      scenarios::TopologyParams p;
      p.set("n", std::int64_t{2000});
      const core::PlanarGraph g = scenarios::build_topology(generator, p, seed).graph;
      core::PackOptions opt;
      opt.acceleration = core::Acceleration::chebyshev;
      opt.max_iterations = 20000;
      const core::PackResult r = core::pack(g, opt);
      SCOPED_TRACE(std::string(generator) + " seed " + std::to_string(seed) + ": " + std::to_string(r.iterations) + " sweeps");
      EXPECT_EQ(r.status, core::PackStatus::converged);
      EXPECT_EQ(r.local_ok, g.num_vertices());
      const core::RoutingStats m = core::evaluate_routing(g, r.circles, core::Scheme::greedy_power, {2000, 7});
      EXPECT_EQ(m.delivered, m.pairs);
    }
}
