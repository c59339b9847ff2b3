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

#include "laguerre/core/diagrams/AffineDiagram.hpp"

namespace laguerre::core {

/// Voronoi diagram of points, clipped to a box, with its dual Delaunay triangulation (the API is
/// AffineDiagram's).
using VoronoiDiagram = AffineDiagram<Point2>;

}  // namespace laguerre::core
