#pragma once
// A third minimal host with no dependency on sim/: a small discrete-event loop (time-ordered, FIFO
// among equal times) whose links lose each copy with probability `loss`, duplicate a message with
// probability `dup`, and delay each copy uniformly in [latency_lo, latency_hi] (so they reorder), with
// working timers and crash-stop failures. It lets the heavy lossy-link property tests run without the
// simulation kernel, and proves the reliability layer needs nothing but the Runtime.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <queue>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "SyncHost.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols::testing {

struct LossyConfig {
  double loss = 0;                  // probability that one copy is lost
  double dup = 0;                   // probability that a message is sent twice
  Duration latency_lo = 1'000'000;  // 1 ms
  Duration latency_hi = 5'000'000;  // 5 ms
  std::uint64_t seed = 1;
  std::vector<std::pair<NodeId, Time>> crashes;  // (node id, time): crash-stop
  std::uint64_t max_events = 100'000'000;
};

// A configuration with the given loss and duplication probabilities and seed, the rest default.
inline LossyConfig lossy_config(double loss, double dup, std::uint64_t seed) {
  LossyConfig c;
  c.loss = loss;
  c.dup = dup;
  c.seed = seed;
  return c;
}

class LossyHost {
public:
  struct Stats {
    std::uint64_t sent = 0, lost = 0, duplicated = 0, delivered = 0, events = 0, timers = 0;
    Time end = 0;
    bool drained = false;
  };

  class NodeRuntime final : public Runtime {
  public:
    NodeRuntime(LossyHost& host, std::size_t index, NodeId self, std::vector<NodeId> neighbours)
        : host_(host), index_(index), self_(self), neighbours_(std::move(neighbours)) {}
    NodeId self() const override { return self_; }
    Time now() const override { return host_.now_; }
    void send(NodeId to, std::span<const std::byte> bytes) override {
      if (std::find(neighbours_.begin(), neighbours_.end(), to) == neighbours_.end())
        throw std::invalid_argument("Node " + std::to_string(self_) + " sent to non-neighbour " + std::to_string(to) + ".");
      host_.post(index_, to, bytes);
    }
    void broadcast(std::span<const std::byte> bytes) override {
      for (NodeId to : neighbours_) host_.post(index_, to, bytes);
    }
    TimerHandle schedule(Duration after, TimerId timer) override {
      if (after < 0) throw std::invalid_argument("negative timer delay");
      return host_.push(host_.now_ + after, Event::alarm, index_, 0, timer, {});
    }
    bool cancel(TimerHandle handle) override { return host_.live_timers_.erase(handle) == 1; }
    std::uint64_t random_u64() override { return host_.rng_.next(); }

  private:
    LossyHost& host_;
    std::size_t index_;
    NodeId self_;
    std::vector<NodeId> neighbours_;
  };

  // Builds the node of a vertex from its runtime and static knowledge.
  using Factory = std::function<std::unique_ptr<Node>(Runtime&, const LocalKnowledge&)>;

  // Packing nodes with `params`.
  LossyHost(const core::PlanarGraph& g, PackingParams params, LossyConfig config)
      : LossyHost(g, [&](Runtime& rt, const LocalKnowledge& k) { return std::make_unique<PackingNode>(rt, k, params); },
                  std::move(config)) {}

  // The nodes `make` builds.
  LossyHost(const core::PlanarGraph& g, const Factory& make, LossyConfig config)
      : config_(std::move(config)), rng_(config_.seed * 0x9e3779b97f4a7c15ull + 17) {
    for (core::Vertex v = 0; v < g.num_vertices(); ++v) {
      const LocalKnowledge k = local_knowledge(g, v);
      runtimes_.push_back(std::make_unique<NodeRuntime>(*this, v, k.id, k.neighbours));
      index_[k.id] = v;
      nodes_.push_back(make(*runtimes_.back(), k));
    }
    crash_at_.assign(nodes_.size(), -1);
    for (auto [id, t] : config_.crashes) crash_at_[index_.at(id)] = t;
  }

  Stats run() {
    for (std::size_t v = 0; v < nodes_.size(); ++v)
      if (up(v)) nodes_[v]->on_start();
    while (!queue_.empty() && stats_.events < config_.max_events) {
      Event e = queue_.top();
      queue_.pop();
      now_ = e.at;
      if (e.kind == Event::alarm && live_timers_.erase(e.seq) == 0) continue;  // cancelled
      ++stats_.events;
      if (!up(e.node)) continue;  // crashed: it neither receives nor runs timers
      if (e.kind == Event::alarm) {
        ++stats_.timers;
        nodes_[e.node]->on_timer(e.timer);
      } else {
        ++stats_.delivered;
        nodes_[e.node]->on_message(e.from, e.bytes);
      }
    }
    stats_.drained = queue_.empty();
    stats_.end = now_;
    return stats_;
  }

  PackingNode& node(core::Vertex v) { return as<PackingNode>(v); }
  template <class T>
  T& as(core::Vertex v) { return static_cast<T&>(*nodes_[v]); }
  std::size_t size() const { return nodes_.size(); }
  bool crashed(core::Vertex v) const { return crash_at_[v] >= 0; }

private:
  struct Event {
    enum Kind : std::uint8_t { message, alarm };
    Time at = 0;
    std::uint64_t seq = 0;
    Kind kind = message;
    std::size_t node = 0;
    NodeId from = 0;
    TimerId timer = 0;
    std::vector<std::byte> bytes;
  };
  struct Later {
    bool operator()(const Event& a, const Event& b) const { return a.at != b.at ? a.at > b.at : a.seq > b.seq; }
  };

  bool up(std::size_t v) const { return crash_at_[v] < 0 || now_ < crash_at_[v]; }
  double uniform() { return rng_.uniform01(); }
  Duration latency() {
    const auto span = static_cast<std::uint64_t>(config_.latency_hi - config_.latency_lo + 1);
    return config_.latency_lo + static_cast<Duration>(rng_.next() % span);
  }

  std::uint64_t push(Time at, Event::Kind kind, std::size_t node, NodeId from, TimerId timer, std::span<const std::byte> bytes) {
    Event e{at, ++seq_, kind, node, from, timer, {bytes.begin(), bytes.end()}};
    if (kind == Event::alarm) live_timers_.insert(e.seq);
    queue_.push(std::move(e));
    return seq_;
  }

  void post(std::size_t from, NodeId to, std::span<const std::byte> bytes) {
    if (!up(from)) return;
    ++stats_.sent;
    const std::size_t target = index_.at(to);
    const NodeId from_id = runtimes_[from]->self();
    const int copies = uniform() < config_.dup ? 2 : 1;
    stats_.duplicated += copies - 1;
    for (int c = 0; c < copies; ++c) {
      if (uniform() < config_.loss) {
        ++stats_.lost;
        continue;
      }
      push(now_ + latency(), Event::message, target, from_id, 0, bytes);
    }
  }

  LossyConfig config_;
  core::SplitMix64 rng_;
  std::vector<std::unique_ptr<NodeRuntime>> runtimes_;
  std::vector<std::unique_ptr<Node>> nodes_;
  std::unordered_map<NodeId, core::Vertex> index_;
  std::vector<Time> crash_at_;
  std::priority_queue<Event, std::vector<Event>, Later> queue_;
  std::unordered_set<std::uint64_t> live_timers_;
  std::uint64_t seq_ = 0;
  Time now_ = 0;
  Stats stats_;
};

}  // namespace laguerre::protocols::testing
