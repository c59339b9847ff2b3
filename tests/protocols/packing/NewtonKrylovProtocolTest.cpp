// Newton–Krylov in the network (Acceleration::newton_krylov): Jacobi-preconditioned CG whose matrix-
// vector products are neighbour exchanges and whose dot products are sums on the layout tree. The
// synchronous run equals core::pack's reference (core::NewtonKrylovMethod) bit for bit — radii,
// circles, iteration count, outcome — under FIFO and shuffled delivery, on triangulations and
// 3-connected graphs, and over lossy, duplicating links; a crash ends every survivor with the failure
// status; asynchronous mode is refused.

#include <gtest/gtest.h>

#include "laguerre/core/Error.hpp"
#include "../LossyCompare.hpp"
#include "../SyncCompare.hpp"
#include "../TestGraphs.hpp"

using namespace laguerre;
using namespace laguerre::protocols;
using namespace laguerre::protocols::testing;

namespace {
PackingParams krylov(int steps = 1) {
  PackingParams p;
  p.acceleration = core::Acceleration::newton_krylov;
  p.steps_per_check = steps;
  return p;
}

std::string label(std::size_t n, std::uint64_t seed, int steps) {
  return "n=" + std::to_string(n) + " seed=" + std::to_string(seed) + " N=" + std::to_string(steps);
}
}  // namespace

TEST(NewtonKrylovProtocol, TriangulationsEqualCoreBitForBitFifo) {
  for (std::size_t n : {4, 5, 8, 16, 40, 90, 200})
    for (std::uint64_t seed = 1; seed <= 2; ++seed)
      for (int steps : {1, 3}) {
        const core::PlanarGraph g = delaunay(n, seed);
        if (core::choose_root(core::PackingComplex::from_graph(g), core::RootRule::deepest) == core::none) continue;
        expect_sync_equals_core(g, krylov(steps), 0, label(n, seed, steps));
        if (::testing::Test::HasFailure()) return;
      }
}

TEST(NewtonKrylovProtocol, LargeGraphsEqualCoreBitForBit) {
  expect_sync_equals_core(delaunay(500, 3), krylov(), 0, "n=500");
  expect_sync_equals_core(three_connected(300, 4), krylov(2), 5, "3-connected n=300 shuffled");
}

TEST(NewtonKrylovProtocol, ThreeConnectedGraphsEqualCoreBitForBitFifo) {
  for (std::size_t n : {5, 8, 12, 20, 35, 80})
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const core::PlanarGraph g = three_connected(n, 100 * n + seed);
      expect_sync_equals_core(g, krylov(static_cast<int>(seed)), 0, label(n, seed, static_cast<int>(seed)));
      if (::testing::Test::HasFailure()) return;
    }
}

TEST(NewtonKrylovProtocol, EqualsCoreUnderRandomDeliveryOrder) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const int steps = static_cast<int>(seed % 3) + 1;
    expect_sync_equals_core(delaunay(30 + 20 * seed, seed + 100), krylov(steps), seed,
                            "shuffled " + label(30 + 20 * seed, seed, steps));
    PackingParams p = krylov(steps);
    p.root = seed % 2 ? core::RootRule::deepest : core::RootRule::smallest_id;
    expect_sync_equals_core(three_connected(15 + 10 * seed, seed + 7), p, seed + 50,
                            "shuffled 3-connected " + label(15 + 10 * seed, seed, steps));
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(NewtonKrylovProtocol, IterationCapAndExactUpdateEqualCore) {
  PackingParams p = krylov(2);
  p.max_iterations = 3;  // stopped before LPD: the same radii and the cap outcome at every node
  EXPECT_EQ(expect_sync_equals_core(delaunay(150, 5), p, 0, "cap 3"), 3);
  p.update = core::UpdateRule::exact;
  p.max_iterations = 100000;
  expect_sync_equals_core(three_connected(40, 6), p, 4, "exact update");
}

TEST(NewtonKrylovProtocol, NeedsFarFewerStepsThanPlainAndChebyshev) {
  // The iteration counts that the bit-for-bit comparisons pin down (Newton steps vs sweeps).
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    const core::PlanarGraph g = three_connected(120, seed + 30);
    PackingParams cheb;
    cheb.acceleration = core::Acceleration::chebyshev;
    const int chebyshev = core::pack(g, reference_options(cheb)).iterations;
    const int nk = expect_sync_equals_core(g, krylov(), 0, "seed " + std::to_string(seed));
    EXPECT_LT(3 * nk, chebyshev) << "seed " << seed;
  }
}

TEST(NewtonKrylovProtocol, LossyDuplicatingLinksGiveCoresPackingBitForBit) {
  PackingParams p = krylov(2);
  enable_lossy_links(p, 5'000'000);  // the lossy host's latency is 1–5 ms
  const LossyTotals t = expect_lossy_equals_core(delaunay(40, 11), p, lossy_config(0.25, 0.25, 5), "loss 0.25 dup 0.25");
  EXPECT_GT(t.counters.retransmissions, 0u);
  EXPECT_GT(t.counters.duplicates, 0u);
  p.steps_per_check = 1;
  const LossyTotals u = expect_lossy_equals_core(three_connected(30, 4), p, lossy_config(0.3, 0.2, 9), "3-connected loss 0.3");
  EXPECT_GT(u.counters.relayed, 0u);
  EXPECT_GT(u.counters.retransmissions, 0u);
}

TEST(NewtonKrylovProtocol, ACrashMidStepEndsEverySurvivorWithTheFailureStatus) {
  const core::PlanarGraph g = delaunay(40, 11);
  PackingParams p = krylov(2);
  enable_lossy_links(p, 5'000'000);
  const LossyConfig c = lossy_config(0.1, 0.05, 3);
  LossyHost clean(g, p, c);
  const Time end = clean.run().end;
  ASSERT_GT(end, 0);
  for (core::Vertex victim : {core::Vertex{0}, core::Vertex{17}})
    for (Time at : {end / 4, end / 2}) {  // in the rounds phase: CG iterates and tree sums in flight
      SCOPED_TRACE("victim " + std::to_string(victim) + " at " + std::to_string(at));
      expect_crash_detected(g, p, g.id(victim), at, c);
    }
}

TEST(NewtonKrylovProtocol, AsynchronousModeIsRefused) {
  PackingParams p = krylov();
  p.asynchronous = true;
  EXPECT_THROW(DequeHost(delaunay(20, 1), p), core::InternalError);
}
