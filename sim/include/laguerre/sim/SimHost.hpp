#pragma once
/// @file
/// The host adapter: runs protocols::Node objects on the Simulator, one protocols::Runtime per node.
///
/// The mapping is thin: Runtime::send/broadcast → Simulator::send/broadcast (protocol node ids are
/// the network's user ids), schedule/cancel → kernel timers (the TimerHandle is the kernel handle's
/// value, never 0), random_u64 → the node's counter-based stream keyed by (seed, node id), now → the
/// simulated clock. Messages are tagged with a phase by an optional classifier over their bytes
/// (e.g. the codec's message-type byte), since the runtime interface itself carries no phase.
///
/// A node that recovers from a crash keeps its state and gets protocols::Node::on_recover (timers
/// that fell inside the outage are lost; the node re-arms what it needs there).

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "laguerre/protocols/Runtime.hpp"
#include "laguerre/sim/Simulator.hpp"

namespace laguerre::sim {

/// Hosts one protocols::Node per network node on a Simulator.
class SimHost final : private NodeHandler {
public:
  /// Builds the node for index `v`, given the runtime it must use (which outlives it).
  using NodeFactory = std::function<std::unique_ptr<protocols::Node>(protocols::Runtime&, NodeIndex)>;
  /// Maps a message's bytes to the phase its traffic is counted under.
  using PhaseOf = std::function<Phase(std::span<const std::byte>)>;

  /// A host of `network` whose nodes `factory` builds (all of them, in index order, right away).
  /// Without `phase_of`, every message counts under phase 0. With `held` (one flag per node, e.g.
  /// HostRunner::ownership), it builds and holds only the nodes v with held[v] != 0, on a simulator
  /// built for that part (Simulator's constructor), for a partitioned run. Throws
  /// core::InternalError (a broken precondition) if the factory returns a null node.
  SimHost(Network network, SimConfig config, const NodeFactory& factory, PhaseOf phase_of = {},
          std::vector<std::uint8_t> held = {});
  SimHost(const SimHost&) = delete;
  SimHost& operator=(const SimHost&) = delete;
  ~SimHost() override;

  /// Runs the simulation (see Simulator::run).
  RunReport run(const RunLimits& limits = {}) { return simulator_.run(limits); }
  /// The simulator (metrics, trace, clock, network).
  Simulator& simulator() { return simulator_; }
  /// The simulator, read-only.
  const Simulator& simulator() const { return simulator_; }
  /// The node at index `v` (a held node).
  protocols::Node& node(NodeIndex v) { return *nodes_[simulator_.local_index(v)]; }
  /// The number of node objects built (simulator().local_count()).
  std::size_t built_nodes() const { return nodes_.size(); }
  /// The runtime serving the node at index `v` (a held node).
  protocols::Runtime& runtime(NodeIndex v);
  /// Runtime calls rejected because they named an unknown node or a non-neighbour (they also throw).
  std::uint64_t bad_destinations() const { return bad_destinations_; }

private:
  class NodeRuntime;
  /// One link of a node, keyed by the user id of the neighbour it leads to.
  struct IdLink {
    protocols::NodeId id;
    LinkIndex link;
  };

  /// The link from `v` to its neighbour with user id `to`, if `to` is one.
  std::optional<LinkIndex> link_to(NodeIndex v, protocols::NodeId to) const;
  /// Counts a send from `v` to `to`, which is not a neighbour of `v`, and throws core::InternalError.
  [[noreturn]] void reject(NodeIndex v, protocols::NodeId to);

  Phase phase(std::span<const std::byte> bytes) const;
  void on_start(Simulator& sim, NodeIndex v) override;
  void on_message(Simulator& sim, NodeIndex v, NodeIndex from, Phase phase,
                  std::span<const std::byte> bytes) override;
  void on_timer(Simulator& sim, NodeIndex v, std::uint64_t timer) override;
  void on_recover(Simulator& sim, NodeIndex v) override;
  void prefetch(NodeIndex v) const override;
  void prefetch_state(NodeIndex v) const override;

  Simulator simulator_;
  PhaseOf phase_of_;
  // Per held node (Simulator::local_index) and per link of a held node (local_link_start):
  std::vector<IdLink> links_by_id_;  // the held nodes' rows in network order, each row sorted by id
  std::unique_ptr<NodeRuntime[]> runtimes_;
  std::vector<std::unique_ptr<protocols::Node>> nodes_;
  std::uint64_t bad_destinations_ = 0;
};

}  // namespace laguerre::sim
