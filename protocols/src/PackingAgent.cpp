#include "PackingAgent.hpp"

#include <algorithm>
#include <limits>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"
#include "laguerre/core/packing/RadiusOnly.hpp"
#include "laguerre/protocols/LocalChecks.hpp"

namespace laguerre::protocols::detail {

PackingAgent::PackingAgent(AgentHost& host, std::size_t index, AgentSpec spec, PackingParams params)
    : host_(host), index_(index), know_(std::move(spec)), params_(params), deg_(know_.neighbours.size()),
      accelerator_(params.acceleration) {
  nbr_depth_.assign(deg_, unknown);
  nbr_depth_seen_.assign(deg_, 0);
  nbr_wave_.assign(deg_, unknown);
  nbr_wave_seen_.assign(deg_, 0);
  child_.assign(deg_, 0);
  shape_up_.assign(deg_, 0);
  radius_.assign(deg_, {});
  placed_in_.assign(deg_, {});
  face_in_.assign(deg_, {});
  star_h_.assign(deg_, std::numeric_limits<double>::infinity());
  check_circles_.assign(deg_, core::Circle{});
  // Intersection cosines of the star, as PackingComplex stores them: an edge of K is orthogonal iff
  // it touches a face vertex. Empty for a tangent-only star (the closed-form update applies).
  if (know_.polygon_here) {
    for (std::size_t i = 0; i < deg_; ++i) {
      spoke_.push_back(cos_spoke(i));
      rim_.push_back(cos_rim(i));
    }
  }
  h_ = know_.boundary ? std::numeric_limits<double>::infinity() : 1.0;  // core::initial_radii
  // Asynchronous mode: every interior vertex starts from the same X (version 0); boundary
  // neighbours' entries are never read.
  latest_h_.assign(deg_, 1.0);
  latest_step_.assign(deg_, 0);
  radius_only_ = params.termination == core::Termination::radius_only;
  gap_ = params.radius_only_gap;
}

std::size_t PackingAgent::children() const {
  return static_cast<std::size_t>(std::count(child_.begin(), child_.end(), std::uint8_t{1}));
}

VertexState PackingAgent::state() const {
  VertexState s;
  s.id = know_.id;
  s.depth = depth_;
  s.is_root = is_root_;
  s.wave = wave_;
  s.parent = parent_;
  s.steps = step_;
  s.round = round_;
  s.h = h_;
  s.placement = placed_;
  s.local = local_;
  s.phase = phase_;
  return s;
}

void PackingAgent::send(std::size_t i, const PackingMessage& m) {
  encode(m, buffer_);
  send_encoded(i);
}

void PackingAgent::send_encoded(std::size_t i) { host_.send(index_, i, buffer_); }

void PackingAgent::broadcast(const PackingMessage& m) {
  encode(m, buffer_);
  for (std::size_t i = 0; i < deg_; ++i) send_encoded(i);
}

bool PackingAgent::better(std::uint32_t d1, NodeId id1, std::uint32_t d2, NodeId id2) const {
  return d1 > d2 || (d1 == d2 && id1 < id2);
}

void PackingAgent::start() {
  if (phase_ != PackingPhase::idle) return;
  phase_ = PackingPhase::depth;
  if (know_.boundary) depth_ = 0;
  broadcast(DepthMsg{0, know_.boundary});
  advance_depth();
  maybe_candidate();
}

void PackingAgent::receive(std::size_t i, const PackingMessage& m) {
  // Asynchronous mode: the last round's updates do not wait for every neighbour's value, so a
  // neighbour's final RadiusMsg may still be on its way (e.g. retransmitted) when the stop decision
  // arrives. It is stale, not unexpected.
  if (phase_ == PackingPhase::finished && params_.asynchronous && std::holds_alternative<RadiusMsg>(m)) return;
  if (phase_ == PackingPhase::idle || phase_ == PackingPhase::finished) {
    ++host_.counters().unexpected;
    return;
  }
  std::visit([&](const auto& msg) { handle(i, msg); }, m);
}

// ---- Depth: pulse-synchronized BFS from the boundary (over K) -----------------------------------

bool PackingAgent::record_pulse(std::vector<std::uint32_t>& value, std::vector<std::uint32_t>& seen, std::size_t& known,
                                std::size_t i, std::uint32_t pulse, bool final) {
  if (!final) {
    seen[i] = std::max(seen[i], pulse + 1);
    return true;
  }
  if (value[i] != unknown) return false;  // a neighbour's final pulse comes once
  value[i] = pulse;
  ++known;
  return true;
}

void PackingAgent::handle(std::size_t i, const DepthMsg& m) {
  if (!record_pulse(nbr_depth_, nbr_depth_seen_, nbr_depths_known_, i, m.pulse, m.final)) {
    ++host_.counters().unexpected;
    return;
  }
  advance_depth();
  maybe_candidate();
  if (nbr_depths_known_ == deg_) {
    advance_wave();
    maybe_finish_setup();
  }
}

void PackingAgent::advance_depth() {
  // Status of neighbour i at pulse p is known if its final depth is known or it said "unknown" at
  // some pulse ≥ p. In a synchronous BFS the first pulse at which a neighbour's depth is known is that
  // depth, so v's depth is 1 + the first pulse p at which some neighbour has depth ≤ p.
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

// ---- Election: echo with extinction over (depth, id), original vertices only -----------------------

void PackingAgent::maybe_candidate() {
  if (candidate_checked_ || wave_started_ || depth_ == unknown || nbr_depths_known_ < deg_) return;
  candidate_checked_ = true;
  if (phase_ == PackingPhase::depth) phase_ = PackingPhase::election;
  start_own_wave();
  maybe_echo();  // an echo held back until this decision (see maybe_echo) may go now
}

void PackingAgent::start_own_wave() {
  // core::choose_root ranges over the vertices of G: face vertices only relay the election.
  if (know_.boundary || know_.is_face) return;
  const bool deepest = params_.root == core::RootRule::deepest;
  const std::uint32_t key = deepest ? depth_ : 0;
  // Only local maxima among interior G-neighbours start a wave: the global maximum is one.
  for (std::size_t i = 0; i < deg_; ++i)
    if (interior_nbr(i) && !know_.face_nbr[i] && !better(key, know_.id, deepest ? nbr_depth_[i] : 0, know_.neighbours[i]))
      return;
  if (in_wave_ && !better(key, know_.id, best_depth_, best_id_)) return;
  in_wave_ = true;
  best_depth_ = key;
  best_id_ = know_.id;
  echo_parent_ = deg_;
  echo_count_ = 0;
  echoed_ = false;
  broadcast(ElectionMsg{key, know_.id});
}

void PackingAgent::handle(std::size_t i, const ElectionMsg& m) {
  if (wave_started_) return;  // a late token of an extinguished wave
  if (!in_wave_ || better(m.depth, m.id, best_depth_, best_id_)) {
    in_wave_ = true;
    best_depth_ = m.depth;
    best_id_ = m.id;
    echo_parent_ = i;
    echo_count_ = 1;
    echoed_ = false;
    encode(m, buffer_);
    for (std::size_t j = 0; j < deg_; ++j)
      if (j != i) send_encoded(j);
  } else if (m.depth == best_depth_ && m.id == best_id_) {
    ++echo_count_;
  } else {
    return;  // weaker wave: extinguished here
  }
  if (echo_count_ > deg_) {
    ++host_.counters().unexpected;
    return;
  }
  maybe_echo();
}

void PackingAgent::maybe_echo() {
  // A vertex echoes a wave (or, as its initiator, wins) once every neighbour's token is in — and only
  // once it has decided whether it is a candidate itself. Without that wait, a vertex whose depth is
  // known late (long delays, retransmissions) could echo a weaker wave, let it complete and elect the
  // wrong root before starting its own stronger wave. With it, no wave completes without the
  // strongest candidate's echo, which that candidate never gives to a weaker wave: only the strongest
  // wave completes, whatever the delays.
  if (!candidate_checked_ || !in_wave_ || echoed_ || echo_count_ < deg_) return;
  echoed_ = true;
  if (echo_parent_ == deg_) begin_wave(deg_, know_.id, know_.neighbours[0]);
  else send(echo_parent_, ElectionMsg{best_depth_, best_id_});
}

// ---- Wave set-up: the combinatorial layout wave on K ------------------------------------------------

void PackingAgent::handle(std::size_t i, const StartMsg& m) {
  if (wave_started_) {
    if (m.root != root_id_) ++host_.counters().unexpected;
    return;
  }
  begin_wave(i, m.root, m.first);
}

void PackingAgent::begin_wave(std::size_t from, NodeId root, NodeId first) {
  wave_started_ = true;
  phase_ = PackingPhase::wave;
  root_id_ = root;
  is_root_ = root == know_.id;
  is_first_ = first == know_.id;
  encode(StartMsg{root, first}, buffer_);
  for (std::size_t j = 0; j < deg_; ++j)
    if (j != from) send_encoded(j);
  const auto root_index = static_cast<std::size_t>(
      std::find(know_.neighbours.begin(), know_.neighbours.end(), root) - know_.neighbours.begin());
  if (is_root_) {
    wave_ = 0;
    parent_ = know_.id;
    parent_index_ = deg_;
    broadcast(WaveMsg{0, true, parent_});
  } else if (is_first_ && root_index != deg_) {
    wave_ = 0;
    parent_ = root;
    parent_index_ = root_index;
    broadcast(WaveMsg{0, true, parent_});
  } else {
    broadcast(WaveMsg{0, false, 0});
  }
  advance_wave();
  maybe_finish_setup();
}

void PackingAgent::handle(std::size_t i, const WaveMsg& m) {
  if (!record_pulse(nbr_wave_, nbr_wave_seen_, nbr_waves_known_, i, m.pulse, m.placed)) {
    ++host_.counters().unexpected;
    return;
  }
  if (m.placed) child_[i] = m.parent == know_.id ? 1 : 0;
  advance_wave();
  maybe_finish_setup();
}

void PackingAgent::advance_wave() {
  // Pulse p decides whether v is placed in wave p + 1 (core::lay_out's round p + 1): it needs every
  // K-neighbour's status at p and which neighbours are interior. Face vertices take part exactly as
  // lay_out treats them: as vertices of K, placed and anchoring by the same rule.
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

void PackingAgent::maybe_finish_setup() {
  if (setup_done_ || wave_ == unknown || nbr_waves_known_ < deg_ || nbr_depths_known_ < deg_) return;
  setup_done_ = true;
  advance_shape();
}

// ---- Shape: OR of "touches a face vertex" up the layout tree, then down -----------------------------

void PackingAgent::handle(std::size_t i, const ShapeMsg& m) {
  if (!m.down) {
    // From a child (checked once the tree is known, in advance_shape); may precede our set-up's end.
    if (shape_up_[i] != 0) {
      ++host_.counters().unexpected;
      return;
    }
    shape_up_[i] = m.polygon ? 2 : 1;
    advance_shape();
    return;
  }
  if (!setup_done_ || shape_known_ || is_root_ || i != parent_index_) {
    ++host_.counters().unexpected;
    return;
  }
  learn_shape(m.polygon);
}

void PackingAgent::advance_shape() {
  if (!setup_done_ || shape_sent_) return;
  bool any = know_.polygon_here;
  for (std::size_t i = 0; i < deg_; ++i) {
    if (shape_up_[i] != 0 && !child_[i]) {
      ++host_.counters().unexpected;
      shape_up_[i] = 0;
    }
    if (!child_[i]) continue;
    if (shape_up_[i] == 0) return;
    any = any || shape_up_[i] == 2;
  }
  shape_sent_ = true;
  if (!is_root_) {
    send(parent_index_, ShapeMsg{false, any});
    return;
  }
  // The root knows the answer for the whole of K (the tree spans it).
  learn_shape(any);
}

void PackingAgent::learn_shape(bool polygon) {
  // The answer for the whole of K: pass it down the tree and start round 0.
  shape_known_ = true;
  polygon_ = polygon;
  encode(ShapeMsg{true, polygon_}, buffer_);
  for (std::size_t j = 0; j < deg_; ++j)
    if (child_[j]) send_encoded(j);
  phase_ = PackingPhase::rounds;
  round_ = 0;
  begin_round();
}

// ---- Rounds -------------------------------------------------------------------------------------------

void PackingAgent::begin_round() {
  placed_this_round_ = false;
  checked_this_round_ = false;
  reported_ = false;
  reports_ = 0;
  reports_ok_ = true;
  const auto cap = static_cast<std::uint32_t>(params_.max_iterations);
  const auto n = static_cast<std::uint32_t>(params_.steps_per_check);
  round_end_step_ = round_ == 0 ? step_ : step_ + std::min(n, cap - std::min(cap, step_));
  round_start_step_ = step_;
  sent_step_ = final_sent_ == step_;  // radius-only: the end-of-round exchange already sent X(step_)
  // Asynchronous mode: the counter of round r + 1 (that of round r − 1, done) starts afresh; no
  // neighbour can be in round r + 1 before this node has reported round r.
  arrivals_[(round_ + 1) & 1] = 0;
  advance_steps();
}

std::uint32_t PackingAgent::round_of_step(std::uint32_t s) const {
  // Every node runs the same schedule: round r ≥ 1 does steps ((r − 1)·N, min(r·N, cap)].
  const auto n = static_cast<std::uint32_t>(params_.steps_per_check);
  return (s + n - 1) / n;
}

void PackingAgent::handle_async_radius(std::size_t i, const RadiusMsg& m) {
  // m.step = the sender's update count after the update that produced m.h (its version). Neighbours
  // are at most one round ahead; a message of an earlier round may still arrive late (reordering) and
  // only refreshes the value if newer. Keep the newest value.
  const std::uint32_t r = m.step == 0 ? 0 : round_of_step(m.step);
  if (phase_ != PackingPhase::rounds || know_.boundary || !interior_nbr(i) || m.step == 0 ||
      m.step > static_cast<std::uint32_t>(params_.max_iterations) || r > round_ + 1) {
    ++host_.counters().unexpected;
    return;
  }
  if (m.step > latest_step_[i]) {
    latest_step_[i] = m.step;
    latest_h_[i] = m.h;
  }
  if (r >= round_) ++arrivals_[r & 1];
  advance_steps();
}

void PackingAgent::advance_async_steps() {
  // Chaotic relaxation: update k ≥ 2 of a round waits for k − 1 radius messages of this round (from
  // any neighbours), update 1 for none. Deadlock-free: if every interior vertex makes j updates of
  // round r, each has sent j messages to every interior neighbour, so each vertex with an interior
  // neighbour has received ≥ j and can make update j + 1; a vertex without one never waits.
  bool any_interior = false;
  for (std::size_t i = 0; i < deg_; ++i) any_interior = any_interior || interior_nbr(i);
  while (step_ < round_end_step_) {
    const std::uint32_t k = step_ - round_start_step_ + 1;
    if (k >= 2 && any_interior && arrivals_[round_ & 1] < k - 1) return;
    for (std::size_t i = 0; i < deg_; ++i) star_h_[i] = interior_nbr(i) ? latest_h_[i] : std::numeric_limits<double>::infinity();
    h_ = core::star_updated_radius(h_, core::StarView{star_h_, spoke_, rim_}, params_.update);
    ++step_;
    encode(RadiusMsg{step_, h_}, buffer_);
    for (std::size_t i = 0; i < deg_; ++i)
      if (interior_nbr(i)) send_encoded(i);
  }
}

void PackingAgent::handle(std::size_t i, const RadiusMsg& m) {
  if (params_.asynchronous) {
    handle_async_radius(i, m);
    return;
  }
  // Radius-only: round 0 ends with an exchange of X(0), which may reach a node still in set-up.
  const bool early = radius_only_ && phase_ == PackingPhase::wave && m.step == 0;
  if ((phase_ != PackingPhase::rounds && !early) || know_.boundary || !interior_nbr(i) || m.step < step_ ||
      m.step > step_ + 1) {
    ++host_.counters().unexpected;
    return;
  }
  radius_[i][m.step & 1] = Slot{m.step, m.h};
  if (early) return;
  if (radius_only_ && !layout_round_ && step_ == round_end_step_) {
    advance_radius_check();
    return;
  }
  advance_steps();
}

void PackingAgent::advance_steps() {
  if (know_.boundary) step_ = round_end_step_;  // horocycles never change
  if (params_.asynchronous) {
    advance_async_steps();
    if (step_ == round_end_step_) advance_layout();
    return;
  }
  while (step_ < round_end_step_) {
    if (!sent_step_) {
      sent_step_ = true;
      encode(RadiusMsg{step_, h_}, buffer_);
      for (std::size_t i = 0; i < deg_; ++i)
        if (interior_nbr(i)) send_encoded(i);
    }
    const std::size_t slot = step_ & 1;
    for (std::size_t i = 0; i < deg_; ++i) {
      if (!interior_nbr(i)) {
        star_h_[i] = std::numeric_limits<double>::infinity();
        continue;
      }
      if (radius_[i][slot].tag != step_) return;
      star_h_[i] = radius_[i][slot].h;
    }
    // The Jacobi update on K: every neighbour value is from step t, the cosines are those of
    // PackingComplex (spoke_/rim_ empty iff tangent_only), as in core::thurston_sweep; then this
    // vertex's local acceleration, as core::pack applies it after the sweep.
    h_ = accelerator_.next(h_, core::star_updated_radius(h_, core::StarView{star_h_, spoke_, rim_}, params_.update));
    ++step_;
    sent_step_ = false;
  }
  if (radius_only_ && !layout_round_) {
    advance_radius_check();
    return;
  }
  advance_layout();
}

void PackingAgent::advance_radius_check() {
  // One radius exchange ends the round: X(step_) to the interior neighbours (it is also the next
  // round's first exchange, which therefore is not sent again), then the closing gap with every
  // neighbour's X(step_) — the same star, cosines and function as core::pack's check.
  if (checked_this_round_ || phase_ != PackingPhase::rounds) return;
  if (!know_.boundary && !sent_step_) {
    sent_step_ = true;
    final_sent_ = step_;
    encode(RadiusMsg{step_, h_}, buffer_);
    for (std::size_t i = 0; i < deg_; ++i)
      if (interior_nbr(i)) send_encoded(i);
  }
  if (!know_.boundary) {
    const std::size_t slot = step_ & 1;
    for (std::size_t i = 0; i < deg_; ++i) {
      if (!interior_nbr(i)) {
        star_h_[i] = std::numeric_limits<double>::infinity();
        continue;
      }
      if (radius_[i][slot].tag != step_) return;
      star_h_[i] = radius_[i][slot].h;
    }
  }
  radius_ok_ = core::radius_only_holds(h_, core::StarView{star_h_, spoke_, rim_}, know_.boundary, gap_);
  checked_this_round_ = true;
  advance_convergecast();
}

void PackingAgent::handle(std::size_t i, const PlacedMsg& m) {
  if (m.round != round_ && m.round != round_ + 1) {
    ++host_.counters().unexpected;
    return;
  }
  placed_in_[i][m.round & 1] = PlacedSlot{m.round, m.h, {{m.centre_re, m.centre_im}, {m.cx, m.cy, m.cr}}};
  if (params_.asynchronous && interior_nbr(i)) {
    // The sender's X after its last update of round m.round: version min(round·N, cap).
    const auto version = static_cast<std::uint32_t>(std::min<std::uint64_t>(
        std::uint64_t{m.round} * static_cast<std::uint64_t>(params_.steps_per_check),
        static_cast<std::uint64_t>(params_.max_iterations)));
    if (version > latest_step_[i]) {
      latest_step_[i] = version;
      latest_h_[i] = m.h;
    }
  }
  if (phase_ == PackingPhase::rounds) advance_layout();
}

void PackingAgent::handle(std::size_t i, const FaceCirclesMsg& m) {
  // Only from a face vertex, with one circle per member of its face (its degree is not known here:
  // the size is checked against the walk when used), at most one round ahead.
  if (!know_.face_nbr[i] || know_.is_face || (m.round != round_ && m.round != round_ + 1)) {
    ++host_.counters().unexpected;
    return;
  }
  FaceSlot& s = face_in_[i][m.round & 1];
  s.tag = m.round;
  s.circles.clear();
  for (const FaceCircle& c : m.circles) s.circles.push_back({c.x, c.y, c.r});
  if (phase_ == PackingPhase::rounds) advance_layout();
}

void PackingAgent::advance_layout() {
  if (step_ < round_end_step_ || phase_ != PackingPhase::rounds || (radius_only_ && !layout_round_)) return;
  const std::size_t slot = round_ & 1;
  auto heard = [&](std::size_t i) { return placed_in_[i][slot].tag == round_; };
  if (!placed_this_round_) {
    const core::LayoutVertex me{h_, !know_.boundary};
    if (is_root_) {
      placed_ = core::place_root(h_);
    } else if (is_first_) {
      if (!heard(parent_index_)) return;
      placed_ = core::place_first_neighbour(placed_in_[parent_index_][slot].h, me, polygon_ ? cos_spoke(parent_index_) : 1.0);
    } else {
      if (!heard(anchor_a_) || !heard(anchor_b_)) return;
      const PlacedSlot& a = placed_in_[anchor_a_][slot];
      const PlacedSlot& b = placed_in_[anchor_b_][slot];
      // lay_out's cosines: 1 everywhere for a triangulation, else those of K, with the overlap formula.
      const core::FaceCosines c = polygon_ ? core::FaceCosines{cos_spoke(anchor_a_), cos_spoke(anchor_b_), cos_rim(anchor_a_), true}
                                           : core::FaceCosines{};
      placed_ = core::place_in_face(me, {a.h, interior_nbr(anchor_a_)}, a.at, {b.h, interior_nbr(anchor_b_)}, b.at, c);
    }
    placed_this_round_ = true;
    broadcast(PlacedMsg{round_, h_, placed_.centre.real(), placed_.centre.imag(), placed_.circle.x,
                        placed_.circle.y, placed_.circle.r});
  }
  if (!checked_this_round_) {
    for (std::size_t i = 0; i < deg_; ++i)
      if (!heard(i)) return;
    if (!check()) return;
    checked_this_round_ = true;
  }
  advance_convergecast();
}

bool PackingAgent::check() {
  const std::size_t slot = round_ & 1;
  if (know_.is_face) {
    // core checks G only: a face vertex's part is to hand its members the circles of the face.
    FaceCirclesMsg fc;
    fc.round = round_;
    for (std::size_t i = 0; i < deg_; ++i) {
      const core::Circle& c = placed_in_[i][slot].at.circle;
      fc.circles.push_back({c.x, c.y, c.r});
    }
    broadcast(fc);
    local_ = core::LocalCondition::holds;
    return true;
  }
  if (!polygon_) {
    // LPD lists a boundary vertex's neighbours from w1, just after the outer wedge (lpd_first_dart).
    const std::size_t start = know_.boundary ? (know_.outer_gap + 1) % deg_ : 0;
    for (std::size_t j = 0; j < deg_; ++j) check_circles_[j] = placed_in_[(start + j) % deg_][slot].at.circle;
    local_ = core::check_lpd_at(placed_.circle, check_circles_, know_.boundary);
    return true;
  }
  // GLPD (core::check_all's choice when some inner face is not a triangle), from the circles of the
  // G-neighbours and, per polygon face, the face vertex's FaceCirclesMsg of this round.
  const std::size_t gdeg = know_.g_k.size();
  for (std::size_t i = 0; i < gdeg; ++i)
    if (know_.g_face[i] != nullptr) {
      const FaceSlot& s = face_in_[know_.g_k[i] + 1][slot];
      if (s.tag != round_) return false;
      if (s.circles.size() != know_.g_face[i]->size()) {
        ++host_.counters().unexpected;
        return false;  // a malformed face message: never decide on it
      }
    }
  std::vector<core::Circle> nb(gdeg);
  std::vector<std::uint64_t> nid(gdeg);
  for (std::size_t i = 0; i < gdeg; ++i) {
    nb[i] = placed_in_[know_.g_k[i]][slot].at.circle;
    nid[i] = know_.neighbours[know_.g_k[i]];
  }
  std::vector<std::vector<core::Circle>> fc(gdeg);
  std::vector<std::vector<std::uint64_t>> fid(gdeg);
  std::vector<GlpdWedge> wedges(gdeg);
  for (std::size_t i = 0; i < gdeg; ++i) {
    const std::size_t j = i + 1 == gdeg ? 0 : i + 1;
    if (know_.boundary && i == know_.g_outer_gap) {
      wedges[i].outer = true;
      continue;
    }
    if (const std::vector<NodeId>* walk = know_.g_face[i]) {
      // Rotate the host-ordered circles to start at this vertex: walk[p] is the host.
      const std::size_t m = walk->size();
      const std::size_t p = static_cast<std::size_t>(std::min_element(walk->begin(), walk->end()) - walk->begin());
      const FaceSlot& s = face_in_[know_.g_k[i] + 1][slot];
      for (std::size_t k = 0; k < m; ++k) {
        fc[i].push_back(s.circles[(k + m - p) % m]);
        fid[i].push_back((*walk)[k]);
      }
    } else {
      fc[i] = {placed_.circle, nb[i], nb[j]};
      fid[i] = {know_.id, nid[i], nid[j]};
    }
    wedges[i].circles = fc[i];
    wedges[i].ids = fid[i];
  }
  local_ = check_glpd_local(placed_.circle, know_.id, nb, nid, know_.boundary, know_.g_outer_gap, wedges);
  return true;
}

void PackingAgent::handle(std::size_t i, const ReportMsg& m) {
  if (phase_ != PackingPhase::rounds || !child_[i] || m.round != round_) {
    ++host_.counters().unexpected;
    return;
  }
  ++reports_;
  reports_ok_ = reports_ok_ && m.ok;
  advance_convergecast();
}

void PackingAgent::advance_convergecast() {
  if (!checked_this_round_ || reported_ || reports_ < children()) return;
  reported_ = true;
  const bool radius_phase = radius_only_ && !layout_round_;
  const bool ok = reports_ok_ && (radius_phase ? radius_ok_ : local_ == core::LocalCondition::holds);
  if (!is_root_) {
    send(parent_index_, ReportMsg{round_, ok});
    return;
  }
  const bool at_cap = step_ >= static_cast<std::uint32_t>(params_.max_iterations);
  // Radius-only: the layout is made when the test holds everywhere, and at the cap (coordinates).
  const Verdict v = radius_phase ? (ok || at_cap ? Verdict::layout : Verdict::next)
                                 : (ok ? Verdict::converged : (at_cap ? Verdict::cap : Verdict::next));
  apply_decision(v);
}

void PackingAgent::handle(std::size_t i, const DecisionMsg& m) {
  // A radius-only round's report is answered by next or layout, any other report by next, converged or cap.
  const bool radius_phase = radius_only_ && !layout_round_;
  const bool fits = radius_phase ? m.verdict == Verdict::next || m.verdict == Verdict::layout : m.verdict != Verdict::layout;
  if (phase_ != PackingPhase::rounds || is_root_ || i != parent_index_ || m.round != round_ || !reported_ || !fits) {
    ++host_.counters().unexpected;
    return;
  }
  apply_decision(m.verdict);
}

void PackingAgent::apply_decision(Verdict v) {
  encode(DecisionMsg{round_, v}, buffer_);
  for (std::size_t i = 0; i < deg_; ++i)
    if (child_[i]) send_encoded(i);
  if (v == Verdict::layout) {  // the same round, laid out and checked exactly
    layout_round_ = true;
    checked_this_round_ = false;
    reported_ = false;
    reports_ = 0;
    reports_ok_ = true;
    advance_layout();
    return;
  }
  if (v == Verdict::next) {
    if (layout_round_) gap_ /= 2;  // a failed exact check (core::pack halves alike)
    layout_round_ = false;
    ++round_;
    begin_round();
    return;
  }
  phase_ = PackingPhase::finished;
  outcome_ = v == Verdict::converged ? PackingOutcome::converged : PackingOutcome::cap;
}

}  // namespace laguerre::protocols::detail
