// The hyperbolic baseline's set-up as a per-node protocol (protocols/HyperbolicSetup.hpp) on the
// simulation kernel: with constant latency every node ends with the tree parent, depth, q and address
// of core::HyperbolicTreeEmbedding, and its neighbours' addresses; the simulator's message counts per
// type are those of the design (docs/hyperbolic-baseline.md) exactly; with random latencies the nodes
// still agree on a spanning tree and its addresses.

#include <gtest/gtest.h>

#include <vector>

#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/random/Random.hpp"
#include "laguerre/core/routing/HyperbolicEmbedding.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"

using namespace laguerre;
using protocols::MessageType;

namespace {

sim::LinkModel constant_links() { return {}; }  // 1 ms on every link

// A path of n vertices on a line (deep: the sweep's root is its middle, q = 3).
core::PlanarGraph path(std::size_t n) {
  std::vector<std::vector<core::Vertex>> rot(n);
  for (core::Vertex v = 0; v + 1 < n; ++v) rot[v].push_back(v + 1), rot[v + 1].push_back(v);
  return core::PlanarGraph::from_rotation(rot);
}

// A random recursive tree (vertex v hangs on a uniform earlier vertex): any rotation is planar.
core::PlanarGraph random_tree(std::size_t n, std::uint64_t seed) {
  core::SplitMix64 rng(seed);
  std::vector<std::vector<core::Vertex>> rot(n);
  for (core::Vertex v = 1; v < n; ++v) {
    const auto p = static_cast<core::Vertex>(rng.next() % v);
    rot[p].push_back(v), rot[v].push_back(p);
  }
  return core::PlanarGraph::from_rotation(rot);
}

std::vector<core::PlanarGraph> graphs() {
  std::vector<core::PlanarGraph> out;
  for (std::uint64_t s = 0; s < 12; ++s) {
    out.push_back(core::random_delaunay_triangulation(20 + 15 * s, 100 + s).graph);
    out.push_back(core::random_three_connected(20 + 15 * s, 200 + s).graph);
    out.push_back(random_tree(10 + 9 * s, 300 + s));
  }
  out.push_back(path(61));
  out.push_back(path(2));
  return out;
}

std::uint64_t sent(const scenarios::HyperbolicSetupOutcome& o, MessageType t) {
  const auto k = static_cast<std::size_t>(t);
  return k < o.by_phase.size() ? o.by_phase[k].messages_sent : 0;
}
std::uint64_t bytes(const scenarios::HyperbolicSetupOutcome& o, MessageType t) {
  const auto k = static_cast<std::size_t>(t);
  return k < o.by_phase.size() ? o.by_phase[k].bytes_sent : 0;
}

// Everything the nodes hold equals the central embedding's; the counts are the design's.
void expect_equal_to_core(const core::PlanarGraph& g, const core::HyperbolicTreeEmbedding& e,
                          const scenarios::HyperbolicSetupOutcome& o) {
  const std::size_t n = g.num_vertices(), m = g.num_edges();
  ASSERT_EQ(o.done_nodes, n);
  EXPECT_EQ(o.rejected, 0u);
  EXPECT_EQ(o.inconsistent_tables, 0u);
  ASSERT_EQ(o.root, e.root());
  ASSERT_EQ(o.tiling_degree, e.tiling_degree());
  std::uint64_t state = 0, address_bytes = 0;
  const std::size_t width = core::hyperbolic_side_bits(e.tiling_degree());
  const auto packed = [&](core::Vertex v) { return (e.address_bits(v) + 7) / 8; };
  for (core::Vertex v = 0; v < n; ++v) {
    EXPECT_EQ(o.parents[v], e.parent(v)) << v;
    EXPECT_EQ(o.depths[v], e.depth(v)) << v;
    ASSERT_EQ(o.addresses[v], e.address(v)) << v;
    EXPECT_EQ(o.addresses[v].size() * width, e.address_bits(v));
    state += 12 + packed(v);
    for (const core::Vertex u : g.neighbours(v)) state += 4 + packed(u);
    if (v != e.root()) address_bytes += 15 + packed(v);  // to the child from its parent
  }
  EXPECT_EQ(o.state_bytes, state);
  // Per type: a BFS is a flood of 2|E| (one message per neighbour per node) and an echo of |V| − 1.
  const std::uint64_t bfs = e.swept() ? 3 : 1, tree_edges = n - 1;
  EXPECT_EQ(sent(o, MessageType::hyperbolic_sweep), bfs * 2 * m);
  EXPECT_EQ(sent(o, MessageType::hyperbolic_echo), bfs * tree_edges);
  EXPECT_EQ(sent(o, MessageType::hyperbolic_root), e.swept() ? e.sweep_start_depth() + (e.sweep_length() + 1) / 2 : 0);
  EXPECT_EQ(sent(o, MessageType::hyperbolic_address), tree_edges + 2 * (m - tree_edges));
  EXPECT_EQ(o.messages, core::hyperbolic_setup_cost(e, m).messages);
  EXPECT_LE(sent(o, MessageType::hyperbolic_sweep) + sent(o, MessageType::hyperbolic_echo), bfs * (2 * m + n));
  // Bytes: fixed-size messages at their size; addresses down the tree as computed above, over the
  // non-tree edges each sender's own.
  EXPECT_EQ(bytes(o, MessageType::hyperbolic_sweep), 15 * sent(o, MessageType::hyperbolic_sweep));
  EXPECT_EQ(bytes(o, MessageType::hyperbolic_echo), 15 * sent(o, MessageType::hyperbolic_echo));
  EXPECT_EQ(bytes(o, MessageType::hyperbolic_root), 7 * sent(o, MessageType::hyperbolic_root));
  std::uint64_t table_bytes = 0;
  for (core::Vertex v = 0; v < n; ++v)
    for (const core::Vertex u : g.neighbours(v))
      if (e.parent(u) != v && e.parent(v) != u) table_bytes += 15 + packed(v);
  EXPECT_EQ(bytes(o, MessageType::hyperbolic_address), address_bytes + table_bytes);
  EXPECT_EQ(o.bytes, bytes(o, MessageType::hyperbolic_sweep) + bytes(o, MessageType::hyperbolic_echo) +
                         bytes(o, MessageType::hyperbolic_root) + bytes(o, MessageType::hyperbolic_address));
}

}  // namespace

TEST(HyperbolicSetupSim, NodesHoldTheCentralEmbeddingBitForBitAndTheDesignsCounts) {
  std::size_t checked = 0;
  for (const core::PlanarGraph& g : graphs()) {
    SCOPED_TRACE(std::to_string(g.num_vertices()) + " vertices, " + std::to_string(g.num_edges()) + " edges");
    const core::HyperbolicTreeEmbedding e(g);
    expect_equal_to_core(g, e, scenarios::run_hyperbolic_setup(g, {}, constant_links(), 7));
    ++checked;
  }
  EXPECT_EQ(checked, 38u);
}

TEST(HyperbolicSetupSim, AGivenRootSkipsTheDoubleSweep) {
  for (std::uint64_t s = 0; s < 6; ++s) {
    const core::PlanarGraph g = core::random_three_connected(40 + 10 * s, 400 + s).graph;
    core::HyperbolicOptions opt;
    opt.root = static_cast<core::Vertex>((17 * s + 3) % g.num_vertices());
    const core::HyperbolicTreeEmbedding e(g, opt);
    ASSERT_FALSE(e.swept());
    expect_equal_to_core(g, e, scenarios::run_hyperbolic_setup(g, {}, constant_links(), 7, opt.root));
  }
}

TEST(HyperbolicSetupSim, RandomLatenciesStillGiveOneSpanningTreeAndConsistentAddresses) {
  sim::LinkModel jitter;
  jitter.latency = sim::LatencyModel::uniform(sim::milliseconds(1), sim::milliseconds(9));
  std::size_t differs = 0;
  for (std::uint64_t s = 0; s < 8; ++s) {
    const core::PlanarGraph g = core::random_delaunay_triangulation(60 + 20 * s, 500 + s).graph;
    const auto o = scenarios::run_hyperbolic_setup(g, {}, jitter, 11 + s);
    const std::size_t n = g.num_vertices();
    ASSERT_EQ(o.done_nodes, n);
    EXPECT_EQ(o.rejected, 0u);
    EXPECT_EQ(o.inconsistent_tables, 0u);
    ASSERT_LT(o.root, n);
    EXPECT_TRUE(o.addresses[o.root].empty());
    std::size_t sides_needed = 3;
    std::vector<std::size_t> children(n, 0);
    for (core::Vertex v = 0; v < n; ++v) {
      if (v == o.root) continue;
      const core::Vertex p = o.parents[v];
      ASSERT_LT(p, n);
      EXPECT_EQ(o.depths[v], o.depths[p] + 1);  // labels increase down the tree: no cycle, one tree
      ASSERT_EQ(o.addresses[v].size(), o.depths[v]);
      EXPECT_TRUE(std::equal(o.addresses[p].begin(), o.addresses[p].end(), o.addresses[v].begin()));  // parent's, then a side
      EXPECT_LT(o.addresses[v].back(), o.tiling_degree);
      ++children[p];
    }
    for (core::Vertex v = 0; v < n; ++v) sides_needed = std::max(sides_needed, children[v] + (v == o.root ? 0 : 1));
    EXPECT_EQ(o.tiling_degree, sides_needed);
    const core::HyperbolicTreeEmbedding e(g);
    for (core::Vertex v = 0; v < n; ++v) differs += o.parents[v] != e.parent(v);
  }
  std::printf("[ figures  ] random latencies: %zu parents differ from the BFS tree of constant latency\n", differs);
}
