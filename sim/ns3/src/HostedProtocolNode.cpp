// The C++20 half of the ns-3 adapter: protocols::Runtime over a HostPort.
#include "laguerre/ns3/HostedProtocolNode.hpp"

#include <type_traits>

#include "laguerre/core/Error.hpp"

namespace laguerre::ns3host {

static_assert(std::is_same_v<NodeId, protocols::NodeId> && std::is_same_v<Time, protocols::Time> &&
                  std::is_same_v<Duration, protocols::Duration> && std::is_same_v<TimerId, protocols::TimerId> &&
                  std::is_same_v<TimerHandle, protocols::TimerHandle>,
              "HostPort.hpp's types must be protocols::Runtime's");

HostedProtocolNode::HostedProtocolNode(HostPort& port, const NodeFactory& make, SendObserver observe)
    : port_(port),
      observe_(std::move(observe)),
      stream_(sim::RandomStream::of(port.seed(), sim::StreamKind::node, port.self())),
      node_(make(*this)) {
  LAGUERRE_PRECONDITION(node_ != nullptr, "The node factory of an ns-3 host returned no node.");
}

HostedProtocolNode::~HostedProtocolNode() = default;

void HostedProtocolNode::start() { node_->on_start(); }

void HostedProtocolNode::message(NodeId from, const std::byte* data, std::size_t size) {
  node_->on_message(from, std::span<const std::byte>(data, size));
}

void HostedProtocolNode::timer(TimerId timer) { node_->on_timer(timer); }

void HostedProtocolNode::send(protocols::NodeId to, std::span<const std::byte> bytes) {
  port_.send(to, bytes.data(), bytes.size());
  if (observe_) observe_(to, bytes);
}

void HostedProtocolNode::broadcast(std::span<const std::byte> bytes) {
  for (const NodeId to : port_.neighbours()) send(to, bytes);
}

HostedFactory hosted(HostedProtocolNode::NodeFactory make, SendObserver observe) {
  return [make = std::move(make), observe = std::move(observe)](HostPort& port) -> std::unique_ptr<HostedNode> {
    return std::make_unique<HostedProtocolNode>(port, make, observe);
  };
}

protocols::Node& protocol_node(HostedNode& hosted_node) {
  auto* h = dynamic_cast<HostedProtocolNode*>(&hosted_node);
  LAGUERRE_PRECONDITION(h != nullptr, "protocol_node: this hosted node was not built by ns3host::hosted.");
  return h->node();
}

}  // namespace laguerre::ns3host
