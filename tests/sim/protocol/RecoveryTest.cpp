// Crash with recovery (Network::add_crash with a recovery time, protocols::Node::on_recover): the
// packing protocol's reliability layer masks an outage shorter than the detection time (the run
// converges bit for bit with core::pack); after a longer outage the survivors have detected the crash
// and ended with neighbour_failed, and the recovered node ends with a final outcome too: the event
// queue drains, never a hang. Runs are deterministic per seed (trace hash).

#include <gtest/gtest.h>

#include <bit>
#include <memory>
#include <optional>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/sim/SimHost.hpp"

using namespace laguerre;
using protocols::PackingNode;
using protocols::PackingOutcome;

namespace {

struct Outage {
  core::Vertex victim = 0;
  sim::Time at = 0;
  sim::Time back = 0;
};

struct SimRun {
  std::unique_ptr<sim::SimHost> host;
  sim::RunReport report;
  PackingNode& node(core::Vertex v) { return static_cast<PackingNode&>(host->node(v)); }
};

SimRun simulate(const core::PlanarGraph& g, double loss, std::uint64_t seed, std::optional<Outage> outage) {
  sim::LinkModel link;
  link.latency = sim::LatencyModel::uniform(sim::milliseconds(1), sim::milliseconds(5));
  link.loss = loss;
  link.duplication = 0.05;
  sim::Network net = sim::network_of(g, link);
  if (outage) net.add_crash(outage->victim, outage->at, outage->back);
  protocols::PackingParams p;
  p.steps_per_check = 2;
  protocols::enable_lossy_links(p, sim::milliseconds(5));
  sim::SimConfig config;
  config.seed = seed;
  config.trace = sim::TraceMode::hash_only;
  SimRun r;
  r.host = std::make_unique<sim::SimHost>(std::move(net), config, [&](protocols::Runtime& rt, sim::NodeIndex v) {
    return std::make_unique<PackingNode>(rt, protocols::local_knowledge(g, v), p);
  });
  r.report = r.host->run({.until = sim::seconds(3600)});
  return r;
}

std::uint64_t bits(double d) { return std::bit_cast<std::uint64_t>(d); }

core::PlanarGraph graph(std::uint64_t seed) {
  return core::prepare_for_packing(seed % 2 ? core::random_three_connected(30, seed)
                                            : core::random_delaunay_triangulation(30, seed));
}

}  // namespace

TEST(RecoverySim, AShortOutageIsMaskedAndTheRunConvergesBitForBit) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const core::PlanarGraph g = graph(seed);
    const SimRun clean = simulate(g, 0.1, seed, std::nullopt);
    core::PackOptions opt;
    opt.steps_per_check = 2;
    const core::PackResult want = core::pack(g, opt);
    // 120 ms down, a third into the run: far below the detection time (24 backed-off retransmissions).
    // (60 ms missed every message and timer of vertex 7 once the set-up got shorter.)
    const Outage o{static_cast<core::Vertex>(seed * 7 % g.num_vertices()), clean.report.simulated_time / 3,
                   clean.report.simulated_time / 3 + sim::milliseconds(120)};
    SCOPED_TRACE("seed " + std::to_string(seed) + " victim " + std::to_string(o.victim));
    SimRun r = simulate(g, 0.1, seed, o);
    ASSERT_EQ(r.report.reason, sim::StopReason::queue_empty);
    EXPECT_GT(r.host->simulator().traffic().total().messages_dropped + r.host->simulator().timers_dropped(), 0u)
        << "the outage dropped traffic or timers";
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      ASSERT_EQ(r.node(v).outcome(), PackingOutcome::converged) << "vertex " << v;
      EXPECT_EQ(r.node(v).steps(), static_cast<std::uint32_t>(want.iterations));
      EXPECT_EQ(bits(r.node(v).placement().circle.r), bits(want.circles[v].r)) << "vertex " << v;
      EXPECT_EQ(r.node(v).counters().links_failed, 0u);
    }
  }
}

TEST(RecoverySim, ALongOutageEndsEveryNodeWithAFinalStatus) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const core::PlanarGraph g = graph(seed);
    const SimRun clean = simulate(g, 0.05 * static_cast<double>(seed % 3), seed, std::nullopt);
    // Down for 5 s from a quarter into the run: the neighbours detect the crash long before it is back.
    const Outage o{static_cast<core::Vertex>(seed * 11 % g.num_vertices()), clean.report.simulated_time / 4,
                   clean.report.simulated_time / 4 + sim::seconds(5)};
    SCOPED_TRACE("seed " + std::to_string(seed) + " victim " + std::to_string(o.victim));
    SimRun r = simulate(g, 0.05 * static_cast<double>(seed % 3), seed, o);
    ASSERT_EQ(r.report.reason, sim::StopReason::queue_empty) << "no hang, no endless chatter";
    EXPECT_GT(r.report.simulated_time, o.back) << "the node came back and ended after its recovery";
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      EXPECT_TRUE(r.node(v).is_final()) << "vertex " << v;
      EXPECT_EQ(r.node(v).outcome(), PackingOutcome::neighbour_failed) << "vertex " << v;
      if (v != o.victim) {
        EXPECT_EQ(r.node(v).suspect(), g.id(o.victim)) << "the survivors detected the crash";
      }
    }
    EXPECT_GE(r.node(o.victim).finished_at(), o.back);
    if (seed <= 2) {
      SimRun again = simulate(g, 0.05 * static_cast<double>(seed % 3), seed, o);
      EXPECT_EQ(r.host->simulator().trace().hash(), again.host->simulator().trace().hash());
      EXPECT_EQ(r.report.simulated_time, again.report.simulated_time);
      SimRun other = simulate(g, 0.05 * static_cast<double>(seed % 3), seed + 100, o);
      EXPECT_NE(r.host->simulator().trace().hash(), other.host->simulator().trace().hash());
    }
  }
}
