#pragma once
/// @file
/// Runs a scenario: expands sweep points × repetitions into runs, gives each run its own seed, and
/// executes them on worker threads. A run = build the topology → run the packing protocol in the
/// simulator → route the pairs with every scheme → a RunRecord.
///
/// ## Seeds
/// Let mix(x) be the SplitMix64 output function applied to x + 0x9E3779B97F4A7C15 (Steele, Lea and
/// Flood 2014: z = x + γ; z = (z ^ z>>30)·0xBF58476D1CE4E5B9; z = (z ^ z>>27)·0x94D049BB133111EB;
/// z ^ z>>31). Then
///  - run seed        = mix(mix(mix(scenario seed) ^ point) ^ repetition) — the simulator's streams
///    and the pair sample;
///  - topology seed   = mix(mix(mix(scenario seed) ^ fnv1a64(canonical topology text)) ^ repetition),
///    where the canonical text lists the generator and its parameters; sweep points that differ only
///    outside `topology` therefore share their graphs (common random numbers: a comparison of network
///    conditions or protocol settings is paired).
/// Neither depends on --jobs or on the order in which runs finish.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"
#include "laguerre/core/random/Random.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"
#include "laguerre/scenarios/Scenario.hpp"
#include "laguerre/scenarios/Topology.hpp"
#include "laguerre/scenarios/fields/SensorNetwork.hpp"
#include "laguerre/sim/HostRunner.hpp"

namespace laguerre::scenarios {

/// The seed mixers of the file comment: core's SplitMix64 step and 64-bit FNV-1a (core/random/Random.hpp).
using core::fnv1a64;
using core::splitmix64;

/// The run seed of (scenario seed, point, repetition) (see the file comment).
std::uint64_t derive_run_seed(std::uint64_t scenario_seed, std::size_t point, std::size_t repetition);

/// The topology seed of (scenario seed, topology, repetition) (see the file comment).
std::uint64_t derive_topology_seed(std::uint64_t scenario_seed, const TopologySpec& topology, std::size_t repetition);

/// The canonical text of a topology: "generator;name=value;…" with parameters sorted by name.
std::string canonical_text(const TopologySpec& topology);

/// One planned run.
struct RunPlan {
  std::size_t point = 0;          ///< sweep point index
  std::size_t repetition = 0;     ///< from 0
  std::uint64_t seed = 0;         ///< run seed
  std::uint64_t topology_seed = 0;  ///< topology seed
};

/// Every run of `scenario`, point-major (all repetitions of point 0, then point 1, …).
std::vector<RunPlan> plan_runs(const Scenario& scenario);

/// How a run ended.
enum class RunStatus {
  ok,             ///< the protocol converged and the pairs were routed
  not_converged,  ///< iteration cap (routed anyway on the last layout)
  node_failed,    ///< a node detected a failure and the run was abandoned (nothing routed)
  unsupported,    ///< the topology could not be built or packed (see RunRecord::message)
  error,          ///< anything else (see RunRecord::message)
};

/// Name of a status ("ok", "not_converged", "node_failed", "unsupported", "error").
std::string_view to_string(RunStatus status);

/// Routing results of one scheme in one run.
struct SchemeResult {
  core::Scheme scheme = core::Scheme::greedy_power;  ///< the scheme
  std::size_t pairs = 0;                             ///< pairs routed
  std::size_t delivered = 0;                         ///< pairs delivered
  double delivery_rate = 0;                          ///< delivered / pairs (NaN without pairs)
  double stretch_mean = 0;                           ///< mean hop stretch (NaN if none delivered)
  double stretch_p95 = 0;                            ///< 95th percentile (nearest rank)
  double stretch_max = 0;                            ///< largest
  double hops_mean = 0;                              ///< mean hops of delivered pairs
  std::string positions;                             ///< "packing", "physical" or "tree" (hyperbolic)
  /// Schemes with their own setup: messages and bytes per node to set it up — hyperbolic: its
  /// protocol simulated (protocols/HyperbolicSetup.hpp); a geometric scheme on physical positions:
  /// one position exchange (a message of 16 payload bytes per directed link) — and, for hyperbolic,
  /// the bits of a node's coordinate (mean, max); NaN for the others, whose setup is the run's
  /// packing protocol (greedy power, and the geometric schemes on the packing's centres).
  double setup_messages_per_node = std::numeric_limits<double>::quiet_NaN();
  double setup_bytes_per_node = std::numeric_limits<double>::quiet_NaN();
  /// Routing state a node holds once set up, mean bytes: its and its neighbours' coordinates (greedy
  /// power 24-byte circles, the geometric schemes 16-byte positions, hyperbolic the set-up's
  /// HyperbolicSetupNode::state_bytes).
  double state_bytes_per_node = std::numeric_limits<double>::quiet_NaN();
  double coordinate_bits_mean = std::numeric_limits<double>::quiet_NaN();
  double coordinate_bits_max = std::numeric_limits<double>::quiet_NaN();
  /// A field with `attach: true`: the same scheme over pairs of all sensors (greedy power with the
  /// attachment, the others on the planarization of all sensors; fields/SensorNetwork.hpp). The
  /// fields above are then the core pairs.
  std::optional<AllPairsStats> all_pairs;
};

/// The result of one run.
struct RunRecord {
  RunPlan plan;                        ///< which run
  RunStatus status = RunStatus::error; ///< how it ended
  std::string message;                 ///< explanation for a status other than ok
  std::string family;                  ///< generator name
  std::string topology;                ///< topology name
  std::string topology_note;           ///< the generator's report (e.g. a sensor field's repair), or ""
  std::string kind;                    ///< "triangulated_disc" / "three_connected" ("" if not built)
  std::size_t sensors = 0;             ///< sensors deployed (= vertices of the topology unless a field's repair dropped some)
  std::size_t nodes = 0;               ///< sensors routed: every sensor with attach, else the packed vertices
  std::size_t core_nodes = 0;          ///< vertices packed by the protocol (its messages are over these)
  std::size_t unreachable_sensors = 0; ///< attach: sensors in other link components than the core (own trees only)
  std::size_t edges = 0;               ///< edges
  std::uint32_t iterations = 0;        ///< protocol: Thurston steps to its stop
  std::uint32_t rounds = 0;            ///< protocol: rounds
  std::size_t holds_nodes = 0;         ///< nodes where LPD/GLPD holds at the end
  std::uint64_t messages = 0;          ///< protocol messages
  std::uint64_t bytes = 0;             ///< protocol bytes
  double messages_per_node = 0;        ///< messages / nodes
  std::uint64_t max_node_messages = 0; ///< most messages of one node
  std::uint64_t retransmissions = 0;   ///< reliability layer retransmissions
  double simulated_seconds = 0;        ///< simulated time of the protocol
  std::uint64_t events = 0;            ///< simulator events
  int exact_iterations = -1;           ///< iterations to an exact packing (core::pack), -1 if not asked or not reached
  int core_lpd_iterations = -1;        ///< iterations to LPD/GLPD seen by the same core::pack run, -1 if not asked
  std::vector<SchemeResult> routing;   ///< per scheme, in the scenario's order
  double wall_seconds = 0;             ///< wall-clock time of the whole run
};

/// What pictures need from a run (kept only for the runs RunnerOptions::keep_artifacts selects).
struct RunArtifacts {
  Topology topology;                                 ///< the graph and its positions
  core::CircleEmbedding circles;                     ///< the embedding routed on (packing)
  std::vector<core::LocalCondition> local;           ///< per node, at the end
  std::vector<std::vector<core::Vertex>> greedy_routes;  ///< sample routes, greedy power
  std::vector<std::vector<core::Vertex>> gfg_routes;     ///< the same pairs, GFG (on the routing positions)
  core::CircleEmbedding gfg_positions;               ///< where GFG routed (radius 0 circles or the packing)
};

/// Progress of run_scenario, reported after each finished run.
struct RunProgress {
  std::size_t done = 0;           ///< runs finished
  std::size_t total = 0;          ///< runs planned
  double elapsed_seconds = 0;     ///< since the start
};

/// Several processes sharing the runs of a sweep (e.g. MPI ranks: tools/laguerre/Parallel.cpp), every
/// one calling run_scenario with the same scenario: each executes the runs it owns, one at a time (the
/// runs that keep artifacts on process 0, the others dealt round-robin in plan order), and all_gather
/// gives every process the records of all, so each ends with the ScenarioResults of a single process
/// (artifacts on process 0 only).
class RunSplit {
public:
  virtual ~RunSplit() = default;
  /// This process, in [0, size()).
  virtual std::size_t rank() const = 0;
  /// The processes.
  virtual std::size_t size() const = 0;
  /// Called once by every process with its bytes; returns every process's, concatenated in rank order.
  virtual std::vector<std::byte> all_gather(std::span<const std::byte> mine) = 0;
};

/// The bytes of `record` appended to `out`, and the record read back at `at` (advanced): how
/// RunSplit moves records between processes of one build. decode_record(encode_record(r)) has every
/// field of r.
void encode_record(const RunRecord& record, std::vector<std::byte>& out);
RunRecord decode_record(std::span<const std::byte> in, std::size_t& at);

/// Options of run_scenario.
struct RunnerOptions {
  unsigned jobs = 0;                                        ///< worker threads (0 = hardware threads)
  std::function<void(const RunProgress&)> on_progress;      ///< called under a lock, any thread
  /// A run's protocol simulation in progress (ProtocolSetup::on_progress: about once a second, in-process
  /// simulations only); called under the same lock as on_progress, any thread.
  std::function<void(const RunPlan&, const ProtocolProgress&)> on_protocol_progress;
  std::function<bool(const RunPlan&)> keep_artifacts;       ///< which runs keep RunArtifacts
  /// How the protocol simulations run (nullptr: in this process). With one (e.g. sim/mpi's, every MPI
  /// rank making the same calls), runs go one at a time in plan order and `jobs` is ignored.
  sim::HostRunner* host_runner = nullptr;
  /// Runs shared with other processes (nullptr: every run here); excludes host_runner, and runs go
  /// one at a time (`jobs` is ignored).
  RunSplit* split = nullptr;
};

/// Results in plan order.
struct ScenarioResults {
  std::vector<RunRecord> records;                    ///< one per planned run, plan order
  std::vector<std::optional<RunArtifacts>> artifacts;  ///< same indexing; set where kept
  double wall_seconds = 0;                           ///< total wall-clock time
};

/// Executes one run. Never throws for a bad topology or a failing protocol (see RunStatus).
/// The protocol simulation runs on `host_runner` (nullptr: in this process) and reports to
/// `on_progress` (ProtocolSetup::on_progress) if given.
RunRecord execute_run(const Scenario& scenario, const RunPlan& plan, RunArtifacts* artifacts = nullptr,
                      sim::HostRunner* host_runner = nullptr,
                      const std::function<void(const ProtocolProgress&)>& on_progress = {});

/// Executes every run of `scenario` on `options.jobs` threads; the result does not depend on jobs.
ScenarioResults run_scenario(const Scenario& scenario, const RunnerOptions& options = {});

}  // namespace laguerre::scenarios
