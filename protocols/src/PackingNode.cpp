#include "laguerre/protocols/PackingNode.hpp"

#include <algorithm>
#include <deque>
#include <stdexcept>
#include <string>

#include "PackingAgent.hpp"

namespace laguerre::protocols {

LocalKnowledge local_knowledge(const core::PlanarGraph& g, core::Vertex v) {
  LocalKnowledge k;
  k.id = g.id(v);
  k.boundary = g.is_boundary(v);
  const core::Dart first = g.first_dart(v);
  const bool triangulated = g.inner_faces_are_triangles();
  for (std::uint32_t i = 0; i < g.degree(v); ++i) {
    const core::Dart d = first + i;
    k.neighbours.push_back(g.id(g.head(d)));
    // Wedge i (neighbour i to neighbour i+1, counter-clockwise) is the face left of dart v→neighbour i.
    if (k.boundary && k.outer_gap == LocalKnowledge::no_gap && g.face_of(d) == g.outer_face()) k.outer_gap = i;
    if (triangulated) continue;
    std::vector<NodeId> walk;
    const core::Face f = g.face_of(d);
    if (f != g.outer_face() && g.face_size(f) > 3) {
      core::Dart e = d;
      do {
        walk.push_back(g.id(g.tail(e)));
        e = g.next_in_face(e);
      } while (e != d);
    }
    k.faces.push_back(std::move(walk));
  }
  if (!triangulated) {  // keep `faces` empty unless some face at v is a polygon
    bool any = false;
    for (const auto& w : k.faces) any = any || !w.empty();
    if (!any) k.faces.clear();
  }
  return k;
}

void enable_lossy_links(PackingParams& params, Duration max_latency) {
  const Duration l = std::max<Duration>(max_latency, 1);
  params.ack_delay = l / 2;
  params.retransmit_after = 3 * l;
}

// ---- Private state ----------------------------------------------------------------------------------

struct PackingNode::Wedge {
  std::vector<NodeId> walk;  // from this node, counter-clockwise
  NodeId face_id = 0;        // face_vertex_id of the face
  NodeId host = 0;           // smallest id on the face
  std::size_t agent = 0;     // index in agents_ if hosted here, else 0
};

// The reliability layer's state for one G-neighbour (docs/protocol.md, "Loss, duplication and crashes").
struct PackingNode::Link {
  struct Pending {  // a frame not yet acknowledged
    std::uint32_t seq = 0;
    std::vector<std::byte> payload;
    Time sent_at = 0;            // first transmission
    bool retransmitted = false;  // Karn: no RTT sample from it
  };
  std::uint32_t next_seq = 0;  // next sequence number to send
  std::deque<Pending> unacked;  // by seq
  TimerHandle retransmit_timer = 0;
  Duration period = 0;  // current retransmission period
  Duration rto = 0;     // current timeout (backoff resets to it)
  Duration srtt = 0;    // smoothed round trip (ns)
  Duration rttvar = 0;  // its mean deviation (ns)
  bool has_rtt = false;  // a sample was taken
  int attempts = 0;      // retransmissions since progress
  AckInfo received;      // what we have of the reverse link
  bool ack_pending = false;
  TimerHandle ack_timer = 0;
  Time last_heard = 0;
  bool dead = false;
};

struct PackingNode::Local {
  std::size_t agent;
  std::size_t from_index;
  std::vector<std::byte> bytes;
};

namespace {
// Timer ids: kind in the top byte, G-neighbour index below.
constexpr TimerId timer_retransmit = TimerId{1} << 56;
constexpr TimerId timer_ack = TimerId{2} << 56;
constexpr TimerId timer_probe = TimerId{3} << 56;
constexpr TimerId timer_kind = TimerId{0xff} << 56;

/// Serial-number order of 32-bit sequence numbers (RFC 1982): a is before b iff b − a, taken mod 2^32,
/// lies in [1, 2^31).
bool seq_before(std::uint32_t a, std::uint32_t b) { return a != b && static_cast<std::uint32_t>(b - a) < (1u << 31); }
}  // namespace

PackingNode::PackingNode(Runtime& runtime, LocalKnowledge knowledge, PackingParams params)
    : rt_(runtime), params_(params), know_(std::move(knowledge)), deg_(know_.neighbours.size()) {
  const std::string who = "Node " + std::to_string(know_.id);
  if (deg_ == 0) throw std::invalid_argument(who + " has no neighbours.");
  if (deg_ >= 0xffffffffu) throw std::invalid_argument(who + " has too many neighbours.");
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
  if (params.steps_per_check < 1) throw std::invalid_argument("steps_per_check must be at least 1.");
  if (params.max_iterations < 0) throw std::invalid_argument("max_iterations must not be negative.");
  if (params.retransmit_after < 0 || params.ack_delay < 0 || params.probe_after < 0)
    throw std::invalid_argument("retransmit_after, ack_delay and probe_after must not be negative.");
  if (params.backoff_cap < 1 || params.max_retransmissions < 1)
    throw std::invalid_argument("backoff_cap and max_retransmissions must be at least 1.");
  if (params.rto_min < 0) throw std::invalid_argument("rto_min must not be negative.");
  if (lossy()) {
    if (params_.probe_after == 0) params_.probe_after = 32 * params_.retransmit_after;
    if (params_.rto_min == 0) params_.rto_min = std::max<Duration>(1, params_.retransmit_after / 4);
    links_.assign(deg_, Link{});
    for (Link& l : links_) {
      l.period = l.rto = params_.retransmit_after;
      l.next_seq = params_.initial_seq;
      l.received.next = params_.initial_seq;
    }
  }
  if (!know_.faces.empty() && know_.faces.size() != deg_)
    throw std::invalid_argument(who + " lists faces for some but not all of its wedges.");

  // The star of this node's vertex in K: a face vertex right after neighbour i for each polygon wedge.
  detail::AgentSpec own;
  own.id = know_.id;
  own.boundary = know_.boundary;
  own.g_outer_gap = know_.outer_gap;
  for (std::size_t i = 0; i < deg_; ++i) {
    if (know_.boundary && i == know_.outer_gap) own.outer_gap = static_cast<std::uint32_t>(own.neighbours.size());
    own.g_k.push_back(static_cast<std::uint32_t>(own.neighbours.size()));
    own.neighbours.push_back(know_.neighbours[i]);
    own.face_nbr.push_back(0);
    own.g_face.push_back(nullptr);
    if (know_.faces.empty() || know_.faces[i].empty()) continue;
    const std::vector<NodeId>& walk = know_.faces[i];
    const std::size_t next = i + 1 == deg_ ? 0 : i + 1;
    if (walk.size() < 4 || walk[0] != know_.id || walk[1] != know_.neighbours[i] || walk.back() != know_.neighbours[next])
      throw std::invalid_argument(who + "'s face walk for wedge " + std::to_string(i) +
                                  " does not run from it through its neighbours around that wedge.");
    for (NodeId u : walk)
      if (u > max_face_node_id)
        throw std::invalid_argument(who + " is on a polygon face with node id " + std::to_string(u) +
                                    ", above the largest id the 3-connected mode supports (2^31 − 1).");
    if (know_.boundary && i == know_.outer_gap) throw std::invalid_argument(who + " lists a face for its outer wedge.");
    Wedge w;
    w.walk = walk;
    const auto host = std::min_element(walk.begin(), walk.end());
    w.host = *host;
    w.face_id = face_vertex_id(w.host, host + 1 == walk.end() ? walk.front() : *(host + 1));
    wedges_.push_back(std::move(w));
    own.neighbours.push_back(wedges_.back().face_id);
    own.face_nbr.push_back(1);
    own.polygon_here = true;
  }
  // g_face points into wedges_, which no longer grows.
  for (std::size_t i = 0, k = 0; i < deg_; ++i)
    if (!know_.faces.empty() && !know_.faces[i].empty()) own.g_face[i] = &wedges_[k++].walk;

  host_ = std::make_unique<detail::AgentHost>(*this);
  agents_.push_back(std::make_unique<detail::PackingAgent>(*host_, 0, std::move(own), params));
  // Hosted face vertices: neighbours = the face's walk from the host (docs/protocol.md, "Face vertices").
  for (Wedge& w : wedges_) {
    if (w.host != know_.id) continue;
    detail::AgentSpec fs;
    fs.id = w.face_id;
    fs.is_face = true;
    fs.polygon_here = true;
    fs.neighbours = w.walk;
    fs.face_nbr.assign(w.walk.size(), 0);
    w.agent = agents_.size();
    agents_.push_back(std::make_unique<detail::PackingAgent>(*host_, w.agent, std::move(fs), params));
  }
}

PackingNode::~PackingNode() = default;

std::size_t PackingNode::index_of(NodeId id) const {
  const auto it = std::lower_bound(sorted_ids_.begin(), sorted_ids_.end(), std::make_pair(id, std::uint32_t{0}));
  return it != sorted_ids_.end() && it->first == id ? it->second : deg_;
}

const PackingNode::Wedge* PackingNode::wedge_of_face(NodeId face_id) const {
  for (const Wedge& w : wedges_)
    if (w.face_id == face_id) return &w;
  return nullptr;
}

void PackingNode::agent_send(std::size_t agent, std::size_t k_index, std::span<const std::byte> bytes) {
  const detail::AgentSpec& s = agents_[agent]->spec();
  const NodeId to = s.neighbours[k_index];
  if (agent == 0 && !s.face_nbr[k_index]) {  // an edge of G: a plain message
    transmit(index_of(to), bytes);
    return;
  }
  const NodeId face = agent == 0 ? to : s.id;
  const Wedge& w = *wedge_of_face(face);
  const NodeId target_node = agent == 0 ? w.host : to;
  if (target_node == know_.id) {  // between this node's own vertex and a face vertex it hosts
    const std::size_t target_agent = agent == 0 ? w.agent : 0;
    const auto& tn = agents_[target_agent]->spec().neighbours;
    const auto from = static_cast<std::size_t>(std::find(tn.begin(), tn.end(), s.id) - tn.begin());
    local_.push_back({target_agent, from, {bytes.begin(), bytes.end()}});
    return;
  }
  send_relay(w, s.id, to, bytes);
}

void PackingNode::send_relay(const Wedge& w, NodeId source, NodeId target, std::span<const std::byte> payload) {
  // The target node (the face's host when the target is the face vertex) sits at position p of the
  // walk from here; go the shorter way round: forward p hops, or backward m − p.
  const NodeId node = target == w.face_id ? w.host : target;
  const std::size_t m = w.walk.size();
  const auto p = static_cast<std::size_t>(std::find(w.walk.begin(), w.walk.end(), node) - w.walk.begin());
  const bool backward = p > m - p;
  RelayMsg r{w.face_id, source, target, backward, {payload.begin(), payload.end()}};
  encode(r, relay_buffer_);
  transmit(index_of(backward ? w.walk.back() : w.walk[1]), relay_buffer_);
}

void PackingNode::handle_relay(std::size_t from, RelayMsg& m) {
  // Accept only an envelope for one of our faces, arriving from the neighbour that precedes us in its
  // direction of travel, between the face vertex and a member of the face: then it reaches its target
  // within |f| − 1 hops and can never circle the face.
  const Wedge* w = wedge_of_face(m.face);
  const NodeId member = m.source == m.face ? m.target : m.source;
  if (w == nullptr || know_.neighbours[from] != (m.backward ? w->walk[1] : w->walk.back()) ||
      std::find(w->walk.begin(), w->walk.end(), member) == w->walk.end()) {
    ++counters_.unexpected;
    return;
  }
  const NodeId node = m.target == m.face ? w->host : m.target;
  if (node != know_.id) {
    ++counters_.relayed;
    encode(m, relay_buffer_);
    transmit(index_of(m.backward ? w->walk.back() : w->walk[1]), relay_buffer_);
    return;
  }
  const std::size_t agent = m.target == m.face ? w->agent : 0;
  const auto& nb = agents_[agent]->spec().neighbours;
  const auto i = static_cast<std::size_t>(std::find(nb.begin(), nb.end(), m.source) - nb.begin());
  if (i == nb.size()) {
    ++counters_.unexpected;
    return;
  }
  deliver_payload(agent, i, m.payload);
}

void PackingNode::deliver_payload(std::size_t agent, std::size_t from_index, std::span<const std::byte> bytes) {
  PackingMessage m;  // envelopes never nest
  if (decode(bytes, m) != DecodeStatus::ok) {
    ++counters_.bad_payload;
    return;
  }
  agents_[agent]->receive(from_index, m);
}

void PackingNode::handle_hop(std::size_t from, PackingHop& m) {
  // A plain message comes from G-neighbour `from`, which is K-neighbour g_k[from] of the own vertex.
  if (auto* r = std::get_if<RelayMsg>(&m)) handle_relay(from, *r);
  else agents_[0]->receive(agents_[0]->spec().g_k[from], std::get<PackingMessage>(m));
}

void PackingNode::drain() {
  // Local deliveries between this node's agents, after the callback that produced them (never
  // re-entrant); they may produce more, delivered in turn. An abandoned run delivers nothing more.
  if (failed_) local_.clear();
  for (std::size_t next = 0; next < local_.size(); ++next) {
    Local l = std::move(local_[next]);  // receive() may append to local_
    PackingMessage m;
    if (decode(l.bytes, m) != DecodeStatus::ok) continue;  // our own encoding: cannot happen
    agents_[l.agent]->receive(l.from_index, m);
  }
  local_.clear();
  if (finished_at_ < 0 && is_final()) finished_at_ = rt_.now();
}

void PackingNode::on_start() {
  for (auto& a : agents_) a->start();
  drain();
  if (lossy()) probe_timer_ = rt_.schedule(params_.probe_after, timer_probe);
}

void PackingNode::on_timer(TimerId timer) {
  const std::size_t i = static_cast<std::size_t>(timer & ~timer_kind);
  const TimerId kind = timer & timer_kind;
  if (!lossy() || (kind != timer_probe && i >= deg_)) {
    ++counters_.unexpected;
    return;
  }
  if (kind == timer_retransmit) {
    links_[i].retransmit_timer = 0;
    on_retransmit(i);
  } else if (kind == timer_ack) {
    links_[i].ack_timer = 0;
    if (links_[i].ack_pending && !links_[i].dead) {
      links_[i].ack_pending = false;
      encode(AckMsg{links_[i].received}, frame_buffer_);
      raw_send(know_.neighbours[i], frame_buffer_);
      ++counters_.acks;
    }
  } else if (kind == timer_probe) {
    probe_timer_ = 0;
    on_probe();
  } else {
    ++counters_.unexpected;
  }
  drain();
}

void PackingNode::on_recover() {
  if (!lossy()) return;  // reliable links: nothing was armed
  // Timers that fell in the outage are gone; those due later are still live. Cancel-then-schedule
  // is right in both cases (cancelling a dead handle is a no-op).
  for (std::size_t i = 0; i < deg_; ++i) {
    Link& l = links_[i];
    if (l.dead) continue;
    if (!l.unacked.empty()) arm_retransmit(i);
    if (l.ack_timer != 0) rt_.cancel(l.ack_timer);
    l.ack_timer = 0;
    if (l.ack_pending) ack_owed_.push_back(i);
  }
  if (probe_timer_ != 0) rt_.cancel(probe_timer_);
  probe_timer_ = is_final() ? 0 : rt_.schedule(params_.probe_after, timer_probe);
  flush_acks();
}

// ---- The reliability layer (lossy mode; docs/protocol.md, "Loss, duplication and crashes") ----------

void PackingNode::raw_send(NodeId to, std::span<const std::byte> bytes) {
  rt_.send(to, bytes);
  ++counters_.sent;
  counters_.bytes_sent += bytes.size();
}

void PackingNode::transmit(std::size_t i, std::span<const std::byte> bytes) {
  if (!lossy()) {
    raw_send(know_.neighbours[i], bytes);
    return;
  }
  send_frame(i, bytes);
}

void PackingNode::send_frame(std::size_t i, std::span<const std::byte> payload) {
  Link& l = links_[i];
  if (l.dead) return;  // its neighbour is suspected: the run is ending anyway
  const std::uint32_t seq = l.next_seq++;
  l.unacked.push_back({seq, std::vector<std::byte>(payload.begin(), payload.end()), rt_.now(), false});
  ++counters_.frames;
  put_frame(i, seq, payload);
  if (l.retransmit_timer == 0) arm_retransmit(i);
}

void PackingNode::put_frame(std::size_t i, std::uint32_t seq, std::span<const std::byte> payload) {
  Link& l = links_[i];
  // The frame carries our acknowledgement of the reverse link: no standalone ack is owed any more.
  FrameMsg f{seq, l.received, {payload.begin(), payload.end()}};
  encode(f, frame_buffer_);
  raw_send(know_.neighbours[i], frame_buffer_);
  l.ack_pending = false;
  if (l.ack_timer != 0) {
    rt_.cancel(l.ack_timer);
    l.ack_timer = 0;
  }
}

void PackingNode::arm_retransmit(std::size_t i) {
  Link& l = links_[i];
  if (l.retransmit_timer != 0) rt_.cancel(l.retransmit_timer);
  l.retransmit_timer = rt_.schedule(l.period, timer_retransmit | i);
}

void PackingNode::on_retransmit(std::size_t i) {
  Link& l = links_[i];
  if (l.dead || l.unacked.empty()) return;
  if (l.attempts >= params_.max_retransmissions) {
    give_up(i);
    return;
  }
  ++l.attempts;
  for (Link::Pending& p : l.unacked) {
    put_frame(i, p.seq, p.payload);
    p.retransmitted = true;
    ++counters_.retransmissions;
  }
  l.period = std::min(2 * l.period, params_.backoff_cap * params_.retransmit_after);
  arm_retransmit(i);
}

void PackingNode::handle_ack(std::size_t i, const AckInfo& a) {
  // Drop every frame the neighbour proves it has: below a.next, or flagged in the bitmap above it.
  Link& l = links_[i];
  const std::size_t before = l.unacked.size();
  bool timed = false;  // Karn: the newest newly acknowledged frame sent only once gives the sample
  Time timed_at = 0;
  std::erase_if(l.unacked, [&](const Link::Pending& e) {
    const std::uint32_t k = e.seq - a.next;  // mod 2^32
    const bool acked = seq_before(e.seq, a.next) || (k >= 1 && k <= 64 && ((a.bits >> (k - 1)) & 1u) != 0);
    if (acked && !e.retransmitted && (!timed || e.sent_at > timed_at)) {
      timed = true;
      timed_at = e.sent_at;
    }
    return acked;
  });
  if (l.unacked.size() == before) return;
  if (timed && params_.adaptive_rto) sample_rtt(l, rt_.now() - timed_at);
  // Progress: the link is alive; start the backoff again (or stop the timer if nothing is left).
  l.attempts = 0;
  l.period = l.rto;
  if (l.unacked.empty()) {
    if (l.retransmit_timer != 0) rt_.cancel(l.retransmit_timer);
    l.retransmit_timer = 0;
  } else {
    arm_retransmit(i);
  }
}

void PackingNode::sample_rtt(Link& l, Duration r) {
  // Jacobson/Karels in integer nanoseconds (docs/protocol.md, "Adaptive timeout").
  r = std::max<Duration>(r, 0);
  if (!l.has_rtt) {
    l.srtt = r;
    l.rttvar = r / 2;
    l.has_rtt = true;
  } else {
    const Duration err = l.srtt > r ? l.srtt - r : r - l.srtt;
    l.rttvar = (3 * l.rttvar + err) / 4;
    l.srtt = (7 * l.srtt + r) / 8;
  }
  l.rto = std::clamp<Duration>(l.srtt + 4 * l.rttvar, params_.rto_min,
                               std::max<Duration>(params_.rto_min, params_.backoff_cap * params_.retransmit_after));
}

void PackingNode::handle_frame(std::size_t i, FrameMsg& f) {
  Link& l = links_[i];
  handle_ack(i, f.ack);
  // Every copy re-arms our ack: if the copy is a retransmission, our earlier ack was lost.
  if (!l.ack_pending) {
    l.ack_pending = true;
    ack_owed_.push_back(i);
  }
  AckInfo& r = l.received;
  bool fresh = false;
  if (f.seq == r.next) {
    // Advance past every sequence number already held (bit k ↔ r.next + 1 + k).
    fresh = true;
    for (;;) {
      ++r.next;
      const bool have = (r.bits & 1u) != 0;
      r.bits >>= 1;
      if (!have) break;
    }
  } else if (seq_before(r.next, f.seq)) {
    const std::uint32_t k = f.seq - r.next - 1;  // mod 2^32
    if (k >= 64) {
      ++counters_.out_of_window;
      return;
    }
    fresh = ((r.bits >> k) & 1u) == 0;
    r.bits |= std::uint64_t{1} << k;
  }
  if (!fresh) {
    ++counters_.duplicates;
    return;
  }
  deliver_frame_payload(i, f.payload);
}

void PackingNode::deliver_frame_payload(std::size_t i, std::span<const std::byte> payload) {
  if (payload.empty()) return;  // a probe: its only purpose was the ack
  FramePayload m;  // frames never nest
  if (decode(payload, m) != DecodeStatus::ok) {
    ++counters_.bad_payload;
    return;
  }
  if (const auto* fail = std::get_if<FailureMsg>(&m)) {
    declare_failure(fail->suspect, i);
    return;
  }
  if (failed_) return;  // the run is abandoned: the protocol does not run any more
  handle_hop(i, std::get<PackingHop>(m));
}

void PackingNode::flush_acks() {
  // After a callback: acks still owed (no frame to that neighbour carried them) go alone, at once or
  // after ack_delay in case a frame leaves first.
  for (std::size_t i : ack_owed_) {
    Link& l = links_[i];
    if (!l.ack_pending || l.dead) continue;
    if (params_.ack_delay == 0) {
      l.ack_pending = false;
      encode(AckMsg{l.received}, frame_buffer_);
      raw_send(know_.neighbours[i], frame_buffer_);
      ++counters_.acks;
    } else if (l.ack_timer == 0) {
      l.ack_timer = rt_.schedule(params_.ack_delay, timer_ack | i);
    }
  }
  ack_owed_.clear();
}

void PackingNode::on_probe() {
  if (is_final()) return;  // a finished node no longer probes: the queue may drain
  const Time now = rt_.now();
  for (std::size_t i = 0; i < deg_; ++i) {
    Link& l = links_[i];
    if (l.dead || !l.unacked.empty() || now - l.last_heard < params_.probe_after) continue;
    ++counters_.probes;
    send_frame(i, {});
  }
  probe_timer_ = rt_.schedule(params_.probe_after, timer_probe);
}

void PackingNode::give_up(std::size_t i) {
  Link& l = links_[i];
  l.dead = true;
  l.unacked.clear();
  l.ack_pending = false;
  if (l.ack_timer != 0) rt_.cancel(l.ack_timer);
  l.ack_timer = 0;
  ++counters_.links_failed;
  declare_failure(know_.neighbours[i], deg_);
}

void PackingNode::declare_failure(NodeId suspect, std::size_t except) {
  if (failed_) return;  // the notice already went out from here: the flood stops
  failed_ = true;
  suspect_ = suspect;
  if (probe_timer_ != 0) rt_.cancel(probe_timer_);
  probe_timer_ = 0;
  const std::vector<std::byte> notice = encode(FailureMsg{suspect});
  for (std::size_t j = 0; j < deg_; ++j)
    if (j != except) send_frame(j, notice);
}

bool PackingNode::is_final() const { return failed_ || agents_[0]->phase() == PackingPhase::finished; }

void PackingNode::on_message(NodeId from, std::span<const std::byte> bytes) {
  ++counters_.received;
  const std::size_t i = index_of(from);
  if (i == deg_) {
    ++counters_.not_a_neighbour;
    return;
  }
  if (lossy()) {
    LinkMessage m;  // on lossy links everything travels in frames
    const DecodeStatus s = decode(bytes, m);
    ++counters_.decode[static_cast<std::size_t>(s)];
    if (s != DecodeStatus::ok) return;
    links_[i].last_heard = rt_.now();
    if (auto* f = std::get_if<FrameMsg>(&m)) handle_frame(i, *f);
    else handle_ack(i, std::get<AckMsg>(m).ack);
    drain();
    flush_acks();
    return;
  }
  PackingHop m;
  const DecodeStatus s = decode(bytes, m);
  ++counters_.decode[static_cast<std::size_t>(s)];
  if (s == DecodeStatus::ok) handle_hop(i, m);
  drain();
}

Duration PackingNode::rto(std::size_t i) const { return i < links_.size() ? links_[i].rto : 0; }
PackingPhase PackingNode::phase() const { return agents_[0]->phase(); }
PackingOutcome PackingNode::outcome() const {
  return failed_ ? PackingOutcome::neighbour_failed : agents_[0]->outcome();
}
std::uint32_t PackingNode::depth() const { return agents_[0]->state().depth; }
bool PackingNode::is_root() const { return agents_[0]->state().is_root; }
std::uint32_t PackingNode::wave() const { return agents_[0]->state().wave; }
NodeId PackingNode::parent() const { return agents_[0]->state().parent; }
std::size_t PackingNode::children() const { return agents_[0]->children(); }
std::uint32_t PackingNode::steps() const { return agents_[0]->state().steps; }
std::uint32_t PackingNode::round() const { return agents_[0]->state().round; }
double PackingNode::h() const { return agents_[0]->state().h; }
const core::PlacedCircle& PackingNode::placement() const { return agents_[0]->placement(); }
core::LocalCondition PackingNode::local_condition() const { return agents_[0]->state().local; }
bool PackingNode::polygon_faces() const { return agents_[0]->polygon(); }
VertexState PackingNode::state() const { return agents_[0]->state(); }
std::vector<core::Circle> PackingNode::neighbour_circles() const {
  std::vector<core::Circle> out;
  for (std::uint32_t k : agents_[0]->spec().g_k) out.push_back(agents_[0]->neighbour_circle(k));
  return out;
}
VertexState PackingNode::hosted_face_state(std::size_t k) const { return agents_.at(k + 1)->state(); }
const std::vector<NodeId>& PackingNode::hosted_face_walk(std::size_t k) const { return agents_.at(k + 1)->spec().neighbours; }

}  // namespace laguerre::protocols
