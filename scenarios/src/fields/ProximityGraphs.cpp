#include "laguerre/scenarios/fields/ProximityGraphs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Delaunay.hpp"

namespace laguerre::scenarios {

using core::Point2;
using core::Sign;
using core::Vertex;

namespace {

void check_radius(double radius) {
  LAGUERRE_PRECONDITION(radius > 0 && std::isfinite(radius),
                        "the unit-disk radius must be a positive finite number, not " + std::to_string(radius) + ".");
}

/// Points bucketed in a uniform grid of square cells of side h ≥ R(1 + 1e-9): two points at distance
/// ≤ R lie in the same or adjacent cells despite the rounding of the cell computation. The side grows
/// when the box would need more than 4n + 16 cells (sparse points, tiny R): still correct, only slower.
class Grid {
public:
  Grid(std::span<const Point2> points, double radius) : points_(points) {
    xmin_ = ymin_ = std::numeric_limits<double>::infinity();
    double xmax = -xmin_, ymax = -ymin_;
    for (Point2 p : points) {
      xmin_ = std::min(xmin_, p.x);
      ymin_ = std::min(ymin_, p.y);
      xmax = std::max(xmax, p.x);
      ymax = std::max(ymax, p.y);
    }
    if (points.empty()) xmin_ = ymin_ = xmax = ymax = 0;
    h_ = radius * (1 + 1e-9);
    const double limit = 4.0 * static_cast<double>(points.size()) + 16;
    while (((xmax - xmin_) / h_ + 1) * ((ymax - ymin_) / h_ + 1) > limit) h_ *= 2;
    nx_ = static_cast<std::size_t>((xmax - xmin_) / h_) + 1;
    ny_ = static_cast<std::size_t>((ymax - ymin_) / h_) + 1;
    start_.assign(nx_ * ny_ + 1, 0);
    cell_.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      cell_[i] = cell_of(points[i]);
      ++start_[cell_[i] + 1];
    }
    for (std::size_t c = 0; c < nx_ * ny_; ++c) start_[c + 1] += start_[c];
    members_.resize(points.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i) members_[fill[cell_[i]]++] = static_cast<Vertex>(i);
  }

  /// Calls f(j) for every point j in the cells whose index ranges cover [x0, x1] × [y0, y1], widened by one
  /// cell on each side (so rounding never loses a point of the box).
  template <class F>
  void for_each_near(double x0, double y0, double x1, double y1, F&& f) const {
    const auto clampx = [&](double x) { return clamp_index((x - xmin_) / h_, nx_); };
    const auto clampy = [&](double y) { return clamp_index((y - ymin_) / h_, ny_); };
    const std::size_t cx0 = clampx(x0) > 0 ? clampx(x0) - 1 : 0, cx1 = std::min(clampx(x1) + 1, nx_ - 1);
    const std::size_t cy0 = clampy(y0) > 0 ? clampy(y0) - 1 : 0, cy1 = std::min(clampy(y1) + 1, ny_ - 1);
    for (std::size_t cy = cy0; cy <= cy1; ++cy)
      for (std::size_t cx = cx0; cx <= cx1; ++cx) {
        const std::size_t c = cy * nx_ + cx;
        for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) f(members_[k]);
      }
  }

  /// Calls f(j) for every point j in the 3 × 3 cells around point i.
  template <class F>
  void for_each_candidate(std::size_t i, F&& f) const {
    const std::size_t cx = cell_[i] % nx_, cy = cell_[i] / nx_;
    for (std::size_t y = cy > 0 ? cy - 1 : 0; y <= std::min(cy + 1, ny_ - 1); ++y)
      for (std::size_t x = cx > 0 ? cx - 1 : 0; x <= std::min(cx + 1, nx_ - 1); ++x) {
        const std::size_t c = y * nx_ + x;
        for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) f(members_[k]);
      }
  }

  double cell_size() const { return h_; }

private:
  static std::size_t clamp_index(double t, std::size_t n) {
    if (!(t > 0)) return 0;
    if (t >= static_cast<double>(n - 1)) return n - 1;
    return static_cast<std::size_t>(t);
  }
  std::size_t cell_of(Point2 p) const { return clamp_index((p.y - ymin_) / h_, ny_) * nx_ + clamp_index((p.x - xmin_) / h_, nx_); }

  std::span<const Point2> points_;
  double xmin_ = 0, ymin_ = 0, h_ = 1;
  std::size_t nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_;
  std::vector<std::size_t> cell_;
  std::vector<Vertex> members_;
};

/// The unit-disk graph as sorted adjacency lists (compressed rows).
struct Adjacency {
  std::vector<std::size_t> offset;
  std::vector<Vertex> list;
  std::span<const Vertex> operator[](std::size_t v) const { return {list.data() + offset[v], offset[v + 1] - offset[v]}; }
};

Adjacency unit_disk_adjacency(std::span<const Point2> points, double radius, const Grid& grid) {
  const std::size_t n = points.size();
  Adjacency adj;
  adj.offset.assign(n + 1, 0);
  std::vector<Vertex> row;
  for (std::size_t i = 0; i < n; ++i) {
    row.clear();
    grid.for_each_candidate(i, [&](Vertex j) {
      if (j != i && core::compare_length(points[i], points[j], radius) != Sign::positive) row.push_back(j);
    });
    std::sort(row.begin(), row.end());
    adj.offset[i + 1] = adj.offset[i] + row.size();
    adj.list.insert(adj.list.end(), row.begin(), row.end());
  }
  return adj;
}

EdgeList edges_of(const Adjacency& adj) {
  EdgeList edges;
  for (std::size_t u = 0; u + 1 < adj.offset.size(); ++u)
    for (Vertex v : adj[u])
      if (u < v) edges.emplace_back(static_cast<Vertex>(u), v);
  return edges;
}

/// UDG edges uv (u < v) that no other neighbour w of u rejects: reject(u, v, w) true means w witnesses
/// that uv is not an edge. Both spanners' witnesses lie within |uv| ≤ R of u (see the header), so u's
/// neighbours are enough.
template <class Reject>
EdgeList filtered_udg(std::span<const Point2> points, double radius, Reject&& reject) {
  check_radius(radius);
  const Grid grid(points, radius);
  const Adjacency adj = unit_disk_adjacency(points, radius, grid);
  EdgeList edges;
  for (std::size_t u = 0; u < points.size(); ++u)
    for (Vertex v : adj[u]) {
      if (v < u) continue;
      bool keep = true;
      for (Vertex w : adj[u])
        if (w != v && reject(points[u], points[v], points[w])) {
          keep = false;
          break;
        }
      if (keep) edges.emplace_back(static_cast<Vertex>(u), v);
    }
  return edges;
}

bool gabriel_reject(Point2 u, Point2 v, Point2 w) { return core::diametral_side(u, v, w) != Sign::positive; }

bool rng_reject(Point2 u, Point2 v, Point2 w) {
  return core::compare_distance(u, w, v) == Sign::negative && core::compare_distance(v, w, u) == Sign::negative;
}

void add_triangle_edges(EdgeList& edges, const std::array<std::size_t, 3>& t) {
  for (int i = 0; i < 3; ++i) {
    const auto a = static_cast<Vertex>(t[i]), b = static_cast<Vertex>(t[(i + 1) % 3]);
    edges.emplace_back(std::min(a, b), std::max(a, b));
  }
}

void sort_unique(EdgeList& edges) {
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
}

}  // namespace

EdgeList delaunay_edges(std::span<const Point2> points) {
  EdgeList edges;
  for (const auto& t : core::delaunay_triangles(points)) add_triangle_edges(edges, t);
  sort_unique(edges);
  return edges;
}

EdgeList restricted_delaunay_edges(const core::Domain& domain, std::span<const Point2> points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    LAGUERRE_PRECONDITION(domain.locate(points[i]) == core::DomainSide::inside,
                          "point " + std::to_string(i) + " is not strictly inside the domain.");
  EdgeList edges;
  for (const auto& t : core::delaunay_triangles(points))
    if (domain.triangle_inside(points[t[0]], points[t[1]], points[t[2]])) add_triangle_edges(edges, t);
  sort_unique(edges);
  return edges;
}

EdgeList unit_disk_edges(std::span<const Point2> points, double radius) {
  check_radius(radius);
  const Grid grid(points, radius);
  return edges_of(unit_disk_adjacency(points, radius, grid));
}

EdgeList gabriel_edges(std::span<const Point2> points, double radius) {
  return filtered_udg(points, radius, gabriel_reject);
}

EdgeList relative_neighbourhood_edges(std::span<const Point2> points, double radius) {
  return filtered_udg(points, radius, rng_reject);
}

EdgeList local_delaunay_edges(std::span<const Point2> points, double radius, unsigned k) {
  LAGUERRE_PRECONDITION(k > 0, "the localized Delaunay graph needs k >= 1 hops.");
  EdgeList edges = gabriel_edges(points, radius);
  const std::size_t n = points.size();
  const Grid grid(points, radius);
  const Adjacency adj = unit_disk_adjacency(points, radius, grid);

  // Candidates: the triangles at u of Del(N[u]) whose smallest vertex is u and whose third edge is short.
  std::vector<std::array<Vertex, 3>> candidates;
  std::vector<Point2> local;
  std::vector<Vertex> ids;
  for (std::size_t u = 0; u < n; ++u) {
    const auto nb = adj[u];
    if (nb.size() < 2 || nb.back() < u) continue;
    ids.assign(1, static_cast<Vertex>(u));
    ids.insert(ids.end(), nb.begin(), nb.end());
    local.clear();
    for (Vertex v : ids) local.push_back(points[v]);
    for (const auto& t : core::delaunay_triangles(local)) {
      if (t[0] != 0) continue;  // triples start at their smallest local index; 0 is u
      const Vertex v = ids[t[1]], w = ids[t[2]];
      if (v < u || w < u) continue;
      if (core::compare_length(points[v], points[w], radius) == Sign::positive) continue;
      candidates.push_back({static_cast<Vertex>(u), v, w});  // counter-clockwise
    }
  }

  // A candidate survives if no point within k hops of its vertices is strictly inside its circumcircle.
  // Such a point lies within k R of a vertex: scan the grid there, and only for points inside the
  // circle compute hop distances (breadth-first from the three vertices, at most k levels).
  std::vector<std::uint32_t> stamp(n, 0);
  std::uint32_t round = 0;
  std::vector<Vertex> frontier, next;
  const double reach = static_cast<double>(k) * radius;
  for (const auto& tri : candidates) {
    const Point2 a = points[tri[0]], b = points[tri[1]], c = points[tri[2]];
    std::vector<Vertex> inside;
    double x0 = std::min({a.x, b.x, c.x}) - reach, y0 = std::min({a.y, b.y, c.y}) - reach;
    double x1 = std::max({a.x, b.x, c.x}) + reach, y1 = std::max({a.y, b.y, c.y}) + reach;
    // Narrow the scan to the circumcircle's box when the triangle is well-shaped (its sine at a is at
    // least 1e-6): the circumcentre computed in doubles is then within ~1e-9 R of the true one, far
    // inside the 1e-6 (r + R) margin. The exact in_circle below still decides every point scanned.
    const double bx = b.x - a.x, by = b.y - a.y, cx = c.x - a.x, cy = c.y - a.y;
    const double det = bx * cy - by * cx, lb = bx * bx + by * by, lc = cx * cx + cy * cy;
    if (det > 1e-6 * std::sqrt(lb * lc)) {
      const double ox = (cy * lb - by * lc) / (2 * det), oy = (bx * lc - cx * lb) / (2 * det);
      const double r = std::sqrt(ox * ox + oy * oy), margin = 1e-6 * (r + radius);
      x0 = std::max(x0, a.x + ox - r - margin);
      y0 = std::max(y0, a.y + oy - r - margin);
      x1 = std::min(x1, a.x + ox + r + margin);
      y1 = std::min(y1, a.y + oy + r + margin);
    }
    grid.for_each_near(x0, y0, x1, y1, [&](Vertex x) {
                         if (x != tri[0] && x != tri[1] && x != tri[2] &&
                             core::in_circle(a, b, c, points[x]) == Sign::positive)
                           inside.push_back(x);
                       });
    bool empty = true;
    if (!inside.empty()) {
      ++round;
      frontier.assign(tri.begin(), tri.end());
      for (Vertex v : frontier) stamp[v] = round;
      for (unsigned level = 0; level < k && !frontier.empty(); ++level) {
        next.clear();
        for (Vertex v : frontier)
          for (Vertex w : adj[v])
            if (stamp[w] != round) {
              stamp[w] = round;
              next.push_back(w);
            }
        frontier.swap(next);
      }
      for (Vertex x : inside)
        if (stamp[x] == round) {
          empty = false;
          break;
        }
    }
    if (empty) add_triangle_edges(edges, {tri[0], tri[1], tri[2]});
  }
  sort_unique(edges);
  return edges;
}

}  // namespace laguerre::scenarios
