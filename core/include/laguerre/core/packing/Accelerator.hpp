#pragma once
/// @file
/// Extrapolation ("super steps") that accelerates Thurston's iteration.

#include <vector>

#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// Geometric extrapolation of Thurston's iteration, after Collins & Stephenson (2003).
///
/// Once the fast error modes have died out, successive sweep changes Δ_k = y_{k+1} − y_k (in the
/// variable y = log X = −2h of the interior vertices) become nearly parallel with a stable ratio
/// λ = |Δ_k| / |Δ_{k−1}| < 1: the error decays like a geometric series along one direction. Summing
/// the rest of the series, y + λ/(1−λ) Δ_k, jumps most of the remaining way. The jump is taken only
/// when cos(Δ_k, Δ_{k−1}) ≥ 0.95 and λ < 1, is capped (factor ≤ 50, and no vertex's hyperbolic radius
/// may shrink by more than half), and the history is reset after each jump. The decision uses two
/// global sums, so a distributed network can take it with the convergecast it already runs.
class Accelerator {
public:
  /// Observes the sweep from `before` to `after` and may extrapolate `after` in place.
  /// Returns whether it extrapolated.
  bool after_sweep(const PackingComplex& k, const Radii& before, Radii& after);
  /// Number of extrapolations so far.
  int jumps() const { return jumps_; }

private:
  std::vector<double> previous_;  // Δ_{k−1} over all vertices (0 on the boundary)
  std::vector<double> scratch_;   // Δ_k while it is being computed
  bool has_previous_ = false;
  int jumps_ = 0;
};

}  // namespace laguerre::core
