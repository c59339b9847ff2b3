#pragma once
/// @file
/// The Delaunay triangulation of a point set and the exact proximity predicates of the Delaunay family
/// (empty circles, diametral discs, lengths against a radius): a small facade over CGAL, whose headers
/// stay inside core/src/geometry/Delaunay.cpp.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::core {

/// Triangles of a Delaunay triangulation of `points`, as index triples in counter-clockwise order.
///
/// Precondition: the points are finite and pairwise distinct (InternalError naming two equal indices otherwise);
/// fewer than 3 points or all points collinear give no triangle. For points in general position the
/// triangulation is unique; when four or more points are cocircular, CGAL's choice (symbolic
/// perturbation) is returned. Triangles are sorted by their index triples, each triple starting at its
/// smallest index, so the result does not depend on CGAL's insertion order. Cost O(n log n) expected.
std::vector<std::array<std::size_t, 3>> delaunay_triangles(std::span<const Point2> points);

/// In-circle test: for (a, b, c) counter-clockwise, positive if d lies strictly inside the circle
/// through a, b, c, zero on it, negative outside (the sign flips for clockwise (a, b, c); for collinear
/// a, b, c it is the side of d relative to that line). Exact. Degree 4.
Sign in_circle(Point2 a, Point2 b, Point2 c, Point2 d);

/// Diametral-disc test: sign of (u − w)·(v − w). Negative if w lies strictly inside the disc with
/// diameter uv (the angle at w is obtuse), zero on its circle, positive outside. Exact. Degree 2.
Sign diametral_side(Point2 u, Point2 v, Point2 w);

/// Sign of |a − b|² − r²: whether the distance from a to b is less than (negative), equal to (zero) or
/// greater than (positive) r ≥ 0. Exact for the given doubles. Degree 2.
Sign compare_length(Point2 a, Point2 b, double r);

}  // namespace laguerre::core
