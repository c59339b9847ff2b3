#pragma once
/// @file
/// GLPD (thesis Def. 5.2.4) decided from what one node can gather G-face-locally: its circle, its
/// neighbours' circles and the circles of every vertex of its incident faces. It makes the same
/// exact decision, with the same first failing reason, as core::check_glpd on the whole graph.

#include <cstdint>
#include <span>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"

namespace laguerre::protocols {

/// The face of one wedge (neighbour i, neighbour i+1) around a node, for `check_glpd_local`.
struct GlpdWedge {
  bool outer = false;                        ///< the wedge is the outer face (then the spans are ignored)
  std::span<const core::Circle> circles;     ///< the face's circles, counter-clockwise walk from the node
  std::span<const std::uint64_t> ids;        ///< the matching vertex ids (the perturbation priorities)
};

/// GLPD at a node of a 3-connected plane graph from G-face-local data.
///
/// `v`, `v_id`: the node's circle and id. `wedges[i]` is the face left of the dart towards neighbour i
/// (between neighbour i and i+1, counter-clockwise), whose walk is (v, neighbour i, …, neighbour i+1);
/// `neighbours`/`neighbour_ids` are the neighbours' circles and ids in the same order (from the
/// neighbour that core::PlanarGraph::first_dart names, for the same first failing reason as core).
/// For a boundary node, `outer_gap` is the index of the outer wedge.
///
/// Argument of equality with core::check_glpd: the three steps run in the same order over the same
/// faces and call the same exact predicates (is_strictly_convex; check_lpd_at_perturbed, i.e. the
/// perturbed LPD core; segment_meets_power_cell). The only difference is how the diagonals of G(φ) at
/// v are found: core walks the fan of lower-hull apices from v, we take the diagonals of
/// core::regular_triangulation_diagonals that contain corner 0 (= v), by increasing corner index,
/// which is counter-clockwise in the wedge. After the perturbation the regular triangulation of a
/// strictly convex polygon is unique (no four lifted points are coplanar), so both list the same
/// diagonals in the same order, and every decision is exact.
core::LocalCondition check_glpd_local(const core::Circle& v, std::uint64_t v_id, std::span<const core::Circle> neighbours,
                                      std::span<const std::uint64_t> neighbour_ids, bool boundary,
                                      std::uint32_t outer_gap, std::span<const GlpdWedge> wedges);

}  // namespace laguerre::protocols
