#pragma once
/// @file
/// PHOLD on a graph, the workload of the parallel kernel's tests and benchmarks (tools/bench/mpi.sh).
///
/// Fujimoto's PHOLD with locality: each node starts `population` messages, each to a neighbour
/// drawn from the node's own stream; every copy a node receives it forwards the same way, one hop
/// further. The link model supplies the delay (phold_links: PHOLD's 0.1 + ~1 time unit as a uniform
/// latency in [100 ms, 2.1 s]; its minimum is the lookahead). Unlike the fully connected PHOLD of
/// tools/bench/phold.sh, destinations are neighbours, so a partition can keep most traffic local.
/// Messages are 16 bytes: origin id and hop count (little-endian).

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "laguerre/sim/Simulator.hpp"

namespace laguerre::sim::mpi {

/// A side × side torus (4 neighbours per node; side ≥ 3), every link following `link`.
inline Network torus(NodeIndex side, const LinkModel& link) {
  std::vector<Edge> edges;
  edges.reserve(2 * std::size_t{side} * side);
  for (NodeIndex r = 0; r < side; ++r) {
    for (NodeIndex c = 0; c < side; ++c) {
      const NodeIndex v = r * side + c;
      edges.emplace_back(v, r * side + (c + 1) % side);
      edges.emplace_back(v, ((r + 1) % side) * side + c);
    }
  }
  Network net(std::size_t{side} * side, edges);
  net.set_link_model(link);
  return net;
}

/// PHOLD's delay law as a link model: uniform in [100 ms, 2.1 s] (mean 1.1 s, lookahead 100 ms).
inline LinkModel phold_links() { return LinkModel{LatencyModel::uniform(milliseconds(100), milliseconds(2100)), 0, 0}; }

/// The PHOLD node handler (one object serves every node; see the file comment).
class Phold final : public NodeHandler {
public:
  /// What one node saw: copies received and an FNV-1a hash of their bytes in arrival order.
  struct NodeState {
    std::uint64_t received = 0;     ///< copies delivered to the node
    std::uint64_t digest = 0xcbf29ce484222325ULL;  ///< FNV-1a 64 over their bytes, in order
  };

  /// A handler for `nodes` nodes (the simulator's local_count()) starting `population` messages each.
  explicit Phold(std::size_t nodes, unsigned population = 1) : population_(population), state_(nodes) {}

  void on_start(Simulator& sim, NodeIndex v) override {
    for (unsigned i = 0; i < population_; ++i) forward(sim, v, sim.network().id(v), 0);
  }
  void on_message(Simulator& sim, NodeIndex v, NodeIndex, Phase, std::span<const std::byte> bytes) override {
    NodeState& s = state_[sim.local_index(v)];
    ++s.received;
    s.digest = fnv1a(bytes, s.digest);
    std::uint64_t origin = 0, hops = 0;
    std::memcpy(&origin, bytes.data(), 8);
    std::memcpy(&hops, bytes.data() + 8, 8);
    forward(sim, v, origin, hops + 1);
  }
  void on_timer(Simulator&, NodeIndex, std::uint64_t) override {}

  /// The state of the node at local index `i` (Simulator::local_index; the node's own index on a
  /// whole simulator, meaningful on the node's owner).
  const NodeState& state(NodeIndex i) const { return state_[i]; }

private:
  void forward(Simulator& sim, NodeIndex v, std::uint64_t origin, std::uint64_t hops) {
    const auto nbrs = sim.network().neighbours(v);
    if (nbrs.empty()) return;
    std::array<std::byte, 16> bytes{};
    std::memcpy(bytes.data(), &origin, 8);
    std::memcpy(bytes.data() + 8, &hops, 8);
    sim.send(v, nbrs[sim.node_stream(v).below(nbrs.size())], bytes);
  }

  unsigned population_;
  std::vector<NodeState> state_;
};

}  // namespace laguerre::sim::mpi
