#pragma once
/// @file
/// The one CGAL entry point of the star mesher: the fan of triangles around one point in the Delaunay
/// triangulation of a small point set (already mapped by the star's stretching F_v).

#include <array>
#include <cstddef>
#include <vector>

namespace laguerre::core::detail {

/// The Delaunay fan around `points[centre]`: each entry {a, b} is a finite triangle (centre, a, b),
/// counter-clockwise, listed in counter-clockwise order around the centre. `on_hull` is set when the
/// centre lies on the convex hull of `points` (the fan is then open). Exact predicates (Epick); for
/// cocircular points the triangulation is CGAL's (any Delaunay triangulation).
void delaunay_fan(const std::vector<std::array<double, 2>>& points, std::size_t centre,
                  std::vector<std::array<std::size_t, 2>>& fan, bool& on_hull);

}  // namespace laguerre::core::detail
