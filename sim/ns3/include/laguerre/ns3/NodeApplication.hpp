#pragma once
/// @file
/// The ns-3 (C++17) half of the adapter: an ns3::Application that hosts one laguerre node
/// (a HostedNode; HostedProtocolNode.hpp wraps a protocols::Node into one). Include it from C++17
/// code only (ns-3 3.37's headers are not C++20).
///
/// Mapping of the Runtime contract (README, "Embedding laguerre in another simulator"):
///  - send → one UDP datagram (UdpSocketFactory, one socket bound to `port` on every address of the
///    node) to the neighbour's address given in `configure`; the payload is the message's bytes;
///  - schedule → ns3::Simulator::Schedule, cancel → EventId::Cancel, now → Simulator::Now in ns;
///  - receive → the datagram's source address names the neighbour (datagrams from any other address
///    are dropped and counted); datagrams and timers are queued and handed to the node one at a
///    time, never while it is inside a callback;
///  - random_u64 → the node's counter-based stream keyed by (`seed`, node id), sim/Random.hpp's
///    StreamKind::node, as the simulator keys it (kept by HostedProtocolNode: sim/Random.hpp is
///    C++20); each hosted node starts the stream afresh.

#include <cstdint>
#include <deque>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "laguerre/ns3/HostPort.hpp"
#include "ns3/application.h"
#include "ns3/event-id.h"
#include "ns3/ipv4-address.h"
#include "ns3/ptr.h"
#include "ns3/socket.h"

namespace laguerre::ns3host {

/// A neighbour of the hosted node and the address its datagrams go to (and come from).
struct Neighbour {
  NodeId id = 0;               ///< its node id
  ::ns3::Ipv4Address address;  ///< its address on the link or channel the two share
};

/// The application hosting one laguerre node on an ns-3 node with an internet stack.
class NodeApplication final : public ::ns3::Application, private HostPort {
public:
  /// The largest payload of one UDP datagram over IPv4.
  static constexpr std::size_t max_datagram = 65507;

  /// ns-3's type id ("laguerre::ns3host::NodeApplication").
  static ::ns3::TypeId GetTypeId();
  NodeApplication();
  ~NodeApplication() override;

  /// Sets the node's id, its neighbours (distinct ids and addresses, not the node itself), the UDP
  /// port every node of the run listens on, and the run's seed. Call once, before the application
  /// starts. Throws core::InternalError (a broken precondition) otherwise.
  void configure(NodeId self, std::vector<Neighbour> neighbours, std::uint16_t port, std::uint64_t seed);
  /// Hosts the node `make` builds, replacing (and destroying) the current one: its pending timers
  /// are cancelled and its undelivered input dropped. The new node starts when the application does,
  /// or, if it already runs, in an event at the current time in this ns-3 node's context.
  void host(const HostedFactory& make);
  /// The hosted node (null before `host`).
  HostedNode* hosted() { return node_.get(); }
  /// Datagram statistics since the application started.
  const HostCounters& counters() const { return counters_; }
  /// When the hosted node last got a callback (ns; -1 if never).
  Time last_activity() const { return last_activity_; }

private:
  struct Input {
    bool is_timer = false;
    NodeId from = 0;
    TimerId timer = 0;
    TimerHandle handle = 0;  // a timer's, so that cancel can still withdraw it from the queue
    std::vector<std::byte> bytes;
  };

  void StartApplication() override;
  void StopApplication() override;
  void DoDispose() override;

  NodeId self() const override { return self_; }
  Time now() const override;
  const std::vector<NodeId>& neighbours() const override { return neighbour_ids_; }
  void send(NodeId to, const std::byte* data, std::size_t size) override;
  TimerHandle schedule(Duration after, TimerId timer) override;
  bool cancel(TimerHandle handle) override;
  std::uint64_t seed() const override { return seed_; }

  void start_node();
  void receive(::ns3::Ptr<::ns3::Socket> socket);
  void fire(TimerHandle handle, TimerId timer);
  void dispatch();
  void cancel_all();

  NodeId self_ = 0;
  bool configured_ = false;
  bool running_ = false;
  bool busy_ = false;     // inside a callback of the hosted node
  bool started_ = false;  // the hosted node's start ran
  std::uint16_t port_ = 0;
  std::uint64_t seed_ = 0;
  std::vector<Neighbour> neighbours_;
  std::vector<NodeId> neighbour_ids_;
  std::vector<std::pair<std::uint32_t, NodeId>> by_address_;  // sorted, for the source of a datagram
  ::ns3::Ptr<::ns3::Socket> socket_;
  std::unique_ptr<HostedNode> node_;
  std::deque<Input> inbox_;
  std::unordered_map<TimerHandle, ::ns3::EventId> timers_;
  TimerHandle next_handle_ = 1;
  HostCounters counters_;
  Time last_activity_ = -1;
};

}  // namespace laguerre::ns3host
