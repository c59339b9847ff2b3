#pragma once
// One protocol vertex of K (a node's own vertex or a face vertex it hosts): the state machine of
// docs/protocol.md, addressing its K-neighbours by index through an AgentHost. It handles
// PackingMessage only (relays, frames and failure notices are PackingNode's). Private to the library.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "laguerre/protocols/PackingNode.hpp"

namespace laguerre::protocols::detail {

// What a protocol vertex knows statically: its star in K and, for an original vertex, its G-faces.
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

// How an agent reaches its K-neighbours and its node's counters.
class AgentHost {
public:
  explicit AgentHost(PackingNode& node) : node_(node) {}
  void send(std::size_t agent, std::size_t k_index, std::span<const std::byte> bytes) {
    node_.agent_send(agent, k_index, bytes);
  }
  PackingCounters& counters() { return node_.counters_; }

private:
  PackingNode& node_;
};

class PackingAgent {
public:
  PackingAgent(AgentHost& host, std::size_t index, AgentSpec spec, PackingParams params);

  void start();
  void receive(std::size_t k_index, const PackingMessage& m);

  PackingPhase phase() const { return phase_; }
  PackingOutcome outcome() const { return outcome_; }
  std::size_t children() const;
  bool polygon() const { return polygon_; }
  VertexState state() const;
  const core::PlacedCircle& placement() const { return placed_; }
  const AgentSpec& spec() const { return know_; }
  // Circle of K-neighbour i in the current round's layout (as heard).
  const core::Circle& neighbour_circle(std::size_t i) const { return placed_in_[i][round_ & 1].at.circle; }

private:
  static constexpr std::uint32_t unknown = 0xffffffffu;

  struct Slot {
    std::uint32_t tag = unknown;
    double h = 0;
  };
  struct PlacedSlot {
    std::uint32_t tag = unknown;
    double h = 0;
    core::PlacedCircle at;
  };
  struct FaceSlot {
    std::uint32_t tag = unknown;
    std::vector<core::Circle> circles;  // host walk order
  };

  void send(std::size_t i, const PackingMessage& m);
  void send_encoded(std::size_t i);
  void broadcast(const PackingMessage& m);
  bool interior_nbr(std::size_t i) const { return nbr_depth_[i] != 0; }
  double cos_spoke(std::size_t i) const { return know_.is_face || know_.face_nbr[i] ? 0.0 : 1.0; }
  double cos_rim(std::size_t i) const {
    const std::size_t j = i + 1 == deg_ ? 0 : i + 1;
    return know_.face_nbr[i] || know_.face_nbr[j] ? 0.0 : 1.0;
  }

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

  // Neighbour i's status at a pulse (depth or wave): `final` fixes its value to `pulse`, otherwise it
  // has passed `pulse`; false for a second final pulse.
  static bool record_pulse(std::vector<std::uint32_t>& value, std::vector<std::uint32_t>& seen, std::size_t& known,
                           std::size_t i, std::uint32_t pulse, bool final);
  void advance_depth();
  void maybe_candidate();
  void start_own_wave();
  void maybe_echo();
  void begin_wave(std::size_t from, NodeId root, NodeId first);
  void advance_wave();
  void maybe_finish_setup();
  void learn_shape(bool polygon);
  void advance_shape();
  void begin_round();
  void advance_steps();
  void advance_async_steps();
  void handle_async_radius(std::size_t i, const RadiusMsg& m);
  std::uint32_t round_of_step(std::uint32_t s) const;
  void advance_layout();
  void advance_radius_check();  // radius-only termination: the round's end without a layout
  bool check();  // false while waiting for data
  void advance_convergecast();
  void apply_decision(Verdict v);
  bool better(std::uint32_t d1, NodeId id1, std::uint32_t d2, NodeId id2) const;

  AgentHost& host_;
  std::size_t index_;
  AgentSpec know_;
  PackingParams params_;
  std::size_t deg_ = 0;
  std::vector<std::byte> buffer_;
  PackingPhase phase_ = PackingPhase::idle;
  PackingOutcome outcome_ = PackingOutcome::running;

  // Depth phase.
  std::uint32_t depth_ = unknown;
  std::uint32_t depth_pulse_ = 0;
  std::vector<std::uint32_t> nbr_depth_;
  std::vector<std::uint32_t> nbr_depth_seen_;
  std::size_t nbr_depths_known_ = 0;

  // Election.
  bool candidate_checked_ = false;
  bool in_wave_ = false;
  std::uint32_t best_depth_ = 0;
  NodeId best_id_ = 0;
  std::size_t echo_parent_ = 0;
  std::size_t echo_count_ = 0;
  bool echoed_ = false;  // the current wave's echo (or win) is done

  // Wave set-up.
  bool wave_started_ = false;
  bool is_root_ = false;
  bool is_first_ = false;
  NodeId root_id_ = 0;
  std::uint32_t wave_ = unknown;
  std::uint32_t wave_pulse_ = 0;
  NodeId parent_ = 0;
  std::size_t parent_index_ = 0;
  std::size_t anchor_a_ = 0, anchor_b_ = 0;
  std::vector<std::uint32_t> nbr_wave_;
  std::vector<std::uint32_t> nbr_wave_seen_;
  std::vector<std::uint8_t> child_;
  std::size_t nbr_waves_known_ = 0;
  bool setup_done_ = false;

  // Shape.
  std::vector<std::uint8_t> shape_up_;  // per neighbour: 0 none, 1 false, 2 true
  bool shape_sent_ = false;
  bool shape_known_ = false;
  bool polygon_ = false;

  // Rounds.
  std::uint32_t round_ = 0;
  std::uint32_t step_ = 0;
  std::uint32_t round_end_step_ = 0;
  std::uint32_t round_start_step_ = 0;
  // Asynchronous mode: newest known radius h of each neighbour and its version (update count), and the
  // number of radius messages received per round (by parity).
  std::vector<double> latest_h_;
  std::vector<std::uint32_t> latest_step_;
  std::array<std::uint32_t, 2> arrivals_{};
  bool sent_step_ = false;
  double h_ = 0;
  core::LocalAccelerator accelerator_;  // plain: returns the update unchanged
  std::vector<std::array<Slot, 2>> radius_;
  std::vector<double> star_h_, spoke_, rim_;
  std::vector<std::array<PlacedSlot, 2>> placed_in_;
  std::vector<std::array<FaceSlot, 2>> face_in_;  // per K-neighbour (used for face-vertex neighbours)
  bool placed_this_round_ = false;
  bool checked_this_round_ = false;
  bool reported_ = false;
  core::PlacedCircle placed_;
  core::LocalCondition local_ = core::LocalCondition::unrepresentable;
  std::size_t reports_ = 0;
  bool reports_ok_ = true;
  std::vector<core::Circle> check_circles_;
  // Radius-only termination (docs/radius-only.md): whether this round's layout was asked for (by a
  // Verdict::layout), the step whose radii the end-of-round exchange sent, the round's test outcome
  // and the current gap tolerance (halved by every failed exact check, at every node alike).
  bool radius_only_ = false;
  bool layout_round_ = false;
  std::uint32_t final_sent_ = unknown;
  bool radius_ok_ = false;
  double gap_ = 0;
};

}  // namespace laguerre::protocols::detail
