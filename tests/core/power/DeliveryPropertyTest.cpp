// The point of LPD/GLPD: when the condition holds at every vertex, greedy power routing delivers
// (thesis Corollaries after Theorems 5.2.1 and 5.2.4), i.e. for every vertex v and every other vertex
// u some neighbour w of v is strictly closer to p(u) in power than v is. Checked exhaustively, with
// exact comparisons, on seeded jittered packings.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "laguerre/core/power/LocalPowerDiagram.hpp"

using namespace laguerre::core;

namespace {

// Fewer trials in unoptimized (sanitizer) builds, where the exhaustive greedy check dominates.
#ifdef NDEBUG
constexpr int num_trials = 3000;
#else
constexpr int num_trials = 500;
#endif

// Greedy progress towards every target from every vertex (the local-cell criterion of thesis
// Theorem 5.2.3: Cell_G(v) contains no site but p(v)).
bool greedy_delivers(const PlanarGraph& g, const CircleEmbedding& phi) {
  for (Vertex v = 0; v < g.num_vertices(); ++v)
    for (Vertex u = 0; u < g.num_vertices(); ++u) {
      if (u == v) continue;
      bool progress = false;
      for (Vertex w : g.neighbours(v))
        if (w == u || compare_power(centre(phi[u]), phi[w], phi[v]) == Sign::negative) progress = true;
      if (!progress) return false;
    }
  return true;
}

// k × k patch of the hexagonal packing: vertex (i, j) at (2i + j, √3 j), neighbours at 0°, 60°, …
PlanarGraph hex_patch(int k) {
  auto idx = [k](int i, int j) { return static_cast<Vertex>(i + k * j); };
  const int di[6] = {1, 0, -1, -1, 0, 1}, dj[6] = {0, 1, 1, 0, -1, -1};
  std::vector<std::vector<Vertex>> rot(static_cast<std::size_t>(k * k));
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i)
      for (int s = 0; s < 6; ++s) {
        const int a = i + di[s], b = j + dj[s];
        if (a >= 0 && a < k && b >= 0 && b < k) rot[idx(i, j)].push_back(idx(a, b));
      }
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  return g.with_outer_dart(g.find_dart(idx(1, 0), idx(0, 0)));
}

PlanarGraph square_grid(int k) {
  auto idx = [k](int i, int j) { return static_cast<Vertex>(i + k * j); };
  std::vector<std::vector<Vertex>> rot(static_cast<std::size_t>(k * k));
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      auto& r = rot[idx(i, j)];
      if (i + 1 < k) r.push_back(idx(i + 1, j));
      if (j + 1 < k) r.push_back(idx(i, j + 1));
      if (i > 0) r.push_back(idx(i - 1, j));
      if (j > 0) r.push_back(idx(i, j - 1));
    }
  PlanarGraph g = PlanarGraph::from_rotation(rot);
  return g.with_outer_dart(g.find_dart(idx(1, 0), idx(0, 0)));
}

struct Tally {
  int all_hold = 0, some_fail = 0, stuck = 0;  // stuck: greedy fails (only possible when some check fails)
};

template <class Place>
Tally run(const PlanarGraph& g, int trials, std::uint64_t seed, Place place) {
  std::mt19937_64 rng(seed);
  Tally t;
  for (int trial = 0; trial < trials; ++trial) {
    const CircleEmbedding phi = place(rng, trial);
    bool all = true;
    for (LocalCondition c : check_all(g, phi)) all = all && c == LocalCondition::holds;
    if (!all) {
      ++t.some_fail;
      t.stuck += !greedy_delivers(g, phi);
      continue;
    }
    ++t.all_hold;
    EXPECT_TRUE(greedy_delivers(g, phi)) << "trial " << trial << ": the local condition holds everywhere "
                                          << "but greedy power routing gets stuck";
  }
  return t;
}

/// Circles on a k×k lattice, vertex i + k·j: centre scale·(base(i, j) + amount·(u, u')), radius
/// scale·exp(amount·u''), with u, u', u'' uniform in [−1, 1) drawn in that order.
template <class Base>
CircleEmbedding jittered_lattice(int k, double scale, double amount, std::mt19937_64& rng, const Base& base) {
  std::uniform_real_distribution<double> u(-1, 1);
  CircleEmbedding phi(static_cast<std::size_t>(k * k));
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      const Point2 b = base(i, j);
      phi[static_cast<std::size_t>(i + k * j)] = {scale * (b.x + amount * u(rng)), scale * (b.y + amount * u(rng)),
                                                  scale * std::exp(amount * u(rng))};
    }
  return phi;
}

}  // namespace

TEST(DeliveryProperty, LpdEverywhereDeliversOnJitteredHexagonalPackings) {
  const int k = 5;
  const PlanarGraph g = hex_patch(k);
  ASSERT_TRUE(g.inner_faces_are_triangles());
  const double s = 1.0 / 12;  // the patch spans about 12 units: keep it inside the unit disc
  const Tally t = run(g, num_trials, 42, [&](std::mt19937_64& rng, int trial) {
    return jittered_lattice(k, s, 0.05 + 1.2 * (trial % 10) / 10.0, rng, [](int i, int j) {
      return Point2{static_cast<double>(2 * i + j - 6), std::sqrt(3.0) * j - 3.5};
    });
  });
  std::cout << "  all hold " << t.all_hold << ", some fail " << t.some_fail << " (greedy stuck in " << t.stuck << ")\n";
  EXPECT_GT(t.all_hold, num_trials / 10);
  EXPECT_GT(t.some_fail, num_trials / 10);
}

TEST(DeliveryProperty, GlpdEverywhereDeliversOnJitteredOrthogonalGrids) {
  const int k = 5;
  const PlanarGraph g = square_grid(k);
  ASSERT_FALSE(g.inner_faces_are_triangles());
  const double s = 1.0 / 8;
  const Tally t = run(g, num_trials, 43, [&](std::mt19937_64& rng, int trial) {
    return jittered_lattice(k, s, 0.02 + 0.6 * (trial % 10) / 10.0, rng, [](int i, int j) {
      return Point2{static_cast<double>(2 * i - 4), static_cast<double>(2 * j - 4)};
    });
  });
  std::cout << "  all hold " << t.all_hold << ", some fail " << t.some_fail << " (greedy stuck in " << t.stuck << ")\n";
  EXPECT_GT(t.all_hold, num_trials / 10);
  EXPECT_GT(t.some_fail, num_trials / 10);
}
