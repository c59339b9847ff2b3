#pragma once
// A minimal second host for the node runtime, with no dependency on sim/: every node gets a Runtime
// whose send/broadcast append to one std::deque; `run` delivers messages one at a time, either in
// FIFO order (a synchronous round-robin network) or in a seeded random order (arbitrary delays and
// reordering, still reliable). It proves that the protocol code needs nothing but the Runtime.

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/core/random/Random.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols::testing {

class DequeHost {
public:
  struct Envelope {
    NodeId from;
    NodeId to;
    std::vector<std::byte> bytes;
  };

  class NodeRuntime final : public Runtime {
  public:
    NodeRuntime(DequeHost& host, NodeId self, std::vector<NodeId> neighbours, std::uint64_t seed)
        : host_(host), self_(self), neighbours_(std::move(neighbours)), random_(seed ^ (self * 0xd1342543de82ef95ull)) {}
    NodeId self() const override { return self_; }
    Time now() const override { return static_cast<Time>(host_.delivered_); }
    void send(NodeId to, std::span<const std::byte> bytes) override {
      if (std::find(neighbours_.begin(), neighbours_.end(), to) == neighbours_.end())
        throw std::invalid_argument("Node " + std::to_string(self_) + " sent to non-neighbour " + std::to_string(to) + ".");
      host_.queue_.push_back({self_, to, {bytes.begin(), bytes.end()}});
    }
    void broadcast(std::span<const std::byte> bytes) override {
      for (NodeId to : neighbours_) host_.queue_.push_back({self_, to, {bytes.begin(), bytes.end()}});
    }
    TimerHandle schedule(Duration, TimerId) override { return ++host_.timers_; }
    bool cancel(TimerHandle) override { return false; }
    std::uint64_t random_u64() override { return random_.next(); }

  private:
    DequeHost& host_;
    NodeId self_;
    std::vector<NodeId> neighbours_;
    core::SplitMix64 random_;
  };

  // Builds the node of vertex v (any protocol) on the runtime the host made for it.
  using Factory = std::function<std::unique_ptr<Node>(Runtime&, core::Vertex)>;

  // One node per vertex of g, made by `make`.
  DequeHost(const core::PlanarGraph& g, const Factory& make, std::uint64_t seed = 1) {
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      const LocalKnowledge k = local_knowledge(g, v);
      runtimes_.push_back(std::make_unique<NodeRuntime>(*this, k.id, k.neighbours, seed));
      index_[k.id] = v;
      nodes_.push_back(make(*runtimes_.back(), v));
    }
  }

  // One PackingNode per vertex of g, with the knowledge `local_knowledge` gives.
  DequeHost(const core::PlanarGraph& g, PackingParams params, std::uint64_t seed = 1)
      : DequeHost(
            g, [&](Runtime& rt, core::Vertex v) { return std::make_unique<PackingNode>(rt, local_knowledge(g, v), params); },
            seed) {}

  // Starts every node, then delivers until no message is left or `max_messages` were delivered.
  // With `shuffle_seed` ≠ 0 each delivery picks a uniformly random queued message.
  void run(std::uint64_t shuffle_seed = 0, std::uint64_t max_messages = 200'000'000) {
    for (auto& n : nodes_) n->on_start();
    deliver(shuffle_seed, max_messages);
  }

  // Delivers queued messages (as run, without starting the nodes).
  void deliver(std::uint64_t shuffle_seed = 0, std::uint64_t max_messages = 200'000'000) {
    core::SplitMix64 rng(shuffle_seed);
    const std::uint64_t limit = delivered_ + max_messages;
    while (!queue_.empty() && delivered_ < limit) {
      if (shuffle_seed != 0) {
        const std::size_t k = static_cast<std::size_t>(rng.next() % queue_.size());
        std::swap(queue_[k], queue_.front());
      }
      Envelope e = std::move(queue_.front());
      queue_.pop_front();
      ++delivered_;
      bytes_ += e.bytes.size();
      if (e.bytes.size() >= 2) ++by_type_[std::to_integer<std::uint8_t>(e.bytes[1])];
      nodes_[index_.at(e.to)]->on_message(e.from, e.bytes);
    }
  }

  PackingNode& node(core::Vertex v) { return as<PackingNode>(v); }
  template <class T>
  T& as(core::Vertex v) {
    return dynamic_cast<T&>(*nodes_[v]);
  }
  std::size_t size() const { return nodes_.size(); }
  std::uint64_t delivered() const { return delivered_; }
  std::uint64_t bytes() const { return bytes_; }
  // Messages delivered of type t (a relayed message counts as a relay).
  std::uint64_t delivered(MessageType t) const { return by_type_[static_cast<std::uint8_t>(t)]; }

private:
  std::vector<std::unique_ptr<NodeRuntime>> runtimes_;
  std::vector<std::unique_ptr<Node>> nodes_;
  std::unordered_map<NodeId, core::Vertex> index_;
  std::deque<Envelope> queue_;
  std::uint64_t delivered_ = 0;
  std::uint64_t bytes_ = 0;
  std::array<std::uint64_t, 256> by_type_{};
  TimerHandle timers_ = 0;
};

}  // namespace laguerre::protocols::testing
