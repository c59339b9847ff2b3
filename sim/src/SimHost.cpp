#include "laguerre/sim/SimHost.hpp"

#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

/// The Runtime of one node: a (host, index) pair forwarding to the simulator.
class SimHost::NodeRuntime final : public protocols::Runtime {
public:
  NodeRuntime(SimHost& host, NodeIndex v) : host_(host), v_(v) {}

  protocols::NodeId self() const override { return host_.simulator_.network().id(v_); }
  protocols::Time now() const override { return host_.simulator_.now(); }

  void send(protocols::NodeId to, std::span<const std::byte> bytes) override {
    const auto index = host_.simulator_.network().index_of(to);
    if (!index) ++host_.bad_destinations_;
    LAGUERRE_PRECONDITION(index.has_value(), "Node " + std::to_string(self()) + " cannot send to node " +
                                                 std::to_string(to) + ": no such node in the network.");
    if (!host_.simulator_.network().find_link(v_, *index)) ++host_.bad_destinations_;
    host_.simulator_.send(v_, *index, bytes, host_.phase(bytes));  // throws for a non-neighbour
  }

  void broadcast(std::span<const std::byte> bytes) override {
    host_.simulator_.broadcast(v_, bytes, host_.phase(bytes));
  }

  protocols::TimerHandle schedule(protocols::Duration after, protocols::TimerId timer) override {
    return host_.simulator_.schedule_timer(v_, after, timer).value;
  }

  bool cancel(protocols::TimerHandle handle) override {
    return host_.simulator_.cancel_timer(TimerHandle{handle});
  }

  std::uint64_t random_u64() override { return host_.simulator_.node_stream(v_).next_u64(); }

private:
  SimHost& host_;
  NodeIndex v_;
};

SimHost::SimHost(Network network, SimConfig config, const NodeFactory& factory, PhaseOf phase_of)
    : simulator_(std::move(network), config, *this), phase_of_(std::move(phase_of)) {
  const std::size_t n = simulator_.network().node_count();
  runtimes_.reserve(n);
  nodes_.reserve(n);
  for (NodeIndex v = 0; v < n; ++v) {
    runtimes_.push_back(std::make_unique<NodeRuntime>(*this, v));
    nodes_.push_back(factory(*runtimes_.back(), v));
    LAGUERRE_PRECONDITION(nodes_.back() != nullptr,
                          "The node factory returned no node for index " + std::to_string(v) + ".");
  }
}

SimHost::~SimHost() {
  nodes_.clear();  // nodes go first: they hold references to their runtimes
}

protocols::Runtime& SimHost::runtime(NodeIndex v) { return *runtimes_[v]; }

Phase SimHost::phase(std::span<const std::byte> bytes) const {
  return phase_of_ ? phase_of_(bytes) : Phase{0};
}

void SimHost::on_start(Simulator&, NodeIndex v) { nodes_[v]->on_start(); }

void SimHost::on_message(Simulator& sim, NodeIndex v, NodeIndex from, Phase,
                         std::span<const std::byte> bytes) {
  nodes_[v]->on_message(sim.network().id(from), bytes);
}

void SimHost::on_timer(Simulator&, NodeIndex v, std::uint64_t timer) { nodes_[v]->on_timer(timer); }

void SimHost::on_recover(Simulator&, NodeIndex v) { nodes_[v]->on_recover(); }

}  // namespace laguerre::sim
