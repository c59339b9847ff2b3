#pragma once
/// @file
/// Newton–Krylov steps on the angle sums as a network computes them (Acceleration::newton_krylov):
/// Newton's system −J δu = θ − 2π (u = log tanh(h/2), −J symmetric positive definite, Newton.hpp)
/// solved by conjugate gradients with the Jacobi preconditioner, where each CG iteration is one
/// neighbour exchange plus one sum over the layout tree, and the step is damped as NewtonMethod does
/// (at most a factor e² per radius, halved until ‖θ − 2π‖₂ decreases, else a plain Thurston sweep).
///
/// Three pieces, shared by core::pack (the centralized reference, `NewtonKrylovMethod`) and the
/// distributed protocol (one `KrylovVertex` per protocol vertex, `KrylovRoot` at the tree's root), so
/// that both perform the same floating-point operations in the same order:
///  - KrylovVertex: what an interior vertex computes from its own values and its neighbours';
///  - tree sums: a vertex's partial is its own KrylovSums, then each child's partial `combine`d in the
///    vertex's neighbour order (counter-clockwise from core's first dart); the root's is the total;
///  - KrylovRoot: the scalar decisions (CG coefficients, stop, step length, accept) from the totals,
///    broadcast down the tree as a KrylovDecision.
/// docs/protocol.md ("Newton–Krylov in the network") gives the message schedule.

#include <cstdint>
#include <vector>

#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// What one vertex contributes to a tree sum: three sums and a maximum.
struct KrylovSums {
  double sum[3] = {0, 0, 0};  ///< summed up the tree
  double max = 0;             ///< maximum up the tree
};

/// Adds a child's partial to `into` (sums added in index order, max taken).
void combine(KrylovSums& into, const KrylovSums& child);

/// What the root decides after a tree sum (the next thing every vertex does).
enum class KrylovAction : std::uint8_t {
  iterate = 0,  ///< CG update with a = α, b = β, then exchange z and sum again
  solved = 1,   ///< CG done: sum the maximum of the direction |δs|
  trial = 2,    ///< try radii h·e^{t δs}, t = a: exchange them and sum ‖θ − 2π‖²
  accept = 3,   ///< keep the trial radii: the Newton step is done
  reject = 4    ///< no improving step: a plain Thurston update instead
};

/// The root's decision, broadcast down the tree.
struct KrylovDecision {
  KrylovAction action = KrylovAction::reject;  ///< what to do
  double a = 0;  ///< α (iterate) or t (trial)
  double b = 0;  ///< β (iterate)
};

/// Limits of a Newton–Krylov step.
struct KrylovLimits {
  static constexpr int max_cg = 5000;       ///< CG iterations per Newton step
  static constexpr int max_halvings = 40;   ///< step halvings of the line search
  static constexpr double max_forcing = 0.9;  ///< CG stops at ‖r‖ ≤ clamp(‖θ − 2π‖₂, 1e-14, this)·‖θ − 2π‖₂
};

/// The root's scalar state through one Newton step (Chronopoulos–Gear CG: one sum per iteration).
class KrylovRoot {
public:
  /// Forgets the previous Newton step.
  void reset() { *this = KrylovRoot{}; }
  /// The decision after a tree sum whose total is `total`.
  KrylovDecision decide(const KrylovSums& total);
  /// CG iterations so far in this Newton step.
  int cg_iterations() const { return iterations_; }

private:
  enum class Stage : std::uint8_t { cg, direction, trial };
  Stage stage_ = Stage::cg;
  int iterations_ = 0, halvings_ = 0;
  double norm0_ = 0, tol2_ = 0, gamma_ = 0, alpha_ = 0, t_ = 0;
};

/// One interior vertex's part of a Newton–Krylov step.
class KrylovVertex {
public:
  /// Starts a Newton step at radius `h` with the star `s` (neighbour radii of this step): θ − 2π and
  /// this vertex's row of A = −∂θ/∂u; CG starts at x = 0, r = θ − 2π, z = r / A_vv.
  void begin(double h, const StarView& s);
  /// The value this vertex sends its neighbours for the next sum: z (CG) or its trial radius.
  double value() const { return trial_mode_ ? trial_ : z_; }
  /// CG: w = A z from the neighbours' z (0 for boundary neighbours); returns (r·z, z·w, r·r; 0).
  KrylovSums cg_sums(const std::vector<double>& neighbour_z);
  /// The direction δs = δu · sinh h / h; returns (0, 0, 0; |δs|, ∞ if not finite).
  KrylovSums direction_sums();
  /// The line search at the trial radii (neighbours' in `trial_star`): ((θ − 2π)², 0, 0; |θ − 2π|).
  KrylovSums trial_sums(const StarView& trial_star) const;
  /// Applies the root's decision (iterate: CG update; trial: the trial radius). Returns the new radius
  /// for accept (the trial radius) and reject (`plain`, the plain update), else the current one.
  double apply(const KrylovDecision& d, double plain);

private:
  double h_ = 0, diag_ = 0;
  std::vector<double> off_;  // A_vj per neighbour (counter-clockwise), 0 for boundary neighbours
  double x_ = 0, r_ = 0, z_ = 0, p_ = 0, s_ = 0, w_ = 0, delta_ = 0, trial_ = 0;
  bool trial_mode_ = false;
};

/// What one Newton–Krylov step did (centralized reference).
struct KrylovStep {
  bool improved = false;  ///< the Newton step was accepted (else a plain sweep was taken)
  int cg_iterations = 0;  ///< CG iterations
  int trials = 0;         ///< line-search trials
  int exchanges = 0;      ///< neighbour exchanges: the radius exchange, one per CG sum, one per trial
  int sums = 0;           ///< tree sums (convergecast + broadcast)
};

/// The centralized reference: the distributed step, vertex by vertex, with the tree sums of `tree`
/// (a layout of k: its parent and wave arrays).
class NewtonKrylovMethod {
public:
  /// One step on the interior radii `h` (Jacobi plain update on rejection, with `rule`).
  KrylovStep step(const PackingComplex& k, Radii& h, const Layout& tree, UpdateRule rule);

private:
  KrylovSums reduce(const PackingComplex& k, const Layout& tree);
  std::vector<KrylovVertex> vertices_;
  std::vector<KrylovSums> own_;
  std::vector<Vertex> order_;  // children before parents
  KrylovRoot root_;
};

}  // namespace laguerre::core
