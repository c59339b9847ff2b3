#pragma once
/// @file
/// Greedy power embeddings: Thurston's iteration stopped by LPD/GLPD, exact packing or angle error.

#include <cstdint>
#include <string_view>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/packing/Accelerator.hpp"
#include "laguerre/core/packing/Layout.hpp"
#include "laguerre/core/packing/Newton.hpp"
#include "laguerre/core/packing/RadiusOnly.hpp"
#include "laguerre/core/packing/Thurston.hpp"
#include "laguerre/core/power/LocalPowerDiagram.hpp"

namespace laguerre::core {

/// Which condition ends the iteration.
enum class StopRule {
  lpd,    ///< LPD (triangulations) / GLPD (3-connected graphs) at every vertex: a greedy embedding
  exact,  ///< the thesis's exact packing: every edge's tangency error ≤ tolerance × smaller radius
  angle,  ///< every interior angle sum within `angle_epsilon` of 2π
  cap     ///< only the iteration cap
};

/// Name of a stopping rule ("lpd", "exact", "angle", "cap").
std::string_view to_string(StopRule rule);
/// Parses a stopping rule name; throws InputError listing the valid names (PackingNames.hpp).
StopRule parse_stop_rule(std::string_view name);

/// Name of a termination test ("layout", "radius-only").
std::string_view to_string(Termination t);
/// Parses a termination test name; throws InputError listing the valid names (PackingNames.hpp).
Termination parse_termination(std::string_view name);

/// How a packing run ended.
enum class PackStatus {
  converged,      ///< the stopping rule holds
  iteration_cap,  ///< `max_iterations` sweeps without the rule holding
  time_limit,     ///< `PackOptions::time_limit` seconds passed without the rule holding
  precision_loss  ///< the final layout is collapsed or unrepresentable in doubles (Precision): nothing is
                  ///< claimed, whatever the exact checks said on the stored numbers. Such layouts met
                  ///< mid-run are not checked and do not end the run (PackResult::skipped_checks)
};

/// Name of a status.
std::string_view to_string(PackStatus status);

/// Parameters of a packing run.
struct PackOptions {
  StopRule stop = StopRule::lpd;                 ///< the stopping rule
  Sweep sweep = Sweep::jacobi;                   ///< update order
  UpdateRule update = UpdateRule::uniform_neighbour;  ///< per-vertex update
  RootRule root = RootRule::deepest;             ///< layout root
  int steps_per_check = 1;                       ///< N ≥ 1 (precondition): sweeps between two layouts and checks
  int max_iterations = 100000;                   ///< cap on sweeps
  double angle_epsilon = 1e-9;                   ///< for StopRule::angle (radians)
  double tangency_tolerance = 0.01;              ///< for StopRule::exact (fraction of smaller radius)
  bool track_all = false;                        ///< evaluate every rule at every check (for tables)
  Acceleration acceleration = Acceleration::plain;  ///< sweep acceleration (see Accelerator)
  NewtonSolver newton_solver = NewtonSolver::cholesky;  ///< linear solver of Acceleration::newton
  Termination termination = Termination::layout;  ///< for StopRule::lpd: see Termination
  double radius_only_gap = 1e-2;                  ///< the radius-only gate's initial closing gap (radians);
                                                  ///< at most 1e-8 for binary128 layouts under Newton (refined radii)
  LayoutMethod layout_method = LayoutMethod::wave;   ///< placements of the checks' layouts (wave: the network's)
  LayoutArithmetic layout_arithmetic = LayoutArithmetic::binary64;  ///< arithmetic of the checks' layouts
  double time_limit = 0;  ///< > 0: wall seconds after which the run stops, tested after every sweep or Newton
                          ///< step (a step in progress is finished); the current radii are then laid out and
                          ///< checked like at the cap, and the run ends PackStatus::time_limit unless the rule holds
};

/// Wall seconds of a packing run by phase (`PackResult::phase_seconds`).
struct PackPhaseSeconds {
  double setup = 0;        ///< the packing complex, initial radii and root
  double sweeps = 0;       ///< Thurston sweeps and accelerators, Newton–Krylov steps, Newton's fall-back sweeps
  double jacobian = 0;     ///< Acceleration::newton: assembling the Jacobian
  double solve = 0;        ///< Acceleration::newton: factorizing and solving (or CG)
  double line_search = 0;  ///< Acceleration::newton: the residuals before each step and of the damped trials
  double layout = 0;       ///< the checks' layouts
  double checks = 0;       ///< LPD/GLPD, tangency and angle checks, the radius-only gate
  double final = 0;        ///< statistics after the run (the LPD count and tangency error of the final layout)
};

/// Result of a packing run.
struct PackResult {
  PackStatus status = PackStatus::iteration_cap;  ///< how it ended
  StopRule rule = StopRule::lpd;                  ///< the rule that was asked for
  int iterations = 0;                             ///< sweeps performed
  int first_lpd = -1;       ///< first checked iteration with LPD/GLPD everywhere (-1: never seen)
  int first_exact = -1;     ///< first checked iteration with an exact packing (tracked rules only)
  int first_angle = -1;     ///< first checked iteration with angle error ≤ epsilon (tracked only)
  int jumps = 0;            ///< accelerated steps taken (PackOptions::acceleration; Newton: improving Newton steps; local kinds: extrapolated vertex updates)
  long long linear_iterations = 0;  ///< Acceleration::newton_krylov: CG iterations over all Newton steps
  long long exchanges = 0;   ///< Acceleration::newton_krylov: neighbour exchanges (radius, CG, line search)
  long long tree_sums = 0;   ///< Acceleration::newton_krylov: sums over the layout tree
  double angle_error = 0;   ///< max |θ − 2π| at the end
  double max_tangency_error = 0;  ///< max tangency error over G's edges at the end
  CircleEmbedding circles;        ///< φ on G's vertices (indexed by Vertex of G), in doubles
  CircleEmbedding128 circles128;  ///< φ on G's vertices in binary128 when the layout keeps them
                                  ///< (LayoutArithmetic::binary128; empty otherwise): then LPD/GLPD, the
                                  ///< tangency errors and the precision status are decided on these
  CircleEmbedding face_circles;   ///< circles of the face vertices (3-connected graphs), per face vertex
  std::vector<LocalCondition> local;  ///< LPD/GLPD outcome per vertex of G at the end
  std::size_t local_ok = 0;           ///< number of vertices where it holds
  int layouts = 0;                    ///< layouts computed by the checks (one per check unless radius-only)
  int skipped_checks = 0;  ///< mid-run layouts left unchecked because they were collapsed or unrepresentable
                           ///< (Precision): no LPD/GLPD or exact-packing decision on them; the final layout is
                           ///< always checked
  int decision_step = 0;  ///< sweeps computed when the run stopped (iterations + D with Termination::radius_flood)
  int flood_depth = 0;    ///< Termination::radius_flood: D, the steps from a test to its decision (0 otherwise)
  PackPhaseSeconds phase_seconds;     ///< where the run's wall time went
  Layout layout;                      ///< the final layout of the whole complex
  Radii radii;                        ///< final hyperbolic radius h per vertex of the complex (∞ on the boundary)
};

/// Observer of a packing run (Boost.Graph-style visitor); the default does nothing.
class PackVisitor {
public:
  virtual ~PackVisitor() = default;
  /// After each checked iteration: iteration count, angle error, vertices satisfying LPD/GLPD.
  virtual void on_check(int /*iteration*/, double /*angle_error*/, std::size_t /*local_ok*/) {}
  /// After each checked iteration's layout, before `on_check` or `on_unchecked`.
  virtual void on_layout(int /*iteration*/, const Layout& /*layout*/) {}
  /// Instead of `on_check` when a mid-run layout is collapsed or unrepresentable (`precision`): its
  /// coordinates are not checked (PackResult::skipped_checks).
  virtual void on_unchecked(int /*iteration*/, double /*angle_error*/, Precision /*precision*/) {}
};

/// Computes a greedy power embedding of G (a triangulated disc or a 3-connected planar graph whose
/// outer face is set) by the algorithm of thesis §5.3.1: horocycles on the boundary, radius 1 inside,
/// then repeat {N Thurston sweeps; layout; check} until the stopping rule holds.
PackResult pack(const PlanarGraph& g, const PackOptions& options = {}, PackVisitor* visitor = nullptr);

/// Largest tangency error over the edges of G in a layout (see tangency_error).
double max_tangency_error(const PlanarGraph& g, const CircleEmbedding& circles);
/// max_tangency_error on binary128 circles.
double max_tangency_error(const PlanarGraph& g, const CircleEmbedding128& circles);

}  // namespace laguerre::core
