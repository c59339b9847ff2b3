// Synchronous protocol = centralized core::pack (Jacobi, stop = lpd), bit for bit, on many random
// Delaunay triangulations: radii, layout circles and centres, wave numbers, layout tree, local
// outcomes and the iteration count. LAGUERRE_PROPERTY_CASES scales the number of seeds per size.

#include <gtest/gtest.h>

#include <cstdlib>

#include "../SyncCompare.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {
std::uint64_t cases(std::uint64_t fallback) {
  const char* s = std::getenv("LAGUERRE_PROPERTY_CASES");
  return s ? std::max<std::uint64_t>(1, std::strtoull(s, nullptr, 10)) : fallback;
}
}  // namespace

TEST(SyncPackingProperty, EqualsCoreOnRandomTriangulations) {
  const std::uint64_t seeds = cases(24);
  std::size_t graphs = 0, total_iterations = 0;
  for (std::size_t n : {4, 6, 10, 25, 50, 100, 200})
    for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
      const core::PlanarGraph g = core::prepare_for_packing(core::random_delaunay_triangulation(n, 1000 * n + seed));
      if (core::choose_root(core::PackingComplex::from_graph(g), core::RootRule::deepest) == core::none) continue;
      PackingParams p;
      p.steps_per_check = 1 + static_cast<int>(seed % 4);  // N = 1 … 4
      // Every third case delivers in a random order (arbitrary delays, reordering).
      expect_sync_equals_core(g, p, seed % 3 == 0 ? seed : 0,
                              "n=" + std::to_string(n) + " seed=" + std::to_string(seed) + " N=" + std::to_string(p.steps_per_check));
      if (::testing::Test::HasFailure()) return;
      ++graphs;
      core::PackOptions o;
      o.steps_per_check = p.steps_per_check;
      total_iterations += static_cast<std::size_t>(core::pack(g, o).iterations);
    }
  RecordProperty("graphs", static_cast<int>(graphs));
  RecordProperty("iterations", static_cast<int>(total_iterations));
  EXPECT_GT(graphs, 100u);
  EXPECT_GT(total_iterations, 10 * graphs);  // the runs do iterate
}
