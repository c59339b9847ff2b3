#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Delaunay.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/scenarios/fields/Deployment.hpp"
#include "laguerre/scenarios/fields/FieldGraph.hpp"
#include "laguerre/scenarios/fields/ProximityGraphs.hpp"

using namespace laguerre::scenarios;
using laguerre::core::Domain;
using laguerre::core::Point2;
using laguerre::core::Sign;
using laguerre::core::Vertex;
namespace core = laguerre::core;

namespace {

/// Points with small integer coordinates: every expression below is exact in plain doubles, and ties
/// (equal distances, cocircular and collinear points) are frequent.
std::vector<Point2> integer_points(std::size_t n, int range, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::set<std::pair<int, int>> seen;
  std::vector<Point2> out;
  while (out.size() < n) {
    const int x = static_cast<int>(engine() % static_cast<std::uint64_t>(range));
    const int y = static_cast<int>(engine() % static_cast<std::uint64_t>(range));
    if (seen.emplace(x, y).second) out.push_back({double(x), double(y)});
  }
  return out;
}

double d2(Point2 a, Point2 b) { return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y); }

/// Brute-force definitions in plain arithmetic (exact for integer points).
EdgeList brute(const std::vector<Point2>& p, double r, bool rng) {
  EdgeList out;
  for (Vertex u = 0; u < p.size(); ++u)
    for (Vertex v = u + 1; v < p.size(); ++v) {
      if (d2(p[u], p[v]) > r * r) continue;
      bool ok = true;
      for (Vertex w = 0; w < p.size() && ok; ++w) {
        if (w == u || w == v) continue;
        if (rng)
          ok = !(d2(p[u], p[w]) < d2(p[u], p[v]) && d2(p[v], p[w]) < d2(p[u], p[v]));
        else
          ok = (p[u].x - p[w].x) * (p[v].x - p[w].x) + (p[u].y - p[w].y) * (p[v].y - p[w].y) > 0;
      }
      if (ok) out.emplace_back(u, v);
    }
  return out;
}

EdgeList brute_udg(const std::vector<Point2>& p, double r) {
  EdgeList out;
  for (Vertex u = 0; u < p.size(); ++u)
    for (Vertex v = u + 1; v < p.size(); ++v)
      if (d2(p[u], p[v]) <= r * r) out.emplace_back(u, v);
  return out;
}

bool subset(const EdgeList& a, const EdgeList& b) { return std::includes(b.begin(), b.end(), a.begin(), a.end()); }

EdgeList intersect(const EdgeList& a, const EdgeList& b) {
  EdgeList out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

/// The first pair of edges whose closed segments meet outside a shared endpoint, as a message, or "".
std::string crossing(const std::vector<Point2>& p, const EdgeList& e) {
  for (std::size_t i = 0; i < e.size(); ++i)
    for (std::size_t j = i + 1; j < e.size(); ++j) {
      const auto [a, b] = e[i];
      const auto [c, d] = e[j];
      if (a == c || a == d || b == c || b == d) continue;
      if (core::segments_intersect(p[a], p[b], p[c], p[d]))
        return std::to_string(a) + "-" + std::to_string(b) + " x " + std::to_string(c) + "-" + std::to_string(d);
    }
  return "";
}

std::vector<Point2> random_points(std::size_t n, std::uint64_t seed) {
  return deploy_uniform(Domain::rectangle(0, 0, 1, 1), n, seed);
}

}  // namespace

TEST(ProximityGraphs, GabrielRngAndUdgMatchBruteForceOnIntegerPoints) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const auto p = integer_points(70, 12, seed);  // 70 of 144 lattice points: many ties
    for (double r : {2.0, 3.0, 5.0, 100.0}) {
      SCOPED_TRACE("seed " + std::to_string(seed) + ", R " + std::to_string(r));
      EXPECT_EQ(unit_disk_edges(p, r), brute_udg(p, r));
      EXPECT_EQ(gabriel_edges(p, r), brute(p, r, false));
      EXPECT_EQ(relative_neighbourhood_edges(p, r), brute(p, r, true));
    }
  }
}

TEST(ProximityGraphs, GabrielAndRngMatchBruteForceOnRandomPoints) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto p = random_points(150, seed);
    for (double r : {0.08, 0.15, 2.0}) {
      EdgeList g, rn;
      for (Vertex u = 0; u < p.size(); ++u)
        for (Vertex v = u + 1; v < p.size(); ++v) {
          if (core::compare_length(p[u], p[v], r) == Sign::positive) continue;
          bool gab = true, rel = true;
          for (Vertex w = 0; w < p.size(); ++w) {
            if (w == u || w == v) continue;
            gab = gab && core::diametral_side(p[u], p[v], p[w]) == Sign::positive;
            rel = rel && !(core::compare_distance(p[u], p[w], p[v]) == Sign::negative &&
                           core::compare_distance(p[v], p[w], p[u]) == Sign::negative);
          }
          if (gab) g.emplace_back(u, v);
          if (rel) rn.emplace_back(u, v);
        }
      EXPECT_EQ(gabriel_edges(p, r), g);
      EXPECT_EQ(relative_neighbourhood_edges(p, r), rn);
    }
  }
}

TEST(ProximityGraphs, NestingRngGabrielDelaunayUdg) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    for (const auto& [p, r] : {std::pair{random_points(400, seed), 0.1}, std::pair{integer_points(100, 14, seed), 3.0}}) {
      const EdgeList del = delaunay_edges(p), udg = unit_disk_edges(p, r);
      const EdgeList gab = gabriel_edges(p, r), rng = relative_neighbourhood_edges(p, r);
      EXPECT_TRUE(subset(rng, gab));
      EXPECT_TRUE(subset(gab, intersect(del, udg)));
      EXPECT_EQ(crossing(p, gab), "");
    }
  }
}

TEST(ProximityGraphs, DelaunayFacadeHasEmptyCircles) {
  const auto p = random_points(300, 11);
  const auto tris = core::delaunay_triangles(p);
  for (const auto& t : tris) {
    ASSERT_EQ(core::orientation(p[t[0]], p[t[1]], p[t[2]]), Sign::positive);
    for (std::size_t x = 0; x < p.size(); ++x)
      if (x != t[0] && x != t[1] && x != t[2]) {
        ASSERT_NE(core::in_circle(p[t[0]], p[t[1]], p[t[2]], p[x]), Sign::positive);
      }
  }
  // Euler: a triangulation of n points with h on the hull has 2n − 2 − h triangles.
  std::set<std::pair<std::size_t, std::size_t>> directed;
  for (const auto& t : tris)
    for (int i = 0; i < 3; ++i) directed.emplace(t[i], t[(i + 1) % 3]);
  std::size_t hull = 0;
  for (auto [a, b] : directed) hull += directed.count({b, a}) == 0;
  EXPECT_EQ(tris.size(), 2 * p.size() - 2 - hull);
  const std::vector<Point2> twice{{0, 0}, {1, 0}, {0, 0}};
  EXPECT_THROW(core::delaunay_triangles(twice), laguerre::core::InternalError);
  const std::vector<Point2> line{{0, 0}, {1, 0}, {2, 0}};
  EXPECT_TRUE(core::delaunay_triangles(line).empty());
}

TEST(ProximityGraphs, LocalDelaunayIsPlaneContainsGabrielAndMatchesItsDefinition) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const auto p = random_points(120, seed);
    for (double r : {0.12, 0.2}) {
      for (unsigned k : {1u, 2u, 3u}) {
        SCOPED_TRACE("seed " + std::to_string(seed) + ", R " + std::to_string(r) + ", k " + std::to_string(k));
        const EdgeList ldel = local_delaunay_edges(p, r, k);
        const EdgeList udg = unit_disk_edges(p, r);
        EXPECT_TRUE(subset(gabriel_edges(p, r), ldel));
        EXPECT_TRUE(subset(ldel, udg));
        if (k >= 2) {
          EXPECT_EQ(crossing(p, ldel), "");
        }
        // Brute force: every triple with UDG edges, circumcircle empty of the k-hop neighbourhood.
        std::vector<std::vector<Vertex>> adj(p.size());
        for (auto [a, b] : udg) {
          adj[a].push_back(b);
          adj[b].push_back(a);
        }
        EdgeList expected = gabriel_edges(p, r);
        const std::set<std::pair<Vertex, Vertex>> in_udg(udg.begin(), udg.end());
        for (Vertex a = 0; a < p.size(); ++a)
          for (Vertex b = a + 1; b < p.size(); ++b)
            for (Vertex c = b + 1; c < p.size(); ++c) {
              if (!in_udg.count({a, b}) || !in_udg.count({a, c}) || !in_udg.count({b, c})) continue;
              std::vector<int> hops(p.size(), -1);
              std::vector<Vertex> frontier{a, b, c};
              for (Vertex v : frontier) hops[v] = 0;
              for (unsigned level = 1; level <= k; ++level) {
                std::vector<Vertex> next;
                for (Vertex v : frontier)
                  for (Vertex w : adj[v])
                    if (hops[w] < 0) {
                      hops[w] = static_cast<int>(level);
                      next.push_back(w);
                    }
                frontier = next;
              }
              const bool ccw = core::orientation(p[a], p[b], p[c]) == Sign::positive;
              const Point2 pa = p[a], pb = ccw ? p[b] : p[c], pc = ccw ? p[c] : p[b];
              bool empty = true;
              for (Vertex x = 0; x < p.size() && empty; ++x)
                if (x != a && x != b && x != c && hops[x] >= 0 && core::in_circle(pa, pb, pc, p[x]) == Sign::positive)
                  empty = false;
              if (empty) {
                expected.emplace_back(a, b);
                expected.emplace_back(a, c);
                expected.emplace_back(b, c);
              }
            }
        std::sort(expected.begin(), expected.end());
        expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
        EXPECT_EQ(ldel, expected);
      }
    }
  }
}

TEST(ProximityGraphs, RestrictedDelaunayKeepsOnlyTrianglesInsideTheDomain) {
  const Domain domain({{0, 0}, {10, 0}, {10, 10}, {6, 10}, {6, 4}, {4, 4}, {4, 10}, {0, 10}},  // a U
                      {{{1, 1}, {3, 1}, {2, 3}}, {{7, 5}, {9, 5}, {9, 7}, {7, 7}}});
  const auto p = deploy_uniform(domain, 600, 5);
  const EdgeList edges = restricted_delaunay_edges(domain, p);
  // No edge meets the boundary (the points are strictly inside, so meeting means crossing).
  std::vector<std::pair<Point2, Point2>> boundary;
  const auto add = [&](const std::vector<Point2>& poly) {
    for (std::size_t i = 0; i < poly.size(); ++i) boundary.emplace_back(poly[i], poly[(i + 1) % poly.size()]);
  };
  add(domain.outer());
  for (const auto& h : domain.holes()) add(h);
  for (auto [a, b] : edges)
    for (auto [s, t] : boundary) ASSERT_FALSE(core::segments_intersect(p[a], p[b], s, t));
  // No boundary vertex strictly inside a kept triangle (with the above: no boundary point in one).
  const FieldGraph fg =
      build_field_graph(domain, p, {FieldGraphType::delaunay, 0, 2, RepairPolicy::three_connected_core, "U"});
  const auto& g = fg.input.graph;
  std::size_t triangles = 0;
  for (core::Face f = 0; f < g.num_faces(); ++f) {
    if (f == g.outer_face() || g.face_size(f) != 3) continue;
    ++triangles;
    const auto darts = g.face_darts(f);
    const Point2 a = fg.input.positions[g.tail(darts[0])], b = fg.input.positions[g.tail(darts[1])],
                 c = fg.input.positions[g.tail(darts[2])];
    for (auto [s, t] : boundary)
      ASSERT_FALSE(core::orientation(a, b, s) == Sign::positive && core::orientation(b, c, s) == Sign::positive &&
                   core::orientation(c, a, s) == Sign::positive);
  }
  // The two holes stay faces (the core is 3-connected, not a triangulated disc) and few points are lost.
  EXPECT_EQ(fg.kind, core::GraphKind::three_connected);
  EXPECT_TRUE(core::is_three_connected(g));
  EXPECT_EQ(fg.report.non_triangular_faces, 2u);
  std::size_t big_faces = 0;
  for (core::Face f = 0; f < g.num_faces(); ++f) big_faces += f != g.outer_face() && g.face_size(f) > 3;
  EXPECT_EQ(big_faces, 2u);
  EXPECT_LT(fg.report.removed_points, 30u);
  EXPECT_GT(triangles, 1000u);
  // In a convex domain without holes, nothing is dropped.
  const Domain square = Domain::rectangle(0, 0, 1, 1);
  const auto q = deploy_uniform(square, 500, 9);
  EXPECT_EQ(restricted_delaunay_edges(square, q), delaunay_edges(q));
  const std::vector<Point2> outside{{0.5, 0.5}, {0.2, 0.2}, {2, 2}};
  EXPECT_THROW(restricted_delaunay_edges(square, outside), laguerre::core::InternalError);
}
