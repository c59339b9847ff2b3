#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/sim/Simulator.hpp"

namespace laguerre::sim {
namespace {

/// Node 0 sends `count` numbered messages to node 1 at time 0; node 1 records what arrives.
struct Blaster final : NodeHandler {
  std::uint32_t count = 0;
  struct Arrival {
    Time time;
    std::uint32_t number;
  };
  std::vector<Arrival> arrivals;
  void on_start(Simulator& sim, NodeIndex v) override {
    if (v != 0) return;
    for (std::uint32_t i = 0; i < count; ++i) {
      std::byte bytes[4];
      std::memcpy(bytes, &i, 4);
      sim.send(0, 1, bytes, 3);
    }
  }
  void on_message(Simulator& sim, NodeIndex, NodeIndex, Phase, std::span<const std::byte> b) override {
    std::uint32_t i;
    std::memcpy(&i, b.data(), 4);
    arrivals.push_back({sim.now(), i});
  }
  void on_timer(Simulator&, NodeIndex, std::uint64_t) override {}
};

Network pair(const LinkModel& model) {
  const Edge edges[] = {{0, 1}};
  Network net(2, edges);
  net.set_link_model(model);
  return net;
}

TEST(LinkTest, LossRateIsWithinABinomialBound) {
  Blaster b;
  b.count = 20'000;
  const double p = 0.2;
  Simulator sim(pair(LinkModel{LatencyModel::constant(1000), p, 0}), SimConfig{.seed = 4}, b);
  sim.run();
  const double lost = static_cast<double>(b.count - b.arrivals.size());
  const double mean = b.count * p, sd = std::sqrt(b.count * p * (1 - p));
  EXPECT_LT(std::abs(lost - mean), 4.5 * sd);
  const TrafficCounters c = sim.traffic().get(0, 3);
  EXPECT_EQ(c.messages_sent, b.count);
  EXPECT_EQ(c.bytes_sent, 4u * b.count);
  EXPECT_EQ(c.messages_lost, static_cast<std::uint64_t>(lost));
  EXPECT_EQ(sim.traffic().get(1, 3).messages_received, b.arrivals.size());
  EXPECT_EQ(sim.traffic().total().bytes_received, 4u * b.arrivals.size());
}

TEST(LinkTest, DuplicationRateIsWithinABinomialBoundAndCopiesAreIdentical) {
  Blaster b;
  b.count = 20'000;
  const double p = 0.1;
  Simulator sim(pair(LinkModel{LatencyModel::uniform(1000, 5000), 0, p}), SimConfig{.seed = 5}, b);
  sim.run();
  const double extra = static_cast<double>(b.arrivals.size() - b.count);
  EXPECT_LT(std::abs(extra - b.count * p), 4.5 * std::sqrt(b.count * p * (1 - p)));
  EXPECT_EQ(sim.traffic().get(0, 3).messages_duplicated, static_cast<std::uint64_t>(extra));
  std::vector<int> copies(b.count, 0);
  for (const auto& a : b.arrivals) ++copies[a.number];
  EXPECT_EQ(*std::min_element(copies.begin(), copies.end()), 1);
  EXPECT_EQ(*std::max_element(copies.begin(), copies.end()), 2);
}

TEST(LinkTest, UniformLatencyStaysInBoundsAndReorders) {
  Blaster b;
  b.count = 5'000;
  Simulator sim(pair(LinkModel{LatencyModel::uniform(1000, 3000), 0, 0}), SimConfig{.seed = 6}, b);
  sim.run();
  ASSERT_EQ(b.arrivals.size(), b.count);
  Time lo = time_max, hi = 0;
  double sum = 0;
  std::size_t inversions = 0;
  for (std::size_t i = 0; i < b.arrivals.size(); ++i) {
    lo = std::min(lo, b.arrivals[i].time);
    hi = std::max(hi, b.arrivals[i].time);
    sum += static_cast<double>(b.arrivals[i].time);
    if (i > 0 && b.arrivals[i].number < b.arrivals[i - 1].number) ++inversions;
  }
  EXPECT_GE(lo, 1000);
  EXPECT_LE(hi, 3000);
  EXPECT_LE(lo, 1010);  // both ends are reached (2001 equally likely values, 5000 draws)
  EXPECT_GE(hi, 2990);
  EXPECT_NEAR(sum / b.count, 2000, 30);
  EXPECT_GT(inversions, 1000u);  // random latency reorders
}

TEST(LinkTest, ConstantLatencyKeepsFifoOrder) {
  Blaster b;
  b.count = 1'000;
  Simulator sim(pair(LinkModel{LatencyModel::constant(2500), 0, 0}), SimConfig{}, b);
  sim.run();
  ASSERT_EQ(b.arrivals.size(), b.count);
  for (std::uint32_t i = 0; i < b.count; ++i) {
    EXPECT_EQ(b.arrivals[i].number, i);
    EXPECT_EQ(b.arrivals[i].time, 2500);
  }
}

TEST(LinkTest, DistanceLatencyIsAffineInTheDistance) {
  Blaster b;
  b.count = 100;
  const Edge edges[] = {{0, 1}};
  Network net(2, edges);
  net.set_positions({{0, 0}, {3, 4}});
  net.set_link_model(LinkModel{LatencyModel::distance(100, 1000.0), 0, 0});
  EXPECT_DOUBLE_EQ(net.link_length(0), 5.0);
  Simulator sim(std::move(net), SimConfig{}, b);
  sim.run();
  for (const auto& a : b.arrivals) EXPECT_EQ(a.time, 5100);

  Blaster j;
  j.count = 1000;
  Network jittered(2, edges);
  jittered.set_positions({{0, 0}, {3, 4}});
  jittered.set_link_model(LinkModel{LatencyModel::distance(100, 1000.0, 50), 0, 0});
  Simulator sim2(std::move(jittered), SimConfig{}, j);
  sim2.run();
  for (const auto& a : j.arrivals) {
    EXPECT_GE(a.time, 5100);
    EXPECT_LE(a.time, 5150);
  }
}

TEST(LinkTest, ModelsRejectBadParameters) {
  EXPECT_THROW(LatencyModel::constant(-1), laguerre::core::InternalError);
  EXPECT_THROW(LatencyModel::uniform(5, 4), laguerre::core::InternalError);
  EXPECT_THROW(LatencyModel::distance(0, -1.0), laguerre::core::InternalError);
  EXPECT_THROW(LatencyModel::distance(0, std::nan("")), laguerre::core::InternalError);
  EXPECT_THROW((LinkModel{LatencyModel::constant(1), 1.5, 0}.validate()), laguerre::core::InternalError);
  EXPECT_THROW((LinkModel{LatencyModel::constant(1), 0, -0.1}.validate()), laguerre::core::InternalError);
  EXPECT_THROW((LinkModel{LatencyModel::constant(1), std::nan(""), 0}.validate()), laguerre::core::InternalError);
  const LatencyModel d = LatencyModel::distance(10, 2.0, 7);
  EXPECT_EQ(d.min_latency(3.0), 16);
  EXPECT_EQ(d.max_latency(3.0), 23);
}

TEST(LinkTest, DistanceLatencyWithoutPositionsIsRejected) {
  Blaster b;
  const Edge edges[] = {{0, 1}};
  Network net(2, edges);
  net.set_link_model(LinkModel{LatencyModel::distance(0, 1.0), 0, 0});
  EXPECT_THROW(Simulator(std::move(net), SimConfig{}, b), laguerre::core::InternalError);
}

TEST(LinkTest, DecisionsArePureFunctionsOfTheMessageStream) {
  const LinkModel m{LatencyModel::uniform(0, 1'000'000), 0.3, 0.3};
  for (std::uint64_t k = 0; k < 100; ++k) {
    RandomStream a(k), b(k);
    const LinkDecision x = decide(m, 0, a), y = decide(m, 0, b);
    EXPECT_EQ(x.lost, y.lost);
    EXPECT_EQ(x.latency, y.latency);
    EXPECT_EQ(x.duplicated, y.duplicated);
    EXPECT_EQ(x.duplicate_latency, y.duplicate_latency);
  }
}

}  // namespace
}  // namespace laguerre::sim
