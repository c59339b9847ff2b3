// The Simulator's order at equal times (Simulator.hpp, "Order at equal times"): crashes and
// recoveries first, then starts, then copies by (sender, receiver, message index, copy), then
// timers in the order their node set them; never the order in which events were scheduled.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "laguerre/sim/Simulator.hpp"

namespace laguerre::sim {
namespace {

/// A star: node 0 in the middle, nodes 1…4 around it; every latency 1 ms.
Network star() {
  const std::vector<Edge> edges{{0, 1}, {0, 2}, {0, 3}, {0, 4}};
  Network net(5, edges);
  net.set_link_model(LinkModel{LatencyModel::constant(milliseconds(1)), 0, 0});
  return net;
}

/// Records what happens at node 0 as text; the leaves send to 0 at start in decreasing index order,
/// twice each, and node 0 sets timers due exactly when the copies arrive.
struct Probe final : NodeHandler {
  std::vector<std::string> seen;
  void on_start(Simulator& sim, NodeIndex v) override {
    if (v == 0) {
      // Set in the order b, a: they fire in the order they were set, after every copy due then.
      sim.schedule_timer(0, milliseconds(1), 'b');
      sim.schedule_timer(0, milliseconds(1), 'a');
      return;
    }
    const std::byte first[] = {std::byte{1}}, second[] = {std::byte{2}};
    sim.send(v, 0, first);
    sim.send(v, 0, second);
  }
  void on_message(Simulator&, NodeIndex v, NodeIndex from, Phase, std::span<const std::byte> bytes) override {
    if (v == 0) seen.push_back("m" + std::to_string(from) + "." + std::to_string(static_cast<int>(bytes[0])));
  }
  void on_timer(Simulator&, NodeIndex v, std::uint64_t timer) override {
    if (v == 0) seen.push_back(std::string("t") + static_cast<char>(timer));
  }
};

TEST(EventKeyTest, CopiesComeBySenderAndIndexThenTimersInTheOrderSet) {
  Probe p;
  Simulator sim(star(), SimConfig{}, p);
  sim.run();
  const std::vector<std::string> expected{"m1.1", "m1.2", "m2.1", "m2.2", "m3.1", "m3.2", "m4.1", "m4.2", "tb", "ta"};
  EXPECT_EQ(p.seen, expected);
}

/// Leaves send one copy each to node 0 from a timer, leaf 4 first and leaf 1 last.
struct Reversed final : NodeHandler {
  std::vector<NodeIndex> arrivals;
  void on_start(Simulator& sim, NodeIndex v) override {
    if (v != 0) sim.schedule_timer(v, microseconds(10) * static_cast<Duration>(5 - v), 0);
  }
  void on_timer(Simulator& sim, NodeIndex v, std::uint64_t) override {
    const std::byte b[] = {std::byte{0}};
    sim.send(v, 0, b);
  }
  void on_message(Simulator&, NodeIndex, NodeIndex from, Phase, std::span<const std::byte>) override {
    arrivals.push_back(from);
  }
};

TEST(EventKeyTest, CopiesDueAtOneInstantComeBySenderWhateverTheirSendingOrder) {
  Network net = star();
  // Leaf v sends at 10 µs · (5 − v) (4 first, 1 last) over a link of latency 1 ms − that, so all
  // four copies reach node 0 at 1 ms exactly, scheduled in the order 4, 3, 2, 1.
  for (NodeIndex v = 1; v <= 4; ++v) {
    net.set_link_model(v, 0, LinkModel{LatencyModel::constant(milliseconds(1) - microseconds(10) * (5 - v)), 0, 0});
  }
  Reversed r;
  Simulator sim(std::move(net), SimConfig{}, r);
  sim.run();
  EXPECT_EQ(r.arrivals, (std::vector<NodeIndex>{1, 2, 3, 4}));
  EXPECT_EQ(sim.now(), milliseconds(1));
}

}  // namespace
}  // namespace laguerre::sim
