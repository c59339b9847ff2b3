#pragma once
/// @file
/// The distributed circle-packing protocol (thesis §5.3) for triangulated discs and 3-connected plane
/// graphs: one `PackingNode` per network node, hosted through `Runtime`. Modes: synchronous (the
/// radii, circles and iteration count of core::pack bit for bit), optionally over lossy links with
/// crash detection (the reliability layer, on when `PackingParams::retransmit_after` > 0; still bit
/// for bit), and asynchronous (same stop rule, results depend on timing). docs/protocol.md describes
/// the phases, the face vertices of 3-connected graphs, the reliability layer and the message sets.
///
/// Guarantees, given a connected graph with at least one interior vertex, every node built with
/// `local_knowledge` and the same PackingParams, and a host that keeps the Runtime contract:
///  - reliable links, any delays and any delivery order: every node ends in PackingPhase::finished
///    with PackingOutcome::converged or cap, holding core::pack's result for its vertex;
///  - lossy, duplicating links with the reliability layer: the same, unless a node stops answering
///    for about `max_retransmissions` backed-off periods; then every surviving node ends with
///    PackingOutcome::neighbour_failed, and every node goes quiet (the host's queue drains).
/// Malformed messages, messages of another message set (Codec.hpp) and messages that do not fit the
/// node's state are counted (PackingCounters) and dropped, never trusted.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/core/packing/Accelerator.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/packing/Placement.hpp"
#include "laguerre/core/packing/RadiusOnly.hpp"
#include "laguerre/core/packing/Thurston.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/Reliable.hpp"
#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols {

/// The static knowledge of vertex v of g, with neighbours listed from `g.neighbours(v)[0]` (the order
/// that makes the node's sums agree with core's bit for bit), the outer-face wedge located and, when
/// some inner face of g is not a triangle, the walks of v's non-triangle inner faces.
LocalKnowledge local_knowledge(const core::PlanarGraph& g, core::Vertex v);

/// Largest node id the 3-connected mode supports (face vertex ids pack two node ids).
inline constexpr NodeId max_face_node_id = (NodeId{1} << 31) - 1;

/// The id of the face vertex of the face whose walk has `successor` right after its host `host`
/// (both ≤ max_face_node_id): 2^63 + host·2^31 + successor, never a node id.
constexpr NodeId face_vertex_id(NodeId host, NodeId successor) { return (NodeId{1} << 63) | (host << 31) | successor; }

/// Parameters shared by all nodes of a run: the values core::PackOptions would hold, plus the
/// reliability layer's (inherited; `retransmit_after` = 0, the default, means reliable links and no
/// layer).
struct PackingParams : ReliableParams {
  int steps_per_check = 1;                                        ///< N: Thurston steps per round (≥ 1)
  int max_iterations = 100000;                                    ///< cap on steps (≥ 0)
  core::UpdateRule update = core::UpdateRule::uniform_neighbour;  ///< per-vertex update
  core::RootRule root = core::RootRule::deepest;                  ///< which root the election picks
  bool asynchronous = false;  ///< asynchronous Thurston updates (chaotic relaxation); not bit for bit with core
  /// plain, or (synchronous mode only) a local acceleration (core::is_local: chebyshev, local_superstep;
  /// each protocol vertex runs a core::LocalAccelerator on its own updates, with no extra message) or
  /// newton_krylov (Newton steps whose CG runs in the network: core/packing/NewtonKrylov.hpp).
  core::Acceleration acceleration = core::Acceleration::plain;
  /// layout: every round lays out and checks LPD/GLPD (thesis §5.3); radius_only (synchronous mode
  /// only): every round ends with one radius exchange and the closing-gap test (core/packing/
  /// RadiusOnly.hpp) instead, the layout wave and exact check run only when it holds everywhere (or
  /// at the cap), and each failed exact check halves the gap — core::pack with Termination::radius_only
  /// bit for bit (docs/radius-only.md); radius_flood (synchronous only): the test's AND travels on the
  /// radius exchange itself (GateRadiusMsg, every K-edge, boundary included) and is decided D steps
  /// after each tested step with no convergecast — core::pack with Termination::radius_flood bit for bit.
  core::Termination termination = core::Termination::layout;
  double radius_only_gap = 1e-2;  ///< initial closing-gap tolerance (radians, > 0) of radius_only
};

/// The centralized computation a synchronous run with `params` equals bit for bit: core::pack with
/// stop = lpd, Jacobi sweeps, and the update, root, N, cap, acceleration and termination of `params`.
core::PackOptions reference_options(const PackingParams& params);

/// Turns the reliability layer on with periods fitted to links whose one-way latency is at most
/// `max_latency` ns: ack_delay = max_latency / 2, retransmit_after = 3 × max_latency (above the longest
/// round trip plus the ack delay), other fields unchanged.
void enable_lossy_links(PackingParams& params, Duration max_latency);

/// Where a node is in the protocol.
enum class PackingPhase : std::uint8_t {
  idle,      ///< on_start not yet called
  depth,     ///< BFS from the boundary
  election,  ///< leader election
  wave,      ///< combinatorial layout wave (and the shape convergecast)
  rounds,    ///< Thurston steps, layout, check, convergecast
  finished,  ///< the root's decision to stop reached this node
};

/// How a node's run ended.
enum class PackingOutcome : std::uint8_t {
  running,    ///< not finished
  converged,  ///< LPD/GLPD holds everywhere
  cap,        ///< the iteration cap was reached first
  neighbour_failed,  ///< some node stopped answering (PackingNode::suspect names it); the run was abandoned
};

/// Per-node message statistics (physical messages: a relayed envelope counts at every hop): the
/// reliability layer's on lossy links (inherited; zero otherwise, but for the fields both count), and
/// the protocol's. `unexpected` also counts messages of the node's set that do not fit its state,
/// `bad_payload` also relay payloads that did not decode.
struct PackingCounters : ReliableCounters {
  std::uint64_t relayed = 0;  ///< RelayMsg envelopes forwarded for others

  /// Adds `o` field by field (totals over nodes).
  PackingCounters& operator+=(const PackingCounters& o) {
    ReliableCounters::operator+=(o);
    relayed += o.relayed;
    return *this;
  }
};

/// The state of one protocol vertex (the node's own vertex or a hosted face vertex).
struct VertexState {
  NodeId id = 0;                    ///< protocol id (node id, or face_vertex_id for a face vertex)
  std::uint32_t depth = 0;          ///< depth from the boundary in K
  NodeId bfs_parent = 0;            ///< parent in the depth BFS forest: the first neighbour (K order) one
                                    ///< shallower; its own id on the boundary
  bool is_root = false;             ///< whether it is the elected root
  std::uint32_t wave = 0;           ///< layout wave in which it is placed
  NodeId parent = 0;                ///< parent in the layout tree (its own id for the root)
  std::uint32_t steps = 0;          ///< Thurston steps done
  std::uint32_t round = 0;          ///< current round
  double h = 0;                     ///< current hyperbolic radius (∞ on the boundary)
  core::PlacedCircle placement;     ///< placement in the latest layout
  core::LocalCondition local = core::LocalCondition::unrepresentable;  ///< latest local check
  PackingPhase phase = PackingPhase::idle;  ///< phase
};

namespace detail {
class PackingAgent;
}  // namespace detail

/// One node of the packing protocol: its own protocol vertex plus the face vertices it hosts, and (on
/// lossy links, `PackingParams::retransmit_after` > 0) the reliability layer under them: a
/// ReliableNode (Reliable.hpp) that the node owns and through which its protocol talks to the host.
class PackingNode final : public Node {
public:
  /// A node with its static knowledge; `runtime` must outlive it. Throws core::InternalError (a broken precondition) if the
  /// knowledge is inconsistent (no neighbours, repeated neighbours, itself as neighbour, a boundary
  /// node without an outer wedge or an interior node with one, face walks that do not match the
  /// neighbours) or the parameters are out of range (an acceleration the network cannot run, or a local
  /// one in asynchronous mode); core::InputError if a polygon-face node id is above
  /// 2^31 − 1 (ids come from the user's graph file).
  PackingNode(Runtime& runtime, LocalKnowledge knowledge, PackingParams params);
  /// Destroys the node and its hosted vertices.
  ~PackingNode() override;
  /// Not copyable (its agents refer to it).
  PackingNode(const PackingNode&) = delete;
  /// Not copyable.
  PackingNode& operator=(const PackingNode&) = delete;

  /// Starts the node's own vertex and the face vertices it hosts.
  void on_start() override;
  /// Decodes a message of the node's set (PackingHop; LinkMessage with the reliability layer, whose
  /// frames carry a FramePayload): an envelope is relayed or delivered to a hosted vertex, a failure
  /// notice ends the run, a protocol message goes to the node's own vertex.
  void on_message(NodeId from, std::span<const std::byte> bytes) override;
  /// The reliability layer's timers (retransmission, delayed ack, probe); without it, counted as
  /// unexpected.
  void on_timer(TimerId timer) override;
  /// Back from an outage: re-arms the reliability layer's timers (retransmissions, owed acks, probes
  /// while running); the node's state survived, lost messages are recovered like any loss.
  void on_recover() override;
  /// Whether the node is done: stopped by the decision, or ended by a failure.
  bool is_final() const override;
  /// A reliability layer under the node (its own or one wrapping it) declared `suspect` failed: the
  /// run is abandoned with PackingOutcome::neighbour_failed.
  void on_failure(NodeId suspect) override;
  /// Prefetches the neighbour list and the own vertex's records (the receive path's first reads).
  void prefetch() const override;

  /// The current phase.
  PackingPhase phase() const;
  /// How the run ended (running until the stop decision or a failure notice arrives).
  PackingOutcome outcome() const;
  /// The node suspected of having failed (meaningful when outcome() is neighbour_failed).
  NodeId suspect() const { return suspect_; }
  /// When the node became final (the runtime's clock at the end of that callback); -1 while running.
  Time finished_at() const { return finished_at_; }
  /// The current retransmission timeout towards neighbour i (lossy mode; 0 without it).
  Duration rto(std::size_t i) const;
  /// This node's id.
  NodeId id() const { return know_.id; }
  /// Depth from the boundary in K (set-up result; meaningful once past the depth phase).
  std::uint32_t depth() const;
  /// Whether this node is the elected root.
  bool is_root() const;
  /// Layout wave in which this node is placed (set-up result).
  std::uint32_t wave() const;
  /// Parent in the layout tree (its own id for the root; a face vertex id when placed from one).
  NodeId parent() const;
  /// Number of children in the layout tree.
  std::size_t children() const;
  /// Thurston steps done (the iteration count, equal at every node).
  std::uint32_t steps() const;
  /// Current round (the number of the last or current layout).
  std::uint32_t round() const;
  /// Current hyperbolic radius (∞ on the boundary).
  double h() const;
  /// This node's placement in the latest layout.
  const core::PlacedCircle& placement() const;
  /// The local LPD/GLPD outcome in the latest layout.
  core::LocalCondition local_condition() const;
  /// Whether the run packs G′ (some inner face is not a triangle; known after the set-up).
  bool polygon_faces() const;
  /// Message statistics (the protocol's and, on lossy links, the reliability layer's).
  PackingCounters counters() const;
  /// Number of face vertices this node hosts.
  std::size_t hosted_faces() const { return faces_.size(); }
  /// The walk (ids, from this node) of hosted face k < hosted_faces().
  const std::vector<NodeId>& hosted_face_walk(std::size_t k) const;
  /// The state of hosted face vertex k < hosted_faces().
  VertexState hosted_face_state(std::size_t k) const;
  /// The state of this node's own vertex.
  VertexState state() const;
  /// The circles of the neighbours (in `LocalKnowledge::neighbours` order) in the latest layout this
  /// node has checked: after convergence, what ForwardingNode needs (Forwarding.hpp).
  std::vector<core::Circle> neighbour_circles() const;

private:
  friend class detail::PackingAgent;
  struct Wedge;     // a non-triangle inner face at this node
  struct Local;     // a message between two agents of this node, delivered after the callback
  class Protocol;   // the protocol as the reliability layer's inner node

  std::size_t index_of(NodeId id) const;
  detail::PackingAgent& agent(std::size_t k) const { return k == 0 ? *own_ : *faces_[k - 1]; }
  const Wedge* wedge_of_face(NodeId face_id) const;
  void agent_send(std::size_t agent, std::size_t k_index, std::span<const std::byte> bytes);
  void send_relay(const Wedge& w, NodeId source, NodeId target, std::span<const std::byte> payload);
  void handle_relay(std::size_t from, const RelayView& m);
  void deliver_payload(std::size_t agent, std::size_t from_index, std::span<const std::byte> bytes);
  void drain();
  void start();
  void receive(NodeId from, std::span<const std::byte> bytes);
  void transmit(std::size_t i, std::span<const std::byte> bytes);
  void broadcast_all(std::span<const std::byte> bytes);  // transmit to every neighbour, in order
  static constexpr std::size_t sorted_from = 17;  // degree from which index_of searches sorted_ids_

  // What a node holds (docs/protocol.md, "Node state"): O(degree) in a few arrays; the polygon-face,
  // lossy-link and acceleration state only in the runs that need it. Order: everything a delivered
  // message reads or writes in a synchronous run (on_message, receive, drain, the agents' sends and
  // the hot counters) lies in the object's first four cache lines, which the host prefetches
  // (sim::SimHost::prefetch); the rest follows.
  Runtime* rt_;  // the host's runtime, or the reliability layer's
  std::unique_ptr<ReliableNode> link_;                        // lossy mode: the layer under the protocol
  std::unique_ptr<detail::PackingAgent> own_;                 // agent 0: the node's own vertex
  std::size_t deg_ = 0;
  Time finished_at_ = -1;
  bool failed_ = false;
  std::vector<Local> local_;                                  // FIFO, emptied by drain()
  std::vector<std::byte> scratch_;                            // the agents' encoding buffer
  const void* own_tags_ = nullptr;    // the own agent's radius tags and radii (for prefetch)
  const void* own_radius_ = nullptr;
  LocalKnowledge know_;   // its `faces` moved into wedges_
  PackingCounters counters_;  // the protocol's (on lossy links, received/decode count frame payloads)
  PackingParams params_;  // the agents read it from here
  std::vector<std::pair<NodeId, std::uint32_t>> sorted_ids_;  // (id, index) for lookup; only past sorted_from
  std::vector<Wedge> wedges_;                                 // polygon faces at this node
  std::vector<std::unique_ptr<detail::PackingAgent>> faces_;  // agents 1, 2, …: hosted face vertices
  std::vector<std::byte> local_bytes_;                        // their bytes (see Local)
  std::vector<std::byte> relay_buffer_;
  NodeId suspect_ = 0;
};

}  // namespace laguerre::protocols
