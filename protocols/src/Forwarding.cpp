#include "laguerre/protocols/Forwarding.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::protocols {

namespace {
bool finite_circle(const core::Circle& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.r) && c.r >= 0;
}
}  // namespace

ForwardingNode::ForwardingNode(Runtime& runtime, PacketSink& sink, NodeId id, std::vector<NodeId> neighbours,
                               core::Circle own, std::vector<core::Circle> neighbour_circles)
    : rt_(runtime), sink_(sink), id_(id), neighbours_(std::move(neighbours)), own_(own),
      circles_(std::move(neighbour_circles)) {
  const std::string who = "Forwarding node " + std::to_string(id_);
  if (circles_.size() != neighbours_.size())
    throw std::invalid_argument(who + " has " + std::to_string(neighbours_.size()) + " neighbours but " +
                                std::to_string(circles_.size()) + " neighbour circles.");
  std::vector<NodeId> sorted = neighbours_;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw std::invalid_argument(who + " lists a neighbour twice.");
  if (std::binary_search(sorted.begin(), sorted.end(), id_)) throw std::invalid_argument(who + " lists itself as a neighbour.");
  if (!finite_circle(own_)) throw std::invalid_argument(who + " has a circle that is not finite.");
  for (const core::Circle& c : circles_)
    if (!finite_circle(c)) throw std::invalid_argument(who + " knows a neighbour circle that is not finite.");
}

std::size_t ForwardingNode::next_hop(double tx, double ty) const {
  // core::greedy_next: running argmin of the exact power to t over the neighbours, ties to the
  // smaller id; then the winner must be strictly better than the holder.
  const core::Point2 t{tx, ty};
  const std::size_t deg = neighbours_.size();
  std::size_t best = deg;
  for (std::size_t i = 0; i < deg; ++i) {
    if (best != deg) {
      const core::Sign s = core::compare_power(t, circles_[i], circles_[best]);
      if (s == core::Sign::positive || (s == core::Sign::zero && neighbours_[i] > neighbours_[best])) continue;
    }
    best = i;
  }
  if (best == deg) return deg;
  return core::compare_power(t, circles_[best], own_) == core::Sign::negative ? best : deg;
}

void ForwardingNode::originate(const DataPacket& p) {
  if (!finite_circle(p.target_circle)) throw std::invalid_argument("The target circle of a packet must be finite.");
  handle(DataMsg{p.packet, id_, p.target, p.target_circle.x, p.target_circle.y, p.target_circle.r, p.ttl, 0});
}

void ForwardingNode::on_message(NodeId from, std::span<const std::byte> bytes) {
  ++counters_.received;
  Message m;
  if (std::find(neighbours_.begin(), neighbours_.end(), from) == neighbours_.end() || decode(bytes, m) != DecodeStatus::ok ||
      !std::holds_alternative<DataMsg>(m)) {
    ++counters_.rejected;
    return;
  }
  handle(std::get<DataMsg>(m));
}

void ForwardingNode::handle(const DataMsg& m) {
  // core::Router::route_memoryless, one node's share: delivered, dead end, hop limit, forward.
  auto end = [&](PacketOutcome o) { sink_.on_packet_end({m.packet, m.source, m.target, o, id_, m.hops}); };
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

}  // namespace laguerre::protocols
