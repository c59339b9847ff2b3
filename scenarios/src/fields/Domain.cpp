#include "laguerre/scenarios/fields/Domain.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace laguerre::scenarios {

using core::orientation;
using core::Point2;
using core::Sign;
using Box = Domain::Box;

namespace {

std::string point_text(Point2 p) {
  std::ostringstream s;
  s.precision(17);
  s << '(' << p.x << ", " << p.y << ')';
  return s.str();
}

std::string polygon_name(std::size_t hole) {  // hole 0 is the outer polygon
  return hole == 0 ? "the outer polygon" : "hole " + std::to_string(hole);
}

Box box_of(const Polygon& p) {
  Box b{p[0].x, p[0].y, p[0].x, p[0].y};
  for (Point2 q : p) {
    b.xmin = std::min(b.xmin, q.x);
    b.xmax = std::max(b.xmax, q.x);
    b.ymin = std::min(b.ymin, q.y);
    b.ymax = std::max(b.ymax, q.y);
  }
  return b;
}

/// Whether p lies on the closed segment [a, b]. Exact.
bool on_segment(Point2 a, Point2 b, Point2 p) {
  return orientation(a, b, p) == Sign::zero && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
         std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

bool on_polygon(const Polygon& poly, Point2 p) {
  for (std::size_t i = 0; i < poly.size(); ++i)
    if (on_segment(poly[i], poly[(i + 1) % poly.size()], p)) return true;
  return false;
}

/// Crossing-number test for p not on the boundary of poly: a ray from p towards +x crosses the edge
/// a→b iff the edge straddles the ray's line (one end strictly above p, the other not) and p lies on
/// the proper side of it (left of upward edges, right of downward ones). Exact.
bool inside_polygon(const Polygon& poly, Point2 p) {
  bool inside = false;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    if ((a.y > p.y) == (b.y > p.y)) continue;
    const Sign s = orientation(a, b, p);
    if ((b.y > a.y && s == Sign::positive) || (b.y < a.y && s == Sign::negative)) inside = !inside;
  }
  return inside;
}

/// Sign of a coordinate difference, exactly.
int direction(double from, double to) { return (to > from) - (to < from); }

void check_polygon(const Polygon& poly, std::size_t index) {
  const std::string name = polygon_name(index);
  const std::size_t k = poly.size();
  if (k < 3) throw std::invalid_argument(name + " has " + std::to_string(k) + " vertices; a polygon needs at least 3.");
  for (std::size_t i = 0; i < k; ++i)
    if (!std::isfinite(poly[i].x) || !std::isfinite(poly[i].y))
      throw std::invalid_argument("vertex " + std::to_string(i) + " of " + name + " has a non-finite coordinate.");
  std::vector<std::size_t> order(k);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto key = [&](std::size_t i) { return std::pair{poly[i].x, poly[i].y}; };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return std::pair{key(a), a} < std::pair{key(b), b}; });
  for (std::size_t i = 1; i < k; ++i)
    if (key(order[i]) == key(order[i - 1]))
      throw std::invalid_argument("vertices " + std::to_string(order[i - 1]) + " and " + std::to_string(order[i]) + " of " +
                                  name + " are both at " + point_text(poly[order[i]]) + "; a polygon repeats no vertex.");
  std::vector<Box> boxes(k);
  for (std::size_t i = 0; i < k; ++i) boxes[i] = box_of({poly[i], poly[(i + 1) % k]});
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = i + 1; j < k; ++j) {
      const Point2 a = poly[i], b = poly[(i + 1) % k], c = poly[j], d = poly[(j + 1) % k];
      if (j == i + 1 || (i == 0 && j == k - 1)) {
        // Consecutive edges share one vertex m; they overlap iff collinear and doubling back.
        const Point2 m = j == i + 1 ? b : a, p = j == i + 1 ? a : b, q = j == i + 1 ? d : c;
        if (orientation(p, m, q) == Sign::zero &&
            direction(m.x, p.x) == direction(m.x, q.x) && direction(m.y, p.y) == direction(m.y, q.y))
          throw std::invalid_argument("edges " + std::to_string(i) + " and " + std::to_string(j) + " of " + name +
                                      " overlap (the boundary doubles back at " + point_text(m) +
                                      "); the polygon must be simple.");
        continue;
      }
      if (boxes[i].xmax < boxes[j].xmin || boxes[j].xmax < boxes[i].xmin || boxes[i].ymax < boxes[j].ymin ||
          boxes[j].ymax < boxes[i].ymin)
        continue;
      if (core::segments_intersect(a, b, c, d))
        throw std::invalid_argument("edges " + std::to_string(i) + " (" + point_text(a) + " to " + point_text(b) + ") and " +
                                    std::to_string(j) + " (" + point_text(c) + " to " + point_text(d) + ") of " + name +
                                    " cross or touch; the polygon must be simple.");
    }
}

/// Orientation of a simple polygon, from its lexicographically smallest vertex (a convex corner).
Sign polygon_orientation(const Polygon& poly) {
  const std::size_t k = poly.size();
  std::size_t m = 0;
  for (std::size_t i = 1; i < k; ++i)
    if (std::pair{poly[i].x, poly[i].y} < std::pair{poly[m].x, poly[m].y}) m = i;
  return orientation(poly[(m + k - 1) % k], poly[m], poly[(m + 1) % k]);
}

/// First pair of intersecting edges of two polygons, or {k, k}.
std::pair<std::size_t, std::size_t> first_crossing(const Polygon& p, const Polygon& q) {
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j)
      if (core::segments_intersect(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()])) return {i, j};
  return {p.size(), q.size()};
}

/// Whether the closed segment [p, q] meets the open triangle abc (counter-clockwise). By the separating
/// axis theorem for convex polygons, they are disjoint iff one of the four edge lines weakly separates
/// them: the segment lies in the closed right side of a triangle edge, or the triangle in one closed
/// side of line pq.
bool segment_meets_open_triangle(Point2 a, Point2 b, Point2 c, Point2 p, Point2 q) {
  const Point2 t[3] = {a, b, c};
  for (int i = 0; i < 3; ++i) {
    const Point2 x = t[i], y = t[(i + 1) % 3];
    if (orientation(x, y, p) != Sign::positive && orientation(x, y, q) != Sign::positive) return false;
  }
  const Sign sa = orientation(p, q, a), sb = orientation(p, q, b), sc = orientation(p, q, c);
  if (sa != Sign::negative && sb != Sign::negative && sc != Sign::negative) return false;
  if (sa != Sign::positive && sb != Sign::positive && sc != Sign::positive) return false;
  return true;
}

double signed_area(const Polygon& poly) {
  double s = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    s += a.x * b.y - a.y * b.x;
  }
  return s / 2;
}

}  // namespace

Domain::Domain(Polygon outer, std::vector<Polygon> holes) : outer_(std::move(outer)), holes_(std::move(holes)) {
  check_polygon(outer_, 0);
  for (std::size_t h = 0; h < holes_.size(); ++h) check_polygon(holes_[h], h + 1);
  if (polygon_orientation(outer_) == Sign::negative) std::reverse(outer_.begin(), outer_.end());
  for (Polygon& hole : holes_)
    if (polygon_orientation(hole) == Sign::positive) std::reverse(hole.begin(), hole.end());
  for (std::size_t h = 0; h < holes_.size(); ++h) {
    const Polygon& hole = holes_[h];
    const auto [i, j] = first_crossing(hole, outer_);
    if (i < hole.size())
      throw std::invalid_argument(polygon_name(h + 1) + " meets the boundary of the outer polygon (near " +
                                  point_text(hole[i]) + "); holes must lie strictly inside the outer polygon.");
    if (!inside_polygon(outer_, hole[0]))
      throw std::invalid_argument(polygon_name(h + 1) + " lies outside the outer polygon (its vertex 0 is at " +
                                  point_text(hole[0]) + "); holes must lie strictly inside the outer polygon.");
    for (std::size_t g = 0; g < h; ++g) {
      const Polygon& other = holes_[g];
      const bool touch = first_crossing(hole, other).first < hole.size();
      if (touch || inside_polygon(other, hole[0]) || inside_polygon(hole, other[0]))
        throw std::invalid_argument(polygon_name(g + 1) + " and " + polygon_name(h + 1) +
                                    (touch ? " meet" : " overlap (one lies inside the other)") +
                                    "; holes must be pairwise disjoint.");
    }
  }
  bounds_ = box_of(outer_);
}

Domain Domain::rectangle(double xmin, double ymin, double xmax, double ymax) {
  if (!(xmin < xmax) || !(ymin < ymax))
    throw std::invalid_argument("a rectangle needs xmin < xmax and ymin < ymax.");
  return Domain({{xmin, ymin}, {xmax, ymin}, {xmax, ymax}, {xmin, ymax}});
}

double Domain::area() const {
  double a = signed_area(outer_);
  for (const Polygon& h : holes_) a += signed_area(h);  // holes are clockwise: negative
  return a;
}

std::size_t Domain::num_boundary_edges() const {
  std::size_t k = outer_.size();
  for (const Polygon& h : holes_) k += h.size();
  return k;
}

Domain::Location Domain::locate(Point2 p) const {
  if (on_polygon(outer_, p)) return Location::boundary;
  for (const Polygon& h : holes_)
    if (on_polygon(h, p)) return Location::boundary;
  if (!inside_polygon(outer_, p)) return Location::outside;
  for (const Polygon& h : holes_)
    if (inside_polygon(h, p)) return Location::outside;
  return Location::inside;
}

bool Domain::triangle_inside(Point2 a, Point2 b, Point2 c) const {
  if (orientation(a, b, c) != Sign::positive)
    throw std::invalid_argument("Domain::triangle_inside needs a counter-clockwise triangle.");
  const Box t{std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y})};
  const auto test = [&](const Polygon& poly) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Point2 p = poly[i], q = poly[(i + 1) % poly.size()];
      if (std::max(p.x, q.x) <= t.xmin || std::min(p.x, q.x) >= t.xmax || std::max(p.y, q.y) <= t.ymin ||
          std::min(p.y, q.y) >= t.ymax)
        continue;  // the open triangle lies strictly inside its box
      if (segment_meets_open_triangle(a, b, c, p, q)) return true;
    }
    return false;
  };
  if (test(outer_)) return false;
  for (const Polygon& h : holes_)
    if (test(h)) return false;
  // No boundary point in the open triangle: it lies wholly inside or wholly outside; a vertex strictly
  // inside the domain decides (the domain contains a neighbourhood of it, which meets the triangle).
  for (Point2 v : {a, b, c}) {
    const Location l = locate(v);
    if (l == Location::inside) return true;
    if (l == Location::outside) return false;  // a vertex strictly outside: the open triangle is too
  }
  throw std::invalid_argument("Domain::triangle_inside needs a vertex strictly inside the domain; all three are on its boundary.");
}

}  // namespace laguerre::scenarios
