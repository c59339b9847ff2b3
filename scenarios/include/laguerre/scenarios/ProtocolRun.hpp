#pragma once
/// @file
/// Runs the distributed packing protocol (protocols::PackingNode, one actor per node) on the
/// discrete-event simulator and gathers what the nodes hold and what the network carried — the part
/// of `laguerre simulate` that scenarios reuse.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"
#include "laguerre/scenarios/NetworkModel.hpp"
#include "laguerre/sim/Link.hpp"
#include "laguerre/sim/Network.hpp"

namespace laguerre::scenarios {

/// How to run the protocol.
struct ProtocolSetup {
  bool asynchronous = false;                    ///< asynchronous Thurston updates
  int steps_per_round = 1;                      ///< N
  int max_iterations = 100000;                  ///< cap on steps
  core::RootRule root = core::RootRule::deepest;  ///< root election
  sim::LinkModel link;                          ///< every link's model
  std::vector<CrashSpec> crashes;               ///< crashes for good
  std::optional<sim::Duration> retransmit_after;  ///< explicit reliability period (else 3 × longest latency)
  std::uint64_t seed = 1;                       ///< root of the simulator's random streams
};

/// What a protocol run produced.
struct ProtocolOutcome {
  core::CircleEmbedding circles;              ///< each node's final circle
  std::vector<core::LocalCondition> local;    ///< each node's last local check
  std::size_t converged_nodes = 0;            ///< nodes that ended `converged`
  std::size_t holds_nodes = 0;                ///< nodes whose local condition holds
  std::size_t failed_nodes = 0;               ///< surviving nodes that ended `neighbour_failed`
  std::size_t crashed_nodes = 0;              ///< nodes scheduled to crash
  std::uint32_t iterations = 0;               ///< Thurston steps (the largest over the nodes)
  std::uint32_t rounds = 0;                   ///< rounds (the largest over the nodes)
  std::uint64_t messages = 0;                 ///< messages sent (all nodes, retransmissions included)
  std::uint64_t bytes = 0;                    ///< their bytes
  std::uint64_t max_node_messages = 0;        ///< most messages sent by one node
  std::uint64_t retransmissions = 0;          ///< reliability layer: retransmitted frames
  double simulated_seconds = 0;               ///< simulated time at the end
  double wall_seconds = 0;                    ///< wall-clock time of the simulation
  std::uint64_t events = 0;                   ///< events processed
  /// Whether every node converged.
  bool converged() const { return converged_nodes == circles.size(); }
};

/// The simulated network of `g` (same indices, user ids) with `link` on every link and `positions`
/// (if not empty). Crashes are not added.
sim::Network make_network(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                          const sim::LinkModel& link);

/// Runs the protocol on `g` (prepared for packing). Throws std::invalid_argument if a crash names an
/// unknown node or a distance latency is used without positions.
ProtocolOutcome run_packing_protocol(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                                     const ProtocolSetup& setup);

}  // namespace laguerre::scenarios
