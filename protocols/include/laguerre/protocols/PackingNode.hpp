#pragma once
/// @file
/// The distributed circle-packing protocol of thesis §5.3, synchronous mode, for triangulated discs
/// and 3-connected plane graphs: one `PackingNode` per network node, hosted through `Runtime`.
///
/// ## Design note: tolerating loss and duplication (planned, not implemented)
///
/// The synchronous mode assumes reliable links. The plan keeps its results bit for bit under loss,
/// duplication and delay, because every value a node computes is keyed by its position in the run,
/// never by when or how often a message arrives:
///  - *Idempotent state messages.* Each message already names its slot: (pulse) for Depth/Wave,
///    (step) for Radius, (round) for Placed/FaceCircles/Report/Decision, (direction) for Shape. A
///    receiver stores at most one value per (neighbour, type, key) and ignores a repeat with the same
///    key and value as a *duplicate* (its own counter, not `unexpected`); the handlers that today count
///    a second copy (final depth, placed wave, echo tokens, child reports) move to per-neighbour flags.
///    Two slots per neighbour still suffice: neighbours stay at most one step/round apart.
///  - *Retransmission timers.* Every node keeps, per neighbour, the last message of each type it sent
///    for the current key and re-sends it when a timer (`Runtime::schedule`, period from
///    `PackingParams`) fires, until receipt is proven. Most proofs are implicit: a neighbour's message
///    with a later key (Radius step t + 1, a Report for round r, the next pulse) shows it holds ours.
///    Report and Decision, which nothing later acknowledges before the next round, get an explicit
///    Ack(type, round). A finished node keeps answering with its final Decision, so a lost "stop"
///    cannot strand a subtree.
///  - *Relayed face traffic* is retransmitted end to end (face host ↔ member, keyed as above); relays
///    stay stateless.
///  - *Crashes.* A neighbour that proves nothing for a bounded number of periods is declared
///    unreachable; the node reports that status up the tree (or to its neighbours during set-up) and
///    the run ends with it instead of hanging.
///  - Set-up (BFS, echo election, wave) uses the same rules; the election's echo counts per-neighbour
///    flags, so a duplicated token cannot complete a wave early.
///
/// ## Phases and messages
///
/// **Set-up** (once; three sub-phases, each self-starting, so nodes need no common clock):
///  1. *Depth* (DepthMsg): a pulse-synchronized BFS from the boundary (boundary nodes have depth 0).
///     At pulse p a node whose depth is still unknown tells its neighbours so; at pulse d(v), when
///     some neighbour announced depth d(v) − 1 and every neighbour's pulse d(v) − 1 status is known,
///     it announces its final depth. In a synchronous BFS the first finite value is the distance, so
///     every depth is exact; a node sends d(v) + 1 messages per link. Afterwards each node knows which
///     neighbours are on the boundary (depth 0), hence which carry horocycles (X = 0).
///  2. *Election* (ElectionMsg): echo with extinction over the keys (depth, id) — larger depth wins,
///     then smaller id (RootRule::deepest), or the smallest id (RootRule::smallest_id). Interior nodes
///     whose key beats all interior neighbours' start an echo wave; a node joins the strongest wave it
///     has seen and ignores weaker ones; the only wave that completes is the strongest one's, whose
///     initiator thus learns it is the root. This is the vertex core::choose_root picks.
///  3. *Wave* (StartMsg, then WaveMsg): the root floods Start(root, first = its neighbour 0) and every
///     node runs pulses of the combinatorial layout wave: root and first are placed at pulse 0; a node
///     is placed at pulse r when, among the neighbours placed at pulses < r, some inner-face wedge has
///     both ends placed, and it takes the wedge `core::choose_placement_wedge` picks — exactly
///     core::lay_out's rule. The wedge (a, b) and the parent (`core::parent_is_first_anchor`) are then
///     fixed for the whole run: they depend only on the graph. Each placed node announces its parent,
///     so every node learns its children in the layout tree.
///
/// **Rounds** r = 0, 1, 2, … (round 0 does no Thurston step, as core::pack checks before sweeping):
///  1. *Thurston steps* (RadiusMsg): min(N, cap − steps) steps; in step t every interior node sends
///     X(t) to its interior neighbours, waits for theirs (boundary neighbours are horocycles, X = 0,
///     with no message) and computes X(t + 1) with `core::star_updated_radius` from its neighbours in
///     its counter-clockwise order — the Jacobi sweep, bit for bit.
///  2. *Layout* (PlacedMsg): the root places itself with `core::place_root`, its first neighbour with
///     `core::place_first_neighbour` once it hears the root, every other node with
///     `core::place_in_face` once it hears its two anchors (a, b) in this round; each node then sends
///     its circle (and X) to all neighbours.
///  3. *Check*: with every neighbour's circle of this round, `core::check_lpd_at`.
///  4. *Convergecast* (ReportMsg) of the AND up the layout tree; the root decides (all hold:
///     converged; otherwise cap reached: cap; otherwise next) and sends *Decision* (DecisionMsg) down
///     the tree; each node forwards it to its children and stops or starts the next round.
///
/// Neighbours are at most one step / round apart, so per-neighbour two-slot buffers (by parity)
/// hold every early message. A message that does not fit the current state is counted as unexpected
/// and dropped; a malformed one is counted per DecodeStatus and dropped.
///
/// ## Face vertices (3-connected graphs, thesis §5.3.2)
///
/// core::pack packs the complex K = G′: one face vertex per inner face with more than 3 vertices,
/// joined to the face's vertices at angle π/2. The protocol runs on K itself: every vertex of K is a
/// *protocol vertex* (an agent with the state machine above), and the node with the smallest id on
/// a face, its *host*, also runs that face's vertex. Everything above — depth BFS, election, layout
/// wave, Thurston steps with intersection cosines, layout, convergecast — then holds on K verbatim,
/// which is why it reproduces core::pack on K (whose depth, root, wave and tree are those of K). A
/// link of K between a face vertex and a face member w is emulated G-face-locally: the host delivers
/// locally when w is itself, else wraps the message in a RelayMsg that walks the face's boundary the
/// shorter way round (every member knows the face's walk, so each relay knows its next hop).
///
/// A face vertex's id is `face_vertex_id(host, successor)`: the host's id and the id that follows it
/// in the face's walk determine the face, and every member can compute it. A face vertex lists its
/// neighbours from its host, counter-clockwise; core lists them from the face vertex of smallest
/// *index*, so the two agree bit for bit when ids increase with vertex indices (as in every graph
/// laguerre generates or reads). Node ids must then be below 2^31.
///
/// Added messages: *Shape* (ShapeMsg), once after the wave set-up: the OR of "some incident inner
/// face has more than 3 vertices" up the layout tree and the root's answer down; every node then uses
/// core's global choices (overlap angles in the layout, GLPD instead of LPD in the check), as
/// core::pack does for the whole graph. *Face circles* (FaceCirclesMsg): in each round, a face vertex
/// that has heard every member's circle sends all of them to every member, who then has the circles
/// of every vertex of its incident faces and decides GLPD with `check_glpd_local` (LocalChecks.hpp),
/// exactly as core::check_glpd. A face vertex's own check is trivially true (core checks G only).
///
/// Limits (the synchronous mode's assumptions): reliable links (any delay, any order); a triangulated
/// disc or a 3-connected plane graph with at least one interior vertex.

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/Placement.hpp"
#include "laguerre/core/packing/Thurston.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"
#include "laguerre/protocols/Codec.hpp"
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

/// Parameters shared by all nodes of a run (the same values core::PackOptions would hold).
struct PackingParams {
  int steps_per_check = 1;                                        ///< N: Thurston steps per round (≥ 1)
  int max_iterations = 100000;                                    ///< cap on steps (≥ 0)
  core::UpdateRule update = core::UpdateRule::uniform_neighbour;  ///< per-vertex update
  core::RootRule root = core::RootRule::deepest;                  ///< which root the election picks
};

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
};

/// Per-node message statistics (physical messages: a relayed envelope counts at every hop).
struct PackingCounters {
  std::uint64_t sent = 0;                                     ///< messages handed to the runtime (a broadcast counts once per neighbour)
  std::uint64_t bytes_sent = 0;                               ///< their bytes
  std::uint64_t received = 0;                                 ///< messages received
  std::array<std::uint64_t, decode_status_count> decode{};    ///< received messages per DecodeStatus
  std::uint64_t not_a_neighbour = 0;                          ///< from an id that is not a neighbour
  std::uint64_t unexpected = 0;                               ///< well-formed but not fitting the state
  std::uint64_t relayed = 0;                                  ///< RelayMsg envelopes forwarded for others
  std::uint64_t bad_payload = 0;                              ///< relayed payloads that did not decode
};

/// The state of one protocol vertex (the node's own vertex or a hosted face vertex).
struct VertexState {
  NodeId id = 0;                    ///< protocol id (node id, or face_vertex_id for a face vertex)
  std::uint32_t depth = 0;          ///< depth from the boundary in K
  bool is_root = false;             ///< whether it is the elected root
  std::uint32_t wave = 0;           ///< layout wave in which it is placed
  NodeId parent = 0;                ///< parent in the layout tree (its own id for the root)
  std::uint32_t steps = 0;          ///< Thurston steps done
  std::uint32_t round = 0;          ///< current round
  double x = 0;                     ///< current X = e^{-2h}
  core::PlacedCircle placement;     ///< placement in the latest layout
  core::LocalCondition local = core::LocalCondition::unrepresentable;  ///< latest local check
  PackingPhase phase = PackingPhase::idle;  ///< phase
};

namespace detail {
class PackingAgent;
class AgentHost;
}  // namespace detail

/// One node of the packing protocol (synchronous mode): its own protocol vertex plus the face
/// vertices it hosts.
class PackingNode final : public Node {
public:
  /// A node with its static knowledge; `runtime` must outlive it. Throws std::invalid_argument if the
  /// knowledge is inconsistent (no neighbours, repeated neighbours, itself as neighbour, a boundary
  /// node without an outer wedge or an interior node with one, face walks that do not match the
  /// neighbours, ids too large for face vertices) or the parameters are out of range.
  PackingNode(Runtime& runtime, LocalKnowledge knowledge, PackingParams params);
  /// Destroys the node and its hosted vertices.
  ~PackingNode() override;
  /// Not copyable (its agents refer to it).
  PackingNode(const PackingNode&) = delete;
  /// Not copyable.
  PackingNode& operator=(const PackingNode&) = delete;

  /// Starts the node's own vertex and the face vertices it hosts.
  void on_start() override;
  /// Decodes a message: an envelope is relayed or delivered to a hosted vertex, anything else goes to
  /// the node's own vertex.
  void on_message(NodeId from, std::span<const std::byte> bytes) override;
  /// The synchronous mode sets no timers: counted as unexpected.
  void on_timer(TimerId timer) override;

  /// The current phase.
  PackingPhase phase() const;
  /// How the run ended (running until the stop decision arrives).
  PackingOutcome outcome() const;
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
  /// Current X = e^{-2h}.
  double x() const;
  /// This node's placement in the latest layout.
  const core::PlacedCircle& placement() const;
  /// The local LPD/GLPD outcome in the latest layout.
  core::LocalCondition local_condition() const;
  /// Whether the run packs G′ (some inner face is not a triangle; known after the set-up).
  bool polygon_faces() const;
  /// Message statistics.
  const PackingCounters& counters() const { return counters_; }
  /// Number of face vertices this node hosts.
  std::size_t hosted_faces() const { return agents_.size() - 1; }
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
  friend class detail::AgentHost;
  struct Wedge {        // a non-triangle inner face at this node
    std::vector<NodeId> walk;   // from this node, counter-clockwise
    NodeId face_id = 0;         // face_vertex_id of the face
    NodeId host = 0;            // smallest id on the face
    std::size_t agent = 0;      // index in agents_ if hosted here, else 0
  };
  struct Local {        // a message between two agents of this node, delivered after the callback
    std::size_t agent;
    std::size_t from_index;
    std::vector<std::byte> bytes;
  };

  std::size_t index_of(NodeId id) const;
  const Wedge* wedge_of_face(NodeId face_id) const;
  void agent_send(std::size_t agent, std::size_t k_index, std::span<const std::byte> bytes);
  void send_relay(const Wedge& w, NodeId source, NodeId target, std::span<const std::byte> payload);
  void handle_relay(std::size_t from, RelayMsg& m);
  void deliver_payload(std::size_t agent, std::size_t from_index, std::span<const std::byte> bytes);
  void drain();

  Runtime& rt_;
  LocalKnowledge know_;
  std::size_t deg_ = 0;
  std::vector<std::pair<NodeId, std::uint32_t>> sorted_ids_;  // (id, index) for lookup
  std::vector<Wedge> wedges_;                                 // polygon faces at this node
  std::vector<std::unique_ptr<detail::PackingAgent>> agents_; // [0]: own vertex; then hosted faces
  std::unique_ptr<detail::AgentHost> host_;
  std::deque<Local> local_;
  std::vector<std::byte> relay_buffer_;
  PackingCounters counters_;
};

}  // namespace laguerre::protocols
