#pragma once
// One protocol vertex of K (a node's own vertex or a face vertex it hosts): the state machine of
// docs/protocol.md, addressing its K-neighbours by index through its PackingNode. It handles
// PackingMessage only (relays, frames and failure notices are PackingNode's). Private to the library.
//
// Memory layout (docs/protocol.md, "Node state"): what every mode needs lives in the agent and in
// one array of Peer records (one per K-neighbour) plus one array of radii; what only some runs need
// is allocated only for them, each behind its own pointer: Polygon (a node on or hosting a polygon
// face: the G-structure, the face circles, the cosines), core::LocalAccelerator (a local
// acceleration). A further mode adds its own per-node struct the same way.

#include <array>
#include <complex>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "laguerre/protocols/PackingNode.hpp"

namespace laguerre::protocols::detail {

// What a protocol vertex knows statically: its star in K and, for an original vertex, its G-faces.
// The constructor's input; the agent keeps it in its own compact form.
struct AgentSpec {
  NodeId id = 0;
  std::vector<NodeId> neighbours;            // K-neighbours, counter-clockwise from core's first dart
  bool boundary = false;
  std::uint32_t outer_gap = LocalKnowledge::no_gap;  // K index of the outer wedge
  bool is_face = false;                      // a face vertex
  std::vector<std::uint8_t> face_nbr;        // per K-neighbour: 1 if it is a face vertex
  bool polygon_here = false;                 // is or touches a face vertex
  // Original vertices: G-neighbour i is K-neighbour g_k[i]; g_face[i] is the walk (from this vertex)
  // of the polygon face in G-wedge i, or null; g_outer_gap is the G index of the outer wedge.
  std::vector<std::uint32_t> g_k;
  std::vector<const std::vector<NodeId>*> g_face;
  std::uint32_t g_outer_gap = LocalKnowledge::no_gap;
};

class PackingAgent {
public:
  PackingAgent(PackingNode& node, std::size_t index, AgentSpec spec);
  ~PackingAgent();

  void start();
  void receive(std::size_t k_index, const PackingMessage& m);
  // The same for a RadiusMsg decoded on its own (PackingNode's fast path: no PackingMessage).
  void receive(std::size_t k_index, const RadiusMsg& m);
  // What the radius path reads, for PackingNode::prefetch: this object's first two cache lines hold
  // every field of it (see the member order); then the radius tags and the radii (no peer record).
  // The two arrays are allocated once, by the constructor.
  const void* radius_data() const { return radius_.get(); }
  const void* radius_tag_data() const { return radius_tag_.get(); }

  PackingPhase phase() const { return phase_; }
  PackingOutcome outcome() const { return outcome_; }
  std::size_t children() const;
  bool polygon() const { return polygon_; }
  VertexState state() const;
  const core::PlacedCircle& placement() const { return placed_; }
  NodeId id() const { return id_; }
  std::size_t degree() const { return deg_; }
  NodeId neighbour(std::size_t i) const { return peers_[i].id; }
  bool face_neighbour(std::size_t i) const { return peers_[i].face != 0; }
  // The K index of neighbour `id`, or degree() if it is none.
  std::size_t index_of(NodeId id) const;
  // Number of G-neighbours (original vertices) and the K index of G-neighbour g.
  std::size_t g_degree() const { return poly_ ? poly_->g_k.size() : deg_; }
  std::uint32_t k_of_g(std::size_t g) const { return poly_ ? poly_->g_k[g] : static_cast<std::uint32_t>(g); }
  // Whether it is or touches a face vertex (else its K-neighbours are its G-neighbours, in order).
  bool touches_faces() const { return polygon_here_; }
  // Circle of K-neighbour i in the current round's layout (as heard).
  const core::Circle& neighbour_circle(std::size_t i) const { return peers_[i].circle[round_ & 1]; }

private:
  // Whether a message is taken now: none before the set-up starts or once finished (counted as
  // unexpected), except a stale RadiusMsg after an asynchronous stop (dropped quietly). Both
  // receive() overloads ask it.
  bool takes(bool radius);

  static constexpr std::uint32_t unknown = 0xffffffffu;

  // Per K-neighbour state, one record each (set-up BFS and election, tree, the latest radius and circle tags).
  struct Peer {
    NodeId id = 0;
    std::uint32_t depth = unknown;    // its smallest depth estimate heard (final once `final` is in)
    std::uint32_t claim_depth = unknown;  // the depth of its newest parent claim (bfs & claim_bit: "you")
    std::uint32_t wave = unknown;     // its placement estimate in the layout wave (final once it has ended)
    std::uint32_t wave_seq = 0;       // seq of its newest WaveMsg (StartMsg: 1)
    std::uint32_t placed_tag[2] = {unknown, unknown};  // round of circle[parity]
    core::Circle circle[2];           // its circle in the layout of a round, by parity
    std::uint32_t latest_step = 0;    // asynchronous mode: version of its newest radius
    std::uint8_t face = 0;            // 1 if it is a face vertex
    std::uint8_t child = 0;           // 1 if it is a child in the layout tree
    std::uint8_t height_up = 0;       // 1 once its height report is in (radius-flood set-up)
    std::uint8_t bfs = 0;             // BFS forest: child_bit, report_bit, claim_bit, held_bit
  };
  // What placing needs of an anchor (the first neighbour's parent, or anchor a / b) in a round.
  struct AnchorSlot {
    std::uint32_t tag = unknown;
    double h = 0;
    std::complex<double> centre;
  };
  struct FaceSlot {
    std::uint32_t tag = unknown;
    std::vector<core::Circle> circles;  // host walk order
  };
  // Only for a vertex that is or touches a face vertex (3-connected graphs with polygon faces).
  struct Polygon {
    std::vector<std::uint32_t> g_k;                  // AgentSpec::g_k
    std::vector<const std::vector<NodeId>*> g_face;  // AgentSpec::g_face
    std::vector<double> spoke, rim;                  // the star's intersection cosines
    std::vector<std::array<FaceSlot, 2>> face_in;    // per K-neighbour (used for face-vertex neighbours)
  };

  void send(std::size_t i, const PackingMessage& m);
  void send_encoded(std::size_t i);
  void broadcast(const PackingMessage& m);
  void send_to_all_encoded();  // the encoded message to every K-neighbour
  std::vector<std::byte>& buffer();
  PackingCounters& counters();
  bool interior_nbr(std::size_t i) const { return peers_[i].depth != 0; }
  bool interior_fast(std::size_t i) const { return mask_ready_ ? (interior_mask_ >> i) & 1 : interior_nbr(i); }
  // Synchronous mode: whether every interior neighbour's radius of step s is in.
  bool heard_all(std::uint32_t s) const { return (heard_step_[s & 1] == s ? heard_[s & 1] : 0) == interior_nbrs_; }
  double cos_spoke(std::size_t i) const { return is_face_ || peers_[i].face ? 0.0 : 1.0; }
  double cos_rim(std::size_t i) const {
    const std::size_t j = i + 1 == deg_ ? 0 : i + 1;
    return peers_[i].face || peers_[j].face ? 0.0 : 1.0;
  }
  core::StarView star(const double* h) const;

  void handle(std::size_t i, const DepthMsg& m);
  void handle(std::size_t i, const ElectionMsg& m);
  void handle(std::size_t i, const StartMsg& m);
  void handle(std::size_t i, const WaveMsg& m);
  void handle(std::size_t i, const RadiusMsg& m);
  void handle(std::size_t i, const PlacedMsg& m);
  void handle(std::size_t i, const ReportMsg& m);
  void handle(std::size_t i, const DecisionMsg& m);
  void handle(std::size_t i, const ShapeMsg& m);
  void handle(std::size_t i, const FaceCirclesMsg& m);
  void handle(std::size_t i, const KrylovValueMsg& m);
  void handle(std::size_t i, const KrylovSumMsg& m);
  void handle(std::size_t i, const KrylovDecisionMsg& m);
  void handle(std::size_t i, const GateRadiusMsg& m);
  void handle(std::size_t i, const HeightMsg& m);

  // Depth (PackingAgent.cpp, "Depth"): the event-driven BFS and the ring tokens that end it.
  static constexpr std::uint8_t child_bit = 1;   // Peer::bfs: a child in the BFS forest (known at `final`)
  static constexpr std::uint8_t report_bit = 2;  // its election report is in
  static constexpr std::uint8_t claim_bit = 4;   // its newest claim says this vertex is its parent
  static constexpr std::uint8_t held_bit = 8;    // an estimate of it whose acknowledgement is held
  void hear_claim(Peer& p, std::uint32_t depth, bool yes);
  void depth_quiet();  // all own depth messages acknowledged
  void offer_settled(NodeId id);
  void handle_settled(std::size_t i, const ElectionMsg& m);
  void handle_final(std::size_t i, const ElectionMsg& m);
  // from: the K index it came from (deg: this vertex's own token); winner: whose `settled` token it was.
  void learn_final(std::size_t from, NodeId winner);
  // Election (PackingAgent.cpp, "Election"): the subtree's best key up the BFS forest, the boundary's
  // round the ring, the winner's down the forest.
  void advance_key();
  void offer_ring(std::uint32_t depth, NodeId id);  // a boundary vertex forwards a ring key if it is the best yet
  bool better_key(std::uint32_t d1, NodeId id1) const { return better(d1, id1, best_depth_, best_id_); }
  // Layout wave (PackingAgent.cpp, "Layout wave"): the root starts it; a vertex joins it at its first
  // StartMsg / WaveMsg; advance_wave re-estimates its placement from its neighbours' estimates.
  void start_layout_wave();
  bool join_wave(std::size_t from);  // true if this message engages the vertex (Dijkstra–Scholten)
  void advance_wave();
  void end_wave_message(std::size_t from, bool engaged_now);  // acknowledges, maybe releases
  void release_wave();
  void learn_shape(bool polygon);
  void advance_height();
  void learn_height(std::uint32_t height);
  void begin_rounds();
  void begin_round();
  void advance_steps();
  void advance_async_steps();
  // Newton–Krylov mode (PackingAgent.cpp, "Newton–Krylov steps").
  struct KrylovState;
  void krylov_begin_step();
  void krylov_exchange();
  void krylov_advance();
  void krylov_apply(const KrylovDecisionMsg& m);
  void handle_async_radius(std::size_t i, const RadiusMsg& m);
  std::uint32_t round_of_step(std::uint32_t s) const;
  void advance_layout();
  void advance_radius_check();  // radius-only termination: the round's end without a layout
  // Radius-flood termination (PackingAgent.cpp, "Radius-flood steps").
  struct FloodState;
  void flood_advance();
  void flood_finish_step();
  void flood_lay_out(std::uint32_t step, double h);
  void flood_resume();
  bool check();  // false while waiting for data
  void advance_convergecast();
  void apply_decision(Verdict v);
  bool better(std::uint32_t d1, NodeId id1, std::uint32_t d2, NodeId id2) const;

  PackingNode& node_;
  const PackingParams& params_;  // the node's
  NodeId id_ = 0;
  std::uint32_t index_ = 0;      // in the node's agents
  std::uint32_t deg_ = 0;
  std::uint32_t outer_gap_ = LocalKnowledge::no_gap;
  std::uint32_t g_outer_gap_ = LocalKnowledge::no_gap;
  bool boundary_ = false;
  bool is_face_ = false;
  bool polygon_here_ = false;
  PackingPhase phase_ = PackingPhase::idle;
  PackingOutcome outcome_ = PackingOutcome::running;
  std::unique_ptr<Peer[]> peers_;
  // Radii heard, by step parity: radius_[p·deg + i] of neighbour i (∞ for boundary neighbours, which
  // never send one), so that a step reads its star in place. Asynchronous mode: the first deg entries
  // hold the newest radius of each neighbour.
  std::unique_ptr<double[]> radius_;
  // radius_tag_[p·deg + i]: the step whose radius radius_[p·deg + i] holds (unknown until one is heard).
  // Apart from the peer records, with the interior mask below, so that the radius path reads no peer record.
  std::unique_ptr<std::uint32_t[]> radius_tag_;
  std::unique_ptr<Polygon> poly_;
  std::unique_ptr<core::LocalAccelerator> accelerator_;  // a local acceleration only

  // Rounds: what a radius message touches, kept in the object's first two cache lines with the
  // fields and pointers above (PackingNode::prefetch loads them).
  std::uint32_t round_ = 0;
  std::uint32_t step_ = 0;
  std::uint32_t round_end_step_ = 0;
  std::uint32_t round_start_step_ = 0;
  std::uint32_t interior_nbrs_ = 0;  // known at the end of the set-up
  // Synchronous radii heard, by step parity: heard_[p] distinct interior neighbours have sent their
  // radius of step heard_step_[p] (so a step need not read every peer record to know it is complete).
  std::uint32_t heard_step_[2] = {unknown, unknown};
  std::uint32_t heard_[2] = {0, 0};
  // Bit i: K-neighbour i is interior (interior_nbr(i)); valid once mask_ready_ (the depths are final,
  // degree ≤ 64).
  std::uint64_t interior_mask_ = 0;
  bool mask_ready_ = false;
  bool sent_step_ = false;
  bool asynchronous_ = false;  // params_.asynchronous
  bool radius_only_ = false;
  bool layout_round_ = false;
  core::UpdateRule update_ = core::UpdateRule::uniform_neighbour;  // params_.update
  double h_ = 0;
  std::unique_ptr<KrylovState> krylov_;  // Newton–Krylov mode only
  std::unique_ptr<FloodState> flood_;    // Termination::radius_flood only

  // Depth phase: the estimate, the depth messages not yet acknowledged, the neighbour told it is the
  // parent at depth_ (deg: none), and on the boundary the `settled` ring (quiet: every own message
  // acknowledged; the smallest id sent and the smallest held until quiet), then `final`.
  std::uint32_t depth_ = unknown;
  std::uint32_t depth_deficit_ = 0;
  std::uint32_t told_ = 0;  // deg until a parent is told
  bool depth_final_ = false;
  bool quiet_ = false;

  // Election. The best key of the BFS subtree (own and reported; no_key until one is heard) and the
  // child it came from (deg: this vertex); on the boundary, the best ring key forwarded (or sent) so
  // far and the best one held until the subtree's key is known.
  static constexpr NodeId no_key = ~NodeId{0};
  NodeId settled_sent_ = no_key, held_settled_ = no_key;
  std::uint32_t bfs_parent_ = unknown;  // K index (deg for a boundary vertex)
  bool key_reported_ = false;
  std::uint32_t best_depth_ = 0;
  NodeId best_id_ = no_key;
  std::size_t best_child_ = 0;
  std::uint32_t ring_depth_ = 0, held_depth_ = 0;
  NodeId ring_id_ = no_key, held_id_ = no_key;

  // Layout wave. Dijkstra–Scholten termination: `ds_parent_` is the K index of the neighbour whose
  // message engaged this vertex (deg for the root, the initiator; unknown while idle), `ds_deficit_`
  // the StartMsg / WaveMsg it sent that are not yet acknowledged, `ds_polygon_` the OR of its own
  // "touches a face vertex" and of the acknowledgements it received.
  bool wave_started_ = false;
  bool is_root_ = false;
  bool is_first_ = false;
  NodeId root_id_ = 0;
  std::uint32_t wave_ = unknown;
  std::uint32_t wave_seq_ = 0;  // WaveMsg sent
  NodeId parent_ = 0;
  std::size_t parent_index_ = 0;
  std::size_t anchor_a_ = 0, anchor_b_ = 0;
  std::uint32_t ds_parent_ = unknown;
  std::uint32_t ds_deficit_ = 0;
  bool ds_polygon_ = false;

  // Shape and height (after the wave).
  bool shape_known_ = false;
  bool polygon_ = false;
  bool height_sent_ = false;

  // Rounds (the hot part is above).
  // Asynchronous mode: the number of radius messages received per round (by parity).
  std::array<std::uint32_t, 2> arrivals_{};
  bool placed_this_round_ = false;
  bool checked_this_round_ = false;
  bool reported_ = false;
  bool reports_ok_ = true;
  // The anchors' records by parity: [0] anchor a (or the first neighbour's parent), [1] anchor b.
  AnchorSlot anchors_[2][2];
  core::PlacedCircle placed_;
  core::LocalCondition local_ = core::LocalCondition::unrepresentable;
  std::size_t reports_ = 0;
  // Radius-only termination (docs/radius-only.md): whether this round's layout was asked for (by a
  // Verdict::layout), the step whose radii the end-of-round exchange sent, the round's test outcome
  // and the current gap tolerance (halved by every failed exact check, at every node alike).
  std::uint32_t final_sent_ = unknown;
  bool radius_ok_ = false;
  double gap_ = 0;
  std::uint32_t height_ = 0;  // the largest wave of the subtree heard so far, then of K (HeightMsg)
};

}  // namespace laguerre::protocols::detail
