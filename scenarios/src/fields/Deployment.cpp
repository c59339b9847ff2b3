#include "laguerre/scenarios/fields/Deployment.hpp"

#include "laguerre/core/Error.hpp"
#include "laguerre/core/random/Random.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>

namespace laguerre::scenarios {

using core::Point2;

namespace {

/// Draw budget shared by the rejection loops.
std::size_t draw_budget(std::size_t n) { return 1000 * n + 1000000; }

[[noreturn]] void hopeless(std::size_t n, std::size_t accepted, const char* what) {
  throw core::InputError(std::string("the ") + what + " deployment accepted only " + std::to_string(accepted) +
                         " of " + std::to_string(n) + " points after " + std::to_string(draw_budget(n)) +
                         " draws; the domain is too thin for rejection sampling.");
}

/// Uniform point of the domain's bounding box, kept iff strictly inside; `budget` counts draws.
bool draw_uniform(const core::Domain& domain, core::SeededRandom& random, Point2& out, std::size_t& budget) {
  const auto [xmin, ymin, xmax, ymax] = domain.bounding_box();
  while (budget > 0) {
    --budget;
    const Point2 p{xmin + (xmax - xmin) * random.uniform01(), ymin + (ymax - ymin) * random.uniform01()};
    if (domain.locate(p) == core::DomainSide::inside) {
      out = p;
      return true;
    }
  }
  return false;
}

/// Redraws, in index order, every point equal to an earlier one (by `draw`), until all are distinct.
template <class Draw>
void make_distinct(std::vector<Point2>& points, Draw&& draw) {
  for (;;) {
    std::vector<std::size_t> order(points.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    const auto key = [&](std::size_t i) { return std::tuple{points[i].x, points[i].y, i}; };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
    bool repeated = false;
    for (std::size_t k = 1; k < order.size(); ++k)
      if (points[order[k]].x == points[order[k - 1]].x && points[order[k]].y == points[order[k - 1]].y) {
        points[order[k]] = draw();
        repeated = true;
      }
    if (!repeated) return;
  }
}

}  // namespace

std::vector<Point2> deploy_uniform(const core::Domain& domain, std::size_t n, std::uint64_t seed) {
  LAGUERRE_PRECONDITION(n > 0, "a deployment needs at least one point.");
  core::SeededRandom random(seed);
  std::size_t budget = draw_budget(n);
  std::vector<Point2> points(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!draw_uniform(domain, random, points[i], budget)) hopeless(n, i, "uniform");
  make_distinct(points, [&] {
    Point2 p;
    if (!draw_uniform(domain, random, p, budget)) hopeless(n, n - 1, "uniform");
    return p;
  });
  return points;
}

std::vector<Point2> deploy_clustered(const core::Domain& domain, std::size_t n, const ClusterOptions& options,
                                     std::uint64_t seed) {
  LAGUERRE_PRECONDITION(n > 0, "a deployment needs at least one point.");
  LAGUERRE_PRECONDITION(options.clusters > 0, "a clustered deployment needs at least one cluster.");
  LAGUERRE_PRECONDITION(options.spread > 0 && std::isfinite(options.spread),
                        "the cluster spread must be a positive finite number, not " + std::to_string(options.spread) +
                            ".");
  core::SeededRandom random(seed);
  std::size_t budget = draw_budget(n);
  std::vector<Point2> parents(options.clusters);
  for (std::size_t i = 0; i < parents.size(); ++i)
    if (!draw_uniform(domain, random, parents[i], budget)) hopeless(n, 0, "clustered");
  const auto offset = [&]() -> Point2 {
    for (;;) {  // a uniform point of the square [-1, 1]², kept in the open unit disc (minus the centre)
      const double u = 2 * random.uniform01() - 1, v = 2 * random.uniform01() - 1, s = u * u + v * v;
      if (s >= 1 || s == 0) continue;
      if (options.shape == ClusterShape::disc) return {options.spread * u, options.spread * v};
      const double f = options.spread * std::sqrt(-2 * std::log(s) / s);  // Marsaglia's polar method
      return {f * u, f * v};
    }
  };
  const auto draw_child = [&](std::size_t accepted) -> Point2 {
    while (budget > 0) {
      --budget;
      const Point2 parent = parents[random.below(parents.size())];
      const Point2 d = offset();
      const Point2 p{parent.x + d.x, parent.y + d.y};
      if (domain.locate(p) == core::DomainSide::inside) return p;
    }
    hopeless(n, accepted, "clustered");
  };
  std::vector<Point2> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = draw_child(i);
  make_distinct(points, [&] { return draw_child(n - 1); });
  return points;
}

}  // namespace laguerre::scenarios
