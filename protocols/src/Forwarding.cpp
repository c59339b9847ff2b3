#include "laguerre/protocols/Forwarding.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace laguerre::protocols {

namespace {

using core::Point2;
using core::Sign;

bool finite_circle(const core::Circle& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.r) && c.r >= 0;
}
bool finite_point(Point2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

std::vector<Point2> centres(const std::vector<core::Circle>& circles) {
  std::vector<Point2> out;
  out.reserve(circles.size());
  for (const core::Circle& c : circles) out.push_back(core::centre(c));
  return out;
}

int sgn(Sign s) { return static_cast<int>(s); }

/// Sign of (a − p)·(b − p), exactly. compare_deviation(p, b, a, p) compares the angle between a − p
/// and b − p with that of the zero vector p − p, which it defines as π/2: it is negative exactly when
/// the angle is below π/2, i.e. when the dot product is positive (and zero when a or b equals p).
Sign dot_sign(Point2 p, Point2 a, Point2 b) {
  return static_cast<Sign>(-sgn(core::compare_deviation(p, b, a, p)));
}

/// core's in_open_sector: whether the direction t − p lies strictly inside the counter-clockwise
/// sector at p from the ray p→a to the ray p→b (`same_ray`: a node of degree one, the full turn minus
/// the ray p→a).
bool in_open_sector(Point2 p, Point2 a, Point2 b, Point2 t, bool same_ray) {
  const Sign a_t = core::orientation(p, a, t);
  if (same_ray) return a_t != Sign::zero || dot_sign(p, a, t) == Sign::negative;
  const Sign t_b = core::orientation(p, t, b);
  switch (core::orientation(p, a, b)) {
    case Sign::positive: return a_t == Sign::positive && t_b == Sign::positive;
    case Sign::negative: return a_t == Sign::positive || t_b == Sign::positive;
    case Sign::zero: break;
  }
  return dot_sign(p, a, b) == Sign::negative && a_t == Sign::positive;
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
    throw std::invalid_argument(who + " has " + std::to_string(neighbours_.size()) + " neighbours but " +
                                std::to_string(circles_.size()) + " neighbour circles.");
  if (positions_.size() != neighbours_.size())
    throw std::invalid_argument(who + " has " + std::to_string(neighbours_.size()) + " neighbours but " +
                                std::to_string(positions_.size()) + " neighbour positions.");
  std::vector<NodeId> sorted = neighbours_;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw std::invalid_argument(who + " lists a neighbour twice.");
  if (std::binary_search(sorted.begin(), sorted.end(), id_)) throw std::invalid_argument(who + " lists itself as a neighbour.");
  if (!finite_circle(own_)) throw std::invalid_argument(who + " has a circle that is not finite.");
  for (const core::Circle& c : circles_)
    if (!finite_circle(c)) throw std::invalid_argument(who + " knows a neighbour circle that is not finite.");
  if (!finite_point(position_)) throw std::invalid_argument(who + " has a position that is not finite.");
  for (const Point2& p : positions_)
    if (!finite_point(p)) throw std::invalid_argument(who + " knows a neighbour position that is not finite.");
}

std::size_t ForwardingNode::next_hop(double tx, double ty) const {
  // core::greedy_next: running argmin of the exact power to t over the neighbours, ties to the
  // smaller id; then the winner must be strictly better than the holder.
  const Point2 t{tx, ty};
  const std::size_t deg = neighbours_.size();
  std::size_t best = deg;
  for (std::size_t i = 0; i < deg; ++i) {
    if (best != deg) {
      const Sign s = core::compare_power(t, circles_[i], circles_[best]);
      if (s == Sign::positive || (s == Sign::zero && neighbours_[i] > neighbours_[best])) continue;
    }
    best = i;
  }
  if (best == deg) return deg;
  return core::compare_power(t, circles_[best], own_) == Sign::negative ? best : deg;
}

std::size_t ForwardingNode::next_hop_euclid(Point2 t) const {
  const std::size_t deg = neighbours_.size();
  std::size_t best = deg;
  for (std::size_t i = 0; i < deg; ++i) {
    if (best != deg) {
      const Sign s = core::compare_distance(t, positions_[i], positions_[best]);
      if (s == Sign::positive || (s == Sign::zero && neighbours_[i] > neighbours_[best])) continue;
    }
    best = i;
  }
  if (best == deg) return deg;
  return core::compare_distance(t, positions_[best], position_) == Sign::negative ? best : deg;
}

std::size_t ForwardingNode::next_hop_compass(Point2 t) const {
  // core::compass_next: the least deviation from the direction of t (compare_deviation is negative
  // when its first point deviates less), ties to the smaller id; never a dead end with a neighbour.
  const std::size_t deg = neighbours_.size();
  std::size_t best = deg;
  for (std::size_t i = 0; i < deg; ++i) {
    if (best != deg) {
      const Sign s = core::compare_deviation(position_, t, positions_[i], positions_[best]);
      if (s == Sign::positive || (s == Sign::zero && neighbours_[i] > neighbours_[best])) continue;
    }
    best = i;
  }
  return best;
}

std::size_t ForwardingNode::index_of(NodeId n) const {
  const auto it = std::find(neighbours_.begin(), neighbours_.end(), n);
  return it == neighbours_.end() ? no_neighbour : static_cast<std::size_t>(it - neighbours_.begin());
}

void ForwardingNode::originate(const DataPacket& p) {
  if (p.scheme == core::Scheme::greedy_power) {
    if (!finite_circle(p.target_circle)) throw std::invalid_argument("The target circle of a packet must be finite.");
    handle(DataMsg{p.packet, id_, p.target, p.target_circle.x, p.target_circle.y, p.target_circle.r, p.ttl, 0});
    return;
  }
  if (!finite_point(p.target_position)) throw std::invalid_argument("The target position of a packet must be finite.");
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
    if (core::compare_distance(t, position_, p) == Sign::negative) {
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
  std::size_t d = deg;
  for (std::size_t i = 0; i < deg && d == deg; ++i) {
    const std::size_t b = (i + 1) % deg;
    if (in_open_sector(position_, positions_[i], positions_[b], t, i == b)) d = b;
  }
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
  // The face change rule before traversing self → neighbours_[d] (core's route_gfg, rule 3). The
  // position λ of a proper crossing of the edge [a, b] with the line PT is o_P / (o_P − o_T) with
  // o_X = orient(a, b, X); since a and b lie strictly on opposite sides of PT, sign(o_P − o_T) =
  // sign(orient(P, T, b)), so λ > 0 and λ ≤ 1 are sign conditions on orientation predicates, and two
  // crossings compare with core::compare_crossings_along: all exact, as in core.
  const Point2 p{m.px, m.py}, t{m.tx, m.ty};
  const std::size_t deg = neighbours_.size();
  const Point2 pa = position_;
  for (;;) {
    const Point2 pb = positions_[d];
    const int sa = sgn(core::orientation(p, t, pa)), sb = sgn(core::orientation(p, t, pb));
    if (sa * sb < 0) {
      bool beyond_last = false;
      if (m.crossed)
        beyond_last = core::compare_crossings_along(p, t, pa, pb, {m.ax, m.ay}, {m.bx, m.by}) == Sign::positive;
      else
        beyond_last = sgn(core::orientation(pa, pb, p)) * sb > 0;
      const int ot = sgn(core::orientation(pa, pb, t));
      if (beyond_last && ot * sb <= 0) {
        m.crossed = true;
        m.ax = pa.x;
        m.ay = pa.y;
        m.bx = pb.x;
        m.by = pb.y;
        if (ot > 0) {
          // T is left of self → b: continue in the face on the other side of the edge, from here.
          d = (d + 1) % deg;
          m.walk_tail = id_;
          m.walk_head = neighbours_[d];
          continue;
        }
        m.walk_tail = id_;
        m.walk_head = neighbours_[d];
      }
    }
    break;
  }
  if (m.hops >= m.ttl) return end(m, PacketOutcome::ttl_exceeded);
  forward(m, d);
}

}  // namespace laguerre::protocols
