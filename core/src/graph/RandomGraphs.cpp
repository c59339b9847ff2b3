#include "laguerre/core/graph/RandomGraphs.hpp"

#include "laguerre/core/random/Random.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>

#include "laguerre/core/graph/GraphKind.hpp"

namespace laguerre::core {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tds = CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_with_info_2<Vertex, Kernel>>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;

/// n distinct uniform points in the open unit disc and their Delaunay edges (as index pairs).
/// A point equal to an earlier one is redrawn; the whole set is redrawn in the probability-zero event
/// that all points are collinear. The Delaunay edges of points in general position do not depend on
/// the insertion order, so CGAL's spatial sorting of the range does not affect the result.
void draw_delaunay(std::size_t n, SeededRandom& random, std::vector<Point2>& points,
                   std::vector<std::pair<Vertex, Vertex>>& edges) {
  const auto draw_point = [&random]() {
    for (;;) {
      const double x = 2 * random.uniform01() - 1, y = 2 * random.uniform01() - 1;
      if (x * x + y * y < 1) return Point2{x, y};
    }
  };
  for (;;) {
    points.clear();
    for (std::size_t i = 0; i < n; ++i) points.push_back(draw_point());
    for (;;) {  // replace repeated points, in index order
      std::vector<Vertex> order(n);
      for (Vertex i = 0; i < n; ++i) order[i] = i;
      const auto key = [&](Vertex i) { return std::tuple{points[i].x, points[i].y, i}; };
      std::sort(order.begin(), order.end(), [&](Vertex a, Vertex b) { return key(a) < key(b); });
      bool repeated = false;
      for (std::size_t k = 1; k < n; ++k)
        if (points[order[k]].x == points[order[k - 1]].x && points[order[k]].y == points[order[k - 1]].y) {
          points[order[k]] = draw_point();
          repeated = true;
        }
      if (!repeated) break;
    }
    std::vector<std::pair<Kernel::Point_2, Vertex>> sites;
    sites.reserve(n);
    for (Vertex i = 0; i < n; ++i) sites.emplace_back(Kernel::Point_2(points[i].x, points[i].y), i);
    Delaunay dt;
    dt.insert(sites.begin(), sites.end());
    if (dt.dimension() < 2) continue;
    edges.clear();
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
      const auto f = e->first;
      const int i = e->second;
      edges.emplace_back(f->vertex(Delaunay::cw(i))->info(), f->vertex(Delaunay::ccw(i))->info());
    }
    return;
  }
}

std::vector<std::uint64_t> iota_ids(std::size_t n) {
  std::vector<std::uint64_t> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = i;
  return ids;
}

std::string generator_name(const char* family, std::size_t n, std::uint64_t seed) {
  return std::string(family) + "(n=" + std::to_string(n) + ", seed=" + std::to_string(seed) + ")";
}

std::uint64_t dart_key(Vertex u, Vertex v) { return (static_cast<std::uint64_t>(u) << 32) | v; }

/// Edge deletion preserving 3-connectivity, on a mutable rotation system with explicit face walks.
class Thinning {
public:
  explicit Thinning(const PlanarGraph& g) : rotation_(g.num_vertices()), walks_(g.num_faces()) {
    for (Vertex v = 0; v < g.num_vertices(); ++v) {
      const auto list = g.neighbours(v);
      rotation_[v].assign(list.begin(), list.end());
    }
    for (Face f = 0; f < g.num_faces(); ++f)
      for (Dart d : g.face_darts(f)) {
        walks_[f].push_back(g.tail(d));
        face_[dart_key(g.tail(d), g.head(d))] = f;
      }
  }

  Face face(Vertex u, Vertex v) const { return face_.at(dart_key(u, v)); }

  /// Deletes edge uv if the graph stays 3-connected and the merged face has at most `max_face` vertices.
  bool try_delete(Vertex u, Vertex v, std::size_t max_face) {
    if (rotation_[u].size() <= 3 || rotation_[v].size() <= 3) return false;
    const Face f1 = face(u, v), f2 = face(v, u);
    if (walks_[f1].size() + walks_[f2].size() - 2 > max_face) return false;
    // Merged walk: f1 is u→v→a1…ak→u and f2 is v→u→b1…bl→v; the new face is v→a1…ak→u→b1…bl→v.
    const auto from = [](const std::vector<Vertex>& walk, Vertex start) {
      std::vector<Vertex> out(walk.size());
      const auto at = std::find(walk.begin(), walk.end(), start);
      std::rotate_copy(walk.begin(), at, walk.end(), out.begin());
      return out;
    };
    const std::vector<Vertex> w1 = from(walks_[f1], u), w2 = from(walks_[f2], v);
    std::vector<Vertex> merged(w1.begin() + 1, w1.end());  // v, a1 … ak
    merged.insert(merged.end(), w2.begin() + 1, w2.end());  // u, b1 … bl
    // The old graph is 3-connected, so only pairs (merged face, other face) can break the criterion of
    // is_three_connected: each other face may meet the merged one in at most one vertex or one edge
    // whose other side it is.
    std::vector<std::pair<Face, std::size_t>> meets;  // (other face, position in merged)
    for (std::size_t i = 0; i < merged.size(); ++i)
      for (Vertex w : rotation_[merged[i]]) {
        const Face h = face(merged[i], w);
        if (h != f1 && h != f2) meets.emplace_back(h, i);
      }
    std::sort(meets.begin(), meets.end());
    const std::size_t k = merged.size();
    for (std::size_t a = 0; a < meets.size();) {
      std::size_t b = a;
      while (b < meets.size() && meets[b].first == meets[a].first) ++b;
      if (b - a >= 3) return false;
      if (b - a == 2) {
        const std::size_t i = meets[a].second, j = meets[a + 1].second;  // i < j
        const Face h = meets[a].first;
        if (j == i + 1) {  // merged has the dart merged[i]→merged[j]; its other side must be h
          if (face(merged[j], merged[i]) != h) return false;
        } else if (i == 0 && j == k - 1) {  // the dart merged[j]→merged[0]
          if (face(merged[i], merged[j]) != h) return false;
        } else {
          return false;
        }
      }
      a = b;
    }
    std::erase(rotation_[u], v);
    std::erase(rotation_[v], u);
    face_.erase(dart_key(u, v));
    face_.erase(dart_key(v, u));
    for (std::size_t i = 0; i < k; ++i) face_[dart_key(merged[i], merged[(i + 1) % k])] = f1;
    walks_[f1] = std::move(merged);
    walks_[f2].clear();
    return true;
  }

  /// The remaining edges as index pairs.
  std::vector<std::pair<Vertex, Vertex>> edges() const {
    std::vector<std::pair<Vertex, Vertex>> out;
    for (Vertex v = 0; v < rotation_.size(); ++v)
      for (Vertex w : rotation_[v])
        if (v < w) out.emplace_back(v, w);
    return out;
  }

private:
  std::vector<std::vector<Vertex>> rotation_;
  std::vector<std::vector<Vertex>> walks_;
  std::unordered_map<std::uint64_t, Face> face_;
};

}  // namespace

GraphInput random_delaunay_triangulation(std::size_t n, std::uint64_t seed) {
  if (n < 3)
    throw GraphInputError(generator_name("random_delaunay_triangulation", n, seed), 0, 0,
                          "a random Delaunay triangulation needs at least 3 vertices, not " + std::to_string(n) + ".");
  SeededRandom random(seed);
  std::vector<Point2> points;
  std::vector<std::pair<Vertex, Vertex>> edges;
  draw_delaunay(n, random, points, edges);
  return graph_from_drawing(iota_ids(n), std::move(points), edges,
                            generator_name("random_delaunay_triangulation", n, seed), false);
}

GraphInput random_three_connected(std::size_t n, std::uint64_t seed, double deletions_per_vertex,
                                  std::size_t max_face_size) {
  const std::string name = generator_name("random_three_connected", n, seed);
  if (n < 4)
    throw GraphInputError(name, 0, 0, "a random 3-connected graph needs at least 4 vertices, not " + std::to_string(n) + ".");
  if (max_face_size < 4)
    throw GraphInputError(name, 0, 0,
                          "the maximum face size of a random 3-connected graph must be at least 4, not " +
                              std::to_string(max_face_size) + ".");
  if (!(deletions_per_vertex >= 0) || !std::isfinite(deletions_per_vertex))
    throw GraphInputError(name, 0, 0, "the number of deletions per vertex must be a finite non-negative number.");
  SeededRandom random(seed);
  std::vector<Point2> points;
  std::vector<std::pair<Vertex, Vertex>> edges;
  GraphInput start;
  constexpr int max_attempts = 10000;
  for (int attempt = 0;; ++attempt) {
    if (attempt == max_attempts)
      throw std::runtime_error("No 3-connected Delaunay triangulation of " + std::to_string(n) +
                               " random points was found in " + std::to_string(max_attempts) + " attempts.");
    draw_delaunay(n, random, points, edges);
    start = graph_from_drawing(iota_ids(n), points, edges, name, false);
    if (is_three_connected(start.graph)) break;
  }
  const PlanarGraph& g = start.graph;
  std::vector<std::pair<Vertex, Vertex>> candidates;
  for (Dart d = 0; d < g.num_darts(); ++d) {
    const Vertex u = g.tail(d), v = g.head(d);
    if (u < v && g.face_of(d) != g.outer_face() && g.face_of(g.twin(d)) != g.outer_face())
      candidates.emplace_back(u, v);
  }
  for (std::size_t i = candidates.size(); i > 1; --i)  // Fisher–Yates with our own integer draws
    std::swap(candidates[i - 1], candidates[random.below(i)]);
  const auto target = static_cast<std::size_t>(std::llround(deletions_per_vertex * static_cast<double>(n)));
  Thinning thinning(g);
  std::size_t deleted = 0;
  for (auto [u, v] : candidates) {
    if (deleted >= target) break;
    if (thinning.try_delete(u, v, max_face_size)) ++deleted;
  }
  return graph_from_drawing(iota_ids(n), std::move(points), thinning.edges(), name, false);
}

}  // namespace laguerre::core
