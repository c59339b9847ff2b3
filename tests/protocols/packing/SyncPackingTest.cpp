#include <gtest/gtest.h>

#include <optional>

#include "laguerre/core/Error.hpp"
#include "../NullRuntime.hpp"
#include "../SyncCompare.hpp"
#include "../TestGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {
bool has_interior(const core::PlanarGraph& g) {
  for (core::Vertex v = 0; v < g.num_vertices(); ++v)
    if (!g.is_boundary(v)) return true;
  return false;
}
}  // namespace

TEST(LocalKnowledge, MatchesTheGraph) {
  const core::PlanarGraph g = delaunay(30, 2);
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    const LocalKnowledge k = local_knowledge(g, v);
    EXPECT_EQ(k.id, g.id(v));
    ASSERT_EQ(k.neighbours.size(), g.degree(v));
    EXPECT_EQ(k.neighbours[0], g.id(g.neighbours(v)[0]));
    EXPECT_EQ(k.boundary, g.is_boundary(v));
    if (g.is_boundary(v)) {
      // w1 = the neighbour after the outer wedge is where LPD starts listing (lpd_first_dart).
      ASSERT_LT(k.outer_gap, k.neighbours.size());
      EXPECT_EQ(k.neighbours[(k.outer_gap + 1) % k.neighbours.size()], g.id(g.head(core::lpd_first_dart(g, v))));
    } else {
      EXPECT_EQ(k.outer_gap, LocalKnowledge::no_gap);
    }
  }
}

TEST(PackingNode, RejectsInconsistentKnowledge) {
  laguerre::protocols::testing::NullRuntime rt;
  EXPECT_THROW(PackingNode(rt, LocalKnowledge{1, {}, false, LocalKnowledge::no_gap, {}, {}}, {}), laguerre::core::InternalError);
  EXPECT_THROW(PackingNode(rt, LocalKnowledge{1, {2, 1}, false, LocalKnowledge::no_gap, {}, {}}, {}), laguerre::core::InternalError);
  EXPECT_THROW(PackingNode(rt, LocalKnowledge{1, {2, 3, 2}, false, LocalKnowledge::no_gap, {}, {}}, {}), laguerre::core::InternalError);
  EXPECT_THROW(PackingNode(rt, LocalKnowledge{1, {2, 3}, true, 5, {}, {}}, {}), laguerre::core::InternalError);
  EXPECT_THROW(PackingNode(rt, LocalKnowledge{1, {2, 3}, false, 0, {}, {}}, {}), laguerre::core::InternalError);
  PackingParams bad;
  bad.steps_per_check = 0;
  EXPECT_THROW(PackingNode(rt, LocalKnowledge{1, {2, 3}, false, LocalKnowledge::no_gap, {}, {}}, bad), laguerre::core::InternalError);
}

TEST(PackingNode, MalformedAndForeignMessagesAreCountedNotTrusted) {
  const core::PlanarGraph g = delaunay(12, 3);
  DequeHost host(g, PackingParams{});
  PackingNode& n = host.node(0);
  n.on_start();
  const std::byte junk[3] = {std::byte{wire_version}, std::byte{5}, std::byte{0}};
  n.on_message(g.id(g.neighbours(0)[0]), junk);
  EXPECT_EQ(n.counters().decode[static_cast<std::size_t>(DecodeStatus::truncated)], 1u);
  const std::vector<std::byte> ok = encode(DepthMsg{false, 0, 987654321});
  n.on_message(987654321, ok);
  EXPECT_EQ(n.counters().not_a_neighbour, 1u);
  n.on_timer(7);
  EXPECT_EQ(n.counters().unexpected, 1u);
}

TEST(SyncPacking, ElectionPicksCoresRoot) {
  for (core::RootRule rule : {core::RootRule::deepest, core::RootRule::smallest_id})
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      const core::PlanarGraph g = delaunay(20 + 7 * seed, seed);
      PackingParams p;
      p.root = rule;
      p.max_iterations = 0;  // set-up and round 0 only
      DequeHost host(g, p);
      host.run(seed);
      const core::Vertex root = core::choose_root(core::PackingComplex::from_graph(g), rule);
      std::size_t roots = 0;
      for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
        roots += host.node(v).is_root();
        EXPECT_EQ(host.node(v).is_root(), v == root) << "seed " << seed;
        EXPECT_EQ(host.node(v).phase(), PackingPhase::finished);
      }
      EXPECT_EQ(roots, 1u);
    }
}

TEST(SyncPacking, EqualsCoreBitForBitFifo) {
  for (std::size_t n : {4, 5, 8, 16, 40, 90})
    for (std::uint64_t seed = 1; seed <= 4; ++seed)
      for (int steps : {1, 3}) {
        const core::PlanarGraph g = delaunay(n, seed);
        if (!has_interior(g)) continue;
        PackingParams p;
        p.steps_per_check = steps;
        expect_sync_equals_core(g, p, 0, "n=" + std::to_string(n) + " seed=" + std::to_string(seed) + " N=" + std::to_string(steps));
      }
}

TEST(SyncPacking, EqualsCoreUnderRandomDeliveryOrder) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const core::PlanarGraph g = delaunay(30 + 10 * seed, seed + 100);
    PackingParams p;
    p.steps_per_check = static_cast<int>(seed % 3) + 1;
    expect_sync_equals_core(g, p, seed, "shuffled seed=" + std::to_string(seed));
  }
}

TEST(SyncPacking, IterationCapAndExactUpdate) {
  const core::PlanarGraph g = delaunay(60, 9);
  expect_cap_and_exact_update_equal_core(g, 3, 0);
  PackingParams p;
  p.max_iterations = 7;
  p.steps_per_check = 4;  // the last round is partial (3 steps), as in core::pack
  expect_sync_equals_core(g, p, 0, "cap 7 N=4");
  p.max_iterations = 100000;
  p.steps_per_check = 2;
  p.root = core::RootRule::smallest_id;
  expect_sync_equals_core(g, p, 3, "smallest id root");
}

// The layout wave is event-driven with Dijkstra–Scholten termination (docs/protocol.md, "Set-up"):
// StartMsg to the root's neighbours, a WaveMsg to every neighbour each time a vertex's placement
// estimate changes, one acknowledgement (ShapeMsg up) per StartMsg / WaveMsg, the shape broadcast
// down the tree. The pulse-synchronized wave it replaces sent deg(v)·(wave(v) + 1) WaveMsg per vertex,
// a StartMsg flood (Σ deg − (n − 1)) and a shape convergecast and broadcast (2(n − 1)): O(n · diameter)
// messages against O(edges) here. The waves, parents and every later bit stay core's
// (EqualsCoreBitForBit*); this counts the messages, in FIFO and in shuffled order.
TEST(SyncPacking, LayoutWaveCostsFewerMessagesThanThePulses) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const core::PlanarGraph g = delaunay(400, seed);
    PackingParams p;
    p.max_iterations = 0;
    const core::PackResult r = core::pack(g, reference_options(p));
    const std::uint64_t n = g.num_vertices(), darts = 2 * g.num_edges();
    std::uint64_t pulses = 0;
    for (core::Vertex v = 0; v < n; ++v) pulses += std::uint64_t{g.degree(v)} * (r.layout.wave[v] + 2);
    pulses += n - 1;
    for (std::uint64_t order : {std::uint64_t{0}, seed}) {
      SCOPED_TRACE("seed " + std::to_string(seed) + " order " + std::to_string(order));
      DequeHost host(g, p);
      host.run(order);
      const std::uint64_t wave = host.delivered(MessageType::start) + host.delivered(MessageType::wave);
      const std::uint64_t acks = host.delivered(MessageType::shape) - (n - 1);  // less the broadcast down
      EXPECT_EQ(acks, wave) << "one acknowledgement per wave message";
      EXPECT_EQ(host.delivered(MessageType::height), 0u) << "the height convergecast is radius-flood's";
      // Measured: FIFO 5.8× fewer than the pulses (1.2 WaveMsg per dart), shuffled 1.8–2.2× (3.2–3.9).
      EXPECT_LT(wave + acks + (n - 1), pulses / (order == 0 ? 4 : 1));
      if (order == 0) {
        EXPECT_LE(2 * wave, 3 * darts) << "about one estimate per vertex with equal delays";
      }
      for (core::Vertex v = 0; v < n; ++v) {
        EXPECT_EQ(host.node(v).wave(), r.layout.wave[v]);
        EXPECT_EQ(host.node(v).counters().unexpected, 0u);
      }
    }
  }
}

// The depth BFS (docs/protocol.md, "Set-up"): estimates that only decrease, each acknowledged
// (Dijkstra–Scholten), so with equal delays (FIFO) every vertex's first estimate is its depth and it
// sends it once: exactly one estimate and one acknowledgement per dart, 2·darts DepthMsg, where the
// pulse BFS it replaces sent Σ deg(v)·(d(v) + 1). In shuffled order a vertex may take several
// estimates (and send corrections to a former parent); the depths and the BFS parents (the first
// neighbour in K order one shallower) are the same in every order, on triangulations and on K.
TEST(SyncPacking, DepthBfsCostsAnEstimateAndAnAckPerDartInFifoOrder) {
  auto expect_bfs = [](const core::PlanarGraph& g, DequeHost& host) {
    const core::PackingComplex k = core::PackingComplex::from_graph(g);
    const auto depth = boundary_depths(k.graph);
    const auto ids = protocol_ids(g, k);
    for (core::Vertex v = 0; v < k.graph.num_vertices(); ++v) {
      SCOPED_TRACE("vertex " + std::to_string(v));
      NodeId parent = ids[v];  // the boundary's
      for (core::Vertex w : k.graph.neighbours(v))
        if (depth[v] > 0 && depth[w] + 1 == depth[v]) {
          parent = ids[w];
          break;
        }
      const std::optional<VertexState> st = v < g.num_vertices() ? host.node(v).state() : hosted_state(host, ids[v]);
      ASSERT_TRUE(st.has_value());
      EXPECT_EQ(st->depth, depth[v]);
      EXPECT_EQ(st->bfs_parent, parent);
    }
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) EXPECT_EQ(host.node(v).counters().unexpected, 0u);
  };
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const core::PlanarGraph g = delaunay(100 * seed + 100, seed);
    PackingParams p;
    p.max_iterations = 0;
    const std::uint64_t n = g.num_vertices(), darts = 2 * g.num_edges();
    const auto depth = boundary_depths(g);
    std::uint64_t pulses = 0;
    for (core::Vertex v = 0; v < n; ++v) pulses += std::uint64_t{g.degree(v)} * (depth[v] + 1);
    for (std::uint64_t order : {std::uint64_t{0}, seed, seed + 10}) {
      SCOPED_TRACE("seed " + std::to_string(seed) + " order " + std::to_string(order));
      DequeHost host(g, p);
      host.run(order);
      const std::uint64_t sent = host.delivered(MessageType::depth);
      // Measured shuffled: 4.0–5.2 DepthMsg per dart (pulses: 3.5–4.3 per dart here, growing with the depth).
      if (order == 0) {
        EXPECT_EQ(sent, 2 * darts);
        EXPECT_LT(sent, pulses);
      } else {
        EXPECT_LE(sent, 8 * darts);
      }
      EXPECT_GE(sent, 2 * darts);
      expect_bfs(g, host);
    }
  }
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {  // K: face vertices take part as vertices
    const core::PlanarGraph g = three_connected(60 + 20 * seed, seed);
    PackingParams p;
    p.max_iterations = 0;
    for (std::uint64_t order : {std::uint64_t{0}, seed}) {
      SCOPED_TRACE("3-connected seed " + std::to_string(seed) + " order " + std::to_string(order));
      DequeHost host(g, p);
      host.run(order);
      expect_bfs(g, host);
    }
  }
}

// The election (docs/protocol.md, "Set-up"): one report per vertex up the BFS forest, the boundary
// ring (each key forwarded only while it is the best its vertex has seen: at most b keys per ring
// link, b the boundary's size) and one path down of the root's depth; the echo with extinction it
// replaces sent a token on every edge for every wave a vertex joined (Θ(edges · depth) here).
TEST(SyncPacking, ElectionCostsAReportPerVertexAndTheRing) {
  for (core::RootRule rule : {core::RootRule::deepest, core::RootRule::smallest_id})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const core::PlanarGraph g = delaunay(400, seed);
      PackingParams p;
      p.root = rule;
      p.max_iterations = 0;
      std::uint64_t b = 0;
      for (core::Vertex v = 0; v < g.num_vertices(); ++v) b += g.is_boundary(v);
      const auto depth = boundary_depths(g);
      const core::Vertex root = core::choose_root(core::PackingComplex::from_graph(g), rule);
      for (std::uint64_t order : {std::uint64_t{0}, seed}) {
        SCOPED_TRACE("seed " + std::to_string(seed) + " order " + std::to_string(order));
        DequeHost host(g, p);
        host.run(order);
        const std::uint64_t reports = g.num_vertices() - b;
        // Before it, the depth BFS's tokens: `settled` round the ring (from once round to b·(b+1)/2
        // in all, Chang–Roberts) and `final`, n + 1 in every order (both ways round the ring, then
        // once to every interior vertex).
        const std::uint64_t final_tokens = g.num_vertices() + 1;
        EXPECT_GE(host.delivered(MessageType::election), reports + b + depth[root] + b + final_tokens);
        EXPECT_LE(host.delivered(MessageType::election), reports + b * b + depth[root] + b * (b + 1) / 2 + final_tokens);
        for (core::Vertex v = 0; v < g.num_vertices(); ++v) EXPECT_EQ(host.node(v).is_root(), v == root);
      }
    }
}
