#pragma once
/// @file
/// The simulated network: nodes (with user ids and optional positions), undirected adjacency from an
/// edge list, a link model per directed link, and a schedule of node crashes and recoveries.

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/protocols/Runtime.hpp"
#include "laguerre/sim/Link.hpp"
#include "laguerre/sim/Time.hpp"

namespace laguerre::sim {

/// Dense index of a node in a Network, 0 … node_count() − 1.
using NodeIndex = std::uint32_t;
/// Dense index of a directed link (u → v): position of v in u's neighbour list, offset by u's start.
using LinkIndex = std::uint32_t;
/// A position in the plane (the runtime's type, so hosts and nodes agree).
using Position = protocols::Position;
/// An undirected edge between two node indices.
using Edge = std::pair<NodeIndex, NodeIndex>;

/// One scheduled outage of a node.
struct Crash {
  NodeIndex node = 0;                ///< the node that crashes
  Time at = 0;                       ///< when it crashes
  std::optional<Time> recover_at;    ///< when it comes back (never, if empty)
};

/// An immutable topology with mutable models (link models, positions, ids, failures).
class Network {
public:
  /// A network of `node_count` nodes joined by `edges` (undirected; duplicates and both orientations
  /// are merged). Node ids default to the indices. Throws core::InternalError (a broken precondition) for a self-loop or an
  /// endpoint out of range, and std::length_error past 2^32 − 1 nodes or directed links.
  Network(std::size_t node_count, std::span<const Edge> edges);

  /// Number of nodes.
  std::size_t node_count() const { return offsets_.size() - 1; }
  /// Number of directed links (twice the number of undirected edges).
  std::size_t link_count() const { return targets_.size(); }
  /// Neighbours of `v`, by increasing index.
  std::span<const NodeIndex> neighbours(NodeIndex v) const {
    return {targets_.data() + offsets_[v], offsets_[v + 1] - offsets_[v]};
  }
  /// The directed link u → v, or nothing if v is not a neighbour of u (binary search).
  std::optional<LinkIndex> find_link(NodeIndex u, NodeIndex v) const;
  /// The directed link from `u` to its i-th neighbour.
  LinkIndex link_at(NodeIndex u, std::size_t i) const { return static_cast<LinkIndex>(offsets_[u] + i); }
  /// Sender of directed link `l`.
  NodeIndex link_source(LinkIndex l) const { return sources_[l]; }
  /// Receiver of directed link `l`.
  NodeIndex link_target(LinkIndex l) const { return targets_[l]; }

  /// Sets the user ids (e.g. core::PlanarGraph ids) the runtime and random streams see.
  /// Throws core::InternalError (a broken precondition) if the count is wrong or an id repeats.
  void set_ids(std::vector<std::uint64_t> ids);
  /// The user id of `v`.
  std::uint64_t id(NodeIndex v) const { return ids_.empty() ? v : ids_[v]; }
  /// The index of the node with user id `id`, if any (a binary search).
  std::optional<NodeIndex> index_of(std::uint64_t id) const;

  /// Sets every node's position. Throws core::InternalError (a broken precondition) on a count mismatch or a non-finite
  /// coordinate.
  void set_positions(std::vector<Position> positions);
  /// Whether positions were given.
  bool has_positions() const { return !positions_.empty(); }
  /// Position of `v` (requires has_positions()).
  const Position& position(NodeIndex v) const { return positions_[v]; }
  /// Euclidean distance between the endpoints of link `l` (0 without positions).
  double link_length(LinkIndex l) const;

  /// Sets the model of every directed link (validated).
  void set_link_model(const LinkModel& model);
  /// Sets the model of the directed link u → v only (validated). Throws core::InternalError (a broken precondition) if
  /// there is no such link.
  void set_link_model(NodeIndex u, NodeIndex v, const LinkModel& model);
  /// The model of directed link `l`.
  const LinkModel& link_model(LinkIndex l) const { return models_[model_of_link_.empty() ? 0 : model_of_link_[l]]; }

  /// Schedules a crash of `node` at `at`, and its recovery at `recover_at` if given. Throws
  /// core::InternalError (a broken precondition) for an unknown node, a negative time, or a recovery not after the crash.
  void add_crash(NodeIndex node, Time at, std::optional<Time> recover_at = std::nullopt);
  /// The failure schedule, in insertion order.
  std::span<const Crash> crashes() const { return crashes_; }

  /// Throws core::InternalError (a broken precondition) if a distance-based latency is used without positions.
  void validate() const;

private:
  std::vector<std::size_t> offsets_;        // CSR: neighbours of v are targets_[offsets_[v] …]
  std::vector<NodeIndex> targets_;
  std::vector<NodeIndex> sources_;
  std::vector<std::uint64_t> ids_;          // empty: ids are indices
  std::vector<std::pair<std::uint64_t, NodeIndex>> index_of_id_;  // (id, index) by id; empty with ids_
  std::vector<Position> positions_;
  std::vector<LinkModel> models_{LinkModel{}};
  std::vector<std::uint32_t> model_of_link_;  // index into models_ per link; empty: models_[0] everywhere
  std::vector<Crash> crashes_;
};

/// The network of a planar graph: one node per vertex (same indices), one link per edge, the
/// graph's user ids, every link following `link`.
Network network_of(const core::PlanarGraph& g, const LinkModel& link = {});

}  // namespace laguerre::sim
