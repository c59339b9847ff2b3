// Benchmarks of the Apollonius and anisotropic diagrams (issue 5): Apollonius through CGAL's
// Apollonius_graph_hierarchy_2 against the linearization (thesis Algorithm 1, a 3D regular
// triangulation) at 10^3 … 10^6 sites, and the anisotropic vertices through the regular complex in R⁵
// at 10^2 … 10^4 sites. Run: build/<dir>/tools/bench/bench_diagrams_aw --benchmark_counters_tabular=true
// (anchor on this machine kind: Apollonius_graph_hierarchy_2 takes about 7 s for 10^6 sites).
#include <benchmark/benchmark.h>

#include <CGAL/Apollonius_graph_2.h>
#include <CGAL/Apollonius_graph_filtered_traits_2.h>
#include <CGAL/Apollonius_graph_hierarchy_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <chrono>
#include <cmath>
#include <random>

#include "laguerre/core/diagrams/AnisotropicDiagram.hpp"
#include "laguerre/core/diagrams/ApolloniusDiagram.hpp"

using namespace laguerre::core;

namespace {

/// n sites uniform in the unit square, weights up to half the typical spacing.
std::vector<ApolloniusSite> apollonius_sites(std::size_t n) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0, 1), w(0, 0.5 / std::sqrt(static_cast<double>(n)));
  std::vector<ApolloniusSite> s(n);
  for (auto& x : s) x = {u(rng), u(rng), w(rng)};
  return s;
}

/// n sites uniform in the unit square, metrics with eigenvalues in [1, 4] and random axes.
std::vector<AnisotropicSite> anisotropic_sites(std::size_t n) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0, 1), e(1, 4), angle(0, 3.14159);
  std::vector<AnisotropicSite> s(n);
  for (auto& x : s) {
    const double l1 = e(rng), l2 = e(rng), t = angle(rng), c = std::cos(t), sn = std::sin(t);
    x = {u(rng), u(rng), l1 * c * c + l2 * sn * sn, (l1 - l2) * c * sn, l1 * sn * sn + l2 * c * c};
  }
  return s;
}

template <ApolloniusDiagram (*Build)(const std::vector<ApolloniusSite>&)>
void BM_Apollonius(benchmark::State& state) {
  const auto sites = apollonius_sites(static_cast<std::size_t>(state.range(0)));
  std::size_t vertices = 0, hidden = 0;
  for (auto _ : state) {
    const ApolloniusDiagram d = Build(sites);
    vertices = d.vertices.size(), hidden = d.hidden.size();
    benchmark::DoNotOptimize(d.vertices.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["hidden"] = static_cast<double>(hidden);
}

/// CGAL alone on the same sites (issue 14 §5: where the facade's time goes): the hierarchy filled
/// one site at a time in the input order (what apollonius_diagram_cgal does), or after CGAL's
/// spatial_sort (Hilbert order); no index, no edges, no vertices read back.
template <bool Sorted>
void BM_CgalApolloniusRaw(benchmark::State& state) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Gt = CGAL::Apollonius_graph_filtered_traits_2<K>;
  using Ag = CGAL::Apollonius_graph_hierarchy_2<Gt>;
  std::vector<Gt::Site_2> sites;
  for (const ApolloniusSite& x : apollonius_sites(static_cast<std::size_t>(state.range(0))))
    sites.emplace_back(K::Point_2(x.x, x.y), x.w);
  double sort_seconds = 0;
  if constexpr (Sorted) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<K::Point_2> points;
    for (const Gt::Site_2& x : sites) points.push_back(x.point());
    std::vector<std::size_t> order(sites.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    CGAL::spatial_sort(order.begin(), order.end(),
                       CGAL::Spatial_sort_traits_adapter_2<K, decltype(CGAL::make_property_map(points))>(
                           CGAL::make_property_map(points)),
                       CGAL::Hilbert_sort_median_policy());
    std::vector<Gt::Site_2> sorted;
    for (const std::size_t i : order) sorted.push_back(sites[i]);
    sites.swap(sorted);
    sort_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  std::size_t vertices = 0;
  for (auto _ : state) {
    Ag ag;
    for (const Gt::Site_2& x : sites) ag.insert(x);
    vertices = ag.number_of_vertices();
    benchmark::DoNotOptimize(vertices);
  }
  state.counters["visible"] = static_cast<double>(vertices);
  state.counters["sort_s"] = sort_seconds;
}

void BM_AnisotropicVertices(benchmark::State& state) {
  const auto sites = anisotropic_sites(static_cast<std::size_t>(state.range(0)));
  std::size_t vertices = 0, candidates = 0;
  for (auto _ : state) {
    const AnisotropicDiagram d = anisotropic_diagram(sites);
    vertices = d.vertices.size(), candidates = d.candidate_triangles;
    benchmark::DoNotOptimize(d.vertices.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["candidates"] = static_cast<double>(candidates);
}

}  // namespace

BENCHMARK_TEMPLATE(BM_Apollonius, apollonius_diagram_cgal)
    ->Name("BM_ApolloniusCgal")->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000)
    ->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_TEMPLATE(BM_CgalApolloniusRaw, false)
    ->Name("BM_CgalApolloniusRaw")->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000)
    ->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_TEMPLATE(BM_CgalApolloniusRaw, true)
    ->Name("BM_CgalApolloniusRawHilbert")->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000)
    ->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_TEMPLATE(BM_Apollonius, apollonius_diagram_linearized)
    ->Name("BM_ApolloniusLinearized")->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000)
    ->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_AnisotropicVertices)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_MAIN();
