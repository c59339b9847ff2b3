#pragma once
/// @file
/// Accelerations of Thurston's iteration: geometric extrapolation ("super steps") and Anderson mixing.

#include <string_view>
#include <vector>

#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// How sweeps are accelerated. Both methods only need a few global sums per sweep, which a network
/// can gather with the convergecast it already runs each round.
enum class Acceleration {
  plain,       ///< plain Thurston sweeps
  superstep,   ///< Collins & Stephenson's geometric extrapolation along a stable error direction
  anderson,    ///< Anderson mixing of the last few sweeps (AA(m), type II)
  newton       ///< not a sweep: damped Newton steps on the angle sums (Newton.hpp; centralized only)
};

/// Name of an acceleration ("plain", "superstep", "anderson", "newton").
std::string_view to_string(Acceleration a);
/// Parses an acceleration name; throws InputError listing the valid names (PackingNames.hpp).
Acceleration parse_acceleration(std::string_view name);

/// Accelerates the fixed-point iteration y ← F(y) that Thurston sweeps perform, in the variable
/// y = log X = −2h of the interior vertices.
///
/// - superstep: once successive changes Δ_k = F(y_k) − y_k are nearly parallel (cosine ≥ 0.95) with a
///   stable ratio λ = |Δ_k| / |Δ_{k−1}| < 1, the error decays like a geometric series along one
///   direction; y + λ/(1−λ) Δ_k sums the rest of the series (factor capped at 50). History is reset
///   after each jump.
/// - anderson: y_{k+1} = F(y_k) − ΔG γ with γ minimising |f_k − ΔF γ| over the last m = 6 residual
///   differences (f = F(y) − y, ΔF and ΔG the differences of residuals and of images), solved by
///   regularised normal equations. A step whose residual norm grows by more than 10× restarts the
///   history with a plain sweep.
/// In both, no hyperbolic radius may shrink below half its value in one step (X stays in (0, 1)).
class Accelerator {
public:
  /// An accelerator of the given kind (`plain` never changes anything).
  explicit Accelerator(Acceleration kind = Acceleration::superstep) : kind_(kind) {}
  /// Observes the sweep from `before` (y_k) to `after` (F(y_k)) and may replace `after` by an
  /// accelerated iterate. Returns whether it did.
  bool after_sweep(const PackingComplex& k, const Radii& before, Radii& after);
  /// Number of accelerated steps so far.
  int jumps() const { return jumps_; }

private:
  bool superstep(const PackingComplex& k, const Radii& before, Radii& after);
  bool anderson(const PackingComplex& k, const Radii& before, Radii& after);

  Acceleration kind_;
  std::vector<double> previous_;  // superstep: Δ_{k−1} over all vertices (0 on the boundary)
  std::vector<double> scratch_;   // superstep: Δ_k while it is being computed
  bool has_previous_ = false;
  // anderson: interior indices, last residual and image, and the difference histories (column-major).
  std::vector<std::uint32_t> interior_;
  std::vector<double> last_f_, last_g_;
  std::vector<std::vector<double>> dF_, dG_;
  double last_norm_ = 0;
  int jumps_ = 0;
};

}  // namespace laguerre::core
