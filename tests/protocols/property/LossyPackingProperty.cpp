// The reliability layer over many seeds (docs/protocol.md, "Loss, duplication and crashes"), on the
// lossy host: with loss 0–20%, duplication 0–10% and uniform 1–5 ms latency, every run drains, every
// node finishes with core::pack's radii, circles and iteration count bit for bit (LPD/GLPD outcome
// included), duplicates are detected whenever duplication is on. LAGUERRE_PROPERTY_CASES sets the number
// of seeds (defaults: 30 per triangulation, 12 per 3-connected graph, to keep this executable, which also
// holds the synchronous property tests, under 10 s). Crash properties run on the simulation kernel
// (tests/sim/protocol).

#include <gtest/gtest.h>

#include "../LossyCompare.hpp"
#include "../TestGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {

// Loss in {0, 5, 10, 15, 20}%, duplication in {0, 2.5, 5, 7.5, 10}%, mixed by seed.
LossyConfig config_for(std::uint64_t seed) {
  return lossy_config(0.05 * static_cast<double>(seed % 5), 0.025 * static_cast<double>((seed / 5) % 5), seed);
}

PackingParams params_for(std::uint64_t seed) {
  PackingParams p;
  p.steps_per_check = 1 + static_cast<int>(seed % 3);
  enable_lossy_links(p, 5'000'000);
  return p;
}

// One lossy run per seed on g, with the checks of expect_lossy_equals_core plus the counters' sense.
void check_seeds(const core::PlanarGraph& g, std::uint64_t seeds, const std::string& name, std::size_t& runs) {
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    const LossyConfig c = config_for(seed);
    const LossyTotals t = expect_lossy_equals_core(g, params_for(seed), c, name + " seed=" + std::to_string(seed));
    if (::testing::Test::HasFailure()) return;
    if (c.dup > 0) {
      EXPECT_GT(t.counters.duplicates, 0u) << name << " seed " << seed;
    }
    if (c.loss > 0) {
      EXPECT_GT(t.counters.retransmissions, 0u) << name << " seed " << seed;
    }
    if (c.loss == 0 && c.dup == 0) {
      // Lossless: only the adaptive timeout undercutting a late round trip retransmits (rarely), and
      // each such copy arrives as a duplicate.
      EXPECT_LE(t.counters.retransmissions * 100, t.counters.frames) << name << " seed " << seed;
      EXPECT_EQ(t.counters.duplicates, t.counters.retransmissions) << name << " seed " << seed;
    }
    EXPECT_EQ(t.counters.out_of_window, 0u);
    ++runs;
  }
}

}  // namespace

TEST(LossyPackingProperty, TriangulationsEqualCoreUnderLossAndDuplication) {
  const std::uint64_t seeds = property_cases(30);
  std::size_t runs = 0;
  for (std::size_t n : {20, 45, 80}) {
    const core::PlanarGraph g = delaunay(n, 31 * n + 1);
    check_seeds(g, seeds, "triangulation n=" + std::to_string(n), runs);
    if (HasFailure()) return;
  }
  EXPECT_EQ(runs, 3 * seeds);
}

TEST(LossyPackingProperty, ThreeConnectedGraphsEqualCoreUnderLossAndDuplication) {
  const std::uint64_t seeds = property_cases(12);
  std::size_t runs = 0;
  for (std::size_t n : {20, 40}) {
    const core::PlanarGraph g = three_connected(n, 53 * n + 2);
    ASSERT_TRUE(core::PackingComplex::from_graph(g).has_face_vertices());
    check_seeds(g, seeds, "3-connected n=" + std::to_string(n), runs);
    if (HasFailure()) return;
  }
  EXPECT_EQ(runs, 2 * seeds);
}
