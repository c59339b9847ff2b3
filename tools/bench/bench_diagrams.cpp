// Benchmarks of the diagram library (issue 5): Voronoi, power and Möbius/multiplicatively weighted
// diagrams at 10^3 … 10^6 sites, side by side with CGAL's raw structures (Regular_triangulation_2
// insertion — anchor: about 1.0 s for 10^6 sites on this machine kind — and the Regular_triangulation_3
// of the lifted spheres that the Möbius construction starts from).
// Run: tools/bench/diagrams.sh, or build/<dir>/tools/bench/bench_diagrams --benchmark_counters_tabular=true
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_3.h>
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "laguerre/core/diagrams/MobiusDiagram.hpp"
#include "laguerre/core/diagrams/PowerDiagram.hpp"
#include "laguerre/core/diagrams/VoronoiDiagram.hpp"

using namespace laguerre::core;

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

/// n sites uniform in the unit square; power weights up to a quarter of the squared typical spacing.
std::vector<WeightedPoint> weighted_sites(std::size_t n) {
  std::mt19937_64 rng(42);
  const double spacing2 = 1.0 / static_cast<double>(n);
  std::uniform_real_distribution<double> u(0, 1), w(0, 0.25 * spacing2);
  std::vector<WeightedPoint> s(n);
  for (auto& x : s) x = {u(rng), u(rng), w(rng)};
  return s;
}

/// n Möbius sites uniform in the unit square: λ in [1, 2], μ up to a typical spacing² (so cells are of
/// comparable sizes and few are empty).
std::vector<MobiusSite> mobius_sites(std::size_t n) {
  std::mt19937_64 rng(42);
  const double spacing2 = 1.0 / static_cast<double>(n);
  std::uniform_real_distribution<double> u(0, 1), l(1, 2), m(0, spacing2);
  std::vector<MobiusSite> s(n);
  for (auto& x : s) x = {u(rng), u(rng), l(rng), m(rng)};
  return s;
}

/// n multiplicatively weighted sites, weights in [1, 1.5] (λ = 1/w²).
std::vector<MobiusSite> mw_sites(std::size_t n) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(0, 1), w(1, 1.5);
  std::vector<MobiusSite> s(n);
  for (auto& x : s) x = multiplicative_site(u(rng), u(rng), w(rng));
  return s;
}

const Box unit{0, 0, 1, 1};

void sizes(benchmark::internal::Benchmark* b, std::int64_t max) {
  for (std::int64_t n = 1000; n <= max; n *= 10) b->Arg(n);
  b->Unit(benchmark::kMillisecond);
}

void BM_CgalRegularTriangulation2(benchmark::State& state) {
  using RT = CGAL::Regular_triangulation_2<K>;
  const auto s = weighted_sites(static_cast<std::size_t>(state.range(0)));
  std::vector<RT::Weighted_point> p;
  for (const auto& x : s) p.emplace_back(K::Point_2(x.x, x.y), x.w);
  for (auto _ : state) {
    RT rt;
    rt.insert(p.begin(), p.end());
    benchmark::DoNotOptimize(rt.number_of_vertices());
  }
  state.counters["sites/s"] = benchmark::Counter(static_cast<double>(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_CgalRegularTriangulation2)->Apply([](auto* b) { sizes(b, 1000000); });

void BM_VoronoiDiagram(benchmark::State& state) {
  std::vector<Point2> p;
  for (const auto& x : weighted_sites(static_cast<std::size_t>(state.range(0)))) p.push_back({x.x, x.y});
  for (auto _ : state) {
    VoronoiDiagram d(p, unit);
    benchmark::DoNotOptimize(d.edges().size());
  }
  state.counters["sites/s"] = benchmark::Counter(static_cast<double>(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_VoronoiDiagram)->Apply([](auto* b) { sizes(b, 1000000); });

void BM_PowerDiagram(benchmark::State& state) {
  const auto s = weighted_sites(static_cast<std::size_t>(state.range(0)));
  std::size_t hidden = 0;
  for (auto _ : state) {
    PowerDiagram d(s, unit);
    hidden = d.hidden_sites().size();
    benchmark::DoNotOptimize(d.edges().size());
  }
  state.counters["sites/s"] = benchmark::Counter(static_cast<double>(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["hidden"] = static_cast<double>(hidden);
}
BENCHMARK(BM_PowerDiagram)->Apply([](auto* b) { sizes(b, 1000000); });

/// The first step of the Möbius construction alone: CGAL's 3D regular triangulation of the lifted spheres.
void BM_CgalRegularTriangulation3Lifted(benchmark::State& state) {
  using RT3 = CGAL::Regular_triangulation_3<K>;
  const auto s = mobius_sites(static_cast<std::size_t>(state.range(0)));
  std::vector<RT3::Weighted_point> p;
  for (const auto& x : s) {
    const double l = x.lambda, pp = x.x * x.x + x.y * x.y, h = (1 - l) / 2;
    p.emplace_back(K::Point_3(l * x.x, l * x.y, h), l * (l - 1) * pp + h * h + x.mu);
  }
  for (auto _ : state) {
    RT3 rt;
    rt.insert(p.begin(), p.end());
    benchmark::DoNotOptimize(rt.number_of_vertices());
  }
  state.counters["sites/s"] = benchmark::Counter(static_cast<double>(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_CgalRegularTriangulation3Lifted)->Apply([](auto* b) { sizes(b, 1000000); });

template <std::vector<MobiusSite> (*Make)(std::size_t)>
void BM_Mobius(benchmark::State& state) {
  const auto s = Make(static_cast<std::size_t>(state.range(0)));
  std::size_t vertices = 0, edges = 0, empty = 0;
  for (auto _ : state) {
    MobiusDiagram d(s, unit);
    vertices = d.vertices().size(), edges = d.edges().size(), empty = d.empty_sites().size();
  }
  state.counters["sites/s"] = benchmark::Counter(static_cast<double>(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["edges"] = static_cast<double>(edges);
  state.counters["empty"] = static_cast<double>(empty);
}
BENCHMARK(BM_Mobius<mobius_sites>)->Name("BM_MobiusDiagram")->Apply([](auto* b) { sizes(b, 1000000); });
BENCHMARK(BM_Mobius<mw_sites>)->Name("BM_MultiplicativelyWeighted")->Apply([](auto* b) { sizes(b, 1000000); });

}  // namespace

BENCHMARK_MAIN();
