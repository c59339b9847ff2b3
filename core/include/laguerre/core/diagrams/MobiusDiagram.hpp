#pragma once
/// @file
/// Möbius diagrams of the plane (thesis §2.1.1) by linearization (Thm 2.1.1), and multiplicatively
/// weighted Voronoi diagrams as their special case μ = 0, λ = 1/w².
///
/// Linearization. On the paraboloid Q = {(x, z) : z = |x|²} of R³ the power to the sphere Σ_i of centre
/// (λ_i p_i, (1 − λ_i)/2) and squared radius R_i = λ_i²|p_i|² + ((1 − λ_i)/2)² − λ_i|p_i|² + μ_i equals
/// δ_i(x) + z²: the common term z² does not change the minimum, so the Möbius diagram is the vertical
/// projection of the power diagram of the Σ_i restricted to Q. Every combinatorial decision is exact
/// for the input doubles (filtered: interval arithmetic, then exact rationals):
/// - the 3D regular triangulation of the Σ_i (CGAL::Regular_triangulation_3 on lazy exact numbers: the
///   Σ_i are not rounded) gives the hidden sites (empty cells; more sites may have empty cells: their
///   power cell misses Q; all are reported in `empty_sites()`) and `locate` (exact point location);
/// - the *vertices* are the points where a power edge (dual of a triangle ijk) crosses Q: a point of
///   the power line ∩ Q (coordinates a + b√D, D rational) is a vertex when neither apex of the two
///   tetrahedra on ijk is strictly closer; an apex at equal distance means four or more sites meet
///   there, and such raw vertices are merged through the tetrahedra they tie with (one vertex, exactly);
/// - the *edges* lie on the bisectors of the triangulation's edges ij: a circle (λ_i ≠ λ_j; the site
///   with the larger λ is inside) or a line (λ_i = λ_j); whether the bisector just before and just
///   after each vertex on it belongs to the cells of i and j is decided exactly (the sign of the
///   derivative of δ_k − δ_i along the bisector for the other sites k at the vertex, or of δ_k − δ_i
///   elsewhere on the bisector at a tangency), and for a bisector without vertices at one of its points;
/// - the order of the ends of unbounded edges along the frame, where the doubles cannot tell, is their
///   exact order at infinity.
/// What stays in doubles is the geometry (vertex coordinates, rounded once from the exact values;
/// circle centres and radii) and the order of the vertices along one bisector by their double angle:
/// two distinct vertices closer than the doubles resolve may be ordered wrongly, which `is_valid`
/// reports ("ordered wrongly in doubles").
///
/// Input range: every site's lifted sphere (the centre's coordinates λx, λy, (1 − λ)/2 and the weight)
/// must be at most max_lifted_magnitude = 1e75 in magnitude (InputError otherwise, require_liftable):
/// the predicates multiply up to four such numbers, which then stay within double range, so the
/// interval filter works instead of falling back to exact arithmetic everywhere.
///
/// Cells. Unbounded pieces (rays, lines: only between sites of equal smallest λ) are clipped to the
/// *frame*, the smallest box containing the requested box, every vertex and every bounded edge, grown
/// by 5 %; the frame's sides become boundary pieces with no neighbour. Every cell is then a set of
/// connected components, each an outer boundary (counter-clockwise, the cell on the left) with holes
/// (clockwise). A Möbius cell may be disconnected and not simply connected (thesis Fig. 2.1).
///
/// Degenerate inputs: equal sites keep one representative (the others are hidden); all λ equal gives a
/// power diagram (a 2-dimensional triangulation in R³, straight edges); collinear lifted centres give a
/// 1-dimensional triangulation (parallel edges, no vertices); λ may be any real (λ ≤ 0 is accepted: the
/// linearization does not need λ > 0), but the sites must be finite.
///
/// Weakly hidden sites. A site k with δ_k = (1 − t) δ_i + t δ_j for two other sites i, j and some
/// 0 < t < 1 (δ_k − δ_i and δ_k − δ_j proportional with opposite signs: the three sites have one common
/// bisector, e.g. (0, 0, 1, 1), (2, 0, 1, 1), (1, 0, 1, 0) on x = 1) is never strictly nearest: δ_k ≥
/// min(δ_i, δ_j), with equality only on the bisector of i and j. Its cell has no interior (at most a piece
/// of that bisector, which is the edge of i and j). When i and j are neighbours of k in the lifted
/// triangulation (always the case when k's lifted power cell is a piece of plane, i.e. its cell a
/// curve piece), k is *weakly hidden*: it is removed from the triangulation (no other cell changes), listed
/// in `hidden_sites()`, `weakly_hidden_sites()` and `empty_sites()`, never returned by `locate`, and the
/// edge of i and j is built as for any two neighbours. Decided exactly (interval filter, then
/// rationals). When no two neighbours of k give such a combination but two other sites do, k's lifted
/// cell has dimension at most 1 (its cell is at most two points): k is kept in the triangulation, with an
/// empty cell, like any site whose cell is a point.

#include <memory>
#include <string>
#include <vector>

#include "laguerre/core/diagrams/AffineDiagram.hpp"

namespace laguerre::core {

/// Largest magnitude of a lifted sphere's centre coordinate or weight (see the file comment).
inline constexpr double max_lifted_magnitude = 1e75;

/// The largest magnitude among the lifted sphere's centre coordinates λx, λy, (1 − λ)/2 and its weight
/// λ(λ − 1)|p|² + ((1 − λ)/2)² + μ, in doubles (infinite when they overflow).
double lifted_magnitude(const MobiusSite& s);

/// Throws InputError at `source`:`line` naming `what` (e.g. "site 3") when the lifted sphere of `s`
/// exceeds max_lifted_magnitude.
void require_liftable(const MobiusSite& s, const std::string& source, std::size_t line, const std::string& what);

/// A piece of curve: an arc of circle or a straight segment, oriented from `from` to `to`.
struct CurvePiece {
  bool is_arc = false;  ///< arc of circle (else segment)
  Point2 from;          ///< start point
  Point2 to;            ///< end point (equal to `from` for a full circle)
  Point2 centre;        ///< arc: centre
  double radius = 0;    ///< arc: radius
  double start = 0;     ///< arc: angle of `from` around the centre (radians)
  double sweep = 0;     ///< arc: signed angle swept (positive counter-clockwise; ±2π for a full circle)

  /// Points along the piece, from `from` to `to` inclusive; arcs sampled every `max_step` radians or
  /// finer, so that the chords stay within `max_error` of the arc.
  std::vector<Point2> sample(double max_step = 0.05, double max_error = 1e300) const;
  /// The piece traversed backwards.
  CurvePiece reversed() const;
  /// Contribution ½∮(x dy − y dx) of the piece to the signed area of a closed loop, in coordinates
  /// relative to `origin` (a point near the loop keeps the rounding relative to the loop's size).
  double area_term(Point2 origin = {}) const;
  /// Point halfway along the piece.
  Point2 midpoint() const;
};

/// A vertex of a Möbius diagram: a point equidistant from three sites, nearer than every other site.
struct MobiusVertex {
  Point2 point;                      ///< position
  std::array<SiteIndex, 3> sites{};  ///< the three sites, increasing
};

/// An edge of a Möbius diagram between sites a < b: an arc of their bisector circle, a full circle, or a
/// segment of their bisector line (clipped to the frame when unbounded).
struct MobiusEdge {
  SiteIndex a = no_site;       ///< first site
  SiteIndex b = no_site;       ///< second site
  CurvePiece curve;            ///< geometry; for an arc, counter-clockwise
  std::size_t from = npos;     ///< vertex index at curve.from, npos for a frame point or a full circle
  std::size_t to = npos;       ///< vertex index at curve.to, npos for a frame point or a full circle
  SiteIndex left = no_site;    ///< the site on the left of the curve as oriented (a or b)
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);  ///< "no vertex"
};

/// One piece of a cell's boundary: the curve (the cell on its left) and the site across it.
struct BoundaryPiece {
  CurvePiece curve;                ///< oriented with the cell on the left
  SiteIndex across = no_site;      ///< the neighbouring site, no_site for the frame
  std::size_t edge = MobiusEdge::npos;  ///< index in edges(), npos for the frame
};

/// A closed boundary curve of a cell.
struct BoundaryLoop {
  std::vector<BoundaryPiece> pieces;  ///< consecutive pieces
  bool closed = true;                 ///< whether the last piece ends where the first starts
  /// Signed area enclosed (positive counter-clockwise), summed relative to `origin`.
  double area(Point2 origin = {}) const;
  /// Polyline through the loop (arcs sampled as in CurvePiece::sample).
  std::vector<Point2> polyline(double max_step = 0.05, double max_error = 1e300) const;
};

/// A connected component of a cell: the outer boundary and its holes.
struct CellComponent {
  BoundaryLoop outer;               ///< counter-clockwise
  std::vector<BoundaryLoop> holes;  ///< clockwise
  /// Area of the component (outer area plus the negative hole areas), summed relative to `origin`.
  double area(Point2 origin = {}) const;
};

/// Möbius diagram of Möbius sites by linearization; see the file comment.
class MobiusDiagram {
 public:
  /// Builds the diagram of `sites` (finite values, lifted spheres within max_lifted_magnitude; throws
  /// InputError otherwise); `box` is the
  /// requested window (the frame contains it).
  MobiusDiagram(std::vector<MobiusSite> sites, const Box& box);
  /// Destructor.
  ~MobiusDiagram();
  /// Move constructor.
  MobiusDiagram(MobiusDiagram&&) noexcept;
  /// Move assignment.
  MobiusDiagram& operator=(MobiusDiagram&&) noexcept;

  /// The input sites.
  const std::vector<MobiusSite>& sites() const;
  /// The frame: the box containing every bounded feature (see the file comment).
  const Box& frame() const;
  /// Dimension of the 3D regular triangulation of the lifted spheres.
  int dimension() const;
  /// Sites whose sphere Σ_i is not a vertex of the 3D regular triangulation: hidden there (duplicates
  /// included) or weakly hidden (see the file comment).
  std::vector<SiteIndex> hidden_sites() const;
  /// The weakly hidden sites (see the file comment), increasing.
  std::vector<SiteIndex> weakly_hidden_sites() const;
  /// Sites whose Möbius cell is empty (hidden ones included).
  std::vector<SiteIndex> empty_sites() const;
  /// Edges of the 3D regular triangulation between visible sites (a < b), sorted: a superset of the
  /// pairs of sites with a common Möbius edge.
  const std::vector<std::pair<SiteIndex, SiteIndex>>& lifted_edges() const;
  /// The vertices.
  const std::vector<MobiusVertex>& vertices() const;
  /// The edges.
  const std::vector<MobiusEdge>& edges() const;
  /// The components of the cell of site i (empty when the cell is empty).
  const std::vector<CellComponent>& cell(SiteIndex i) const;
  /// A site minimizing δ at q: located in the 3D power diagram at the lifted point (q, |q|²), exactly
  /// (the lifted point is not rounded); no_site without sites. O(log n) expected when the
  /// lifted triangulation is 3-dimensional; CGAL scans all vertices in lower dimensions (equal λ).
  SiteIndex locate(Point2 q) const;
  /// Which cell component contains q, by the computed boundaries: (site, component index), or
  /// (no_site, 0) outside the frame or on no component (a point on a boundary may go either way).
  /// Brute force over the components' polylines (arcs within 1e-7 × the frame size), built on the
  /// first call: meant for tests and small diagrams, and not thread-safe on that first call.
  std::pair<SiteIndex, std::size_t> locate_in_cells(Point2 q) const;
  /// Checks the invariants: no vertices ordered wrongly along a bisector, loops closed, every edge used
  /// once by each of its two sites' cells, vertex sites equidistant (relative 1e-6), component areas
  /// adding up to the frame's area.
  /// With `verbose`, writes the first violated invariant on std::cerr. False also when a vertex is not
  /// finite (input beyond what doubles represent).
  bool is_valid(bool verbose = false) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace laguerre::core
