#pragma once
/// @file
/// Euclidean Voronoi diagram and its dual Delaunay triangulation, through CGAL's Delaunay_triangulation_2
/// with exact predicates (Epick).
///
/// Cells are clipped to the box given at construction. Equal points keep one representative; the
/// others are reported hidden (their cell is the representative's). Cocircular points are triangulated
/// in one of the valid ways (CGAL's symbolic perturbation): some dual edges then have a primal edge of
/// length zero, which `edges()` omits. Collinear points give a 1-dimensional triangulation (no
/// vertices; cells are parallel strips).

#include <memory>
#include <utility>
#include <vector>

#include "laguerre/core/diagrams/AffineDiagram.hpp"

namespace laguerre::core {

/// Voronoi diagram of points, clipped to a box, with its dual Delaunay triangulation.
class VoronoiDiagram {
 public:
  /// Builds the diagram of `sites` (finite coordinates; throws InputError otherwise) and
  /// clips the cells to `box` (must be valid).
  VoronoiDiagram(std::vector<Point2> sites, const Box& box);
  /// Destructor.
  ~VoronoiDiagram();
  /// Move constructor.
  VoronoiDiagram(VoronoiDiagram&&) noexcept;
  /// Move assignment.
  VoronoiDiagram& operator=(VoronoiDiagram&&) noexcept;

  /// The input sites, in input order.
  const std::vector<Point2>& sites() const;
  /// The clipping box.
  const Box& box() const;
  /// Dimension of the Delaunay triangulation (−1 no site, 0 one vertex, 1 collinear, 2 general).
  int dimension() const;
  /// Whether site i is a duplicate of an earlier-kept equal point.
  bool is_hidden(SiteIndex i) const;
  /// The duplicate sites, increasing.
  std::vector<SiteIndex> hidden_sites() const;
  /// Edges of the Delaunay triangulation (the dual graph), as pairs (a < b), sorted.
  const std::vector<std::pair<SiteIndex, SiteIndex>>& dual_edges() const;
  /// Finite Delaunay triangles (counter-clockwise) with their circumcentres (the Voronoi vertices).
  const std::vector<DiagramVertex>& vertices() const;
  /// Voronoi cell of site i clipped to the box (convex, counter-clockwise; empty for a duplicate).
  const Polygon& cell(SiteIndex i) const;
  /// Edges of the diagram clipped to the box, sorted by (a, b).
  const std::vector<StraightEdge>& edges() const;
  /// A site nearest to q (exact; among ties, the one CGAL reaches first); no_site without sites.
  SiteIndex locate(Point2 q) const;
  /// Checks the invariants (as PowerDiagram::is_valid; CGAL's validity includes the local empty-circle
  /// property of every edge).
  /// With `verbose`, writes the first violated invariant on std::cerr. False also when a vertex is not
  /// finite (input beyond what doubles represent).
  bool is_valid(bool verbose = false) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace laguerre::core
