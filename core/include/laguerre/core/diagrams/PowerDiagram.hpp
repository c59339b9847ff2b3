#pragma once
/// @file
/// Power (Laguerre) diagram and its dual regular triangulation, through CGAL's Regular_triangulation_2
/// with exact predicates (Epick).
///
/// Sites are weighted points (p_i, w_i); the power cell of i is {x : |x − p_i|² − w_i ≤ |x − p_j|² − w_j
/// for all j}, a convex polygon, possibly empty: then site i is *hidden* (it is not a vertex of the
/// regular triangulation). Equal sites (same point and weight) keep one representative, the others are
/// reported hidden. Cells are clipped to the box given at construction (unbounded cells included).
/// Combinatorial decisions (triangulation, hidden sites, point location) are exact for the double
/// inputs; cell polygons and vertices are double constructions.
///
/// Degenerate inputs: collinear sites give a 1-dimensional triangulation (no triangles, no vertices;
/// cells are parallel strips); four or more sites with a common orthogonal circle are triangulated in
/// one of the valid ways (CGAL's symbolic perturbation), so some dual edges have a primal edge of length
/// zero, which `edges()` omits.

#include <memory>
#include <utility>
#include <vector>

#include "laguerre/core/diagrams/AffineDiagram.hpp"

namespace laguerre::core {

/// Power diagram of weighted points, clipped to a box, with its dual regular triangulation.
class PowerDiagram {
 public:
  /// Builds the diagram of `sites` (finite coordinates and weights; throws InputError
  /// otherwise) and clips the cells to `box` (must be valid).
  PowerDiagram(std::vector<WeightedPoint> sites, const Box& box);
  /// Destructor.
  ~PowerDiagram();
  /// Move constructor.
  PowerDiagram(PowerDiagram&&) noexcept;
  /// Move assignment.
  PowerDiagram& operator=(PowerDiagram&&) noexcept;

  /// The input sites, in input order.
  const std::vector<WeightedPoint>& sites() const;
  /// The clipping box.
  const Box& box() const;
  /// Dimension of the regular triangulation (−1 no site, 0 one vertex, 1 collinear, 2 general).
  int dimension() const;
  /// Whether site i is hidden (empty power cell, or a duplicate of another site).
  bool is_hidden(SiteIndex i) const;
  /// The hidden sites, increasing.
  std::vector<SiteIndex> hidden_sites() const;
  /// Edges of the regular triangulation (the dual graph), as pairs (a < b), sorted.
  const std::vector<std::pair<SiteIndex, SiteIndex>>& dual_edges() const;
  /// Finite triangles of the regular triangulation (counter-clockwise) with their power vertices.
  const std::vector<DiagramVertex>& vertices() const;
  /// Power cell of site i clipped to the box: a convex counter-clockwise polygon, empty when hidden or
  /// outside the box.
  const Polygon& cell(SiteIndex i) const;
  /// Edges of the diagram clipped to the box, sorted by (a, b).
  const std::vector<StraightEdge>& edges() const;
  /// A site whose closed power cell contains q (exact; among ties, the one CGAL reaches first);
  /// no_site when there are no sites.
  SiteIndex locate(Point2 q) const;
  /// Checks the invariants: CGAL's triangulation validity, hidden sites are exactly the sites without
  /// a vertex, dual edges are symmetric neighbourhoods, every cell is convex and counter-clockwise,
  /// every non-empty cell's centroid locates in its own site (or on a tie), the cell areas add up to
  /// the box area.
  /// With `verbose`, writes the first violated invariant on std::cerr. False also when a vertex is not
  /// finite (input beyond what doubles represent).
  bool is_valid(bool verbose = false) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace laguerre::core
