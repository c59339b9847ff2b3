#pragma once
/// @file
/// The topology registry: maps a generator name and its scenario parameters to a planar graph ready
/// for packing (kind decided, outer face chosen), with physical node positions when the generator has
/// them.
///
/// Every generator is one entry of the registry: its parameters (name, type, range, default value),
/// its cross-parameter check and its build function, so that the scenario loader can validate a file
/// before anything runs, `build_topology` trusts validated parameters and fills in the declared
/// defaults, and the documentation (`generators_help`) is generated from the same entries. A
/// generator that is declared but not yet implemented (`GeneratorInfo::available` false) is rejected
/// by the loader with its `unavailable_reason`.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::scenarios {

/// The type of a generator parameter, as written in a scenario file.
enum class ParamType {
  integer,   ///< a whole number within [min, max]
  number,    ///< a finite real number within [min, max]
  boolean,   ///< true or false
  choice,    ///< one of `choices`
  file,      ///< a path to an existing file, relative to the scenario file's folder
  polygons,  ///< a list of polygons, each a list of at least 3 points [x, y]
  text,      ///< a string, checked by the generator's `check` (e.g. a metric-field specification)
};

/// A list of polygons (outer boundary first, then holes), each a list of points.
using Polygons = std::vector<std::vector<core::Point2>>;

/// A validated parameter value: integer, number, boolean, text (choice and file) or polygons.
using ParamValue = std::variant<std::int64_t, double, bool, std::string, Polygons>;

/// One parameter a generator accepts.
struct ParamSpec {
  std::string name;                                          ///< key under `topology:`
  ParamType type = ParamType::integer;                       ///< its type
  std::string help;                                          ///< one line for the documentation
  double min = -std::numeric_limits<double>::infinity();     ///< smallest accepted value (integer, number)
  double max = std::numeric_limits<double>::infinity();      ///< largest accepted value (integer, number)
  std::vector<std::string> choices;                          ///< accepted values (choice)
  bool required = false;                                     ///< must be given
  std::optional<ParamValue> default_value;                   ///< what builders use when it is not given
  std::string default_text;  ///< the default, as documented: describe(*default_value), or a phrase for
                             ///< a default that is no value ("the unit square"); empty if none
};

/// The parameters of one topology, by name, in the order they were given.
class TopologyParams {
public:
  /// Sets (or replaces) parameter `name`.
  void set(const std::string& name, ParamValue value);
  /// Whether `name` was given.
  bool has(std::string_view name) const;
  /// Integer parameter `name`, or `fallback` if absent.
  std::int64_t integer(std::string_view name, std::int64_t fallback) const;
  /// Number parameter `name` (an integer is widened), or `fallback` if absent.
  double number(std::string_view name, double fallback) const;
  /// Boolean parameter `name`, or `fallback` if absent.
  bool boolean(std::string_view name, bool fallback) const;
  /// Text (choice or file) parameter `name`, or `fallback` if absent.
  std::string text(std::string_view name, const std::string& fallback) const;
  /// Polygons parameter `name`, or an empty list if absent.
  Polygons polygons(std::string_view name) const;
  /// The value of `name` as written in tables ("" if absent).
  std::string describe(std::string_view name) const;
  /// Every (name, value), in insertion order.
  const std::vector<std::pair<std::string, ParamValue>>& entries() const { return entries_; }

private:
  const ParamValue* find(std::string_view name) const;
  std::vector<std::pair<std::string, ParamValue>> entries_;
};

/// A value as written in tables: integers plainly, numbers with %g, polygons as a count.
std::string describe(const ParamValue& value);

/// A problem found by a generator's own cross-parameter check.
struct ParamIssue {
  std::string param;     ///< the parameter it is about (the key under `topology:`)
  std::string found;     ///< what was found
  std::string expected;  ///< what was expected
};

struct SensorNetwork;  // fields/SensorNetwork.hpp

/// A topology ready for the packing protocol.
struct Topology {
  core::PlanarGraph graph;              ///< prepared for packing (see core::prepare_for_packing)
  core::GraphKind kind{};               ///< triangulated disc or 3-connected
  std::vector<core::Point2> positions;  ///< physical positions by vertex, or empty
  std::string name;                     ///< e.g. "delaunay(n=50)" or "graphs/x.txt#2"
  std::string family;                   ///< the generator name
  std::string note;                     ///< what the generator reports (e.g. a sensor field's repair), or ""
  std::vector<std::uint64_t> removed;   ///< ids of input vertices the outer rule removed (core::prepare_input)
  /// A sensor field built with `attach: true`: every sensor, its links and its attachment to `graph`
  /// (the core, whose ids are sensor indices); null otherwise.
  std::shared_ptr<const SensorNetwork> sensors;
};

/// What the registry knows about a generator.
struct GeneratorInfo {
  std::string name;                 ///< the name scenario files use (`topology.generator`)
  std::string summary;              ///< one line for the documentation
  std::vector<ParamSpec> params;    ///< accepted parameters (besides `generator`)
  bool positions = false;           ///< whether it yields physical node positions
  bool available = true;            ///< false: declared, not wired yet
  std::string unavailable_reason;   ///< why not (a full sentence), when !available
  /// Checks beyond each parameter's type and range (e.g. a radius required by some graph types, a
  /// domain's polygons being simple); run by the loader on parameters that passed those. May be empty.
  std::function<std::vector<ParamIssue>(const TopologyParams&)> check;
  /// Builds the topology from validated parameters (absent ones take their `default_value`), a seed and
  /// a repetition number; empty when !available.
  std::function<Topology(const TopologyParams&, std::uint64_t seed, std::size_t repetition)> build;
};

/// A topology that could not be built or is not packable (not a triangulated disc, not 3-connected):
/// bad input, with no location of its own (`what()` is the message).
class TopologyError : public core::InputError {
public:
  explicit TopologyError(const std::string& message) : core::InputError(message, std::string(), 0, message) {}
};

/// Every registered generator, in documentation order.
const std::vector<GeneratorInfo>& topology_generators();

/// The generator called `name`, or nullptr.
const GeneratorInfo* find_generator(std::string_view name);

/// The registered names, comma-separated (only the available ones if `available_only`).
std::string generator_names(bool available_only);

/// The documentation of every generator, from the registry: per generator a line `name: summary`, then
/// one line per parameter `  name (type[, range or choices]; required | default D): help`.
std::string generators_help();

/// Builds the topology of generator `generator` with validated `params` from `seed`. `repetition`
/// (from 0) selects the graph of a multi-graph file when `index` is 0. Throws TopologyError when the
/// generator is unavailable, the input is unreadable, or the graph cannot be packed.
Topology build_topology(std::string_view generator, const TopologyParams& params, std::uint64_t seed,
                        std::size_t repetition = 0);

}  // namespace laguerre::scenarios
