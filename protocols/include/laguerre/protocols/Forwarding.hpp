#pragma once
/// @file
/// Packet forwarding hop by hop, after the packing protocol has converged: greedy power routing and
/// the core's baselines (greedy Euclidean, compass, greedy-face-greedy), each node deciding from its
/// own local knowledge only: its circle and position, its neighbours' circles and positions, and the
/// counter-clockwise rotation of its neighbours.
///
/// Every decision is core's: the rules of core/routing/NextHop.hpp over the node's neighbour view
/// (the same functions core::Router decides with), so a packet's path hop by hop is core::route's:
///  - greedy power: the neighbour u minimising pow(p(t), u), ties to the smallest id, if strictly
///    better than the holder; otherwise a dead end;
///  - greedy Euclidean: the same with |p(t) − p(u)|² on the positions;
///  - compass: the neighbour whose direction deviates least from that of p(t), ties to the smallest id;
///  - gfg: greedy Euclidean until a local minimum, then face routing (below).
/// Core breaks ties by vertex index, so the two agree when ids increase with indices. As core::route,
/// a node checks in this order: it is the target (delivered), it has no admissible next hop (dead end),
/// the packet has used its `ttl` hops (ttl exceeded), else it forwards. A route never jumps to an
/// adjacent target.
///
/// Positions: power routing uses the circles; the other schemes use the nodes' positions, which a host
/// sets to the deployment's coordinates, or (for graphs without coordinates) to the circles' centres,
/// as core does when it routes every scheme on one embedding. The neighbour list must be the
/// counter-clockwise rotation, starting where core::PlanarGraph::neighbours starts (face routing's
/// first face is searched from neighbours[0], as core searches from the first dart).
///
/// Greedy-face-greedy hop by hop (core's Router::route_gfg, one node's share). The packet (RouteMsg)
/// carries its mode; in perimeter mode it also carries P (the entry node's position), the position of
/// the last face change (P itself, or the crossing of the line PT with an edge, kept symbolically as
/// that edge's end points: core::FaceChange), and the first edge of the walk since that change.
///  - greedy mode at v: the greedy Euclidean next hop if any; otherwise v enters perimeter mode: the
///    first face is the one whose corner at v (between two consecutive neighbours) contains the
///    direction of T (none: dead end).
///  - perimeter mode at v, arrived from u: delivered at t; back to greedy mode if v is strictly closer
///    to T than P; otherwise the next edge is the right-hand rule's (the neighbour after u
///    counter-clockwise), and if it is the walk's first edge the walk went round a face without
///    progress: a loop (possible only in a drawing that is not plane).
///  - before sending along an edge v → w, v applies the face change rule: if the edge properly crosses
///    the line PT strictly beyond the last face change and not beyond T, that crossing becomes the last
///    face change, and if T lies left of v → w the packet turns to the next neighbour counter-clockwise
///    (the other face of the edge), testing again.
///
/// Compass loops: compass routing is memoryless, so a packet that reaches a node a second time will
/// cycle forever; core reports `loop` at the revisited node. Hop by hop, each node remembers the hop
/// count at which it first held each compass packet (source, packet id): a later arrival with another
/// hop count is a loop, one with the same count a duplicate of the network (ignored and counted).
/// Greedy schemes cannot revisit a node (their metric strictly decreases).
///
/// Messages: DataMsg (greedy power) and RouteMsg (the other schemes), Codec.hpp, one per hop. Outcomes
/// go to a PacketSink the host provides (no I/O): the node where a packet ends reports it; each node
/// reports the hops it makes.

#include <cstdint>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/routing/NextHop.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols {

/// How a packet's journey ended.
enum class PacketOutcome : std::uint8_t {
  delivered,     ///< the target received it
  dead_end,      ///< a node had no admissible next hop (greedy local minimum; GFG found no face)
  ttl_exceeded,  ///< the hop limit was reached first
  loop,          ///< the packet would cycle forever (compass revisit; GFG walked a face without progress)
};

/// The outcome's name: "delivered", "dead_end", "ttl_exceeded" or "loop".
std::string_view to_string(PacketOutcome o);

/// A data packet as the source's host injects it.
struct DataPacket {
  std::uint64_t packet = 0;      ///< packet id
  NodeId target = 0;             ///< target node id
  core::Circle target_circle;    ///< the target's circle (greedy power; only its centre is used)
  std::uint32_t ttl = 0;         ///< hop limit
  core::Scheme scheme = core::Scheme::greedy_power;  ///< routing scheme
  core::Point2 target_position;  ///< the target's position (the other schemes; from a location service)
};

/// The end of one packet's journey.
struct PacketReport {
  std::uint64_t packet = 0;   ///< packet id
  NodeId source = 0;          ///< source node
  NodeId target = 0;          ///< target node
  PacketOutcome outcome = PacketOutcome::delivered;  ///< how it ended
  NodeId at = 0;              ///< where it ended: the target, the dead end, the revisited node (loop),
                              ///< or the holder at the limit
  std::uint32_t hops = 0;     ///< hops taken
  core::Scheme scheme = core::Scheme::greedy_power;  ///< routing scheme
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
  std::uint64_t forwarded = 0;   ///< DataMsg and RouteMsg sent
  std::uint64_t received = 0;    ///< messages received
  std::uint64_t rejected = 0;    ///< malformed, from a non-neighbour, or not a data packet
  std::uint64_t duplicates = 0;  ///< a compass packet received again with the same hop count (ignored)
};

/// Whether a forwarding node accepts `c` as a circle: finite centre and radius, radius ≥ 0.
bool forwardable(const core::Circle& c);

/// One node of hop-by-hop forwarding (every scheme).
class ForwardingNode final : public Node {
public:
  /// A node with id `id`, neighbours `neighbours` (counter-clockwise, see the file comment) and
  /// circles `own` and `neighbour_circles` (same order as `neighbours`); positions are the circles'
  /// centres. `runtime` and `sink` must outlive it. Throws core::InternalError (a broken precondition) if the sizes differ,
  /// a neighbour repeats or is the node itself, or a circle is not finite with r ≥ 0.
  ForwardingNode(Runtime& runtime, PacketSink& sink, NodeId id, std::vector<NodeId> neighbours, core::Circle own,
                 std::vector<core::Circle> neighbour_circles);

  /// As above with explicit positions for the geometric schemes (`neighbour_positions` in the order of
  /// `neighbours`). Throws core::InternalError (a broken precondition) also if a position is not finite or the sizes differ.
  ForwardingNode(Runtime& runtime, PacketSink& sink, NodeId id, std::vector<NodeId> neighbours, core::Circle own,
                 std::vector<core::Circle> neighbour_circles, core::Point2 position,
                 std::vector<core::Point2> neighbour_positions);

  /// Nothing to do: the node is ready once constructed.
  void on_start() override {}
  /// Forwards, delivers or ends (dead end, hop limit, loop) a DataMsg or RouteMsg from a neighbour;
  /// rejects anything else.
  void on_message(NodeId from, std::span<const std::byte> bytes) override;
  /// No timers are set: counted as rejected.
  void on_timer(TimerId) override { ++counters_.rejected; }

  /// Injects a packet at this node (its source), as if it had just arrived with 0 hops. Throws
  /// core::InternalError (a broken precondition) if the target circle (greedy power) or position (other schemes) is not
  /// finite.
  void originate(const DataPacket& p);

  /// The greedy power decision for a target centre: index of the next hop in `neighbours`, or the
  /// degree for a dead end.
  std::size_t next_hop(double tx, double ty) const;
  /// The greedy Euclidean decision for a target position: index of the next hop, or the degree.
  std::size_t next_hop_euclid(core::Point2 t) const;
  /// The compass decision for a target position: index of the next hop, or the degree (no neighbour).
  std::size_t next_hop_compass(core::Point2 t) const;

  /// This node's id.
  NodeId id() const { return id_; }
  /// Statistics.
  const ForwardingCounters& counters() const { return counters_; }

private:
  static constexpr std::size_t no_neighbour = static_cast<std::size_t>(-1);

  core::NeighbourView view() const;
  void handle(const DataMsg& m);
  void handle(RouteMsg m, std::size_t from);
  void gfg(RouteMsg& m, std::size_t from);
  void perimeter_step(RouteMsg& m, std::size_t d);
  void forward(RouteMsg& m, std::size_t next);
  void end(const RouteMsg& m, PacketOutcome o);
  std::size_t index_of(NodeId n) const;

  Runtime& rt_;
  PacketSink& sink_;
  NodeId id_;
  std::vector<NodeId> neighbours_;
  core::Circle own_;
  std::vector<core::Circle> circles_;
  core::Point2 position_;
  std::vector<core::Point2> positions_;
  std::map<std::pair<NodeId, std::uint64_t>, std::uint32_t> compass_seen_;  // (source, packet) → hops
  std::vector<std::byte> buffer_;
  ForwardingCounters counters_;
};

}  // namespace laguerre::protocols
