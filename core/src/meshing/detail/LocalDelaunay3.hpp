#pragma once
/// @file
/// The CGAL entry points of the 3D star mesher: the star of one point in the Delaunay triangulation of
/// a small point set for a constant metric M, and the exact 3D predicates the mesher decides with.
///
/// As in 2D (LocalDelaunay.hpp), the star is computed on the input points with exact predicates in the
/// metric: a CGAL 3D Delaunay triangulation whose in-sphere and coplanar in-circle tests lift x ↦ xᵀMx
/// (interval filter, rational fallback), so every combinatorial decision is exact for every metric
/// (non-diagonal ones included: no stretched, rounded coordinates).

#include <array>
#include <cstddef>
#include <vector>

namespace laguerre::core::detail {

/// The star of `points[centre]` in the Delaunay triangulation of `points` for the metric with entries
/// {xx, xy, xz, yy, yz, zz}: each entry {i, j, k} is a finite tetrahedron (centre, i, j, k), positively
/// oriented (exactly: never flat).
/// `on_hull`: the centre is on the convex hull. False when the points span less than 3 dimensions
/// (`star` is then empty). Cospherical ties are broken by CGAL's symbolic perturbation.
bool delaunay_star3(const std::vector<std::array<double, 3>>& points, std::size_t centre,
                    const std::array<double, 6>& metric, std::vector<std::array<std::size_t, 3>>& star, bool& on_hull);

/// The sign of the M-in-sphere determinant (exact: metric_in_sphere_filter, then an interval filter,
/// then rational arithmetic): positive iff t is
/// strictly inside the M-circumsphere of the positively oriented tetrahedron (p, q, r, s). The tests'
/// oracle for the stars.
int metric_in_sphere(const std::array<double, 3>& p, const std::array<double, 3>& q, const std::array<double, 3>& r,
                     const std::array<double, 3>& s, const std::array<double, 3>& t, const std::array<double, 6>& metric);

/// metric_in_sphere without metric_in_sphere_filter (interval filter, then rational arithmetic): the
/// tests' oracle for the filter.
int metric_in_sphere_unfiltered(const std::array<double, 3>& p, const std::array<double, 3>& q,
                                const std::array<double, 3>& r, const std::array<double, 3>& s,
                                const std::array<double, 3>& t, const std::array<double, 6>& metric);

/// metric_in_sphere_filter's answer when floating point cannot decide.
inline constexpr int kUndecided = 2;

/// The sign of the M-in-sphere determinant of metric_in_sphere in floating point with a certified error
/// bound (the determinant and its absolute-value expansion P, |fl(D) − D| ≤ 2⁻⁴⁸·fl(P) + 2⁻¹⁰⁰⁰ after
/// exact power-of-two scaling; the derivation is at the definition): +1 or −1 only when that is the
/// exact sign, else kUndecided (nearly cospherical points, degenerate or out-of-range input), for which
/// metric_in_sphere goes on with the interval filter and the rational determinant.
int metric_in_sphere_filter(const std::array<double, 3>& p, const std::array<double, 3>& q,
                            const std::array<double, 3>& r, const std::array<double, 3>& s,
                            const std::array<double, 3>& t, const std::array<double, 6>& metric);

/// Exact orientation: +1 iff d lies on the side of the plane abc where (b − a) × (c − a) points.
int orientation3(const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c,
                 const std::array<double, 3>& d);

/// Whether the closed segment [p, q] meets the closed triangle abc (exact).
bool segment_meets_triangle(const std::array<double, 3>& p, const std::array<double, 3>& q,
                            const std::array<double, 3>& a, const std::array<double, 3>& b,
                            const std::array<double, 3>& c);

}  // namespace laguerre::core::detail
