// Benchmarks of the uniform topology generators (scenarios/generators): graphs per second for uniform
// random triangulations (Poulalhon–Schaeffer) and uniform random 3-connected planar graphs (closure of
// binary trees into dissections, with rejection), at n = 10^3 .. 10^6 vertices. The counter
// "attempts" is the mean number of trees drawn per accepted 3-connected graph.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "laguerre/scenarios/generators/UniformThreeConnected.hpp"
#include "laguerre/scenarios/generators/UniformTriangulation.hpp"

using namespace laguerre;

namespace {

void BM_UniformTriangulation(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::uint64_t seed = 0;
  for (auto _ : state) {
    const core::PlanarGraph g = scenarios::uniform_triangulation(n, ++seed);
    benchmark::DoNotOptimize(g.num_darts());
  }
  state.SetItemsProcessed(state.iterations());  // graphs per second
}
BENCHMARK(BM_UniformTriangulation)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMillisecond);

void BM_UniformThreeConnected(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::uint64_t seed = 0;
  double attempts = 0;
  for (auto _ : state) {
    scenarios::ThreeConnectedStats stats;
    const core::PlanarGraph g = scenarios::uniform_three_connected(n, ++seed, 0, &stats);
    attempts += static_cast<double>(stats.attempts);
    benchmark::DoNotOptimize(g.num_darts());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["attempts"] = benchmark::Counter(attempts / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_UniformThreeConnected)->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
