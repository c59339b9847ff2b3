#pragma once
// Runs the protocol with its reliability layer on the lossy host and core::pack on the same graph, and
// compares bit for bit (radii, circles, centres, iteration count, local outcomes, face vertices); also
// checks that the run drained and that the nodes' counters are consistent.

#include <gtest/gtest.h>

#include <string>

#include "LossyHost.hpp"
#include "SyncCompare.hpp"

namespace laguerre::protocols::testing {

// Totals over the nodes of one run.
struct LossyTotals {
  PackingCounters counters;
  LossyHost::Stats host;
  int iterations = -1;
};

inline LossyTotals expect_lossy_equals_core(const core::PlanarGraph& g, const PackingParams& params,
                                            const LossyConfig& config, const std::string& label) {
  SCOPED_TRACE(label);
  LossyTotals totals;
  [&] {
    const core::PackResult r = core::pack(g, reference_options(params));
    totals.iterations = r.iterations;
    const core::PackingComplex k = core::PackingComplex::from_graph(g);
    const auto ids = protocol_ids(g, k);
    LossyHost host(g, params, config);
    totals.host = host.run();
    ASSERT_TRUE(totals.host.drained) << "the event queue must drain (no infinite chatter)";
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      const PackingNode& n = host.node(v);
      SCOPED_TRACE("vertex " + std::to_string(v));
      ASSERT_EQ(n.phase(), PackingPhase::finished);
      EXPECT_EQ(n.steps(), static_cast<std::uint32_t>(r.iterations));
      EXPECT_EQ(bits(n.h()), bits(r.radii[v])) << n.h() << " vs " << r.radii[v];
      expect_same_circle(n.placement(), r.layout, v);
      EXPECT_EQ(n.local_condition(), r.local[v]);
      if (r.status == core::PackStatus::converged) {
        EXPECT_EQ(n.outcome(), PackingOutcome::converged);
      } else if (r.status == core::PackStatus::iteration_cap) {
        EXPECT_EQ(n.outcome(), PackingOutcome::cap);
      }
      const auto& c = n.counters();
      EXPECT_EQ(c.unexpected, 0u);
      EXPECT_EQ(c.not_a_neighbour, 0u);
      EXPECT_EQ(c.bad_payload, 0u);
      EXPECT_EQ(c.links_failed, 0u);
      EXPECT_EQ(c.decode[0], c.received);
      totals.counters += c;
    }
    for (std::size_t i = 0; i < k.face_of_vertex.size(); ++i) {
      const core::Vertex fv = static_cast<core::Vertex>(g.num_vertices() + i);
      const NodeId fid = ids[fv];
      const std::optional<VertexState> st = hosted_state(host, fid);
      ASSERT_TRUE(st.has_value());
      EXPECT_EQ(bits(st->h), bits(r.radii[fv]));
      expect_same_circle(st->placement, r.layout, fv);
    }
    // The host's ledger and the nodes' agree: every message a node sent went through the host, and
    // every copy the host delivered was received by a node.
    EXPECT_EQ(totals.counters.sent, totals.host.sent);
    EXPECT_EQ(totals.counters.received, totals.host.delivered);
    EXPECT_EQ(totals.counters.sent, totals.counters.frames + totals.counters.retransmissions + totals.counters.acks);
  }();
  return totals;
}

// Runs g with node `victim` crashing at `at` under `params`; checks every survivor ends with
// neighbour_failed naming the victim and that the queue drains; returns the host's statistics.
inline LossyHost::Stats expect_crash_detected(const core::PlanarGraph& g, const PackingParams& params, NodeId victim,
                                              Time at, LossyConfig c) {
  c.crashes = {{victim, at}};
  LossyHost host(g, params, c);
  const LossyHost::Stats s = host.run();
  EXPECT_TRUE(s.drained);
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    if (g.id(v) == victim) continue;
    SCOPED_TRACE("survivor " + std::to_string(v));
    EXPECT_EQ(host.node(v).outcome(), PackingOutcome::neighbour_failed);
    EXPECT_EQ(host.node(v).suspect(), victim);
    EXPECT_TRUE(host.node(v).is_final());
    EXPECT_EQ(host.node(v).counters().unexpected, 0u);
  }
  return s;
}

}  // namespace laguerre::protocols::testing
