#pragma once
/// @file
/// Accelerations of Thurston's iteration: geometric extrapolation ("super steps") and Anderson mixing.

#include <string_view>
#include <vector>

#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// How sweeps are accelerated. superstep and anderson need a few global sums per sweep (centralized
/// only); chebyshev and local_superstep are local: each vertex reads only its own radius history
/// (LocalAccelerator), so the distributed protocol runs them with no extra message.
enum class Acceleration {
  plain,       ///< plain Thurston sweeps
  superstep,   ///< Collins & Stephenson's geometric extrapolation along a stable error direction
  anderson,    ///< Anderson mixing of the last few sweeps (AA(m), type II)
  newton,      ///< not a sweep: damped Newton steps on the angle sums (Newton.hpp; centralized only)
  chebyshev,   ///< local adaptive Chebyshev (second-order Richardson) iteration, per vertex
  local_superstep,  ///< Collins & Stephenson's extrapolation with the ratio each vertex sees locally
  newton_krylov     ///< not a sweep: damped Newton steps solved by CG in the network (NewtonKrylov.hpp)
};

/// Whether the distributed protocol can run `a` (plain and the local accelerations).
constexpr bool is_local(Acceleration a) {
  return a == Acceleration::plain || a == Acceleration::chebyshev || a == Acceleration::local_superstep;
}

/// Whether the distributed protocol can run `a`: the local kinds and newton_krylov (synchronous mode
/// only: its CG iterates must be consistent).
constexpr bool runs_in_network(Acceleration a) { return is_local(a) || a == Acceleration::newton_krylov; }

/// Name of an acceleration ("plain", "superstep", "anderson", "newton", "chebyshev", "local-superstep",
/// "newton-krylov").
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
  /// An accelerator of the given kind (`plain`, `newton` and the local kinds, which are
  /// LocalAccelerator's, never change anything).
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

/// The local accelerations of Thurston's Jacobi iteration, as one interior vertex runs them: its state
/// is its own radius history, its input its current radius h = h_k and its plain update f = F(h_k)_v;
/// no global quantity, no set-up constant. core::pack holds one per vertex and the distributed
/// protocol one per protocol vertex, both calling `next` with the same values in the same order (bit
/// for bit). docs/protocol.md derives the method; in short, with residual d_k = f − h_k:
///
/// - chebyshev: the second-order (stationary Chebyshev) iteration h_{k+1} = h_{k−1} + ω (f − h_{k−1}),
///   ω = 2 / (1 + √(1 − ρ²)). ρ, the vertex's estimate of the spectral radius of the Jacobi map, starts
///   at 0 (ω = 1: plain Thurston) and only grows. The vertex measures its contraction
///   q = (d_k / d_{k−4})^{1/4} over its last five residuals when they have one sign; when two successive
///   q agree within 4% of 1 − q (a real dominant mode μ = q, which the Perron–Frobenius vector of the
///   monotone Thurston map shows at every vertex), and if q is clearly outside the circle
///   |μ| = √(ω − 1) (q > μ + (1 − μ)/4; inside it every q ≠ μ would give λ > ρ and ratchet ρ to 1), the
///   Jacobi eigenvalue behind it is λ = (q² + ω − 1) / (ω q), and ρ ← max(ρ, λ).
/// - local_superstep: when two successive q ∈ (0, 1) agree as above, jumps to f + min(50, q/(1−q)) d_k
///   (the rest of the geometric series at this vertex), then forgets its history.
///
/// Safeguard: a value outside [f/2, 2f] (or not finite) is replaced by f, the plain update, and the
/// history is cleared; after 20 such restarts the vertex stays plain for good, so the iteration ends as
/// Thurston's, which converges.
class LocalAccelerator {
public:
  /// The state of a vertex that has not updated yet; `kind` not local or `plain`: `next` returns f.
  explicit LocalAccelerator(Acceleration kind = Acceleration::plain) : kind_(kind) {}
  /// The vertex's next radius. Pre: h and f finite and positive. Post: in [f/2, 2f].
  double next(double h, double f);
  /// Whether the last `next` extrapolated (returned something else than f).
  bool accelerated() const { return accelerated_; }
  /// The current estimate of the Jacobi map's spectral radius (chebyshev; 0 otherwise).
  double rho() const { return rho_; }
  /// Safeguard restarts so far.
  int restarts() const { return restarts_; }

private:
  bool stable_ratio(double d, double& q);
  Acceleration kind_;
  double previous_ = 0;  // h_{k−1} (chebyshev), valid if has_previous_
  bool has_previous_ = false;
  static constexpr int window = 5;  // residuals per ratio estimate
  double history_[window] = {};  // d_k, d_{k−1}, …; the first seen_ are valid
  int seen_ = 0;
  double last_q_ = 0;    // the last ratio; valid if has_q_
  bool has_q_ = false;
  int stable_ = 0;       // successive ratios agreeing with the one before
  double rho_ = 0;
  double omega_ = 1;
  int restarts_ = 0;
  bool accelerated_ = false;
};

}  // namespace laguerre::core
