#include "laguerre/core/geometry/Delaunay.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "laguerre/core/Error.hpp"
#include "../detail/FastFilter.hpp"
#include "../detail/Filtered.hpp"

namespace laguerre::core {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Triangulation = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
}  // namespace

std::vector<std::array<std::size_t, 3>> delaunay_triangles(std::span<const Point2> points) {
  const std::size_t n = points.size();
  std::vector<std::array<std::size_t, 3>> triangles;
  if (n < 3) return triangles;
  std::vector<std::pair<Kernel::Point_2, std::size_t>> sites;
  sites.reserve(n);
  for (std::size_t i = 0; i < n; ++i) sites.emplace_back(Kernel::Point_2(points[i].x, points[i].y), i);
  Triangulation dt;
  dt.insert(sites.begin(), sites.end());
  if (dt.number_of_vertices() != n) {  // CGAL merged equal points: name two of them
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    const auto key = [&](std::size_t i) { return std::pair{points[i].x, points[i].y}; };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return std::pair{key(a), a} < std::pair{key(b), b}; });
    for (std::size_t k = 1; k < n; ++k)
      if (key(order[k]) == key(order[k - 1]))
        throw InternalError("precondition failed: delaunay_triangles needs distinct points, but points " +
                            std::to_string(order[k - 1]) + " and " + std::to_string(order[k]) + " are equal.");
    throw InternalError(
        "precondition failed: delaunay_triangles: some points could not be inserted (non-finite coordinates?).");
  }
  if (dt.dimension() < 2) return triangles;
  triangles.reserve(dt.number_of_faces());
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    std::array<std::size_t, 3> t{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // keeps the ccw order
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

// Double-precision filters in the style of detail/FastFilter.hpp: the differences are kept in
// [1e-60, 1e60] (or zero), so no product of up to four of them overflows or underflows; the error bounds
// then follow Shewchuk's analysis (in-circle: (10 + 96u)u times the permanent; we use 2^-49 ≈ 16u) and
// a 9u bound for the degree-2 dot product.
namespace {
bool small_range(double d) { return detail::in_range(d, 1e-60, 1e60); }
}  // namespace

Sign in_circle(Point2 a, Point2 b, Point2 c, Point2 d) {
  const double adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y, cdx = c.x - d.x, cdy = c.y - d.y;
  if (small_range(adx) && small_range(ady) && small_range(bdx) && small_range(bdy) && small_range(cdx) &&
      small_range(cdy)) {
    const double alift = adx * adx + ady * ady, blift = bdx * bdx + bdy * bdy, clift = cdx * cdx + cdy * cdy;
    const double bc = bdx * cdy - bdy * cdx, ca = cdx * ady - cdy * adx, ab = adx * bdy - ady * bdx;
    const double det = alift * bc + blift * ca + clift * ab;
    const double permanent = (std::fabs(bdx * cdy) + std::fabs(bdy * cdx)) * alift +
                             (std::fabs(cdx * ady) + std::fabs(cdy * adx)) * blift +
                             (std::fabs(adx * bdy) + std::fabs(ady * bdx)) * clift;
    const double bound = 0x1.0p-49 * permanent;
    if (det > bound) return Sign::positive;
    if (det < -bound) return Sign::negative;
  }
  return detail::filtered([&]<class NT>() {
    const NT ax = NT(a.x) - NT(d.x), ay = NT(a.y) - NT(d.y);
    const NT bx = NT(b.x) - NT(d.x), by = NT(b.y) - NT(d.y);
    const NT cx = NT(c.x) - NT(d.x), cy = NT(c.y) - NT(d.y);
    const NT a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    return detail::sign_of<NT>(a2 * (bx * cy - by * cx) - b2 * (ax * cy - ay * cx) + c2 * (ax * by - ay * bx));
  });
}

Sign diametral_side(Point2 u, Point2 v, Point2 w) {
  const double ax = u.x - w.x, ay = u.y - w.y, bx = v.x - w.x, by = v.y - w.y;
  if (detail::in_range(ax) && detail::in_range(ay) && detail::in_range(bx) && detail::in_range(by)) {
    const double dot = ax * bx + ay * by, bound = detail::kSquaresError * (std::fabs(ax * bx) + std::fabs(ay * by));
    if (dot > bound) return Sign::positive;
    if (dot < -bound) return Sign::negative;
  }
  return detail::filtered([&]<class NT>() {
    return detail::sign_of<NT>((NT(u.x) - NT(w.x)) * (NT(v.x) - NT(w.x)) + (NT(u.y) - NT(w.y)) * (NT(v.y) - NT(w.y)));
  });
}

Sign compare_length(Point2 a, Point2 b, double r) {
  const double r2 = r * r;  // rounded by at most 2^-53 r², far inside the bound below
  if (r2 >= 1e-200 && r2 <= 1e200)
    if (const auto s = detail::certified_sign(detail::approx_distance(a, b), detail::Approx{r2, detail::kSquaresError * r2}))
      return *s;
  return detail::filtered([&]<class NT>() {
    const NT dx = NT(a.x) - NT(b.x), dy = NT(a.y) - NT(b.y), R(r);
    return detail::sign_of<NT>(dx * dx + dy * dy - R * R);
  });
}

}  // namespace laguerre::core
