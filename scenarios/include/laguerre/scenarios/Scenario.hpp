#pragma once
/// @file
/// A scenario: one experiment read from a YAML file (schema in scenarios/README.md) — a topology,
/// a network model, protocol parameters, routing schemes and pairs, outputs — and its sweep points,
/// the Cartesian product of the `sweep` section's lists, each a complete configuration.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "laguerre/core/EnumNames.hpp"
#include "laguerre/core/packing/Accelerator.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/RadiusOnly.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/scenarios/NetworkModel.hpp"
#include "laguerre/scenarios/Topology.hpp"
#include "laguerre/sim/Link.hpp"

namespace laguerre::scenarios {

/// `topology:` — a generator and its parameters.
struct TopologySpec {
  std::string generator;   ///< a registry name (see Topology.hpp)
  TopologyParams params;   ///< validated against the generator's ParamSpecs
};

/// `network:` — link model and failures of the simulated network.
struct NetworkSpec {
  std::string latency_text = "constant:1ms";       ///< as written
  sim::LatencyModel latency = sim::LatencyModel::constant(sim::milliseconds(1));  ///< parsed
  double loss = 0;                                 ///< loss probability per copy, [0, 1)
  double duplication = 0;                          ///< duplication probability per message, [0, 1]
  std::vector<CrashSpec> crashes;                  ///< outages, for good or with a recovery
  std::optional<sim::Duration> retransmit_after;   ///< first retransmission period (reliability layer)
  /// Whether the reliability layer is needed (loss, duplication, crashes or an explicit period).
  bool lossy() const { return loss > 0 || duplication > 0 || !crashes.empty() || retransmit_after.has_value(); }
};

/// The stopping rule a scenario asks for.
enum class StopSpec {
  lpd,    ///< the protocol's local rule (LPD on triangulated discs, GLPD on 3-connected graphs)
  glpd,   ///< synonym of lpd (the protocol picks the rule from the graph's kind)
  exact,  ///< continue centrally (core::pack) to the thesis's exact packing and route on it
};
/// StopSpec: lpd, glpd, exact.
inline constexpr core::EnumNames<StopSpec, 3> stop_spec_names{
    {{StopSpec::lpd, "lpd"}, {StopSpec::glpd, "glpd"}, {StopSpec::exact, "exact"}}};

/// How the packing runs: the distributed protocol (synchronous or asynchronous updates), or centrally.
enum class ProtocolMode { sync, async, central };
/// ProtocolMode: sync, async, central (`laguerre simulate --mode` offers the first two).
inline constexpr core::EnumNames<ProtocolMode, 3> protocol_mode_names{
    {{ProtocolMode::sync, "sync"}, {ProtocolMode::async, "async"}, {ProtocolMode::central, "central"}}};

/// `protocol:` — the distributed packing protocol's parameters.
struct ProtocolSpec {
  bool asynchronous = false;                   ///< mode: sync (default) or async
  /// mode `central`: no simulation — core::pack runs the same Jacobi iteration centrally (with
  /// `acceleration`) and the run routes on its result; messages and simulated time are then 0. For
  /// routing questions on networks too large to simulate to convergence.
  bool central = false;
  /// Modes sync and central: plain, chebyshev, local-superstep, newton-krylov (core::runs_in_network);
  /// central only: superstep, anderson, newton; async: plain only.
  core::Acceleration acceleration = core::Acceleration::plain;
  int steps_per_round = 1;                     ///< N, Thurston steps per round
  core::Termination termination = core::Termination::layout;  ///< the termination test (sync and central)
  StopSpec stop = StopSpec::lpd;               ///< stopping rule
  int max_iterations = 100000;                 ///< cap on Thurston steps
  core::RootRule root = core::RootRule::deepest;  ///< layout root election
  bool exact_reference = false;                ///< also count iterations to an exact packing (core::pack)
};

/// Which coordinates greedy Euclidean, compass and GFG routing use.
enum class GeometricPositions {
  automatic,  ///< physical positions when the topology has them, else the packing's centres
  packing,    ///< the packing's centres
  physical,   ///< the physical positions (the generator must provide them)
};
/// GeometricPositions: auto, packing, physical.
inline constexpr core::EnumNames<GeometricPositions, 3> positions_names{{{GeometricPositions::automatic, "auto"},
                                                                         {GeometricPositions::packing, "packing"},
                                                                         {GeometricPositions::physical, "physical"}}};

/// `routing:` — schemes and pairs.
/// The routing schemes as scenario files and the command line spell them (core::to_string(Scheme) is
/// the underscore form of the outputs).
inline constexpr core::EnumNames<core::Scheme, 5> scheme_names{{{core::Scheme::greedy_power, "greedy-power"},
                                                                {core::Scheme::greedy_euclid, "greedy-euclid"},
                                                                {core::Scheme::compass, "compass"},
                                                                {core::Scheme::gfg, "gfg"},
                                                                {core::Scheme::hyperbolic, "hyperbolic"}}};

struct RoutingSpec {
  std::vector<core::Scheme> schemes{core::all_schemes.begin(), core::all_schemes.end()};  ///< in order
  std::size_t pairs = 0;                     ///< 0 = all ordered pairs, else a seeded sample of k
  GeometricPositions positions = GeometricPositions::automatic;  ///< for the non-power schemes
  std::size_t sample_routes = 3;             ///< routes drawn in pictures (greedy power vs GFG)
};

/// `outputs:` — what `laguerre run` writes.
struct OutputSpec {
  bool json = true;                  ///< results.json
  bool csv = true;                   ///< results.csv
  bool pictures = true;              ///< one picture per sweep point (first repetition)
  std::size_t picture_max_nodes = 20000;  ///< no picture above this many nodes
};

/// One complete configuration (a sweep point).
struct ScenarioConfig {
  TopologySpec topology;   ///< the graph
  NetworkSpec network;     ///< the network model
  ProtocolSpec protocol;   ///< the packing protocol
  RoutingSpec routing;     ///< routing schemes and pairs
  OutputSpec outputs;      ///< outputs
};

/// A sweep point: the values its swept keys take, and the resulting configuration.
struct ScenarioPoint {
  std::size_t index = 0;                                     ///< position in the Cartesian product
  std::vector<std::pair<std::string, std::string>> values;   ///< (key path, value as written)
  ScenarioConfig config;                                     ///< the configuration at this point
};

/// A loaded, validated scenario.
struct Scenario {
  std::string name;                     ///< `name:`
  std::string source;                   ///< the file it was read from
  std::uint64_t seed = 1;               ///< `seed:`
  std::size_t repetitions = 1;          ///< `repetitions:`
  std::vector<std::string> sweep_keys;  ///< swept key paths, in file order (the product's digits)
  std::vector<ScenarioPoint> points;    ///< every point (one when nothing is swept)
};

/// Name of a stopping rule ("lpd", "glpd", "exact").
std::string_view to_string(StopSpec stop);
/// Name of a positions rule ("auto", "packing", "physical").
std::string_view to_string(GeometricPositions positions);
/// A scheme as scenario files write it ("greedy-power", "greedy-euclid", "compass", "gfg", "hyperbolic").
std::string scheme_name(core::Scheme scheme);

}  // namespace laguerre::scenarios
