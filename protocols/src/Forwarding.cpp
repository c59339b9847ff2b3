#include "laguerre/protocols/Forwarding.hpp"
#include "laguerre/core/Error.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace laguerre::protocols {

namespace {

using core::Point2;

bool finite_point(Point2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

std::vector<Point2> centres(const std::vector<core::Circle>& circles) {
  std::vector<Point2> out;
  out.reserve(circles.size());
  for (const core::Circle& c : circles) out.push_back(core::centre(c));
  return out;
}

}  // namespace

std::string_view to_string(PacketOutcome o) {
  switch (o) {
    case PacketOutcome::delivered: return "delivered";
    case PacketOutcome::dead_end: return "dead_end";
    case PacketOutcome::ttl_exceeded: return "ttl_exceeded";
    case PacketOutcome::loop: return "loop";
  }
  return "?";
}

ForwardingNode::ForwardingNode(Runtime& runtime, PacketSink& sink, NodeId id, std::vector<NodeId> neighbours,
                               core::Circle own, std::vector<core::Circle> neighbour_circles)
    : ForwardingNode(runtime, sink, id, std::move(neighbours), own, neighbour_circles, core::centre(own),
                     centres(neighbour_circles)) {}

ForwardingNode::ForwardingNode(Runtime& runtime, PacketSink& sink, NodeId id, std::vector<NodeId> neighbours,
                               core::Circle own, std::vector<core::Circle> neighbour_circles, core::Point2 position,
                               std::vector<core::Point2> neighbour_positions)
    : rt_(runtime), sink_(sink), id_(id), neighbours_(std::move(neighbours)), own_(own),
      circles_(std::move(neighbour_circles)), position_(position), positions_(std::move(neighbour_positions)) {
  const std::string who = "Forwarding node " + std::to_string(id_);
  if (circles_.size() != neighbours_.size())
    throw core::InternalError(who + " has " + std::to_string(neighbours_.size()) + " neighbours but " +
                                std::to_string(circles_.size()) + " neighbour circles.");
  if (positions_.size() != neighbours_.size())
    throw core::InternalError(who + " has " + std::to_string(neighbours_.size()) + " neighbours but " +
                                std::to_string(positions_.size()) + " neighbour positions.");
  std::vector<NodeId> sorted = neighbours_;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw core::InternalError(who + " lists a neighbour twice.");
  if (std::binary_search(sorted.begin(), sorted.end(), id_)) throw core::InternalError(who + " lists itself as a neighbour.");
  if (!forwardable(own_)) throw core::InternalError(who + " has a circle that is not finite.");
  for (const core::Circle& c : circles_)
    if (!forwardable(c)) throw core::InternalError(who + " knows a neighbour circle that is not finite.");
  if (!finite_point(position_)) throw core::InternalError(who + " has a position that is not finite.");
  for (const Point2& p : positions_)
    if (!finite_point(p)) throw core::InternalError(who + " knows a neighbour position that is not finite.");
}

bool forwardable(const core::Circle& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.r) && c.r >= 0;
}

core::NeighbourView ForwardingNode::view() const { return {own_, position_, circles_, positions_, neighbours_}; }

std::size_t ForwardingNode::next_hop(double tx, double ty) const { return core::greedy_power_hop(view(), {tx, ty}); }

std::size_t ForwardingNode::next_hop_euclid(Point2 t) const { return core::greedy_euclid_hop(view(), t); }

std::size_t ForwardingNode::next_hop_compass(Point2 t) const { return core::compass_hop(view(), t); }

std::size_t ForwardingNode::index_of(NodeId n) const {
  const auto it = std::find(neighbours_.begin(), neighbours_.end(), n);
  return it == neighbours_.end() ? no_neighbour : static_cast<std::size_t>(it - neighbours_.begin());
}

void ForwardingNode::originate(const DataPacket& p) {
  if (p.scheme == core::Scheme::greedy_power) {
    if (!forwardable(p.target_circle)) throw core::InternalError("The target circle of a packet must be finite.");
    handle(DataMsg{p.packet, id_, p.target, p.target_circle.x, p.target_circle.y, p.target_circle.r, p.ttl, 0});
    return;
  }
  if (!finite_point(p.target_position)) throw core::InternalError("The target position of a packet must be finite.");
  RouteMsg m;
  m.packet = p.packet;
  m.source = id_;
  m.target = p.target;
  m.scheme = static_cast<RouteScheme>(static_cast<std::uint8_t>(p.scheme));
  m.tx = p.target_position.x;
  m.ty = p.target_position.y;
  m.ttl = p.ttl;
  handle(m, no_neighbour);
}

void ForwardingNode::on_message(NodeId from, std::span<const std::byte> bytes) {
  ++counters_.received;
  ForwardingMessage m;
  const std::size_t i = index_of(from);
  if (i == no_neighbour || decode(bytes, m) != DecodeStatus::ok) {
    ++counters_.rejected;
    return;
  }
  if (const auto* d = std::get_if<DataMsg>(&m)) return handle(*d);
  handle(std::get<RouteMsg>(m), i);
}

void ForwardingNode::handle(const DataMsg& m) {
  // core::Router::route_memoryless, one node's share: delivered, dead end, hop limit, forward.
  auto end = [&](PacketOutcome o) {
    sink_.on_packet_end({m.packet, m.source, m.target, o, id_, m.hops, core::Scheme::greedy_power});
  };
  if (m.target == id_) return end(PacketOutcome::delivered);
  const std::size_t next = next_hop(m.tx, m.ty);
  if (next == neighbours_.size()) return end(PacketOutcome::dead_end);
  if (m.hops >= m.ttl) return end(PacketOutcome::ttl_exceeded);
  DataMsg out = m;
  ++out.hops;
  encode(out, buffer_);
  rt_.send(neighbours_[next], buffer_);
  ++counters_.forwarded;
  sink_.on_forward(id_, neighbours_[next], m.packet, m.source, out.hops);
}

void ForwardingNode::end(const RouteMsg& m, PacketOutcome o) {
  sink_.on_packet_end(
      {m.packet, m.source, m.target, o, id_, m.hops, static_cast<core::Scheme>(static_cast<std::uint8_t>(m.scheme))});
}

void ForwardingNode::forward(RouteMsg& m, std::size_t next) {
  ++m.hops;
  encode(m, buffer_);
  rt_.send(neighbours_[next], buffer_);
  ++counters_.forwarded;
  sink_.on_forward(id_, neighbours_[next], m.packet, m.source, m.hops);
}

void ForwardingNode::handle(RouteMsg m, std::size_t from) {
  if (m.scheme == RouteScheme::compass) {
    const auto [it, first] = compass_seen_.try_emplace({m.source, m.packet}, m.hops);
    if (!first) {
      if (it->second == m.hops) {
        ++counters_.duplicates;
        return;
      }
      return end(m, PacketOutcome::loop);
    }
  }
  if (m.target == id_) return end(m, PacketOutcome::delivered);
  const Point2 t{m.tx, m.ty};
  std::size_t next = neighbours_.size();
  switch (m.scheme) {
    case RouteScheme::greedy_euclid: next = next_hop_euclid(t); break;
    case RouteScheme::compass: next = next_hop_compass(t); break;
    case RouteScheme::gfg: return gfg(m, from);
  }
  if (next == neighbours_.size()) return end(m, PacketOutcome::dead_end);
  if (m.hops >= m.ttl) return end(m, PacketOutcome::ttl_exceeded);
  forward(m, next);
}

void ForwardingNode::gfg(RouteMsg& m, std::size_t from) {
  const Point2 t{m.tx, m.ty};
  const std::size_t deg = neighbours_.size();
  if (m.perimeter) {
    const Point2 p{m.px, m.py};
    if (core::leaves_perimeter(position_, p, t)) {
      m.perimeter = false;  // back to greedy mode: clear the perimeter block (canonical encoding)
      m.px = m.py = 0;
      m.crossed = false;
      m.ax = m.ay = m.bx = m.by = 0;
      m.walk_tail = m.walk_head = 0;
    } else {
      // Right-hand rule: arrived along from → self, leave along the next dart counter-clockwise
      // after self → from (core: next_ccw(twin(d))).
      const std::size_t d = (from + 1) % deg;
      if (id_ == m.walk_tail && neighbours_[d] == m.walk_head) return end(m, PacketOutcome::loop);
      return perimeter_step(m, d);
    }
  }
  // Greedy mode.
  const std::size_t u = next_hop_euclid(t);
  if (u != deg) {
    if (m.hops >= m.ttl) return end(m, PacketOutcome::ttl_exceeded);
    return forward(m, u);
  }
  // A local minimum: enter perimeter mode here; the first face is the one whose corner here contains
  // the direction of T (searched from neighbours[0], as core searches from the first dart).
  const std::size_t d = core::first_face_hop(view(), t);
  if (d == deg) return end(m, PacketOutcome::dead_end);
  m.perimeter = true;
  m.px = position_.x;
  m.py = position_.y;
  m.crossed = false;
  m.ax = m.ay = m.bx = m.by = 0;
  m.walk_tail = id_;
  m.walk_head = neighbours_[d];
  perimeter_step(m, d);
}

void ForwardingNode::perimeter_step(RouteMsg& m, std::size_t d) {
  // The face change rule before traversing self → neighbours_[d] (core's route_gfg, rule 3); the
  // last face change travels in the message.
  const Point2 p{m.px, m.py}, t{m.tx, m.ty};
  core::FaceChange last{m.crossed, {m.ax, m.ay}, {m.bx, m.by}};
  const core::FaceHop hop = core::face_hop(view(), p, t, last, d);
  if (hop.changed) {
    m.crossed = true;
    m.ax = last.a.x;
    m.ay = last.a.y;
    m.bx = last.b.x;
    m.by = last.b.y;
    m.walk_tail = id_;
    m.walk_head = neighbours_[hop.next];
  }
  if (m.hops >= m.ttl) return end(m, PacketOutcome::ttl_exceeded);
  forward(m, hop.next);
}

}  // namespace laguerre::protocols
