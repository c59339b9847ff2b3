#pragma once
/// @file
/// The narrow interface between a node's protocol code and whatever hosts it (our discrete-event
/// kernel, a test harness, an Asio/UDP runtime, an ns-3 `Application` adapter, an MPI partition).
///
/// Contract, in both directions:
///  - A node never owns a loop, never blocks, never reads a clock or does I/O, and has no globals. It
///    only reacts to `Node::on_start`, `Node::on_message` and `Node::on_timer`, and acts through the
///    `Runtime` it was constructed with.
///  - A host calls `on_start` exactly once, before any other callback, and never calls a node
///    re-entrantly: `send`, `broadcast` and `schedule` only enqueue; delivery happens after the
///    current callback returns.
///  - `send`/`broadcast` copy the bytes before returning, so a node may reuse its buffer. The span
///    given to `on_message` is valid only during that call.
///  - Messages travel only between neighbours (the node's static neighbour list). A host may lose,
///    duplicate, delay or reorder them, as its channel model says; protocols document what they
///    tolerate.
///  - Time is an integer number of nanoseconds of the host's (simulated or real) clock.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace laguerre::protocols {

/// A node's network identity: the user id of its vertex (core::PlanarGraph::id).
using NodeId = std::uint64_t;
/// A point in time, in nanoseconds of the host's clock.
using Time = std::int64_t;
/// A span of time, in nanoseconds.
using Duration = std::int64_t;
/// A protocol-chosen tag identifying what a timer is for (returned to the node by on_timer).
using TimerId = std::uint64_t;
/// A host-chosen handle identifying one scheduled timer (for cancel); never 0 for a live timer.
using TimerHandle = std::uint64_t;

/// A position in the plane (for hosts whose nodes know where they are, e.g. for distance-based
/// latency; the packing protocol does not use it).
struct Position {
  double x = 0;  ///< abscissa
  double y = 0;  ///< ordinate
};

/// Everything a node knows about the network before the first message: its static local knowledge.
///
/// `neighbours` lists the ids of the neighbours in counter-clockwise order around the node. The order
/// is cyclic, but its starting point matters for bit-exact reproduction of the centralized iteration
/// (floating-point sums run around the node starting from `neighbours[0]`): build it with
/// `local_knowledge` (PackingNode.hpp) to start where core::PlanarGraph::neighbours(v) starts.
/// For a boundary node, `outer_gap` = i says that the outer face lies between `neighbours[i]` and
/// `neighbours[(i + 1) % degree]` (going counter-clockwise); interior nodes have `outer_gap` = none.
struct LocalKnowledge {
  static constexpr std::uint32_t no_gap = 0xffffffffu;  ///< `outer_gap` of an interior node

  NodeId id = 0;                       ///< this node's id
  std::vector<NodeId> neighbours;      ///< neighbour ids, counter-clockwise
  bool boundary = false;               ///< whether the node lies on the outer face
  std::uint32_t outer_gap = no_gap;    ///< boundary nodes: index i of the outer-face wedge (see above)
  std::optional<Position> position;    ///< the node's position, when the deployment knows it
  /// Faces, for 3-connected graphs: empty when every inner wedge is a triangle; otherwise one entry
  /// per neighbour i: the ids of the inner face between `neighbours[i]` and `neighbours[i + 1]`
  /// (counter-clockwise), as its counter-clockwise walk starting at this node (so entry[1] =
  /// neighbours[i] and entry.back() = neighbours[i + 1]) when it has more than 3 vertices, and empty
  /// for triangles and the outer face. G-face-local knowledge (thesis §5.3.2): a face discovery phase
  /// (a token walking each face) would compute it from the rotations alone.
  std::vector<std::vector<NodeId>> faces;
};

/// What a host provides to the node it runs (one Runtime object per node).
class Runtime {
public:
  virtual ~Runtime() = default;

  /// The id of the node this runtime serves.
  virtual NodeId self() const = 0;
  /// Current time of the host's clock, in nanoseconds.
  virtual Time now() const = 0;
  /// Sends `bytes` to neighbour `to` (copied before returning). Sending to a non-neighbour is a
  /// programmer error the host may reject by throwing core::InternalError (LAGUERRE_PRECONDITION).
  virtual void send(NodeId to, std::span<const std::byte> bytes) = 0;
  /// Sends `bytes` to every neighbour (copied before returning).
  virtual void broadcast(std::span<const std::byte> bytes) = 0;
  /// Schedules `on_timer(timer)` after `after` ≥ 0 nanoseconds; returns a handle for `cancel`.
  virtual TimerHandle schedule(Duration after, TimerId timer) = 0;
  /// Cancels a pending timer; returns false if it already fired or was cancelled (not an error).
  virtual bool cancel(TimerHandle handle) = 0;
  /// Next value of this node's random stream, keyed by (run seed, node id) so that it does not depend
  /// on how the host interleaves nodes.
  virtual std::uint64_t random_u64() = 0;
};

/// What a protocol implements: the callbacks a host invokes. Nodes hold a `Runtime&` given at
/// construction, which must outlive them.
class Node {
public:
  virtual ~Node() = default;

  /// Called once, before any other callback.
  virtual void on_start() = 0;
  /// A message from neighbour `from`; `bytes` is valid only during the call. Malformed input must be
  /// rejected (and counted), never trusted.
  virtual void on_message(NodeId from, std::span<const std::byte> bytes) = 0;
  /// A timer scheduled with `Runtime::schedule(…, timer)` fired.
  virtual void on_timer(TimerId timer) = 0;
  /// The node is back after a crash (hosts that model outages call it; never before on_start). Its
  /// state survived, but messages sent to it and timers due during the outage were lost: a node
  /// re-arms what it needs here. The default does nothing.
  virtual void on_recover() {}
  /// A layer under the node (ReliableNode, Reliable.hpp) declared node `suspect` failed and delivers
  /// nothing more to it; called at most once. The default does nothing.
  virtual void on_failure(NodeId suspect) { static_cast<void>(suspect); }
  /// Whether the node's work is done for good: a layer under it then stops probing its neighbours
  /// for liveness. The default: never.
  virtual bool is_final() const { return false; }
  /// A hint from a host that delivers messages from a queue: a message for this node is a few
  /// events ahead; start loading (__builtin_prefetch) the state on_message will touch. Must not
  /// change anything. The default does nothing.
  virtual void prefetch() const {}
};

}  // namespace laguerre::protocols
