#pragma once
/// @file
/// The laguerre (C++20) half of the ns-3 adapter: a protocols::Node running on a HostPort. The node
/// sees a protocols::Runtime whose calls go to the port (broadcast = one send per neighbour, in the
/// port's order); the port's callbacks go to the node. Include it from C++20 code only; the ns-3
/// (C++17) half is NodeApplication.hpp.

#include <functional>
#include <memory>
#include <span>

#include "laguerre/ns3/HostPort.hpp"
#include "laguerre/protocols/Runtime.hpp"
#include "laguerre/sim/Random.hpp"

namespace laguerre::ns3host {

/// Sees every message the node sends, after the port accepted it (for traffic statistics).
using SendObserver = std::function<void(NodeId to, std::span<const std::byte> bytes)>;

/// A protocols::Node hosted through a HostPort; its random stream is sim::RandomStream::of(port.seed(),
/// StreamKind::node, port.self()), as in the simulator.
class HostedProtocolNode final : public HostedNode, private protocols::Runtime {
public:
  /// Builds the node, given the runtime it must use (valid as long as this object).
  using NodeFactory = std::function<std::unique_ptr<protocols::Node>(protocols::Runtime&)>;

  /// The node `make` builds on `port` (which must outlive this object). Throws core::InternalError
  /// (a broken precondition) if `make` returns a null node.
  HostedProtocolNode(HostPort& port, const NodeFactory& make, SendObserver observe = {});
  HostedProtocolNode(const HostedProtocolNode&) = delete;
  HostedProtocolNode& operator=(const HostedProtocolNode&) = delete;
  ~HostedProtocolNode() override;

  /// Node::on_start.
  void start() override;
  /// Node::on_message.
  void message(NodeId from, const std::byte* data, std::size_t size) override;
  /// Node::on_timer.
  void timer(TimerId timer) override;

  /// The hosted node.
  protocols::Node& node() { return *node_; }
  /// The hosted node, read-only.
  const protocols::Node& node() const { return *node_; }

private:
  protocols::NodeId self() const override { return port_.self(); }
  protocols::Time now() const override { return port_.now(); }
  void send(protocols::NodeId to, std::span<const std::byte> bytes) override;
  void broadcast(std::span<const std::byte> bytes) override;
  protocols::TimerHandle schedule(protocols::Duration after, protocols::TimerId timer) override {
    return port_.schedule(after, timer);
  }
  bool cancel(protocols::TimerHandle handle) override { return port_.cancel(handle); }
  std::uint64_t random_u64() override { return stream_.next_u64(); }

  HostPort& port_;
  SendObserver observe_;
  sim::RandomStream stream_;
  std::unique_ptr<protocols::Node> node_;
};

/// A HostedFactory for NodeApplication::host: a HostedProtocolNode of the node `make` builds.
HostedFactory hosted(HostedProtocolNode::NodeFactory make, SendObserver observe = {});

/// The protocol node inside a hosted node that `hosted` built (core::InternalError otherwise).
protocols::Node& protocol_node(HostedNode& hosted_node);

}  // namespace laguerre::ns3host
