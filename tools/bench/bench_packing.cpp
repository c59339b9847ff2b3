// Benchmarks of the packing core: one Thurston sweep, one layout + LPD check, and whole runs to LPD
// and to an exact packing, on random Delaunay triangulations of n points in the unit disc.
// tools/bench/run.sh prints the table; run directly for Google Benchmark's own output.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>

#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/graph/RandomGraphs.hpp"
#include "laguerre/core/packing/Packer.hpp"

using namespace laguerre::core;

namespace {
const PlanarGraph& triangulation(std::size_t n) {
  static std::map<std::size_t, PlanarGraph> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, prepare_for_packing(random_delaunay_triangulation(n, 42))).first;
  return it->second;
}

void BM_ThurstonSweep(benchmark::State& state) {
  const PackingComplex k = PackingComplex::from_graph(triangulation(static_cast<std::size_t>(state.range(0))));
  Radii X = initial_radii(k), scratch;
  const Sweep sweep = state.range(1) ? Sweep::gauss_seidel : Sweep::jacobi;
  for (auto _ : state) {
    thurston_sweep(k, X, sweep, UpdateRule::uniform_neighbour, scratch);
    benchmark::DoNotOptimize(X.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(k.graph.num_vertices()));
  state.SetLabel(state.range(1) ? "gauss-seidel" : "jacobi");
}
BENCHMARK(BM_ThurstonSweep)->ArgsProduct({{1000, 10000, 100000, 1000000}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_LayoutAndLpdCheck(benchmark::State& state) {
  const PlanarGraph& g = triangulation(static_cast<std::size_t>(state.range(0)));
  const PackingComplex k = PackingComplex::from_graph(g);
  Radii X = initial_radii(k), scratch;
  for (int i = 0; i < 20; ++i) thurston_sweep(k, X, Sweep::jacobi, UpdateRule::uniform_neighbour, scratch);
  const Vertex root = choose_root(k, RootRule::deepest);
  for (auto _ : state) {
    const Layout lay = lay_out(k, X, root);
    const auto status = check_all(g, lay.circles);
    benchmark::DoNotOptimize(status.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(g.num_vertices()));
}
BENCHMARK(BM_LayoutAndLpdCheck)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

// The same on the state where LPD first holds everywhere (what the last checks of a run cost; the
// early checks above meet inconsistent layouts whose near-degeneracies fall back to exact arithmetic).
void BM_LayoutAndLpdCheckAtLpd(benchmark::State& state) {
  const PlanarGraph& g = triangulation(static_cast<std::size_t>(state.range(0)));
  const PackingComplex k = PackingComplex::from_graph(g);
  PackOptions opt;
  opt.acceleration = Acceleration::anderson;
  opt.steps_per_check = std::max(1, static_cast<int>(state.range(0) / 1000));
  const Radii X = pack(g, opt).radii;
  const Vertex root = choose_root(k, RootRule::deepest);
  std::size_t ok = 0;
  for (auto _ : state) {
    const Layout lay = lay_out(k, X, root);
    const auto status = check_all(g, lay.circles);
    ok = static_cast<std::size_t>(std::count(status.begin(), status.end(), LocalCondition::holds));
  }
  state.counters["lpd_ok"] = static_cast<double>(ok);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(g.num_vertices()));
}
BENCHMARK(BM_LayoutAndLpdCheckAtLpd)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

// Whole runs: counters report the sweeps to LPD or to an exact packing. Arguments: n, rule (0 LPD,
// 1 exact packing), N (sweeps per check), acceleration (0 plain, 1 superstep, 2 anderson, 3 newton:
// then "sweeps" counts Newton steps).
void BM_Pack(benchmark::State& state) {
  const PlanarGraph& g = triangulation(static_cast<std::size_t>(state.range(0)));
  PackOptions opt;
  opt.stop = state.range(1) ? StopRule::exact : StopRule::lpd;
  opt.steps_per_check = static_cast<int>(state.range(2));
  opt.acceleration = static_cast<Acceleration>(state.range(3));
  opt.max_iterations = 2000000;
  PackResult r;
  for (auto _ : state) r = pack(g, opt);
  state.counters["sweeps"] = r.iterations;
  state.counters["converged"] = r.status == PackStatus::converged;
  state.counters["min_radius"] = r.layout.smallest_radius;
  state.SetLabel(std::string(state.range(1) ? "exact" : "LPD") + ", " + std::string(to_string(opt.acceleration)));
}
BENCHMARK(BM_Pack)
    ->ArgsProduct({{1000}, {0, 1}, {1}, {0, 1, 2, 3}})
    ->ArgsProduct({{10000}, {0, 1}, {10}, {0, 1, 2}})
    ->ArgsProduct({{10000}, {0, 1}, {1}, {3}})
    ->ArgsProduct({{100000}, {0, 1}, {100}, {2}})
    ->ArgsProduct({{100000}, {0, 1}, {1}, {3}})
    ->Iterations(1)->Unit(benchmark::kSecond);

// 10^6 vertices to LPD (run.sh --huge): Newton steps (minutes), and Anderson mixing (not reached
// within 90 CPU minutes on 2026-11-20). Plain Thurston sweeps would take days at this size.
void BM_PackHuge(benchmark::State& state) { BM_Pack(state); }
BENCHMARK(BM_PackHuge)->Args({1000000, 0, 1, 3})->Args({1000000, 0, 200, 2})->Iterations(1)->Unit(benchmark::kSecond);
}  // namespace

BENCHMARK_MAIN();
