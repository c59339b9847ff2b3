// Every routing scheme hop by hop (greedy power, greedy Euclidean, compass, greedy-face-greedy),
// through the deque host, gives exactly core::route: same path, outcome, stopping node and hop count,
// for every ordered pair, on random Delaunay triangulations and random 3-connected graphs, with the
// graphs' own drawings, with the packing's centres, with jittered (no longer plane) drawings that make
// compass and GFG loop, with the default hop limit and tight ones, in FIFO and shuffled delivery order.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>

#include "laguerre/core/Error.hpp"
#include "../NullRuntime.hpp"
#include "../SyncHost.hpp"
#include "Outcomes.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/protocols/Forwarding.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {

struct Recorder final : PacketSink {
  std::map<std::uint64_t, std::map<std::uint32_t, NodeId>> hops;  // packet → (hop number → node reached)
  std::map<std::uint64_t, PacketReport> ends;
  std::size_t double_ends = 0;
  void on_packet_end(const PacketReport& r) override { double_ends += !ends.emplace(r.packet, r).second; }
  void on_forward(NodeId, NodeId next, std::uint64_t packet, NodeId, std::uint32_t hop) override {
    hops[packet][hop] = next;
  }
};

// Tallies of core's outcomes (to check that the comparisons exercise every case).
struct Tally {
  std::map<core::RouteOutcome, std::size_t> outcomes;
  std::size_t perimeter = 0;  // gfg packets whose path differs from greedy Euclidean's
};

// Routes every ordered pair of g with scheme `s` hop by hop (circles `phi` for greedy power, positions
// `pos` for the others) and compares with core::route.
void expect_equal(const core::PlanarGraph& g, const core::CircleEmbedding& phi, const std::vector<core::Point2>& pos,
                  core::Scheme s, std::size_t ttl, std::uint64_t shuffle, Tally& tally, const std::string& label) {
  SCOPED_TRACE(label + " scheme=" + std::string(core::to_string(s)) + " ttl=" + std::to_string(ttl));
  const std::size_t n = g.num_vertices();
  for (core::Vertex v = 1; v < n; ++v) ASSERT_LT(g.id(v - 1), g.id(v)) << "ties need ids increasing with indices";
  core::CircleEmbedding geo(n);
  for (core::Vertex v = 0; v < n; ++v) geo[v] = {pos[v].x, pos[v].y, 0.0};
  const core::CircleEmbedding& used = s == core::Scheme::greedy_power ? phi : geo;
  const std::size_t limit = std::min<std::size_t>(ttl == 0 ? core::default_ttl(g, s) : ttl, 0xffffffffu);

  Recorder sink;
  DequeHost host(
      g,
      [&](Runtime& rt, core::Vertex v) {
        std::vector<core::Circle> circles;
        std::vector<core::Point2> points;
        for (core::Vertex w : g.neighbours(v)) {
          circles.push_back(phi[w]);
          points.push_back(pos[w]);
        }
        return std::make_unique<ForwardingNode>(rt, sink, g.id(v), local_knowledge(g, v).neighbours, phi[v], circles,
                                                pos[v], points);
      },
      3);
  std::uint64_t packet = 0;
  for (core::Vertex a = 0; a < n; ++a)
    for (core::Vertex b = 0; b < n; ++b)
      host.as<ForwardingNode>(a).originate(
          {packet++, g.id(b), phi[b], static_cast<std::uint32_t>(limit), s, core::centre(geo[b])});
  host.deliver(shuffle);
  EXPECT_EQ(sink.double_ends, 0u);

  packet = 0;
  for (core::Vertex a = 0; a < n; ++a)
    for (core::Vertex b = 0; b < n; ++b, ++packet) {
      const core::Route want = core::route(g, used, s, a, b, limit);
      ++tally.outcomes[want.outcome];
      if (s == core::Scheme::gfg && want.path != core::route(g, geo, core::Scheme::greedy_euclid, a, b, limit).path)
        ++tally.perimeter;
      ASSERT_TRUE(sink.ends.count(packet)) << a << "→" << b << " never ended";
      const PacketReport& end = sink.ends.at(packet);
      std::vector<NodeId> path{g.id(a)};
      if (sink.hops.count(packet))
        for (const auto& [hop, node] : sink.hops.at(packet)) {
          EXPECT_EQ(hop, path.size()) << "hop numbers are consecutive";
          path.push_back(node);
        }
      std::vector<NodeId> expect;
      for (core::Vertex v : want.path) expect.push_back(g.id(v));
      EXPECT_EQ(path, expect) << a << "→" << b;
      EXPECT_EQ(as_core(end.outcome), want.outcome) << a << "→" << b;
      EXPECT_EQ(end.hops, want.hops()) << a << "→" << b;
      EXPECT_EQ(end.source, g.id(a));
      EXPECT_EQ(end.scheme, s);
      EXPECT_EQ(end.at, want.stuck == core::none ? g.id(b) : g.id(want.stuck)) << a << "→" << b;
    }
  for (core::Vertex v = 0; v < n; ++v) {
    EXPECT_EQ(host.as<ForwardingNode>(v).counters().rejected, 0u);
    EXPECT_EQ(host.as<ForwardingNode>(v).counters().duplicates, 0u);
  }
}

void all_schemes(const core::PlanarGraph& g, const core::CircleEmbedding& phi, const std::vector<core::Point2>& pos,
                 std::uint64_t seed, Tally& tally, const std::string& label) {
  for (core::Scheme s : core::all_schemes) {
    expect_equal(g, phi, pos, s, 0, seed % 2 ? seed : 0, tally, label);
    expect_equal(g, phi, pos, s, 1 + seed % 4, 0, tally, label);
  }
}

std::vector<core::Point2> centres_of(const core::CircleEmbedding& phi) {
  std::vector<core::Point2> out;
  for (const core::Circle& c : phi) out.push_back(core::centre(c));
  return out;
}

// The graph's own drawing (radius-0 circles for power routing, which then equals Euclidean routing).
void on_drawing(const core::GraphInput& in, std::uint64_t seed, Tally& tally, const std::string& label) {
  std::vector<core::Point2> pos;
  for (const auto& p : in.positions) pos.push_back({p.x, p.y});
  ASSERT_EQ(pos.size(), in.graph.num_vertices());
  core::CircleEmbedding phi;
  for (const auto& p : pos) phi.push_back({p.x, p.y, 0.0});
  all_schemes(in.graph, phi, pos, seed, tally, label + " drawing");
}

// The packing: circles for power routing, their centres for the others.
void on_packing(const core::GraphInput& in, std::uint64_t seed, Tally& tally, const std::string& label) {
  const core::PlanarGraph g = core::prepare_for_packing(in);
  const core::PackResult r = core::pack(g);
  ASSERT_EQ(r.status, core::PackStatus::converged);
  all_schemes(g, r.circles, centres_of(r.circles), seed, tally, label + " packing");
}

void on_drawing_and_packing(const core::GraphInput& in, std::uint64_t seed, Tally& tally, const std::string& label) {
  on_drawing(in, seed, tally, label);
  on_packing(in, seed, tally, label);
}

// A drawing moved by random offsets of the order of the edge lengths: no longer plane, yet the
// hop-by-hop decisions must still be core's (loops and dead ends included).
void on_jittered(const core::GraphInput& in, std::uint64_t seed, Tally& tally, const std::string& label) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  std::vector<core::Point2> pos;
  for (const auto& p : in.positions) pos.push_back({p.x + jitter(rng), p.y + jitter(rng)});
  core::CircleEmbedding phi;
  for (const auto& p : pos) phi.push_back({p.x, p.y, 0.05});
  for (core::Scheme s : {core::Scheme::compass, core::Scheme::gfg})
    expect_equal(in.graph, phi, pos, s, 0, seed, tally, label + " jittered");
}

}  // namespace

TEST(ForwardingSchemes, EqualCoreRouteOnTriangulations) {
  Tally tally;
  for (std::size_t n : {5, 12, 30})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const core::GraphInput in = core::random_delaunay_triangulation(n, 50 * n + seed);
      on_drawing_and_packing(in, seed, tally, "tri n=" + std::to_string(n) + " seed=" + std::to_string(seed));
    }
  EXPECT_GT(tally.outcomes[core::RouteOutcome::delivered], 0u);
  EXPECT_GT(tally.outcomes[core::RouteOutcome::ttl_exceeded], 0u);
}

TEST(ForwardingSchemes, EqualCoreRouteOnThreeConnectedGraphs) {
  Tally tally;
  for (std::size_t n : {8, 20, 35})
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const core::GraphInput in = core::random_three_connected(n, 70 * n + seed);
      on_drawing_and_packing(in, seed, tally, "3c n=" + std::to_string(n) + " seed=" + std::to_string(seed));
    }
  EXPECT_GT(tally.outcomes[core::RouteOutcome::dead_end], 0u) << "greedy Euclidean gets stuck on sparse drawings";
  EXPECT_GT(tally.perimeter, 0u) << "GFG's face routing must be exercised";
}

TEST(ForwardingSchemes, EqualCoreRouteOnDrawingsThatAreNotPlane) {
  Tally tally;
  for (std::size_t n : {10, 25})
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      const core::GraphInput in = core::random_three_connected(n, 90 * n + seed);
      on_jittered(in, seed, tally, "3c n=" + std::to_string(n) + " seed=" + std::to_string(seed));
    }
  EXPECT_GT(tally.outcomes[core::RouteOutcome::loop], 0u) << "compass and GFG loops must be exercised";
}

TEST(ForwardingSchemes, CompassDuplicatesAreNotLoops) {
  // A line 1 — 2 — 3: node 2 receives the same compass packet twice with the same hop count (a
  // duplicate of the network): it forwards it once and counts the duplicate.
  NullRuntime rt;
  Recorder sink;
  ForwardingNode f(rt, sink, 2, {1, 3}, {1, 0, 0}, {{0, 0, 0}, {2, 0, 0}});
  RouteMsg m;
  m.packet = 5;
  m.source = 1;
  m.target = 3;
  m.scheme = RouteScheme::compass;
  m.tx = 2;
  m.ttl = 9;
  m.hops = 1;
  f.on_message(1, encode(m));
  f.on_message(1, encode(m));
  EXPECT_EQ(f.counters().forwarded, 1u);
  EXPECT_EQ(f.counters().duplicates, 1u);
  EXPECT_TRUE(sink.ends.empty());
  m.hops = 4;  // the same packet later in its journey: a loop
  f.on_message(1, encode(m));
  ASSERT_TRUE(sink.ends.count(5));
  EXPECT_EQ(sink.ends[5].outcome, PacketOutcome::loop);
  EXPECT_EQ(sink.ends[5].at, 2u);
  EXPECT_EQ(sink.ends[5].hops, 4u);
}

TEST(ForwardingSchemes, RejectsBadPositions) {
  NullRuntime rt;
  Recorder sink;
  const core::Circle c{0, 0, 0.1}, d{0.3, 0, 0.1};
  EXPECT_THROW(ForwardingNode(rt, sink, 1, {2}, c, {d}, {0, 0}, {}), laguerre::core::InternalError);
  EXPECT_THROW(ForwardingNode(rt, sink, 1, {2}, c, {d}, {NAN, 0}, {{1, 0}}), laguerre::core::InternalError);
  EXPECT_THROW(ForwardingNode(rt, sink, 1, {2}, c, {d}, {0, 0}, {{0, INFINITY}}), laguerre::core::InternalError);
  ForwardingNode f(rt, sink, 1, {2}, c, {d}, {0, 0}, {{1, 0}});
  EXPECT_THROW(f.originate({1, 2, d, 4, core::Scheme::gfg, {NAN, 0}}), laguerre::core::InternalError);
  f.originate({2, 2, d, 4, core::Scheme::greedy_euclid, {-1, 0}});  // the neighbour is farther
  EXPECT_EQ(sink.ends[2].outcome, PacketOutcome::dead_end);
  f.originate({3, 1, d, 4, core::Scheme::compass, {5, 5}});  // to itself
  EXPECT_EQ(sink.ends[3].outcome, PacketOutcome::delivered);
  EXPECT_EQ(sink.ends[3].hops, 0u);
}
