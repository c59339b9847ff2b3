#pragma once
/// @file
/// Damped Newton's method on the angle sums: a centralized solver for large packings.
///
/// Thurston's iteration converges linearly with a rate that degrades with the depth of the graph:
/// on uniform random maps of 5000 vertices, whose small cuts enclose circles of hyperbolic radius
/// 10^-10, plain Jacobi sweeps still have angle errors of 3·10^-3 after 10^4 sweeps and Anderson
/// mixing oscillates. Newton's method solves θ(v) = 2π for all interior v at once: in the variables
/// s = log h of the interior vertices it solves J δ = 2π − θ with J = ∂θ/∂s, the sparse Jacobian
/// (one row per interior vertex, non-zeros on its star), by sparse LU; then it halves the step until
/// the largest angle error decreases (a damped step that can never make things worse). Near the
/// solution convergence is quadratic, so 10–30 steps reach rounding level.
///
/// J is assembled per triangle corner by central differences in s (step 10^-5; the truncation error
/// 10^-10 of a derivative only slows the final quadratic phase, it cannot move the solution, which is
/// the zero of the exactly evaluated θ). This is not what a network computes: it is a centralized
/// shortcut for routing experiments on networks too large to iterate (`protocol.mode: central`).

#include <cstddef>

#include "laguerre/core/packing/PackingComplex.hpp"
#include "laguerre/core/packing/Thurston.hpp"

namespace laguerre::core {

/// Outcome of one Newton step.
struct NewtonStep {
  bool improved = false;     ///< whether the step decreased the largest angle error
  double error_before = 0;   ///< max |θ − 2π| before the step
  double error_after = 0;    ///< max |θ − 2π| after (equal to before when !improved)
  int halvings = 0;          ///< step halvings of the line search
};

/// One damped Newton step on the interior radii `h` (changed in place only when it improves).
NewtonStep newton_step(const PackingComplex& k, Radii& h);

}  // namespace laguerre::core
