#include "laguerre/sim/SimHost.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

/// The Runtime of one node: a (host, index) pair forwarding to the simulator.
class SimHost::NodeRuntime final : public protocols::Runtime {
public:
  /// Attaches the runtime to node `v` of `host` (once, before the node is built).
  void bind(SimHost& host, NodeIndex v) {
    host_ = &host;
    v_ = v;
  }

  protocols::NodeId self() const override { return host_->simulator_.network().id(v_); }
  protocols::Time now() const override { return host_->simulator_.now(); }

  void send(protocols::NodeId to, std::span<const std::byte> bytes) override {
    const auto link = host_->link_to(v_, to);
    if (!link) host_->reject(v_, to);  // throws
    host_->simulator_.send_on_link(*link, bytes, host_->phase(bytes));
  }

  void broadcast(std::span<const std::byte> bytes) override {
    host_->simulator_.broadcast(v_, bytes, host_->phase(bytes));
  }

  protocols::TimerHandle schedule(protocols::Duration after, protocols::TimerId timer) override {
    return host_->simulator_.schedule_timer(v_, after, timer).value;
  }

  bool cancel(protocols::TimerHandle handle) override {
    return host_->simulator_.cancel_timer(TimerHandle{handle});
  }

  std::uint64_t random_u64() override { return host_->simulator_.node_stream(v_).next_u64(); }

private:
  SimHost* host_ = nullptr;
  NodeIndex v_ = 0;
};

SimHost::SimHost(Network network, SimConfig config, const NodeFactory& factory, PhaseOf phase_of,
                 std::vector<std::uint8_t> held)
    : simulator_(std::move(network), config, *this, std::move(held)), phase_of_(std::move(phase_of)) {
  const Network& net = simulator_.network();
  const std::size_t n = simulator_.local_count();
  // Each held node's links sorted by the neighbour's user id: the runtime resolves a destination id
  // with a binary search in the sender's row, never a global lookup.
  std::size_t links = 0;
  for (std::size_t i = 0; i < n; ++i) links += net.neighbours(simulator_.local_node(i)).size();
  links_by_id_.reserve(links);
  for (std::size_t i = 0; i < n; ++i) {
    const NodeIndex v = simulator_.local_node(i);
    const auto row = net.neighbours(v);
    for (std::size_t j = 0; j < row.size(); ++j) links_by_id_.push_back({net.id(row[j]), net.link_at(v, j)});
    const auto first = links_by_id_.end() - static_cast<std::ptrdiff_t>(row.size());
    std::sort(first, links_by_id_.end(), [](const IdLink& a, const IdLink& b) { return a.id < b.id; });
  }
  runtimes_ = std::make_unique<NodeRuntime[]>(n);
  nodes_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const NodeIndex v = simulator_.local_node(i);
    runtimes_[i].bind(*this, v);
    nodes_.push_back(factory(runtimes_[i], v));
    LAGUERRE_PRECONDITION(nodes_.back() != nullptr,
                          "The node factory returned no node for index " + std::to_string(v) + ".");
  }
}

std::optional<LinkIndex> SimHost::link_to(NodeIndex v, protocols::NodeId to) const {
  const Network& net = simulator_.network();
  const IdLink* first = links_by_id_.data() + simulator_.local_link_start(v);
  const IdLink* last = first + net.neighbours(v).size();
  const IdLink* it = std::lower_bound(first, last, to, [](const IdLink& a, protocols::NodeId id) { return a.id < id; });
  if (it == last || it->id != to) return std::nullopt;
  return it->link;
}

void SimHost::reject(NodeIndex v, protocols::NodeId to) {
  ++bad_destinations_;
  const Network& net = simulator_.network();
  const bool known = net.index_of(to).has_value();
  LAGUERRE_PRECONDITION(known, "Node " + std::to_string(net.id(v)) + " cannot send to node " + std::to_string(to) +
                                   ": no such node in the network.");
  core::detail::assertion_failed("precondition", "link_to(v, to).has_value()", __FILE__, __LINE__,
                                 "Node " + std::to_string(net.id(v)) + " cannot send to node " + std::to_string(to) +
                                     ": they are not neighbours.");
}

SimHost::~SimHost() {
  nodes_.clear();  // nodes go first: they hold references to their runtimes
}

protocols::Runtime& SimHost::runtime(NodeIndex v) { return runtimes_[simulator_.local_index(v)]; }

Phase SimHost::phase(std::span<const std::byte> bytes) const {
  return phase_of_ ? phase_of_(bytes) : Phase{0};
}

void SimHost::on_start(Simulator&, NodeIndex v) { nodes_[simulator_.local_index(v)]->on_start(); }

void SimHost::on_message(Simulator& sim, NodeIndex v, NodeIndex from, Phase,
                         std::span<const std::byte> bytes) {
  nodes_[simulator_.local_index(v)]->on_message(sim.network().id(from), bytes);
}

void SimHost::on_timer(Simulator&, NodeIndex v, std::uint64_t timer) {
  nodes_[simulator_.local_index(v)]->on_timer(timer);
}

void SimHost::prefetch(NodeIndex v) const {
  const char* node = reinterpret_cast<const char*>(nodes_[simulator_.local_index(v)].get());
  for (int line = 0; line < 4; ++line) __builtin_prefetch(node + 64 * line);  // its first fields
  __builtin_prefetch(links_by_id_.data() + simulator_.local_link_start(v));  // for its replies
}

void SimHost::prefetch_state(NodeIndex v) const { nodes_[simulator_.local_index(v)]->prefetch(); }

void SimHost::on_recover(Simulator&, NodeIndex v) { nodes_[simulator_.local_index(v)]->on_recover(); }

}  // namespace laguerre::sim
