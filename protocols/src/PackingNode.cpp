#include "laguerre/protocols/PackingNode.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"

namespace laguerre::protocols {

LocalKnowledge local_knowledge(const core::PlanarGraph& g, core::Vertex v) {
  LocalKnowledge k;
  k.id = g.id(v);
  k.boundary = g.is_boundary(v);
  const core::Dart first = g.first_dart(v);
  for (std::uint32_t i = 0; i < g.degree(v); ++i) {
    k.neighbours.push_back(g.id(g.head(first + i)));
    // Wedge i (neighbour i to neighbour i+1, counter-clockwise) is the face left of dart v→neighbour i.
    if (k.boundary && k.outer_gap == LocalKnowledge::no_gap && g.face_of(first + i) == g.outer_face()) k.outer_gap = i;
  }
  return k;
}

PackingNode::PackingNode(Runtime& runtime, LocalKnowledge knowledge, PackingParams params)
    : rt_(runtime), know_(std::move(knowledge)), params_(params), deg_(know_.neighbours.size()) {
  const std::string who = "Node " + std::to_string(know_.id);
  if (deg_ == 0) throw std::invalid_argument(who + " has no neighbours.");
  if (deg_ >= unknown) throw std::invalid_argument(who + " has too many neighbours.");
  for (std::size_t i = 0; i < deg_; ++i) {
    if (know_.neighbours[i] == know_.id) throw std::invalid_argument(who + " lists itself as a neighbour.");
    sorted_ids_.emplace_back(know_.neighbours[i], static_cast<std::uint32_t>(i));
  }
  std::sort(sorted_ids_.begin(), sorted_ids_.end());
  for (std::size_t i = 1; i < deg_; ++i)
    if (sorted_ids_[i].first == sorted_ids_[i - 1].first)
      throw std::invalid_argument(who + " lists neighbour " + std::to_string(sorted_ids_[i].first) + " twice.");
  if (know_.boundary && know_.outer_gap >= deg_)
    throw std::invalid_argument(who + " is on the boundary but its outer-face wedge is not one of its wedges.");
  if (!know_.boundary && know_.outer_gap != LocalKnowledge::no_gap)
    throw std::invalid_argument(who + " is interior but has an outer-face wedge.");
  if (params_.steps_per_check < 1) throw std::invalid_argument("steps_per_check must be at least 1.");
  if (params_.max_iterations < 0) throw std::invalid_argument("max_iterations must not be negative.");
  nbr_depth_.assign(deg_, unknown);
  nbr_depth_seen_.assign(deg_, 0);
  nbr_wave_.assign(deg_, unknown);
  nbr_wave_seen_.assign(deg_, 0);
  child_.assign(deg_, 0);
  radius_.assign(deg_, {});
  placed_in_.assign(deg_, {});
  star_x_.assign(deg_, 0.0);
  check_circles_.assign(deg_, core::Circle{});
  x_ = know_.boundary ? 0.0 : core::x_of_radius(1.0);  // core::initial_radii
}

std::size_t PackingNode::children() const {
  return static_cast<std::size_t>(std::count(child_.begin(), child_.end(), std::uint8_t{1}));
}

std::size_t PackingNode::index_of(NodeId id) const {
  const auto it = std::lower_bound(sorted_ids_.begin(), sorted_ids_.end(), std::make_pair(id, std::uint32_t{0}));
  return it != sorted_ids_.end() && it->first == id ? it->second : deg_;
}

void PackingNode::send(std::size_t i, const Message& m) {
  encode(m, buffer_);
  send_encoded(i);
}

void PackingNode::send_encoded(std::size_t i) {
  rt_.send(know_.neighbours[i], buffer_);
  ++counters_.sent;
  counters_.bytes_sent += buffer_.size();
}

void PackingNode::broadcast(const Message& m) {
  encode(m, buffer_);
  rt_.broadcast(buffer_);
  counters_.sent += deg_;
  counters_.bytes_sent += deg_ * buffer_.size();
}

bool PackingNode::better(std::uint32_t d1, NodeId id1, std::uint32_t d2, NodeId id2) const {
  return d1 > d2 || (d1 == d2 && id1 < id2);
}

void PackingNode::on_start() {
  if (phase_ != PackingPhase::idle) return;
  phase_ = PackingPhase::depth;
  if (know_.boundary) depth_ = 0;
  broadcast(DepthMsg{0, know_.boundary});
  advance_depth();
  maybe_candidate();
}

void PackingNode::on_timer(TimerId) { ++counters_.unexpected; }  // the synchronous mode sets no timers

void PackingNode::on_message(NodeId from, std::span<const std::byte> bytes) {
  ++counters_.received;
  const std::size_t i = index_of(from);
  if (i == deg_) {
    ++counters_.not_a_neighbour;
    return;
  }
  Message m;
  const DecodeStatus s = decode(bytes, m);
  ++counters_.decode[static_cast<std::size_t>(s)];
  if (s != DecodeStatus::ok) return;
  if (phase_ == PackingPhase::idle || phase_ == PackingPhase::finished) {
    ++counters_.unexpected;
    return;
  }
  std::visit([&](const auto& msg) { handle(i, msg); }, m);
}

// ---- Depth: pulse-synchronized BFS from the boundary ----------------------------------------------

void PackingNode::handle(std::size_t i, const DepthMsg& m) {
  if (m.final) {
    if (nbr_depth_[i] != unknown) {
      ++counters_.unexpected;
      return;
    }
    nbr_depth_[i] = m.pulse;
    ++nbr_depths_known_;
  } else {
    nbr_depth_seen_[i] = std::max(nbr_depth_seen_[i], m.pulse + 1);
  }
  advance_depth();
  maybe_candidate();
  if (nbr_depths_known_ == deg_) {  // the wave may have been waiting for the neighbours' depths
    advance_wave();
    maybe_finish_setup();
  }
}

void PackingNode::advance_depth() {
  // Status of neighbour i at pulse p is known if its final depth is known (depth ≤ p: that depth;
  // depth > p: "unknown at p") or it said "unknown" at some pulse ≥ p. In a synchronous BFS the first
  // pulse at which a neighbour's depth is known is that depth, so v's depth is 1 + the first pulse p
  // at which some neighbour has depth ≤ p.
  while (depth_ == unknown) {
    const std::uint32_t p = depth_pulse_;
    bool found = false;
    for (std::size_t i = 0; i < deg_; ++i) {
      if (nbr_depth_[i] == unknown && nbr_depth_seen_[i] <= p) return;
      found = found || nbr_depth_[i] <= p;
    }
    ++depth_pulse_;
    if (found) depth_ = depth_pulse_;
    broadcast(DepthMsg{depth_pulse_, found});
  }
}

// ---- Election: echo with extinction over (depth, id) ---------------------------------------------

void PackingNode::maybe_candidate() {
  if (candidate_checked_ || wave_started_ || depth_ == unknown || nbr_depths_known_ < deg_) return;
  candidate_checked_ = true;
  if (phase_ == PackingPhase::depth) phase_ = PackingPhase::election;
  if (know_.boundary) return;
  const bool deepest = params_.root == core::RootRule::deepest;
  const std::uint32_t key = deepest ? depth_ : 0;
  // Only local maxima start a wave: the global maximum is one, so the election still completes,
  // with far fewer extinguished waves than if every node started.
  for (std::size_t i = 0; i < deg_; ++i)
    if (interior_nbr(i) && !better(key, know_.id, deepest ? nbr_depth_[i] : 0, know_.neighbours[i])) return;
  if (in_wave_ && !better(key, know_.id, best_depth_, best_id_)) return;
  in_wave_ = true;
  best_depth_ = key;
  best_id_ = know_.id;
  echo_parent_ = deg_;
  echo_count_ = 0;
  broadcast(ElectionMsg{key, know_.id});
}

void PackingNode::handle(std::size_t i, const ElectionMsg& m) {
  if (wave_started_) {  // a late token of an extinguished wave
    return;
  }
  if (!in_wave_ || better(m.depth, m.id, best_depth_, best_id_)) {
    // Join the stronger wave: the sender is our parent; forward to everyone else.
    in_wave_ = true;
    best_depth_ = m.depth;
    best_id_ = m.id;
    echo_parent_ = i;
    echo_count_ = 1;
    encode(m, buffer_);
    for (std::size_t j = 0; j < deg_; ++j)
      if (j != i) send_encoded(j);
  } else if (m.depth == best_depth_ && m.id == best_id_) {
    ++echo_count_;
  } else {
    return;  // weaker wave: extinguished here
  }
  if (echo_count_ > deg_) {
    ++counters_.unexpected;
    return;
  }
  if (echo_count_ < deg_) return;
  // Every neighbour has sent this wave's token: echo to the parent, or, at the initiator, win.
  if (echo_parent_ == deg_) begin_wave(deg_, know_.id, know_.neighbours[0]);
  else send(echo_parent_, ElectionMsg{best_depth_, best_id_});
}

// ---- Wave set-up: the combinatorial layout wave ----------------------------------------------------

void PackingNode::handle(std::size_t i, const StartMsg& m) {
  if (wave_started_) {
    if (m.root != root_id_) ++counters_.unexpected;
    return;
  }
  begin_wave(i, m.root, m.first);
}

void PackingNode::begin_wave(std::size_t from, NodeId root, NodeId first) {
  wave_started_ = true;
  phase_ = PackingPhase::wave;
  root_id_ = root;
  is_root_ = root == know_.id;
  is_first_ = first == know_.id;
  encode(StartMsg{root, first}, buffer_);
  for (std::size_t j = 0; j < deg_; ++j)
    if (j != from) send_encoded(j);
  if (is_root_) {
    wave_ = 0;
    parent_ = know_.id;
    parent_index_ = deg_;
    broadcast(WaveMsg{0, true, parent_});
  } else if (is_first_ && index_of(root) != deg_) {
    wave_ = 0;
    parent_ = root;
    parent_index_ = index_of(root);
    broadcast(WaveMsg{0, true, parent_});
  } else {
    broadcast(WaveMsg{0, false, 0});
  }
  advance_wave();
  maybe_finish_setup();
}

void PackingNode::handle(std::size_t i, const WaveMsg& m) {
  if (m.placed) {
    if (nbr_wave_[i] != unknown) {
      ++counters_.unexpected;
      return;
    }
    nbr_wave_[i] = m.pulse;
    child_[i] = m.parent == know_.id ? 1 : 0;
    ++nbr_waves_known_;
  } else {
    nbr_wave_seen_[i] = std::max(nbr_wave_seen_[i], m.pulse + 1);
  }
  advance_wave();
  maybe_finish_setup();
}

void PackingNode::advance_wave() {
  // Pulse p decides whether v is placed in wave p + 1: it needs every neighbour's status at p (known
  // as for the depth pulses) and which neighbours are interior (their depths).
  if (!wave_started_ || nbr_depths_known_ < deg_) return;
  while (wave_ == unknown) {
    const std::uint32_t p = wave_pulse_;
    for (std::size_t i = 0; i < deg_; ++i)
      if (nbr_wave_[i] == unknown && nbr_wave_seen_[i] <= p) return;
    const auto d = static_cast<std::uint32_t>(deg_);
    const std::uint32_t w = core::choose_placement_wedge(
        d, [&](std::uint32_t j) { return j != know_.outer_gap; },
        [&](std::uint32_t j) { return nbr_wave_[j] <= p; }, [&](std::uint32_t j) { return interior_nbr(j); });
    ++wave_pulse_;
    if (w == d) {
      broadcast(WaveMsg{wave_pulse_, false, 0});
      continue;
    }
    wave_ = wave_pulse_;
    anchor_a_ = w;
    anchor_b_ = w + 1 == d ? 0 : w + 1;
    parent_index_ = core::parent_is_first_anchor(interior_nbr(anchor_a_), interior_nbr(anchor_b_)) ? anchor_a_ : anchor_b_;
    parent_ = know_.neighbours[parent_index_];
    broadcast(WaveMsg{wave_pulse_, true, parent_});
  }
}

void PackingNode::maybe_finish_setup() {
  if (setup_done_ || wave_ == unknown || nbr_waves_known_ < deg_ || nbr_depths_known_ < deg_) return;
  setup_done_ = true;
  phase_ = PackingPhase::rounds;
  round_ = 0;
  begin_round();
}

// ---- Rounds -------------------------------------------------------------------------------------------

void PackingNode::begin_round() {
  placed_this_round_ = false;
  checked_this_round_ = false;
  reported_ = false;
  reports_ = 0;
  reports_ok_ = true;
  // As core::pack: round 0 checks the initial radii; round r ≥ 1 runs min(N, cap − steps) sweeps.
  const auto cap = static_cast<std::uint32_t>(params_.max_iterations);
  const auto n = static_cast<std::uint32_t>(params_.steps_per_check);
  round_end_step_ = round_ == 0 ? step_ : step_ + std::min(n, cap - std::min(cap, step_));
  sent_step_ = false;
  advance_steps();
}

void PackingNode::handle(std::size_t i, const RadiusMsg& m) {
  // A neighbour is at most one step ahead: it needs our X(t) to compute its X(t + 1).
  if (phase_ != PackingPhase::rounds || know_.boundary || !interior_nbr(i) || m.step < step_ || m.step > step_ + 1) {
    ++counters_.unexpected;
    return;
  }
  radius_[i][m.step & 1] = Slot{m.step, m.x};
  advance_steps();
}

void PackingNode::advance_steps() {
  if (know_.boundary) step_ = round_end_step_;  // horocycles never change
  while (step_ < round_end_step_) {
    if (!sent_step_) {
      sent_step_ = true;
      encode(RadiusMsg{step_, x_}, buffer_);
      for (std::size_t i = 0; i < deg_; ++i)
        if (interior_nbr(i)) send_encoded(i);
    }
    const std::size_t slot = step_ & 1;
    for (std::size_t i = 0; i < deg_; ++i) {
      if (!interior_nbr(i)) {
        star_x_[i] = 0.0;
        continue;
      }
      if (radius_[i][slot].tag != step_) return;
      star_x_[i] = radius_[i][slot].x;
    }
    // The Jacobi update: every neighbour value is from step t, as in core::thurston_sweep.
    x_ = core::star_updated_radius(x_, core::StarView{star_x_, {}, {}}, params_.update);
    ++step_;
    sent_step_ = false;
  }
  advance_layout();
}

void PackingNode::handle(std::size_t i, const PlacedMsg& m) {
  // A neighbour is at most one round ahead: its round r + 1 needs the decision of round r, which
  // needs our report of round r.
  if (m.round != round_ && m.round != round_ + 1) {
    ++counters_.unexpected;
    return;
  }
  placed_in_[i][m.round & 1] = PlacedSlot{m.round, m.x, {{m.centre_re, m.centre_im}, {m.cx, m.cy, m.cr}}};
  if (phase_ == PackingPhase::rounds) advance_layout();
}

void PackingNode::advance_layout() {
  if (step_ < round_end_step_ || phase_ != PackingPhase::rounds) return;
  const std::size_t slot = round_ & 1;
  auto heard = [&](std::size_t i) { return placed_in_[i][slot].tag == round_; };
  if (!placed_this_round_) {
    const core::LayoutVertex me{x_, !know_.boundary};
    if (is_root_) {
      placed_ = core::place_root(x_);
    } else if (is_first_) {
      if (!heard(parent_index_)) return;
      placed_ = core::place_first_neighbour(placed_in_[parent_index_][slot].x, me, 1.0);
    } else {
      if (!heard(anchor_a_) || !heard(anchor_b_)) return;
      const PlacedSlot& a = placed_in_[anchor_a_][slot];
      const PlacedSlot& b = placed_in_[anchor_b_][slot];
      placed_ = core::place_in_face(me, {a.x, interior_nbr(anchor_a_)}, a.at, {b.x, interior_nbr(anchor_b_)}, b.at,
                                    core::FaceCosines{});
    }
    placed_this_round_ = true;
    broadcast(PlacedMsg{round_, x_, placed_.centre.real(), placed_.centre.imag(), placed_.circle.x,
                        placed_.circle.y, placed_.circle.r});
  }
  if (!checked_this_round_) {
    for (std::size_t i = 0; i < deg_; ++i)
      if (!heard(i)) return;
    // LPD lists a boundary vertex's neighbours from w1, just after the outer wedge (lpd_first_dart).
    const std::size_t start = know_.boundary ? (know_.outer_gap + 1) % deg_ : 0;
    for (std::size_t j = 0; j < deg_; ++j) check_circles_[j] = placed_in_[(start + j) % deg_][slot].at.circle;
    local_ = core::check_lpd_at(placed_.circle, check_circles_, know_.boundary);
    checked_this_round_ = true;
  }
  advance_convergecast();
}

void PackingNode::handle(std::size_t i, const ReportMsg& m) {
  if (phase_ != PackingPhase::rounds || !child_[i] || m.round != round_) {
    ++counters_.unexpected;
    return;
  }
  ++reports_;
  reports_ok_ = reports_ok_ && m.ok;
  advance_convergecast();
}

void PackingNode::advance_convergecast() {
  if (!checked_this_round_ || reported_ || reports_ < children()) return;
  reported_ = true;
  const bool ok = reports_ok_ && local_ == core::LocalCondition::holds;
  if (!is_root_) {
    send(parent_index_, ReportMsg{round_, ok});
    return;
  }
  // The root decides, as core::pack's loop: stop when the rule holds, else when the cap is reached.
  const Verdict v = ok ? Verdict::converged
                       : (step_ >= static_cast<std::uint32_t>(params_.max_iterations) ? Verdict::cap : Verdict::next);
  apply_decision(v);
}

void PackingNode::handle(std::size_t i, const DecisionMsg& m) {
  if (phase_ != PackingPhase::rounds || is_root_ || i != parent_index_ || m.round != round_ || !reported_) {
    ++counters_.unexpected;
    return;
  }
  apply_decision(m.verdict);
}

void PackingNode::apply_decision(Verdict v) {
  encode(DecisionMsg{round_, v}, buffer_);
  for (std::size_t i = 0; i < deg_; ++i)
    if (child_[i]) send_encoded(i);
  if (v == Verdict::next) {
    ++round_;
    begin_round();
    return;
  }
  phase_ = PackingPhase::finished;
  outcome_ = v == Verdict::converged ? PackingOutcome::converged : PackingOutcome::cap;
}

}  // namespace laguerre::protocols
