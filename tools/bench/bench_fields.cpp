// Sensor-field constructions (scenarios/fields): points per second of deployment, restricted Delaunay,
// unit-disk graph, Gabriel, RNG and LDel^(2) at 10^4 and 10^5 points, mean UDG degree ≈ 12 (R scaled
// with √(area / n)). Run: build/release/tools/bench/bench_fields
#include <benchmark/benchmark.h>

#include <cmath>

#include "laguerre/scenarios/fields/Deployment.hpp"
#include "laguerre/scenarios/fields/FieldGraph.hpp"
#include "laguerre/scenarios/fields/ProximityGraphs.hpp"

namespace {

using namespace laguerre::scenarios;
using laguerre::core::Domain;

/// The unit square with two square holes (area 0.92).
const Domain& domain() {
  static const Domain d({{0, 0}, {1, 0}, {1, 1}, {0, 1}},
                        {{{0.2, 0.2}, {0.4, 0.2}, {0.4, 0.4}, {0.2, 0.4}}, {{0.6, 0.5}, {0.8, 0.5}, {0.8, 0.7}, {0.6, 0.7}}});
  return d;
}

/// Radius giving a mean unit-disk degree of about 12: n π R² / area = 12.
double radius(std::size_t n) { return std::sqrt(12 * domain().area() / (3.141592653589793 * static_cast<double>(n))); }

template <class F>
void run(benchmark::State& state, F&& f) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto points = deploy_uniform(domain(), n, 1);
  std::size_t edges = 0;
  for (auto _ : state) {
    const EdgeList e = f(points, radius(n));
    edges = e.size();
    benchmark::DoNotOptimize(e.data());
  }
  state.counters["edges/point"] = static_cast<double>(edges) / static_cast<double>(n);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

void BM_DeployUniform(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(deploy_uniform(domain(), n, 1).data());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}
void BM_RestrictedDelaunay(benchmark::State& state) {
  run(state, [](const auto& p, double) { return restricted_delaunay_edges(domain(), p); });
}
void BM_UnitDisk(benchmark::State& state) { run(state, [](const auto& p, double r) { return unit_disk_edges(p, r); }); }
void BM_Gabriel(benchmark::State& state) { run(state, [](const auto& p, double r) { return gabriel_edges(p, r); }); }
void BM_RelativeNeighbourhood(benchmark::State& state) {
  run(state, [](const auto& p, double r) { return relative_neighbourhood_edges(p, r); });
}
void BM_LocalDelaunay2(benchmark::State& state) {
  run(state, [](const auto& p, double r) { return local_delaunay_edges(p, r, 2); });
}
/// The whole pipeline for a field with holes: restricted Delaunay, report, three-connected core.
void BM_FieldGraphDelaunayCore(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto points = deploy_uniform(domain(), n, 1);
  const FieldGraphOptions o{FieldGraphType::delaunay, 0, 2, RepairPolicy::three_connected_core, "bench"};
  for (auto _ : state) benchmark::DoNotOptimize(build_field_graph(domain(), points, o).report.removed_points);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

}  // namespace

BENCHMARK(BM_DeployUniform)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RestrictedDelaunay)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_UnitDisk)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Gabriel)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RelativeNeighbourhood)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LocalDelaunay2)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FieldGraphDelaunayCore)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
