#pragma once
/// @file
/// Result types shared by the affine diagrams (Euclidean Voronoi, power): straight edges, vertices and
/// the dual triangles, with the sites they separate.

#include <array>
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

}  // namespace laguerre::core
