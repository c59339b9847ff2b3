// The parallel kernel gives the sequential run, bit for bit: the same trace (hash and records), the
// same traffic counters per node and phase, the same event count, end time and timer drops, and
// the same per-node results, on 1, 2 and 4 ranks (CTest runs this program under each), with METIS
// and with adversarial partitions, on PHOLD, a timer-driven lossy, duplicating, crashing gossip, and
// the packing protocol (synchronous, lossy, crashing, asynchronous) through SimHost; and the same
// when each rank builds and holds only its own nodes (a Simulator or SimHost built for its part).

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/sim/SimHost.hpp"
#include "laguerre/sim/mpi/Parallel.hpp"
#include "laguerre/sim/mpi/Phold.hpp"

namespace laguerre::sim::mpi {
namespace {

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int world_size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

/// Partitions of the network for the current number of ranks.
enum class Split { metis, round_robin, halves_reversed };
std::vector<int> split(const Network& net, Split how) {
  const int size = world_size();
  std::vector<int> owner(net.node_count());
  switch (how) {
    case Split::metis: return metis_partition(net, size);
    case Split::round_robin:  // every link is cut: the most exchange there can be
      for (std::size_t v = 0; v < owner.size(); ++v) owner[v] = static_cast<int>(v % static_cast<std::size_t>(size));
      return owner;
    case Split::halves_reversed:  // contiguous blocks, the last nodes on rank 0
      for (std::size_t v = 0; v < owner.size(); ++v) {
        owner[v] = size - 1 - static_cast<int>(v * static_cast<std::size_t>(size) / owner.size());
      }
      return owner;
  }
  return owner;
}

/// The number of nodes `owner` gives this rank.
std::size_t my_share(const std::vector<int>& owner) {
  return static_cast<std::size_t>(std::count(owner.begin(), owner.end(), world_rank()));
}

std::vector<std::byte> bytes_of(std::initializer_list<std::uint64_t> values) {
  std::vector<std::byte> out(values.size() * 8);
  std::size_t i = 0;
  for (const std::uint64_t v : values) std::memcpy(out.data() + 8 * i++, &v, 8);
  return out;
}

/// Compares a parallel report (rank 0) with the sequential simulator that ran the same thing.
void expect_same_run(const Simulator& seq, const RunReport& seq_report, const ParallelReport& par) {
  EXPECT_EQ(par.run.reason, seq_report.reason);
  EXPECT_EQ(par.run.simulated_time, seq_report.simulated_time);
  EXPECT_EQ(par.run.events_processed, seq_report.events_processed);
  EXPECT_EQ(par.timers_dropped, seq.timers_dropped());
  EXPECT_EQ(par.trace.hash(), seq.trace().hash()) << std::hex << par.trace.hash() << " vs " << seq.trace().hash();
  EXPECT_EQ(par.trace.count(), seq.trace().count());
  if (seq.trace().mode() == TraceMode::records) {
    ASSERT_EQ(par.trace.records().size(), seq.trace().records().size());
    for (std::size_t i = 0; i < par.trace.records().size(); ++i) {
      ASSERT_EQ(par.trace.records()[i], seq.trace().records()[i]) << "record " << i;
    }
  }
  ASSERT_EQ(par.traffic.phase_count(), seq.traffic().phase_count());
  for (std::size_t p = 0; p < seq.traffic().phase_count(); ++p) {
    for (NodeIndex v = 0; v < seq.network().node_count(); ++v) {
      ASSERT_EQ(par.traffic.get(v, static_cast<Phase>(p)), seq.traffic().get(v, static_cast<Phase>(p)))
          << "node " << v << " phase " << p;
    }
  }
  const int ranks = world_size();
  EXPECT_EQ(par.ranks, ranks);
  ASSERT_EQ(par.nodes.size(), static_cast<std::size_t>(ranks));
  std::uint64_t nodes = 0, events = 0;
  for (int r = 0; r < ranks; ++r) {
    nodes += par.nodes[static_cast<std::size_t>(r)];
    events += par.events[static_cast<std::size_t>(r)];
  }
  EXPECT_EQ(nodes, seq.network().node_count());
  EXPECT_EQ(events, seq_report.events_processed);
}

// --- PHOLD -------------------------------------------------------------------------------------

struct PholdCase {
  LinkModel link;
  unsigned population;
  Time until;
  Split how;
};

void check_phold(const PholdCase& c) {
  const NodeIndex side = 10;
  Phold seq_model(side * side, c.population);
  Simulator seq(torus(side, c.link), SimConfig{.seed = 7, .trace = TraceMode::records}, seq_model);
  const RunReport seq_report = seq.run({.until = c.until});

  Phold par_model(side * side, c.population);
  Simulator part(torus(side, c.link), SimConfig{.seed = 7, .trace = TraceMode::records}, par_model);
  ParallelRun run(part, split(part.network(), c.how));
  const ParallelReport par = run.run({.until = c.until});
  const auto states = run.gather_nodes([&](NodeIndex v) {
    return bytes_of({par_model.state(v).received, par_model.state(v).digest});
  });
  if (world_rank() != 0) return;
  EXPECT_GT(seq.trace().count(), 1000u);
  expect_same_run(seq, seq_report, par);
  for (NodeIndex v = 0; v < side * side; ++v) {
    EXPECT_EQ(states[v], bytes_of({seq_model.state(v).received, seq_model.state(v).digest})) << "node " << v;
  }
  if (world_size() > 1) {
    EXPECT_GT(par.remote_copies, 0u);
    EXPECT_GT(par.cut_links, 0u);
    EXPECT_EQ(par.lookahead, c.link.latency.min_latency(0));
    EXPECT_GT(par.windows, 10u);
  } else {
    EXPECT_EQ(par.remote_copies, 0u);
    EXPECT_EQ(par.lookahead, time_max);
  }
}

TEST(ParallelPhold, MetisPartitionGivesTheSequentialRun) {
  check_phold({phold_links(), 2, seconds(20), Split::metis});
}

TEST(ParallelPhold, EveryLinkCutGivesTheSequentialRun) {
  check_phold({phold_links(), 2, seconds(20), Split::round_robin});
}

TEST(ParallelPhold, ConstantLatencyTiesEverywhereGiveTheSequentialRun) {
  // Every event falls on a multiple of 100 ms: equal timestamps at one node are the rule, so this
  // checks that ties are broken by the event keys, not by the order copies arrive from ranks.
  check_phold({LinkModel{LatencyModel::constant(milliseconds(100)), 0, 0}, 3, seconds(5), Split::halves_reversed});
  check_phold({LinkModel{LatencyModel::constant(milliseconds(100)), 0, 0}, 3, seconds(5), Split::round_robin});
}

TEST(ParallelPhold, LossAndDuplicationGiveTheSequentialRun) {
  check_phold({LinkModel{LatencyModel::uniform(milliseconds(1), milliseconds(3)), 0.1, 0.1}, 4, seconds(1),
               Split::metis});
}

TEST(ParallelPhold, SimulatorsBuiltForTheirPartsGiveTheSequentialRun) {
  // Each rank's Simulator and model hold only its nodes (and their links): same run, bit for bit.
  const NodeIndex side = 10;
  const LinkModel link{LatencyModel::uniform(milliseconds(1), milliseconds(3)), 0.1, 0.1};
  for (const Split how : {Split::metis, Split::round_robin}) {
    Phold seq_model(side * side, 4);
    Simulator seq(torus(side, link), SimConfig{.seed = 7, .trace = TraceMode::records}, seq_model);
    const RunReport seq_report = seq.run({.until = seconds(1)});
    Network net = torus(side, link);
    std::vector<int> owner = split(net, how);
    const std::size_t share = my_share(owner);
    Phold par_model(share, 4);
    Simulator part(std::move(net), SimConfig{.seed = 7, .trace = TraceMode::records}, par_model,
                   owned_flags(owner, world_rank()));
    EXPECT_EQ(part.local_count(), share);
    ParallelRun run(part, owner);
    const ParallelReport par = run.run({.until = seconds(1)});
    const auto states = run.gather_nodes([&](NodeIndex v) {
      const Phold::NodeState& st = par_model.state(part.local_index(v));
      return bytes_of({st.received, st.digest});
    });
    if (world_rank() != 0) continue;
    expect_same_run(seq, seq_report, par);
    EXPECT_EQ(par.held_nodes, par.nodes);  // every rank held its share, no more
    for (NodeIndex v = 0; v < side * side; ++v) {
      EXPECT_EQ(states[v], bytes_of({seq_model.state(v).received, seq_model.state(v).digest})) << "node " << v;
    }
  }
}

TEST(ParallelPhold, ASimulatorBuiltForAPartRefusesAnotherPartAndARunAlone) {
  Phold model(8, 1);
  std::vector<std::uint8_t> even(16), odd(16);
  for (std::size_t v = 0; v < 16; ++v) even[v] = v % 2 == 0, odd[v] = v % 2 == 1;
  Simulator part(torus(4, phold_links()), SimConfig{.seed = 1}, model, even);
  EXPECT_EQ(part.local_count(), 8u);
  EXPECT_EQ(part.local_node(3), 6u);
  EXPECT_EQ(part.local_index(6), 3u);
  Simulator none(torus(4, phold_links()), SimConfig{.seed = 1}, model, std::vector<std::uint8_t>(16, 0));
  EXPECT_EQ(none.local_count(), 0u);  // a rank may own no node
  EXPECT_THROW(part.run({.until = seconds(1)}), core::InternalError);  // not partitioned
  struct Nowhere final : RemoteOutbox {
    void post(Time, std::uint64_t, NodeIndex, NodeIndex, Phase, std::span<const std::byte>) override {}
  } nowhere;
  EXPECT_THROW(part.partition(odd, nowhere), core::InternalError);
  EXPECT_THROW(Simulator(torus(4, phold_links()), SimConfig{}, model, std::vector<std::uint8_t>(15, 1)),
               core::InternalError);
}

TEST(ParallelPhold, AContinuedRunEqualsOneRun) {
  const LinkModel link = phold_links();
  Phold seq_model(64, 1);
  Simulator seq(torus(8, link), SimConfig{.seed = 3, .trace = TraceMode::hash_only}, seq_model);
  const RunReport seq_report = seq.run({.until = seconds(30)});
  Phold par_model(64, 1);
  Simulator part(torus(8, link), SimConfig{.seed = 3, .trace = TraceMode::hash_only}, par_model);
  ParallelRun run(part, split(part.network(), Split::metis));
  const ParallelReport first = run.run({.until = seconds(12)});
  const ParallelReport second = run.run({.until = seconds(30)});
  if (world_rank() != 0) return;
  EXPECT_EQ(first.run.reason, StopReason::time_limit);
  EXPECT_EQ(first.run.simulated_time, seconds(12));
  EXPECT_EQ(second.run.simulated_time, seq_report.simulated_time);
  EXPECT_EQ(first.run.events_processed + second.run.events_processed, seq_report.events_processed);
  // The second report's trace covers the whole run (the ranks keep their records).
  EXPECT_EQ(second.trace.hash(), seq.trace().hash());
}

TEST(ParallelPhold, ZeroLatencyBetweenRanksIsRefusedOnEveryRank) {
  const LinkModel instant{LatencyModel::uniform(0, milliseconds(1)), 0, 0};
  Phold model(16, 1);
  Simulator part(torus(4, instant), SimConfig{.seed = 1}, model);
  const std::vector<int> owner = split(part.network(), Split::round_robin);
  if (world_size() == 1) {
    ParallelRun run(part, owner);  // nothing is cut: no lookahead needed
    const ParallelReport r = run.run({.until = milliseconds(50)});
    if (world_rank() == 0) {
      EXPECT_GT(r.run.events_processed, 0u);
    }
    return;
  }
  try {
    ParallelRun run(part, owner);
    FAIL() << "a zero-latency cut link was accepted";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("zero latency"), std::string::npos) << e.what();
  }
}

TEST(ParallelPhold, AnEventBudgetIsRefused) {
  Phold model(16, 1);
  Simulator part(torus(4, phold_links()), SimConfig{.seed = 1}, model);
  ParallelRun run(part, split(part.network(), Split::metis));
  EXPECT_THROW(run.run({.max_events = 10}), core::InternalError);
}

/// PHOLD whose node 5 throws at its 3rd message (or asks the run to stop, with `stop`).
struct Faulty final : NodeHandler {
  Phold inner;
  bool stop;
  int seen = 0;
  Faulty(std::size_t n, bool s) : inner(n), stop(s) {}
  void on_start(Simulator& sim, NodeIndex v) override { inner.on_start(sim, v); }
  void on_timer(Simulator&, NodeIndex, std::uint64_t) override {}
  void on_message(Simulator& sim, NodeIndex v, NodeIndex from, Phase phase, std::span<const std::byte> b) override {
    if (v == 5 && ++seen == 3) {
      if (stop) {
        sim.request_stop();
      } else {
        throw std::runtime_error("node 5 failed");
      }
    }
    inner.on_message(sim, v, from, phase, b);
  }
};

TEST(ParallelPhold, AFailingHandlerStopsEveryRankWithoutAHang) {
  for (const bool stop : {false, true}) {
    Faulty model(36, stop);
    Simulator part(torus(6, phold_links()), SimConfig{.seed = 2}, model);
    const std::vector<int> owner = split(part.network(), Split::round_robin);
    ParallelRun run(part, owner);
    try {
      run.run({.until = seconds(60)});
      FAIL() << "the failure was not reported";
    } catch (const core::InternalError& e) {
      // The owner of node 5 reports its own error (a refused request_stop is a precondition); the
      // others that another rank failed.
      if (owner[5] != world_rank()) {
        EXPECT_NE(std::string(e.what()).find("another MPI rank failed"), std::string::npos) << e.what();
      } else {
        EXPECT_TRUE(stop) << e.what();
        EXPECT_NE(std::string(e.what()).find("request_stop"), std::string::npos) << e.what();
      }
    } catch (const std::runtime_error& e) {
      EXPECT_FALSE(stop);
      EXPECT_EQ(owner[5], world_rank());
      EXPECT_STREQ(e.what(), "node 5 failed");
    }
  }
}

// --- A timer-driven gossip: timers (set and cancelled), broadcasts, phases, loss, duplication,
// overlapping crashes -----------------------------------------------------------------------------

struct Chatter final : NodeHandler {
  std::vector<std::uint64_t> heard, pending;
  explicit Chatter(std::size_t n) : heard(n, 0), pending(n, 0) {}
  void on_start(Simulator& sim, NodeIndex v) override { arm(sim, v); }
  void on_recover(Simulator& sim, NodeIndex v) override { arm(sim, v); }
  void arm(Simulator& sim, NodeIndex v) {
    auto& rng = sim.node_stream(v);
    // Two timers, the second often cancelled: cancellations must not disturb the keys' order.
    sim.schedule_timer(v, microseconds(200) * static_cast<Duration>(1 + rng.below(5)), 1);
    const TimerHandle spare = sim.schedule_timer(v, microseconds(300), 2);
    if (rng.below(3) != 0) sim.cancel_timer(spare);
  }
  void on_timer(Simulator& sim, NodeIndex v, std::uint64_t timer) override {
    auto& rng = sim.node_stream(v);
    const std::vector<std::byte> bytes = bytes_of({sim.network().id(v), timer, rng.next_u64()});
    if (timer == 2 || rng.below(8) == 0) {
      sim.broadcast(v, bytes, 1);
    } else {
      const auto nbrs = sim.network().neighbours(v);
      sim.send(v, nbrs[rng.below(nbrs.size())], bytes, 0);
    }
    if (++pending[v] < 25) arm(sim, v);
  }
  void on_message(Simulator& sim, NodeIndex v, NodeIndex, Phase phase, std::span<const std::byte> bytes) override {
    heard[v] = fnv1a(bytes, heard[v] + 1);
    if (phase == 0 && sim.node_stream(v).below(2) == 0) {
      const auto nbrs = sim.network().neighbours(v);
      sim.send(v, nbrs[sim.node_stream(v).below(nbrs.size())], bytes, 2);
    }
  }
};

Network chatter_network() {
  // Latencies on a 100 µs grid (many ties) with loss and duplication; overlapping and permanent crashes.
  Network net = torus(7, LinkModel{LatencyModel::uniform(microseconds(100), microseconds(400)), 0.1, 0.1});
  net.add_crash(3, microseconds(1000), microseconds(3000));
  net.add_crash(3, microseconds(2000), microseconds(2500));
  net.add_crash(20, 0, microseconds(1500));  // never started before it recovers
  net.add_crash(41, microseconds(2200));     // never recovers
  return net;
}

TEST(ParallelChatter, TimersCrashesLossAndDuplicationGiveTheSequentialRun) {
  for (const Split how : {Split::metis, Split::round_robin}) {
    Chatter seq_model(49);
    Simulator seq(chatter_network(), SimConfig{.seed = 11, .trace = TraceMode::records}, seq_model);
    const RunReport seq_report = seq.run();
    Chatter par_model(49);
    Simulator part(chatter_network(), SimConfig{.seed = 11, .trace = TraceMode::records}, par_model);
    ParallelRun run(part, split(part.network(), how));
    const ParallelReport par = run.run();
    const auto states = run.gather_nodes([&](NodeIndex v) { return bytes_of({par_model.heard[v], par_model.pending[v]}); });
    if (world_rank() != 0) continue;
    ASSERT_EQ(seq_report.reason, StopReason::queue_empty);
    const TrafficCounters total = seq.traffic().total();
    EXPECT_GT(total.messages_lost, 0u);
    EXPECT_GT(total.messages_duplicated, 0u);
    EXPECT_GT(total.messages_dropped, 0u);
    EXPECT_GT(seq.timers_dropped(), 0u);
    expect_same_run(seq, seq_report, par);
    for (NodeIndex v = 0; v < 49; ++v) {
      EXPECT_EQ(states[v], bytes_of({seq_model.heard[v], seq_model.pending[v]})) << "node " << v;
    }
  }
}

TEST(ParallelChatter, SimulatorsBuiltForTheirPartsGiveTheSequentialRun) {
  // Timers, cancellations, crashes, loss and duplication with each rank holding only its nodes'
  // streams, timer counts, crash state, counters and links.
  Chatter seq_model(49);
  Simulator seq(chatter_network(), SimConfig{.seed = 11, .trace = TraceMode::records}, seq_model);
  const RunReport seq_report = seq.run();
  for (const Split how : {Split::metis, Split::halves_reversed}) {
    const std::vector<int> owner = split(chatter_network(), how);
    Chatter par_model(49);
    Simulator part(chatter_network(), SimConfig{.seed = 11, .trace = TraceMode::records}, par_model,
                   owned_flags(owner, world_rank()));
    ParallelRun run(part, owner);
    const ParallelReport par = run.run();
    const auto states = run.gather_nodes([&](NodeIndex v) { return bytes_of({par_model.heard[v], par_model.pending[v]}); });
    if (world_rank() != 0) continue;
    expect_same_run(seq, seq_report, par);
    EXPECT_EQ(par.held_nodes, par.nodes);
    for (NodeIndex v = 0; v < 49; ++v) {
      EXPECT_EQ(states[v], bytes_of({seq_model.heard[v], seq_model.pending[v]})) << "node " << v;
    }
  }
}

// --- The packing protocol through SimHost ---------------------------------------------------------

struct PackingCase {
  const char* name;
  LinkModel link;
  bool lossy;
  bool asynchronous;
  std::optional<std::pair<NodeIndex, Time>> crash;
};

Network packing_network(const core::PlanarGraph& g, const PackingCase& c) {
  Network net = network_of(g, c.link);
  if (c.crash) net.add_crash(c.crash->first, c.crash->second);
  return net;
}

/// The host of case `c`, whole or (with `runner`) holding only the nodes the runner gives this rank;
/// `built` (if given) counts the node objects the factory made.
std::unique_ptr<SimHost> packing_host(const core::PlanarGraph& g, const PackingCase& c, HostRunner* runner = nullptr,
                                      std::size_t* built = nullptr) {
  Network net = packing_network(g, c);
  std::vector<std::uint8_t> held = runner != nullptr ? runner->ownership(net) : std::vector<std::uint8_t>{};
  protocols::PackingParams p;
  p.steps_per_check = 2;
  p.asynchronous = c.asynchronous;
  if (c.lossy) protocols::enable_lossy_links(p, milliseconds(5));
  return std::make_unique<SimHost>(std::move(net), SimConfig{.seed = 5, .trace = TraceMode::records},
                                   [&g, p, built](protocols::Runtime& rt, NodeIndex v) -> std::unique_ptr<protocols::Node> {
                                     if (built != nullptr) ++*built;
                                     return std::make_unique<protocols::PackingNode>(rt, protocols::local_knowledge(g, v), p);
                                   },
                                   SimHost::PhaseOf{}, std::move(held));
}

std::vector<std::byte> describe(SimHost& host, NodeIndex v) {
  const auto& n = static_cast<const protocols::PackingNode&>(host.node(v));
  return bytes_of({static_cast<std::uint64_t>(n.outcome()), n.steps(), std::bit_cast<std::uint64_t>(n.h()),
                   std::bit_cast<std::uint64_t>(n.placement().circle.x), std::bit_cast<std::uint64_t>(n.placement().circle.y),
                   std::bit_cast<std::uint64_t>(n.placement().circle.r), static_cast<std::uint64_t>(n.finished_at()),
                   n.suspect()});
}

TEST(ParallelPacking, SyncLossyCrashingAndAsynchronousRunsGiveTheSequentialRun) {
  const core::PlanarGraph g = core::prepare_for_packing(core::random_delaunay_triangulation(40, 4242));
  const LinkModel reliable{LatencyModel::constant(milliseconds(1)), 0, 0};
  const LinkModel lossy{LatencyModel::uniform(milliseconds(1), milliseconds(5)), 0.15, 0.05};
  const PackingCase cases[] = {
      {"sync", reliable, false, false, std::nullopt},
      {"lossy", lossy, true, false, std::nullopt},
      {"crash", lossy, true, false, std::pair{NodeIndex{7}, milliseconds(30)}},
      {"async", reliable, false, true, std::nullopt},
  };
  for (const PackingCase& c : cases) {
    SCOPED_TRACE(c.name);
    auto seq = packing_host(g, c);
    const RunReport seq_report = seq->run({.until = seconds(3600)});
    auto par_host = packing_host(g, c);
    ParallelRun run(par_host->simulator(), split(par_host->simulator().network(), Split::metis));
    const ParallelReport par = run.run({.until = seconds(3600)});
    const auto states = run.gather_nodes([&](NodeIndex v) { return describe(*par_host, v); });
    if (world_rank() != 0) continue;
    EXPECT_EQ(seq_report.reason, StopReason::queue_empty);
    expect_same_run(seq->simulator(), seq_report, par);
    for (NodeIndex v = 0; v < g.num_vertices(); ++v) EXPECT_EQ(states[v], describe(*seq, v)) << "node " << v;
    if (!c.crash && !c.asynchronous) {  // and the sequential run is the centralized packing
      const core::PackResult core_result = core::pack(g, core::PackOptions{.steps_per_check = 2});
      const auto& n0 = static_cast<const protocols::PackingNode&>(seq->node(0));
      EXPECT_EQ(std::bit_cast<std::uint64_t>(n0.h()), std::bit_cast<std::uint64_t>(core_result.radii[0]));
    }
  }
}

TEST(ParallelPacking, HostsBuiltThroughTheRunnerHoldOnlyTheirNodesAndGiveTheSequentialRun) {
  // MpiHostRunner::ownership partitions before the host is built: each rank's factory makes only its
  // share of the node objects, and the run is still the sequential one.
  const core::PlanarGraph g = core::prepare_for_packing(core::random_delaunay_triangulation(40, 4242));
  const LinkModel lossy{LatencyModel::uniform(milliseconds(1), milliseconds(5)), 0.15, 0.05};
  const PackingCase cases[] = {
      {"sync", LinkModel{LatencyModel::constant(milliseconds(1)), 0, 0}, false, false, std::nullopt},
      {"crash", lossy, true, false, std::pair{NodeIndex{7}, milliseconds(30)}},
      {"async", LinkModel{LatencyModel::constant(milliseconds(1)), 0, 0}, false, true, std::nullopt},
  };
  for (const PackingCase& c : cases) {
    SCOPED_TRACE(c.name);
    auto seq = packing_host(g, c);
    const RunReport seq_report = seq->run({.until = seconds(3600)});
    MpiHostRunner runner;
    std::size_t built = 0;
    auto host = packing_host(g, c, &runner, &built);
    const std::vector<int> owner = metis_partition(packing_network(g, c), world_size());  // what ownership used
    EXPECT_EQ(built, my_share(owner));
    EXPECT_EQ(host->built_nodes(), built);
    EXPECT_EQ(host->simulator().local_count(), built);
    if (world_size() > 1) {
      EXPECT_LT(built, g.num_vertices());
    }
    runner.run(*host, {.until = seconds(3600)});
    const auto states = runner.gather([&](NodeIndex v) { return describe(*host, v); });
    std::uint64_t mine = built;
    std::vector<std::uint64_t> all_built(static_cast<std::size_t>(world_size()));
    MPI_Gather(&mine, 1, MPI_UINT64_T, all_built.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    if (world_rank() != 0) continue;
    const ParallelReport& par = runner.report();
    expect_same_run(seq->simulator(), seq_report, par);
    EXPECT_EQ(all_built, par.nodes);  // node objects per rank = the partition's part sizes
    EXPECT_EQ(par.held_nodes, par.nodes);
    for (NodeIndex v = 0; v < g.num_vertices(); ++v) EXPECT_EQ(states[v], describe(*seq, v)) << "node " << v;
  }
}

}  // namespace
}  // namespace laguerre::sim::mpi
