// The node-local forms of core's per-vertex computations (StarView) agree bit for bit with the
// centralized ones, on triangulations and on the G′ complexes of 3-connected graphs (orthogonal
// edges, exact solve), for both update rules.

#include <gtest/gtest.h>

#include <bit>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

using namespace laguerre::core;

namespace {
void expect_star_equals_centralized(const PackingComplex& k, int sweeps) {
  Radii X = initial_radii(k), scratch;
  for (int s = 0; s < sweeps; ++s) thurston_sweep(k, X, Sweep::jacobi, UpdateRule::uniform_neighbour, scratch);
  const PlanarGraph& g = k.graph;
  std::vector<double> nx, spoke, rim;
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    if (g.is_boundary(v)) continue;
    nx.clear();
    spoke.clear();
    rim.clear();
    for (std::uint32_t i = 0; i < g.degree(v); ++i) {
      const Dart d = g.first_dart(v) + i;
      nx.push_back(X[g.head(d)]);
      spoke.push_back(k.cos_angle[d]);
      rim.push_back(k.cos_angle[g.next_in_face(d)]);
    }
    StarView s{nx, {}, {}};
    if (!k.tangent_only[v]) s = StarView{nx, spoke, rim};
    EXPECT_EQ(std::bit_cast<std::uint64_t>(star_angle_sum(X[v], s)), std::bit_cast<std::uint64_t>(angle_sum(k, X, v)));
    for (UpdateRule rule : {UpdateRule::uniform_neighbour, UpdateRule::exact})
      EXPECT_EQ(std::bit_cast<std::uint64_t>(star_updated_radius(X[v], s, rule)),
                std::bit_cast<std::uint64_t>(updated_radius(k, X, v, rule)));
  }
}
}  // namespace

TEST(NodeLocalCore, StarUpdateEqualsCentralizedOnTriangulations) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed)
    expect_star_equals_centralized(PackingComplex::from_graph(prepare_for_packing(random_delaunay_triangulation(60, seed))),
                                   static_cast<int>(seed));
}

TEST(NodeLocalCore, StarUpdateEqualsCentralizedOnThreeConnectedComplexes) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const PackingComplex k = PackingComplex::from_graph(prepare_for_packing(random_three_connected(60, seed)));
    ASSERT_TRUE(k.has_face_vertices());
    expect_star_equals_centralized(k, static_cast<int>(seed));
  }
}
