#pragma once
// Runs the protocol on the deque host and core::pack on the same graph, and compares bit for bit.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <deque>
#include <string>

#include "SyncHost.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"

namespace laguerre::protocols::testing {

inline std::uint64_t bits(double d) { return std::bit_cast<std::uint64_t>(d); }

// Hop distance from the boundary (core's rule for RootRule::deepest).
inline std::vector<std::uint32_t> boundary_depths(const core::PlanarGraph& g) {
  std::vector<std::uint32_t> depth(g.num_vertices(), core::none);
  std::deque<core::Vertex> q;
  for (core::Vertex v = 0; v < g.num_vertices(); ++v)
    if (g.is_boundary(v)) depth[v] = 0, q.push_back(v);
  while (!q.empty()) {
    const core::Vertex v = q.front();
    q.pop_front();
    for (core::Vertex w : g.neighbours(v))
      if (depth[w] == core::none) depth[w] = depth[v] + 1, q.push_back(w);
  }
  return depth;
}

// Compares one protocol run with core::pack (Jacobi, stop = lpd) on g; returns the host for more checks.
inline void expect_sync_equals_core(const core::PlanarGraph& g, const PackingParams& params, std::uint64_t shuffle_seed,
                                    const std::string& label) {
  SCOPED_TRACE(label);
  core::PackOptions opt;
  opt.stop = core::StopRule::lpd;
  opt.sweep = core::Sweep::jacobi;
  opt.update = params.update;
  opt.root = params.root;
  opt.steps_per_check = params.steps_per_check;
  opt.max_iterations = params.max_iterations;
  const core::PackResult r = core::pack(g, opt);
  const core::PackingComplex k = core::PackingComplex::from_graph(g);
  const core::Vertex root = core::choose_root(k, params.root);
  ASSERT_NE(root, core::none) << "test graphs must have an interior vertex";
  const auto depth = boundary_depths(g);

  DequeHost host(g, params);
  host.run(shuffle_seed);
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    const PackingNode& n = host.node(v);
    SCOPED_TRACE("vertex " + std::to_string(v));
    ASSERT_EQ(n.phase(), PackingPhase::finished);
    EXPECT_EQ(n.depth(), depth[v]);
    EXPECT_EQ(n.is_root(), v == root);
    EXPECT_EQ(n.wave(), r.layout.wave[v]);
    EXPECT_EQ(n.parent(), v == root ? g.id(v) : g.id(r.layout.parent[v]));
    EXPECT_EQ(n.steps(), static_cast<std::uint32_t>(r.iterations));
    EXPECT_EQ(bits(n.x()), bits(r.radii[v])) << n.x() << " vs " << r.radii[v];
    EXPECT_EQ(bits(n.placement().circle.x), bits(r.layout.circles[v].x));
    EXPECT_EQ(bits(n.placement().circle.y), bits(r.layout.circles[v].y));
    EXPECT_EQ(bits(n.placement().circle.r), bits(r.layout.circles[v].r));
    EXPECT_EQ(bits(n.placement().centre.real()), bits(r.layout.centre[v].real()));
    EXPECT_EQ(bits(n.placement().centre.imag()), bits(r.layout.centre[v].imag()));
    EXPECT_EQ(n.local_condition(), r.local[v]);
    const auto& c = n.counters();
    EXPECT_EQ(c.unexpected, 0u);
    EXPECT_EQ(c.not_a_neighbour, 0u);
    EXPECT_EQ(c.decode[0], c.received);
    if (r.status == core::PackStatus::converged) {
      EXPECT_EQ(n.outcome(), PackingOutcome::converged);
    } else if (r.status == core::PackStatus::iteration_cap) {
      EXPECT_EQ(n.outcome(), PackingOutcome::cap);
    }
  }
}

}  // namespace laguerre::protocols::testing
