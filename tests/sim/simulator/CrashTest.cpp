#include <gtest/gtest.h>

#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/sim/Simulator.hpp"

namespace laguerre::sim {
namespace {

/// Every node broadcasts one byte each millisecond until 50 ms (a periodic timer, re-armed in
/// on_timer and on_recover).
struct Beacon final : NodeHandler {
  std::vector<int> starts, recoveries;
  std::vector<std::vector<Time>> received;
  explicit Beacon(std::size_t n) : starts(n), recoveries(n), received(n) {}
  void on_start(Simulator& sim, NodeIndex v) override {
    ++starts[v];
    tick(sim, v);
  }
  void on_recover(Simulator& sim, NodeIndex v) override {
    ++recoveries[v];
    sim.schedule_timer(v, milliseconds(1), 0);
  }
  void on_message(Simulator& sim, NodeIndex v, NodeIndex, Phase, std::span<const std::byte>) override {
    received[v].push_back(sim.now());
  }
  void on_timer(Simulator& sim, NodeIndex v, std::uint64_t) override { tick(sim, v); }
  void tick(Simulator& sim, NodeIndex v) {
    const std::byte b{1};
    sim.broadcast(v, std::span(&b, 1));
    if (sim.now() < milliseconds(49)) sim.schedule_timer(v, milliseconds(1), 0);
  }
};

Network line() {
  const Edge edges[] = {{0, 1}, {1, 2}};
  Network net(3, edges);
  net.set_link_model(LinkModel{LatencyModel::constant(milliseconds(1)), 0, 0});
  return net;
}

TEST(CrashTest, MessagesToAndFromACrashedNodeAreDroppedAndCounted) {
  Network net = line();
  net.add_crash(1, milliseconds(10), milliseconds(30));
  Beacon b(3);
  Simulator sim(std::move(net), SimConfig{}, b);
  sim.run();
  // Node 1 is down during [10 ms, 30 ms): the crash precedes, at equal time, what the run scheduled,
  // and so does the recovery. Neighbours send at 0..49 ms, arrivals at 1..50 ms; the ones in
  // [10, 30) ms (20 per neighbour) are dropped at node 1.
  EXPECT_EQ(sim.traffic().node_total(1).messages_dropped, 40u);
  for (Time t : b.received[1]) EXPECT_TRUE(t < milliseconds(10) || t >= milliseconds(30)) << t;
  EXPECT_EQ(b.received[1].size(), 2u * 50 - 40);
  // Node 1's timer at 10 ms fell in the outage; on_recover re-armed it at 31 ms.
  EXPECT_EQ(sim.timers_dropped(), 1u);
  EXPECT_EQ(b.recoveries[1], 1);
  EXPECT_EQ(b.starts, (std::vector<int>{1, 1, 1}));
  // Node 1 sent at 0..9 ms and 31..49 ms; nodes 0 and 2 got those.
  EXPECT_EQ(b.received[0].size(), 10u + 19u);
  EXPECT_EQ(sim.traffic().node_total(1).messages_sent, 2u * (10 + 19));
  EXPECT_TRUE(sim.is_up(1));
}

/// Sends from a crashed node (a host calling send on a down node) are dropped at the sender.
struct Sender final : NodeHandler {
  void on_start(Simulator& sim, NodeIndex v) override {
    if (v == 0) sim.schedule_timer(0, milliseconds(5), 0);
  }
  void on_message(Simulator&, NodeIndex, NodeIndex, Phase, std::span<const std::byte>) override {}
  void on_timer(Simulator& sim, NodeIndex, std::uint64_t) override {
    const std::byte b[3]{};
    sim.send(1, 0, b, 2);  // node 1 is down now
    sim.broadcast(1, b, 2);
  }
};

TEST(CrashTest, SendsByACrashedNodeAreDroppedAtTheSender) {
  Network net = line();
  net.add_crash(1, milliseconds(1));
  Sender s;
  Simulator sim(std::move(net), SimConfig{}, s);
  sim.run();
  const TrafficCounters c = sim.traffic().get(1, 2);
  EXPECT_EQ(c.messages_dropped, 3u);
  EXPECT_EQ(c.bytes_dropped, 9u);
  EXPECT_EQ(c.messages_sent, 0u);
  EXPECT_FALSE(sim.is_up(1));
}

TEST(CrashTest, ANodeDownAtTimeZeroStartsWhenItRecovers) {
  Network net = line();
  net.add_crash(2, 0, milliseconds(20));
  Beacon b(3);
  Simulator sim(std::move(net), SimConfig{}, b);
  sim.run();
  EXPECT_EQ(b.starts, (std::vector<int>{1, 1, 1}));
  EXPECT_EQ(b.recoveries[2], 0);
  // Node 2 started at 20 ms: node 1 hears it from 21 ms on.
  EXPECT_FALSE(b.received[2].empty());
  for (Time t : b.received[2]) EXPECT_GE(t, milliseconds(20));
}

TEST(CrashTest, OverlappingOutagesKeepTheNodeDownUntilTheLastEnds) {
  Network net = line();
  net.add_crash(1, milliseconds(10), milliseconds(30));
  net.add_crash(1, milliseconds(20), milliseconds(40));
  Beacon b(3);
  Simulator sim(std::move(net), SimConfig{}, b);
  sim.run();
  for (Time t : b.received[1]) EXPECT_TRUE(t < milliseconds(10) || t >= milliseconds(40)) << t;
  EXPECT_EQ(b.recoveries[1], 1);
}

TEST(CrashTest, SendingToANonNeighbourThrows) {
  struct Bad final : NodeHandler {
    void on_start(Simulator& sim, NodeIndex v) override {
      if (v == 0) {
        const std::byte b{};
        sim.send(0, 2, std::span(&b, 1));
      }
    }
    void on_message(Simulator&, NodeIndex, NodeIndex, Phase, std::span<const std::byte>) override {}
    void on_timer(Simulator&, NodeIndex, std::uint64_t) override {}
  } bad;
  Simulator sim(line(), SimConfig{}, bad);
  EXPECT_THROW(sim.run(), laguerre::core::InternalError);
}

TEST(CrashTest, TimersCanBeCancelled) {
  struct Timers final : NodeHandler {
    std::vector<std::uint64_t> fired;
    void on_start(Simulator& sim, NodeIndex v) override {
      if (v != 0) return;
      const TimerHandle a = sim.schedule_timer(0, 10, 1);
      sim.schedule_timer(0, 20, 2);
      EXPECT_TRUE(sim.cancel_timer(a));
      EXPECT_FALSE(sim.cancel_timer(a));
      EXPECT_THROW(sim.schedule_timer(0, -1, 3), laguerre::core::InternalError);
    }
    void on_message(Simulator&, NodeIndex, NodeIndex, Phase, std::span<const std::byte>) override {}
    void on_timer(Simulator&, NodeIndex, std::uint64_t t) override { fired.push_back(t); }
  } timers;
  Simulator sim(line(), SimConfig{}, timers);
  const RunReport r = sim.run();
  EXPECT_EQ(timers.fired, (std::vector<std::uint64_t>{2}));
  EXPECT_EQ(r.reason, StopReason::queue_empty);
  EXPECT_EQ(r.simulated_time, 20);
  EXPECT_GT(r.peak_memory_bytes, 0u);
  EXPECT_EQ(r.events_processed, 4u);  // three starts and one timer
}

}  // namespace
}  // namespace laguerre::sim
