#pragma once
/// @file
/// Every sensor of a field routed: the link graph (unit-disk or quasi-unit-disk), the attachment of
/// the sensors outside the packed 3-connected core, and routing measured over all sensor pairs.
///
/// The rule (docs/sensor-attachment.md has the design and the measurements):
///  - The *links* are the radio graph every sensor has: UDG(R), or the quasi-unit-disk graph
///    QUDG(ρR, R, p) (a pair at distance ≤ ρR is a link, one in (ρR, R] is a link with probability p,
///    decided per pair by a hash of the seed and the two ids, none beyond R).
///  - The *planarization* is the field's planar spanner (Gabriel, RNG, LDel^(k)) on all sensors,
///    intersected with the links; the *core* is its 3-connected core (FieldGraph.hpp), packed to GLPD.
///  - *Attachment*: in the link component of the core, a sensor at hop distance d ≥ 1 from the core
///    (in the link graph) takes as parent its smallest-id link neighbour at distance d − 1 and adopts
///    that neighbour's anchor; core sensors are their own anchors (depth 0). Every other link component
///    is one tree of the same rule rooted at its smallest-id sensor. The trees are the routes inside an
///    attachment: a packet goes up to the anchor, greedy power on the core to the target's anchor, then
///    down the target's tree; two sensors of one tree meet at their lowest common ancestor.
///  - Pairs in different link components are *disconnected*: no scheme can deliver them. They are
///    counted (AllPairsStats::disconnected) and excluded from the delivery rate and the stretch, whose
///    reference is the BFS hop distance in the link graph.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/core/routing/Router.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/fields/ProximityGraphs.hpp"

namespace laguerre::scenarios {

/// Radio links between sensors.
struct LinkOptions {
  bool quasi = false;        ///< false: UDG(radius); true: QUDG(inner_ratio · radius, radius, probability)
  double radius = 0;         ///< R, > 0
  double inner_ratio = 0.75; ///< ρ in (0, 1]
  double probability = 0.5;  ///< p in [0, 1]
  std::uint64_t seed = 0;    ///< decides the links in (ρR, R]
};

/// The link edges of `options` (sorted, u < v). Symmetric and deterministic in (seed, u, v).
EdgeList link_edges(std::span<const core::Point2> points, const LinkOptions& options);

/// Edges in both sorted lists.
EdgeList common_edges(const EdgeList& a, const EdgeList& b);

/// How every sensor hangs on the core (see the file comment). Indexed by sensor (deployment index).
struct Attachment {
  std::vector<core::Vertex> anchor;      ///< the core sensor (or component root) of its tree
  std::vector<core::Vertex> parent;      ///< next hop towards the anchor; itself for an anchor
  std::vector<std::uint32_t> depth;      ///< hops to the anchor
  std::vector<std::uint32_t> component;  ///< link component label (smallest member)
  std::vector<core::Vertex> core_vertex; ///< vertex of the core graph, or core::none
  std::size_t attached = 0;              ///< sensors outside the core, in the core's link component
  std::size_t stray = 0;                 ///< sensors in other link components
};

/// A deployed field with all its sensors: positions, links, planarization and attachment.
struct SensorNetwork {
  std::vector<core::Point2> points;  ///< every sensor, by deployment index
  EdgeList links;                    ///< the link graph
  EdgeList planar;                   ///< the planarization (spanner ∩ links) on all sensors
  Attachment attachment;             ///< filled by attach_to_core
};

/// The attachment of the file comment for `sensors` sensors joined by `links`; the core's vertex ids
/// are sensor indices (below `sensors`). Cost O(n + links).
Attachment attach_to_core(std::size_t sensors, const EdgeList& links, const core::PlanarGraph& core);

/// Routes one packet between two sensors; the Route's path lists sensor ids.
using SensorRouter = std::function<core::Route(core::Vertex source, core::Vertex target)>;

/// Greedy power with attachment (not thread-safe: one router per thread): up the source's tree, greedy power on `core` with `phi` between the
/// anchors, down the target's tree (see the file comment).
SensorRouter attached_router(const SensorNetwork& net, const core::PlanarGraph& core, const core::CircleEmbedding& phi);

/// Scheme `s` on the planarization of all sensors, at their physical positions (one plane drawing
/// per component of the planarization; a packet whose target lies in another component ends dead_end
/// where it starts).
class PlanarizationRouter {
public:
  explicit PlanarizationRouter(const SensorNetwork& net);
  /// The router of scheme `s` (valid while this object lives; not thread-safe).
  SensorRouter router(core::Scheme s) const;

private:
  struct Part {
    core::PlanarGraph graph;
    core::CircleEmbedding positions;
  };
  std::vector<Part> parts_;
  std::vector<std::unique_ptr<core::Router>> routers_;  // one per part, bound to it
  std::vector<std::size_t> part_of_;        // per sensor; SIZE_MAX for an isolated sensor
  std::vector<core::Vertex> local_;         // per sensor, its vertex in its part
};

/// Routing over sensor pairs. Delivery and stretch are over the connected pairs only.
struct AllPairsStats {
  std::size_t pairs = 0;         ///< pairs selected among all sensors
  std::size_t disconnected = 0;  ///< of which in different link components (excluded below)
  std::size_t delivered = 0;     ///< connected pairs delivered
  double delivery_rate = 0;      ///< delivered / (pairs − disconnected); NaN without connected pairs
  double stretch_mean = 0;       ///< hops / BFS hops in the link graph, delivered pairs (NaN if none)
  double stretch_p95 = 0;        ///< 95th percentile (nearest rank)
  double stretch_max = 0;        ///< largest
  double hops_mean = 0;          ///< mean hops of delivered pairs
  std::size_t invalid_routes = 0;  ///< delivered routes with a hop that is not a link (a bug if > 0)
};

/// Routes the pairs `selection` designates among all sensors (core::select_pairs) with every router;
/// one BFS in the link graph per distinct source serves all of them. Deterministic.
std::vector<AllPairsStats> evaluate_all_pairs(const SensorNetwork& net, std::span<const SensorRouter> routers,
                                              const core::PairSelection& selection);

}  // namespace laguerre::scenarios
