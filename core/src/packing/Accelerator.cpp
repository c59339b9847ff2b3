#include "laguerre/core/packing/Accelerator.hpp"

#include <algorithm>
#include <cmath>

namespace laguerre::core {

bool Accelerator::after_sweep(const PackingComplex& k, const Radii& before, Radii& after) {
  const std::size_t n = after.size();
  previous_.resize(n, 0.0);
  double dot = 0, norm_now = 0, norm_prev = 0;
  // Δ_k in y = log X; boundary entries stay 0.
  std::vector<double>& prev = previous_;
  std::vector<double>& delta = scratch_;
  delta.assign(n, 0.0);
  for (Vertex v = 0; v < n; ++v) {
    if (k.graph.is_boundary(v)) continue;
    const double d = std::log(after[v]) - std::log(before[v]);
    delta[v] = d;
    norm_now += d * d;
    dot += d * prev[v];
    norm_prev += prev[v] * prev[v];
  }
  const bool had = has_previous_;
  prev.swap(delta);
  has_previous_ = true;
  if (!had || norm_prev == 0 || norm_now == 0) return false;
  const double lambda = std::sqrt(norm_now / norm_prev);
  const double cosine = dot / std::sqrt(norm_now * norm_prev);
  if (!(lambda < 1) || cosine < 0.95) return false;
  double factor = std::min(50.0, lambda / (1 - lambda));
  // Keep every hyperbolic radius above half its value: y' = y + f Δ ≤ y / 2 where Δ > 0.
  for (Vertex v = 0; v < n; ++v) {
    const double d = prev[v];
    if (d > 0) factor = std::min(factor, (-0.5 * std::log(after[v])) / d);
  }
  if (!(factor > 0)) return false;
  for (Vertex v = 0; v < n; ++v)
    if (!k.graph.is_boundary(v)) after[v] = std::exp(std::log(after[v]) + factor * prev[v]);
  has_previous_ = false;
  ++jumps_;
  return true;
}

}  // namespace laguerre::core
