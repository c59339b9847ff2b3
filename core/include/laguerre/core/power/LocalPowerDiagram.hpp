#pragma once
/// @file
/// Local power cells and the local conditions of thesis §5.2: LPD (Def. 5.2.2) for triangulated discs,
/// the φ-triangulation G(φ) (Def. 5.2.3) and GLPD (Def. 5.2.4) for 3-connected planar graphs.
///
/// Notation. For a vertex v with circle φ(v) = (p(v), σ(v)) and a neighbour w, the half-plane
///     H_w = {x : pow(x, v) ≤ pow(x, w)} = {x : 2 x·(p(w) − p(v)) ≤ z(w) − z(v)},  z = |p|² − σ²,
/// has outward normal p(w) − p(v). The *local cell* of v is the intersection of H_w over the
/// neighbours w of v: the cell of v in the power diagram of v and its neighbours only. Its edges are
/// exactly the adjacencies Cell(v) ∩ Cell(w) of that local diagram.
///
/// Exactness. Every decision below is taken with the filtered exact predicates of Predicates.hpp on
/// the stored doubles; no floating-point rounding enters an outcome. Only `local_cell_polygon`
/// (pictures) computes in doubles.
///
/// Binary128. The checks also take circles with binary128 coordinates (Circle128, the coordinates of a
/// LayoutArithmetic::binary128 layout): the same code, templated on the circle type, decided by the
/// same exact predicates on those numbers' exact values.
///
/// Degenerate inputs. LPD is decided on the embedding as stored: an edge of zero length (three
/// bisectors through one point) is *not* an adjacency. GLPD is decided, as Def. 5.2.3 prescribes, on
/// an infinitesimally perturbed embedding ("Simulation of Simplicity"): the lifted height
/// z(u) = |p(u)|² − σ(u)² of every vertex u is raised by ε^(k(u)), where k orders the vertices by
/// increasing user id, so a smaller id receives an infinitely larger perturbation (its circle shrinks
/// infinitely more). The φ-triangulation and the LPD test inside GLPD use the same perturbation, so
/// the exactly degenerate target of the packing (each face's circles orthogonal to one face circle)
/// satisfies GLPD, as Theorem 5.2.6 states, and every node of a face computes the same G(φ).

#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// Outcome of a local check: `holds`, or the first reason it fails (in the order the checks run).
enum class LocalCondition : std::uint8_t {
  holds,                        ///< the condition holds at the vertex
  site_outside_cell,            ///< p(v) is not in the closed local cell of v
  neighbour_order,              ///< the neighbours' directions do not turn strictly left once around v
  missing_edge,                 ///< some neighbour's cell does not share an edge of positive length with v's
  boundary_vertex_inside_disc,  ///< Cell(v) ∩ Cell(w1) ∩ Cell(wn) is a point in the closed unit disc
  face_not_convex,              ///< an inner face incident to v is not strictly convex (GLPD only)
  cell_crosses_face,            ///< the local cell in G meets a face edge not incident to v (GLPD only)
  unrepresentable,              ///< a circle involved has a NaN or infinite coordinate or a negative radius
};

/// Name of a LocalCondition ("holds", "site_outside_cell", …).
std::string_view to_string(LocalCondition c);

/// LPD(v, φ) (Def. 5.2.2) from what a node knows: its circle and its neighbours' circles.
///
/// `ccw_neighbours` lists the neighbours' circles in counter-clockwise order. For an interior vertex
/// the order is cyclic and may start anywhere. For a `boundary` vertex it must run w1 … wn, where w1
/// and wn are the neighbours along the boundary and the outer face lies between wn and w1 going
/// counter-clockwise (see `lpd_first_dart`).
///
/// Decides exactly whether (1) p(v) lies in the closed local cell, (2) the local cell has an edge of
/// positive length on every H_wi, these edges following the order w1 … wn counter-clockwise (cyclically
/// for an interior vertex, whose cell must then be bounded), and (3) for a boundary vertex the corner
/// Cell(v) ∩ Cell(wn) ∩ Cell(w1) on the outer-face side is empty or strictly outside the unit disc.
/// Cost: 4·deg filtered predicates, no heap allocation.
LocalCondition check_lpd_at(const Circle& v, std::span<const Circle> ccw_neighbours, bool boundary);
/// check_lpd_at on binary128 circles.
LocalCondition check_lpd_at(const Circle128& v, std::span<const Circle128> ccw_neighbours, bool boundary);

/// As `check_lpd_at`, decided on the symbolically perturbed embedding (see the file comment):
/// `v_priority` and `priorities[i]` are the user ids of v and of `ccw_neighbours[i]` (distinct).
/// Differs from `check_lpd_at` only where an exact predicate is zero. The unit-disc test of the
/// boundary rule is not perturbed: a corner exactly on the unit circle fails.
LocalCondition check_lpd_at_perturbed(const Circle& v, std::uint64_t v_priority,
                                      std::span<const Circle> ccw_neighbours,
                                      std::span<const std::uint64_t> priorities, bool boundary);

/// The dart v→w1 from which v's neighbours are listed for LPD: for a boundary vertex the dart just
/// after (counter-clockwise) the dart whose left face is the outer face, so that the outer face lies
/// between wn and w1; for an interior vertex `first_dart(v)`. O(deg v).
Dart lpd_first_dart(const PlanarGraph& g, Vertex v);

/// LPD(v, φ) in g, a triangulated disc (every inner face a triangle). O(deg v) predicates.
LocalCondition check_lpd(const PlanarGraph& g, const CircleEmbedding& phi, Vertex v);
/// check_lpd on binary128 circles.
LocalCondition check_lpd(const PlanarGraph& g, const CircleEmbedding128& phi, Vertex v);

/// GLPD(v, φ) (Def. 5.2.4) in g, a 3-connected planar graph: the inner faces incident to v are
/// strictly convex (else `face_not_convex`); LPD(v) holds in G(φ) on the perturbed embedding (else the
/// LPD reason); and for each non-triangle inner face f = (v, w1 … wn) the local cell of v in g
/// (g-neighbours only, unperturbed, closed) meets none of the closed edges [wi, wi+1], i = 1 … n−1,
/// i.e. it crosses ∂f only along [wn v] and [v w1] (else `cell_crosses_face`).
/// Cost: O(Σ over incident faces f of |f|·(deg v + |f|)) predicates.
LocalCondition check_glpd(const PlanarGraph& g, const CircleEmbedding& phi, Vertex v);
/// check_glpd on binary128 circles.
LocalCondition check_glpd(const PlanarGraph& g, const CircleEmbedding128& phi, Vertex v);

/// `check_lpd` if every inner face of g is a triangle, `check_glpd` otherwise. The dispatch is O(1):
/// in a simple graph every inner face has at least 3 sides, so all are triangles iff
/// 2·E − |outer| = 3·(F − 1).
LocalCondition check_local(const PlanarGraph& g, const CircleEmbedding& phi, Vertex v);
/// check_local on binary128 circles.
LocalCondition check_local(const PlanarGraph& g, const CircleEmbedding128& phi, Vertex v);

/// `check_local` at every vertex, indexed by Vertex.
std::vector<LocalCondition> check_all(const PlanarGraph& g, const CircleEmbedding& phi);
/// check_all on binary128 circles.
std::vector<LocalCondition> check_all(const PlanarGraph& g, const CircleEmbedding128& phi);

/// Whether the closed polygon `ccw_polygon` (at least 3 centres) is strictly convex and
/// counter-clockwise: every corner a strict left turn and the boundary winding exactly once. Exact.
bool is_strictly_convex(std::span<const Circle> ccw_polygon);
/// is_strictly_convex on binary128 centres.
bool is_strictly_convex(std::span<const Circle128> ccw_polygon);

/// Diagonals of the regular triangulation (dual of the power diagram) of the circles of a strictly
/// convex counter-clockwise polygon, on the perturbed embedding with `priorities` (distinct user ids,
/// one per corner): pairs (i, j) of polygon indices, i < j, sorted. Every corner is a vertex of it
/// (Lemma 5.2.1), so this is a triangulation of the polygon. The result depends only on the circles
/// and priorities, not on which corner the polygon starts at. O(|polygon|²) predicates.
std::vector<std::pair<std::uint32_t, std::uint32_t>> regular_triangulation_diagonals(
    std::span<const Circle> ccw_polygon, std::span<const std::uint64_t> priorities);

/// Diagonals of G(φ) (Def. 5.2.3) inside each non-triangle inner face of g, as vertex pairs (u, w)
/// with u < w, grouped by face in face order. Precondition: every such face is strictly convex
/// in `phi` (InternalError otherwise; check_glpd reports face_not_convex as an outcome).
std::vector<std::pair<Vertex, Vertex>> phi_triangulation_diagonals(const PlanarGraph& g, const CircleEmbedding& phi);

/// G(φ): g with the diagonals of `phi_triangulation_diagonals`, same vertices, ids and outer face.
/// Precondition: every non-triangle inner face is strictly convex in `phi` (InternalError otherwise).
PlanarGraph phi_triangulation(const PlanarGraph& g, const CircleEmbedding& phi);

/// The local cell of v (power cell among v and its g-neighbours) clipped to the square
/// [−box_half_width, box_half_width]², as a counter-clockwise polygon in doubles — for pictures only
/// (empty if the clipped cell is empty).
std::vector<Point2> local_cell_polygon(const PlanarGraph& g, const CircleEmbedding& phi, Vertex v,
                                       double box_half_width = 2.0);

}  // namespace laguerre::core
