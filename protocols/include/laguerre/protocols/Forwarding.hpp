#pragma once
/// @file
/// Greedy power forwarding hop by hop, after the packing protocol has converged: each node knows its
/// circle and its neighbours' circles (the final layout, PackingNode::neighbour_circles) and forwards a
/// data packet to the neighbour of least power distance to the target's centre.
///
/// The rule is core::greedy_power_next_hop's, decided with the same exact predicate
/// (core::compare_power: the exact sign of pow(p(t), u) − pow(p(t), w) on the stored doubles, which
/// core's filter only accelerates): the neighbour u minimising pow(p(t), u), ties to the smallest id,
/// if strictly better than the holder; otherwise the packet is at a dead end. Core breaks ties by
/// vertex index, so the two agree when ids increase with indices. As core::route, a node checks in
/// this order: it is the target (delivered), it has no better neighbour (dead end), the packet has
/// used its `ttl` hops (ttl exceeded), else it forwards. A route never jumps to an adjacent target.
///
/// Messages: DataMsg (Codec.hpp), one per hop. Outcomes go to a PacketSink the host provides (no
/// I/O): the node where a packet ends reports it; each node reports the hops it makes.

#include <cstdint>
#include <span>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols {

/// How a packet's journey ended.
enum class PacketOutcome : std::uint8_t {
  delivered,     ///< the target received it
  dead_end,      ///< a node had no neighbour strictly closer (in power) to the target
  ttl_exceeded,  ///< the hop limit was reached first
};

/// A data packet as the source's host injects it.
struct DataPacket {
  std::uint64_t packet = 0;  ///< packet id
  NodeId target = 0;         ///< target node id
  core::Circle target_circle;  ///< the target's circle (from a location service; only its centre is used)
  std::uint32_t ttl = 0;     ///< hop limit
};

/// The end of one packet's journey.
struct PacketReport {
  std::uint64_t packet = 0;   ///< packet id
  NodeId source = 0;          ///< source node
  NodeId target = 0;          ///< target node
  PacketOutcome outcome = PacketOutcome::delivered;  ///< how it ended
  NodeId at = 0;              ///< the node where it ended (the target, the dead end, or the holder at the limit)
  std::uint32_t hops = 0;     ///< hops taken
};

/// Where forwarding nodes report (implemented by the host; called from within node callbacks).
class PacketSink {
public:
  virtual ~PacketSink() = default;
  /// A packet's journey ended at `report.at`.
  virtual void on_packet_end(const PacketReport& report) = 0;
  /// Node `at` forwarded packet `packet` (from `source`) to `next`; `hops` counts this hop.
  virtual void on_forward(NodeId /*at*/, NodeId /*next*/, std::uint64_t /*packet*/, NodeId /*source*/,
                          std::uint32_t /*hops*/) {}
};

/// Per-node forwarding statistics.
struct ForwardingCounters {
  std::uint64_t forwarded = 0;   ///< DataMsg sent
  std::uint64_t received = 0;    ///< messages received
  std::uint64_t rejected = 0;    ///< malformed, from a non-neighbour, or not a DataMsg
};

/// One node of greedy power forwarding.
class ForwardingNode final : public Node {
public:
  /// A node with id `id`, neighbours `neighbours` and circles `own` and `neighbour_circles` (same
  /// order as `neighbours`); `runtime` and `sink` must outlive it. Throws std::invalid_argument if the
  /// sizes differ, a neighbour repeats or is the node itself, or a circle is not finite with r ≥ 0.
  ForwardingNode(Runtime& runtime, PacketSink& sink, NodeId id, std::vector<NodeId> neighbours, core::Circle own,
                 std::vector<core::Circle> neighbour_circles);

  /// Nothing to do: the node is ready once constructed.
  void on_start() override {}
  /// Forwards, delivers or drops (dead end, hop limit) a DataMsg from a neighbour; rejects anything else.
  void on_message(NodeId from, std::span<const std::byte> bytes) override;
  /// No timers are set: counted as rejected.
  void on_timer(TimerId) override { ++counters_.rejected; }

  /// Injects a packet at this node (its source), as if it had just arrived with 0 hops. Throws
  /// std::invalid_argument if the target circle is not finite with r ≥ 0.
  void originate(const DataPacket& p);

  /// The greedy power decision for a target centre: index of the next hop in `neighbours`, or the
  /// degree for a dead end.
  std::size_t next_hop(double tx, double ty) const;

  /// This node's id.
  NodeId id() const { return id_; }
  /// Statistics.
  const ForwardingCounters& counters() const { return counters_; }

private:
  void handle(const DataMsg& m);

  Runtime& rt_;
  PacketSink& sink_;
  NodeId id_;
  std::vector<NodeId> neighbours_;
  core::Circle own_;
  std::vector<core::Circle> circles_;
  std::vector<std::byte> buffer_;
  ForwardingCounters counters_;
};

}  // namespace laguerre::protocols
