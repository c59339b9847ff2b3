// Greedy power forwarding hop by hop through the deque host, on the embeddings the packing protocol
// computed, gives exactly core::route(…, Scheme::greedy_power, …): same path, outcome and stopping
// node for every ordered pair, on triangulations and 3-connected graphs, converged or not, with the
// default hop limit and a tight one.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

#include "laguerre/core/Error.hpp"
#include "../SyncCompare.hpp"
#include "../NullRuntime.hpp"
#include "Outcomes.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/protocols/Forwarding.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {

// Records every packet's path (from the forwarding reports) and end.
struct Recorder final : PacketSink {
  std::map<std::uint64_t, std::vector<NodeId>> paths;
  std::map<std::uint64_t, PacketReport> ends;
  void on_packet_end(const PacketReport& r) override { ends[r.packet] = r; }
  void on_forward(NodeId at, NodeId next, std::uint64_t packet, NodeId, std::uint32_t) override {
    auto& p = paths[packet];
    if (p.empty()) p.push_back(at);
    p.push_back(next);
  }
};

bool finite(const core::CircleEmbedding& c) {
  for (const core::Circle& x : c)
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.r) || x.r < 0) return false;
  return true;
}

// Packs g with the protocol, then routes all ordered pairs hop by hop and through core::route.
// Returns the number of packets that did not arrive (to check the cases are exercised).
std::size_t expect_forwarding_equals_core(const core::PlanarGraph& g, const PackingParams& params, std::size_t ttl,
                                          std::uint64_t shuffle, const std::string& label) {
  SCOPED_TRACE(label);
  const std::size_t n = g.num_vertices();
  DequeHost packing(g, params);
  packing.run();
  core::CircleEmbedding phi(n);
  for (core::Vertex v = 0; v < n; ++v) phi[v] = packing.node(v).placement().circle;
  // The circles the nodes hold are core::pack's (proven bit for bit in tests/protocols/packing).
  core::PackOptions o;
  o.steps_per_check = params.steps_per_check;
  o.max_iterations = params.max_iterations;
  const core::PackResult r = core::pack(g, o);
  for (core::Vertex v = 0; v < n; ++v) EXPECT_EQ(bits(phi[v].r), bits(r.circles[v].r));
  if (!finite(phi)) return 0;

  Recorder sink;
  DequeHost fwd(
      g,
      [&](Runtime& rt, core::Vertex v) {
        const PackingNode& p = packing.node(v);
        return std::make_unique<ForwardingNode>(rt, sink, g.id(v), local_knowledge(g, v).neighbours, p.placement().circle,
                                                p.neighbour_circles());
      },
      7);
  const std::size_t limit = ttl == 0 ? core::default_ttl(g, core::Scheme::greedy_power) : ttl;
  std::uint64_t packet = 0;
  for (core::Vertex s = 0; s < n; ++s)
    for (core::Vertex t = 0; t < n; ++t)
      fwd.as<ForwardingNode>(s).originate(
          {packet++, g.id(t), phi[t], static_cast<std::uint32_t>(limit), core::Scheme::greedy_power, {}});
  fwd.deliver(shuffle);

  std::size_t failed = 0;
  packet = 0;
  for (core::Vertex s = 0; s < n; ++s)
    for (core::Vertex t = 0; t < n; ++t, ++packet) {
      const core::Route expect = core::route(g, phi, core::Scheme::greedy_power, s, t, limit);
      if (!sink.ends.count(packet)) {
        ADD_FAILURE() << "packet " << s << "→" << t << " never ended";
        return failed;
      }
      const PacketReport& end = sink.ends.at(packet);
      std::vector<NodeId> path = sink.paths.count(packet) ? sink.paths.at(packet) : std::vector<NodeId>{g.id(s)};
      std::vector<NodeId> want;
      for (core::Vertex v : expect.path) want.push_back(g.id(v));
      EXPECT_EQ(path, want) << s << "→" << t;
      EXPECT_EQ(as_core(end.outcome), expect.outcome) << s << "→" << t;
      EXPECT_EQ(end.hops, expect.hops());
      EXPECT_EQ(end.source, g.id(s));
      EXPECT_EQ(end.at, expect.stuck == core::none ? g.id(t) : g.id(expect.stuck));
      failed += end.outcome != PacketOutcome::delivered;
    }
  for (core::Vertex v = 0; v < n; ++v) EXPECT_EQ(fwd.as<ForwardingNode>(v).counters().rejected, 0u);
  return failed;
}

// The three comparisons run on each graph: the converged embedding with the default hop limit (where
// the packing guarantees delivery), the converged one with the hop limit `tight_ttl`, and the
// embedding after `steps` Thurston steps only (greedy may get stuck); each with its delivery shuffle.
struct Cases {
  std::size_t tight_ttl;
  int steps;
  std::array<std::uint64_t, 3> shuffles;
};

// Runs the cases on g; returns the failures of the last two.
std::size_t expect_cases(const core::PlanarGraph& g, const std::string& label, const Cases& c, const char* guarantee) {
  PackingParams p;
  EXPECT_EQ(expect_forwarding_equals_core(g, p, 0, c.shuffles[0], label), 0u) << guarantee;
  std::size_t failed = expect_forwarding_equals_core(g, p, c.tight_ttl, c.shuffles[1],
                                                     label + " ttl=" + std::to_string(c.tight_ttl));
  p.max_iterations = c.steps;
  failed += expect_forwarding_equals_core(g, p, 0, c.shuffles[2], label + " " + std::to_string(c.steps) + " steps");
  return failed;
}

}  // namespace

TEST(Forwarding, EqualsCoreRouteOnTriangulations) {
  std::size_t failed = 0;
  for (std::size_t n : {6, 12, 25})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const core::PlanarGraph g = core::prepare_for_packing(core::random_delaunay_triangulation(n, 50 * n + seed));
      const std::string label = "tri n=" + std::to_string(n) + " seed=" + std::to_string(seed);
      failed += expect_cases(g, label, {2, 1, {0, seed, seed}}, "LPD guarantees delivery");
    }
  EXPECT_GT(failed, 0u) << "the tight hop limit and unconverged embeddings must exercise the failures";
}

TEST(Forwarding, EqualsCoreRouteOnThreeConnectedGraphs) {
  std::size_t failed = 0;
  for (std::size_t n : {8, 15, 25})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const core::PlanarGraph g = core::prepare_for_packing(core::random_three_connected(n, 70 * n + seed));
      const std::string label = "3c n=" + std::to_string(n) + " seed=" + std::to_string(seed);
      failed += expect_cases(g, label, {3, 2, {seed, 0, 0}}, "GLPD guarantees delivery");
    }
  EXPECT_GT(failed, 0u);
}

TEST(Forwarding, RejectsBadInputAndForeignMessages) {
  laguerre::protocols::testing::NullRuntime rt;
  Recorder sink;
  const core::Circle c{0, 0, 0.1}, d{0.3, 0, 0.1};
  EXPECT_THROW(ForwardingNode(rt, sink, 1, {2, 3}, c, {d}), laguerre::core::InternalError);
  EXPECT_THROW(ForwardingNode(rt, sink, 1, {2, 2}, c, {d, d}), laguerre::core::InternalError);
  EXPECT_THROW(ForwardingNode(rt, sink, 1, {1}, c, {d}), laguerre::core::InternalError);
  EXPECT_THROW(ForwardingNode(rt, sink, 1, {2}, c, {{NAN, 0, 1}}), laguerre::core::InternalError);
  ForwardingNode f(rt, sink, 1, {2}, c, {d});
  f.on_message(9, encode(DataMsg{1, 5, 6, 0, 0, 0, 4, 1}));  // not a neighbour
  f.on_message(2, encode(ReportMsg{0, true}));                // not data
  const std::byte junk[2] = {std::byte{1}, std::byte{12}};
  f.on_message(2, junk);
  EXPECT_EQ(f.counters().rejected, 3u);
  f.originate({7, 1, c, 4, core::Scheme::greedy_power, {}});  // to itself: delivered with no hop
  ASSERT_TRUE(sink.ends.count(7));
  EXPECT_EQ(sink.ends[7].outcome, PacketOutcome::delivered);
  EXPECT_EQ(sink.ends[7].hops, 0u);
  f.originate({8, 5, core::Circle{-1, 0, 0}, 4, core::Scheme::greedy_power, {}});  // the neighbour is farther: dead end here
  EXPECT_EQ(sink.ends[8].outcome, PacketOutcome::dead_end);
  EXPECT_EQ(sink.ends[8].at, 1u);
}
