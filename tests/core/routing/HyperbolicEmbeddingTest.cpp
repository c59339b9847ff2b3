// Kleinberg's hyperbolic tree embedding (Scheme::hyperbolic): distances against a high-precision
// oracle built from absolute coordinates, the greedy property by brute force on random graphs,
// delivery through the Router, determinism, and what happens where doubles cannot represent the points.

#include <gtest/gtest.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/random/Random.hpp"
#include "laguerre/core/routing/HyperbolicEmbedding.hpp"
#include "laguerre/core/routing/Router.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"

using namespace laguerre::core;

namespace {

using Adjacency = std::vector<std::vector<Vertex>>;

/// A random tree on n vertices (vertex v > 0 hangs off a uniform earlier vertex, or off one of the
/// first `hubs` vertices half of the time, for high degrees) plus `extra` random non-tree edges.
Adjacency random_graph(std::size_t n, std::size_t extra, std::size_t hubs, std::uint64_t seed) {
  SeededRandom rng(seed);
  Adjacency adj(n);
  auto has = [&](Vertex a, Vertex b) {
    for (Vertex x : adj[a])
      if (x == b) return true;
    return false;
  };
  for (Vertex v = 1; v < n; ++v) {
    const Vertex p = static_cast<Vertex>(hubs > 0 && rng.below(2) == 0 ? rng.below(std::min<std::size_t>(hubs, v))
                                                                          : rng.below(v));
    adj[v].push_back(p);
    adj[p].push_back(v);
  }
  for (std::size_t k = 0; k < extra && n > 2; ++k) {
    const auto a = static_cast<Vertex>(rng.below(n)), b = static_cast<Vertex>(rng.below(n));
    if (a == b || has(a, b)) continue;
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
  return adj;
}

Adjacency path(std::size_t n) {
  Adjacency adj(n);
  for (Vertex v = 0; v + 1 < n; ++v) {
    adj[v].push_back(v + 1);
    adj[v + 1].push_back(v);
  }
  return adj;
}

/// Oracle: absolute upper-half-plane coordinates M_v(i) of every node, M_v = G_{j1}⋯G_{jk} with
/// G_j = R_j·H multiplied out from the root in `bits`-bit MPFR, and cosh of their distances from the
/// half-plane formula cosh d = 1 + |z − w|² / (2 Im z Im w). Independent of the embedding's
/// relative, conjugated, interval evaluation; needs bits ≳ 2·depth·D/ln 2.
class Oracle {
public:
  Oracle(const HyperbolicTreeEmbedding& e, mpfr_prec_t bits) : bits_(bits), x_(e.size()), y_(e.size()) {
    const std::size_t n = e.size();
    const std::uint32_t q = e.tiling_degree();
    mpfr_t pi, t, h, c, s, tmp;
    mpfr_inits2(bits, pi, t, h, c, s, tmp, static_cast<mpfr_ptr>(nullptr));
    mpfr_const_pi(pi, MPFR_RNDN);
    mpfr_div_ui(t, pi, 2 * q, MPFR_RNDN);
    mpfr_cot(h, t, MPFR_RNDN);
    std::vector<std::array<mpfr_t, 4>> gen(q), mat(n);
    for (std::uint32_t j = 0; j < q; ++j) {
      for (auto& v : gen[j]) mpfr_init2(v, bits);
      mpfr_mul_ui(t, pi, j, MPFR_RNDN);
      mpfr_div_ui(t, t, q, MPFR_RNDN);
      mpfr_sin_cos(s, c, t, MPFR_RNDN);
      mpfr_div(gen[j][0], s, h, MPFR_RNDN);
      mpfr_mul(gen[j][1], c, h, MPFR_RNDN);
      mpfr_neg(gen[j][1], gen[j][1], MPFR_RNDN);
      mpfr_div(gen[j][2], c, h, MPFR_RNDN);
      mpfr_mul(gen[j][3], s, h, MPFR_RNDN);
    }
    // Nodes in order of depth, so that parents come first.
    std::vector<Vertex> order(n);
    for (Vertex v = 0; v < n; ++v) order[v] = v;
    std::stable_sort(order.begin(), order.end(), [&](Vertex a, Vertex b) { return e.depth(a) < e.depth(b); });
    for (const Vertex v : order) {
      for (auto& m : mat[v]) mpfr_init2(m, bits);
      if (v == e.root()) {
        mpfr_set_ui(mat[v][0], 1, MPFR_RNDN), mpfr_set_ui(mat[v][1], 0, MPFR_RNDN);
        mpfr_set_ui(mat[v][2], 0, MPFR_RNDN), mpfr_set_ui(mat[v][3], 1, MPFR_RNDN);
      } else {
        const auto& p = mat[e.parent(v)];
        const auto& g = gen[e.child_index(v)];
        for (int r = 0; r < 2; ++r)
          for (int col = 0; col < 2; ++col) {
            mpfr_mul(mat[v][2 * r + col], p[2 * r], g[col], MPFR_RNDN);
            mpfr_mul(tmp, p[2 * r + 1], g[2 + col], MPFR_RNDN);
            mpfr_add(mat[v][2 * r + col], mat[v][2 * r + col], tmp, MPFR_RNDN);
          }
      }
      // z = (a i + b) / (c i + d): x = (ac + bd) / (c² + d²), y = 1 / (c² + d²).
      mpfr_init2(x_[v].v, bits);
      mpfr_init2(y_[v].v, bits);
      const auto& m = mat[v];
      mpfr_mul(tmp, m[2], m[2], MPFR_RNDN);
      mpfr_fma(tmp, m[3], m[3], tmp, MPFR_RNDN);
      mpfr_ui_div(y_[v].v, 1, tmp, MPFR_RNDN);
      mpfr_mul(x_[v].v, m[0], m[2], MPFR_RNDN);
      mpfr_fma(x_[v].v, m[1], m[3], x_[v].v, MPFR_RNDN);
      mpfr_mul(x_[v].v, x_[v].v, y_[v].v, MPFR_RNDN);
    }
    for (auto& g : gen)
      for (auto& v : g) mpfr_clear(v);
    for (auto& m : mat)
      for (auto& v : m) mpfr_clear(v);
    mpfr_clears(pi, t, h, c, s, tmp, static_cast<mpfr_ptr>(nullptr));
  }
  ~Oracle() {
    for (auto& v : x_) mpfr_clear(v.v);
    for (auto& v : y_) mpfr_clear(v.v);
  }
  Oracle(const Oracle&) = delete;
  Oracle& operator=(const Oracle&) = delete;

  /// ln cosh d(a, b) as a double (enough to compare with the embedding's distance()).
  double distance(Vertex a, Vertex b) const {
    mpfr_t dx, dy, num, den;
    mpfr_inits2(bits_, dx, dy, num, den, static_cast<mpfr_ptr>(nullptr));
    mpfr_sub(dx, x_[a].v, x_[b].v, MPFR_RNDN);
    mpfr_sub(dy, y_[a].v, y_[b].v, MPFR_RNDN);
    mpfr_mul(num, dx, dx, MPFR_RNDN);
    mpfr_fma(num, dy, dy, num, MPFR_RNDN);
    mpfr_mul(den, y_[a].v, y_[b].v, MPFR_RNDN);
    mpfr_mul_ui(den, den, 2, MPFR_RNDN);
    mpfr_div(num, num, den, MPFR_RNDN);
    mpfr_add_ui(num, num, 1, MPFR_RNDN);
    mpfr_acosh(num, num, MPFR_RNDN);
    const double d = mpfr_get_d(num, MPFR_RNDN);
    mpfr_clears(dx, dy, num, den, static_cast<mpfr_ptr>(nullptr));
    return d;
  }

private:
  struct Big {
    mpfr_t v;
  };
  mpfr_prec_t bits_;
  std::vector<Big> x_, y_;
};

/// The BFS tree path's next node from v towards t.
Vertex tree_next(const HyperbolicTreeEmbedding& e, Vertex v, Vertex t) {
  // t in v's subtree: the child on the way; otherwise the parent.
  Vertex x = t;
  while (e.depth(x) > e.depth(v) + 1) x = e.parent(x);
  if (e.depth(x) == e.depth(v) + 1 && e.parent(x) == v) return x;
  return e.parent(v);
}

}  // namespace

TEST(HyperbolicEmbedding, TreeEdgesHaveTheTilingsLengthAndDistancesMatchTheOracle) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Adjacency adj = random_graph(60, 30, seed % 3, seed);
    const HyperbolicTreeEmbedding e(adj);
    // D = 2 artanh cos(π/q): e.g. ln 3 for q = 3.
    if (e.tiling_degree() == 3) {
      EXPECT_NEAR(e.edge_length(), std::log(3.0), 1e-14);
    }
    const Oracle oracle(e, 256 + 4 * static_cast<mpfr_prec_t>(e.max_depth() * e.edge_length()));
    for (Vertex v = 0; v < e.size(); ++v) {
      if (v != e.root()) {
        EXPECT_NEAR(e.distance(v, e.parent(v)), e.edge_length(), 1e-12) << v;
      }
      EXPECT_LE(e.distance(e.root(), v), e.depth(v) * e.edge_length() * (1 + 1e-12) + 1e-12);
      for (Vertex w = 0; w < e.size(); w += 7)
        EXPECT_NEAR(e.distance(v, w), oracle.distance(v, w), 1e-9 * (1 + oracle.distance(v, w))) << v << " " << w;
    }
  }
}

TEST(HyperbolicEmbedding, GreedyPropertyHoldsForEveryPairByBruteForce) {
  std::size_t graphs = 0, pairs = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const std::size_t n = 2 + seed * 2;
    const Adjacency adj = random_graph(n, seed % 4 == 0 ? 0 : n / 2, seed % 5, 100 + seed);
    const HyperbolicTreeEmbedding e(adj);
    const Oracle oracle(e, 256 + 4 * static_cast<mpfr_prec_t>(e.max_depth() * e.edge_length()));
    ++graphs;
    for (Vertex t = 0; t < n; ++t)
      for (Vertex v = 0; v < n; ++v) {
        if (v == t) continue;
        ++pairs;
        // The tree neighbour towards t is certified strictly closer (the bisector argument) …
        const Vertex next = tree_next(e, v, t);
        ASSERT_EQ(e.compare_distance(t, next, v), Sign::negative) << "seed " << seed << ": " << v << " -> " << t;
        // … so the greedy decision over all edges moves, certified, to a neighbour the oracle finds
        // strictly closer and (up to the oracle's rounding) of least distance.
        const HyperbolicHop hop = hyperbolic_hop(e, adj[v], v, t);
        ASSERT_TRUE(hop.certified);
        ASSERT_LT(hop.next, adj[v].size());
        const Vertex u = adj[v][hop.next];
        EXPECT_LT(oracle.distance(u, t), oracle.distance(v, t));
        double least = oracle.distance(u, t);
        for (Vertex w : adj[v]) least = std::min(least, oracle.distance(w, t));
        EXPECT_NEAR(oracle.distance(u, t), least, 1e-9 * (1 + least));
      }
  }
  EXPECT_EQ(graphs, 30u);
  EXPECT_GT(pairs, 10000u);
}

TEST(HyperbolicEmbedding, MirrorImagesAreExactTiesLeftUndecidedNotGuessed) {
  // A node with children on sides j and q − j is mirror-symmetric about the line through its parent:
  // those two children are exactly equidistant from the parent. A star of 5 leaves under a child c
  // of the root (q = 6): c's children take sides 1..5, and sides 1/5 and 2/4 are mirror pairs.
  Adjacency adj(8);
  auto link = [&](Vertex a, Vertex b) {
    adj[a].push_back(b);
    adj[b].push_back(a);
  };
  link(0, 1);  // 0 is the root (forced), 1 its only child
  for (Vertex leaf = 2; leaf < 7; ++leaf) link(1, leaf);
  link(0, 7);
  HyperbolicOptions o;
  o.root = 0;
  const HyperbolicTreeEmbedding e(adj, o);
  ASSERT_EQ(e.tiling_degree(), 6u);
  std::vector<Vertex> by_side(6, none);
  for (Vertex leaf = 2; leaf < 7; ++leaf) by_side[e.child_index(leaf)] = leaf;
  for (std::uint32_t j = 1; j <= 2; ++j) {
    ASSERT_NE(by_side[j], none);
    ASSERT_NE(by_side[6 - j], none);
    EXPECT_FALSE(e.compare_distance(0, by_side[j], by_side[6 - j]).has_value());
    EXPECT_NEAR(e.distance(0, by_side[j]), e.distance(0, by_side[6 - j]), 1e-12);
  }
  // Not a tie: the middle child (side 3, opposite the parent) is the farthest from the root.
  EXPECT_EQ(e.compare_distance(0, by_side[3], by_side[2]), Sign::positive);
  // A holder adjacent to both members of a tie (and not to anything closer) still moves, certified,
  // to the smaller index: node 8 hangs off the side-1 leaf and is also linked to its mirror image.
  adj.emplace_back();
  link(by_side[1], 8);
  link(by_side[5], 8);
  const HyperbolicTreeEmbedding tied(adj, o);
  ASSERT_EQ(tied.child_index(by_side[1]), e.child_index(by_side[1]));
  ASSERT_FALSE(tied.compare_distance(0, by_side[1], by_side[5]).has_value());
  const HyperbolicHop hop = hyperbolic_hop(tied, adj[8], 8, 0);
  EXPECT_TRUE(hop.certified);
  EXPECT_EQ(adj[8][hop.next], std::min(by_side[1], by_side[5]));
}

TEST(HyperbolicEmbedding, RouterDeliversEveryPairOnPlanarGraphs) {
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    for (const GraphInput& in : {random_three_connected(100, seed), random_delaunay_triangulation(100, seed)}) {
      const PlanarGraph& g = in.graph;
      CircleEmbedding phi(g.num_vertices(), Circle{0, 0, 1});  // ignored by the hyperbolic scheme
      const RoutingStats st = evaluate_routing(g, phi, Scheme::hyperbolic);
      EXPECT_EQ(st.pairs, g.num_vertices() * (g.num_vertices() - 1));
      EXPECT_EQ(st.delivered, st.pairs) << in.name;
      EXPECT_GE(st.stretch_mean, 1.0);
    }
  }
}

TEST(HyperbolicEmbedding, IsDeterministic) {
  const GraphInput in = random_three_connected(300, 7);
  const HyperbolicTreeEmbedding a(in.graph), b(in.graph);
  ASSERT_EQ(a.root(), b.root());
  ASSERT_EQ(a.tiling_degree(), b.tiling_degree());
  for (Vertex v = 0; v < a.size(); ++v) {
    EXPECT_EQ(a.parent(v), b.parent(v));
    EXPECT_EQ(a.child_index(v), b.child_index(v));
  }
  const CircleEmbedding phi(in.graph.num_vertices(), Circle{0, 0, 1});
  Router r1(in.graph, phi), r2(in.graph, phi);
  for (Vertex s = 0; s < 300; s += 17)
    for (Vertex t = 0; t < 300; t += 13) EXPECT_EQ(r1.route(Scheme::hyperbolic, s, t).path, r2.route(Scheme::hyperbolic, s, t).path);
}

TEST(HyperbolicEmbedding, DeepPathIsRoutedExactlyWhereDiscCoordinatesWouldNeedThousandsOfBits) {
  // A 3000-node path: the root is its middle (depth 1500), q = 3, D = ln 3, and the chain zig-zags
  // along a geodesic. A Poincaré-disc coordinate of an end node needs thousands of bits; the address
  // needs 2 bits a level, and the relative evaluation decides every hop, certified.
  const std::size_t n = 3000;
  const Adjacency adj = path(n);
  const HyperbolicTreeEmbedding e(adj);
  EXPECT_EQ(e.max_depth(), 1500u);
  EXPECT_EQ(e.tiling_degree(), 3u);
  const Vertex far = e.depth(0) > e.depth(static_cast<Vertex>(n - 1)) ? 0 : static_cast<Vertex>(n - 1);
  EXPECT_EQ(e.address_bits(far), 3000u);
  EXPECT_GT(e.disc_coordinate_bits(far), 2000u);
  const Oracle oracle(e, 256 + 4 * static_cast<mpfr_prec_t>(e.max_depth() * e.edge_length()));
  for (Vertex v = 0; v < n; v += 250)
    EXPECT_NEAR(e.distance(v, static_cast<Vertex>(n - 1)), oracle.distance(v, static_cast<Vertex>(n - 1)),
                1e-9 * oracle.distance(v, static_cast<Vertex>(n - 1)));
  EXPECT_GT(e.distance(0, static_cast<Vertex>(n - 1)), 0.3 * (n - 1) * e.edge_length());
  for (Vertex v = 0; v + 1 < n; v += 97) {
    const HyperbolicHop hop = hyperbolic_hop(e, adj[v], v, static_cast<Vertex>(n - 1));
    ASSERT_TRUE(hop.certified) << v;
    EXPECT_EQ(adj[v][hop.next], v + 1);
  }
}

namespace {
/// Greedy hops from s to t with hyperbolic_hop: "delivered", "uncertified" or "dead_end", checking
/// with the (exact) address evaluation that every hop taken strictly decreases the distance.
std::string walk(const HyperbolicTreeEmbedding& e, const Adjacency& adj, const HyperbolicTreeEmbedding& exact, Vertex s,
                 Vertex t) {
  for (Vertex v = s; v != t;) {
    const HyperbolicHop hop = hyperbolic_hop(e, adj[v], v, t);
    if (hop.next == adj[v].size()) return hop.certified ? "dead_end" : "uncertified";
    const Vertex u = adj[v][hop.next];
    EXPECT_EQ(exact.compare_distance(t, u, v), Sign::negative) << "a hop that does not get closer: " << v << " -> " << u;
    v = u;
  }
  return "delivered";
}
}  // namespace

TEST(HyperbolicEmbedding, DiscCoordinatesInDoublesFailDetectablyOnADeepPath) {
  // The classical representation: each node holds its Poincaré-disc point in two doubles. Its boxes
  // reach the unit circle once d(root, v) exceeds ~37 (1 − |w|² ≈ 4e^{−d} below the doubles' spacing
  // near 1), from where comparisons are undecided: routes are reported `uncertified`, never
  // delivered on a guess. The address representation delivers the same pairs.
  const std::size_t n = 401;
  const Adjacency adj = path(n);
  HyperbolicOptions o;
  o.coordinates = HyperbolicCoordinates::disc_double;
  const HyperbolicTreeEmbedding disc(adj, o), exact(adj);
  ASSERT_EQ(disc.root(), 200u);
  ASSERT_EQ(disc.disc_box(0).size(), 4u);
  EXPECT_TRUE(exact.disc_box(0).empty());
  // Where both decide, they agree: the enclosures of 2·cosh d overlap.
  for (Vertex v = 190; v <= 210; ++v) {
    const auto a = disc.norm(v, 200), b = exact.address_norm(v, 200);
    if (v == 200) continue;
    EXPECT_LE(std::max(a.lo, b.lo * std::ldexp(1.0, 2 * b.exp)), std::min(a.hi, b.hi * std::ldexp(1.0, 2 * b.exp))) << v;
  }
  // Near the root the double coordinates still route; from the ends they cannot, and say so.
  EXPECT_EQ(walk(disc, adj, exact, 195, 205), "delivered");
  EXPECT_EQ(walk(disc, adj, exact, 0, 400), "uncertified");
  EXPECT_EQ(walk(disc, adj, exact, 400, 0), "uncertified");
  EXPECT_EQ(walk(exact, adj, exact, 0, 400), "delivered");
  EXPECT_EQ(walk(exact, adj, exact, 400, 0), "delivered");
  std::size_t uncertified = 0, delivered = 0;
  for (Vertex s = 140; s <= 260; s += 10)
    for (Vertex t = 140; t <= 260; t += 10) {
      if (s == t) continue;
      const std::string r = walk(disc, adj, exact, s, t);
      EXPECT_NE(r, "dead_end");
      (r == "delivered" ? delivered : uncertified) += 1;
    }
  EXPECT_GT(uncertified, 0u);
  EXPECT_GT(delivered, 0u);
}

TEST(HyperbolicEmbedding, RejectsBadInput) {
  EXPECT_THROW(HyperbolicTreeEmbedding(Adjacency{}), InputError);
  EXPECT_THROW(HyperbolicTreeEmbedding(Adjacency{{1}, {0}, {}}), InputError);  // disconnected
  EXPECT_THROW(HyperbolicTreeEmbedding(Adjacency{{5}}), InputError);          // neighbour out of range
  HyperbolicOptions o;
  o.tiling_degree = 3;
  const Adjacency star{{1, 2, 3, 4}, {0}, {0}, {0}, {0}};
  o.root = 0;
  EXPECT_THROW(HyperbolicTreeEmbedding(star, o), InputError);  // the root needs 4 sides
  o.tiling_degree = 4;
  EXPECT_EQ(HyperbolicTreeEmbedding(star, o).tiling_degree(), 4u);
}
