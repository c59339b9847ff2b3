#include "laguerre/core/routing/RoutingMetrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "laguerre/core/random/Random.hpp"
#include "laguerre/core/routing/Router.hpp"

namespace laguerre::core {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kMaxFailuresKept = 100;

/// Hop distances from `source` by breadth-first search.
void bfs(const PlanarGraph& g, Vertex source, std::vector<std::uint32_t>& dist, std::vector<Vertex>& queue) {
  std::fill(dist.begin(), dist.end(), std::numeric_limits<std::uint32_t>::max());
  queue.clear();
  dist[source] = 0;
  queue.push_back(source);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const Vertex v = queue[head];
    for (const Vertex w : g.neighbours(v))
      if (dist[w] == std::numeric_limits<std::uint32_t>::max()) {
        dist[w] = dist[v] + 1;
        queue.push_back(w);
      }
  }
}

std::uint64_t ordered_pairs(std::size_t n) { return n < 2 ? 0 : std::uint64_t{n} * std::uint64_t{n - 1}; }

}  // namespace

std::vector<std::pair<Vertex, Vertex>> select_pairs(std::size_t n, const PairSelection& selection) {
  std::vector<std::pair<Vertex, Vertex>> result;
  const std::uint64_t total = ordered_pairs(n);
  if (total == 0) return result;
  // Pair index k ∈ [0, n(n−1)) ↔ (s, t): s = k / (n−1), t = the (k mod (n−1))-th vertex other than s.
  // Increasing k is increasing (s, t), so sorted indices give pairs grouped by source.
  auto pair_of = [&](std::uint64_t k) {
    const auto s = static_cast<Vertex>(k / (n - 1));
    auto t = static_cast<Vertex>(k % (n - 1));
    if (t >= s) ++t;
    return std::pair{s, t};
  };
  if (selection.sample == 0 || selection.sample >= total) {
    result.reserve(total);
    for (std::uint64_t k = 0; k < total; ++k) result.push_back(pair_of(k));
    return result;
  }
  // Floyd's algorithm: for j = N−k .. N−1 draw r uniform in [0, j]; take r, or j if r was taken. Every
  // k-subset is equally likely, k draws, no shuffling of the whole range.
  SeededRandom rng(selection.seed);
  std::unordered_set<std::uint64_t> chosen;
  chosen.reserve(selection.sample);
  std::vector<std::uint64_t> indices;
  indices.reserve(selection.sample);
  for (std::uint64_t j = total - selection.sample; j < total; ++j) {
    const std::uint64_t r = rng.below(j + 1);
    const std::uint64_t pick = chosen.insert(r).second ? r : j;
    if (pick == j) chosen.insert(j);
    indices.push_back(pick);
  }
  std::sort(indices.begin(), indices.end());
  result.reserve(indices.size());
  for (const std::uint64_t k : indices) result.push_back(pair_of(k));
  return result;
}

double nearest_rank_percentile(std::vector<double>& values, unsigned percent) {
  if (values.empty()) return kNaN;
  const std::size_t n = values.size();
  std::size_t rank = (static_cast<std::size_t>(std::min(percent, 100u)) * n + 99) / 100;  // ⌈percent·n/100⌉
  rank = std::max<std::size_t>(rank, 1);
  const auto nth = values.begin() + static_cast<std::ptrdiff_t>(rank - 1);
  std::nth_element(values.begin(), nth, values.end());
  return *nth;
}

RoutingStats evaluate_routing(const PlanarGraph& g, const CircleEmbedding& phi, Scheme s,
                              const PairSelection& pairs, const CircleEmbedding128* phi128) {
  Router router = phi128 != nullptr ? Router(g, phi, *phi128) : Router(g, phi);
  const std::size_t n = g.num_vertices();
  RoutingStats stats;
  stats.scheme = s;
  stats.coordinate_bytes = phi128 != nullptr ? 16 : 8;

  std::vector<std::uint32_t> dist(n);
  std::vector<Vertex> queue;
  queue.reserve(n);
  Vertex bfs_source = none;
  std::vector<double> stretches;
  double stretch_sum = 0, hops_sum = 0, stretch_max = 0;
  Route r;

  auto run = [&](Vertex source, Vertex target) {
    if (source != bfs_source) {
      bfs(g, source, dist, queue);
      bfs_source = source;
    }
    router.route(s, source, target, 0, r);
    ++stats.pairs;
    if (r.outcome == RouteOutcome::delivered) {
      ++stats.delivered;
      const double hops = static_cast<double>(r.hops());
      const double stretch = hops / static_cast<double>(dist[target]);
      hops_sum += hops;
      stretch_sum += stretch;
      stretch_max = std::max(stretch_max, stretch);
      stretches.push_back(stretch);
    } else {
      ++stats.failures_total;
      if (stats.failures.size() < kMaxFailuresKept) stats.failures.push_back({source, target, r.stuck, r.outcome});
    }
  };

  const std::uint64_t total = ordered_pairs(n);
  if (pairs.sample == 0 || pairs.sample >= total) {
    stretches.reserve(total);
    for (Vertex a = 0; a < n; ++a)
      for (Vertex b = 0; b < n; ++b)
        if (a != b) run(a, b);
  } else {
    const auto selected = select_pairs(n, pairs);
    stretches.reserve(selected.size());
    for (const auto& [a, b] : selected) run(a, b);
  }

  const auto delivered = static_cast<double>(stats.delivered);
  stats.delivery_rate = stats.pairs == 0 ? kNaN : delivered / static_cast<double>(stats.pairs);
  if (stats.delivered == 0) {
    stats.stretch_mean = stats.stretch_p95 = stats.stretch_max = stats.hops_mean = kNaN;
  } else {
    stats.stretch_mean = stretch_sum / delivered;
    stats.hops_mean = hops_sum / delivered;
    stats.stretch_max = stretch_max;
    stats.stretch_p95 = nearest_rank_percentile(stretches, 95);
  }
  return stats;
}

}  // namespace laguerre::core
