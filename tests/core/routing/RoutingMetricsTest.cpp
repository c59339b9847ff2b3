// Routing metrics: known stretch answers, failure reports, pair sampling, percentile definition and
// the speed of all-pairs evaluation.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "DrawingGraph.hpp"

using namespace laguerre::core;

namespace {

/// A w × h unit grid; with `diagonals`, every cell also gets its (x, y)–(x+1, y+1) diagonal. With
/// `jitter_seed`, centres move by up to ±0.15 and radii vary in [0.2, 0.45) (still a plane drawing).
std::pair<PlanarGraph, CircleEmbedding> grid(int w, int h, bool diagonals, double radius,
                                              std::uint64_t jitter_seed = 0) {
  std::mt19937_64 rng(jitter_seed);
  auto unit = [&] { return static_cast<double>(rng() >> 11) * 0x1p-53; };
  CircleEmbedding phi;
  std::vector<std::pair<Vertex, Vertex>> edges;
  auto id = [&](int x, int y) { return static_cast<Vertex>(y * w + x); };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (jitter_seed == 0) phi.push_back({double(x), double(y), radius});
      else phi.push_back({x + 0.3 * (unit() - 0.5), y + 0.3 * (unit() - 0.5), 0.2 + 0.25 * unit()});
      if (x + 1 < w) edges.push_back({id(x, y), id(x + 1, y)});
      if (y + 1 < h) edges.push_back({id(x, y), id(x, y + 1)});
      if (diagonals && x + 1 < w && y + 1 < h) edges.push_back({id(x, y), id(x + 1, y + 1)});
    }
  PlanarGraph g = graph_of(phi, edges);
  return {std::move(g), std::move(phi)};
}

}  // namespace

TEST(RoutingMetrics, PathGraphHasUnitStretch) {
  CircleEmbedding phi;
  std::vector<std::pair<Vertex, Vertex>> edges;
  for (Vertex i = 0; i < 5; ++i) {
    phi.push_back({2.0 * i, 0, 1});
    if (i > 0) edges.push_back({i - 1, i});
  }
  const PlanarGraph g = graph_of(phi, edges);
  for (const Scheme s : all_schemes) {
    const RoutingStats st = evaluate_routing(g, phi, s, {});
    EXPECT_EQ(st.scheme, s);
    EXPECT_EQ(st.pairs, 20u);
    EXPECT_EQ(st.delivered, 20u);
    EXPECT_EQ(st.delivery_rate, 1.0);
    EXPECT_EQ(st.stretch_mean, 1.0);
    EXPECT_EQ(st.stretch_p95, 1.0);
    EXPECT_EQ(st.stretch_max, 1.0);
    EXPECT_DOUBLE_EQ(st.hops_mean, 2.0);  // Σ|i − j| over ordered pairs = 40, over 20 pairs
    EXPECT_TRUE(st.failures.empty());
    EXPECT_EQ(st.failures_total, 0u);
  }
}

TEST(RoutingMetrics, GridGreedyIsShortest) {
  // Greedy Euclidean on a 4-neighbour grid always moves along the larger coordinate gap: shortest paths,
  // hops = Manhattan distance.
  const auto [g, phi] = grid(5, 4, false, 0.5);
  const RoutingStats st = evaluate_routing(g, phi, Scheme::greedy_euclid, {});
  const std::size_t n = 20;
  EXPECT_EQ(st.pairs, n * (n - 1));
  EXPECT_EQ(st.delivered, st.pairs);
  EXPECT_EQ(st.stretch_max, 1.0);
  EXPECT_EQ(st.stretch_p95, 1.0);
  double manhattan = 0;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b)
      manhattan += std::abs(int(a % 5) - int(b % 5)) + std::abs(int(a / 5) - int(b / 5));
  EXPECT_DOUBLE_EQ(st.hops_mean, manhattan / double(n * (n - 1)));
  // Equal radii: greedy power decides exactly like greedy Euclidean.
  const RoutingStats power = evaluate_routing(g, phi, Scheme::greedy_power, {});
  EXPECT_EQ(power.delivered, st.delivered);
  EXPECT_DOUBLE_EQ(power.hops_mean, st.hops_mean);
}

TEST(RoutingMetrics, FiveCycleStretchAndFailures) {
  // s 0 (0,0) – a 1 (1,0) – d 2 (3,0) – t 3 (4,0) – c 4 (2,3) – s. Greedy Euclidean, worked out by hand
  // (and by an independent script): 0→3 and 3→0 take 3 hops for a distance of 2 (stretch 1.5), 1→4 and
  // 2→4 are stuck at their sources, the other 16 pairs are shortest.
  const CircleEmbedding phi{{0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {4, 0, 0}, {2, 3, 0}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 0}});
  const RoutingStats st = evaluate_routing(g, phi, Scheme::greedy_euclid, {});
  EXPECT_EQ(st.pairs, 20u);
  EXPECT_EQ(st.delivered, 18u);
  EXPECT_DOUBLE_EQ(st.delivery_rate, 0.9);
  EXPECT_DOUBLE_EQ(st.stretch_mean, 19.0 / 18.0);
  EXPECT_EQ(st.stretch_p95, 1.5);  // rank ⌈0.95·18⌉ = 18: the largest
  EXPECT_EQ(st.stretch_max, 1.5);
  EXPECT_DOUBLE_EQ(st.hops_mean, 28.0 / 18.0);
  EXPECT_EQ(st.failures_total, 2u);
  ASSERT_EQ(st.failures.size(), 2u);
  EXPECT_EQ(st.failures[0].source, 1u);
  EXPECT_EQ(st.failures[0].target, 4u);
  EXPECT_EQ(st.failures[0].stuck, 1u);
  EXPECT_EQ(st.failures[0].outcome, RouteOutcome::dead_end);
  EXPECT_EQ(st.failures[1].source, 2u);
  EXPECT_EQ(st.failures[1].stuck, 2u);
  // GFG recovers both.
  EXPECT_EQ(evaluate_routing(g, phi, Scheme::gfg, {}).delivered, 20u);
}

TEST(RoutingMetrics, KeepsAtMostAHundredFailures) {
  // A path whose centres zigzag across the plane (a plane drawing): greedy fails for many pairs.
  CircleEmbedding phi;
  std::vector<std::pair<Vertex, Vertex>> edges;
  for (Vertex i = 0; i < 30; ++i) {
    phi.push_back({double(i % 2 == 0 ? i : 40 - i), double(i), 0});
    if (i > 0) edges.push_back({i - 1, i});
  }
  const PlanarGraph g = graph_of(phi, edges);
  const RoutingStats st = evaluate_routing(g, phi, Scheme::greedy_euclid, {});
  EXPECT_GT(st.failures_total, 100u);
  EXPECT_EQ(st.failures.size(), 100u);
  EXPECT_EQ(st.failures_total, st.pairs - st.delivered);
}

TEST(RoutingMetrics, UndefinedStatisticsAreNaN) {
  const PlanarGraph g = PlanarGraph::from_rotation({{}});
  const CircleEmbedding phi{{0, 0, 1}};
  const RoutingStats st = evaluate_routing(g, phi, Scheme::greedy_power, {});
  EXPECT_EQ(st.pairs, 0u);
  EXPECT_TRUE(std::isnan(st.delivery_rate));
  EXPECT_TRUE(std::isnan(st.stretch_mean));
}

TEST(PairSelection, AllPairsAreTheNTimesNMinusOneOrderedPairs) {
  const auto all = select_pairs(7, {});
  EXPECT_EQ(all.size(), 42u);
  const std::set<std::pair<Vertex, Vertex>> distinct(all.begin(), all.end());
  EXPECT_EQ(distinct.size(), 42u);
  for (const auto& [s, t] : all) {
    EXPECT_NE(s, t);
    EXPECT_LT(s, 7u);
    EXPECT_LT(t, 7u);
  }
  EXPECT_TRUE(std::is_sorted(all.begin(), all.end()));
  EXPECT_EQ(select_pairs(7, {42, 3}), all);   // a sample as large as the population is everything
  EXPECT_EQ(select_pairs(7, {500, 3}), all);
  EXPECT_TRUE(select_pairs(1, {}).empty());
  EXPECT_TRUE(select_pairs(0, {10, 1}).empty());
}

TEST(PairSelection, SamplesAreDeterministicDistinctAndSorted) {
  const PairSelection a{100, 7}, b{100, 8};
  const auto sa = select_pairs(50, a);
  EXPECT_EQ(sa, select_pairs(50, a));
  EXPECT_NE(sa, select_pairs(50, b));
  EXPECT_EQ(sa.size(), 100u);
  EXPECT_TRUE(std::is_sorted(sa.begin(), sa.end()));
  EXPECT_EQ(std::adjacent_find(sa.begin(), sa.end()), sa.end());
  for (const auto& [s, t] : sa) {
    EXPECT_NE(s, t);
    EXPECT_LT(s, 50u);
    EXPECT_LT(t, 50u);
  }
  // Golden values: the stream is std::mt19937_64 (fully specified by the standard) and the bounded
  // mapping is ours, so these pairs are the same with every standard library.
  const std::vector<std::pair<Vertex, Vertex>> small = select_pairs(10, {3, 12345});
  EXPECT_EQ(small, (std::vector<std::pair<Vertex, Vertex>>{{1, 2}, {1, 7}, {3, 9}}));
}

TEST(PairSelection, EvaluationRoutesExactlyTheSample) {
  const auto [g, phi] = grid(6, 6, true, 0.3);
  const RoutingStats st = evaluate_routing(g, phi, Scheme::greedy_power, {200, 99});
  EXPECT_EQ(st.pairs, 200u);
  const RoutingStats again = evaluate_routing(g, phi, Scheme::greedy_power, {200, 99});
  EXPECT_EQ(again.stretch_mean, st.stretch_mean);
  EXPECT_EQ(again.hops_mean, st.hops_mean);
}

TEST(Percentile, NearestRank) {
  std::vector<double> v;
  for (int i = 20; i >= 1; --i) v.push_back(i);
  EXPECT_EQ(nearest_rank_percentile(v, 95), 19.0);  // ⌈0.95·20⌉ = 19
  EXPECT_EQ(nearest_rank_percentile(v, 100), 20.0);
  EXPECT_EQ(nearest_rank_percentile(v, 0), 1.0);    // rank at least 1
  EXPECT_EQ(nearest_rank_percentile(v, 50), 10.0);
  std::vector<double> ten{10, 9, 8, 7, 6, 5, 4, 3, 2, 1};
  EXPECT_EQ(nearest_rank_percentile(ten, 95), 10.0);  // ⌈9.5⌉ = 10
  EXPECT_EQ(nearest_rank_percentile(ten, 90), 9.0);
  std::vector<double> none_;
  EXPECT_TRUE(std::isnan(nearest_rank_percentile(none_, 95)));
}

TEST(RoutingMetrics, AllPairsSpeed) {
  // A jittered triangulated grid of 45 × 45 = 2025 vertices, ≈ 4.1 M routes with LAGUERRE_ROUTING_BENCH set; a 20 × 20 grid otherwise.
  const bool bench = std::getenv("LAGUERRE_ROUTING_BENCH") != nullptr;
  const int side = bench ? 45 : 20;
  const auto [g, phi] = grid(side, side, true, 0.3, 2024);
  for (const Scheme s : all_schemes) {
    const auto start = std::chrono::steady_clock::now();
    const RoutingStats st = evaluate_routing(g, phi, s, {});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << to_string(s) << ": " << g.num_vertices() << " vertices, " << st.pairs << " pairs in " << seconds
              << " s, delivery " << st.delivery_rate << ", stretch mean " << st.stretch_mean << " p95 "
              << st.stretch_p95 << " max " << st.stretch_max << ", hops " << st.hops_mean << '\n';
    EXPECT_EQ(st.pairs, g.num_vertices() * (g.num_vertices() - 1));
    if (s == Scheme::gfg || s == Scheme::greedy_euclid) {
      EXPECT_EQ(st.delivered, st.pairs) << to_string(s);
    }
  }
}
