#pragma once
/// @file
/// A polygonal domain with holes: the region in which sensor fields are deployed.

#include <cstddef>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::scenarios {

/// A polygon as its vertices in boundary order (the closing edge from the last vertex to the first is
/// implicit).
using Polygon = std::vector<core::Point2>;

/// A closed polygonal region: an outer simple polygon minus the open interiors of hole polygons.
///
/// Validation (the constructor throws std::invalid_argument with a full sentence naming the polygon —
/// "the outer polygon" or "hole 2" (holes count from 1) — and the vertex or edge indices (from 0)):
///  - every polygon has at least 3 vertices, finite coordinates and no repeated vertex;
///  - every polygon is simple: two edges meet only when they are consecutive, and then only at their
///    common vertex (no spikes doubling back), and not all vertices are collinear;
///  - every hole lies strictly inside the outer polygon (no common boundary point);
///  - holes are pairwise disjoint (no common point, neither inside the other).
/// All these decisions use the exact predicates of core/geometry/Predicates.hpp.
/// The orientation is then normalized: the outer polygon counter-clockwise, holes clockwise, so that
/// the domain lies to the left of every boundary edge.
class Domain {
public:
  /// An axis-parallel bounding box.
  struct Box {
    double xmin = 0;  ///< smallest abscissa
    double ymin = 0;  ///< smallest ordinate
    double xmax = 0;  ///< largest abscissa
    double ymax = 0;  ///< largest ordinate
  };

  /// Where a point lies relative to the domain.
  enum class Location { inside, boundary, outside };

  /// Validates and normalizes (see the class comment).
  explicit Domain(Polygon outer, std::vector<Polygon> holes = {});

  /// The rectangle [xmin, xmax] × [ymin, ymax] (xmin < xmax, ymin < ymax), no holes.
  static Domain rectangle(double xmin, double ymin, double xmax, double ymax);

  /// The outer polygon, counter-clockwise.
  const Polygon& outer() const { return outer_; }
  /// The holes, each clockwise.
  const std::vector<Polygon>& holes() const { return holes_; }
  /// Bounding box of the outer polygon.
  const Box& bounds() const { return bounds_; }
  /// Area (outer minus holes), by the shoelace formula in doubles: for densities, never for decisions.
  double area() const;

  /// Exact location of p: on an edge of any polygon is `boundary`; otherwise inside the outer polygon
  /// and outside every hole is `inside`. Crossing-number test with exact orientations; cost O(edges).
  Location locate(core::Point2 p) const;

  /// Whether the open triangle abc lies inside the domain, i.e. no boundary point of the domain is in
  /// its interior. Precondition: a, b, c counter-clockwise and at least one of them strictly inside
  /// (std::invalid_argument otherwise). Exact: a boundary edge meets the open triangle unless a
  /// triangle edge line or the boundary edge's own line weakly separates them. Cost O(edges).
  bool triangle_inside(core::Point2 a, core::Point2 b, core::Point2 c) const;

  /// Total number of boundary edges (outer and holes).
  std::size_t num_boundary_edges() const;

private:
  Polygon outer_;
  std::vector<Polygon> holes_;
  Box bounds_;
};

}  // namespace laguerre::scenarios
