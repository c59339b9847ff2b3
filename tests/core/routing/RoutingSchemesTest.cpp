// Hand-built embeddings with known routes for every scheme.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/routing/Router.hpp"
#include "laguerre/core/routing/Routing.hpp"
#include "DrawingGraph.hpp"

using namespace laguerre::core;

namespace {

using Path = std::vector<Vertex>;

}  // namespace

TEST(Routing, SchemeAndOutcomeNamesRoundTrip) {
  for (const Scheme s : all_schemes) EXPECT_EQ(parse_scheme(to_string(s)), s);
  EXPECT_FALSE(parse_scheme("greedy").has_value());
  EXPECT_FALSE(parse_scheme("").has_value());
  EXPECT_EQ(to_string(RouteOutcome::dead_end), "dead_end");
  EXPECT_EQ(to_string(RouteOutcome::ttl_exceeded), "ttl_exceeded");
}

TEST(Routing, RejectsBadInput) {
  const CircleEmbedding phi{{0, 0, 1}, {2, 0, 1}};
  const PlanarGraph g = graph_of(phi, {{0, 1}});
  EXPECT_THROW(route(g, CircleEmbedding{{0, 0, 1}}, Scheme::greedy_power, 0, 1), laguerre::core::InternalError);
  EXPECT_THROW(route(g, phi, Scheme::greedy_power, 0, 2), laguerre::core::InternalError);
  EXPECT_THROW(Router(g, phi).next_hop(Scheme::gfg, 0, 1), laguerre::core::InternalError);
}

TEST(Routing, SourceEqualsTargetIsDeliveredInZeroHops) {
  const CircleEmbedding phi{{0, 0, 1}, {2, 0, 1}};
  const PlanarGraph g = graph_of(phi, {{0, 1}});
  for (const Scheme s : all_schemes) {
    const Route r = route(g, phi, s, 1, 1);
    EXPECT_EQ(r.outcome, RouteOutcome::delivered);
    EXPECT_EQ(r.path, Path{1});
    EXPECT_EQ(r.hops(), 0u);
    EXPECT_EQ(r.stuck, none);
  }
}

TEST(GreedyPower, DeliversAlongTangentCircles) {
  const CircleEmbedding phi{{0, 0, 1}, {2, 0, 1}, {4, 0, 1}, {6, 0, 1}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {1, 2}, {2, 3}});
  for (const Scheme s : all_schemes) {
    const Route r = route(g, phi, s, 0, 3);
    EXPECT_EQ(r.outcome, RouteOutcome::delivered) << to_string(s);
    EXPECT_EQ(r.path, (Path{0, 1, 2, 3})) << to_string(s);
    EXPECT_EQ(route(g, phi, s, 3, 0).path, (Path{3, 2, 1, 0})) << to_string(s);
  }
}

TEST(GreedyPower, FollowsPowerNotEuclideanDistance) {
  // From s = 0 towards t = 3 at (8, 0): a = 1 at (4, 3) has |a − t|² = 25 but radius 4.5 (power 4.75);
  // b = 2 at (4, −1) has |b − t|² = 17, radius 0.5 (power 16.75). Power picks a, Euclid picks b.
  const CircleEmbedding phi{{0, 0, 1}, {4, 3, 4.5}, {4, -1, 0.5}, {8, 0, 1}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {0, 2}, {1, 2}, {1, 3}, {2, 3}});
  EXPECT_EQ(greedy_power_next_hop(g, phi, 0, 3), 1u);
  EXPECT_EQ(greedy_euclid_next_hop(g, phi, 0, 3), 2u);
  EXPECT_EQ(route(g, phi, Scheme::greedy_power, 0, 3).path, (Path{0, 1, 3}));
  EXPECT_EQ(route(g, phi, Scheme::greedy_euclid, 0, 3).path, (Path{0, 2, 3}));
  EXPECT_EQ(greedy_power_next_hop(g, phi, 3, 3), none);
}

TEST(GreedyPower, StopsAtTheLocalMinimum) {
  // 0 (0,0) r .5 — 1 (3,0) r 2.4 — 2 (3,5) r .5 — 3 (8,0) r .5, plus 0–2. Towards 3:
  // pow from 0: 63.75; its neighbours 1: 25 − 5.76 = 19.24 and 2: 49.75 → 1. At 1 the neighbours are
  // 0 (63.75) and 2 (49.75), both worse than 19.24: a dead end at 1 although 1–2–3 reaches t.
  const CircleEmbedding phi{{0, 0, 0.5}, {3, 0, 2.4}, {3, 5, 0.5}, {8, 0, 0.5}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {1, 2}, {2, 3}, {0, 2}});
  const Route r = route(g, phi, Scheme::greedy_power, 0, 3);
  EXPECT_EQ(r.outcome, RouteOutcome::dead_end);
  EXPECT_EQ(r.stuck, 1u);
  EXPECT_EQ(r.path, (Path{0, 1}));
  EXPECT_EQ(greedy_power_next_hop(g, phi, 1, 3), none);
  // The plane drawing lets GFG recover.
  const Route gfg = route(g, phi, Scheme::gfg, 0, 3);
  EXPECT_EQ(gfg.outcome, RouteOutcome::delivered);
  EXPECT_EQ(gfg.path.back(), 3u);
}

TEST(GreedyPower, EqualPowerIsNotProgressAndTiesGoToTheSmallestIndex) {
  // t = 1 at (4, 0). s = 0 at (0, 0), r = 0: pow = 16. u = 2 at (4, 5), r = 3: pow = 25 − 9 = 16 exactly.
  const CircleEmbedding phi{{0, 0, 0}, {4, 0, 0}, {4, 5, 3}, {-4, 9, 0}};
  const PlanarGraph g = graph_of(phi, {{0, 2}, {2, 1}, {0, 3}, {3, 2}});
  const Route r = route(g, phi, Scheme::greedy_power, 0, 1);
  EXPECT_EQ(r.outcome, RouteOutcome::dead_end);
  EXPECT_EQ(r.stuck, 0u);

  // Mirror-symmetric neighbours at equal power: the smaller index wins whatever the rotation order.
  // 0 (0,0); 3 (1,1) and 1 (1,−1) equal; target 2 (2,0).
  const CircleEmbedding sym{{0, 0, 0.25}, {1, -1, 0.5}, {2, 0, 0.25}, {1, 1, 0.5}};
  const PlanarGraph gs = graph_of(sym, {{0, 1}, {0, 3}, {1, 2}, {3, 2}});
  EXPECT_EQ(greedy_power_next_hop(gs, sym, 0, 2), 1u);
  EXPECT_EQ(greedy_euclid_next_hop(gs, sym, 0, 2), 1u);
  EXPECT_EQ(compass_next_hop(gs, sym, 0, 2), 1u);
}

TEST(GreedyPower, DecidesExactlyBelowDoublePrecision) {
  // Two neighbours whose powers differ by one part in 2^-60 of their size: rounding cannot see it.
  const double e = std::ldexp(1.0, -30);
  // pow(t, 1) = (1 + e)² = 1 + 2e + e², pow(t, 2) = 1 + 2e (radius² = e² exactly): 2 is strictly closer.
  const CircleEmbedding phi{{-5, -5, 0}, {1 + e, 0, 0}, {0, 1 + e, e}, {0, 0, 0}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {0, 2}, {1, 3}, {2, 3}});
  EXPECT_EQ(greedy_power_next_hop(g, phi, 0, 3), 2u);
  EXPECT_EQ(greedy_euclid_next_hop(g, phi, 0, 3), 1u);  // without the radius, 1 and 2 tie: smaller index
}

TEST(GreedyEuclid, DeadEndInFrontOfAVoid) {
  // s = 0 at (0,0) wants t = 3 at (10,0); its only neighbour 1 at (−1,5) is farther (146 > 100).
  // The way round the void: 0 – 1 – 2 (10,5) – 3.
  const CircleEmbedding phi{{0, 0, 0}, {-1, 5, 0}, {10, 5, 0}, {10, 0, 0}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {1, 2}, {2, 3}});
  const Route r = route(g, phi, Scheme::greedy_euclid, 0, 3);
  EXPECT_EQ(r.outcome, RouteOutcome::dead_end);
  EXPECT_EQ(r.stuck, 0u);
  EXPECT_EQ(r.path, (Path{0}));
  const Route f = route(g, phi, Scheme::gfg, 0, 3);
  EXPECT_EQ(f.outcome, RouteOutcome::delivered);
  EXPECT_EQ(f.path, (Path{0, 1, 2, 3}));
}

TEST(GreedyFaceGreedy, WalksAroundAConcaveVoid) {
  // A U-shaped wall: s = 0 at the bottom of the U, t = 1 beyond its closed end. Greedy is stuck at s.
  //   7(0,4)          6(4,4)
  //   |                 |
  //   8(0,2)  0(2,2)  5(4,2)     1(2,-3) below, reached via 4 – 1
  //   |                 |
  //   3(0,0) ------- 4(4,0)
  // with 0 joined to 7 and 6 only (above), so every neighbour of 0 is farther from 1 than 0 is.
  const CircleEmbedding phi{{2, 2, 0}, {2, -3, 0}, {9, 9, 0}, {0, 0, 0}, {4, 0, 0},
                            {4, 2, 0}, {4, 4, 0},  {0, 4, 0}, {0, 2, 0}};
  const PlanarGraph g = graph_of(phi, {{0, 7}, {0, 6}, {7, 8}, {8, 3}, {3, 4}, {4, 5}, {5, 6}, {4, 1}, {6, 2}});
  EXPECT_EQ(route(g, phi, Scheme::greedy_euclid, 0, 1).outcome, RouteOutcome::dead_end);
  const Route r = route(g, phi, Scheme::gfg, 0, 1);
  EXPECT_EQ(r.outcome, RouteOutcome::delivered);
  EXPECT_EQ(r.path.back(), 1u);
  // Every ordered pair is delivered.
  for (Vertex s = 0; s < g.num_vertices(); ++s)
    for (Vertex t = 0; t < g.num_vertices(); ++t)
      EXPECT_EQ(route(g, phi, Scheme::gfg, s, t).outcome, RouteOutcome::delivered) << s << " -> " << t;
}

TEST(GreedyFaceGreedy, SegmentThroughVerticesAndAlongEdges) {
  // Vertices on the x axis: 0 (0,0), 2 (4,0), 3 (6,0), 4 (8,0), with the edges 2–3 and 3–4 along it;
  // 0's neighbours 1 (−1,3) and 5 (−1,−3) lie behind it, so greedy is stuck at 0 towards 4. Many
  // perimeter segments of the all-pairs loop below pass through vertices or along edges.
  const CircleEmbedding phi{{0, 0, 0}, {-1, 3, 0}, {4, 0, 0}, {6, 0, 0}, {8, 0, 0}, {-1, -3, 0}, {4, 3, 0}, {4, -3, 0}};
  const PlanarGraph g =
      graph_of(phi, {{0, 1}, {0, 5}, {1, 6}, {6, 2}, {2, 3}, {3, 4}, {5, 7}, {7, 2}, {6, 3}, {7, 3}});
  EXPECT_EQ(route(g, phi, Scheme::greedy_euclid, 0, 4).outcome, RouteOutcome::dead_end);
  for (Vertex s = 0; s < g.num_vertices(); ++s)
    for (Vertex t = 0; t < g.num_vertices(); ++t)
      EXPECT_EQ(route(g, phi, Scheme::gfg, s, t).outcome, RouteOutcome::delivered) << s << " -> " << t;
}

TEST(GreedyFaceGreedy, ReportsAFruitlessFaceWalkAsALoop) {
  // A planar rotation system drawn with crossing edges (2–3 crosses 0–1): from 3 (1,6) towards 0 (1,5)
  // greedy is stuck at 3 (its neighbours 1 and 2 are farther), and the "face" the rotation walks,
  // 3 → 2 → 1 → 3, never meets the segment [p(3), p(0)]. GFG must report the fruitless walk, not spin.
  const PlanarGraph g = PlanarGraph::from_rotation({{1, 2}, {3, 0, 2}, {3, 1, 0}, {1, 2}});
  const CircleEmbedding phi{{1, 5, 0}, {8, 6, 0}, {2, 1, 0}, {1, 6, 0}};
  EXPECT_TRUE(segments_intersect({2, 1}, {1, 6}, {1, 5}, {8, 6}));
  const Route r = route(g, phi, Scheme::gfg, 3, 0);
  EXPECT_EQ(r.outcome, RouteOutcome::loop);
  EXPECT_EQ(r.path, (Path{3, 2, 1, 3}));
  EXPECT_EQ(r.stuck, 3u);
}

TEST(Compass, LoopsOnAKnownDrawingAndGfgDoesNot) {
  // Found by a seeded search and checked by hand: towards t = 3 (6,16), compass goes
  // 0 → 1 → 6 → 5 → 4 → 0 (deviations 53°, 34°, 4°, 77°, 13° at the successive nodes).
  const CircleEmbedding phi{{3, 15, 0}, {4, 18, 0}, {5, 12, 0}, {6, 16, 0}, {8, 2, 0}, {13, 15, 0}, {19, 15, 0}};
  const PlanarGraph g =
      graph_of(phi, {{0, 1}, {0, 2}, {0, 4}, {1, 2}, {1, 6}, {2, 3}, {4, 5}, {4, 6}, {5, 6}});
  const Route r = route(g, phi, Scheme::compass, 0, 3);
  EXPECT_EQ(r.outcome, RouteOutcome::loop);
  EXPECT_EQ(r.path, (Path{0, 1, 6, 5, 4, 0}));
  EXPECT_EQ(r.stuck, 0u);
  const Route f = route(g, phi, Scheme::gfg, 0, 3);
  EXPECT_EQ(f.outcome, RouteOutcome::delivered);
}

TEST(Compass, PingPongOnATreeIsALoop) {
  // 0 (1,1) has the single neighbour 1 (4,11); from 1 the best-aligned neighbour towards 2 (5,0) is 0.
  const CircleEmbedding phi{{1, 1, 0}, {4, 11, 0}, {5, 0, 0}, {6, 0, 0}, {7, 8, 0}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {1, 4}, {2, 3}, {3, 4}});
  const Route r = route(g, phi, Scheme::compass, 0, 2);
  EXPECT_EQ(r.outcome, RouteOutcome::loop);
  EXPECT_EQ(r.path, (Path{0, 1, 0}));
  EXPECT_EQ(route(g, phi, Scheme::gfg, 0, 2).outcome, RouteOutcome::delivered);
}

TEST(Routing, TtlStopsLongRoutes) {
  const CircleEmbedding phi{{0, 0, 1}, {2, 0, 1}, {4, 0, 1}, {6, 0, 1}, {8, 0, 1}};
  const PlanarGraph g = graph_of(phi, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  for (const Scheme s : all_schemes) {
    const Route r = route(g, phi, s, 0, 4, 2);
    EXPECT_EQ(r.outcome, RouteOutcome::ttl_exceeded) << to_string(s);
    EXPECT_EQ(r.path, (Path{0, 1, 2})) << to_string(s);
    EXPECT_EQ(r.stuck, 2u) << to_string(s);
    EXPECT_EQ(route(g, phi, s, 0, 4, 4).outcome, RouteOutcome::delivered) << to_string(s);
  }
  EXPECT_EQ(default_ttl(g, Scheme::greedy_power), 4u * 5u + 16u);
  EXPECT_GT(default_ttl(g, Scheme::gfg), default_ttl(g, Scheme::greedy_power));
}

namespace {

/// Reference next hops that use only the exact predicates of Predicates.hpp.
Vertex reference_next_hop(const PlanarGraph& g, const CircleEmbedding& phi, Scheme s, Vertex at, Vertex target) {
  if (at == target) return none;
  const Point2 t = centre(phi[target]), v = centre(phi[at]);
  auto cmp = [&](Vertex a, Vertex b) {
    switch (s) {
      case Scheme::greedy_power: return compare_power(t, phi[a], phi[b]);
      case Scheme::greedy_euclid: return compare_distance(t, centre(phi[a]), centre(phi[b]));
      default: return compare_deviation(v, t, centre(phi[a]), centre(phi[b]));
    }
  };
  Vertex best = none;
  for (const Vertex u : g.neighbours(at)) {
    if (best == none) {
      best = u;
      continue;
    }
    const Sign c = cmp(u, best);
    if (c == Sign::negative || (c == Sign::zero && u < best)) best = u;
  }
  if (best == none || s == Scheme::compass) return best;
  return cmp(best, at) == Sign::negative ? best : none;
}

Vertex fast_next_hop(const PlanarGraph& g, const CircleEmbedding& phi, Scheme s, Vertex at, Vertex target) {
  switch (s) {
    case Scheme::greedy_power: return greedy_power_next_hop(g, phi, at, target);
    case Scheme::greedy_euclid: return greedy_euclid_next_hop(g, phi, at, target);
    default: return compass_next_hop(g, phi, at, target);
  }
}

}  // namespace

TEST(Routing, FastDecisionsEqualExactPredicatesOnNearTies) {
  // A star (centre 0, leaves 1..12) plus a target hanging off leaf 1. Centres sit on a coarse lattice
  // moved by 0, ±1 or ±2 ulps, radii come from a small set: most comparisons are exact ties or closer
  // than double rounding can resolve. Every scale from 2^-600 to 2^600 must give the same answers
  // (scaling by a power of two is exact and preserves every decision).
  std::mt19937_64 rng(77);
  std::vector<std::vector<Vertex>> rot(14);
  for (Vertex leaf = 1; leaf <= 12; ++leaf) {
    rot[0].push_back(leaf);
    rot[leaf].push_back(0);
  }
  rot[1].push_back(13);
  rot[13].push_back(1);
  const PlanarGraph g = PlanarGraph::from_rotation(rot);
  const double radii[] = {0, 0.5, 0.25, 1.0 / 3.0, 1};
  std::size_t checked = 0;
  for (int trial = 0; trial < 600; ++trial) {
    CircleEmbedding base;
    for (int i = 0; i < 14; ++i) {
      auto coord = [&] {
        double x = static_cast<double>(static_cast<int>(rng() % 7) - 3) * 0.5;
        for (int k = static_cast<int>(rng() % 5) - 2; k != 0; k += k > 0 ? -1 : 1)
          x = std::nextafter(x, k > 0 ? 10.0 : -10.0);
        return x;
      };
      const double x = coord(), y = coord();
      base.push_back({x, y, radii[rng() % 5]});
    }
    for (const int e : {0, -600, 600}) {
      CircleEmbedding phi = base;
      for (Circle& c : phi) c = {std::ldexp(c.x, e), std::ldexp(c.y, e), std::ldexp(c.r, e)};
      for (const Scheme s : {Scheme::greedy_power, Scheme::greedy_euclid, Scheme::compass})
        for (const Vertex target : {Vertex{13}, Vertex{1}, Vertex{5}}) {
          ASSERT_EQ(fast_next_hop(g, phi, s, 0, target), reference_next_hop(g, phi, s, 0, target))
              << to_string(s) << " trial " << trial << " scale 2^" << e;
          ++checked;
        }
    }
  }
  EXPECT_EQ(checked, 600u * 3u * 9u);
}

namespace {
// The binary128 circles equal to the doubles (widening is exact).
CircleEmbedding128 widened(const CircleEmbedding& phi) {
  CircleEmbedding128 out;
  for (const Circle& c : phi) out.push_back({c.x, c.y, c.r});
  return out;
}

// Every ordered pair routed by `s` on the doubles and on their exact binary128 widening: the same
// decisions (the binary128 predicates are exact on the same numbers), so the same paths and outcomes.
void expect_same_routes(const PlanarGraph& g, const CircleEmbedding& phi, Scheme s) {
  const CircleEmbedding128 phi128 = widened(phi);
  Router doubles(g, phi), quads(g, phi, phi128);
  for (Vertex a = 0; a < g.num_vertices(); ++a)
    for (Vertex b = 0; b < g.num_vertices(); ++b) {
      const Route r = doubles.route(s, a, b), q = quads.route(s, a, b);
      ASSERT_EQ(r.path, q.path) << to_string(s) << " " << a << " -> " << b;
      ASSERT_EQ(r.outcome, q.outcome);
      ASSERT_EQ(r.stuck, q.stuck);
    }
}
}  // namespace

TEST(Binary128Routing, ExactWideningDecidesAsTheDoublesIncludingTiesAndSubUlpDifferences) {
  // The hand-built cases above: exact power ties, mirror ties (smallest index), a difference of one
  // part in 2^-60 that only the exact stage sees.
  const double e = std::ldexp(1.0, -30);
  const std::vector<std::pair<CircleEmbedding, std::vector<std::pair<Vertex, Vertex>>>> cases = {
      {{{0, 0, 0}, {4, 0, 0}, {4, 5, 3}, {-4, 9, 0}}, {{0, 2}, {2, 1}, {0, 3}, {3, 2}}},
      {{{0, 0, 0.25}, {1, -1, 0.5}, {2, 0, 0.25}, {1, 1, 0.5}}, {{0, 1}, {0, 3}, {1, 2}, {3, 2}}},
      {{{-5, -5, 0}, {1 + e, 0, 0}, {0, 1 + e, e}, {0, 0, 0}}, {{0, 1}, {0, 2}, {1, 3}, {2, 3}}},
  };
  for (const auto& [phi, edges] : cases)
    for (const Scheme s : {Scheme::greedy_power, Scheme::greedy_euclid}) expect_same_routes(graph_of(phi, edges), phi, s);
  const CircleEmbedding128 sub = widened(cases[2].first);
  EXPECT_EQ(Router(graph_of(cases[2].first, cases[2].second), cases[2].first, sub).next_hop(Scheme::greedy_power, 0, 3), 2u);
}

TEST(Binary128Routing, RandomDelaunayDrawingsRouteAsTheDoubles) {
  // Random Delaunay triangulations with random radii (greedy power dead ends included): same paths for
  // every ordered pair.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> radius(0, 0.05);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const GraphInput in = random_delaunay_triangulation(60, seed);
    CircleEmbedding phi;
    for (const Point2& p : in.positions) phi.push_back({p.x, p.y, radius(rng)});
    for (const Scheme s : {Scheme::greedy_power, Scheme::greedy_euclid}) expect_same_routes(in.graph, phi, s);
  }
}

TEST(Binary128Routing, OnlyTheGreedySchemesDecideOnBinary128) {
  const CircleEmbedding phi{{0, 0, 1}, {2, 0, 1}};
  const PlanarGraph g = graph_of(phi, {{0, 1}});
  const CircleEmbedding128 phi128 = widened(phi);
  Router router(g, phi, phi128);
  EXPECT_EQ(router.route(Scheme::greedy_power, 0, 1).outcome, RouteOutcome::delivered);
  for (const Scheme s : {Scheme::compass, Scheme::gfg, Scheme::hyperbolic})
    EXPECT_THROW(router.route(s, 0, 1), laguerre::core::InternalError) << to_string(s);
  EXPECT_THROW(Router(g, phi, CircleEmbedding128{{0, 0, 1}}), laguerre::core::InternalError);
  CircleEmbedding128 bad = phi128;
  bad[1].r = bad[1].r / Float128(0);  // +inf
  EXPECT_THROW(Router(g, phi, bad), laguerre::core::InternalError);
}
