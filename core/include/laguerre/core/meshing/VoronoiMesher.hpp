#pragma once
/// @file
/// Anisotropic meshing by refinement of the anisotropic (Labelle–Shewchuk) Voronoi diagram, in the
/// variant of thesis Part II (§2.6–2.8): the Voronoi vertices come from the power diagram of the lifted
/// sites in R⁵ (AnisotropicDiagram.hpp), and the diagram is refined until the triangles dual to its
/// vertices inside Ω triangulate Ω, contain every constraint subsegment and are well shaped.
///
/// Sites. Every site p carries the metric M_p = field(p) and its distance d_p(x) = √((x − p)ᵀM_p(x − p))
/// (AnisotropicDiagram works with the squared distance; every ratio below uses unsquared distances).
/// The initial sites are the endpoints of the constraints (boundary edges and segments), and a
/// constraint is split at every other constraint endpoint lying on it, so that each site on a
/// constraint is a subsegment endpoint.
///
/// Primitives (§2.6–2.7).
///   - Voronoi vertices: `anisotropic_diagram` of all sites (candidate triangles from the regular
///     triangulation in R⁵, conic intersections, kept if no regular-complex neighbour is closer); a
///     vertex is kept when the Domain's exact point location puts it in the closed domain, or when it is
///     within `boundary_tolerance` × its Euclidean radius of ∂Ω (a vertex on the boundary, computed just
///     outside by rounding). T is the set of labels of the kept vertices (the dual triangles).
///   - Encroachment: e = (a, b) is encroached by p when Vor(p) meets [a, b] in the diagram of {a, b, p}.
///     Along z(t) = a + t(b − a), d_a² = t²L_a, d_b² = (1 − t)²L_b and d_p² are quadratics, so this is
///     max_{t∈[0,1]} (min(d_a², d_b²) − d_p²)(t) > 0, evaluated piecewise on either side of the midpoint
///     t* (where d_a = d_b). A maximum within `encroachment_tolerance`·d_a²(t*) of 0 (p's cell touches
///     the segment, as a point on Ruppert's diametral circle does) does not encroach.
///   - Midpoint and breakpoint: the midpoint of e is the point of [a, b] with d_a = d_b; the breakpoint of
///     an encroached e is the point of the closure of [a, b] \ (Vor(a) ∪ Vor(b)) closest to the midpoint
///     (the midpoint itself when another site is closer there, else the nearest root of d_s² − d_a² or
///     d_s² − d_b² over the encroaching sites s).
///   - CONDITIONALLY INSERT(x): if x encroaches a subsegment e, insert the breakpoint of e in the diagram
///     with x added (e was not encroached before, so this is the point of Vor(x) ∩ [a, b] closest to the
///     midpoint), else insert x.
///
/// Rules, in priority order; rule i applies only if no rule j < i does (§2.7):
///   1. a constraint subsegment is encroached: insert its breakpoint;
///   2. a subsegment is not an edge of a triangle of T and its dual Voronoi edge is a complete ellipse
///      (a free constraint endpoint): conditionally insert the second intersection of the bisector
///      conic with the support line of e (the midpoint of e when that intersection does not exist or is
///      outside Ω: numerically a missed vertex; a half of such a split that goes missing again is not
///      split further, the run then ends `stuck`, instead of doubling the missing pieces every round);
///   3. a Voronoi vertex v of label abc is badly shaped, β(v) = r(v)/δ(abc) > B with r(v) = d_a(a, v) and
///      δ the shortest edge, the length of (x, y) being min(d_x(x, y), d_y(x, y)): conditionally insert v;
///   4. a triangle is dual to several Voronoi vertices: conditionally insert the one farthest from its
///      vertices;
///   5. two triangles of T share an edge and overlap (their third vertices are on the same side of it,
///      exact orientation; a triangle with collinear vertices overlaps its neighbours): conditionally
///      insert the Voronoi vertex of the one holding the edge of largest distortion γ(x, y).
///   6. (optional, off by default: Labelle–Shewchuk's size criterion, not in the thesis list) a vertex
///      with r(v) > size_bound: conditionally insert it.
/// When no rule applies the triangles are checked (check_triangulation, and every subsegment an edge):
/// by Theorem 2.7.1 and Lemma 2.7.2 this holds at termination, and a failure (numerically missed
/// vertices) is reported as status `stuck`, never as converged.
///
/// The diagram is kept across rounds (AnisotropicDiagramUpdater: the R⁵ regular triangulation grows and
/// only the candidate triangles around the new sites are recomputed), with the same result as
/// rebuilding it every round (`rebuild_diagram`, kept as the reference the tests compare with).
///
/// Batching. Recomputing the diagram after every insertion costs O(n) per insertion. A round computes
/// the diagram once, finds the first rule that applies, orders its requests (worst first, ties by
/// position) and accepts a request greedily when it is independent of every request accepted before:
/// each request protects the Voronoi vertices that make its rule apply (rule 3: v; rule 4: every vertex
/// of the triangle; rule 5: the vertices of both triangles) and, if it became a breakpoint or is a rule-1
/// breakpoint, the subsegment e and, for a conditional insertion, the two halves e is split into; two
/// requests are independent when neither's insertion point destroys (is within the squared radius of,
/// with relative margin 1e-6) a vertex the other protects, nor encroaches a subsegment the other
/// protects. Then inserting the accepted points one after the other is a sequence of legal
/// applications of the same rule: every protected vertex is still a Voronoi vertex with its label when
/// its point is inserted (a vertex is destroyed only by a new site closer to it than its label), a
/// conditional insertion still encroaches nothing (encroachment involves one new site at a time, and
/// the halves are protected), and a breakpoint is unchanged (no accepted point encroaches its
/// subsegment). The one departure from the one-at-a-time order: a situation of a higher-priority rule
/// created by one point of the batch is handled at the next round rather than before the other points
/// of the batch. Rule 1 cannot be created that way (a conditional insertion never encroaches), and the
/// correctness at termination does not depend on the order. Everything is deterministic: no random
/// numbers, and every ordering has a total tie-break.
///
/// Termination (§2.8) needs K⁴ ≥ (γ² − 1)(1 + γ)⁶ − 1 between neighbours and input angles that are not
/// acute in the metric; otherwise the refinement may not stop, which `max_vertices` turns into the
/// status `max_vertices`.
///
/// Acute input corners (an extension, `corner_shells`, on by default; not in the thesis). Where two
/// constraints meet at less than 90° in the corner's metric M_c — on either side: the diagram is that of
/// the whole plane, so a hole's sharp corner counts too — breakpoints cascade into the corner (each
/// side's new site encroaches the other side's subsegment). As in Ruppert's concentric shells, a
/// subsegment with one such corner c as an endpoint is split instead at the M_c-length from c that is
/// the power of two nearest half its length (a subsegment with two, at its midpoint), so that the sites of
/// both sides sit at equal distances from c and do not encroach each other; and rule 3 leaves a
/// triangle whose angle at c is the input angle (its other vertices on the two constraints), which no
/// refinement can improve. Those triangles are the only ones that may end with β > B.

#include "laguerre/core/diagrams/AnisotropicDiagram.hpp"
#include "laguerre/core/meshing/Domain.hpp"
#include "laguerre/core/meshing/Medit.hpp"
#include "laguerre/core/meshing/MetricField.hpp"

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace laguerre::core {

/// What one round found and did (for instrumentation and tests: see VoronoiMeshOptions::on_round).
struct VoronoiRound {
  std::size_t round = 0;                 ///< 0 for the first round
  std::size_t sites = 0;                 ///< sites when the diagram was computed
  std::array<std::size_t, 7> requests{};  ///< [i]: how many requests rule i (1–6) had; [0] unused
  int rule = 0;                          ///< the rule applied (the first with requests), 0 if none
  std::size_t inserted = 0;              ///< sites inserted by the round
  std::size_t redirected = 0;            ///< of which breakpoints replacing a conditional insertion
};

/// Parameters of the Voronoi refinement (see VoronoiMesher.hpp's file comment).
struct VoronoiMeshOptions {
  double shape_bound = 1.0;             ///< B: largest radius–edge ratio β(v) of a Voronoi vertex
  double size_bound = 0;                ///< rule 6: largest r(v) in the metric (0 or ∞: rule 6 off)
  std::size_t max_vertices = 20000;     ///< stop (status max_vertices) beyond this many sites
  double diagram_tolerance = 1e-9;      ///< AnisotropicOptions::tolerance of the vertex filter
  double encroachment_tolerance = 1e-10;  ///< relative margin of the encroachment test
  double boundary_tolerance = 1e-9;     ///< a vertex this close to ∂Ω (relative to its radius) counts as on it
  bool corner_shells = true;            ///< acute input corners: shell splits and no rule 3 there (see above)
  bool rebuild_diagram = false;         ///< recompute the whole diagram every round (the reference for the update)
  std::vector<Point2> extra_sites;      ///< sites added to the initial constraint endpoints (inside Ω)
  std::function<void(const VoronoiRound&)> on_round;  ///< called after every round, optional
};

/// How a refinement ended.
enum class VoronoiMeshStatus {
  converged,     ///< no rule applies and the dual triangles triangulate Ω with every subsegment
  max_vertices,  ///< stopped at VoronoiMeshOptions::max_vertices
  stuck,         ///< no rule applies but the dual is not a valid triangulation, or nothing could be inserted
};

/// Rule counts and work.
struct VoronoiMeshStats {
  std::size_t encroached = 0;   ///< rule 1: breakpoints of encroached subsegments
  std::size_t ellipse = 0;      ///< rule 2: subsegments whose dual Voronoi edge is a complete ellipse
  std::size_t bad_shape = 0;    ///< rule 3: badly shaped Voronoi vertices
  std::size_t duplicate = 0;    ///< rule 4: triangles dual to several vertices
  std::size_t overlap = 0;      ///< rule 5: overlapping triangles
  std::size_t size = 0;         ///< rule 6: vertices with r(v) above the size bound
  std::size_t redirected = 0;   ///< of the rule 2–6 insertions, those replaced by a breakpoint
  std::size_t rounds = 0;       ///< diagrams computed
  double diagram_seconds = 0;   ///< time spent in anisotropic_diagram
  double seconds = 0;           ///< total time
};

/// The result: the dual triangulation, one metric per vertex, the Voronoi vertex of each triangle.
struct VoronoiMeshResult {
  TriangleMesh mesh;                 ///< sites, dual triangles (counter-clockwise), constraint subsegments
  std::vector<Metric> metrics;       ///< M_p per vertex
  std::vector<Point2> centres;       ///< per triangle, its Voronoi vertex (the farthest if several)
  std::vector<double> shape;         ///< per triangle, β of that vertex
  VoronoiMeshStats stats;            ///< rule counts and work
  VoronoiMeshStatus status = VoronoiMeshStatus::stuck;  ///< how it ended
  std::string message;               ///< "converged", or why not
  /// Whether status is converged.
  bool converged() const { return status == VoronoiMeshStatus::converged; }
};

/// Meshes `domain` for `field` by refinement of the anisotropic Voronoi diagram. Deterministic.
VoronoiMeshResult mesh_with_voronoi(const Domain& domain, const MetricField& field,
                                    const VoronoiMeshOptions& options = {});

/// The site (p, field(p)).
AnisotropicSite site_with_metric(const MetricField& field, Point2 p);

/// The parameter t* ∈ (0, 1) of the midpoint of [a, b]: d_a(a, z) = d_b(b, z) at z = a + t*(b − a).
double midpoint_parameter(const AnisotropicSite& a, const AnisotropicSite& b);

/// max over t ∈ [0, 1] of min(d_a², d_b²) − d_p² at a + t(b − a), and where it is reached: positive iff
/// some point of [a, b] is strictly closer to p than to a and b. {value, t}.
std::array<double, 2> encroachment_margin(const AnisotropicSite& a, const AnisotropicSite& b, const AnisotropicSite& p);

/// Whether p encroaches (a, b): Vor(p) meets [a, b] in the diagram of {a, b, p}, with the relative margin
/// `tolerance` of the file comment.
bool encroaches(const AnisotropicSite& a, const AnisotropicSite& b, const AnisotropicSite& p, double tolerance = 1e-10);

/// The breakpoint of (a, b) among `others` (the other sites; a and b themselves are skipped by
/// position): the parameter t of the point of [a, b] \ (Vor(a) ∪ Vor(b)) closest to the midpoint, or
/// nothing when no site of `others` encroaches (a, b).
std::optional<double> breakpoint_parameter(const AnisotropicSite& a, const AnisotropicSite& b,
                                           const std::vector<AnisotropicSite>& others, double tolerance = 1e-10);

/// β(v) = r(v)/δ(abc) for a Voronoi vertex v of label abc (unsquared distances, see the file comment).
double radius_edge_ratio(const AnisotropicSite& a, const AnisotropicSite& b, const AnisotropicSite& c, Point2 v);

/// Human-readable name of a status ("converged", "max_vertices", "stuck").
std::string to_string(VoronoiMeshStatus status);

}  // namespace laguerre::core
