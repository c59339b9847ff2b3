#pragma once
/// @file
/// The distributed circle-packing protocol of thesis §5.3 for triangulated discs and 3-connected plane
/// graphs: one `PackingNode` per network node, hosted through `Runtime`. Synchronous mode (bit for bit
/// with core::pack), optionally over lossy links and with crash detection, and an asynchronous mode.
///
/// ## Loss, duplication and crashes (`PackingParams::retransmit_after` > 0)
///
/// The synchronous mode needs reliable links but tolerates any delay and any reordering: every
/// message names its slot (pulse, step or round) and every handler is correct whatever the arrival
/// order, as the shuffled-delivery tests show. So the lossy mode does not touch the protocol: it puts
/// a per-link *reliability layer* under it that turns a lossy, duplicating, reordering link into a
/// reliable, reordering one — exactly-once delivery of every message — after which every node
/// computes what it computes on reliable links, hence core::pack's radii, circles and iteration count
/// bit for bit, whatever is lost or duplicated. The rules (PackingNode implements them; the agents
/// are unchanged):
///  - *Frames.* Every message a node hands to a neighbour u (protocol messages, relay envelopes,
///    failure notices) travels in a FrameMsg with the next sequence number of the directed link
///    v → u. The key (link, seq) identifies the message: a receiver records which sequence numbers it
///    has (AckInfo: the first missing one plus a 64-bit selective bitmap above it), delivers a frame's
///    payload only the first time, and counts every further copy as a *duplicate* (a sim duplicate or
///    a retransmission whose ack was lost) — never applied twice. A frame more than 64 ahead of the
///    first missing one is dropped unacknowledged (the sender retransmits it later); a correct node
///    never gets that far ahead, since neighbours stay within a step or a round of each other.
///  - *Acks.* Receipt is proven *implicitly* when a frame goes back: every frame carries the sender's
///    AckInfo of the reverse link (most radius and placement exchanges are answered this way). Where
///    nothing goes back soon (convergecast reports, decisions, relays, the last message of a run) an
///    explicit AckMsg follows after `ack_delay` unless a frame took it first. Relayed face traffic is
///    acknowledged hop by hop (each hop is a link like any other), hence delivered exactly once end to
///    end; relays keep no per-message state beyond their links'. Every received copy,
///    duplicates included, re-arms the ack, so a lost ack is repaired by the next retransmission.
///  - *Retransmission.* Per neighbour, one timer runs while frames to it are unacknowledged; when it
///    fires, every unacknowledged frame to that neighbour is sent again (with a fresh piggybacked ack)
///    and the period doubles (exponential backoff), up to `backoff_cap` × `retransmit_after`. Any
///    progress (a frame newly acknowledged) resets the period to the link's current retransmission
///    timeout (RTO) and the attempt count; the timer is cancelled as soon as nothing is outstanding.
///  - *Adaptive timeout* (`adaptive_rto`, the default). The RTO of each link starts at
///    `retransmit_after` and follows the measured round trips (Jacobson/Karels, as RFC 6298): when an
///    ack newly covers frames, the most recently sent of them that was never retransmitted gives a
///    sample R = now − its send time (Karn's rule: a retransmitted frame gives none, its ack could
///    answer either copy); the first sample sets SRTT = R, RTTVAR = R/2, later ones RTTVAR ←
///    3/4·RTTVAR + 1/4·|SRTT − R|, SRTT ← 7/8·SRTT + 1/8·R (integer nanoseconds), and RTO = SRTT +
///    4·RTTVAR clamped to [`rto_min`, `backoff_cap` × `retransmit_after`]. A sample includes the
///    receiver's ack delay, so the RTO covers it. Without `adaptive_rto` the RTO stays
///    `retransmit_after`: set it above the longest round trip plus `ack_delay` (`enable_lossy_links`
///    does) or copies are merely sent twice. Timing never changes what is delivered, only when.
///  - *Sequence numbers* are 32-bit and wrap: they are compared in serial-number arithmetic (RFC 1982:
///    a is before b iff (a − b) mod 2^32 ≥ 2^31), which is exact as long as fewer than 2^31 frames of
///    one link are in flight or remembered — the window is 65. `initial_seq` (tests) starts every link
///    elsewhere than 0.
///  - *Quiescence.* A node never sends unprompted except (a) new protocol messages, (b) retransmissions
///    of unacknowledged frames, (c) acks of frames it received, (d) probes (below) while it is still
///    running. After the stop decision (a) and (d) end; (b) ends when the last frames are acknowledged
///    — answered by the neighbours' acks, which a finished node keeps sending for every copy it gets —
///    or given up; (c) only answers (b). So every node goes quiet and the host's event queue drains.
///  - *Crashes.* A link whose frames get no acknowledgement after `max_retransmissions` backed-off
///    retransmissions is declared dead and its neighbour *suspected*: the node ends its run with
///    PackingOutcome::neighbour_failed and floods FailureMsg(suspect) to its other neighbours (in
///    frames, so reliably); every node that gets the notice ends likewise and floods it on. A node
///    that is still running but has nothing in flight to a neighbour it has not heard from for
///    `probe_after` sends it an empty frame (a probe), so a crash is detected even when the node is
///    only waiting (e.g. for a dead child's report). Removing one node from a triangulated disc or a
///    3-connected graph leaves it connected, so the notice reaches every survivor; each survivor then
///    stops probing, its frames to the dead node are given up after the bounded retransmissions, and
///    the queue drains. A false suspicion needs max_retransmissions + 1 consecutive lost round trips:
///    at 20% loss per copy, 0.36^25 ≈ 1e-11 per link episode with the default 24.
///  - *Recovery* (Node::on_recover). A node that comes back keeps its state (as after a radio outage,
///    or a reboot from stable storage) and re-arms the timers the outage swallowed: retransmission of
///    its unacknowledged frames, owed acks, and probes while it is still running. Messages lost during
///    the outage are recovered like any loss. So an outage shorter than the detection time (about
///    `max_retransmissions` backed-off periods) is masked: the run converges, bit for bit. After a
///    longer one the survivors have already ended with neighbour_failed, and the node ends too: it
///    receives a neighbour's FailureMsg still being retransmitted to it (naming itself: suspect() is
///    its own id), or every neighbour gave its link up and its own frames and probes go unanswered
///    until it gives up in turn. Either way every node ends with a final outcome and the host's
///    queue drains. (A restart from scratch would need a link re-synchronisation — sequence-number
///    epochs — which this layer does not have.)
///  - *Counters* (PackingCounters): frames, retransmissions, standalone acks, duplicates, probes,
///    links declared dead — per node, physical messages (a retransmission counts again).
///
/// With `retransmit_after` = 0 (the default) nothing of this exists: no frames, timers or acks, the
/// wire traffic is the synchronous mode's, for reliable links.
///
/// ## Asynchronous mode (`PackingParams::asynchronous`)
///
/// Set-up, layout, check, convergecast and decision are those above; only the Thurston steps change.
/// In round r each interior vertex makes N updates (min(N, cap − steps), as above) with
/// `core::star_updated_radius`, each from the *newest* X it knows of every neighbour (whatever step
/// produced it: chaotic relaxation, between Jacobi and Gauss–Seidel), and sends its new X after each
/// update in a RadiusMsg whose `step` is its update count (the value's version; a receiver keeps the
/// highest). Update 1 of a round goes at once; update k ≥ 2 waits until k − 1 radius messages of this
/// round have arrived (from any neighbours), so a vertex never re-solves its star with nothing new.
/// This cannot deadlock: if every interior vertex makes j updates of round r, each has sent j messages
/// to each interior neighbour, so every vertex that has an interior neighbour has received at least j
/// and can make update j + 1 (a vertex without one never waits); neighbours are at most one round
/// apart, so a per-round-parity counter suffices. The layout reads only the X each vertex sends in its
/// PlacedMsg, so every round's layout is consistent and its LPD/GLPD verdict exact; steps() counts
/// updates (N per round at every vertex), the iteration-equivalents. Results depend on message timing,
/// so they are not core::pack's bit for bit; the stop rule (LPD/GLPD everywhere on the layout the
/// nodes hold) is the same. Combines with the reliability layer (which guarantees exactly-once delivery,
/// so the arrival counts stay exact).
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
///     initiator thus learns it is the root. This is the vertex core::choose_root picks. A vertex
///     echoes a wave only once it has decided whether it is a candidate itself (its depth and its
///     neighbours' known): otherwise, with long delays (retransmissions), a deep vertex that learns its
///     depth late could echo a weaker wave to completion before starting its own, and the wrong root
///     would win.
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
/// Limits: reliable links (any delay, any order) unless the reliability layer is on, which adds loss,
/// duplication and crash-stop failures of nodes (not recoveries: a node that comes back resumes with
/// stale links); a triangulated disc or a 3-connected plane graph with at least one interior vertex.

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

/// Parameters shared by all nodes of a run (the same values core::PackOptions would hold, plus the
/// reliability layer's, see "Loss, duplication and crashes").
struct PackingParams {
  int steps_per_check = 1;                                        ///< N: Thurston steps per round (≥ 1)
  int max_iterations = 100000;                                    ///< cap on steps (≥ 0)
  core::UpdateRule update = core::UpdateRule::uniform_neighbour;  ///< per-vertex update
  core::RootRule root = core::RootRule::deepest;                  ///< which root the election picks
  Duration retransmit_after = 0;  ///< first retransmission period (ns); 0 = reliable links, no reliability layer
  int backoff_cap = 8;            ///< longest retransmission period, in multiples of retransmit_after (≥ 1)
  int max_retransmissions = 24;   ///< retransmissions without progress before a neighbour is suspected (≥ 1)
  Duration ack_delay = 0;         ///< wait before a standalone ack (ns), in case a frame can carry it
  Duration probe_after = 0;       ///< silence before a running node probes a neighbour (ns); 0 = 32 × retransmit_after
  bool asynchronous = false;      ///< asynchronous Thurston updates (see "Asynchronous mode"); not bit for bit with core
  bool adaptive_rto = true;       ///< adapt each link's retransmission timeout to measured round trips
  Duration rto_min = 0;           ///< lower clamp of the adaptive timeout (ns); 0 = retransmit_after / 4
  std::uint32_t initial_seq = 0;  ///< first sequence number of every link (all nodes must agree)
};

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
  std::uint64_t frames = 0;                                   ///< frames sent for the first time (lossy mode)
  std::uint64_t retransmissions = 0;                          ///< frames sent again after a timeout
  std::uint64_t acks = 0;                                     ///< standalone acks sent
  std::uint64_t duplicates = 0;                               ///< frames received again (never delivered twice)
  std::uint64_t out_of_window = 0;                            ///< frames too far ahead, dropped unacknowledged
  std::uint64_t probes = 0;                                   ///< empty frames sent to silent neighbours
  std::uint64_t links_failed = 0;                             ///< links given up after max_retransmissions

  /// Adds `o` field by field (totals over nodes).
  PackingCounters& operator+=(const PackingCounters& o) {
    sent += o.sent;
    bytes_sent += o.bytes_sent;
    received += o.received;
    for (std::size_t i = 0; i < decode.size(); ++i) decode[i] += o.decode[i];
    not_a_neighbour += o.not_a_neighbour;
    unexpected += o.unexpected;
    relayed += o.relayed;
    bad_payload += o.bad_payload;
    frames += o.frames;
    retransmissions += o.retransmissions;
    acks += o.acks;
    duplicates += o.duplicates;
    out_of_window += o.out_of_window;
    probes += o.probes;
    links_failed += o.links_failed;
    return *this;
  }
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
  double h = 0;                     ///< current hyperbolic radius (∞ on the boundary)
  core::PlacedCircle placement;     ///< placement in the latest layout
  core::LocalCondition local = core::LocalCondition::unrepresentable;  ///< latest local check
  PackingPhase phase = PackingPhase::idle;  ///< phase
};

namespace detail {
class PackingAgent;
class AgentHost;
}  // namespace detail

/// One node of the packing protocol: its own protocol vertex plus the face vertices it hosts, and (on
/// lossy links) the reliability layer under them.
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
  /// The reliability layer's timers (retransmission, delayed ack, probe); without it, counted as
  /// unexpected.
  void on_timer(TimerId timer) override;
  /// Back from an outage (see "Recovery" in the file comment): re-arms the reliability layer's timers.
  void on_recover() override;

  /// The current phase.
  PackingPhase phase() const;
  /// How the run ended (running until the stop decision or a failure notice arrives).
  PackingOutcome outcome() const;
  /// The node suspected of having failed (meaningful when outcome() is neighbour_failed).
  NodeId suspect() const { return suspect_; }
  /// Whether the node is done: stopped by the decision, or ended by a failure.
  bool is_final() const;
  /// When the node became final (the runtime's clock at the end of that callback); -1 while running.
  Time finished_at() const { return finished_at_; }
  /// The current retransmission timeout towards neighbour i (lossy mode; 0 without it).
  Duration rto(std::size_t i) const { return i < links_.size() ? links_[i].rto : 0; }
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
  struct Link {         // the reliability layer's state for one G-neighbour (see the file comment)
    struct Pending {                                                     // a frame not yet acknowledged
      std::uint32_t seq = 0;
      std::vector<std::byte> payload;
      Time sent_at = 0;                                                  // first transmission
      bool retransmitted = false;                                        // Karn: no RTT sample from it
    };
    std::uint32_t next_seq = 0;                                          // next sequence number to send
    std::deque<Pending> unacked;                                         // by seq
    TimerHandle retransmit_timer = 0;
    Duration period = 0;                                                 // current retransmission period
    Duration rto = 0;                                                    // current timeout (backoff resets to it)
    Duration srtt = 0;                                                   // smoothed round trip (ns)
    Duration rttvar = 0;                                                 // its mean deviation (ns)
    bool has_rtt = false;                                                // a sample was taken
    int attempts = 0;                                                    // retransmissions since progress
    AckInfo received;                                                    // what we have of the reverse link
    bool ack_pending = false;
    TimerHandle ack_timer = 0;
    Time last_heard = 0;
    bool dead = false;
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
  bool lossy() const { return params_.retransmit_after > 0; }
  void transmit(std::size_t i, std::span<const std::byte> bytes);
  void send_frame(std::size_t i, std::span<const std::byte> payload);
  void put_frame(std::size_t i, std::uint32_t seq, std::span<const std::byte> payload);
  void handle_frame(std::size_t i, FrameMsg& f);
  void handle_ack(std::size_t i, const AckInfo& a);
  void sample_rtt(Link& l, Duration r);
  void deliver_frame_payload(std::size_t i, std::span<const std::byte> payload);
  void flush_acks();
  void arm_retransmit(std::size_t i);
  void on_retransmit(std::size_t i);
  void on_probe();
  void give_up(std::size_t i);
  void declare_failure(NodeId suspect, std::size_t except);
  void raw_send(NodeId to, std::span<const std::byte> bytes);

  Runtime& rt_;
  PackingParams params_;
  LocalKnowledge know_;
  std::size_t deg_ = 0;
  std::vector<std::pair<NodeId, std::uint32_t>> sorted_ids_;  // (id, index) for lookup
  std::vector<Wedge> wedges_;                                 // polygon faces at this node
  std::vector<std::unique_ptr<detail::PackingAgent>> agents_; // [0]: own vertex; then hosted faces
  std::unique_ptr<detail::AgentHost> host_;
  std::deque<Local> local_;
  std::vector<std::byte> relay_buffer_;
  std::vector<std::byte> frame_buffer_;
  std::vector<Link> links_;                                   // per G-neighbour (lossy mode)
  std::vector<std::size_t> ack_owed_;                         // links with ack_pending, to flush
  TimerHandle probe_timer_ = 0;
  bool failed_ = false;
  NodeId suspect_ = 0;
  Time finished_at_ = -1;
  PackingCounters counters_;
};

}  // namespace laguerre::protocols
