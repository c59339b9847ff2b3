#pragma once
/// @file
/// The affine diagrams (Euclidean Voronoi: VoronoiDiagram.hpp, power: PowerDiagram.hpp), one class
/// template over the site type, and their result types: straight edges, vertices and the dual
/// triangles, with the sites they separate.

#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "laguerre/core/diagrams/Sites.hpp"

namespace laguerre::core {

/// A straight edge of an affine diagram, on the bisector of sites `a` < `b`, clipped to the box.
/// A dual edge whose primal edge misses the box (or degenerates to a point in a cocircular
/// configuration) has no StraightEdge.
struct StraightEdge {
  SiteIndex a = no_site;  ///< first site (smaller index)
  SiteIndex b = no_site;  ///< second site
  Point2 p;               ///< one end (in the box)
  Point2 q;               ///< other end (in the box)
};

/// A vertex of an affine diagram: the (weighted) circumcentre of a dual triangle; it may lie outside
/// the box.
struct DiagramVertex {
  Point2 point;                      ///< position (double evaluation of the construction)
  std::array<SiteIndex, 3> sites{};  ///< the dual triangle, counter-clockwise
};

/// An affine diagram clipped to a box, with its dual triangulation: `Site` is Point2 (VoronoiDiagram,
/// dual Delaunay triangulation) or WeightedPoint (PowerDiagram, dual regular triangulation).
template <class Site>
class AffineDiagram {
 public:
  /// Builds the diagram of `sites` (finite coordinates and weights; throws InputError otherwise) and
  /// clips the cells to `box` (throws InputError unless valid).
  AffineDiagram(std::vector<Site> sites, const Box& box);
  /// Destructor.
  ~AffineDiagram();
  /// Move constructor.
  AffineDiagram(AffineDiagram&&) noexcept;
  /// Move assignment.
  AffineDiagram& operator=(AffineDiagram&&) noexcept;

  /// The input sites, in input order.
  const std::vector<Site>& sites() const;
  /// The clipping box.
  const Box& box() const;
  /// Dimension of the dual triangulation (−1 no site, 0 one vertex, 1 collinear, 2 general).
  int dimension() const;
  /// Whether site i is hidden (empty cell, or a duplicate of another site).
  bool is_hidden(SiteIndex i) const;
  /// The hidden sites, increasing.
  std::vector<SiteIndex> hidden_sites() const;
  /// Edges of the dual triangulation, as pairs (a < b), sorted.
  const std::vector<std::pair<SiteIndex, SiteIndex>>& dual_edges() const;
  /// Finite triangles of the dual triangulation (counter-clockwise) with their (weighted)
  /// circumcentres, the vertices of the diagram.
  const std::vector<DiagramVertex>& vertices() const;
  /// Cell of site i clipped to the box: a convex counter-clockwise polygon, empty when hidden or
  /// outside the box.
  const Polygon& cell(SiteIndex i) const;
  /// Edges of the diagram clipped to the box, sorted by (a, b).
  const std::vector<StraightEdge>& edges() const;
  /// A site whose closed cell contains q (exact; among ties, the one CGAL reaches first); no_site
  /// when there are no sites.
  SiteIndex locate(Point2 q) const;
  /// Checks the invariants: CGAL's triangulation validity (for Voronoi, the local empty-circle property
  /// of every edge), hidden sites are exactly the sites without a vertex (for Voronoi, duplicates),
  /// dual edges are symmetric neighbourhoods, every cell is convex and counter-clockwise, every
  /// non-empty cell's centroid locates in its own site (or on a tie), the cell areas add up to the box
  /// area, every vertex is finite (not so for input beyond what doubles represent). With `verbose`,
  /// writes the first violated invariant on std::cerr.
  bool is_valid(bool verbose = false) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

extern template class AffineDiagram<Point2>;
extern template class AffineDiagram<WeightedPoint>;

}  // namespace laguerre::core
