#pragma once
/// @file
/// Locally uniform anisotropic meshes by refinement of stars (thesis chapter 3; Boissonnat, Wormser,
/// Yvinec, SoCG 2008), in the plane.
///
/// Every site v carries its metric M_v = field(v) and its *star* S_v: the triangles incident to v in
/// the Delaunay triangulation of all sites for M_v (the Euclidean Delaunay triangulation of F_v(V),
/// F_v = M_v^{1/2}), constrained by the boundary and wall subsegments and restricted to the domain.
/// Stars of different sites disagree in general; a triangle is *consistent* when it belongs to the
/// stars of its three vertices. Refinement inserts points until every triangle of every star is
/// consistent and good, and the mesh is then the union of the stars: each vertex's neighbourhood in the
/// mesh is exactly its own (constrained) Delaunay star for its own metric.
///
/// How a star is computed (core/src/meshing/detail/LocalDelaunay.hpp): the sites of a growing M_v-ball
/// around v keep their own coordinates, and M_v enters only the in-circle predicate (the lifting
/// xᵀM_v x; exact: static filter, intervals, rationals), orientation is that of the plane. The sites
/// are never moved by F_v, so sites collinear on a boundary edge stay collinear for every metric.
/// Every subsegment with both endpoints in the ball is a constraint (the plain Delaunay triangulation
/// is used when they are all Delaunay edges already, the usual case): encroachment is only tested on
/// Ω's side of a boundary subsegment (rule 1), so a site across a hole may lie in its diametral ball,
/// and only the constraint keeps the star from crossing the hole. The fan's triangles are in or out of
/// Ω by the boundary subsegments at v (Ω on their left; the side changes only across them), a
/// combinatorial and exact test. A star is certified when every kept triangle's M_v-circumball lies in
/// the ball, v's own subsegments are constraints, no subsegment leaving the ball crosses a kept
/// triangle (exact orientations), and an open fan's gap is outside Ω.
///
/// Rules, in priority order (a rule applies only when no earlier one does), following §3.4 for 2D:
///   1. encroachment: a boundary/constraint subsegment whose M_a- or M_b-diametral ball (a, b its
///      endpoints) contains a site, or whose metric length exceeds 2·size_bound, or whose endpoints'
///      distortion exceeds γ₀, is split at its midpoint;
///   2. distortion: a triangle with γ(τ) ≥ γ₀ — γ(τ) is estimated as the largest distortion between
///      the star's site and the other vertices and the M_v-circumcentre;
///   3. size: a triangle with M_v-circumradius above size_bound (the size the field prescribes);
///   4. radius–edge ratio above ρ₀ (in M_v);
///   5. inconsistency: a triangle of S_v missing from the star of one of its other vertices.
/// Rules 2–5 refine τ ∈ S_v by a point picked at random (seeded) in its *picking region*, the M_v-ball
/// of radius δ·R_v(τ) around its M_v-circumcentre (§3.4, after Chew and Li–Teng), which avoids the
/// cascades of quasi-cospherical configurations; "insert or snap": a point that encroaches a
/// subsegment, or falls outside the domain, splits that subsegment instead.
///
/// Optional corner rule (`StarMeshOptions::no_lonely_corners`), applied only once rules 1–5 are all
/// satisfied: a site v incident to a single triangle (v, a, b) — a boundary corner whose two
/// subsegments va, vb are joined by the chord ab, so that v has degree 2 and {a, b} separates it from
/// the rest of the mesh — gets a second triangle. In the stretched frame of M_v (F_v = M_v^{1/2}), with
/// s = |va|, t = |vb|, θ the corner angle and d the unit bisector of the corner:
///   6. the point p = v + r·d with r = √(L·U), L = max(s, t)·cos(θ/2), U = the length of the chord of
///      the M_v-circumcircle of (v, a, b) along d, is inserted when L < U (insert or snap, as above).
///      Points of the bisector at distance ≥ L are outside both M_v-diametral balls of va and vb (so p
///      does not encroach them in M_v), points at distance < U are inside the circumcircle (so p
///      destroys the lonely triangle and becomes v's neighbour: v's star gets (v, a, p) and (v, p, b)).
///      L < U always holds for θ ≥ 90° in the metric (the hypothesis of the termination theorem:
///      2·max(s, t)·cos²(θ/2) < s + t); when L ≥ U (only possible at a sharper corner with unequal
///      subsegments) the longer of va, vb is split instead, which equalizes them. Rules 1–5 then run
///      again, and the rule is re-checked at the next convergence.
/// The rule only adds points, so every guarantee of rules 1–5 still holds when the refinement
/// converges; its termination is not covered by the thesis's theorem (the cap `max_vertices` bounds
/// it). With the rule on, every boundary vertex of the merged mesh has degree ≥ 3: a mesh of a domain
/// with holes is then, barring a rare chord between two boundary vertices, a 3-connected plane graph
/// whose holes are inner non-triangular faces (see core/graph/GraphKind.hpp). Off by default: the
/// default refinement is the thesis's, and meshes for a seed stay as they were.
/// 3D (with the sliver rule 4 of §3.4): StarMesher3.hpp.
///
/// Honest gaps.
///  - Fixed: sites on an outer edge not parallel to a metric axis lost their collinearity when stars
///    were computed on the stretched points F_v(p) (rounding), a flat sliver with a non-finite
///    circumcentre entered a star and refining it threw std::domain_error (the diamond |x| + |y| ≤ 1 at
///    uniform:0.2:0.2); and square-with-holes at uniform:0.12:0.06:0 reported "converged" with "a hole
///    in the mesh": a site behind the triangular hole's corner (0.7, 0.8) lay in the diametral ball of
///    a subsegment of the other edge (allowed by the one-sided encroachment), so the unconstrained star
///    had a triangle across the hole, kept by a centroid test. Both are gone with the stars above.
///  - Split points are rounded midpoints: on an edge with inexact direction (the hexagon's √3/2) they
///    lie up to an ulp off the input edge, so the mesh covers Ω up to slivers of that width (the area
///    check of check_triangulation has a relative tolerance of 1e-9). Triangles between such a chain of
///    subsegments and the true edge are classified by the subsegments, not by the input polygon.
///  - If a star still held a triangle whose circumcentre is not finite in doubles, the refinement
///    stops with a non-converged status instead of throwing (a safeguard; not seen in the tests).
///  - mesh_with_stars checks the merged mesh with check_triangulation before reporting "converged";
///    a failure there would be reported as a non-converged status (never seen since the fix).
///  - Termination is the thesis's theorem (corners of at least 90° in the metric, δ small); outside its
///    hypothesis the cap `max_vertices` turns a cascade into a status (e.g. the diamond under
///    thesis:0.1:4:0.2:0.5, whose top and bottom corners are acute in the metric: rule 1 splits the
///    edges there until the cap). Milder violations may still converge (the diamond at
///    uniform:0.2:0.1:0, corners of 53° in the metric, does).
///  - Also fixed on the way: the test that an open fan's gap lies outside Ω took the gap's bisector as
///    ±(w + u) for its unit edge directions, which vanishes for a boundary vertex between two collinear
///    neighbours (every split point of an edge): the test then failed or followed rounding noise, and
///    the star's ball grew, often to the whole domain (a noisy direction could also have certified an
///    incomplete star). The bisector is now w − u turned by 90°. Stars come out the same with 3-5×
///    fewer points queried (tools/bench/mesh.sh --quick: same meshes, 4-7× faster).
///  - The in-circle predicate with the metric costs about 10% more per point than CGAL's Euclidean one
///    (measured where both give the same mesh: the unit square under shock:0.01:0.1:0.05:0.5).
///  - Meshes for a given seed changed with these fixes where stars differed: near holes (e.g.
///    square-with-holes under the default field `shock`, 8237 vertices instead of 8786) and where
///    cocircular ties are now broken on exact coordinates (the square at uniform:0.1:0.1, 84 instead
///    of 83). The bench's shock-layer meshes of the square keep their vertex and triangle counts and
///    quality figures.

#include "laguerre/core/meshing/Domain.hpp"
#include "laguerre/core/meshing/Medit.hpp"
#include "laguerre/core/meshing/MetricField.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace laguerre::core {

/// Parameters of the star refinement (see StarMesher.hpp's file comment).
struct StarMeshOptions {
  double size_bound = 1.0;          ///< largest M_v-circumradius of a triangle (in the field's units)
  double radius_edge_bound = 1.0;   ///< ρ₀: largest M_v-circumradius / shortest M_v-edge (1 ⇔ 30°)
  double distortion_bound = 1.5;    ///< γ₀
  double picking_ratio = 0.1;       ///< δ: radius of the picking region relative to the circumradius
  std::size_t max_vertices = 1000000;  ///< stop (not converged) beyond this many sites
  std::uint64_t seed = 1;           ///< seed of the picking
  bool no_lonely_corners = false;   ///< apply rule 6: no site incident to a single triangle (file comment)
  std::function<void(std::size_t)> progress;  ///< called with the vertex count every 1000 insertions, optional
};

/// How many times each rule refined something, and the work done.
struct StarMeshStats {
  std::size_t encroachment = 0;   ///< rule 1 splits
  std::size_t distortion = 0;     ///< rule 2 insertions
  std::size_t size = 0;           ///< rule 3 insertions
  std::size_t shape = 0;          ///< rule 4 insertions
  std::size_t inconsistency = 0;  ///< rule 5 insertions
  std::size_t snapped = 0;        ///< picked points replaced by a subsegment split
  std::size_t corners = 0;        ///< rule 6 insertions or splits (lonely corners refined)
  std::size_t star_updates = 0;   ///< star recomputations
  std::size_t star_attempts = 0;  ///< local Delaunay triangulations built (a star may need several)
  std::size_t star_points = 0;    ///< points in those triangulations, summed
  std::size_t consistency_sweeps = 0;  ///< full passes looking for inconsistent triangles
};

/// The result: the merged mesh, one metric per vertex, statistics and status.
struct StarMeshResult {
  TriangleMesh mesh;             ///< vertices, consistent triangles (counter-clockwise), constraint subsegments
  std::vector<Metric> metrics;   ///< M_v per vertex
  StarMeshStats stats;           ///< rule counts
  bool converged = false;        ///< every star consistent, every rule met, and check_triangulation passes
  std::string status;            ///< "converged", or why not
};

/// Meshes `domain` for `field` by star refinement. Deterministic for a given seed.
StarMeshResult mesh_with_stars(const Domain& domain, const MetricField& field, const StarMeshOptions& options = {});

/// Checks that `mesh` triangulates `domain`: counter-clockwise triangles, every edge in one or two
/// triangles, edges in one triangle exactly the constraint subsegments on the boundary, and total
/// area equal to the domain's (relative 1e-9). Returns "" when valid, else the first problem found.
std::string check_triangulation(const TriangleMesh& mesh, const Domain& domain);

}  // namespace laguerre::core
