#pragma once
/// @file
/// Damped Newton's method on the angle sums: a centralized solver for large packings.
///
/// Thurston's iteration converges linearly with a rate that degrades with the depth of the graph:
/// on uniform random maps of 5000 vertices, whose small cuts enclose circles of hyperbolic radius
/// 10^-10, plain Jacobi sweeps still have angle errors of 3·10^-3 after 10^4 sweeps and Anderson
/// mixing oscillates. Newton's method solves θ(v) = 2π for all interior v at once, then halves the
/// step until ‖θ − 2π‖₂ decreases (a damped step that can never make things worse). Near the
/// solution convergence is quadratic, so 10–30 steps reach rounding level.
///
/// In the variable u = log tanh(h/2) (u < 0, horocycles at u = 0) the Jacobian J = ∂θ/∂u of the
/// interior angle sums is symmetric negative definite: it is the Hessian of a strictly concave
/// packing functional (Colin de Verdière 1991; Chow–Luo 2003 for intersection angles in [0, π/2]).
/// The derivation, with the closed forms used to assemble J, is in Newton.cpp. So the Newton system
/// −J δu = θ − 2π is solved by a method made for symmetric positive definite systems (`NewtonSolver`);
/// the step is then taken in s = log h along the same direction (δs = δu · sinh h / h).
///
/// This is not what a network computes: it is a centralized shortcut for routing experiments on
/// networks too large to iterate (`protocol.mode: central`).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// How the linear system of a Newton step is solved.
enum class NewtonSolver {
  lu,        ///< J = ∂θ/∂(log h) by central differences, Eigen's sparse LU (COLAMD): the original path
  cholesky,  ///< −∂θ/∂u assembled in closed form, sparse Cholesky: CHOLMOD supernodal when the build
             ///< has it (`cholesky_backend()`), else Eigen's SimplicialLDLT (AMD ordering)
  pcg        ///< −∂θ/∂u, conjugate gradients preconditioned by incomplete Cholesky (Eigen), relative
             ///< residual min(10^-4, ‖θ − 2π‖₂) (inexact Newton), at most 5000 iterations
};

/// Which library `NewtonSolver::cholesky` uses in this build: "cholmod" or "eigen-ldlt".
std::string_view cholesky_backend();

/// Outcome of one Newton step.
struct NewtonStep {
  bool improved = false;     ///< whether the step decreased ‖θ − 2π‖₂
  double error_before = 0;   ///< max |θ − 2π| before the step
  double error_after = 0;    ///< max |θ − 2π| after (equal to before when !improved)
  int halvings = 0;          ///< step halvings of the line search
  int linear_iterations = 0; ///< conjugate-gradient iterations (NewtonSolver::pcg; 0 otherwise)
  double jacobian_seconds = 0;     ///< wall seconds assembling the Jacobian (closed form, or differences for lu)
  double solve_seconds = 0;        ///< wall seconds factorizing and solving (CHOLMOD/LDLT, SparseLU, or CG)
  double line_search_seconds = 0;  ///< wall seconds of the residuals: the one before the step and the damped trials
};

/// Damped Newton steps with one linear solver. The object keeps what does not change between the
/// steps of one complex (interior numbering, sparsity pattern, the solver's symbolic analysis); it
/// may be used on another complex (it then starts over).
class NewtonMethod {
public:
  explicit NewtonMethod(NewtonSolver solver = NewtonSolver::cholesky);
  ~NewtonMethod();
  NewtonMethod(const NewtonMethod&) = delete;
  NewtonMethod& operator=(const NewtonMethod&) = delete;

  /// One damped Newton step on the interior radii `h` (changed in place only when it improves).
  /// A solver failure (factorization or non-finite direction) is a step that does not improve.
  NewtonStep step(const PackingComplex& k, Radii& h);

  /// `h` refined in binary128 (mixed-precision iterative refinement): up to `iterations` Newton
  /// corrections, each from the angle residuals evaluated in binary128 (angle_residuals128), solved
  /// with the Jacobian at `h` factorized in doubles (sparse Cholesky) and applied in binary128; stops
  /// once max |θ − 2π| ≤ `tolerance` (or a solve fails). Boundary entries stay ∞. For layouts whose
  /// deep tiny circles amplify the doubles' 10^-15 rad of flower closure (docs/precision.md).
  /// `angle_error`, when given, receives max |θ − 2π| of the returned radii (evaluated in binary128).
  Radii128 refine128(const PackingComplex& k, const Radii& h, double* angle_error = nullptr, int iterations = 4,
                     double tolerance = 1e-30);

private:
  void bind(const PackingComplex& k);
  struct State;
  // The step itself; `phase(p)` is called when it enters assembly (0), solve (1), line search (2).
  void step_in(const PackingComplex& k, Radii& h, NewtonStep& out, const std::function<void(int)>& phase);
  NewtonSolver solver_;
  std::unique_ptr<State> state_;
};

/// One damped Newton step on the interior radii `h` (a fresh NewtonMethod with `solver`).
NewtonStep newton_step(const PackingComplex& k, Radii& h, NewtonSolver solver = NewtonSolver::cholesky);

/// u = log tanh(h/2) ∈ (−∞, 0] with full relative precision for small and large h (0 for h = ∞).
double u_of_radius(double h);
/// The inverse of u_of_radius: h = log((1 + e^u) / (1 − e^u)) (∞ for u = 0).
double radius_of_u(double u);

/// One entry of a sparse matrix indexed by interior-vertex rows.
struct SparseEntry {
  std::uint32_t row = 0;  ///< row (index into `AngleJacobian::interior`)
  std::uint32_t col = 0;  ///< column (same numbering)
  double value = 0;       ///< value
};

/// J = ∂θ/∂u on the interior vertices, assembled in closed form.
struct AngleJacobian {
  std::vector<Vertex> interior;      ///< the interior vertices, in row order (increasing Vertex)
  std::vector<SparseEntry> entries;  ///< each (row, col) at most once, rows increasing, columns increasing within a row
};

/// The Jacobian of the interior angle sums in u = log tanh(h/2) at radii `h` (interior radii finite).
/// Postcondition: symmetric with negative diagonal and positive or zero off-diagonal entries, every
/// row sum strictly negative up to rounding, so −J is symmetric positive definite (Newton.cpp).
AngleJacobian angle_jacobian(const PackingComplex& k, const Radii& h);

/// Row v of J = ∂θ/∂u in node-local form: returns ∂θ_v/∂u_v and sets `off[i]` = ∂θ_v/∂u of neighbour
/// i of the star (0 for a horocycle), summing the corners around v from neighbour 0. The same closed
/// forms as angle_jacobian (equal up to rounding: the order of the sums differs).
double star_jacobian_row(double hv, const StarView& s, std::vector<double>& off);

}  // namespace laguerre::core
