#include "laguerre/core/meshing/Domain.hpp"

#include "laguerre/core/InputFile.hpp"
#include "laguerre/core/diagrams/SitesFile.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace laguerre::core {

namespace {

std::string point_text(Point2 p) {
  std::ostringstream s;
  s.precision(12);
  s << '(' << p.x << ", " << p.y << ')';
  return s.str();
}

double signed_area(const std::vector<Point2>& poly) {
  double twice = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    twice += a.x * b.y - a.y * b.x;
  }
  return twice / 2;
}

/// The exact orientation of a simple polygon: that of its lowest-leftmost vertex's corner.
Sign polygon_orientation(const std::vector<Point2>& poly) {
  std::size_t k = 0;
  for (std::size_t i = 1; i < poly.size(); ++i)
    if (poly[i].y < poly[k].y || (poly[i].y == poly[k].y && poly[i].x < poly[k].x)) k = i;
  const std::size_t n = poly.size();
  return orientation(poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]);
}

/// Closed segments [a, b] and [c, d] share a point (exact).
bool touch(Point2 a, Point2 b, Point2 c, Point2 d) { return segments_intersect(a, b, c, d); }

bool same(Point2 a, Point2 b) { return a.x == b.x && a.y == b.y; }

/// p lies on the closed segment [a, b] (exact).
bool on_segment(Point2 p, Point2 a, Point2 b) {
  return orientation(a, b, p) == Sign::zero && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
         std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

/// Exact point-in-polygon by crossing parity; `boundary` when p is on an edge.
DomainSide locate_in(const std::vector<Point2>& poly, Point2 p) {
  bool inside = false;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    if (on_segment(p, a, b)) return DomainSide::boundary;
    // Half-open rule on y so that a vertex at p's height is counted once; the crossing is to the right
    // of p iff p is on the left of the upward-directed edge.
    if ((a.y > p.y) != (b.y > p.y)) {
      const Sign s = a.y < b.y ? orientation(a, b, p) : orientation(b, a, p);
      if (s == Sign::positive) inside = !inside;
    }
  }
  return inside ? DomainSide::inside : DomainSide::outside;
}

/// Checks that `poly` is a simple polygon with at least 3 vertices and no repeated vertex.
void check_simple(const std::vector<Point2>& poly, const std::string& name) {
  const std::size_t n = poly.size();
  if (n < 3) throw DomainError(name + " has " + std::to_string(n) + " vertices, expected at least 3");
  for (const Point2& p : poly)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw DomainError(name + " has a non-finite vertex");
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (same(poly[i], poly[j]))
        throw DomainError(name + " repeats the vertex " + point_text(poly[i]) + " (vertices " + std::to_string(i + 1) +
                          " and " + std::to_string(j + 1) + ")");
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      const Point2 a = poly[i], b = poly[(i + 1) % n], c = poly[j], d = poly[(j + 1) % n];
      if (adjacent) {
        // Consecutive edges share one vertex; they must not overlap (fold back).
        const Point2 shared = j == i + 1 ? b : a;
        const Point2 u = j == i + 1 ? a : b, w = j == i + 1 ? d : c;
        // Collinear consecutive edges fold back iff one of the far ends lies on the other edge.
        if (orientation(u, shared, w) == Sign::zero && (on_segment(w, shared, u) || on_segment(u, shared, w)))
          throw DomainError(name + " folds back on itself at " + point_text(shared));
      } else if (touch(a, b, c, d)) {
        throw DomainError(name + " is not simple: edge " + std::to_string(i + 1) + " " + point_text(a) + "–" +
                          point_text(b) + " meets edge " + std::to_string(j + 1) + " " + point_text(c) + "–" +
                          point_text(d));
      }
    }
  if (polygon_orientation(poly) == Sign::zero) throw DomainError(name + " has zero area");
}

std::vector<std::array<Point2, 2>> edges_of(const std::vector<Point2>& poly) {
  std::vector<std::array<Point2, 2>> edges;
  for (std::size_t i = 0; i < poly.size(); ++i) edges.push_back({poly[i], poly[(i + 1) % poly.size()]});
  return edges;
}

/// Whether the closed segment [p, q] meets the open triangle abc (counter-clockwise). By the separating
/// axis theorem for convex polygons they are disjoint iff one of the four edge lines weakly separates
/// them: the segment lies in the closed right side of a triangle edge, or the triangle in one closed
/// side of line pq. Exact.
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

}  // namespace

Domain::Domain(std::vector<Point2> outer, std::vector<std::vector<Point2>> holes,
               std::vector<std::array<Point2, 2>> segments)
    : outer_(std::move(outer)), holes_(std::move(holes)), segments_(std::move(segments)) {
  check_simple(outer_, "the outer boundary");
  if (polygon_orientation(outer_) == Sign::negative) std::reverse(outer_.begin(), outer_.end());
  for (std::size_t h = 0; h < holes_.size(); ++h) {
    const std::string name = "hole " + std::to_string(h + 1);
    check_simple(holes_[h], name);
    if (polygon_orientation(holes_[h]) == Sign::positive) std::reverse(holes_[h].begin(), holes_[h].end());
    for (const Point2& p : holes_[h])
      if (locate_in(outer_, p) != DomainSide::inside)
        throw DomainError(name + " is not strictly inside the outer boundary: vertex " + point_text(p));
    for (const auto& e : edges_of(holes_[h]))
      for (const auto& f : edges_of(outer_))
        if (touch(e[0], e[1], f[0], f[1])) throw DomainError(name + " meets the outer boundary");
    for (std::size_t g = 0; g < h; ++g) {
      for (const auto& e : edges_of(holes_[h]))
        for (const auto& f : edges_of(holes_[g]))
          if (touch(e[0], e[1], f[0], f[1]))
            throw DomainError(name + " meets hole " + std::to_string(g + 1));
      if (locate_in(holes_[g], holes_[h][0]) != DomainSide::outside ||
          locate_in(holes_[h], holes_[g][0]) != DomainSide::outside)
        throw DomainError(name + " and hole " + std::to_string(g + 1) + " are nested");
    }
  }
  std::vector<std::array<Point2, 2>> boundary;
  for (const auto& e : edges_of(outer_)) boundary.push_back(e);
  for (const auto& hole : holes_)
    for (const auto& e : edges_of(hole)) boundary.push_back(e);
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const auto& [a, b] = segments_[s];
    const std::string name = "constraint segment " + std::to_string(s + 1) + " " + point_text(a) + "–" + point_text(b);
    if (same(a, b)) throw DomainError(name + " has zero length");
    for (const Point2& p : {a, b})
      if (locate(p) == DomainSide::outside) throw DomainError(name + " has an endpoint outside the domain");
    for (const auto& e : boundary) {
      if (!touch(a, b, e[0], e[1])) continue;
      // Touching the boundary is allowed only at a segment endpoint lying on it.
      const bool at_endpoint = on_segment(a, e[0], e[1]) || on_segment(b, e[0], e[1]);
      const bool collinear = orientation(e[0], e[1], a) == Sign::zero && orientation(e[0], e[1], b) == Sign::zero;
      if (!at_endpoint || collinear || (on_segment(e[0], a, b) && !same(e[0], a) && !same(e[0], b)) ||
          (on_segment(e[1], a, b) && !same(e[1], a) && !same(e[1], b)))
        throw DomainError(name + " crosses the boundary edge " + point_text(e[0]) + "–" + point_text(e[1]));
    }
    // The midpoint must be inside (a chord between two boundary points could run outside).
    if (locate({(a.x + b.x) / 2, (a.y + b.y) / 2}) != DomainSide::inside)
      throw DomainError(name + " runs outside the domain");
    for (std::size_t t = 0; t < s; ++t) {
      const auto& [c, d] = segments_[t];
      if (!touch(a, b, c, d)) continue;
      const bool shared_endpoint = same(a, c) || same(a, d) || same(b, c) || same(b, d);
      const bool collinear = orientation(a, b, c) == Sign::zero && orientation(a, b, d) == Sign::zero;
      if (!shared_endpoint || collinear)
        throw DomainError(name + " crosses constraint segment " + std::to_string(t + 1));
    }
  }
}

Domain Domain::unit_square() { return Domain({{0, 0}, {1, 0}, {1, 1}, {0, 1}}); }

Domain Domain::rectangle(double xmin, double ymin, double xmax, double ymax) {
  if (!(xmin < xmax) || !(ymin < ymax)) throw DomainError("a rectangle needs xmin < xmax and ymin < ymax");
  return Domain({{xmin, ymin}, {xmax, ymin}, {xmax, ymax}, {xmin, ymax}});
}

std::vector<std::array<Point2, 2>> Domain::constraints() const {
  std::vector<std::array<Point2, 2>> all = edges_of(outer_);
  for (const auto& hole : holes_)
    for (const auto& e : edges_of(hole)) all.push_back(e);
  all.insert(all.end(), segments_.begin(), segments_.end());
  return all;
}

std::vector<Domain::ConstraintPiece> Domain::constraint_pieces() const {
  const auto all = constraints();
  std::vector<Point2> endpoints;
  for (const auto& c : all) endpoints.insert(endpoints.end(), {c[0], c[1]});
  std::vector<ConstraintPiece> pieces;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto [a, b] = all[i];
    std::vector<std::pair<double, Point2>> inner;
    for (const Point2& e : endpoints) {
      const bool at_end = (e.x == a.x && e.y == a.y) || (e.x == b.x && e.y == b.y);
      if (!at_end && orientation(a, b, e) == Sign::zero && std::min(a.x, b.x) <= e.x && e.x <= std::max(a.x, b.x) &&
          std::min(a.y, b.y) <= e.y && e.y <= std::max(a.y, b.y))
        inner.push_back({std::hypot(e.x - a.x, e.y - a.y), e});
    }
    std::sort(inner.begin(), inner.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
    Point2 from = a;
    for (const auto& [d, e] : inner) {
      if (e.x == from.x && e.y == from.y) continue;  // the same endpoint listed twice
      pieces.push_back({from, e, i});
      from = e;
    }
    pieces.push_back({from, b, i});
  }
  return pieces;
}

DomainSide Domain::locate(Point2 p) const {
  const DomainSide side = locate_in(outer_, p);
  if (side != DomainSide::inside) return side;
  for (const auto& hole : holes_) {
    const DomainSide h = locate_in(hole, p);
    if (h == DomainSide::boundary) return DomainSide::boundary;
    if (h == DomainSide::inside) return DomainSide::outside;
  }
  return DomainSide::inside;
}

double Domain::area() const {
  double a = signed_area(outer_);
  for (const auto& hole : holes_) a += signed_area(hole);  // holes are clockwise: negative
  return a;
}

std::array<double, 4> Domain::bounding_box() const {
  std::array<double, 4> box{outer_[0].x, outer_[0].y, outer_[0].x, outer_[0].y};
  for (const Point2& p : outer_) {
    box[0] = std::min(box[0], p.x);
    box[1] = std::min(box[1], p.y);
    box[2] = std::max(box[2], p.x);
    box[3] = std::max(box[3], p.y);
  }
  return box;
}

bool Domain::triangle_inside(Point2 a, Point2 b, Point2 c) const {
  LAGUERRE_PRECONDITION(orientation(a, b, c) == Sign::positive, "Domain::triangle_inside needs a counter-clockwise triangle.");
  const double x0 = std::min({a.x, b.x, c.x}), y0 = std::min({a.y, b.y, c.y});
  const double x1 = std::max({a.x, b.x, c.x}), y1 = std::max({a.y, b.y, c.y});
  const auto meets = [&](Point2 p, Point2 q) {
    if (std::max(p.x, q.x) <= x0 || std::min(p.x, q.x) >= x1 || std::max(p.y, q.y) <= y0 || std::min(p.y, q.y) >= y1)
      return false;  // the open triangle lies strictly inside its box
    return segment_meets_open_triangle(a, b, c, p, q);
  };
  for (const auto& e : constraints())
    if (meets(e[0], e[1])) return false;
  // No boundary point in the open triangle: it lies wholly inside or wholly outside; a vertex strictly
  // inside the domain decides (the domain contains a neighbourhood of it, which meets the triangle).
  for (const Point2 v : {a, b, c}) {
    const DomainSide side = locate(v);
    if (side == DomainSide::inside) return true;
    if (side == DomainSide::outside) return false;  // a vertex strictly outside: the open triangle is too
  }
  LAGUERRE_PRECONDITION(false, "Domain::triangle_inside needs a vertex strictly inside the domain; all three are on its boundary.");
  return false;
}

Domain read_domain(const std::string& path) {
  std::ifstream in = open_input_file(path, "domain file");
  std::vector<Point2> outer;
  std::vector<std::vector<Point2>> holes;
  std::vector<std::array<Point2, 2>> segments;
  std::vector<Point2>* current = nullptr;
  bool have_outer = false;
  std::string text;
  std::size_t line = 0;
  auto fail = [&](const std::string& message) -> DomainError {
    return DomainError(path + ":" + std::to_string(line) + ": " + message);
  };
  auto numbers = [&](std::istringstream& words, std::size_t count, const std::string& what) {
    std::vector<double> v;
    std::string w;
    while (words >> w) {
      char* end = nullptr;
      const double x = std::strtod(w.c_str(), &end);
      if (*end != '\0' || !std::isfinite(x)) throw fail("expected a finite number in " + what + ", found '" + w + "'");
      if (!admissible_magnitude(x))
        throw fail("found '" + w + "' in " + what + "; expected 0 or a magnitude between 1e-150 and 1e150 (squares and "
                   "products of two coordinates must be finite, normal doubles)");
      v.push_back(x);
    }
    if (v.size() != count)
      throw fail("expected " + std::to_string(count) + " numbers for " + what + ", found " + std::to_string(v.size()));
    return v;
  };
  while (std::getline(in, text)) {
    ++line;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    std::string first;
    if (!(words >> first)) continue;
    if (first == "outer") {
      if (have_outer) throw fail("a second 'outer' boundary (a domain has exactly one)");
      have_outer = true;
      current = &outer;
    } else if (first == "hole") {
      holes.emplace_back();
      current = &holes.back();
    } else if (first == "segment") {
      const auto v = numbers(words, 4, "'segment x1 y1 x2 y2'");
      segments.push_back({Point2{v[0], v[1]}, Point2{v[2], v[3]}});
    } else {
      if (!current) throw fail("expected 'outer', 'hole' or 'segment', found '" + first + "'");
      std::istringstream all(text);
      const auto v = numbers(all, 2, "a vertex 'x y'");
      current->push_back({v[0], v[1]});
    }
  }
  if (!have_outer) throw DomainError(path + ": no 'outer' boundary");
  try {
    return Domain(std::move(outer), std::move(holes), std::move(segments));
  } catch (const DomainError& e) {
    throw DomainError(path + ": " + e.what());
  }
}

}  // namespace laguerre::core
