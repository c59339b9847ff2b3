#pragma once
/// @file
/// Basic types shared by every diagram of the thesis, Part I: sites (points, weighted points,
/// Möbius sites), the clipping box, polygons and the "no site" marker.
///
/// Distances (all "smaller is closer"):
/// - Euclidean Voronoi: d(x, p) = |x − p|²;
/// - power (Laguerre): pow(x, s) = |x − p|² − w, w = r² for a circle of radius r (w may be negative);
/// - Möbius (thesis §2.1.1): δ(x, s) = λ|x − p|² − μ; multiplicatively weighted Voronoi
///   is the case μ = 0, λ = 1/w² (distance |x − p| / w).
/// Bad input to the diagrams throws InputError (Error.hpp). Nothing here decides geometry: exact decisions are made in the .cpp files of core/src/diagrams.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::core {

/// Index of a site in the input sequence of a diagram.
using SiteIndex = std::size_t;

/// Marker for "no site" (e.g. a query point outside every cell, an unlabelled pixel).
inline constexpr SiteIndex no_site = std::numeric_limits<SiteIndex>::max();

/// A weighted point of the power diagram: pow(x) = |x − p|² − w.
struct WeightedPoint {
  double x = 0;  ///< abscissa of p
  double y = 0;  ///< ordinate of p
  double w = 0;  ///< weight (squared radius; any real)
};

/// A Möbius site: δ(x) = λ|x − p|² − μ (thesis §2.1.1, Thm 2.1.1).
struct MobiusSite {
  double x = 0;       ///< abscissa of p
  double y = 0;       ///< ordinate of p
  double lambda = 1;  ///< multiplicative weight λ (λ > 0 usually; the linearization accepts any real)
  double mu = 0;      ///< additive weight μ (any real)
};

/// Squared Euclidean distance |q − p|² in doubles (display, oracles; not for decisions).
inline double squared_distance(Point2 q, Point2 p) {
  const double dx = q.x - p.x, dy = q.y - p.y;
  return dx * dx + dy * dy;
}

/// Power distance |q − p|² − w in doubles (display, oracles; not for decisions).
inline double power_distance(Point2 q, const WeightedPoint& s) { return squared_distance(q, {s.x, s.y}) - s.w; }

/// Möbius distance λ|q − p|² − μ in doubles (display, oracles; not for decisions).
inline double mobius_distance(Point2 q, const MobiusSite& s) {
  return s.lambda * squared_distance(q, {s.x, s.y}) - s.mu;
}

/// The Möbius site of the multiplicatively weighted Voronoi site (p, w), w > 0: distance |x − p|²/w²,
/// whose order is that of |x − p|/w (μ = 0, λ = 1/w²).
inline MobiusSite multiplicative_site(double x, double y, double w) { return {x, y, 1.0 / (w * w), 0.0}; }

/// An axis-parallel closed rectangle [xmin, xmax] × [ymin, ymax]: the clipping window of the diagrams.
struct Box {
  double xmin = 0;  ///< left
  double ymin = 0;  ///< bottom
  double xmax = 1;  ///< right
  double ymax = 1;  ///< top

  /// Width xmax − xmin.
  double width() const { return xmax - xmin; }
  /// Height ymax − ymin.
  double height() const { return ymax - ymin; }
  /// Whether the box is non-degenerate and finite (xmin < xmax, ymin < ymax).
  bool valid() const {
    return xmin < xmax && ymin < ymax && width() < std::numeric_limits<double>::infinity() &&
           height() < std::numeric_limits<double>::infinity();
  }
  /// Whether q lies in the closed box.
  bool contains(Point2 q) const { return q.x >= xmin && q.x <= xmax && q.y >= ymin && q.y <= ymax; }
  /// The box grown by `margin` on every side.
  Box expanded(double margin) const { return {xmin - margin, ymin - margin, xmax + margin, ymax + margin}; }
  /// The four corners, counter-clockwise from (xmin, ymin).
  std::vector<Point2> corners() const { return {{xmin, ymin}, {xmax, ymin}, {xmax, ymax}, {xmin, ymax}}; }
};

/// Bounding box of `points` grown by `relative_margin` × the larger side (1 when all points coincide),
/// and by at least 2^-40 × the largest coordinate magnitude, so that the margin survives rounding far
/// from the origin and the box is never flat; the default box for no points.
inline Box bounding_box(std::span<const Point2> points, double relative_margin = 0.1) {
  if (points.empty()) return {};
  Box b{points[0].x, points[0].y, points[0].x, points[0].y};
  for (const Point2& p : points) {
    b.xmin = std::min(b.xmin, p.x), b.ymin = std::min(b.ymin, p.y);
    b.xmax = std::max(b.xmax, p.x), b.ymax = std::max(b.ymax, p.y);
  }
  const double side = std::max(b.width(), b.height());
  const double magnitude = std::max({std::fabs(b.xmin), std::fabs(b.xmax), std::fabs(b.ymin), std::fabs(b.ymax)});
  return b.expanded(std::max(side > 0 ? relative_margin * side : 1.0, magnitude * 0x1p-40));
}

/// A simple polygon as its vertices in counter-clockwise order (not repeated at the end).
using Polygon = std::vector<Point2>;

/// Signed area of a polygon (positive when counter-clockwise), in doubles, summed in coordinates
/// relative to `origin`: a point near the polygon (e.g. a corner of its box) keeps the rounding relative
/// to the polygon's size rather than to its distance from (0, 0).
inline double signed_area(const Polygon& polygon, Point2 origin = {0, 0}) {
  double a = 0;
  for (std::size_t i = 0, n = polygon.size(); i < n; ++i) {
    const Point2 &p = polygon[i], &q = polygon[(i + 1) % n];
    a += (p.x - origin.x) * (q.y - origin.y) - (p.y - origin.y) * (q.x - origin.x);
  }
  return a / 2;
}

}  // namespace laguerre::core
