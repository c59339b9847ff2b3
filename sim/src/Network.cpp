#include "laguerre/sim/Network.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

Network::Network(std::size_t node_count, std::span<const Edge> edges) {
  if (node_count >= 0xffffffffu) {
    throw std::length_error("A network holds at most 2^32 - 2 nodes, got " +
                            std::to_string(node_count) + ".");
  }
  std::vector<std::pair<NodeIndex, NodeIndex>> arcs;
  arcs.reserve(2 * edges.size());
  for (const auto& [u, v] : edges) {
    LAGUERRE_PRECONDITION(u < node_count && v < node_count,
                          "Edge (" + std::to_string(u) + ", " + std::to_string(v) + ") names a node outside 0.." +
                              std::to_string(node_count) + " - 1.");
    LAGUERRE_PRECONDITION(u != v, "Edge (" + std::to_string(u) + ", " + std::to_string(v) +
                                      ") is a self-loop; a node cannot be its own neighbour.");
    arcs.emplace_back(u, v);
    arcs.emplace_back(v, u);
  }
  std::sort(arcs.begin(), arcs.end());
  arcs.erase(std::unique(arcs.begin(), arcs.end()), arcs.end());
  if (arcs.size() >= 0xffffffffu) throw std::length_error("Too many links (2^32 - 1 at most).");
  offsets_.assign(node_count + 1, 0);
  for (const auto& a : arcs) ++offsets_[a.first + 1];
  for (std::size_t v = 0; v < node_count; ++v) offsets_[v + 1] += offsets_[v];
  targets_.reserve(arcs.size());
  sources_.reserve(arcs.size());
  for (const auto& a : arcs) {  // sorted by (source, target): CSR order directly
    sources_.push_back(a.first);
    targets_.push_back(a.second);
  }
}

std::optional<LinkIndex> Network::find_link(NodeIndex u, NodeIndex v) const {
  if (u >= node_count()) return std::nullopt;
  const auto row = neighbours(u);
  const auto it = std::lower_bound(row.begin(), row.end(), v);
  if (it == row.end() || *it != v) return std::nullopt;
  return static_cast<LinkIndex>(offsets_[u] + static_cast<std::size_t>(it - row.begin()));
}

void Network::set_ids(std::vector<std::uint64_t> ids) {
  LAGUERRE_PRECONDITION(ids.size() == node_count(), "Expected " + std::to_string(node_count()) + " node ids, got " +
                                                        std::to_string(ids.size()) + ".");
  std::vector<std::pair<std::uint64_t, NodeIndex>> index(ids.size());
  bool identity = true;
  for (std::size_t v = 0; v < ids.size(); ++v) {
    index[v] = {ids[v], static_cast<NodeIndex>(v)};
    identity = identity && ids[v] == v;
  }
  std::sort(index.begin(), index.end());
  for (std::size_t i = 1; i < index.size(); ++i)
    LAGUERRE_PRECONDITION(index[i].first != index[i - 1].first,
                          "Node id " + std::to_string(index[i].first) + " is given to two nodes.");
  if (identity) {  // ids equal to the indices need no table
    ids_ = {};
    index_of_id_ = {};
    return;
  }
  ids_ = std::move(ids);
  index_of_id_ = std::move(index);
}

std::optional<NodeIndex> Network::index_of(std::uint64_t id) const {
  if (ids_.empty()) {
    if (id < node_count()) return static_cast<NodeIndex>(id);
    return std::nullopt;
  }
  const auto it = std::lower_bound(index_of_id_.begin(), index_of_id_.end(), id,
                                   [](const std::pair<std::uint64_t, NodeIndex>& e, std::uint64_t key) { return e.first < key; });
  if (it == index_of_id_.end() || it->first != id) return std::nullopt;
  return it->second;
}

void Network::set_positions(std::vector<Position> positions) {
  LAGUERRE_PRECONDITION(positions.size() == node_count(), "Expected " + std::to_string(node_count()) +
                                                              " positions, got " + std::to_string(positions.size()) + ".");
  for (std::size_t v = 0; v < positions.size(); ++v)
    LAGUERRE_PRECONDITION(std::isfinite(positions[v].x) && std::isfinite(positions[v].y),
                          "The position of node " + std::to_string(v) + " is not finite.");
  positions_ = std::move(positions);
}

double Network::link_length(LinkIndex l) const {
  if (positions_.empty()) return 0;
  const Position& a = positions_[sources_[l]];
  const Position& b = positions_[targets_[l]];
  return std::hypot(a.x - b.x, a.y - b.y);
}

void Network::set_link_model(const LinkModel& model) {
  model.validate();
  models_.assign(1, model);
  model_of_link_ = {};  // one model for every link: no table
}

void Network::set_link_model(NodeIndex u, NodeIndex v, const LinkModel& model) {
  model.validate();
  const auto link = find_link(u, v);
  LAGUERRE_PRECONDITION(link.has_value(),
                        "There is no link from node " + std::to_string(u) + " to node " + std::to_string(v) + ".");
  if (models_.size() >= 0xffffffffu) throw std::length_error("Too many distinct link models.");
  models_.push_back(model);
  if (model_of_link_.empty()) model_of_link_.assign(link_count(), 0);
  model_of_link_[*link] = static_cast<std::uint32_t>(models_.size() - 1);
}

void Network::add_crash(NodeIndex node, Time at, std::optional<Time> recover_at) {
  LAGUERRE_PRECONDITION(node < node_count(), "Cannot crash node " + std::to_string(node) + ": the network has " +
                                                 std::to_string(node_count()) + " nodes.");
  LAGUERRE_PRECONDITION(at >= 0, "A crash time cannot be negative.");
  LAGUERRE_PRECONDITION(!recover_at || *recover_at > at,
                        "Node " + std::to_string(node) + " must recover after it crashes (at " + std::to_string(at) +
                            " ns), not at " + std::to_string(recover_at.value_or(0)) + " ns.");
  crashes_.push_back(Crash{node, at, recover_at});
}

void Network::validate() const {
  if (!positions_.empty()) return;
  for (const LinkModel& m : models_)
    LAGUERRE_PRECONDITION(m.latency.kind != LatencyKind::distance,
                          "A distance-based latency needs node positions; call Network::set_positions first.");
}

Network network_of(const core::PlanarGraph& g, const LinkModel& link) {
  std::vector<Edge> edges;
  edges.reserve(g.num_edges());
  for (core::Dart d = 0; d < g.num_darts(); ++d)
    if (g.tail(d) < g.head(d)) edges.emplace_back(g.tail(d), g.head(d));
  Network net(g.num_vertices(), edges);
  net.set_ids(g.ids());
  net.set_link_model(link);
  return net;
}

}  // namespace laguerre::sim
