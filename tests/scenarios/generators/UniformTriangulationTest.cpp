#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "MapCensus.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/scenarios/generators/UniformTriangulation.hpp"

using namespace laguerre;
using core::PlanarGraph;
using core::Vertex;

namespace {

/// Number of rooted simple triangulations with n vertices, 2(4m-3)!/(m!(3m-1)!) with m = n - 2 (Tutte,
/// "A census of planar triangulations", Canad. J. Math. 14, 1962), computed as an exact product.
double tutte_triangulations(std::size_t n) {
  if (n == 3) return 1;  // 2 * 1! / (1! 2!)
  const double m = static_cast<double>(n - 2);
  double value = 2.0;  // 2 (4m-3)! / (m! (3m-1)!) = 2/m! * prod_{i=3m}^{4m-3} i
  for (double i = 3 * m; i <= 4 * m - 3; ++i) value *= i;
  for (double i = 2; i <= m; ++i) value /= i;
  return std::round(value);
}

void expect_triangulation(const PlanarGraph& g, std::size_t n) {
  ASSERT_TRUE(g.is_valid(true));
  EXPECT_EQ(g.num_vertices(), n);
  EXPECT_EQ(g.num_edges(), 3 * n - 6);
  for (core::Face f = 0; f < g.num_faces(); ++f) EXPECT_EQ(g.face_size(f), 3u);
  EXPECT_EQ(g.boundary_cycle().size(), 3u);
}

}  // namespace

TEST(UniformTriangulation, TutteCountsMatchTheLiterature) {
  // 1, 1, 3, 13, 68, 399, 2530 rooted simple triangulations with 3..9 vertices (OEIS A000260).
  const std::vector<double> known{1, 1, 3, 13, 68, 399, 2530};
  for (std::size_t i = 0; i < known.size(); ++i) EXPECT_EQ(tutte_triangulations(i + 3), known[i]);
}

TEST(UniformTriangulation, RejectsTooFewVertices) {
  for (std::size_t n : {0, 1, 2}) EXPECT_THROW(scenarios::uniform_triangulation(n, 1), laguerre::core::InternalError);
}

TEST(UniformTriangulation, IsASimpleThreeConnectedTriangulation) {
  for (std::size_t n = 3; n <= 40; ++n)
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
      const PlanarGraph g = scenarios::uniform_triangulation(n, seed);
      expect_triangulation(g, n);
      if (n >= 4) {
        EXPECT_TRUE(core::is_three_connected(g)) << n << " " << seed;
      }
      if (HasFailure()) return;
    }
}

TEST(UniformTriangulation, PreparesAsTriangulatedDiscWithTheRootFaceOutside) {
  const PlanarGraph g = scenarios::uniform_triangulation(200, 7);
  core::GraphKind kind{};
  const PlanarGraph p = core::prepare_for_packing(g, true, &kind);
  EXPECT_EQ(kind, core::GraphKind::triangulated_disc);
  EXPECT_EQ(p.boundary_cycle(), g.boundary_cycle());
  // The two new vertices of the closure (ids n-2, n-1) lie on the root face.
  EXPECT_TRUE(g.is_boundary(198));
  EXPECT_TRUE(g.is_boundary(199));
}

TEST(UniformTriangulation, DeterministicPerSeed) {
  for (std::uint64_t seed : {0ull, 1ull, 12345678901ull}) {
    const PlanarGraph a = scenarios::uniform_triangulation(500, seed), b = scenarios::uniform_triangulation(500, seed);
    ASSERT_EQ(a.num_darts(), b.num_darts());
    for (Vertex v = 0; v < a.num_vertices(); ++v) EXPECT_TRUE(std::ranges::equal(a.neighbours(v), b.neighbours(v)));
    EXPECT_EQ(a.boundary_cycle(), b.boundary_cycle());
  }
  const PlanarGraph c = scenarios::uniform_triangulation(500, 1), d = scenarios::uniform_triangulation(500, 2);
  bool differ = false;
  for (Vertex v = 0; v < c.num_vertices() && !differ; ++v)
    differ = !std::ranges::equal(c.neighbours(v), d.neighbours(v));
  EXPECT_TRUE(differ);
}

// Exact uniformity: with n vertices every rooted triangulation has probability 1/T(n). Samples are
// grouped by isomorphism class of (triangulation, outer face); a class holding r rooted maps (root dart
// on the outer face) must appear with frequency r/T(n). Fixed seeds make the verdict deterministic; the
// significance level is 10^-3. A sampler that redraws a quarter of the samples whose root vertex (a
// new vertex of the closure) has degree 3 fails this test (checked by hand: chi2 = 99 for 7 vertices,
// 232 for 8).
TEST(UniformTriangulation, ExactlyUniformOnSmallSizes) {
  const std::vector<std::pair<std::size_t, std::size_t>> cases{{5, 3000}, {6, 6000}, {7, 20000}, {8, 40000}};
  for (auto [n, samples] : cases) {
    test::Census census;
    for (std::size_t i = 0; i < samples; ++i) census.add(scenarios::uniform_triangulation(n, 1000003 * n + i));
    test::expect_uniform(census, static_cast<std::size_t>(tutte_triangulations(n)),
                         "triangulations with " + std::to_string(n) + " vertices");
  }
}

// Separating triangles (3-cuts): in a uniform random rooted 3-connected triangulation with N = n + 3
// vertices their number is asymptotically normal with mean (10/27) n and variance (320/729) n
// (Z. Gao and G. Schaeffer, "The distribution of the number of small cuts in a random planar
// triangulation", AofA 2010, DMTCS proc. AM, pp. 277-288). Their number is the number of 3-cycles minus
// the 2N - 4 faces.
TEST(UniformTriangulation, SeparatingTrianglesMatchGaoSchaeffer) {
  const std::size_t N = 20000, runs = 4;
  double total = 0;
  for (std::uint64_t seed = 0; seed < runs; ++seed) {
    const PlanarGraph g = scenarios::uniform_triangulation(N, seed);
    total += static_cast<double>(test::count_triangles(g) - (2 * N - 4));
  }
  const double n = static_cast<double>(N - 3);
  const double mean = total / runs, expected = 10.0 / 27.0 * n;
  const double sd_of_mean = std::sqrt(320.0 / 729.0 * n / runs);
  EXPECT_NEAR(mean, expected, 5 * sd_of_mean) << "mean " << mean << " expected " << expected;
  std::printf(
      "[ measured ] separating triangles, N = %zu: mean %.1f over %zu graphs, Gao-Schaeffer %.1f (sd of mean %.1f)\n",
      N, mean, runs, expected, sd_of_mean);
}
