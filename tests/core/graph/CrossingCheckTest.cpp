// The plane check of straight-line drawings (graph_from_drawing) against a brute-force oracle: every
// pair of edges without a common vertex tested with the exact segment predicate.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/Embedding.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"

using namespace laguerre::core;

namespace {
bool brute_force_crossing(const std::vector<Point2>& p, const std::vector<std::pair<Vertex, Vertex>>& e) {
  for (std::size_t i = 0; i < e.size(); ++i)
    for (std::size_t j = i + 1; j < e.size(); ++j) {
      const auto [a, b] = e[i];
      const auto [c, d] = e[j];
      if (a == c || a == d || b == c || b == d) continue;
      if (segments_intersect(p[a], p[b], p[c], p[d])) return true;
    }
  return false;
}
}  // namespace

TEST(CrossingCheck, AgreesWithAllPairsOnPerturbedDelaunayDrawings) {
  std::mt19937_64 rng(11);
  int crossing = 0, plane = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const GraphInput in = random_delaunay_triangulation(200, seed);
    const PlanarGraph& g = in.graph;
    std::vector<std::pair<Vertex, Vertex>> edges;
    for (Dart d = 0; d < g.num_darts(); ++d)
      if (g.tail(d) < g.head(d)) edges.emplace_back(g.tail(d), g.head(d));
    std::vector<Point2> pos = in.positions;
    // Move one vertex by a random amount, from nothing (still plane) to far across the drawing.
    const Vertex v = static_cast<Vertex>(rng() % pos.size());
    const double scale = seed % 4 == 0 ? 0.0 : std::ldexp(1.0, -static_cast<int>(rng() % 12));
    std::uniform_real_distribution<double> u(-1, 1);
    pos[v].x += scale * u(rng);
    pos[v].y += scale * u(rng);
    const bool want = brute_force_crossing(pos, edges);
    std::vector<std::uint64_t> ids(pos.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = g.id(static_cast<Vertex>(i));
    std::string message;
    try {
      graph_from_drawing(ids, pos, edges, "drawing");
    } catch (const InputError& e) {
      message = e.what();
    }
    if (want) {
      EXPECT_NE(message.find("not plane"), std::string::npos) << seed << ": " << message;
      ++crossing;
    } else {
      EXPECT_EQ(message.find("cross or touch"), std::string::npos) << seed << ": " << message;
      ++plane;
    }
  }
  EXPECT_GT(crossing, 5);
  EXPECT_GT(plane, 5);
}
