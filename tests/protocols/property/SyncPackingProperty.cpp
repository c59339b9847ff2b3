// Synchronous protocol = centralized core::pack (Jacobi, stop = lpd), bit for bit, on many random
// Delaunay triangulations: radii, layout circles and centres, wave numbers, layout tree, local
// outcomes and the iteration count. LAGUERRE_PROPERTY_CASES scales the number of seeds per size.

#include <gtest/gtest.h>

#include "../SyncCompare.hpp"
#include "../TestGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

TEST(SyncPackingProperty, EqualsCoreOnRandomTriangulations) {
  const std::uint64_t seeds = property_cases(24);
  std::size_t graphs = 0, total_iterations = 0;
  for (std::size_t n : {4, 6, 10, 25, 50, 100, 200})
    for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
      const core::PlanarGraph g = delaunay(n, 1000 * n + seed);
      if (core::choose_root(core::PackingComplex::from_graph(g), core::RootRule::deepest) == core::none) continue;
      PackingParams p;
      p.steps_per_check = 1 + static_cast<int>(seed % 4);  // N = 1 … 4
      // Every third case delivers in a random order (arbitrary delays, reordering).
      const int it = expect_sync_equals_core(
          g, p, seed % 3 == 0 ? seed : 0, "n=" + std::to_string(n) + " seed=" + std::to_string(seed) + " N=" + std::to_string(p.steps_per_check));
      if (::testing::Test::HasFailure()) return;
      ++graphs;
      total_iterations += static_cast<std::size_t>(it);
    }
  RecordProperty("graphs", static_cast<int>(graphs));
  RecordProperty("iterations", static_cast<int>(total_iterations));
  EXPECT_GT(graphs, 100u);
  EXPECT_GT(total_iterations, 10 * graphs);  // the runs do iterate
}

// The same on random 3-connected plane graphs: K = G′ with face vertices emulated by their hosts and
// relayed along faces; compares every vertex of K (face vertices included), the GLPD outcome of every
// vertex of G and the iteration count. Half the cases deliver in a random order.
TEST(SyncPackingProperty, EqualsCoreOnRandomThreeConnectedGraphs) {
  const std::uint64_t seeds = property_cases(24);
  std::size_t graphs = 0, with_faces = 0, face_vertices = 0, total_iterations = 0;
  for (std::size_t n : {5, 7, 10, 16, 25, 40, 70, 120})
    for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
      const core::PlanarGraph g = three_connected(n, 7000 * n + seed);
      const core::PackingComplex k = core::PackingComplex::from_graph(g);
      if (core::choose_root(k, core::RootRule::deepest) == core::none) continue;
      PackingParams p;
      p.steps_per_check = 1 + static_cast<int>(seed % 3);  // N = 1 … 3
      p.root = seed % 5 == 0 ? core::RootRule::smallest_id : core::RootRule::deepest;
      const int it = expect_sync_equals_core(
          g, p, seed % 2 == 0 ? seed : 0, "3c n=" + std::to_string(n) + " seed=" + std::to_string(seed) + " N=" + std::to_string(p.steps_per_check));
      if (::testing::Test::HasFailure()) return;
      ++graphs;
      with_faces += k.has_face_vertices();
      face_vertices += k.face_of_vertex.size();
      total_iterations += static_cast<std::size_t>(it);
    }
  RecordProperty("graphs", static_cast<int>(graphs));
  RecordProperty("face_vertices", static_cast<int>(face_vertices));
  RecordProperty("iterations", static_cast<int>(total_iterations));
  EXPECT_GT(graphs, 150u);
  EXPECT_GT(with_faces, graphs * 3 / 4);
  EXPECT_GT(total_iterations, 10 * graphs);
}
