// Hop-by-hop forwarding of every scheme hosted on the simulation kernel (random latencies, so packets
// overtake each other): each packet's path, outcome, stopping node and hop count equal
// core::route's, on random triangulations and 3-connected graphs, with the packing's circles for
// greedy power and the graph's drawing (or the packing's centres) for the geometric schemes. The nodes
// are built as `laguerre simulate` builds them (scenarios::make_forwarding_node). Over lossy,
// duplicating links each forwarding node runs over the reliability layer (protocols::ReliableNode),
// and the paths are still core::route's; scenarios::run_forwarding under loss delivers the same
// packets with the same hops as without.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/protocols/Forwarding.hpp"
#include "laguerre/protocols/Reliable.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"
#include "laguerre/sim/SimHost.hpp"

using namespace laguerre;
using protocols::ForwardingNode;
using protocols::PacketOutcome;
using protocols::PacketReport;

namespace {

struct Recorder final : protocols::PacketSink {
  std::map<std::uint64_t, std::map<std::uint32_t, protocols::NodeId>> hops;
  std::map<std::uint64_t, PacketReport> ends;
  void on_packet_end(const PacketReport& r) override { ends[r.packet] = r; }
  void on_forward(protocols::NodeId, protocols::NodeId next, std::uint64_t packet, protocols::NodeId,
                  std::uint32_t hop) override {
    hops[packet][hop] = next;
  }
};

std::string_view name(PacketOutcome o) { return protocols::to_string(o); }

// Routes a seeded sample of pairs (plus every pair for small graphs) with every scheme in one
// simulation and compares with core::route. Returns the number of packets that were not delivered.
// With `loss` > 0 the links also lose (and duplicate 5 % of) the messages, and each node runs over
// the reliability layer.
std::size_t expect_equal(const core::PlanarGraph& g, const core::CircleEmbedding& phi,
                         const std::vector<core::Point2>& pos, std::uint64_t seed, const std::string& label,
                         double loss = 0) {
  SCOPED_TRACE(label);
  const std::size_t n = g.num_vertices();
  core::CircleEmbedding geo(n);
  for (core::Vertex v = 0; v < n; ++v) geo[v] = {pos[v].x, pos[v].y, 0.0};
  sim::LinkModel link;
  link.latency = sim::LatencyModel::uniform(sim::microseconds(100), sim::milliseconds(3));
  link.loss = loss;
  link.duplication = loss > 0 ? 0.05 : 0.0;
  sim::SimConfig config;
  config.seed = seed;
  Recorder sink;
  std::optional<protocols::ReliableParams> reliable;
  if (loss > 0) {
    reliable = protocols::lossy_link_params(sim::milliseconds(3));
    reliable->probes = false;
  }
  sim::SimHost host(sim::network_of(g, link), config, [&](protocols::Runtime& rt, sim::NodeIndex v) {
    return scenarios::make_forwarding_node(rt, sink, g, v, phi, pos, reliable);
  });
  const auto forwarder = [&](core::Vertex v) -> ForwardingNode& { return scenarios::forwarding_node(host.node(v)); };
  const auto pairs = core::select_pairs(n, {n <= 30 ? std::size_t{0} : std::size_t{400}, seed});
  std::uint64_t packet = 0;
  for (core::Scheme s : core::all_schemes)
    for (const auto& [a, b] : pairs)
      forwarder(a).originate({packet++, g.id(b), phi[b], static_cast<std::uint32_t>(core::default_ttl(g, core::Scheme::greedy_power)),
                      s, pos[b]});
  const sim::RunReport report = host.run();
  EXPECT_EQ(report.reason, sim::StopReason::queue_empty);
  if (loss > 0) {
    std::uint64_t retransmissions = 0;
    for (core::Vertex v = 0; v < n; ++v) {
      const auto& r = static_cast<const protocols::ReliableNode&>(host.node(v));
      EXPECT_FALSE(r.failed());
      retransmissions += r.counters().retransmissions;
      EXPECT_EQ(forwarder(v).counters().duplicates, 0u) << "the layer delivers each hop once";
    }
    EXPECT_GT(retransmissions, 0u);
  }

  std::size_t failed = 0;
  packet = 0;
  for (core::Scheme s : core::all_schemes)
    for (const auto& [a, b] : pairs) {
      const core::Route want = core::route(g, s == core::Scheme::greedy_power ? phi : geo, s, a, b,
                                           core::default_ttl(g, core::Scheme::greedy_power));
      const std::uint64_t p = packet++;
      if (!sink.ends.count(p)) {
        ADD_FAILURE() << core::to_string(s) << " " << a << "→" << b << " never ended";
        continue;
      }
      const PacketReport& end = sink.ends.at(p);
      std::vector<protocols::NodeId> path{g.id(a)};
      if (sink.hops.count(p))
        for (const auto& [hop, node] : sink.hops.at(p)) path.push_back(node);
      std::vector<protocols::NodeId> expect;
      for (core::Vertex v : want.path) expect.push_back(g.id(v));
      EXPECT_EQ(path, expect) << core::to_string(s) << " " << a << "→" << b;
      EXPECT_EQ(std::string(name(end.outcome)), std::string(core::to_string(want.outcome))) << core::to_string(s);
      EXPECT_EQ(end.hops, want.hops());
      EXPECT_EQ(end.at, want.stuck == core::none ? g.id(b) : g.id(want.stuck));
      failed += end.outcome != PacketOutcome::delivered;
    }
  return failed;
}

std::vector<core::Point2> centres_of(const core::CircleEmbedding& phi) {
  std::vector<core::Point2> out;
  for (const core::Circle& c : phi) out.push_back(core::centre(c));
  return out;
}

}  // namespace

TEST(ForwardingSim, EverySchemeEqualsCoreOnTriangulations) {
  for (std::size_t n : {20, 80})
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const core::GraphInput in = core::random_delaunay_triangulation(n, 31 * n + seed);
      const core::PlanarGraph g = core::prepare_for_packing(in);
      const core::PackResult r = core::pack(g);
      ASSERT_EQ(r.status, core::PackStatus::converged);
      const std::string label = "tri n=" + std::to_string(n) + " seed=" + std::to_string(seed);
      EXPECT_EQ(expect_equal(g, r.circles, centres_of(r.circles), seed, label + " packing"), 0u)
          << "on a packing's tangency drawing every scheme delivers";
      std::vector<core::Point2> pos(in.positions.begin(), in.positions.end());
      expect_equal(in.graph, r.circles, pos, seed, label + " drawing");
    }
}

TEST(ForwardingSim, EverySchemeEqualsCoreOnThreeConnectedGraphs) {
  std::size_t failed = 0;
  for (std::size_t n : {25, 60})
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const core::GraphInput in = core::random_three_connected(n, 37 * n + seed);
      const core::PlanarGraph g = core::prepare_for_packing(in);
      const core::PackResult r = core::pack(g);
      ASSERT_EQ(r.status, core::PackStatus::converged);
      const std::string label = "3c n=" + std::to_string(n) + " seed=" + std::to_string(seed);
      expect_equal(g, r.circles, centres_of(r.circles), seed, label + " packing");
      std::vector<core::Point2> pos(in.positions.begin(), in.positions.end());
      core::CircleEmbedding flat;
      for (const auto& q : pos) flat.push_back({q.x, q.y, 0.0});
      failed += expect_equal(in.graph, flat, pos, seed, label + " drawing");
    }
  EXPECT_GT(failed, 0u) << "greedy routing on sparse drawings must exercise the failures";
}

TEST(ForwardingSim, EverySchemeEqualsCoreOverLossyLinks) {
  const core::GraphInput tri = core::random_delaunay_triangulation(40, 5);
  const core::GraphInput tc = core::random_three_connected(30, 6);
  for (const core::GraphInput* in : {&tri, &tc}) {
    const core::PlanarGraph g = core::prepare_for_packing(*in);
    const core::PackResult r = core::pack(g);
    ASSERT_EQ(r.status, core::PackStatus::converged);
    for (std::uint64_t seed = 1; seed <= 2; ++seed)
      expect_equal(g, r.circles, centres_of(r.circles), seed, "n=" + std::to_string(g.num_vertices()) + " seed=" +
                   std::to_string(seed) + " loss 0.2", 0.2);
  }
}

TEST(ForwardingSim, RunForwardingUnderLossDeliversWhatTheLosslessRunDelivers) {
  // scenarios::run_forwarding, as `laguerre simulate --loss 0.2` runs it: the same packets delivered,
  // dead-ended, looped, with the same hops; only later.
  const core::PlanarGraph g = core::prepare_for_packing(core::random_delaunay_triangulation(60, 12));
  const core::PackResult r = core::pack(g);
  ASSERT_EQ(r.status, core::PackStatus::converged);
  const auto pairs = core::select_pairs(g.num_vertices(), {300, 4});
  sim::LinkModel link;
  link.latency = sim::LatencyModel::uniform(sim::milliseconds(1), sim::milliseconds(4));
  const std::vector<core::Scheme> schemes(core::all_schemes.begin(), core::all_schemes.end());
  const auto clean = scenarios::run_forwarding(g, r.circles, {}, link, 3, schemes, pairs);
  link.loss = 0.2;
  link.duplication = 0.05;
  const auto lossy = scenarios::run_forwarding(g, r.circles, {}, link, 3, schemes, pairs);
  ASSERT_EQ(clean.size(), lossy.size());
  for (std::size_t i = 0; i < clean.size(); ++i) {
    SCOPED_TRACE(std::string(core::to_string(clean[i].scheme)));
    EXPECT_EQ(lossy[i].packets, pairs.size());
    EXPECT_EQ(lossy[i].delivered, clean[i].delivered);
    EXPECT_EQ(lossy[i].dead_ends, clean[i].dead_ends);
    EXPECT_EQ(lossy[i].loops, clean[i].loops);
    EXPECT_EQ(lossy[i].ttl_exceeded, clean[i].ttl_exceeded);
    EXPECT_EQ(lossy[i].hops_mean, clean[i].hops_mean);
    EXPECT_EQ(clean[i].retransmissions, 0u);
    EXPECT_GT(lossy[i].retransmissions, 0u);
    EXPECT_GT(lossy[i].simulated_seconds, clean[i].simulated_seconds);
  }
  EXPECT_EQ(clean[0].scheme, core::Scheme::greedy_power);
  EXPECT_EQ(clean[0].delivered, pairs.size()) << "greedy power on a packing delivers everything";
}

// scenarios::forwarding_blocker: forwarding runs on a packing outcome only if no node failed and
// every final circle is finite (a run stopped by the cap before its layout was representable leaves
// NaN or infinite circles, which forwarding nodes refuse); `simulate` and `live` then report why.
TEST(ForwardingSim, ForwardingIsBlockedOnAbandonedRunsAndNonFiniteCircles) {
  const core::PlanarGraph g = core::prepare_for_packing(core::random_delaunay_triangulation(30, 4));
  scenarios::ProtocolOutcome po;
  po.circles = core::pack(g).circles;
  EXPECT_EQ(scenarios::forwarding_blocker(po), "");
  scenarios::ProtocolOutcome failed = po;
  failed.failed_nodes = 1;
  EXPECT_NE(scenarios::forwarding_blocker(failed).find("abandoned"), std::string::npos);
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    scenarios::ProtocolOutcome collapsed = po;
    collapsed.circles[7].x = bad;
    EXPECT_NE(scenarios::forwarding_blocker(collapsed).find("not finite"), std::string::npos);
    // What simulate does when blocked: no pairs, so no forwarding node is built (each would refuse the
    // circle with an internal error) and no result comes back.
    EXPECT_TRUE(scenarios::run_forwarding(g, collapsed.circles, {}, {}, 1, {core::Scheme::greedy_power}, {}).empty());
    collapsed = po;
    collapsed.circles[3].r = bad;
    EXPECT_NE(scenarios::forwarding_blocker(collapsed).find("not finite"), std::string::npos);
  }
  scenarios::ProtocolOutcome negative = po;
  negative.circles[0].r = -1e-3;
  EXPECT_NE(scenarios::forwarding_blocker(negative), "");
}
