#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "laguerre/sim/Simulator.hpp"

namespace laguerre::sim {
namespace {

/// A random gossip protocol: each node wakes at random times, sends random bytes to a random
/// neighbour, and forwards some of what it hears. All randomness comes from the
/// node's stream; the channel adds loss, duplication and random latency.
struct Gossip final : NodeHandler {
  int rounds = 20;
  std::vector<int> wakeups;
  explicit Gossip(std::size_t n) : wakeups(n, 0) {}
  void on_start(Simulator& sim, NodeIndex v) override { arm(sim, v); }
  void arm(Simulator& sim, NodeIndex v) {
    auto& rng = sim.node_stream(v);
    sim.schedule_timer(v, static_cast<Duration>(rng.exponential(1e6)), rng.below(1000));
  }
  void on_timer(Simulator& sim, NodeIndex v, std::uint64_t timer) override {
    auto& rng = sim.node_stream(v);
    const auto nbrs = sim.network().neighbours(v);
    std::vector<std::byte> bytes(1 + rng.below(16));
    for (auto& b : bytes) b = static_cast<std::byte>(rng.below(256));
    bytes[0] = static_cast<std::byte>(timer & 0xff);
    sim.send(v, nbrs[rng.below(nbrs.size())], bytes, static_cast<Phase>(rng.below(3)));
    if (++wakeups[v] < rounds) arm(sim, v);
  }
  void on_message(Simulator& sim, NodeIndex v, NodeIndex, Phase phase,
                  std::span<const std::byte> bytes) override {
    // Forward to one random neighbour with probability 1/2, or rarely to all: the expected number
    // of forwarded copies per copy stays below 1, so the epidemic dies out.
    auto& rng = sim.node_stream(v);
    const double u = rng.uniform01();
    if (u < 0.05) {
      sim.broadcast(v, bytes, phase);
    } else if (u < 0.45) {
      const auto nbrs = sim.network().neighbours(v);
      sim.send(v, nbrs[rng.below(nbrs.size())], bytes, phase);
    }
  }
};

/// A 6×6 grid with diagonals.
Network grid(const LinkModel& model) {
  std::vector<Edge> edges;
  const NodeIndex side = 6;
  for (NodeIndex r = 0; r < side; ++r) {
    for (NodeIndex c = 0; c < side; ++c) {
      const NodeIndex v = r * side + c;
      if (c + 1 < side) edges.emplace_back(v, v + 1);
      if (r + 1 < side) edges.emplace_back(v, v + side);
      if (c + 1 < side && r + 1 < side) edges.emplace_back(v, v + side + 1);
    }
  }
  Network net(side * side, edges);
  net.set_link_model(model);
  return net;
}

const LinkModel lossy{LatencyModel::uniform(microseconds(100), milliseconds(2)), 0.1, 0.05};

struct Outcome {
  std::uint64_t hash;
  std::uint64_t deliveries;
  TrafficCounters total;
  Time end;
};

/// The gossip scenario's network: the lossy grid with node 7 down from 3 ms to 9 ms.
Network gossip_network() {
  Network net = grid(lossy);
  net.add_crash(7, milliseconds(3), milliseconds(9));
  return net;
}

Outcome run_gossip(std::uint64_t seed, TraceMode mode = TraceMode::hash_only, Time slice = 0) {
  Gossip g(36);
  Simulator sim(gossip_network(), SimConfig{.seed = seed, .trace = mode}, g);
  if (slice > 0) {
    while (sim.run({.until = sim.now() + slice}).reason != StopReason::queue_empty) {
    }
  } else {
    sim.run();
  }
  return {sim.trace().hash(), sim.trace().count(), sim.traffic().total(), sim.now()};
}

TEST(DeterminismTest, SameSeedGivesTheSameTraceHash) {
  const Outcome a = run_gossip(1);
  const Outcome b = run_gossip(1);
  EXPECT_GT(a.deliveries, 1000u);
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(a.total, b.total);
  EXPECT_EQ(a.end, b.end);
  EXPECT_GT(a.total.messages_lost, 0u);
  EXPECT_GT(a.total.messages_duplicated, 0u);
  EXPECT_GT(a.total.messages_dropped, 0u);
}

TEST(DeterminismTest, DifferentSeedsGiveDifferentTraces) {
  const Outcome a = run_gossip(1);
  for (std::uint64_t seed = 2; seed < 6; ++seed) EXPECT_NE(run_gossip(seed).hash, a.hash);
}

TEST(DeterminismTest, CuttingTheRunIntoTimeSlicesChangesNothing) {
  const Outcome a = run_gossip(3);
  const Outcome b = run_gossip(3, TraceMode::hash_only, microseconds(250));
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(a.total, b.total);
}

TEST(DeterminismTest, AnObserverSeesTheRunInSlicesAndChangesNothing) {
  const Outcome a = run_gossip(3);
  Gossip g(36);
  Simulator sim(gossip_network(), SimConfig{.seed = 3, .trace = TraceMode::hash_only}, g);
  std::vector<std::uint64_t> seen;  // events processed at each call
  sim.set_observer(97, [&] { seen.push_back(sim.kernel().events_processed()); });
  const RunReport r = sim.run();
  EXPECT_EQ(r.reason, StopReason::queue_empty);
  EXPECT_EQ(sim.trace().hash(), a.hash);
  EXPECT_EQ(sim.traffic().total(), a.total);
  EXPECT_EQ(sim.now(), a.end);
  // Called after every 97 events.
  ASSERT_EQ(seen.size(), r.events_processed / 97);
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 97 * (i + 1));
}

TEST(DeterminismTest, AnObserverKeepsTheEventBudget) {
  Gossip g(36);
  Simulator sim(gossip_network(), SimConfig{.seed = 3, .trace = TraceMode::hash_only}, g);
  int calls = 0;
  sim.set_observer(10, [&] { ++calls; });
  const RunReport r = sim.run({.max_events = 25});
  EXPECT_EQ(r.reason, StopReason::event_limit);
  EXPECT_EQ(r.events_processed, 25u);
  EXPECT_EQ(calls, 2);
  sim.set_observer(0, {});  // removed: the rest runs without it
  sim.run();
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(sim.trace().hash(), run_gossip(3).hash);
}

TEST(DeterminismTest, RecordsModeHashesTheSameAndWritesTheTrace) {
  Gossip g(36);
  Simulator sim(gossip_network(), SimConfig{.seed = 3, .trace = TraceMode::records}, g);
  sim.run();
  // Keeping the records changes neither the run nor its hash.
  const Outcome hashed = run_gossip(3);
  EXPECT_EQ(sim.trace().hash(), hashed.hash);
  EXPECT_EQ(sim.trace().count(), hashed.deliveries);
  EXPECT_EQ(sim.traffic().total(), hashed.total);
  EXPECT_EQ(sim.now(), hashed.end);
  // Recompute the hash from the records.
  std::uint64_t h = fnv1a_basis;
  for (const TraceRecord& r : sim.trace().records()) h = fnv1a(Trace::encode(r), h);
  EXPECT_EQ(h, sim.trace().hash());
  EXPECT_EQ(sim.trace().records().size(), sim.trace().count());
  EXPECT_EQ(sim.trace().count(), sim.traffic().total().messages_received);
  std::ostringstream csv;
  sim.trace().write_csv(csv);
  EXPECT_EQ(csv.str().rfind("time_ns,from,to,phase,size,digest\n", 0), 0u);
  std::ostringstream bin;
  sim.trace().write_binary(bin);
  EXPECT_EQ(bin.str().size(), 16 + 38 * sim.trace().records().size());
  // Records are in delivery order.
  for (std::size_t i = 1; i < sim.trace().records().size(); ++i) {
    EXPECT_LE(sim.trace().records()[i - 1].time, sim.trace().records()[i].time);
  }
}

TEST(DeterminismTest, OffModeKeepsTheBasis) {
  Gossip g(36);
  Simulator sim(grid(lossy), SimConfig{.seed = 3}, g);
  sim.run();
  EXPECT_EQ(sim.trace().hash(), fnv1a_basis);
  EXPECT_EQ(sim.trace().count(), 0u);
}

TEST(DeterminismTest, TraceEncodingIsCanonical) {
  const TraceRecord r{0x0102030405060708, 9, 10, 0xAABBCCDDEEFF0011ULL, 12, 13};
  const auto bytes = Trace::encode(r);
  EXPECT_EQ(bytes[0], std::byte{0x08});  // little-endian time
  EXPECT_EQ(bytes[7], std::byte{0x01});
  EXPECT_EQ(bytes[8], std::byte{9});     // from
  EXPECT_EQ(bytes[16], std::byte{10});   // to
  EXPECT_EQ(bytes[24], std::byte{13});   // phase
  EXPECT_EQ(bytes[26], std::byte{12});   // size
  EXPECT_EQ(bytes[30], std::byte{0x11}); // digest
  // FNV-1a 64 reference values.
  EXPECT_EQ(fnv1a({}), 0xcbf29ce484222325ULL);
  const std::byte a[] = {std::byte{'a'}};
  EXPECT_EQ(fnv1a(a), 0xaf63dc4c8601ec8cULL);
}

}  // namespace
}  // namespace laguerre::sim

namespace laguerre::sim {
namespace {

// The gossip scenario's trace hash for seed 1: a golden value that changes only with the channel
// model, the random-stream construction, the kernel's event order or the trace encoding. Update it
// deliberately, never to make a test pass.
TEST(DeterminismTest, GoldenTraceHash) {
  const Outcome a = run_gossip(1);
  EXPECT_EQ(a.hash, 0xab4d0bb99b411a50ULL) << std::hex << "0x" << a.hash << " after " << std::dec << a.deliveries
                            << " deliveries";
}

}  // namespace
}  // namespace laguerre::sim
