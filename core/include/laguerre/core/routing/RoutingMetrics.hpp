#pragma once
/// @file
/// Routing metrics over many source–target pairs: delivery rate, hop stretch, failures.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "laguerre/core/routing/Routing.hpp"

namespace laguerre::core {

/// Which ordered pairs (s, t), s ≠ t, to route.
struct PairSelection {
  std::size_t sample = 0;  ///< number of distinct pairs drawn uniformly; 0 (or ≥ n(n−1)) = all pairs
  std::uint64_t seed = 1;  ///< seed of the SeededRandom (std::mt19937_64) the sample is drawn from
};

/// One pair that was not delivered.
struct RoutingFailure {
  Vertex source = none;                            ///< where the packet started
  Vertex target = none;                            ///< where it was going
  Vertex stuck = none;                             ///< Route::stuck
  RouteOutcome outcome = RouteOutcome::dead_end;   ///< how it ended
};

/// Aggregate routing metrics of one scheme on one embedded graph.
///
/// Hop stretch of a delivered pair = hops / (BFS hop distance in the graph). Statistics that are
/// undefined (no pair, or no delivered pair) are NaN.
struct RoutingStats {
  Scheme scheme = Scheme::greedy_power;  ///< the scheme evaluated
  std::size_t pairs = 0;                 ///< pairs routed
  std::size_t delivered = 0;             ///< pairs delivered
  double delivery_rate = 0;              ///< delivered / pairs
  double stretch_mean = 0;               ///< mean hop stretch over delivered pairs
  double stretch_p95 = 0;                ///< 95th percentile (nearest rank) of the hop stretch
  double stretch_max = 0;                ///< largest hop stretch
  double hops_mean = 0;                  ///< mean hop count over delivered pairs
  std::vector<RoutingFailure> failures;  ///< the first (at most 100) failures, in routing order
  std::size_t failures_total = 0;        ///< number of failures (pairs − delivered)
  int coordinate_bytes = 8;              ///< bytes per coordinate the decisions read: 8 (doubles), 16 (binary128)
};

/// The pairs `selection` designates on a graph of n vertices, sorted by (source, target):
/// all n(n−1) ordered pairs when selection.sample is 0 or at least n(n−1); otherwise `sample`
/// distinct pairs drawn without replacement (Floyd's algorithm) with SeededRandom::below from a
/// SeededRandom seeded with selection.seed (core/random/Random.hpp), so the result depends on the
/// seed only, not on the standard library.
std::vector<std::pair<Vertex, Vertex>> select_pairs(std::size_t n, const PairSelection& selection);

/// Nearest-rank percentile: the value of rank ⌈percent·N/100⌉ (1-based, at least 1) in ascending
/// order; NaN for an empty input. `percent` in [0, 100]. Reorders `values`.
double nearest_rank_percentile(std::vector<double>& values, unsigned percent);

/// Routes every selected pair with scheme `s` and aggregates the results. Hop distances come from one
/// breadth-first search per distinct source. Deterministic. With `phi128` (the binary128 circles of
/// the same embedding) the greedy schemes decide on it (Router); other schemes are then refused.
/// Preconditions (InternalError otherwise): phi.size() == g.num_vertices() and every circle finite,
/// and the same for `phi128`.
RoutingStats evaluate_routing(const PlanarGraph& g, const CircleEmbedding& phi, Scheme s,
                              const PairSelection& pairs = {}, const CircleEmbedding128* phi128 = nullptr);

}  // namespace laguerre::core
