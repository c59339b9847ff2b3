#include "PackingAgent.hpp"

#include <algorithm>
#include <limits>

#include "laguerre/core/packing/HyperbolicTriangle.hpp"
#include "laguerre/core/packing/NewtonKrylov.hpp"
#include "laguerre/core/packing/RadiusOnly.hpp"
#include "laguerre/protocols/LocalChecks.hpp"

namespace laguerre::protocols::detail {

// The state of a Newton–Krylov step (see "Newton–Krylov steps" below); allocated in that mode only.
struct PackingAgent::KrylovState {
  struct Slot {  // a neighbour's exchanged value of a tree sum
    std::uint32_t tag = unknown;
    double h = 0;
  };
  enum class Stage : std::uint8_t { idle, exchange, sum, decision };
  explicit KrylovState(std::size_t deg) : value(deg), sum_tag(deg, unknown), sum(deg), neighbour(deg, 0.0) {}
  Stage stage = Stage::idle;
  std::uint32_t seq = 0;         // the tree sum this vertex is at
  bool trial = false;            // the exchange carries trial radii (else CG's z)
  std::uint32_t steps_left = 0;  // boundary vertices: Newton steps of this round still to relay
  core::KrylovVertex vertex;
  core::KrylovRoot root;
  core::KrylovSums own;
  std::vector<std::array<Slot, 2>> value;  // per neighbour, by seq parity
  std::vector<std::uint32_t> sum_tag;      // per child: the seq of its partial in `sum`
  std::vector<core::KrylovSums> sum;
  std::vector<double> neighbour;           // the exchanged values in neighbour order
};

// The state of the radius-flood termination (see "Radius-flood steps" below); allocated in that mode only.
struct PackingAgent::FloodState {
  static constexpr std::size_t slots = 64;  // pending tested steps at once (core::radius_flood_period)
  explicit FloodState(std::size_t deg) : bits(2 * deg, ~std::uint64_t{0}) {}
  std::uint32_t depth = 0;                   // D: steps from a test to its decision
  int period = 1;                            // every period-th round is tested
  std::uint64_t active = 0;                  // slots of pending tested steps
  std::uint64_t mine = 0;                    // per slot: the AND over the ball heard so far
  std::uint64_t head = 0, tail = 0;          // ordinals of the oldest pending test and of the next one
  std::array<std::uint32_t, slots> test_step{};
  std::array<double, slots> saved_h{};       // this vertex's radius at each pending tested step
  std::vector<std::uint64_t> bits;           // the neighbours' gate bits by step parity: bits[p·deg + i]
  bool sent = false;                         // the exchange of step_ is sent
  bool paused = false;                       // a layout and exact check are under way
  double current_h = 0;                      // X(step_) while a tested iterate is laid out
  std::uint32_t layout_step = 0;             // the step whose radii are laid out
};

PackingAgent::PackingAgent(PackingNode& node, std::size_t index, AgentSpec spec)
    : node_(node), params_(node.params_), id_(spec.id), index_(static_cast<std::uint32_t>(index)),
      deg_(static_cast<std::uint32_t>(spec.neighbours.size())), outer_gap_(spec.outer_gap),
      g_outer_gap_(spec.g_outer_gap), boundary_(spec.boundary), is_face_(spec.is_face),
      polygon_here_(spec.polygon_here), peers_(std::make_unique<Peer[]>(deg_)),
      radius_(std::make_unique<double[]>(2 * std::size_t{deg_})) {
  told_ = deg_;
  asynchronous_ = params_.asynchronous;
  update_ = params_.update;
  for (std::size_t i = 0; i < deg_; ++i) {
    peers_[i].id = spec.neighbours[i];
    peers_[i].face = spec.face_nbr.empty() ? 0 : spec.face_nbr[i];
  }
  // Synchronous mode: boundary neighbours' radii stay ∞ (horocycles), the others are written before
  // they are read. Asynchronous mode: every interior vertex starts from the same X (version 0);
  // boundary neighbours' entries become ∞ when the rounds start.
  std::fill(radius_.get(), radius_.get() + 2 * std::size_t{deg_},
            params_.asynchronous ? 1.0 : std::numeric_limits<double>::infinity());
  radius_tag_ = std::make_unique<std::uint32_t[]>(2 * std::size_t{deg_});
  std::fill(radius_tag_.get(), radius_tag_.get() + 2 * std::size_t{deg_}, unknown);
  if (polygon_here_) {
    poly_ = std::make_unique<Polygon>();
    poly_->g_k = std::move(spec.g_k);
    poly_->g_face = std::move(spec.g_face);
    poly_->face_in.resize(deg_);
    // Intersection cosines of the star, as PackingComplex stores them: an edge of K is orthogonal iff
    // it touches a face vertex. Empty for a tangent-only star (the closed-form update applies).
    if (polygon_here_) {
      for (std::size_t i = 0; i < deg_; ++i) {
        poly_->spoke.push_back(cos_spoke(i));
        poly_->rim.push_back(cos_rim(i));
      }
    }
  }
  if (params_.acceleration != core::Acceleration::plain)
    accelerator_ = std::make_unique<core::LocalAccelerator>(params_.acceleration);
  h_ = boundary_ ? std::numeric_limits<double>::infinity() : 1.0;  // core::initial_radii
  if (params_.acceleration == core::Acceleration::newton_krylov) krylov_ = std::make_unique<KrylovState>(deg_);
  radius_only_ = params_.termination != core::Termination::layout;
  gap_ = params_.radius_only_gap;
  if (params_.termination == core::Termination::radius_flood) flood_ = std::make_unique<FloodState>(deg_);
}

std::size_t PackingAgent::index_of(NodeId id) const {
  std::size_t i = 0;
  while (i < deg_ && peers_[i].id != id) ++i;
  return i;
}

std::vector<std::byte>& PackingAgent::buffer() { return node_.scratch_; }
PackingCounters& PackingAgent::counters() { return node_.counters_; }

core::StarView PackingAgent::star(const double* h) const {
  if (!poly_ || poly_->spoke.empty()) return core::StarView{{h, deg_}, {}, {}};
  return core::StarView{{h, deg_}, poly_->spoke, poly_->rim};
}

PackingAgent::~PackingAgent() = default;

std::size_t PackingAgent::children() const {
  std::size_t c = 0;
  for (std::size_t i = 0; i < deg_; ++i) c += peers_[i].child;
  return c;
}

VertexState PackingAgent::state() const {
  VertexState s;
  s.id = id_;
  s.depth = depth_;
  s.bfs_parent = bfs_parent_ < deg_ ? peers_[bfs_parent_].id : id_;
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
  encode(m, buffer());
  send_encoded(i);
}

void PackingAgent::send_encoded(std::size_t i) { node_.agent_send(index_, i, buffer()); }

void PackingAgent::broadcast(const PackingMessage& m) {
  encode(m, buffer());
  send_to_all_encoded();
}

void PackingAgent::send_to_all_encoded() {
  // Without face vertices the K-neighbours are the node's neighbours: one runtime broadcast (one
  // stored copy in a simulator), the same messages as one send per neighbour in order.
  if (index_ == 0 && !polygon_here_) {
    node_.broadcast_all(buffer());
    return;
  }
  for (std::size_t i = 0; i < deg_; ++i) send_encoded(i);
}

bool PackingAgent::better(std::uint32_t d1, NodeId id1, std::uint32_t d2, NodeId id2) const {
  return d1 > d2 || (d1 == d2 && id1 < id2);
}

void PackingAgent::start() {
  if (phase_ != PackingPhase::idle) return;
  phase_ = PackingPhase::depth;
  if (!boundary_) return;  // engaged by its first estimate
  depth_ = 0;
  bfs_parent_ = deg_;
  depth_deficit_ = deg_;
  broadcast(DepthMsg{false, 0, id_});
}

bool PackingAgent::takes(bool radius) {
  if (phase_ != PackingPhase::idle && phase_ != PackingPhase::finished) return true;
  // Asynchronous mode: the last round's updates do not wait for every neighbour's value, so a
  // neighbour's final RadiusMsg may still be on its way (e.g. retransmitted) when the stop decision
  // arrives. It is stale, not unexpected.
  if (!(radius && asynchronous_ && phase_ == PackingPhase::finished)) ++counters().unexpected;
  return false;
}

void PackingAgent::receive(std::size_t i, const PackingMessage& m) {
  if (takes(std::holds_alternative<RadiusMsg>(m))) std::visit([&](const auto& msg) { handle(i, msg); }, m);
}

void PackingAgent::receive(std::size_t i, const RadiusMsg& m) {
  if (takes(true)) handle(i, m);
}

// ---- Depth: event-driven BFS from the boundary (over K), Dijkstra–Scholten termination --------------
//
// A boundary vertex has depth 0 and sends it to its neighbours; a vertex that hears an estimate e with
// e + 1 below its own takes e + 1 and sends it on: estimates only decrease and never fall below the
// distances, so they reach them whatever the delays (with equal link delays the first estimate a
// vertex hears is its depth: one estimate per dart). Every estimate is acknowledged (DepthMsg ack), and
// the vertex's BFS parent is the first neighbour (K order) whose estimate is one less than its own,
// as the pulse BFS took it. The diffusion is a Dijkstra–Scholten computation with the boundary vertices
// as initiators: a vertex holds the acknowledgement of every estimate it could take its depth from (a
// "candidate", e + 1 = its depth) until all its own messages are acknowledged, and acknowledges any
// other one at once. A held estimate's sender is strictly shallower than the holder, so holds never
// form a cycle, and a vertex with unacknowledged messages holds one; hence once every boundary vertex
// has all its acknowledgements, no message is in flight anywhere and every estimate is final.
// The released acknowledgement of a candidate says whether its sender is the parent; the claim a
// vertex last received from a neighbour decides whether it is that neighbour's child: a claim at a
// smaller depth is newer, and at the same depth a "no" is newer than a "yes" (the parent, the first
// candidate, only moves to lower K indices as candidates arrive, and once told "no" a candidate never
// becomes the parent at that depth); a claim above the neighbour's final depth is void (its estimate
// at the smaller depth replaced it). If a lower candidate arrives after the parent was told "yes", the
// vertex sends that former parent a correction (an estimate naming the new parent), which it
// acknowledges at once. None is needed in FIFO order with equal delays: a vertex's candidates all
// arrive before its own estimates can be acknowledged. Then the boundary ring learns that the
// diffusion has ended (`settled`, Chang–Roberts on the smallest id of a boundary vertex whose messages
// are all acknowledged: it comes back to its sender only after every boundary vertex passed it on
// with its messages acknowledged, which stays so), and its sender sends `final` both ways round the
// ring and each boundary vertex down its BFS subtree; a vertex that gets it knows its depth, its
// neighbours' depths and its BFS children for good.

void PackingAgent::handle(std::size_t i, const DepthMsg& m) {
  if (depth_final_) {  // every depth message is acknowledged before `final` is sent
    ++counters().unexpected;
    return;
  }
  Peer& p = peers_[i];
  if (m.ack) {
    if (depth_deficit_ == 0) {
      ++counters().unexpected;
      return;
    }
    --depth_deficit_;
    if (m.parent != p.id) hear_claim(p, m.depth, m.parent == id_);
    if (depth_deficit_ == 0) depth_quiet();
    return;
  }
  if (m.parent != p.id) {  // a correction: its sender's parent is now another neighbour of it
    hear_claim(p, m.depth, m.parent == id_);
    send(i, DepthMsg{true, depth_, id_});
    return;
  }
  p.depth = std::min(p.depth, m.depth);
  if (m.depth + 1 < depth_) {  // a smaller depth: i is the only candidate
    depth_ = m.depth + 1;
    told_ = deg_;  // the estimate voids the claim the former parent holds
    for (std::size_t j = 0; j < deg_; ++j)
      if (peers_[j].bfs & held_bit) {  // candidates no more
        peers_[j].bfs &= ~held_bit;
        send(j, DepthMsg{true, depth_, id_});
      }
    bfs_parent_ = static_cast<std::uint32_t>(i);
    p.bfs |= held_bit;
    depth_deficit_ += deg_;
    broadcast(DepthMsg{false, depth_, id_});
    return;
  }
  if (m.depth + 1 != depth_ || (p.bfs & held_bit)) {  // not a candidate (an older estimate, overtaken)
    if (m.depth + 1 == depth_) ++counters().unexpected;  // the same estimate twice
    send(i, DepthMsg{true, depth_, id_});
    return;
  }
  if (i < bfs_parent_) {  // a new parent at the same depth
    if (told_ != deg_) {
      ++depth_deficit_;
      send(told_, DepthMsg{false, depth_, p.id});
      told_ = deg_;
    }
    bfs_parent_ = static_cast<std::uint32_t>(i);
  }
  if (depth_deficit_ != 0) {
    p.bfs |= held_bit;
    return;
  }
  send(i, DepthMsg{true, depth_, peers_[bfs_parent_].id});  // "no": the parent has been told
}

void PackingAgent::hear_claim(Peer& p, std::uint32_t depth, bool yes) {
  if (p.claim_depth != unknown && depth > p.claim_depth) return;  // older
  if (depth == p.claim_depth && !(p.bfs & claim_bit)) return;     // "no" is newer than "yes"
  p.claim_depth = depth;
  p.bfs = yes ? p.bfs | claim_bit : p.bfs & ~claim_bit;
}

void PackingAgent::depth_quiet() {
  // Every message this vertex sent is acknowledged: release the candidates, or offer `settled`.
  if (boundary_) {
    quiet_ = true;
    offer_settled(std::min(held_settled_, id_));
    return;
  }
  const NodeId parent = peers_[bfs_parent_].id;
  for (std::size_t j = 0; j < deg_; ++j)
    if (peers_[j].bfs & held_bit) {
      peers_[j].bfs &= ~held_bit;
      if (j == bfs_parent_) told_ = static_cast<std::uint32_t>(j);
      send(j, DepthMsg{true, depth_, parent});
    }
}

void PackingAgent::offer_settled(NodeId id) {
  if (id >= settled_sent_) return;
  settled_sent_ = id;
  send(outer_gap_, ElectionMsg{ElectionStage::settled, 0, id});
}

void PackingAgent::handle_settled(std::size_t i, const ElectionMsg& m) {
  if (!boundary_ || i != (outer_gap_ + 1) % deg_ || m.depth != 0) {
    ++counters().unexpected;
    return;
  }
  if (depth_final_) return;  // a beaten token, late
  if (m.id == id_) {  // back: every boundary vertex has passed it on quiet, so the BFS has ended
    if (!quiet_ || settled_sent_ != id_) {
      ++counters().unexpected;
      return;
    }
    learn_final(deg_, id_);
    return;
  }
  if (!quiet_) {
    held_settled_ = std::min(held_settled_, m.id);
    return;
  }
  offer_settled(m.id);
}

void PackingAgent::handle_final(std::size_t i, const ElectionMsg& m) {
  const std::size_t out = outer_gap_, in = boundary_ ? (outer_gap_ + 1) % deg_ : deg_;
  const bool ring = boundary_ && (i == out || i == in);
  if (m.depth != 0 || !(ring || (!boundary_ && i == bfs_parent_))) {
    ++counters().unexpected;
    return;
  }
  if (depth_final_) {
    if (!boundary_) ++counters().unexpected;  // on the ring the two ways meet
    return;
  }
  learn_final(i, m.id);
}

void PackingAgent::learn_final(std::size_t from, NodeId winner) {
  // Every estimate is final and delivered: the BFS parent (the first neighbour one shallower) and the
  // children (the neighbours whose last valid claim names this vertex) are known for good.
  depth_final_ = true;
  if (!boundary_) {
    std::size_t parent = 0;
    while (parent < deg_ && peers_[parent].depth + 1 != depth_) ++parent;
    if (parent != bfs_parent_ || told_ != bfs_parent_ || depth_deficit_ != 0) ++counters().unexpected;
  }
  const ElectionMsg token{ElectionStage::final, 0, winner};
  encode(token, buffer());
  if (boundary_) {  // on round the ring the way it came (both ways from its sender)
    const std::size_t out = outer_gap_, in = (outer_gap_ + 1) % deg_;
    if (from != in) send_encoded(in);
    if (from != out && out != in) send_encoded(out);
  }
  for (std::size_t j = 0; j < deg_; ++j) {
    Peer& q = peers_[j];
    if ((q.bfs & claim_bit) && q.claim_depth == q.depth) {
      q.bfs |= child_bit;
      send_encoded(j);
    }
  }
  advance_key();
  advance_wave();
  release_wave();
}

// ---- Election: the best key up the BFS forest, round the boundary ring, down to the root --------------
//
// core::choose_root takes the interior vertex of G with the best key (depth, id) (RootRule). Once a
// vertex has `final` (its depth, its neighbours' and its BFS children known for good) and every
// child's report, it reports the best key of its subtree (its own included
// if it is an interior vertex of G) to its BFS parent. A boundary vertex, a BFS root, then offers its
// subtree's best key round the boundary ring (to the neighbour that opens its outer wedge, so every key
// travels the outer face's way round): a key goes on only while it beats every key the vertex has
// offered or forwarded (Chang–Roberts on the maximum), so the best key of all, which beats every
// other, goes round and comes back to the boundary vertex that offered it, while every other key dies
// at that vertex at the latest. That vertex sends the key down its subtree, each vertex to the child
// that reported it, to the vertex whose key it is: the root. Every vertex learns its depths before it
// reports, so the result is core's whatever the delays; messages: one report per vertex, the ring
// (at most b² for b boundary vertices, O(b log b) for random keys) and one path of the root's depth.

void PackingAgent::advance_key() {
  if (key_reported_ || !depth_final_) return;
  std::uint32_t children = 0, reports = 0;
  for (std::size_t i = 0; i < deg_; ++i) {
    children += (peers_[i].bfs & child_bit) != 0;
    reports += (peers_[i].bfs & report_bit) != 0;
  }
  if (reports < children) return;
  if (reports != children) ++counters().unexpected;  // a report from a vertex that is no child
  key_reported_ = true;
  if (phase_ == PackingPhase::depth) phase_ = PackingPhase::election;
  if (!boundary_ && !is_face_) {  // core::choose_root ranges over the vertices of G
    const std::uint32_t key = params_.root == core::RootRule::deepest ? depth_ : 0;
    if (better_key(key, id_)) {
      best_depth_ = key;
      best_id_ = id_;
      best_child_ = deg_;
    }
  }
  if (!boundary_) {
    send(bfs_parent_, ElectionMsg{ElectionStage::report, best_depth_, best_id_});
    return;
  }
  // A held ring key that beats the subtree's goes on instead of it.
  if (held_id_ != no_key && better_key(held_depth_, held_id_)) offer_ring(held_depth_, held_id_);
  else if (best_id_ != no_key) offer_ring(best_depth_, best_id_);
}

void PackingAgent::offer_ring(std::uint32_t depth, NodeId id) {
  if (ring_id_ != no_key && !better(depth, id, ring_depth_, ring_id_)) return;
  ring_depth_ = depth;
  ring_id_ = id;
  send(outer_gap_, ElectionMsg{ElectionStage::ring, depth, id});
}

void PackingAgent::handle(std::size_t i, const ElectionMsg& m) {
  if (m.stage == ElectionStage::settled) return handle_settled(i, m);
  if (m.stage == ElectionStage::final) return handle_final(i, m);
  if (wave_started_) return;  // a late ring key, beaten by the root's
  switch (m.stage) {
    case ElectionStage::settled:
    case ElectionStage::final:
      break;
    case ElectionStage::report:
      if (key_reported_ || (peers_[i].bfs & report_bit) != 0) break;
      peers_[i].bfs |= report_bit;
      if (better_key(m.depth, m.id)) {
        best_depth_ = m.depth;
        best_id_ = m.id;
        best_child_ = i;
      }
      advance_key();
      return;
    case ElectionStage::ring:
      if (!boundary_ || i != (outer_gap_ + 1) % deg_ || m.id == no_key) break;
      if (key_reported_ && m.id == best_id_ && m.depth == best_depth_) {  // our key came back: the best
        if (best_child_ != deg_) send(best_child_, ElectionMsg{ElectionStage::root, m.depth, m.id});
        return;
      }
      if (!key_reported_) {  // held until the subtree's key is known
        if (held_id_ == no_key || better(m.depth, m.id, held_depth_, held_id_)) {
          held_depth_ = m.depth;
          held_id_ = m.id;
        }
        return;
      }
      if (better_key(m.depth, m.id)) offer_ring(m.depth, m.id);
      return;
    case ElectionStage::root:
      if (!key_reported_ || boundary_ || i != bfs_parent_ || m.id != best_id_ || m.depth != best_depth_) break;
      if (best_child_ == deg_) start_layout_wave();
      else send(best_child_, ElectionMsg{ElectionStage::root, m.depth, m.id});
      return;
  }
  ++counters().unexpected;
}

// ---- Layout wave: the combinatorial layout wave on K, event-driven ------------------------------------
//
// core::lay_out places the root and its first neighbour at wave 0 and a vertex at wave p + 1 when some
// inner-face wedge has both ends placed by wave p, taking the wedge choose_placement_wedge picks among
// those: wave(v) = 1 + min over inner wedges (a, b) of max(wave(a), wave(b)), a fixed point of a
// monotone map. Each vertex holds its neighbours' newest estimates (∞ until heard), recomputes its own
// and sends WaveMsg whenever its (wave, parent) changes; estimates only decrease and stay ≥ the true
// waves, so they reach them (chaotic relaxation), whatever the delays — in a network of equal link
// delays the first finite estimate is already the wave, so a vertex sends about one WaveMsg. The end
// is detected by Dijkstra–Scholten: every StartMsg / WaveMsg is acknowledged (ShapeMsg up); the
// message that engages an idle vertex is acknowledged only once the vertex is passive (its depth
// neighbourhood known) and all its own messages are acknowledged. When the root's are, every vertex's
// estimate is final and every WaveMsg delivered, so the root sends ShapeMsg down the layout tree
// (every vertex knows its children from their last WaveMsg), with the OR of the face-vertex bits that
// the acknowledgements carried up the engagement trees (an OR of fixed bits survives re-engagement).

void PackingAgent::start_layout_wave() {
  wave_started_ = true;
  phase_ = PackingPhase::wave;
  root_id_ = id_;
  is_root_ = true;
  wave_ = 0;
  parent_ = id_;
  parent_index_ = deg_;
  ds_parent_ = deg_;
  ds_polygon_ = polygon_here_;
  ds_deficit_ += deg_;
  broadcast(StartMsg{id_, peers_[0].id});  // the root's placement, to its neighbours only
  release_wave();
}

bool PackingAgent::join_wave(std::size_t from) {
  if (!wave_started_) {
    wave_started_ = true;
    phase_ = PackingPhase::wave;
    ds_polygon_ = polygon_here_;
  }
  if (ds_parent_ != unknown) return false;
  ds_parent_ = static_cast<std::uint32_t>(from);
  return true;
}

void PackingAgent::handle(std::size_t i, const StartMsg& m) {
  if (is_root_ || peers_[i].wave_seq != 0 || m.root != peers_[i].id) {
    ++counters().unexpected;
    return;
  }
  const bool engaged_now = join_wave(i);
  root_id_ = m.root;
  peers_[i].wave_seq = 1;
  peers_[i].wave = 0;
  if (m.first == id_ && !is_first_) {
    is_first_ = true;
    wave_ = 0;
    parent_ = m.root;
    parent_index_ = i;
    ++wave_seq_;
    ds_deficit_ += deg_;
    broadcast(WaveMsg{wave_seq_, 0, parent_});
  }
  advance_wave();
  end_wave_message(i, engaged_now);
}

void PackingAgent::handle(std::size_t i, const WaveMsg& m) {
  const bool engaged_now = join_wave(i);
  Peer& p = peers_[i];
  if (m.seq > p.wave_seq) {  // else an older estimate overtaken by a newer one: acknowledged only
    if (p.wave != unknown && m.wave > p.wave) ++counters().unexpected;  // estimates never increase
    p.wave_seq = m.seq;
    p.wave = m.wave;
    p.child = m.parent == id_ ? 1 : 0;
    advance_wave();
  }
  end_wave_message(i, engaged_now);
}

void PackingAgent::advance_wave() {
  // Needs which neighbours are interior (the wedge rule), hence every neighbour's depth. Face vertices
  // take part exactly as lay_out treats them: as vertices of K, placed and anchoring by the same rule.
  if (!wave_started_ || is_root_ || is_first_ || !depth_final_) return;
  const auto d = static_cast<std::uint32_t>(deg_);
  std::uint32_t p = unknown;  // the earliest wave by which some inner wedge has both ends placed
  for (std::uint32_t j = 0; j < d; ++j) {
    const std::uint32_t k = j + 1 == d ? 0 : j + 1;
    if (j != outer_gap_ && peers_[j].wave != unknown && peers_[k].wave != unknown)
      p = std::min(p, std::max(peers_[j].wave, peers_[k].wave));
  }
  if (p == unknown) return;
  const std::uint32_t w = core::choose_placement_wedge(
      d, [&](std::uint32_t j) { return j != outer_gap_; }, [&](std::uint32_t j) { return peers_[j].wave <= p; },
      [&](std::uint32_t j) { return interior_nbr(j); });
  const std::size_t a = w, b = w + 1 == d ? 0 : w + 1;
  const std::size_t parent = core::parent_is_first_anchor(interior_nbr(a), interior_nbr(b)) ? a : b;
  if (wave_ == p + 1 && parent == parent_index_ && a == anchor_a_) return;
  wave_ = p + 1;
  anchor_a_ = a;
  anchor_b_ = b;
  parent_index_ = parent;
  parent_ = peers_[parent].id;
  ++wave_seq_;
  ds_deficit_ += deg_;
  broadcast(WaveMsg{wave_seq_, wave_, parent_});
}

void PackingAgent::end_wave_message(std::size_t from, bool engaged_now) {
  if (!engaged_now) send(from, ShapeMsg{false, false});
  release_wave();
}

void PackingAgent::release_wave() {
  if (ds_parent_ == unknown || ds_deficit_ != 0 || !depth_final_) return;
  const std::uint32_t to = ds_parent_;
  ds_parent_ = unknown;
  if (to == deg_) {  // the root: the wave has ended everywhere
    learn_shape(ds_polygon_);
    return;
  }
  send(to, ShapeMsg{false, ds_polygon_});
}

// ---- Shape and height: the root's answers down the final layout tree ---------------------------------

void PackingAgent::handle(std::size_t i, const ShapeMsg& m) {
  if (!m.down) {  // an acknowledgement of one of our StartMsg / WaveMsg
    if (ds_deficit_ == 0) {
      ++counters().unexpected;
      return;
    }
    --ds_deficit_;
    ds_polygon_ = ds_polygon_ || m.polygon;
    release_wave();
    return;
  }
  if (!wave_started_ || shape_known_ || is_root_ || i != parent_index_ || ds_parent_ != unknown) {
    ++counters().unexpected;
    return;
  }
  learn_shape(m.polygon);
}

void PackingAgent::learn_shape(bool polygon) {
  // The wave has ended: pass the answer for the whole of K down the tree, then (radius-flood) learn the
  // tree's height, and start round 0.
  shape_known_ = true;
  polygon_ = polygon;
  for (std::size_t i = 0; i < deg_; ++i) interior_nbrs_ += interior_nbr(i);
  if (deg_ <= 64) {
    for (std::size_t i = 0; i < deg_; ++i) interior_mask_ |= std::uint64_t{interior_nbr(i)} << i;
    mask_ready_ = true;
  }
  encode(ShapeMsg{true, polygon_}, buffer());
  for (std::size_t j = 0; j < deg_; ++j)
    if (peers_[j].child) send_encoded(j);
  if (flood_) {
    advance_height();
    return;
  }
  begin_rounds();
}

// The height convergecast, once on the final tree: the largest wave of each subtree up, of K down
// (radius-flood's D = 2·height + 2; any mode that needs the height can run it the same way).
void PackingAgent::handle(std::size_t i, const HeightMsg& m) {
  if (!m.down) {
    if (!flood_ || !shape_known_ || !peers_[i].child || peers_[i].height_up) {
      ++counters().unexpected;
      return;
    }
    peers_[i].height_up = 1;
    height_ = std::max(height_, m.height);
    advance_height();
    return;
  }
  if (!flood_ || !height_sent_ || is_root_ || i != parent_index_ || phase_ != PackingPhase::wave) {
    ++counters().unexpected;
    return;
  }
  learn_height(m.height);
}

void PackingAgent::advance_height() {
  if (!shape_known_ || height_sent_) return;
  for (std::size_t i = 0; i < deg_; ++i)
    if (peers_[i].child && !peers_[i].height_up) return;
  height_sent_ = true;
  const std::uint32_t height = std::max(height_, wave_);  // the subtree's largest wave
  if (!is_root_) {
    send(parent_index_, HeightMsg{false, height});
    return;
  }
  learn_height(height);
}

void PackingAgent::learn_height(std::uint32_t height) {
  height_ = height;
  encode(HeightMsg{true, height_}, buffer());
  for (std::size_t j = 0; j < deg_; ++j)
    if (peers_[j].child) send_encoded(j);
  begin_rounds();
}

void PackingAgent::begin_rounds() {
  phase_ = PackingPhase::rounds;
  round_ = 0;
  if (flood_) {
    flood_->depth = core::radius_flood_depth(height_);
    flood_->period = core::radius_flood_period(static_cast<int>(flood_->depth), params_.steps_per_check);
    flood_advance();
    return;
  }
  // Asynchronous mode: boundary neighbours (known by now) count as horocycles in every update.
  if (params_.asynchronous)
    for (std::size_t i = 0; i < deg_; ++i)
      if (!interior_nbr(i)) radius_[i] = std::numeric_limits<double>::infinity();
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
  if (phase_ != PackingPhase::rounds || boundary_ || !interior_nbr(i) || m.step == 0 ||
      m.step > static_cast<std::uint32_t>(params_.max_iterations) || r > round_ + 1) {
    ++counters().unexpected;
    return;
  }
  if (m.step > peers_[i].latest_step) {
    peers_[i].latest_step = m.step;
    radius_[i] = m.h;
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
    h_ = core::star_updated_radius(h_, star(radius_.get()), params_.update);
    ++step_;
    encode(RadiusMsg{step_, h_}, buffer());
    for (std::size_t i = 0; i < deg_; ++i)
      if (interior_nbr(i)) send_encoded(i);
  }
}

void PackingAgent::handle(std::size_t i, const RadiusMsg& m) {
  if (asynchronous_) {
    handle_async_radius(i, m);
    return;
  }
  // Radius-only: round 0 ends with an exchange of X(0), which may reach a node still in set-up.
  const bool early = radius_only_ && phase_ == PackingPhase::wave && m.step == 0;
  if ((phase_ != PackingPhase::rounds && !early) || boundary_ || !interior_fast(i) || m.step < step_ ||
      m.step > step_ + 1) {
    ++counters().unexpected;
    return;
  }
  const std::size_t slot = m.step & 1;
  std::uint32_t& tag = radius_tag_[slot * deg_ + i];
  if (tag != m.step) {  // a radius not yet heard (heard_all counts each once)
    if (heard_step_[slot] != m.step) {
      heard_step_[slot] = m.step;
      heard_[slot] = 0;
    }
    ++heard_[slot];
  }
  tag = m.step;
  radius_[slot * deg_ + i] = m.h;
  if (early) return;
  if (radius_only_ && !layout_round_ && step_ == round_end_step_) {
    advance_radius_check();
    return;
  }
  advance_steps();
}

void PackingAgent::advance_steps() {
  if (boundary_) {
    // Horocycles never change; in Newton–Krylov mode the vertex still relays the round's tree sums.
    if (krylov_ && step_ < round_end_step_) {
      krylov_->steps_left = round_end_step_ - step_;
      krylov_begin_step();
    }
    step_ = round_end_step_;
  }
  if (asynchronous_) {
    advance_async_steps();
    if (step_ == round_end_step_) advance_layout();
    return;
  }
  while (step_ < round_end_step_) {
    if (krylov_ && krylov_->stage != KrylovState::Stage::idle) return;  // a Newton step is under way
    if (!sent_step_) {
      sent_step_ = true;
      encode(RadiusMsg{step_, h_}, buffer());
      if (interior_nbrs_ == deg_) {
        send_to_all_encoded();
      } else {
        for (std::size_t i = 0; i < deg_; ++i)
          if (interior_nbr(i)) send_encoded(i);
      }
    }
    const std::size_t slot = step_ & 1;
    if (!heard_all(step_)) return;
    if (krylov_) {  // the step continues in krylov_apply
      krylov_begin_step();
      return;
    }
    // The Jacobi update on K: every neighbour value is from step t (∞ for boundary neighbours), the
    // cosines are those of PackingComplex (none iff tangent_only), as in core::thurston_sweep; then
    // this vertex's local acceleration, as core::pack applies it after the sweep.
    const double updated = core::star_updated_radius(h_, star(radius_.get() + slot * deg_), update_);
    h_ = accelerator_ ? accelerator_->next(h_, updated) : updated;
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
  const std::size_t slot = step_ & 1;
  if (!boundary_) {
    if (!sent_step_) {
      sent_step_ = true;
      final_sent_ = step_;
      encode(RadiusMsg{step_, h_}, buffer());
      for (std::size_t i = 0; i < deg_; ++i)
        if (interior_nbr(i)) send_encoded(i);
    }
    if (!heard_all(step_)) return;
  }
  radius_ok_ = core::radius_only_holds(h_, star(radius_.get() + slot * deg_), boundary_, gap_);
  checked_this_round_ = true;
  advance_convergecast();
}

// ---- Radius-flood steps (Termination::radius_flood, docs/radius-only.md §8) -------------------------
//
// Every vertex of K, boundary included, exchanges GateRadiusMsg with every K-neighbour at every step:
// its radius (∞ on the boundary) and its gate bits. The closing-gap test of a tested step s starts as
// the vertex's own bit and is ANDed with the neighbours' at every later step, so after the exchange of
// step s + D every vertex holds the AND over its D-ball — all of K, D bounding the diameter — and all
// decide alike, with no convergecast: on 1 they lay out their radii of step s (kept for it) and run
// the exact check as the layout termination does; a failed check halves the gap, drops the pending
// tests and goes on from step s + D. core::pack with Termination::radius_flood computes the same.

void PackingAgent::handle(std::size_t i, const GateRadiusMsg& m) {
  // Step 0 may reach a vertex still in set-up; a neighbour is never more than one step ahead.
  const bool early = phase_ != PackingPhase::rounds && m.step == 0;
  if (!flood_ || (phase_ != PackingPhase::rounds && !early) || m.step < step_ || m.step > step_ + 1 ||
      radius_tag_[(m.step & 1) * deg_ + i] == m.step) {
    ++counters().unexpected;
    return;
  }
  const std::size_t slot = m.step & 1;
  radius_tag_[slot * deg_ + i] = m.step;
  radius_[slot * deg_ + i] = m.h;  // ∞ from a boundary neighbour: what the entry holds anyway
  flood_->bits[slot * deg_ + i] = m.gate;
  if (phase_ == PackingPhase::rounds) flood_advance();
}

void PackingAgent::flood_advance() {
  FloodState& f = *flood_;
  if (phase_ != PackingPhase::rounds || f.paused) return;
  const auto cap = static_cast<std::uint32_t>(params_.max_iterations);
  while (true) {
    if (step_ >= cap) {  // the cap: the current radii are laid out and checked
      flood_lay_out(step_, h_);
      return;
    }
    const std::size_t slot = step_ & 1;
    if (!f.sent) {
      f.sent = true;
      encode(GateRadiusMsg{step_, h_, f.mine | ~f.active}, buffer());
      send_to_all_encoded();
    }
    for (std::size_t i = 0; i < deg_; ++i)
      if (radius_tag_[slot * deg_ + i] != step_) return;
    std::uint64_t heard = ~std::uint64_t{0};
    for (std::size_t i = 0; i < deg_; ++i) heard &= f.bits[slot * deg_ + i];
    f.mine &= heard;
    if (f.head != f.tail && f.test_step[f.head % FloodState::slots] + f.depth == step_) {
      const std::size_t j = f.head % FloodState::slots;
      ++f.head;
      f.active &= ~(std::uint64_t{1} << j);
      if ((f.mine >> j) & 1) {
        flood_lay_out(f.test_step[j], f.saved_h[j]);
        return;
      }
    }
    flood_finish_step();
  }
}

void PackingAgent::flood_finish_step() {
  // The test of this step if it is tested (with the gap in force), then the Jacobi update — the star,
  // cosines and functions of core::pack.
  FloodState& f = *flood_;
  const core::StarView s = star(radius_.get() + (step_ & 1) * deg_);
  if (core::radius_flood_tested(step_, params_.steps_per_check, f.period)) {
    const std::size_t j = f.tail % FloodState::slots;
    const std::uint64_t b = std::uint64_t{1} << j;
    ++f.tail;
    f.active |= b;
    f.test_step[j] = step_;
    f.saved_h[j] = h_;
    f.mine = core::radius_only_holds(h_, s, boundary_, gap_) ? f.mine | b : f.mine & ~b;
  }
  if (!boundary_) {
    const double updated = core::star_updated_radius(h_, s, params_.update);
    h_ = accelerator_ ? accelerator_->next(h_, updated) : updated;
  }
  ++step_;
  f.sent = false;
}

void PackingAgent::flood_lay_out(std::uint32_t step, double h) {
  FloodState& f = *flood_;
  f.paused = true;
  f.current_h = h_;
  f.layout_step = step;
  h_ = h;
  layout_round_ = true;
  placed_this_round_ = false;
  checked_this_round_ = false;
  reported_ = false;
  reports_ = 0;
  reports_ok_ = true;
  round_end_step_ = step_;
  advance_layout();
}

void PackingAgent::flood_resume() {
  // A failed exact check: halve the gap, drop the pending tests, go on from X(step_).
  FloodState& f = *flood_;
  gap_ /= 2;
  f.head = f.tail;
  f.active = 0;
  f.mine = 0;
  h_ = f.current_h;
  f.paused = false;
  flood_finish_step();
  flood_advance();
}

// ---- Newton–Krylov steps (PackingParams::acceleration = newton_krylov) --------------------------------
//
// core::NewtonKrylovMethod in the network (docs/protocol.md, "Newton–Krylov in the network"). A step
// starts once the step's radii are in (the RadiusMsg exchange); then, until the root accepts or
// rejects: [exchange a value with the interior neighbours (KrylovValueMsg)], add up the tree
// (KrylovSumMsg: own sums, then each child's partial in neighbour order), the root decides
// (core::KrylovRoot) and the decision goes down (KrylovDecisionMsg). Every protocol vertex counts the
// tree sums (`seq`, equal everywhere); boundary vertices only relay (their sums are zero). Values run
// at most one sum ahead (a neighbour's next value needs this vertex's partial), hence two slots.

void PackingAgent::krylov_begin_step() {
  KrylovState& k = *krylov_;
  k.root.reset();
  if (boundary_) {
    k.own = {};
    k.stage = KrylovState::Stage::sum;
    krylov_advance();
    return;
  }
  k.vertex.begin(h_, star(radius_.get() + (step_ & 1) * deg_));
  k.trial = false;
  krylov_exchange();
}

void PackingAgent::krylov_exchange() {
  KrylovState& k = *krylov_;
  k.stage = KrylovState::Stage::exchange;
  encode(KrylovValueMsg{k.seq, k.vertex.value()}, buffer());
  for (std::size_t i = 0; i < deg_; ++i)
    if (interior_nbr(i)) send_encoded(i);
  krylov_advance();
}

void PackingAgent::krylov_advance() {
  KrylovState& k = *krylov_;
  if (k.stage == KrylovState::Stage::exchange) {
    for (std::size_t i = 0; i < deg_; ++i) {
      if (!interior_nbr(i)) {
        k.neighbour[i] = k.trial ? std::numeric_limits<double>::infinity() : 0.0;
        continue;
      }
      const KrylovState::Slot& v = k.value[i][k.seq & 1];
      if (v.tag != k.seq) return;
      k.neighbour[i] = v.h;
    }
    k.own = k.trial ? k.vertex.trial_sums(star(k.neighbour.data())) : k.vertex.cg_sums(k.neighbour);
    k.stage = KrylovState::Stage::sum;
  }
  if (k.stage != KrylovState::Stage::sum) return;
  for (std::size_t i = 0; i < deg_; ++i)
    if (peers_[i].child && k.sum_tag[i] != k.seq) return;
  core::KrylovSums total = k.own;
  for (std::size_t i = 0; i < deg_; ++i)
    if (peers_[i].child) core::combine(total, k.sum[i]);
  k.stage = KrylovState::Stage::decision;
  if (!is_root_) {
    send(parent_index_, KrylovSumMsg{k.seq, total.sum[0], total.sum[1], total.sum[2], total.max});
    return;
  }
  const core::KrylovDecision d = k.root.decide(total);
  krylov_apply(KrylovDecisionMsg{k.seq, static_cast<std::uint8_t>(d.action), d.a, d.b});
}

void PackingAgent::krylov_apply(const KrylovDecisionMsg& m) {
  KrylovState& k = *krylov_;
  ++k.seq;
  encode(m, buffer());
  for (std::size_t i = 0; i < deg_; ++i)
    if (peers_[i].child) send_encoded(i);
  const core::KrylovDecision d{static_cast<core::KrylovAction>(m.action), m.a, m.b};
  const bool done = d.action == core::KrylovAction::accept || d.action == core::KrylovAction::reject;
  if (boundary_) {
    k.own = {};
    k.stage = done ? KrylovState::Stage::idle : KrylovState::Stage::sum;
    if (!done) krylov_advance();
    else if (--k.steps_left > 0) krylov_begin_step();
    return;
  }
  // On rejection the plain Jacobi update of this step, from the star of the radius exchange.
  const double plain = d.action == core::KrylovAction::reject
                           ? core::star_updated_radius(h_, star(radius_.get() + (step_ & 1) * deg_), params_.update)
                           : h_;
  const double h = k.vertex.apply(d, plain);
  switch (d.action) {
    case core::KrylovAction::iterate:
    case core::KrylovAction::trial:
      k.trial = d.action == core::KrylovAction::trial;
      krylov_exchange();
      return;
    case core::KrylovAction::solved:
      k.own = k.vertex.direction_sums();
      k.stage = KrylovState::Stage::sum;
      krylov_advance();
      return;
    case core::KrylovAction::accept:
    case core::KrylovAction::reject:
      h_ = h;
      k.stage = KrylovState::Stage::idle;
      ++step_;
      sent_step_ = false;
      advance_steps();
      return;
  }
}

void PackingAgent::handle(std::size_t i, const KrylovValueMsg& m) {
  if (!krylov_ || phase_ != PackingPhase::rounds || boundary_ || !interior_nbr(i) ||
      (m.seq != krylov_->seq && m.seq != krylov_->seq + 1)) {
    ++counters().unexpected;
    return;
  }
  krylov_->value[i][m.seq & 1] = KrylovState::Slot{m.seq, m.value};
  if (krylov_->stage == KrylovState::Stage::exchange) krylov_advance();
}

void PackingAgent::handle(std::size_t i, const KrylovSumMsg& m) {
  if (!krylov_ || phase_ != PackingPhase::rounds || !peers_[i].child || m.seq != krylov_->seq || krylov_->sum_tag[i] == m.seq) {
    ++counters().unexpected;
    return;
  }
  krylov_->sum_tag[i] = m.seq;
  krylov_->sum[i] = core::KrylovSums{{m.s0, m.s1, m.s2}, m.max};
  if (krylov_->stage == KrylovState::Stage::sum) krylov_advance();
}

void PackingAgent::handle(std::size_t i, const KrylovDecisionMsg& m) {
  if (!krylov_ || phase_ != PackingPhase::rounds || is_root_ || i != parent_index_ ||
      krylov_->stage != KrylovState::Stage::decision || m.seq != krylov_->seq) {
    ++counters().unexpected;
    return;
  }
  krylov_apply(m);
}

void PackingAgent::handle(std::size_t i, const PlacedMsg& m) {
  if (m.round != round_ && m.round != round_ + 1) {
    ++counters().unexpected;
    return;
  }
  const std::size_t slot = m.round & 1;
  peers_[i].placed_tag[slot] = m.round;
  peers_[i].circle[slot] = {m.cx, m.cy, m.cr};
  // What placing needs of the anchors (known since the set-up, which every node ends before any
  // round starts).
  if (wave_ != unknown && !is_root_) {
    const AnchorSlot a{m.round, m.h, {m.centre_re, m.centre_im}};
    if (is_first_) {
      if (i == parent_index_) anchors_[0][slot] = a;
    } else {
      if (i == anchor_a_) anchors_[0][slot] = a;
      if (i == anchor_b_) anchors_[1][slot] = a;
    }
  }
  if (params_.asynchronous && interior_nbr(i)) {
    // The sender's X after its last update of round m.round: version min(round·N, cap).
    const auto version = static_cast<std::uint32_t>(std::min<std::uint64_t>(
        std::uint64_t{m.round} * static_cast<std::uint64_t>(params_.steps_per_check),
        static_cast<std::uint64_t>(params_.max_iterations)));
    if (version > peers_[i].latest_step) {
      peers_[i].latest_step = version;
      radius_[i] = m.h;
    }
  }
  if (phase_ == PackingPhase::rounds) advance_layout();
}

void PackingAgent::handle(std::size_t i, const FaceCirclesMsg& m) {
  // Only from a face vertex, with one circle per member of its face (its degree is not known here:
  // the size is checked against the walk when used), at most one round ahead.
  if (!peers_[i].face || is_face_ || (m.round != round_ && m.round != round_ + 1)) {
    ++counters().unexpected;
    return;
  }
  FaceSlot& s = poly_->face_in[i][m.round & 1];
  s.tag = m.round;
  s.circles.clear();
  for (const FaceCircle& c : m.circles) s.circles.push_back({c.x, c.y, c.r});
  if (phase_ == PackingPhase::rounds) advance_layout();
}

void PackingAgent::advance_layout() {
  if (step_ < round_end_step_ || phase_ != PackingPhase::rounds || (radius_only_ && !layout_round_)) return;
  const std::size_t slot = round_ & 1;
  auto heard = [&](std::size_t i) { return peers_[i].placed_tag[slot] == round_; };
  auto anchor_heard = [&](std::size_t k) { return anchors_[k][slot].tag == round_; };
  if (!placed_this_round_) {
    const core::LayoutVertex me{h_, !boundary_};
    if (is_root_) {
      placed_ = core::place_root(h_);
    } else if (is_first_) {
      if (!anchor_heard(0)) return;
      placed_ = core::place_first_neighbour(anchors_[0][slot].h, me, polygon_ ? cos_spoke(parent_index_) : 1.0);
    } else {
      if (!anchor_heard(0) || !anchor_heard(1)) return;
      const AnchorSlot& a = anchors_[0][slot];
      const AnchorSlot& b = anchors_[1][slot];
      const core::PlacedCircle a_at{a.centre, peers_[anchor_a_].circle[slot]};
      const core::PlacedCircle b_at{b.centre, peers_[anchor_b_].circle[slot]};
      // lay_out's cosines: 1 everywhere for a triangulation, else those of K, with the overlap formula.
      const core::FaceCosines c = polygon_ ? core::FaceCosines{cos_spoke(anchor_a_), cos_spoke(anchor_b_), cos_rim(anchor_a_), true}
                                           : core::FaceCosines{};
      placed_ = core::place_in_face(me, {a.h, interior_nbr(anchor_a_)}, a_at, {b.h, interior_nbr(anchor_b_)}, b_at, c);
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
  if (is_face_) {
    // core checks G only: a face vertex's part is to hand its members the circles of the face.
    FaceCirclesMsg fc;
    fc.round = round_;
    for (std::size_t i = 0; i < deg_; ++i) {
      const core::Circle& c = peers_[i].circle[slot];
      fc.circles.push_back({c.x, c.y, c.r});
    }
    broadcast(fc);
    local_ = core::LocalCondition::holds;
    return true;
  }
  if (!polygon_) {
    // LPD lists a boundary vertex's neighbours from w1, just after the outer wedge (lpd_first_dart).
    const std::size_t start = boundary_ ? (outer_gap_ + 1) % deg_ : 0;
    constexpr std::size_t on_stack = 32;  // no allocation for the usual degrees
    std::array<core::Circle, on_stack> stack;
    std::vector<core::Circle> heap(deg_ > on_stack ? deg_ : 0);
    const std::span<core::Circle> circles = deg_ > on_stack ? std::span<core::Circle>(heap) : std::span<core::Circle>(stack.data(), deg_);
    for (std::size_t j = 0; j < deg_; ++j) circles[j] = peers_[(start + j) % deg_].circle[slot];
    local_ = core::check_lpd_at(placed_.circle, circles, boundary_);
    return true;
  }
  // GLPD (core::check_all's choice when some inner face is not a triangle), from the circles of the
  // G-neighbours and, per polygon face, the face vertex's FaceCirclesMsg of this round.
  const std::size_t gdeg = g_degree();
  auto g_face = [&](std::size_t i) -> const std::vector<NodeId>* { return poly_ ? poly_->g_face[i] : nullptr; };
  for (std::size_t i = 0; i < gdeg; ++i)
    if (g_face(i) != nullptr) {
      const FaceSlot& s = poly_->face_in[k_of_g(i) + 1][slot];
      if (s.tag != round_) return false;
      if (s.circles.size() != g_face(i)->size()) {
        ++counters().unexpected;
        return false;  // a malformed face message: never decide on it
      }
    }
  std::vector<core::Circle> nb(gdeg);
  std::vector<std::uint64_t> nid(gdeg);
  for (std::size_t i = 0; i < gdeg; ++i) {
    nb[i] = peers_[k_of_g(i)].circle[slot];
    nid[i] = peers_[k_of_g(i)].id;
  }
  std::vector<std::vector<core::Circle>> fc(gdeg);
  std::vector<std::vector<std::uint64_t>> fid(gdeg);
  std::vector<GlpdWedge> wedges(gdeg);
  for (std::size_t i = 0; i < gdeg; ++i) {
    const std::size_t j = i + 1 == gdeg ? 0 : i + 1;
    if (boundary_ && i == g_outer_gap_) {
      wedges[i].outer = true;
      continue;
    }
    if (const std::vector<NodeId>* walk = g_face(i)) {
      // Rotate the host-ordered circles to start at this vertex: walk[p] is the host.
      const std::size_t m = walk->size();
      const std::size_t p = static_cast<std::size_t>(std::min_element(walk->begin(), walk->end()) - walk->begin());
      const FaceSlot& s = poly_->face_in[k_of_g(i) + 1][slot];
      for (std::size_t k = 0; k < m; ++k) {
        fc[i].push_back(s.circles[(k + m - p) % m]);
        fid[i].push_back((*walk)[k]);
      }
    } else {
      fc[i] = {placed_.circle, nb[i], nb[j]};
      fid[i] = {id_, nid[i], nid[j]};
    }
    wedges[i].circles = fc[i];
    wedges[i].ids = fid[i];
  }
  local_ = check_glpd_local(placed_.circle, id_, nb, nid, boundary_, g_outer_gap_, wedges);
  return true;
}

void PackingAgent::handle(std::size_t i, const ReportMsg& m) {
  if (phase_ != PackingPhase::rounds || !peers_[i].child || m.round != round_) {
    ++counters().unexpected;
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
    ++counters().unexpected;
    return;
  }
  apply_decision(m.verdict);
}

void PackingAgent::apply_decision(Verdict v) {
  encode(DecisionMsg{round_, v}, buffer());
  for (std::size_t i = 0; i < deg_; ++i)
    if (peers_[i].child) send_encoded(i);
  if (v == Verdict::layout) {  // the same round, laid out and checked exactly
    layout_round_ = true;
    checked_this_round_ = false;
    reported_ = false;
    reports_ = 0;
    reports_ok_ = true;
    advance_layout();
    return;
  }
  if (v == Verdict::next && flood_) {
    layout_round_ = false;
    ++round_;
    flood_resume();
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
  if (flood_) step_ = flood_->layout_step;  // the radii laid out and checked are those of that step
  outcome_ = v == Verdict::converged ? PackingOutcome::converged : PackingOutcome::cap;
}

}  // namespace laguerre::protocols::detail
