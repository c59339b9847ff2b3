// Seeded random properties of the kernel and the simulator (label: property). The number of cases
// scales with LAGUERRE_PROPERTY_CASES (default 20).
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "laguerre/sim/EventQueue.hpp"
#include "laguerre/sim/Simulator.hpp"

namespace laguerre::sim {
namespace {

int cases() {
  const char* env = std::getenv("LAGUERRE_PROPERTY_CASES");
  return env != nullptr ? std::max(1, std::atoi(env)) : 20;
}

// The ladder queue pops exactly the reference heap's sequence under hold-model workloads with
// random delay laws (including heavy ties and far outliers).
TEST(SimProperty, LadderQueueEqualsReferenceHeap) {
  for (int c = 0; c < cases(); ++c) {
    RandomStream rng = RandomStream::of(static_cast<std::uint64_t>(c), StreamKind::user, 77);
    const auto pending = 1 + rng.below(3000);
    const Time spread = static_cast<Time>(rng.below(4) == 0 ? 1 : 1 + rng.below(1'000'000'000));
    LadderEventQueue ladder;
    DaryEventHeap<2> heap;
    std::uint64_t seq = 0;
    for (std::uint64_t i = 0; i < pending; ++i) {
      const Event e{rng.uniform_int(0, spread), seq++, i, 0, 0, 0};
      ladder.push(e);
      heap.push(e);
    }
    for (int step = 0; step < 20'000; ++step) {
      ASSERT_EQ(ladder.top().seq, heap.top().seq) << "case " << c << " step " << step;
      const Time now = heap.top().time;
      ladder.pop();
      heap.pop();
      const Time delay = rng.bernoulli(0.001) ? rng.uniform_int(0, 1000 * spread) : rng.uniform_int(0, spread);
      const Event e{now + delay, seq++, 0, 0, 0, 0};
      ladder.push(e);
      heap.push(e);
    }
  }
}

/// Every node pings each neighbour periodically; used to check conservation of messages.
struct Pinger final : NodeHandler {
  void on_start(Simulator& sim, NodeIndex v) override { sim.schedule_timer(v, 0, 0); }
  void on_message(Simulator&, NodeIndex, NodeIndex, Phase, std::span<const std::byte>) override {}
  void on_timer(Simulator& sim, NodeIndex v, std::uint64_t k) override {
    const std::byte b[2] = {std::byte{1}, static_cast<std::byte>(k)};
    sim.broadcast(v, b, static_cast<Phase>(k % 4));
    if (k < 30) sim.schedule_timer(v, static_cast<Duration>(sim.node_stream(v).below(500'000)), k + 1);
  }
};

// Conservation: every copy sent (plus duplicates) is received, lost or dropped; and the run is
// reproducible, whatever the random network and channel.
TEST(SimProperty, MessagesAreConservedAndRunsReproducible) {
  for (int c = 0; c < cases(); ++c) {
    RandomStream rng = RandomStream::of(static_cast<std::uint64_t>(c), StreamKind::user, 78);
    const auto n = static_cast<NodeIndex>(2 + rng.below(40));
    std::vector<Edge> edges;
    for (NodeIndex v = 1; v < n; ++v) edges.emplace_back(v, static_cast<NodeIndex>(rng.below(v)));
    for (int extra = 0; extra < static_cast<int>(n); ++extra) {
      const auto a = static_cast<NodeIndex>(rng.below(n)), b = static_cast<NodeIndex>(rng.below(n));
      if (a != b) edges.emplace_back(a, b);
    }
    const LinkModel model{LatencyModel::uniform(0, static_cast<Duration>(rng.below(2'000'000))),
                          rng.uniform01() * 0.5, rng.uniform01() * 0.3};
    auto run = [&](std::uint64_t seed) {
      Network net(n, edges);
      net.set_link_model(model);
      net.add_crash(0, 1'000'000, 5'000'000);
      Pinger p;
      Simulator sim(std::move(net), SimConfig{.seed = seed, .trace = TraceMode::hash_only}, p);
      sim.run();
      const TrafficCounters t = sim.traffic().total();
      EXPECT_EQ(t.messages_sent + t.messages_duplicated,
                t.messages_received + t.messages_lost + t.messages_dropped)
          << "case " << c;
      return sim.trace().hash();
    };
    EXPECT_EQ(run(static_cast<std::uint64_t>(c)), run(static_cast<std::uint64_t>(c))) << "case " << c;
  }
}

}  // namespace
}  // namespace laguerre::sim
