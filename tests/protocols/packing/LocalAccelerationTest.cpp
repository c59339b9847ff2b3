// The local accelerations (core::LocalAccelerator: chebyshev, local-superstep) in the protocol: each
// node extrapolates its own updates with no extra message, and the synchronous run equals core::pack
// with the same acceleration bit for bit (radii, circles, iteration count, outcome) under FIFO and
// shuffled delivery, on triangulations and 3-connected graphs, and over lossy links.

#include <gtest/gtest.h>

#include "laguerre/core/Error.hpp"
#include "../LossyCompare.hpp"
#include "../SyncCompare.hpp"
#include "../TestGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {
constexpr core::Acceleration local_kinds[] = {core::Acceleration::chebyshev, core::Acceleration::local_superstep};

std::string label(core::Acceleration a, std::size_t n, std::uint64_t seed, int steps) {
  return std::string(core::to_string(a)) + " n=" + std::to_string(n) + " seed=" + std::to_string(seed) +
         " N=" + std::to_string(steps);
}

PackingParams params_of(core::Acceleration a, int steps = 1) {
  PackingParams p;
  p.acceleration = a;
  p.steps_per_check = steps;
  return p;
}
}  // namespace

TEST(LocalAcceleration, TriangulationsEqualCoreBitForBitFifo) {
  for (core::Acceleration a : local_kinds)
    for (std::size_t n : {4, 5, 8, 16, 40, 90, 200})
      for (std::uint64_t seed = 1; seed <= 2; ++seed)
        for (int steps : {1, 3}) {
          const core::PlanarGraph g = delaunay(n, seed);
          if (core::choose_root(core::PackingComplex::from_graph(g), core::RootRule::deepest) == core::none) continue;
          expect_sync_equals_core(g, params_of(a, steps), 0, label(a, n, seed, steps));
          if (::testing::Test::HasFailure()) return;
        }
}

TEST(LocalAcceleration, LargeTriangulationEqualsCoreBitForBit) {
  const core::PlanarGraph g = delaunay(500, 3);
  expect_sync_equals_core(g, params_of(core::Acceleration::chebyshev), 0, "chebyshev n=500");
}

TEST(LocalAcceleration, ThreeConnectedGraphsEqualCoreBitForBitFifo) {
  for (core::Acceleration a : local_kinds)
    for (std::size_t n : {5, 8, 12, 20, 35, 80})
      for (std::uint64_t seed = 1; seed <= 2; ++seed) {
        const core::PlanarGraph g = three_connected(n, 100 * n + seed);
        expect_sync_equals_core(g, params_of(a, static_cast<int>(seed)), 0, label(a, n, seed, static_cast<int>(seed)));
        if (::testing::Test::HasFailure()) return;
      }
}

TEST(LocalAcceleration, EqualsCoreUnderRandomDeliveryOrder) {
  for (core::Acceleration a : local_kinds)
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const int steps = static_cast<int>(seed % 3) + 1;
      expect_sync_equals_core(delaunay(30 + 20 * seed, seed + 100), params_of(a, steps), seed,
                              "shuffled " + label(a, 30 + 20 * seed, seed, steps));
      PackingParams p = params_of(a, steps);
      p.root = seed % 2 ? core::RootRule::deepest : core::RootRule::smallest_id;
      expect_sync_equals_core(three_connected(15 + 10 * seed, seed + 7), p, seed + 50,
                              "shuffled 3-connected " + label(a, 15 + 10 * seed, seed, steps));
      if (::testing::Test::HasFailure()) return;
    }
}

TEST(LocalAcceleration, IterationCapEqualsCore) {
  // Stopped mid-acceleration: the same radii and the cap outcome at every node.
  PackingParams p = params_of(core::Acceleration::chebyshev, 2);
  p.max_iterations = 9;
  expect_sync_equals_core(delaunay(120, 5), p, 0, "cap 9");
  p.update = core::UpdateRule::exact;
  p.max_iterations = 100000;
  expect_sync_equals_core(delaunay(60, 6), p, 4, "exact update");
}

TEST(LocalAcceleration, ChebyshevNeedsFewerStepsThanPlain) {
  // Not a timing: the iteration count that the bit-for-bit comparisons above pin down. Delaunay
  // triangulations are easy for plain sweeps (~75 here); the uniform maps, where the gain is 10-25x,
  // are in tests/scenarios/property.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const core::PlanarGraph g = delaunay(300, seed + 20);
    const int plain = core::pack(g, reference_options(PackingParams{})).iterations;
    const int chebyshev = expect_sync_equals_core(g, params_of(core::Acceleration::chebyshev), 0, "seed " + std::to_string(seed));
    EXPECT_LT(chebyshev, plain) << "seed " << seed;
  }
}

TEST(LocalAcceleration, LossyLinksGiveCoresPackingBitForBit) {
  PackingParams p = params_of(core::Acceleration::chebyshev, 2);
  enable_lossy_links(p, 5'000'000);  // the lossy host's latency is 1–5 ms
  const LossyTotals t = expect_lossy_equals_core(delaunay(40, 11), p, lossy_config(0.25, 0.1, 5), "loss 0.25 dup 0.1");
  EXPECT_GT(t.counters.retransmissions, 0u);
  EXPECT_GT(t.counters.duplicates, 0u);
  p.steps_per_check = 1;
  p.acceleration = core::Acceleration::local_superstep;
  const LossyTotals u = expect_lossy_equals_core(three_connected(30, 4), p, lossy_config(0.2, 0.05, 9), "3-connected loss 0.2");
  EXPECT_GT(u.counters.relayed, 0u);
  EXPECT_GT(u.counters.retransmissions, 0u);
}

TEST(LocalAcceleration, RejectsWhatTheNetworkCannotRun) {
  const core::PlanarGraph g = delaunay(20, 1);
  for (core::Acceleration a : {core::Acceleration::superstep, core::Acceleration::anderson, core::Acceleration::newton})
    EXPECT_THROW(DequeHost(g, params_of(a)), core::InternalError) << core::to_string(a);
  PackingParams p = params_of(core::Acceleration::chebyshev);
  p.asynchronous = true;
  EXPECT_THROW(DequeHost(g, p), core::InternalError);
}
