#pragma once
/// @file
/// The distributed circle-packing protocol of thesis §5.3, synchronous mode, for triangulated discs:
/// one `PackingNode` per network node, hosted through `Runtime`.
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
/// Limits (the synchronous mode's assumptions): reliable links (any delay, any order); a triangulated
/// disc with at least one interior vertex.

#include <array>
#include <complex>
#include <cstdint>
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
/// that makes the node's sums agree with core's bit for bit) and the outer-face wedge located.
LocalKnowledge local_knowledge(const core::PlanarGraph& g, core::Vertex v);

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
  wave,      ///< combinatorial layout wave
  rounds,    ///< Thurston steps, layout, check, convergecast
  finished,  ///< the root's decision to stop reached this node
};

/// How a node's run ended.
enum class PackingOutcome : std::uint8_t {
  running,    ///< not finished
  converged,  ///< LPD holds everywhere
  cap,        ///< the iteration cap was reached first
};

/// Per-node message statistics.
struct PackingCounters {
  std::uint64_t sent = 0;                                     ///< messages handed to the runtime (a broadcast counts once per neighbour)
  std::uint64_t bytes_sent = 0;                               ///< their bytes
  std::uint64_t received = 0;                                 ///< messages received
  std::array<std::uint64_t, decode_status_count> decode{};    ///< received messages per DecodeStatus
  std::uint64_t not_a_neighbour = 0;                          ///< from an id that is not a neighbour
  std::uint64_t unexpected = 0;                               ///< well-formed but not fitting the state
};

/// One node of the packing protocol (synchronous mode, triangulated discs).
class PackingNode final : public Node {
public:
  /// A node with its static knowledge; `runtime` must outlive it. Throws std::invalid_argument if the
  /// knowledge is inconsistent (no neighbours, repeated neighbours, itself as neighbour, a boundary
  /// node without an outer wedge or an interior node with one) or the parameters are out of range.
  PackingNode(Runtime& runtime, LocalKnowledge knowledge, PackingParams params);

  void on_start() override;
  void on_message(NodeId from, std::span<const std::byte> bytes) override;
  void on_timer(TimerId timer) override;

  /// The current phase.
  PackingPhase phase() const { return phase_; }
  /// How the run ended (running until the stop decision arrives).
  PackingOutcome outcome() const { return outcome_; }
  /// This node's id.
  NodeId id() const { return know_.id; }
  /// Depth from the boundary (set-up result; meaningful once past the depth phase).
  std::uint32_t depth() const { return depth_; }
  /// Whether this node is the elected root.
  bool is_root() const { return is_root_; }
  /// Layout wave in which this node is placed (set-up result).
  std::uint32_t wave() const { return wave_; }
  /// Parent in the layout tree (its own id for the root).
  NodeId parent() const { return parent_; }
  /// Number of children in the layout tree.
  std::size_t children() const;
  /// Thurston steps done (the iteration count, equal at every node).
  std::uint32_t steps() const { return step_; }
  /// Current round (the number of the last or current layout).
  std::uint32_t round() const { return round_; }
  /// Current X = e^{-2h}.
  double x() const { return x_; }
  /// This node's placement in the latest layout.
  const core::PlacedCircle& placement() const { return placed_; }
  /// The local LPD outcome in the latest layout.
  core::LocalCondition local_condition() const { return local_; }
  /// Message statistics.
  const PackingCounters& counters() const { return counters_; }

private:
  static constexpr std::uint32_t unknown = 0xffffffffu;

  struct Slot {  // one buffered value tagged with its step or round
    std::uint32_t tag = unknown;
    double x = 0;
  };
  struct PlacedSlot {
    std::uint32_t tag = unknown;
    double x = 0;
    core::PlacedCircle at;
  };

  void send(std::size_t i, const Message& m);
  void send_encoded(std::size_t i);  // sends buffer_ as it is
  void broadcast(const Message& m);
  std::size_t index_of(NodeId id) const;
  bool interior_nbr(std::size_t i) const { return nbr_depth_[i] != 0; }

  void handle(std::size_t i, const DepthMsg& m);
  void handle(std::size_t i, const ElectionMsg& m);
  void handle(std::size_t i, const StartMsg& m);
  void handle(std::size_t i, const WaveMsg& m);
  void handle(std::size_t i, const RadiusMsg& m);
  void handle(std::size_t i, const PlacedMsg& m);
  void handle(std::size_t i, const ReportMsg& m);
  void handle(std::size_t i, const DecisionMsg& m);

  void advance_depth();
  void maybe_candidate();
  void begin_wave(std::size_t from, NodeId root, NodeId first);
  void advance_wave();
  void maybe_finish_setup();
  void begin_round();
  void advance_steps();
  void advance_layout();
  void advance_convergecast();
  void apply_decision(Verdict v);
  bool better(std::uint32_t d1, NodeId id1, std::uint32_t d2, NodeId id2) const;

  Runtime& rt_;
  LocalKnowledge know_;
  PackingParams params_;
  std::size_t deg_ = 0;
  std::vector<std::pair<NodeId, std::uint32_t>> sorted_ids_;  // (id, index) for lookup
  std::vector<std::byte> buffer_;
  PackingCounters counters_;
  PackingPhase phase_ = PackingPhase::idle;
  PackingOutcome outcome_ = PackingOutcome::running;

  // Depth phase.
  std::uint32_t depth_ = unknown;
  std::uint32_t depth_pulse_ = 0;
  std::vector<std::uint32_t> nbr_depth_;         // final depth or unknown
  std::vector<std::uint32_t> nbr_depth_seen_;    // highest "still unknown" pulse + 1 (0: none)
  std::size_t nbr_depths_known_ = 0;

  // Election.
  bool candidate_checked_ = false;
  bool in_wave_ = false;                  // joined some election wave
  std::uint32_t best_depth_ = 0;
  NodeId best_id_ = 0;
  std::size_t echo_parent_ = 0;           // index, or deg_ for the initiator
  std::size_t echo_count_ = 0;

  // Wave set-up.
  bool wave_started_ = false;
  bool is_root_ = false;
  bool is_first_ = false;
  NodeId root_id_ = 0;
  std::uint32_t wave_ = unknown;
  std::uint32_t wave_pulse_ = 0;
  NodeId parent_ = 0;
  std::size_t parent_index_ = 0;          // index of the parent (unused for the root)
  std::size_t anchor_a_ = 0, anchor_b_ = 0;
  std::vector<std::uint32_t> nbr_wave_;       // final wave or unknown
  std::vector<std::uint32_t> nbr_wave_seen_;  // highest "not placed" pulse + 1 (0: none)
  std::vector<std::uint8_t> child_;
  std::size_t nbr_waves_known_ = 0;
  bool setup_done_ = false;

  // Rounds.
  std::uint32_t round_ = 0;
  std::uint32_t step_ = 0;               // steps done
  std::uint32_t round_end_step_ = 0;     // step_ at which this round's sweeps end
  bool sent_step_ = false;               // whether X(step_) was sent
  double x_ = 0;
  std::vector<std::array<Slot, 2>> radius_;
  std::vector<double> star_x_;           // scratch: neighbour X in ccw order
  std::vector<std::array<PlacedSlot, 2>> placed_in_;
  bool placed_this_round_ = false;
  bool checked_this_round_ = false;
  bool reported_ = false;
  core::PlacedCircle placed_;
  core::LocalCondition local_ = core::LocalCondition::unrepresentable;
  std::size_t reports_ = 0;
  bool reports_ok_ = true;
  std::vector<core::Circle> check_circles_;  // scratch
};

}  // namespace laguerre::protocols
