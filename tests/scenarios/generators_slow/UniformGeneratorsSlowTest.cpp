// Heavy variants of tests/scenarios/generators (CTest label `slow`, excluded from the default run):
// exact uniformity at the next sizes up, and the asymptotic properties at 10^5 – 10^6 vertices.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "../generators/MapCensus.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/scenarios/generators/UniformThreeConnected.hpp"
#include "laguerre/scenarios/generators/UniformTriangulation.hpp"

using namespace laguerre;
using core::PlanarGraph;

// 2530 rooted simple triangulations with 9 vertices (Tutte 1962; OEIS A000260).
TEST(UniformGeneratorsSlow, TriangulationsWithNineVerticesExactlyUniform) {
  test::Census census;
  for (std::size_t i = 0; i < 150000; ++i) census.add(scenarios::uniform_triangulation(9, 424242 + i));
  test::expect_uniform(census, 2530, "triangulations with 9 vertices");
}

// 676 and 2209 rooted 3-connected maps with 13 and 14 edges (Tutte 1963; OEIS A000287).
TEST(UniformGeneratorsSlow, ThreeConnectedMapsWith13And14EdgesExactlyUniform) {
  for (auto [m, total, samples] : std::vector<std::array<std::size_t, 3>>{{13, 676, 60000}, {14, 2209, 150000}}) {
    test::Census census;
    for (std::size_t i = 0; i < samples; ++i)
      census.add(scenarios::uniform_three_connected_map_by_edges(m, 31 * m + i * 7919));
    test::expect_uniform(census, total, "3-connected maps with " + std::to_string(m) + " edges");
  }
}

// Gao–Schaeffer (AofA 2010): separating triangles of a uniform 3-connected triangulation with n + 3
// vertices: mean (10/27) n, variance (320/729) n. Here at 10^6 vertices, each graph within 5 sd.
TEST(UniformGeneratorsSlow, SeparatingTrianglesAtAMillionVertices) {
  const std::size_t N = 1000000;
  for (std::uint64_t seed = 0; seed < 2; ++seed) {
    const PlanarGraph g = scenarios::uniform_triangulation(N, seed);
    ASSERT_TRUE(g.is_valid());
    const double n = static_cast<double>(N - 3);
    const double separating = static_cast<double>(test::count_triangles(g) - (2 * N - 4));
    EXPECT_NEAR(separating, 10.0 / 27.0 * n, 5 * std::sqrt(320.0 / 729.0 * n));
  }
}

// Large 3-connected graphs: valid, 3-connected, and edges / vertices close to (7 + sqrt 7)/4.
TEST(UniformGeneratorsSlow, ThreeConnectedAtAMillionVertices) {
  const std::size_t n = 1000000;
  const PlanarGraph g = scenarios::uniform_three_connected(n, 1);
  ASSERT_TRUE(g.is_valid());
  EXPECT_EQ(g.num_vertices(), n);
  EXPECT_TRUE(core::is_three_connected(g));
  EXPECT_NEAR(static_cast<double>(g.num_edges()) / static_cast<double>(n), (7 + std::sqrt(7.0)) / 4, 0.002);
}
