// The reliability layer as a decorator (Reliable.hpp) around a protocol that knows nothing of it: a
// counter node that sends numbered messages to every neighbour. Over links that lose, duplicate and
// reorder, every message reaches its neighbour's inner node exactly once, the inner node's timers pass
// through, probing stops once the inner node is final (the queue drains), and a crash is detected and
// notified to every survivor's inner node once.

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "../LossyHost.hpp"
#include "../NullRuntime.hpp"
#include "../TestGraphs.hpp"
#include "laguerre/protocols/Reliable.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {

constexpr std::uint32_t per_link = 40;  // messages each node sends each neighbour
constexpr TimerId inner_timer = 77;

// Sends per_link numbered messages to each neighbour at start (type byte 0x7e: no codec type), and
// records what arrives; final once it has everything it expects.
class CounterNode final : public Node {
public:
  CounterNode(Runtime& rt, std::vector<NodeId> neighbours) : rt_(rt), neighbours_(std::move(neighbours)) {}
  void on_start() override {
    rt_.schedule(1'000'000, inner_timer);
    for (std::uint32_t i = 0; i < per_link; ++i)
      for (NodeId to : neighbours_) {
        const std::vector<std::byte> m{std::byte{2}, std::byte{0x7e}, std::byte(i & 0xff), std::byte(i >> 8)};
        rt_.send(to, m);
      }
  }
  void on_message(NodeId from, std::span<const std::byte> bytes) override {
    ASSERT_EQ(bytes.size(), 4u);
    ++got[from][static_cast<std::uint32_t>(bytes[2]) | static_cast<std::uint32_t>(bytes[3]) << 8];
    ++total;
  }
  void on_timer(TimerId t) override { timers.push_back(t); }
  void on_failure(NodeId suspect) override { failures.push_back(suspect); }
  bool is_final() const override { return total == per_link * neighbours_.size(); }

  std::map<NodeId, std::map<std::uint32_t, int>> got;  // from → number → copies delivered
  std::size_t total = 0;
  std::vector<TimerId> timers;
  std::vector<NodeId> failures;

private:
  Runtime& rt_;
  std::vector<NodeId> neighbours_;
};

LossyHost::Factory reliable_counters(const ReliableParams& p) {
  return [p](Runtime& rt, const LocalKnowledge& k) -> std::unique_ptr<Node> {
    return std::make_unique<ReliableNode>(rt, k.neighbours, p, [&](Runtime& inner_rt) {
      return std::make_unique<CounterNode>(inner_rt, k.neighbours);
    });
  };
}

const CounterNode& counter(LossyHost& host, core::Vertex v) {
  return static_cast<const CounterNode&>(host.as<ReliableNode>(v).inner());
}

}  // namespace

TEST(ReliableNode, DeliversEveryMessageExactlyOnceOverLossyDuplicatingLinks) {
  const core::PlanarGraph g = delaunay(20, 3);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    LossyHost host(g, reliable_counters(lossy_link_params(5'000'000)), lossy_config(0.3, 0.2, seed));
    const LossyHost::Stats st = host.run();
    ASSERT_TRUE(st.drained) << "probing must stop once the inner nodes are final";
    ASSERT_GT(st.lost, 0u);
    ASSERT_GT(st.duplicated, 0u);
    ReliableCounters totals;
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      const CounterNode& c = counter(host, v);
      const auto nb = local_knowledge(g, v).neighbours;
      ASSERT_EQ(c.got.size(), nb.size()) << "vertex " << v;
      for (NodeId from : nb) {
        ASSERT_EQ(c.got.at(from).size(), per_link);
        for (const auto& [i, copies] : c.got.at(from)) {
          EXPECT_LT(i, per_link);
          EXPECT_EQ(copies, 1) << "vertex " << v << " from " << from << " message " << i;
        }
      }
      EXPECT_EQ(c.timers, std::vector<TimerId>{inner_timer}) << "the inner node's timer passes through once";
      EXPECT_TRUE(c.failures.empty());
      const ReliableNode& r = host.as<ReliableNode>(v);
      EXPECT_FALSE(r.failed());
      EXPECT_TRUE(r.is_final());
      const ReliableCounters& k = r.counters();
      EXPECT_EQ(k.frames, per_link * nb.size() + k.probes);
      EXPECT_EQ(k.links_failed, 0u);
      EXPECT_EQ(k.decode[0], k.received);
      totals.sent += k.sent;
      totals.received += k.received;
      totals.retransmissions += k.retransmissions;
      totals.duplicates += k.duplicates;
    }
    EXPECT_EQ(totals.sent, st.sent);
    EXPECT_EQ(totals.received, st.delivered);
    EXPECT_GT(totals.retransmissions, 0u);
    EXPECT_GT(totals.duplicates, 0u);
  }
}

TEST(ReliableNode, ACrashIsNotifiedOnceToEverySurvivorsInnerNode) {
  const core::PlanarGraph g = delaunay(16, 5);
  for (const Time at : {Time{0}, Time{3'000'000}}) {
    SCOPED_TRACE("crash at " + std::to_string(at));
    LossyConfig c = lossy_config(0.1, 0.05, 4);
    const core::Vertex victim = 6;
    c.crashes = {{g.id(victim), at}};
    LossyHost host(g, reliable_counters(lossy_link_params(5'000'000)), c);
    ASSERT_TRUE(host.run().drained) << "every node goes quiet after the failure flood";
    std::uint64_t given_up = 0;
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      if (v == victim) continue;
      const ReliableNode& r = host.as<ReliableNode>(v);
      EXPECT_TRUE(r.failed()) << "vertex " << v;
      EXPECT_EQ(r.suspect(), g.id(victim)) << "vertex " << v;
      EXPECT_EQ(counter(host, v).failures, std::vector<NodeId>{g.id(victim)}) << "vertex " << v;
      given_up += r.counters().links_failed;
    }
    EXPECT_GT(given_up, 0u);
  }
}

TEST(ReliableNode, RejectsBadNeighboursParametersAndTimerIds) {
  NullRuntime rt;  // self() is 1
  const auto counter_of = [](const std::vector<NodeId>& nb) {
    return [nb](Runtime& r) { return std::make_unique<CounterNode>(r, nb); };
  };
  const ReliableParams ok = lossy_link_params(1000);
  EXPECT_THROW(ReliableNode(rt, {}, ok, counter_of({})), laguerre::core::InternalError);
  EXPECT_THROW(ReliableNode(rt, {2, 1}, ok, counter_of({2, 1})), laguerre::core::InternalError);
  EXPECT_THROW(ReliableNode(rt, {2, 2}, ok, counter_of({2, 2})), laguerre::core::InternalError);
  ReliableParams p = ok;
  p.retransmit_after = 0;
  EXPECT_THROW(ReliableNode(rt, {2}, p, counter_of({2})), laguerre::core::InternalError);
  p = ok;
  p.max_retransmissions = 0;
  EXPECT_THROW(ReliableNode(rt, {2}, p, counter_of({2})), laguerre::core::InternalError);
  EXPECT_THROW(ReliableNode(rt, {2}, ok, [](Runtime&) { return std::unique_ptr<Node>(); }), laguerre::core::InternalError);

  // The runtime served to the inner node: neighbours only, inner timer ids below 2^56.
  Runtime* inner_rt = nullptr;
  ReliableNode n(rt, {2, 3}, ok, [&](Runtime& r) {
    inner_rt = &r;
    return std::make_unique<CounterNode>(r, std::vector<NodeId>{2, 3});
  });
  ASSERT_NE(inner_rt, nullptr);
  EXPECT_EQ(inner_rt->self(), 1u);
  const std::vector<std::byte> m{std::byte{2}, std::byte{0x7e}, std::byte{0}, std::byte{0}};
  EXPECT_THROW(inner_rt->send(4, m), laguerre::core::InternalError);
  EXPECT_THROW(inner_rt->schedule(1, TimerId{1} << 56), laguerre::core::InternalError);
  inner_rt->broadcast(m);
  EXPECT_EQ(n.counters().frames, 2u);
  EXPECT_EQ(n.counters().sent, 2u);
}

TEST(ReliableNode, AFailureNoticeIsNotDeliveredToTheInnerNode) {
  NullRuntime rt;
  ReliableNode n(rt, {2, 3, 4}, lossy_link_params(1000),
                 [](Runtime& r) { return std::make_unique<CounterNode>(r, std::vector<NodeId>{2, 3, 4}); });
  const auto& inner = static_cast<const CounterNode&>(n.inner());
  n.on_message(2, encode(FrameMsg{0, {}, {std::byte{2}, std::byte{0x7e}, std::byte{5}, std::byte{0}}}));
  EXPECT_EQ(inner.total, 1u);
  n.on_message(3, encode(FrameMsg{0, {}, encode(FailureMsg{9})}));
  EXPECT_TRUE(n.failed());
  EXPECT_EQ(n.suspect(), 9u);
  EXPECT_EQ(inner.failures, std::vector<NodeId>{9});
  EXPECT_EQ(n.counters().frames, 2u) << "the notice goes on to every neighbour but the one it came from";
  n.on_message(2, encode(FrameMsg{1, {}, {std::byte{2}, std::byte{0x7e}, std::byte{6}, std::byte{0}}}));
  EXPECT_EQ(inner.total, 1u) << "an abandoned run delivers nothing more";
  n.on_message(4, encode(FrameMsg{0, {}, encode(FailureMsg{9})}));
  EXPECT_EQ(inner.failures.size(), 1u) << "notified once";
  EXPECT_EQ(n.counters().frames, 2u) << "the flood passes each node once";
}
