#include "AffineCells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>


namespace laguerre::core::detail {

namespace {

/// `v` with 6 significant digits (%g: small areas do not print as 0.000000).
std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

/// A polygon vertex with the label of the side that leaves it (a neighbour, or no_site for the box).
struct LabelledVertex {
  Point2 p;
  SiteIndex label;
};

/// Clips `poly` by {x : pow_i(x) ≤ pow_j(x)}, written relative to p_i for accuracy:
/// h(x) = 2 d·(x − p_i) − |d|² − w_i + w_j ≤ 0 with d = p_j − p_i.
void clip(const std::vector<LabelledVertex>& poly, const WeightedPoint& si, const WeightedPoint& sj, SiteIndex j,
          std::vector<LabelledVertex>& out) {
  const double dx = sj.x - si.x, dy = sj.y - si.y;
  const double c = dx * dx + dy * dy + si.w - sj.w;
  auto h = [&](Point2 x) { return 2 * (dx * (x.x - si.x) + dy * (x.y - si.y)) - c; };
  out.clear();
  const std::size_t n = poly.size();
  for (std::size_t k = 0; k < n; ++k) {
    const LabelledVertex& a = poly[k];
    const LabelledVertex& b = poly[(k + 1) % n];
    const double ha = h(a.p), hb = h(b.p);
    const bool ina = ha <= 0, inb = hb <= 0;
    auto crossing = [&] {
      const double t = ha / (ha - hb);
      return Point2{a.p.x + t * (b.p.x - a.p.x), a.p.y + t * (b.p.y - a.p.y)};
    };
    if (ina) out.push_back(a);
    if (ina && !inb) out.push_back({crossing(), j});
    if (!ina && inb) out.push_back({crossing(), a.label});
  }
}

}  // namespace

AffineCells build_affine_cells(const std::vector<WeightedPoint>& sites, const std::vector<bool>& hidden,
                               const std::vector<std::vector<SiteIndex>>& neighbours, const Box& box) {
  AffineCells out;
  const std::size_t n = sites.size();
  out.cells.assign(n, {});
  const double scale = std::max(box.width(), box.height());
  const double tiny = 1e-12 * scale;
  auto near = [tiny](Point2 a, Point2 b) {
    const double dx = a.x - b.x, dy = a.y - b.y;
    return dx * dx + dy * dy <= tiny * tiny;
  };
  std::vector<LabelledVertex> poly, next, clean;
  const std::vector<Point2> corners = box.corners();
  for (SiteIndex i = 0; i < n; ++i) {
    if (hidden[i]) continue;
    poly.clear();
    for (Point2 c : corners) poly.push_back({c, no_site});
    for (SiteIndex j : neighbours[i]) {
      if (poly.empty()) break;
      clip(poly, sites[i], sites[j], j, next);
      poly.swap(next);
    }
    // Drop repeated vertices (a clip through a corner) keeping the label of the last side.
    clean.clear();
    for (const LabelledVertex& v : poly) {
      if (!clean.empty() && near(v.p, clean.back().p)) {
        clean.back().label = v.label;
        continue;
      }
      clean.push_back(v);
    }
    while (clean.size() > 1 && near(clean.front().p, clean.back().p))
      clean.pop_back();
    if (clean.size() < 3) continue;
    for (std::size_t k = 0; k < clean.size(); ++k) {
      out.cells[i].push_back(clean[k].p);
      const SiteIndex j = clean[k].label;
      if (j != no_site && i < j) out.edges.push_back({i, j, clean[k].p, clean[(k + 1) % clean.size()].p});
    }
  }
  for (SiteIndex i = 0; i < n; ++i)
    for (SiteIndex j : neighbours[i])
      if (i < j) out.dual.emplace_back(i, j);
  std::sort(out.dual.begin(), out.dual.end());
  out.dual.erase(std::unique(out.dual.begin(), out.dual.end()), out.dual.end());
  std::sort(out.edges.begin(), out.edges.end(),
            [](const StraightEdge& e, const StraightEdge& f) { return std::pair(e.a, e.b) < std::pair(f.a, f.b); });
  return out;
}

std::string check_affine_cells(const std::vector<WeightedPoint>& sites, const std::vector<bool>& hidden,
                               const AffineCells& cells, const std::vector<DiagramVertex>& vertices, const Box& box,
                               const std::function<SiteIndex(Point2)>& locate) {
  auto fail = [](std::string m) { return m; };
  const std::size_t n = sites.size();
  // A vertex the doubles cannot represent (a circumcentre whose construction overflowed or underflowed
  // to 0/0) makes every other check meaningless.
  for (std::size_t k = 0; k < vertices.size(); ++k)
    if (!std::isfinite(vertices[k].point.x) || !std::isfinite(vertices[k].point.y))
      return fail("vertex " + std::to_string(k) + " is not finite: the sites' coordinates are beyond what doubles represent");
  // Areas relative to a corner of the box: in absolute coordinates their rounding grows with the box's
  // distance from the origin and swamps the areas of a small box far away.
  const Point2 corner{box.xmin, box.ymin};
  // The vertices are circumcentres rounded to doubles: a bisector's offset z_j − z_i (z = |p|² − w)
  // carries an error of about ε·(|p|² + |w|), which 1/(2|p_i − p_j|) carries into the vertex; the cells'
  // areas then err by up to the cells' perimeters times that (large weights on a tiny box make it
  // dominate the relative bound); and every coordinate is rounded to about ε times the box's distance from
  // the origin, which bends the turns of thin cells far away.
  double magnitude = 0, closest = std::numeric_limits<double>::infinity();
  for (const WeightedPoint& s : sites) magnitude = std::max(magnitude, s.x * s.x + s.y * s.y + std::fabs(s.w));
  for (const auto& [a, b] : cells.dual) closest = std::min(closest, std::hypot(sites[a].x - sites[b].x, sites[a].y - sites[b].y));
  const double eps = std::numeric_limits<double>::epsilon();
  const double far = std::max({std::fabs(box.xmin), std::fabs(box.xmax), std::fabs(box.ymin), std::fabs(box.ymax)});
  const double vertex_error = 4 * eps * far + (closest > 0 && std::isfinite(closest) ? 16 * eps * magnitude / closest : 0.0);
  double total = 0;
  for (SiteIndex i = 0; i < n; ++i) {
    const Polygon& c = cells.cells[i];
    if (hidden[i] && !c.empty()) return fail("hidden site " + std::to_string(i) + " has a non-empty cell");
    if (c.empty()) continue;
    // The shoelace sum of rounded vertices inside the box is exact to about ε·|c|·width·height: a cell
    // whose area is below that is degenerate (a sliver between two nearly equal sites), not clockwise.
    const double a = signed_area(c, corner);
    const double slack = 4 * std::numeric_limits<double>::epsilon() * static_cast<double>(c.size()) * box.width() * box.height();
    if (a < -slack) return fail("cell " + std::to_string(i) + " is clockwise");
    total += a;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Point2 u = c[k], v = c[(k + 1) % c.size()], w = c[(k + 2) % c.size()];
      const double cross = (v.x - u.x) * (w.y - v.y) - (v.y - u.y) * (w.x - v.x);
      const double len = std::hypot(v.x - u.x, v.y - u.y) * std::hypot(w.x - v.x, w.y - v.y);
      const double turn_error = 2 * vertex_error * (std::hypot(v.x - u.x, v.y - u.y) + std::hypot(w.x - v.x, w.y - v.y));
      if (cross < -1e-9 * len - turn_error) return fail("cell " + std::to_string(i) + " is not convex");
    }
    // The centroid lies strictly inside a non-degenerate convex cell: it must locate to i, or to a site
    // at equal power distance (a tie).
    Point2 g{0, 0};
    for (Point2 p : c) g.x += p.x / static_cast<double>(c.size()), g.y += p.y / static_cast<double>(c.size());
    if (a <= 1e-12 * box.width() * box.height()) continue;
    const SiteIndex l = locate(g);
    if (l != i) {
      const double di = power_distance(g, sites[i]), dl = power_distance(g, sites[l]);
      if (std::fabs(di - dl) > 1e-9 * (std::fabs(di) + std::fabs(dl) + 1))
        return fail("the centroid of cell " + std::to_string(i) + " locates in cell " + std::to_string(l));
    }
  }
  for (const auto& [a, b] : cells.dual)
    if (a >= b || b >= n || hidden[a] || hidden[b])
      return fail("dual edge (" + std::to_string(a) + ", " + std::to_string(b) + ") is malformed");
  const double area = box.width() * box.height();
  const double area_slack = 1e-7 * area + 4 * (box.width() + box.height()) * vertex_error * static_cast<double>(cells.dual.size() + 1);
  if (n > 0 && std::fabs(total - area) > area_slack)
    return fail("cell areas add up to " + short_number(total) + ", the box has area " + short_number(area));
  return "";
}

}  // namespace laguerre::core::detail
