#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/protocols/Runtime.hpp"
#include "laguerre/sim/SimHost.hpp"

namespace laguerre::sim {
namespace {

/// Flooding with a per-node random back-off: the node with id 100 starts a flood; every node
/// rebroadcasts the first copy it hears after a random delay (a timer), and cancels a second timer.
class Flood final : public protocols::Node {
public:
  explicit Flood(protocols::Runtime& rt) : rt_(rt) {}
  void on_start() override {
    if (rt_.self() == 100) {
      const std::byte msg[] = {std::byte{1}, std::byte{42}};
      rt_.broadcast(msg);
      heard_at = rt_.now();
    }
    const protocols::TimerHandle h = rt_.schedule(1'000'000'000, 99);
    EXPECT_NE(h, 0u);
    cancelled = rt_.cancel(h);
    cancelled_twice = rt_.cancel(h);
  }
  void on_message(protocols::NodeId from, std::span<const std::byte> bytes) override {
    ++copies;
    last_from = from;
    if (heard_at >= 0) return;
    heard_at = rt_.now();
    payload.assign(bytes.begin(), bytes.end());
    rt_.schedule(static_cast<protocols::Duration>(rt_.random_u64() % 1000), 7);
  }
  void on_timer(protocols::TimerId timer) override {
    EXPECT_EQ(timer, 7u);
    const std::byte msg[] = {std::byte{2}, std::byte{42}};
    rt_.broadcast(msg);
  }

  protocols::Time heard_at = -1;
  int copies = 0;
  protocols::NodeId last_from = 0;
  std::vector<std::byte> payload;
  bool cancelled = false;
  bool cancelled_twice = true;

private:
  protocols::Runtime& rt_;
};

Network ring(std::size_t n) {
  std::vector<Edge> edges;
  for (NodeIndex v = 0; v < n; ++v) edges.emplace_back(v, static_cast<NodeIndex>((v + 1) % n));
  Network net(n, edges);
  std::vector<std::uint64_t> ids;
  for (std::size_t v = 0; v < n; ++v) ids.push_back(100 + 7 * v);
  net.set_ids(ids);
  net.set_link_model(LinkModel{LatencyModel::uniform(1000, 2000), 0, 0});
  return net;
}

SimHost::NodeFactory flood_factory() {
  return [](protocols::Runtime& rt, NodeIndex) { return std::make_unique<Flood>(rt); };
}

Phase first_byte(std::span<const std::byte> bytes) {
  return bytes.empty() ? Phase{0} : static_cast<Phase>(bytes[0]);
}

TEST(SimHostTest, RunsProtocolNodesThroughTheRuntime) {
  SimHost host(ring(10), SimConfig{.seed = 5, .trace = TraceMode::hash_only}, flood_factory(), first_byte);
  const RunReport r = host.run();
  EXPECT_EQ(r.reason, StopReason::queue_empty);
  for (NodeIndex v = 0; v < 10; ++v) {
    auto& node = static_cast<Flood&>(host.node(v));
    EXPECT_GE(node.heard_at, 0) << "node " << v;
    EXPECT_EQ(node.copies, 2);  // one from each side of the ring
    EXPECT_TRUE(node.cancelled);
    EXPECT_FALSE(node.cancelled_twice);
    EXPECT_EQ(host.runtime(v).self(), 100 + 7 * v);
  }
  EXPECT_EQ(static_cast<Flood&>(host.node(1)).payload,
            (std::vector<std::byte>{std::byte{1}, std::byte{42}}));
  // Phases come from the first byte: the origin's broadcast is phase 1, the relays phase 2.
  const TrafficMetrics& t = host.simulator().traffic();
  EXPECT_EQ(t.phase_total(1).messages_sent, 2u);
  EXPECT_EQ(t.phase_total(2).messages_sent, 2u * 9);
  EXPECT_EQ(t.total().messages_received, 20u);
}

TEST(SimHostTest, IsDeterministicAndSeedSensitive) {
  auto hash = [](std::uint64_t seed) {
    SimHost host(ring(12), SimConfig{.seed = seed, .trace = TraceMode::hash_only}, flood_factory());
    host.run();
    return host.simulator().trace().hash();
  };
  EXPECT_EQ(hash(1), hash(1));
  EXPECT_NE(hash(1), hash(2));
}

TEST(SimHostTest, RejectsUnknownAndNonNeighbourDestinations) {
  SimHost host(ring(5), SimConfig{}, flood_factory());
  const std::byte b{};
  EXPECT_THROW(host.runtime(0).send(999, std::span(&b, 1)), laguerre::core::InternalError);
  EXPECT_THROW(host.runtime(0).send(100 + 7 * 2, std::span(&b, 1)), laguerre::core::InternalError);
  EXPECT_NO_THROW(host.runtime(0).send(100 + 7 * 1, std::span(&b, 1)));
  EXPECT_EQ(host.bad_destinations(), 2u);
  EXPECT_THROW(SimHost(ring(3), SimConfig{},
                       [](protocols::Runtime&, NodeIndex) { return std::unique_ptr<protocols::Node>(); }),
               laguerre::core::InternalError);
}

TEST(SimHostTest, RandomStreamIsKeyedByNodeId) {
  SimHost host(ring(4), SimConfig{.seed = 9}, flood_factory());
  RandomStream expected = RandomStream::of(9, StreamKind::node, 100 + 7 * 3);
  EXPECT_EQ(host.runtime(3).random_u64(), expected.next_u64());
}

}  // namespace
}  // namespace laguerre::sim

namespace laguerre::sim {
namespace {

/// A node that ticks every millisecond until 30 ms and counts its callbacks; on_recover re-arms.
class Ticker final : public protocols::Node {
public:
  explicit Ticker(protocols::Runtime& rt) : rt_(rt) {}
  void on_start() override {
    ++starts;
    rt_.schedule(1'000'000, 1);
  }
  void on_message(protocols::NodeId, std::span<const std::byte>) override {}
  void on_timer(protocols::TimerId) override {
    ++ticks;
    if (rt_.now() < 30'000'000) rt_.schedule(1'000'000, 1);
  }
  void on_recover() override {
    ++recoveries;
    recovered_at = rt_.now();
    rt_.schedule(1'000'000, 1);
  }
  int starts = 0, ticks = 0, recoveries = 0;
  protocols::Time recovered_at = -1;

private:
  protocols::Runtime& rt_;
};

TEST(SimHostRecovery, ARecoveringNodeGetsOnRecoverAndKeepsItsState) {
  const Edge edges[] = {{0, 1}};
  Network net(2, edges);
  net.add_crash(1, 5'000'000, 12'000'000);  // down in [5 ms, 12 ms)
  SimHost host(std::move(net), SimConfig{}, [](protocols::Runtime& rt, NodeIndex) { return std::make_unique<Ticker>(rt); });
  host.run();
  const auto& a = static_cast<const Ticker&>(host.node(0));
  const auto& b = static_cast<const Ticker&>(host.node(1));
  EXPECT_EQ(a.recoveries, 0);
  EXPECT_EQ(b.recoveries, 1);
  EXPECT_EQ(b.starts, 1) << "a recovery is not a second start";
  EXPECT_EQ(b.recovered_at, 12'000'000);
  EXPECT_EQ(a.ticks, 30);
  // Node 1 ticked at 1..4 ms; its 5 ms timer fell in the outage (dropped, so the chain stopped), and
  // on_recover re-armed it: ticks at 13..30 ms.
  EXPECT_EQ(b.ticks, 4 + 18);
  EXPECT_EQ(host.simulator().timers_dropped(), 1u);
}

}  // namespace
}  // namespace laguerre::sim
