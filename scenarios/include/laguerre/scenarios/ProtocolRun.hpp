#pragma once
/// @file
/// The distributed protocols on the discrete-event simulator, wired once for `laguerre simulate` and
/// the scenario runner: the packing protocol (protocols::PackingNode, one actor per node) with its
/// network model, outages and reliability layer, the check of its result against core::pack, and the
/// hop-by-hop forwarding of packets (protocols::ForwardingNode) on the embedding it produced.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/protocols/Forwarding.hpp"
#include "laguerre/protocols/HyperbolicSetup.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/protocols/Reliable.hpp"
#include "laguerre/protocols/Runtime.hpp"
#include "laguerre/scenarios/NetworkModel.hpp"
#include "laguerre/sim/HostRunner.hpp"
#include "laguerre/sim/Link.hpp"
#include "laguerre/sim/Metrics.hpp"
#include "laguerre/sim/Network.hpp"

namespace laguerre::scenarios {

/// Where a running packing protocol simulation stands (ProtocolSetup::on_progress).
struct ProtocolProgress {
  std::size_t nodes = 0;                 ///< nodes of the network
  protocols::PackingPhase phase = protocols::PackingPhase::idle;  ///< the least advanced node's phase
  std::uint32_t rounds = 0;              ///< rounds every node has completed (the smallest current round)
  std::uint32_t iterations = 0;          ///< Thurston steps every node has done (the smallest count)
  std::size_t holds_nodes = 0;           ///< nodes whose latest local check holds
  std::size_t final_nodes = 0;           ///< nodes in a final state
  std::uint64_t events = 0;              ///< simulator events processed so far
  double wall_seconds = 0;               ///< wall-clock time since the simulation started
  sim::Time simulated_time = 0;          ///< the simulated clock
};

/// How to run the packing protocol.
struct ProtocolSetup {
  bool asynchronous = false;                    ///< asynchronous Thurston updates
  int steps_per_round = 1;                      ///< N
  int max_iterations = 100000;                  ///< cap on steps
  core::RootRule root = core::RootRule::deepest;  ///< root election
  core::Acceleration acceleration = core::Acceleration::plain;  ///< core::runs_in_network (local kinds, newton_krylov), sync only
  core::Termination termination = core::Termination::layout;    ///< radius_only: sync only, not newton_krylov (docs/radius-only.md)
  sim::LinkModel link;                          ///< every link's model
  std::vector<CrashSpec> crashes;               ///< outages, for good or with a recovery
  std::optional<sim::Duration> retransmit_after;  ///< explicit reliability period (else 3 × longest latency)
  bool adaptive_rto = true;                     ///< false: the timeout stays at the period (no RTT estimation)
  std::uint64_t seed = 1;                       ///< root of the simulator's random streams
  sim::HostRunner* runner = nullptr;            ///< how the simulation runs (nullptr: in this process)
  /// Called between events, every `progress_period` seconds of wall time (checked every 2^16 events),
  /// while the simulation runs in this process (not with a `runner`); empty: no observer at all (the
  /// simulator's loop runs alone). The run is the same with or without it.
  std::function<void(const ProtocolProgress&)> on_progress;
  double progress_period = 1.0;                 ///< seconds between on_progress calls
  /// Whether the reliability layer runs: loss, duplication, outages or an explicit period.
  bool lossy() const {
    return link.loss > 0 || link.duplication > 0 || !crashes.empty() || retransmit_after.has_value();
  }
};

/// One outage and how its node ended.
struct OutageOutcome {
  CrashSpec spec;                 ///< as scheduled
  sim::NodeIndex node = 0;        ///< the node's index
  protocols::PackingOutcome outcome = protocols::PackingOutcome::running;  ///< the node's final outcome
  bool final = false;             ///< whether the node ended in a final state
};

/// What a protocol run produced.
struct ProtocolOutcome {
  core::CircleEmbedding circles;              ///< each node's final circle
  std::vector<core::LocalCondition> local;    ///< each node's last local check
  std::size_t converged_nodes = 0;            ///< nodes that ended `converged`
  std::size_t holds_nodes = 0;                ///< nodes whose local condition holds
  std::size_t failed_nodes = 0;               ///< surviving nodes that ended `neighbour_failed`
  std::size_t crashed_nodes = 0;              ///< nodes down for good (an outage without recovery)
  std::map<protocols::NodeId, std::size_t> suspects;  ///< failed survivors per suspected node id
  std::vector<OutageOutcome> outages;         ///< the setup's outages, in order
  std::uint32_t iterations = 0;               ///< Thurston steps (the largest over the nodes)
  std::uint32_t rounds = 0;                   ///< rounds (the largest over the nodes)
  std::uint64_t messages = 0;                 ///< messages sent (all nodes, retransmissions included)
  std::uint64_t bytes = 0;                    ///< their bytes
  std::uint64_t max_node_messages = 0;        ///< most messages sent by one node
  std::uint64_t max_node_bytes = 0;           ///< most bytes sent by one node
  /// Traffic per phase (index: protocols::MessageType; frames under the type they carry).
  std::vector<sim::TrafficCounters> by_phase;
  protocols::PackingCounters reliability;     ///< the nodes' counters, summed (retransmissions, acks, …)
  bool lossy = false;                         ///< whether the reliability layer ran
  sim::Duration retransmit_after = 0;         ///< its first retransmission period (lossy runs)
  bool adaptive_rto = false;                  ///< whether its timeout followed the round trips
  sim::Time simulated_time = 0;               ///< simulated time at the end
  sim::Time finished_at = 0;                  ///< when the last node reached its final outcome
  double wall_seconds = 0;                    ///< wall-clock time of the simulation
  std::uint64_t events = 0;                   ///< events processed
  double events_per_second = 0;               ///< events per wall-clock second
  std::size_t peak_memory_bytes = 0;          ///< peak resident memory of the process
  /// Whether every node converged.
  bool converged() const { return converged_nodes == circles.size(); }
  /// Nodes not down for good.
  std::size_t survivors() const { return circles.size() - crashed_nodes; }
};

/// The simulated network of `g` (same indices, user ids) with `link` on every link and `positions`
/// (if not empty). Outages are not added.
sim::Network make_network(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                          const sim::LinkModel& link);

/// The phase a message's traffic is counted under: its codec message type (byte 1); a reliability
/// frame under the type of the message it carries, a probe (empty frame) or an ack under their own.
sim::Phase traffic_phase(std::span<const std::byte> bytes);

/// The packing nodes' parameters for `setup` (the reliability layer still off).
protocols::PackingParams packing_params(const ProtocolSetup& setup);

/// What the summary of a run reads of one packing node; trivially copyable, so that it can travel
/// between processes (sim::append_bytes).
struct PackingNodeSummary {
  core::Circle circle;                      ///< placement().circle
  core::LocalCondition local;               ///< local_condition()
  protocols::PackingOutcome outcome;        ///< outcome()
  bool final;                               ///< is_final()
  std::uint32_t steps, round;               ///< steps(), round()
  protocols::PackingCounters counters;      ///< counters()
  protocols::Time finished_at;              ///< finished_at()
  protocols::NodeId suspect;                ///< suspect()
};

/// The summary of `node`.
PackingNodeSummary summarize(const protocols::PackingNode& node);

/// collect_packing_nodes from the nodes' summaries (nodes[v] of vertex v; requires one per vertex).
void collect_packing_summaries(const core::PlanarGraph& g, std::span<const PackingNodeSummary> nodes,
                               const std::vector<bool>& down, ProtocolOutcome& out);

/// Fills the per-node fields of `out` (circles, local, converged/holds/failed/crashed counts,
/// suspects, iterations, rounds, reliability, finished_at, and the outcomes of `out.outages`) from
/// the nodes of a finished run, whatever hosted them: `node_of(v)` is vertex v's node, `down[v]`
/// whether v was down for good (empty: no node was).
void collect_packing_nodes(const core::PlanarGraph& g,
                           const std::function<const protocols::PackingNode&(core::Vertex)>& node_of,
                           const std::vector<bool>& down, ProtocolOutcome& out);

/// Fills the traffic fields of `out` (messages, bytes, per-node maxima, by_phase) from `traffic`
/// (indexed by vertex and traffic_phase).
void collect_traffic(const sim::TrafficMetrics& traffic, ProtocolOutcome& out);

/// Runs the protocol on `g` (prepared for packing). Throws core::InputError if an outage names an
/// unknown node (source "crash ID@TIME") or a distance latency is used without positions.
ProtocolOutcome run_packing_protocol(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                                     const ProtocolSetup& setup);

/// The check of a run against the core: "not applicable: …" after a node failure; in asynchronous
/// mode core's LPD/GLPD check (per `kind`) of the nodes' circles ("… holds at K/N nodes"); otherwise
/// whether core::pack with the same N, cap and root gives the same circles and iterations bit for bit
/// ("identical to core::pack, bit for bit" or "DIFFERS from core::pack").
std::string verify_against_core(const core::PlanarGraph& g, core::GraphKind kind, const ProtocolSetup& setup,
                                const ProtocolOutcome& outcome);

/// A forwarding node for vertex `v` of `g`, knowing its own and its neighbours' circles and positions;
/// with `reliable`, inside a protocols::ReliableNode with those parameters (for lossy links).
std::unique_ptr<protocols::Node> make_forwarding_node(protocols::Runtime& rt, protocols::PacketSink& sink,
                                                      const core::PlanarGraph& g, core::Vertex v,
                                                      const core::CircleEmbedding& circles,
                                                      const std::vector<core::Point2>& positions,
                                                      const std::optional<protocols::ReliableParams>& reliable = {});

/// The forwarding node of a node make_forwarding_node built (inside its reliability layer, if any).
protocols::ForwardingNode& forwarding_node(protocols::Node& node);

/// Hop-by-hop forwarding of one scheme: outcomes and hop stretch against BFS shortest paths.
struct ForwardingResult {
  core::Scheme scheme = core::Scheme::greedy_power;  ///< the scheme
  std::size_t packets = 0;        ///< packets sent (one per pair)
  std::size_t delivered = 0;      ///< delivered
  std::size_t dead_ends = 0;      ///< ended at a dead end
  std::size_t loops = 0;          ///< ended in a loop
  std::size_t ttl_exceeded = 0;   ///< ended at the hop limit
  double hops_mean = 0;           ///< hops per delivered packet
  double stretch_mean = std::numeric_limits<double>::quiet_NaN();  ///< hop stretch over delivered packets (NaN if none)
  double stretch_p95 = std::numeric_limits<double>::quiet_NaN();   ///< its nearest-rank 95th percentile (NaN if none)
  double stretch_max = std::numeric_limits<double>::quiet_NaN();   ///< its maximum (NaN if none)
  double simulated_seconds = 0;   ///< simulated time of the forwarding run
  std::uint64_t retransmissions = 0;  ///< frames the reliability layer sent again (lossy links; else 0)
};

/// Where the geometric schemes place the nodes: `positions` if not empty, else the circles' centres.
std::vector<core::Point2> forwarding_positions(const core::CircleEmbedding& circles,
                                               const std::vector<core::Point2>& positions);

/// Packet number `i` (its id) of `pairs`, towards pairs[i].second with `circles` and `positions`
/// (forwarding_positions), under `scheme` with core::route's hop limit (core::default_ttl).
protocols::DataPacket forwarding_packet(const core::PlanarGraph& g, const core::CircleEmbedding& circles,
                                        const std::vector<core::Point2>& positions, core::Scheme scheme,
                                        const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs, std::size_t i);

/// Hop distances (breadth-first search) from every source that appears in `pairs` (row s for source
/// s; the other rows empty).
std::vector<std::vector<std::uint32_t>> hop_distances_from_sources(
    const core::PlanarGraph& g, const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs);

/// One scheme's result from the end reports of its packets (ids = indices into `pairs`, any order),
/// with hop stretch against `hop_distance` (hop_distances_from_sources); timing fields left 0. The
/// reports are summed in packet order, so the same outcomes give the same means to the last bit,
/// whatever order the packets ended in.
ForwardingResult summarize_forwarding(core::Scheme scheme, const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs,
                                      const std::vector<std::vector<std::uint32_t>>& hop_distance,
                                      const std::vector<protocols::PacketReport>& reports);

/// The reliability layer under forwarding nodes on lossy links of one-way latency at most
/// `max_latency` ns: protocols::lossy_link_params without probes (an idle forwarder has nothing to
/// watch, and the queue drains once every packet has arrived and been acknowledged).
protocols::ReliableParams forwarding_reliable_params(sim::Duration max_latency);

/// A PacketSink that keeps every report.
class PacketCollector : public protocols::PacketSink {
public:
  /// Appends `r` to `reports`.
  void on_packet_end(const protocols::PacketReport& r) override { reports.push_back(r); }
  std::vector<protocols::PacketReport> reports;  ///< in the order the packets ended
};

/// What the distributed set-up of the hyperbolic baseline produced (protocols/HyperbolicSetup.hpp).
struct HyperbolicSetupOutcome {
  std::size_t done_nodes = 0;                 ///< nodes that ended with their and their neighbours' addresses
  core::Vertex root = core::none;             ///< the root the nodes chose
  std::uint32_t tiling_degree = 0;            ///< q (the root's)
  std::vector<core::Vertex> parents;          ///< per vertex, its tree parent (none at the root)
  std::vector<std::uint32_t> depths;          ///< per vertex, its depth
  std::vector<std::vector<std::uint32_t>> addresses;  ///< per vertex, its address (child sides from the root)
  std::uint64_t messages = 0;                 ///< messages sent
  std::uint64_t bytes = 0;                    ///< their bytes
  std::uint64_t max_node_messages = 0;        ///< most messages sent by one node
  std::vector<sim::TrafficCounters> by_phase; ///< traffic per codec message type
  std::uint64_t state_bytes = 0;              ///< Σ HyperbolicSetupNode::state_bytes
  std::size_t max_state_bytes = 0;            ///< the largest
  std::uint64_t rejected = 0;                 ///< messages the nodes rejected (0 on a correct run)
  std::size_t inconsistent_tables = 0;        ///< neighbour-table entries unlike that neighbour's own address (0 likewise)
  sim::Time simulated_time = 0;               ///< simulated time at the end
  double wall_seconds = 0;                    ///< wall-clock time of the simulation
};

/// Runs the hyperbolic set-up on `g` (placed at `positions`, if not empty) over links of `link`
/// (reliable: no loss, duplication or outage), neighbours in g's adjacency order, the double sweep
/// from vertex 0 (or from `root`, when given, the tree alone); every message simulated and counted
/// (traffic_phase). Throws core::InputError for a lossy link model or a distance latency without
/// positions.
HyperbolicSetupOutcome run_hyperbolic_setup(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                                            const sim::LinkModel& link, std::uint64_t seed,
                                            core::Vertex root = core::none);

/// Throws InputError (source "--scheme") if `schemes` holds one the per-node forwarding protocol lacks
/// (Scheme::hyperbolic, evaluated by the central router only).
void require_forwarding_schemes(const std::vector<core::Scheme>& schemes);

/// Why packets cannot be forwarded on the outcome of a packing run, or "" if they can: the run was
/// abandoned (a node failed), or some final circle is not finite (a run stopped, by the iteration
/// cap, before its layout was representable in doubles). Forwarding nodes refuse such circles.
std::string forwarding_blocker(const ProtocolOutcome& outcome);

/// Forwards one packet per pair in `pairs` hop by hop, one simulation per scheme, over the links of
/// `link` and the simulator seeded with `seed`; on lossy or duplicating links every forwarding node
/// runs over the reliability layer (protocols::ReliableNode), so each hop arrives exactly once and
/// the outcomes and hop counts are those of loss-free links (only the timing differs). Greedy power routes on `circles`; the other schemes on `positions` if not empty (they also
/// place the network's nodes for distance latencies), else on the circles' centres. Each packet's
/// hop limit is core::default_ttl, so the outcomes are core::route's. Checks require_forwarding_schemes.
/// Without pairs nothing is simulated and no node is built: the result is empty.
std::vector<ForwardingResult> run_forwarding(const core::PlanarGraph& g, const core::CircleEmbedding& circles,
                                             const std::vector<core::Point2>& positions, const sim::LinkModel& link,
                                             std::uint64_t seed, const std::vector<core::Scheme>& schemes,
                                             const std::vector<std::pair<core::Vertex, core::Vertex>>& pairs);

}  // namespace laguerre::scenarios
