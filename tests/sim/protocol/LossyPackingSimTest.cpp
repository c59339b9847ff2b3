// The packing protocol with its reliability layer (PackingNode.hpp, "Loss, duplication and crashes")
// hosted on the simulation kernel: sim's LinkModel loss, duplication and uniform latency, and
// Network::add_crash. Bit for bit with core::pack under loss; every survivor of a crash ends with
// neighbour_failed naming the victim; the event queue always drains; runs are deterministic per seed.

#include <gtest/gtest.h>

#include <bit>
#include <memory>
#include <optional>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/protocols/Reliable.hpp"
#include "laguerre/sim/SimHost.hpp"

using namespace laguerre;
using protocols::PackingNode;
using protocols::PackingOutcome;

namespace {

std::uint64_t bits(double d) { return std::bit_cast<std::uint64_t>(d); }

sim::Network lossy_network(const core::PlanarGraph& g, double loss, double dup) {
  sim::LinkModel link;
  link.latency = sim::LatencyModel::uniform(sim::milliseconds(1), sim::milliseconds(5));
  link.loss = loss;
  link.duplication = dup;
  return sim::network_of(g, link);
}

protocols::PackingParams params(int steps) {
  protocols::PackingParams p;
  p.steps_per_check = steps;
  protocols::enable_lossy_links(p, sim::milliseconds(5));
  return p;
}

struct SimRun {
  std::unique_ptr<sim::SimHost> host;
  sim::RunReport report;
  bool outside = false;
  PackingNode& node(core::Vertex v) {
    protocols::Node& n = host->node(v);
    return static_cast<PackingNode&>(outside ? static_cast<protocols::ReliableNode&>(n).inner() : n);
  }
};

// With `outside`, each node is a ReliableNode wrapping a PackingNode on reliable links (instead of
// the PackingNode's own layer), with the same reliability parameters.
SimRun simulate(const core::PlanarGraph& g, const protocols::PackingParams& p, double loss, double dup, std::uint64_t seed,
             std::optional<std::pair<core::Vertex, sim::Time>> crash = std::nullopt, bool outside = false) {
  sim::Network net = lossy_network(g, loss, dup);
  if (crash) net.add_crash(crash->first, crash->second);
  sim::SimConfig config;
  config.seed = seed;
  config.trace = sim::TraceMode::hash_only;
  SimRun r;
  r.outside = outside;
  protocols::PackingParams reliable_links = p;
  reliable_links.retransmit_after = 0;
  r.host = std::make_unique<sim::SimHost>(
      std::move(net), config, [&](protocols::Runtime& rt, sim::NodeIndex v) -> std::unique_ptr<protocols::Node> {
        const protocols::LocalKnowledge k = protocols::local_knowledge(g, v);
        if (!outside) return std::make_unique<PackingNode>(rt, k, p);
        return std::make_unique<protocols::ReliableNode>(rt, k.neighbours, p, [&](protocols::Runtime& inner) {
          return std::make_unique<PackingNode>(inner, k, reliable_links);
        });
      });
  r.report = r.host->run({.until = sim::seconds(3600)});
  return r;
}

void expect_equals_core(const core::PlanarGraph& g, int steps, double loss, double dup, std::uint64_t seed) {
  SCOPED_TRACE("loss " + std::to_string(loss) + " dup " + std::to_string(dup) + " seed " + std::to_string(seed));
  core::PackOptions opt;
  opt.steps_per_check = steps;
  const core::PackResult core_result = core::pack(g, opt);
  SimRun run = simulate(g, params(steps), loss, dup, seed);
  ASSERT_EQ(run.report.reason, sim::StopReason::queue_empty);
  std::uint64_t duplicates = 0, retransmissions = 0;
  for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
    PackingNode& n = run.node(v);
    SCOPED_TRACE("vertex " + std::to_string(v));
    ASSERT_EQ(n.outcome(), PackingOutcome::converged);
    EXPECT_EQ(n.steps(), static_cast<std::uint32_t>(core_result.iterations));
    EXPECT_EQ(bits(n.h()), bits(core_result.radii[v]));
    EXPECT_EQ(bits(n.placement().circle.x), bits(core_result.circles[v].x));
    EXPECT_EQ(bits(n.placement().circle.y), bits(core_result.circles[v].y));
    EXPECT_EQ(bits(n.placement().circle.r), bits(core_result.circles[v].r));
    EXPECT_EQ(n.local_condition(), core::LocalCondition::holds);
    EXPECT_EQ(n.counters().unexpected, 0u);
    EXPECT_EQ(n.counters().links_failed, 0u);
    duplicates += n.counters().duplicates;
    retransmissions += n.counters().retransmissions;
  }
  if (dup > 0) {
    EXPECT_GT(duplicates, 0u);
  }
  if (loss > 0) {
    EXPECT_GT(retransmissions, 0u);
  }
}

}  // namespace

TEST(LossyPackingSim, TriangulationUnderSimLossAndDuplicationEqualsCore) {
  const core::PlanarGraph g = core::prepare_for_packing(core::random_delaunay_triangulation(60, 4242));
  expect_equals_core(g, 2, 0.0, 0.0, 1);
  expect_equals_core(g, 2, 0.2, 0.05, 2);
  expect_equals_core(g, 1, 0.1, 0.1, 3);
}

TEST(LossyPackingSim, ThreeConnectedUnderSimLossEqualsCore) {
  const core::PlanarGraph g = core::prepare_for_packing(core::random_three_connected(40, 99));
  expect_equals_core(g, 2, 0.2, 0.05, 4);
}

TEST(LossyPackingSim, EverySurvivorOfACrashEndsWithTheFailureStatus) {
  // Seeds × graph kinds × victims × crash times inside the run; deterministic per seed.
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const bool tri = seed % 2 == 0;
    const std::size_t n = 20 + 5 * (seed % 7);
    const core::PlanarGraph g = core::prepare_for_packing(tri ? core::random_delaunay_triangulation(n, seed)
                                                             : core::random_three_connected(n, seed));
    const double loss = 0.05 * static_cast<double>(seed % 5);
    const SimRun clean = simulate(g, params(2), loss, 0.05, seed);
    const sim::Time end = clean.report.simulated_time;
    const auto victim = static_cast<core::Vertex>((seed * 7919) % g.num_vertices());
    const sim::Time at = end * static_cast<sim::Time>(seed % 4) / 10;  // 0, 10, 20 or 30 % of the run
    SCOPED_TRACE("seed " + std::to_string(seed) + " n=" + std::to_string(n) + " victim " + std::to_string(victim) +
                 " at " + std::to_string(at));
    SimRun a = simulate(g, params(2), loss, 0.05, seed, std::pair{victim, at});
    ASSERT_EQ(a.report.reason, sim::StopReason::queue_empty);  // no hang, no endless chatter
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      if (v == victim) continue;
      EXPECT_EQ(a.node(v).outcome(), PackingOutcome::neighbour_failed) << "survivor " << v;
      EXPECT_EQ(a.node(v).suspect(), g.id(victim)) << "survivor " << v;
    }
    if (seed % 4 == 1) {
      SimRun b = simulate(g, params(2), loss, 0.05, seed, std::pair{victim, at});
      EXPECT_EQ(a.host->simulator().trace().hash(), b.host->simulator().trace().hash());
      EXPECT_EQ(a.report.simulated_time, b.report.simulated_time);
    }
  }
}

TEST(LossyPackingSim, LossyRunsAreDeterministicPerSeedAndDifferAcrossSeeds) {
  const core::PlanarGraph g = core::prepare_for_packing(core::random_delaunay_triangulation(30, 17));
  SimRun a = simulate(g, params(2), 0.2, 0.1, 5);
  SimRun b = simulate(g, params(2), 0.2, 0.1, 5);
  SimRun c = simulate(g, params(2), 0.2, 0.1, 6);
  EXPECT_EQ(a.host->simulator().trace().hash(), b.host->simulator().trace().hash());
  EXPECT_EQ(a.report.simulated_time, b.report.simulated_time);
  EXPECT_NE(a.host->simulator().trace().hash(), c.host->simulator().trace().hash());
  for (core::Vertex v = 0; v < g.num_vertices(); ++v)  // the packing itself does not depend on the seed
    EXPECT_EQ(bits(a.node(v).h()), bits(c.node(v).h()));
}

TEST(LossyPackingSim, TheLayerAroundAPackingNodeIsTheLayerInsideIt) {
  // A ReliableNode wrapping a PackingNode on reliable links runs exactly the run of a PackingNode
  // with its own layer: same trace hash, same end, same outcome, with or without a crash.
  const core::PlanarGraph g = core::prepare_for_packing(core::random_three_connected(30, 8));
  for (const bool crash : {false, true}) {
    SCOPED_TRACE(crash ? "crash" : "no crash");
    std::optional<std::pair<core::Vertex, sim::Time>> c;
    if (crash) c = std::pair{core::Vertex{4}, sim::milliseconds(40)};
    SimRun in = simulate(g, params(2), 0.2, 0.1, 9, c);
    SimRun out = simulate(g, params(2), 0.2, 0.1, 9, c, true);
    ASSERT_EQ(out.report.reason, sim::StopReason::queue_empty);
    EXPECT_EQ(in.host->simulator().trace().hash(), out.host->simulator().trace().hash());
    EXPECT_EQ(in.report.simulated_time, out.report.simulated_time);
    EXPECT_EQ(in.report.events_processed, out.report.events_processed);
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      if (crash && v == 4) continue;
      EXPECT_EQ(out.node(v).outcome(), in.node(v).outcome()) << "vertex " << v;
      EXPECT_EQ(out.node(v).outcome(), crash ? PackingOutcome::neighbour_failed : PackingOutcome::converged);
      EXPECT_EQ(bits(out.node(v).h()), bits(in.node(v).h()));
      EXPECT_EQ(out.node(v).finished_at(), in.node(v).finished_at());
    }
  }
}
