#pragma once
/// @file
/// Turning a deployment into a packable planar graph: the construction (restricted Delaunay, unit-disk
/// graph, Gabriel, RNG, localized Delaunay), a report of what came out, and the repair policy.
///
/// ## What a sensor-field topology produces, and what the scenario does about it
///
/// The packing (core::prepare_for_packing) accepts two kinds of graphs: triangulated discs (every
/// inner face a triangle, the outer boundary a simple cycle) and 3-connected plane graphs. A proximity
/// graph of a random deployment is often neither: the unit-disk graph may be disconnected (isolated
/// sensors, a corridor too narrow for the radius); Gabriel and RNG graphs have non-triangular faces and
/// vertices of degree 1 or 2; a restricted Delaunay triangulation in a domain with a narrow neck has
/// cut vertices. Every construction is therefore followed by a report (FieldGraphReport: components,
/// triangulated disc?, 3-connected?, a separating set of one or two vertices) and by the scenario's
/// `repair` policy:
///
///  - `fail` (the default): stop with a FieldGraphError whose message names the construction, the
///    problem and a witness: "the graph is not connected: 3 components, the largest has 480 of the 500
///    points (point 17 cannot be reached from point 0)" or "… is neither a triangulated disc (12 inner
///    faces are not triangles) nor 3-connected: removing point 12 disconnects it".
///  - `largest-block`: keep the largest 2-connected block (most vertices; ties to the block found first)
///    of the graph and drop every other point. If that block is a triangulated disc or 3-connected it is
///    used, otherwise the scenario fails as with `fail`, naming the block's separating pair.
///  - `three-connected-core`: keep the largest connected component; delete vertices of degree ≤ 2
///    (repeatedly, as deleting one lowers its neighbours' degrees); then, while the graph is neither a
///    triangulated disc nor 3-connected, take a separating set S of 1 or 2 vertices
///    (core::find_small_separator) and keep S together with the largest component of G − S. Faces
///    stay as they are, so the holes of the domain stay holes: this is the policy for fields with
///    holes, whose restricted Delaunay triangulation is rarely 3-connected as built (a boundary vertex
///    of degree 2, a chord cutting off a corner). Each round rebuilds the graph (O(n log n)); the bulk
///    deletion of low degrees keeps the number of rounds small. Fails if fewer than 3 points remain.
///  - `triangulate-faces`: keep the largest block as above, then triangulate every inner face that is
///    not a triangle by straight chords inside the face (ear clipping with exact predicates). The result
///    is always a triangulated disc whose outer boundary is the block's outer cycle. Chords join points
///    of the same face and may be longer than the radius: they are virtual links, counted in the report
///    (`added_chords`). Note that a hole of the domain bounded by an inner face is filled too.
///
/// Vertex ids are the indices of the points in the deployment, also after repair (dropped points leave
/// gaps), and the positions are the points: the result is a straight-line drawing (GraphInput with
/// positions, `outer_given` true, outer face the unbounded one).

#include "laguerre/core/Error.hpp"
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/meshing/Domain.hpp"
#include "laguerre/scenarios/fields/ProximityGraphs.hpp"

namespace laguerre::scenarios {

/// The proximity graph built on a deployment (see ProximityGraphs.hpp for the definitions).
enum class FieldGraphType {
  delaunay,                ///< Delaunay triangulation restricted to the domain
  unit_disk,               ///< UDG(R) itself; accepted only when its drawing happens to be plane
  gabriel,                 ///< Gabriel ∩ UDG(R)
  relative_neighbourhood,  ///< RNG ∩ UDG(R)
  local_delaunay           ///< LDel^(k) of Li, Calinescu, Wan and Wang on UDG(R)
};

/// Parses "delaunay", "unit-disk", "gabriel", "rng" or "local-delaunay"; throws core::InputError
/// listing them.
FieldGraphType parse_field_graph_type(std::string_view name);
/// The name parse_field_graph_type accepts.
std::string_view to_string(FieldGraphType type);

/// What to do when the graph is neither a triangulated disc nor 3-connected (see the file comment).
enum class RepairPolicy { fail, largest_block, three_connected_core, triangulate_faces };

/// Parses "fail", "largest-block", "three-connected-core" or "triangulate-faces"; throws core::InputError listing them.
RepairPolicy parse_repair_policy(std::string_view name);
/// The name parse_repair_policy accepts.
std::string_view to_string(RepairPolicy policy);

/// Parameters of a field graph.
struct FieldGraphOptions {
  FieldGraphType type = FieldGraphType::delaunay;  ///< the construction
  double radius = 0;              ///< the unit-disk radius R (all types but delaunay), > 0
  unsigned hops = 2;              ///< k of LDel^(k) (local_delaunay only), ≥ 1; planar for k ≥ 2
  RepairPolicy repair = RepairPolicy::fail;  ///< what to do with an unpackable graph
  std::string source = "field";   ///< names the graph in messages and in GraphInput::name
};

/// What the construction produced, before and after repair.
struct FieldGraphReport {
  std::size_t points = 0;             ///< number of points deployed
  std::size_t edges = 0;              ///< edges of the construction
  std::size_t components = 0;         ///< connected components of the construction
  std::size_t largest_component = 0;  ///< vertices of the largest component
  bool triangulated_disc = false;     ///< the construction is a triangulated disc (connected case only)
  bool three_connected = false;       ///< the construction is 3-connected (connected case only)
  std::size_t non_triangular_faces = 0;  ///< inner faces that are not triangles (connected case only)
  std::vector<std::uint64_t> separator;  ///< ids of a separating set of 1–2 vertices, if connected and found
  bool repaired = false;              ///< whether the repair policy changed the graph
  std::size_t removed_points = 0;     ///< points dropped by the repair
  std::size_t added_chords = 0;       ///< chords added by triangulate-faces
  core::GraphKind kind = core::GraphKind::triangulated_disc;  ///< kind of the final graph

  /// One line for logs, e.g. "gabriel: 500 points, 812 edges, connected, not a triangulated disc
  /// (97 non-triangular inner faces), not 3-connected (point 12 separates); triangulate-faces removed
  /// 3 points and added 140 chords: triangulated disc".
  std::string summary(std::string_view name) const;
};

/// The result: the drawing (graph, positions, ids = point indices), its kind for packing, the report.
struct FieldGraph {
  core::GraphInput input;   ///< the graph with positions; `outer_given` is true
  core::GraphKind kind = core::GraphKind::triangulated_disc;  ///< as decided by prepare_for_packing
  FieldGraphReport report;  ///< what happened
};

/// The `fail` policy's error (also raised when a repair cannot help); what() is the full message,
/// prefixed by the options' source.
class FieldGraphError : public core::InputError {
public:
  /// Builds the error with its report.
  FieldGraphError(const std::string& message, FieldGraphReport report)
      : core::InputError(message), report_(std::move(report)) {}
  /// The report up to the failure.
  const FieldGraphReport& report() const noexcept { return report_; }

private:
  FieldGraphReport report_;
};

/// The radius R at which n uniform points in the domain have mean unit-disk degree `degree`, ignoring
/// boundary effects: n π R² / area = degree. Precondition: n > 0, degree > 0 and finite.
double radius_for_mean_degree(const core::Domain& domain, std::size_t n, double degree);

/// The edges of the construction `options` asks for (no report, no repair). Preconditions: those of
/// the construction (ProximityGraphs.hpp: radius > 0 and finite, hops ≥ 1, points strictly inside the
/// domain for delaunay).
EdgeList field_edges(const core::Domain& domain, std::span<const core::Point2> points, const FieldGraphOptions& options);

/// Builds the construction, reports on it and applies the repair policy. Throws FieldGraphError (see
/// the file comment). Preconditions: those of field_edges.
FieldGraph build_field_graph(const core::Domain& domain, std::span<const core::Point2> points,
                             const FieldGraphOptions& options);

/// The report and repair part alone, for edges computed elsewhere: `edges` must form a plane
/// straight-line drawing on `points` (checked exactly when `check_crossings`, else trusted).
/// `type_name` names the construction in messages.
FieldGraph field_graph_from_edges(std::span<const core::Point2> points, const EdgeList& edges, RepairPolicy repair,
                                  const std::string& source, std::string_view type_name, bool check_crossings);

}  // namespace laguerre::scenarios
