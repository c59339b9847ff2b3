#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/core/Error.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "Neighbours.hpp"
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

core::PackOptions reference_options(const PackingParams& params) {
  core::PackOptions opt;
  opt.stop = core::StopRule::lpd;
  opt.sweep = core::Sweep::jacobi;
  opt.update = params.update;
  opt.root = params.root;
  opt.steps_per_check = params.steps_per_check;
  opt.max_iterations = params.max_iterations;
  opt.acceleration = params.acceleration;
  opt.termination = params.termination;
  opt.radius_only_gap = params.radius_only_gap;
  return opt;
}

void enable_lossy_links(PackingParams& params, Duration max_latency) {
  const ReliableParams r = lossy_link_params(max_latency);
  params.ack_delay = r.ack_delay;
  params.retransmit_after = r.retransmit_after;
}

// ---- Private state ----------------------------------------------------------------------------------

struct PackingNode::Wedge {
  std::vector<NodeId> walk;  // from this node, counter-clockwise
  NodeId face_id = 0;        // face_vertex_id of the face
  NodeId host = 0;           // smallest id on the face
  std::size_t agent = 0;     // index in agents_ if hosted here, else 0
};

// Its bytes are local_bytes_[offset, offset + size): one buffer for every pending local delivery,
// whose capacity is kept, so that local deliveries allocate nothing once it has grown.
struct PackingNode::Local {
  std::size_t agent;
  std::size_t from_index;
  std::size_t offset;
  std::size_t size;
};

// The protocol as seen by the reliability layer: its frames' payloads, its failure notification.
class PackingNode::Protocol final : public Node {
public:
  explicit Protocol(PackingNode& node) : node_(node) {}
  void on_start() override { node_.start(); }
  void on_message(NodeId from, std::span<const std::byte> bytes) override { node_.receive(from, bytes); }
  void on_timer(TimerId) override { ++node_.counters_.unexpected; }
  void on_failure(NodeId suspect) override { node_.on_failure(suspect); }
  bool is_final() const override { return node_.is_final(); }

private:
  PackingNode& node_;
};

PackingNode::PackingNode(Runtime& runtime, LocalKnowledge knowledge, PackingParams params)
    : rt_(&runtime), deg_(knowledge.neighbours.size()), know_(std::move(knowledge)), params_(params) {
  const std::string who = "Node " + std::to_string(know_.id);
  // Checks the list (throws); kept for the lookup only at high degrees, where a scan would be slow.
  sorted_ids_ = detail::sorted_neighbours(know_.id, know_.neighbours);
  if (deg_ < sorted_from) sorted_ids_ = {};
  if (know_.boundary && know_.outer_gap >= deg_)
    throw core::InternalError(who + " is on the boundary but its outer-face wedge is not one of its wedges.");
  if (!know_.boundary && know_.outer_gap != LocalKnowledge::no_gap)
    throw core::InternalError(who + " is interior but has an outer-face wedge.");
  if (params.steps_per_check < 1) throw core::InternalError("steps_per_check must be at least 1.");
  if (params.max_iterations < 0) throw core::InternalError("max_iterations must not be negative.");
  if (!core::runs_in_network(params.acceleration))
    throw core::InternalError("the packing protocol runs plain, local accelerations or newton-krylov only.");
  if (params.asynchronous && params.acceleration != core::Acceleration::plain)
    throw core::InternalError("the accelerations run in synchronous mode only.");
  if (params.termination != core::Termination::layout &&
      (params.asynchronous || !(params.radius_only_gap > 0) || params.acceleration == core::Acceleration::newton_krylov))
    throw core::InternalError("radius-only termination runs in synchronous mode with a positive gap, and not with newton-krylov.");
  validate(params);
  if (!know_.faces.empty() && know_.faces.size() != deg_)
    throw core::InternalError(who + " lists faces for some but not all of its wedges.");

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
      throw core::InternalError(who + "'s face walk for wedge " + std::to_string(i) +
                                  " does not run from it through its neighbours around that wedge.");
    for (NodeId u : walk)
      if (u > max_face_node_id)
        throw core::InputError(who + " is on a polygon face with node id " + std::to_string(u) +
                                    ", above the largest id the 3-connected mode supports (2^31 − 1).");
    if (know_.boundary && i == know_.outer_gap) throw core::InternalError(who + " lists a face for its outer wedge.");
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

  own_ = std::make_unique<detail::PackingAgent>(*this, 0, std::move(own));
  own_tags_ = own_->radius_tag_data();
  own_radius_ = own_->radius_data();
  // Hosted face vertices: neighbours = the face's walk from the host (docs/protocol.md, "Face vertices").
  for (Wedge& w : wedges_) {
    if (w.host != know_.id) continue;
    detail::AgentSpec fs;
    fs.id = w.face_id;
    fs.is_face = true;
    fs.polygon_here = true;
    fs.neighbours = w.walk;
    fs.face_nbr.assign(w.walk.size(), 0);
    w.agent = faces_.size() + 1;
    faces_.push_back(std::make_unique<detail::PackingAgent>(*this, w.agent, std::move(fs)));
  }
  know_.faces = {};  // copied into wedges_
  if (params.retransmit_after > 0)
    link_ = std::make_unique<ReliableNode>(runtime, know_.neighbours, params, [this](Runtime& rt) {
      rt_ = &rt;
      return std::make_unique<Protocol>(*this);
    });
}

PackingNode::~PackingNode() = default;

std::size_t PackingNode::index_of(NodeId id) const {
  if (deg_ >= sorted_from) return detail::neighbour_index(sorted_ids_, id);  // sorted_ids_ is kept
  std::size_t i = 0;
  while (i < deg_ && know_.neighbours[i] != id) ++i;
  return i;
}

const PackingNode::Wedge* PackingNode::wedge_of_face(NodeId face_id) const {
  for (const Wedge& w : wedges_)
    if (w.face_id == face_id) return &w;
  return nullptr;
}

void PackingNode::agent_send(std::size_t agent, std::size_t k_index, std::span<const std::byte> bytes) {
  const detail::PackingAgent& s = this->agent(agent);
  const NodeId to = s.neighbour(k_index);
  if (agent == 0 && !s.face_neighbour(k_index)) {  // an edge of G: a plain message
    transmit(s.touches_faces() ? index_of(to) : k_index, bytes);  // K = G without face vertices
    return;
  }
  const NodeId face = agent == 0 ? to : s.id();
  const Wedge& w = *wedge_of_face(face);
  const NodeId target_node = agent == 0 ? w.host : to;
  if (target_node == know_.id) {  // between this node's own vertex and a face vertex it hosts
    const std::size_t target_agent = agent == 0 ? w.agent : 0;
    const std::size_t from = this->agent(target_agent).index_of(s.id());
    local_.push_back({target_agent, from, local_bytes_.size(), bytes.size()});
    local_bytes_.insert(local_bytes_.end(), bytes.begin(), bytes.end());
    return;
  }
  send_relay(w, s.id(), to, bytes);
}

void PackingNode::send_relay(const Wedge& w, NodeId source, NodeId target, std::span<const std::byte> payload) {
  // The target node (the face's host when the target is the face vertex) sits at position p of the
  // walk from here; go the shorter way round: forward p hops, or backward m − p.
  const NodeId node = target == w.face_id ? w.host : target;
  const std::size_t m = w.walk.size();
  const auto p = static_cast<std::size_t>(std::find(w.walk.begin(), w.walk.end(), node) - w.walk.begin());
  const bool backward = p > m - p;
  encode(RelayView{w.face_id, source, target, backward, payload}, relay_buffer_);
  transmit(index_of(backward ? w.walk.back() : w.walk[1]), relay_buffer_);
}

void PackingNode::handle_relay(std::size_t from, const RelayView& m) {
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
  const std::size_t i = this->agent(agent).index_of(m.source);
  if (i == this->agent(agent).degree()) {
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
  this->agent(agent).receive(from_index, m);
}


void PackingNode::drain() {
  // Local deliveries between this node's agents, after the callback that produced them (never
  // re-entrant); they may produce more, delivered in turn. An abandoned run delivers nothing more.
  if (failed_) {
    local_.clear();
    local_bytes_.clear();
  }
  if (local_.empty()) {  // the usual case: nothing to deliver, local_bytes_ is empty (not even read)
    if (finished_at_ < 0 && is_final()) finished_at_ = rt_->now();
    return;
  }
  for (std::size_t next = 0; next < local_.size(); ++next) {
    const Local l = local_[next];  // receive() may append to local_ and local_bytes_
    PackingMessage m;              // decoded before receive() can move local_bytes_
    if (decode(std::span<const std::byte>(local_bytes_).subspan(l.offset, l.size), m) != DecodeStatus::ok)
      continue;  // our own encoding: cannot happen
    agent(l.agent).receive(l.from_index, m);
  }
  local_.clear();
  local_bytes_.clear();
  if (finished_at_ < 0 && is_final()) finished_at_ = rt_->now();
}

void PackingNode::on_start() {
  if (link_) link_->on_start();
  else start();
}

void PackingNode::start() {
  own_->start();
  for (auto& a : faces_) a->start();
  drain();
}

void PackingNode::on_timer(TimerId timer) {
  if (link_) link_->on_timer(timer);
  else ++counters_.unexpected;  // the protocol has no timers of its own
}

void PackingNode::on_recover() {
  if (link_) link_->on_recover();  // reliable links: nothing was armed
}

void PackingNode::on_message(NodeId from, std::span<const std::byte> bytes) {
  if (link_) link_->on_message(from, bytes);
  else receive(from, bytes);
}

void PackingNode::receive(NodeId from, std::span<const std::byte> bytes) {
  ++counters_.received;
  const std::size_t i = index_of(from);
  if (i == deg_) {
    ++counters_.not_a_neighbour;
    return;
  }
  // An envelope is read in place (its payload a view of `bytes`); any other message of the set is
  // for the own vertex: a plain message comes from G-neighbour i, K-neighbour g_k[i] of the own vertex.
  if (bytes.size() >= 2 && bytes[1] == static_cast<std::byte>(MessageType::relay)) {
    RelayView r;
    const DecodeStatus s = decode(bytes, r);
    ++counters_.decode[static_cast<std::size_t>(s)];
    if (s == DecodeStatus::ok) handle_relay(i, r);
  } else if (bytes.size() >= 2 && bytes[1] == static_cast<std::byte>(MessageType::radius)) {
    RadiusMsg m;  // the hottest message, read in place: the statuses of decoding it as a PackingHop
    const DecodeStatus s = decode(bytes, m);
    ++counters_.decode[static_cast<std::size_t>(s)];
    if (s == DecodeStatus::ok) own_->receive(own_->k_of_g(i), m);
  } else {
    PackingMessage m;  // PackingHop less the relay: the same statuses as decoding a PackingHop
    const DecodeStatus s = decode(bytes, m);
    ++counters_.decode[static_cast<std::size_t>(s)];
    if (s == DecodeStatus::ok) own_->receive(own_->k_of_g(i), m);
  }
  drain();
}

void PackingNode::transmit(std::size_t i, std::span<const std::byte> bytes) {
  rt_->send(know_.neighbours[i], bytes);
  ++counters_.sent;
  counters_.bytes_sent += bytes.size();
}

void PackingNode::broadcast_all(std::span<const std::byte> bytes) {
  rt_->broadcast(bytes);
  counters_.sent += deg_;
  counters_.bytes_sent += deg_ * bytes.size();
}

void PackingNode::on_failure(NodeId suspect) {
  // The layer declared a failure: the run is abandoned, local deliveries are dropped.
  failed_ = true;
  suspect_ = suspect;
  local_.clear();
  local_bytes_.clear();
  if (finished_at_ < 0) finished_at_ = rt_->now();
}

void PackingNode::prefetch() const {
  // Reads this object only (its first lines were prefetched an event or two earlier), never the
  // agent's: a demand load there would stall on the very miss the hint is for.
  __builtin_prefetch(know_.neighbours.data());
  const char* agent = reinterpret_cast<const char*>(own_.get());
  __builtin_prefetch(agent);
  __builtin_prefetch(agent + 64);
  __builtin_prefetch(own_tags_);
  __builtin_prefetch(own_radius_);
}

bool PackingNode::is_final() const { return failed_ || own_->phase() == PackingPhase::finished; }

PackingCounters PackingNode::counters() const {
  if (!link_) return counters_;
  // On lossy links the wire traffic is the layer's; the protocol's received/decode count payloads,
  // and a payload it could not decode is a bad payload.
  PackingCounters c;
  static_cast<ReliableCounters&>(c) = link_->counters();
  c.unexpected += counters_.unexpected;
  c.relayed = counters_.relayed;
  c.bad_payload += counters_.bad_payload + counters_.received - counters_.decode[static_cast<std::size_t>(DecodeStatus::ok)];
  return c;
}

Duration PackingNode::rto(std::size_t i) const { return link_ && i < deg_ ? link_->rto(i) : 0; }
PackingPhase PackingNode::phase() const { return own_->phase(); }
PackingOutcome PackingNode::outcome() const {
  return failed_ ? PackingOutcome::neighbour_failed : own_->outcome();
}
std::uint32_t PackingNode::depth() const { return own_->state().depth; }
bool PackingNode::is_root() const { return own_->state().is_root; }
std::uint32_t PackingNode::wave() const { return own_->state().wave; }
NodeId PackingNode::parent() const { return own_->state().parent; }
std::size_t PackingNode::children() const { return own_->children(); }
std::uint32_t PackingNode::steps() const { return own_->state().steps; }
std::uint32_t PackingNode::round() const { return own_->state().round; }
double PackingNode::h() const { return own_->state().h; }
const core::PlacedCircle& PackingNode::placement() const { return own_->placement(); }
core::LocalCondition PackingNode::local_condition() const { return own_->state().local; }
bool PackingNode::polygon_faces() const { return own_->polygon(); }
VertexState PackingNode::state() const { return own_->state(); }
std::vector<core::Circle> PackingNode::neighbour_circles() const {
  std::vector<core::Circle> out;
  for (std::size_t g = 0; g < own_->g_degree(); ++g) out.push_back(own_->neighbour_circle(own_->k_of_g(g)));
  return out;
}
VertexState PackingNode::hosted_face_state(std::size_t k) const { return faces_.at(k)->state(); }
const std::vector<NodeId>& PackingNode::hosted_face_walk(std::size_t k) const {
  for (const Wedge& w : wedges_)
    if (w.agent == k + 1) return w.walk;
  throw std::out_of_range("PackingNode::hosted_face_walk: no hosted face " + std::to_string(k) + ".");
}

}  // namespace laguerre::protocols
