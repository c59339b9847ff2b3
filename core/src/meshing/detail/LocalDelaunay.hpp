#pragma once
/// @file
/// The one CGAL entry point of the star mesher: the fan of triangles around one point in the
/// constrained Delaunay triangulation of a small point set for a constant metric M.
///
/// The points are the sites' own coordinates (not moved by the stretching F = M^{1/2}): the metric
/// enters only through the in-circle predicate, whose lifting is the quadratic form x ↦ xᵀMx instead
/// of |x|² (a triangle is Delaunay for M iff its M-circumellipse is empty, i.e. its image under F has
/// an empty circumcircle). Orientation is affine invariant and is decided on the input coordinates, so
/// sites that are collinear in the plane (a boundary edge and its split points) stay exactly collinear
/// for every metric: no flat sliver can appear along an edge because the stretch was rounded.

#include <array>
#include <cstddef>
#include <vector>

namespace laguerre::core::detail {

/// The constrained Delaunay fan around `points[centre]` for the metric [[a, b], [b, c]]: each entry
/// {i, j} is a finite triangle (centre, i, j), counter-clockwise, listed in counter-clockwise order
/// around the centre (consecutive entries share the edge (centre, j) = (centre, next i)). `constraints`
/// are index pairs forced as edges (the subsegments near the centre; they must not cross). `on_hull`
/// is set when the centre lies on the convex hull of `points` (the fan is then open). Exact
/// predicates: orientation of the input points, and in-ellipse with the metric's coefficients taken
/// as exact doubles (interval filter, exact rational fallback); cocircular ties are broken by CGAL's
/// symbolic perturbation (any Delaunay triangulation).
void delaunay_fan(const std::vector<std::array<double, 2>>& points, std::size_t centre, std::array<double, 3> metric,
                  const std::vector<std::array<std::size_t, 2>>& constraints,
                  std::vector<std::array<std::size_t, 2>>& fan, bool& on_hull);

/// The sign of the M-in-circle determinant (exact): positive iff t lies strictly inside the
/// M-circumellipse of the counter-clockwise triangle (p, q, r), zero when on it. For tests.
int metric_in_circle(std::array<double, 2> p, std::array<double, 2> q, std::array<double, 2> r,
                     std::array<double, 2> t, std::array<double, 3> metric);

}  // namespace laguerre::core::detail
