#pragma once
/// @file
/// The C++17 boundary between an ns-3 host and a laguerre node. ns-3 3.37's headers compile only as
/// C++17 (template-ids as constructor names are ill-formed in C++20) and laguerre's protocol headers
/// only as C++20 (std::span), so no translation unit sees both: the ns-3 side (NodeApplication.hpp)
/// implements `HostPort`, the laguerre side (HostedProtocolNode.hpp) implements `HostedNode` around a
/// protocols::Node, and this header, which includes neither, is all they share.
///
/// The port mirrors protocols::Runtime (same types, same contract; see Runtime.hpp; the random
/// stream is the hosted node's, keyed by the port's seed and id, as the simulator keys it): `send` copies
/// the bytes before returning and never calls back into the node; `schedule` takes a delay ≥ 0 in
/// nanoseconds; a host calls `HostedNode::start` once, before anything else, and never calls a
/// hosted node re-entrantly.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace laguerre::ns3host {

using NodeId = std::uint64_t;       ///< protocols::NodeId
using Time = std::int64_t;          ///< protocols::Time (ns)
using Duration = std::int64_t;      ///< protocols::Duration (ns)
using TimerId = std::uint64_t;      ///< protocols::TimerId
using TimerHandle = std::uint64_t;  ///< protocols::TimerHandle (never 0 for a live timer)

/// What the host offers the node it runs: protocols::Runtime without the C++20 types.
class HostPort {
public:
  virtual ~HostPort() = default;
  /// The node's id.
  virtual NodeId self() const = 0;
  /// The host's clock, in nanoseconds.
  virtual Time now() const = 0;
  /// The node's neighbours, in the order the host was given them.
  virtual const std::vector<NodeId>& neighbours() const = 0;
  /// Sends `size` bytes at `data` to neighbour `to` (copied before returning). Throws
  /// core::InternalError for a non-neighbour, core::InputError for a message larger than the host's
  /// datagrams can carry.
  virtual void send(NodeId to, const std::byte* data, std::size_t size) = 0;
  /// Schedules the hosted node's `timer(timer)` after `after` ≥ 0 ns; returns a handle for `cancel`.
  virtual TimerHandle schedule(Duration after, TimerId timer) = 0;
  /// Cancels a pending timer; false if it already fired or was cancelled.
  virtual bool cancel(TimerHandle handle) = 0;
  /// The run's seed (the hosted node keys its random stream with it and its id).
  virtual std::uint64_t seed() const = 0;
};

/// A node as its host sees it: protocols::Node without the C++20 types.
class HostedNode {
public:
  virtual ~HostedNode() = default;
  /// Called once, before any other callback.
  virtual void start() = 0;
  /// A message of `size` bytes at `data` from neighbour `from` (valid only during the call).
  virtual void message(NodeId from, const std::byte* data, std::size_t size) = 0;
  /// A timer scheduled with HostPort::schedule fired.
  virtual void timer(TimerId timer) = 0;
};

/// Builds the hosted node of a host, given the port it must use (which outlives it).
using HostedFactory = std::function<std::unique_ptr<HostedNode>(HostPort&)>;

/// A host's datagram statistics (payload bytes; the UDP and IP headers are not counted).
struct HostCounters {
  std::uint64_t datagrams_sent = 0;      ///< datagrams the socket accepted
  std::uint64_t bytes_sent = 0;          ///< their payload bytes
  std::uint64_t send_failures = 0;       ///< datagrams the socket refused (dropped at the sender)
  std::uint64_t datagrams_received = 0;  ///< datagrams handed to the node
  std::uint64_t bytes_received = 0;      ///< their payload bytes
  std::uint64_t unknown_sources = 0;     ///< datagrams from an address that is no neighbour's (dropped)
  std::uint64_t timers_fired = 0;        ///< timers handed to the node

  /// Adds `o` field by field.
  HostCounters& operator+=(const HostCounters& o) {
    datagrams_sent += o.datagrams_sent;
    bytes_sent += o.bytes_sent;
    send_failures += o.send_failures;
    datagrams_received += o.datagrams_received;
    bytes_received += o.bytes_received;
    unknown_sources += o.unknown_sources;
    timers_fired += o.timers_fired;
    return *this;
  }
};

}  // namespace laguerre::ns3host
