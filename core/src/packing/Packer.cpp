#include "laguerre/core/packing/Packer.hpp"

#include "laguerre/core/Error.hpp"
#include "laguerre/core/packing/Accelerator.hpp"
#include "laguerre/core/packing/Newton.hpp"
#include "laguerre/core/packing/NewtonKrylov.hpp"
#include "laguerre/core/packing/PackingNames.hpp"
#include "laguerre/core/packing/RadiusOnly.hpp"

#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

namespace laguerre::core {

std::string_view to_string(StopRule rule) { return name_of(stop_rule_names, rule); }

StopRule parse_stop_rule(std::string_view name) { return parse_name(stop_rule_names, name); }

std::string_view to_string(Termination t) { return name_of(termination_names, t); }

Termination parse_termination(std::string_view name) { return parse_name(termination_names, name); }

std::string_view to_string(PackStatus status) {
  switch (status) {
    case PackStatus::converged: return "converged";
    case PackStatus::iteration_cap: return "iteration_cap";
    case PackStatus::time_limit: return "time_limit";
    case PackStatus::precision_loss: return "precision_loss";
  }
  return "?";
}

namespace {
template <class Embedding>
double max_tangency_error_t(const PlanarGraph& g, const Embedding& circles) {
  double err = 0;
  for (Dart d = 0; d < g.num_darts(); ++d)
    if (g.tail(d) < g.head(d)) {
      const double e = tangency_error(circles, g.tail(d), g.head(d));
      if (std::isnan(e)) return std::numeric_limits<double>::infinity();  // never "within tolerance"
      err = std::max(err, e);
    }
  return err;
}
}  // namespace

double max_tangency_error(const PlanarGraph& g, const CircleEmbedding& circles) { return max_tangency_error_t(g, circles); }
double max_tangency_error(const PlanarGraph& g, const CircleEmbedding128& circles) {
  return max_tangency_error_t(g, circles);
}

PackResult pack(const PlanarGraph& g, const PackOptions& options, PackVisitor* visitor) {
  LAGUERRE_PRECONDITION(options.steps_per_check >= 1, "steps_per_check must be at least 1.");
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  Clock::time_point mark = start;
  PackResult result;
  PackPhaseSeconds& phases = result.phase_seconds;
  auto lap = [&](double& phase) {  // adds the wall time since the previous lap to `phase`
    const Clock::time_point now = Clock::now();
    phase += std::chrono::duration<double>(now - mark).count();
    mark = now;
  };
  // The time limit is tested between steps: a run stops after the step in progress, then its final
  // layout and check are made as at the cap.
  bool timed_out = false;
  // max |θ − 2π| of result.radii when a Newton step just computed it (its accepted trial), else NaN:
  // the check then need not evaluate the angle sums again (the same function of the same radii).
  double known_angle_error = std::numeric_limits<double>::quiet_NaN();
  auto out_of_time = [&] {
    if (options.time_limit > 0 && std::chrono::duration<double>(Clock::now() - start).count() >= options.time_limit)
      timed_out = true;
    return timed_out;
  };
  const PackingComplex k = PackingComplex::from_graph(g);
  result.rule = options.stop;
  result.radii = initial_radii(k);
  Radii scratch;
  const Vertex root = choose_root(k, options.root);
  const std::size_t n = g.num_vertices();

  // Termination::radius_only (docs/radius-only.md): the radius-only test gates the layout; the exact
  // check on the layout still decides. PackingAgent does the same, round by round.
  // The checks decide on the binary128 circles when the layout keeps them, else on the doubles.
  auto check_layout = [&] { return result.circles128.empty() ? check_all(g, result.circles) : check_all(g, result.circles128); };
  auto tangency = [&] {
    return result.circles128.empty() ? max_tangency_error(g, result.circles) : max_tangency_error(g, result.circles128);
  };
  const bool radius_only = options.termination != Termination::layout && options.stop == StopRule::lpd;
  NewtonMethod newton_method(options.newton_solver);
  const bool refine_radii =
      options.acceleration == Acceleration::newton && options.layout_arithmetic == LayoutArithmetic::binary128;
  // Refined binary128 layouts (below) start the gate at 1e-8 at most: refining radii further from
  // convergence costs several binary128 residual evaluations and rarely ends in LPD.
  double gap = options.radius_only_gap;
  if (refine_radii) gap = std::min(gap, 1e-8);
  auto lay_out_and_check = [&](int iteration, bool final) {
    // Returns whether the requested rule holds; records first occurrences of tracked rules.
    ++result.layouts;
    lap(phases.checks);  // (the radius-only gate before it)
    // Mid-run, a collapsed layout is never checked, so the LPD, exact and cap rules cannot end the run
    // on it: the wave may stop at its first collapsed circle. Not for the angle rule (decided on the
    // radii: the run may end with this layout) nor Newton–Krylov (its steps read the whole tree).
    const bool may_stop = !final && options.stop != StopRule::angle && options.acceleration != Acceleration::newton_krylov;
    // binary128 with Newton: the radii themselves refined in binary128 first, so that the flowers
    // close to ~1e-30 rad instead of the doubles' ~1e-15, which the deep tiny circles of large uniform
    // maps amplify past their size (docs/precision.md, "Where both stop").
    if (refine_radii) {
      double refined_error = 0;
      const Radii128 q = newton_method.refine128(k, result.radii, &refined_error);
      result.layout = lay_out(k, q, root, options.layout_method, may_stop);
      // The run goes on from the refined radii, rounded, and reports their angle error.
      for (Vertex v = 0; v < q.size(); ++v) result.radii[v] = static_cast<double>(q[v]);
      known_angle_error = refined_error;
    } else
      result.layout = lay_out(k, result.radii, root, options.layout_method, options.layout_arithmetic, may_stop);
    result.circles.assign(result.layout.circles.begin(), result.layout.circles.begin() + static_cast<long>(n));
    if (result.layout.circles128.empty()) result.circles128.clear();
    else result.circles128.assign(result.layout.circles128.begin(), result.layout.circles128.begin() + static_cast<long>(n));
    lap(phases.layout);
    result.angle_error = std::isnan(known_angle_error) ? angle_error(k, result.radii) : known_angle_error;
    // A collapsed or unrepresentable layout (Precision) carries no claim: mid-run (Newton's first
    // steps, an early wave) it only means "not yet", so its coordinates are not checked at all — no
    // LPD/GLPD and no exact-packing decision is taken on them, and the run goes on. The final layout
    // (the cap) is always checked; if it is collapsed the run ends precision_loss below. The angle
    // rule reads the radii only and is decided either way.
    const bool representable =
        result.layout.precision != Precision::collapsed && result.layout.precision != Precision::unrepresentable;
    const bool skip = !representable && !final;
    result.skipped_checks += skip;
    const bool want_lpd = !skip && (options.stop == StopRule::lpd || options.track_all);
    const bool want_exact = !skip && (options.stop == StopRule::exact || options.track_all);
    const bool want_angle = options.stop == StopRule::angle || options.track_all;
    bool lpd = false, exact = false, angle = false;
    if (want_lpd || (!skip && options.stop == StopRule::cap)) {
      result.local = check_layout();
      result.local_ok = 0;
      for (LocalCondition c : result.local) result.local_ok += c == LocalCondition::holds;
      lpd = result.local_ok == n;
      if (lpd && result.first_lpd < 0) result.first_lpd = iteration;
    }
    if (want_exact) {
      result.max_tangency_error = tangency();
      exact = result.max_tangency_error <= options.tangency_tolerance;
      if (exact && result.first_exact < 0) result.first_exact = iteration;
    }
    if (want_angle) {
      angle = result.angle_error <= options.angle_epsilon;
      if (angle && result.first_angle < 0) result.first_angle = iteration;
    }
    if (visitor) visitor->on_layout(iteration, result.layout);
    if (visitor && skip) visitor->on_unchecked(iteration, result.angle_error, result.layout.precision);
    if (visitor && !skip) visitor->on_check(iteration, result.angle_error, result.local_ok);
    if (radius_only && !lpd) gap /= 2;
    lap(phases.checks);
    switch (options.stop) {
      case StopRule::lpd: return lpd;
      case StopRule::exact: return exact;
      case StopRule::angle: return angle;
      case StopRule::cap: return false;
    }
    return false;
  };
  auto check = [&](int iteration) {
    // At the cap the layout is made whatever the test says: the run ends with coordinates.
    const bool final = iteration >= options.max_iterations || timed_out;
    if (radius_only && !final && !radius_only_everywhere(k, result.radii, gap)) {
      lap(phases.checks);
      return false;
    }
    return lay_out_and_check(iteration, final);
  };

  int it = 0;
  Accelerator accelerator(options.acceleration);
  const bool newton = options.acceleration == Acceleration::newton;
  const bool krylov = options.acceleration == Acceleration::newton_krylov;
  NewtonKrylovMethod krylov_method;
  const bool local = options.acceleration != Acceleration::plain && is_local(options.acceleration);
  const bool accelerate = options.acceleration != Acceleration::plain && !newton && !krylov;
  std::vector<LocalAccelerator> local_state(local ? k.graph.num_vertices() : 0, LocalAccelerator(options.acceleration));
  int local_jumps = 0;
  Radii previous;
  Layout tree;  // Newton–Krylov: the layout tree (combinatorial: every round's)
  auto sweep_once = [&] {
    known_angle_error = std::numeric_limits<double>::quiet_NaN();
    if (newton) {  // a Newton step, or a plain sweep where Newton cannot improve (rounding level)
      const NewtonStep step = newton_method.step(k, result.radii);
      phases.jacobian += step.jacobian_seconds;
      phases.solve += step.solve_seconds;
      phases.line_search += step.line_search_seconds;
      mark = Clock::now();  // the step's time is in its three phases; a fall-back sweep is a sweep
      if (step.improved) {
        known_angle_error = step.error_after;
        ++result.jumps;
        return;
      }
    }
    if (krylov) {  // the network's step: an accepted Newton step, or else a plain Jacobi update
      const KrylovStep ks = krylov_method.step(k, result.radii, tree, options.update);
      result.jumps += ks.improved;
      result.linear_iterations += ks.cg_iterations;
      result.exchanges += ks.exchanges;
      result.tree_sums += ks.sums;
      return;
    }
    if (accelerate) previous = result.radii;
    thurston_sweep(k, result.radii, options.sweep, options.update, scratch);
    if (local) {  // each vertex on its own, as a network node does (PackingAgent::advance_steps)
      for (Vertex v = 0; v < k.graph.num_vertices(); ++v)
        if (!k.graph.is_boundary(v)) {
          result.radii[v] = local_state[v].next(previous[v], result.radii[v]);
          local_jumps += local_state[v].accelerated();
        }
    } else if (accelerate) {
      accelerator.after_sweep(k, previous, result.radii);
    }
  };
  auto step_once = [&] {
    sweep_once();
    lap(phases.sweeps);
  };
  bool done = false;
  if (radius_only && options.termination == Termination::radius_flood) {
    // The gate's AND flooded on the radius exchange (docs/radius-only.md, §8): the test of a tested
    // step s is known everywhere at step s + D; the run lays out X(s) then, and goes on from X(s + D)
    // if the check fails (the pending tests, made with the old tolerance, are dropped).
    LAGUERRE_PRECONDITION(!newton && !krylov, "the flooded radius-only gate runs with Jacobi sweeps (no Newton).");
    lap(phases.setup);
    const int depth = static_cast<int>(radius_flood_depth(lay_out(k, result.radii, root)));
    lap(phases.layout);
    const int period = radius_flood_period(depth, options.steps_per_check);
    result.flood_depth = depth;
    struct Pending {
      int step;
      Radii radii;
    };
    std::deque<Pending> pending;  // the tested steps whose test held, oldest first
    int t = 0;
    while (true) {
      if (t >= options.max_iterations || (t > 0 && out_of_time())) {  // cap or time limit: the current radii are laid out
        done = lay_out_and_check(t, true);
        it = t;
        break;
      }
      if (!pending.empty() && pending.front().step + depth == t) {
        std::swap(result.radii, pending.front().radii);
        if (lay_out_and_check(pending.front().step, false)) {
          done = true;
          it = pending.front().step;
          break;
        }
        std::swap(result.radii, pending.front().radii);
        pending.clear();
      }
      if (radius_flood_tested(t, options.steps_per_check, period) && radius_only_everywhere(k, result.radii, gap))
        pending.push_back({t, result.radii});
      lap(phases.checks);
      step_once();
      ++t;
    }
    result.decision_step = t;
  } else {
    lap(phases.setup);
    done = check(0);
    if (krylov) tree = result.layout;
    while (!done && it < options.max_iterations && !timed_out) {
      const int steps = std::min(options.steps_per_check, options.max_iterations - it);
      for (int s = 0; s < steps; ++s) {
        step_once();
        ++it;
        if (out_of_time()) break;
      }
      done = check(it);  // the final check if out of time
    }
    result.decision_step = it;
  }
  result.iterations = it;
  if (!newton && !krylov) result.jumps = local ? local_jumps : accelerator.jumps();
  result.status = done ? PackStatus::converged : timed_out ? PackStatus::time_limit : PackStatus::iteration_cap;
  // Never claim anything on circles the doubles cannot carry (Layout.hpp, docs/precision.md).
  if (result.layout.precision == Precision::unrepresentable || result.layout.precision == Precision::collapsed)
    result.status = PackStatus::precision_loss;
  // Final statistics that the run may not have tracked.
  if (result.local.empty()) {
    result.local = check_layout();
    result.local_ok = 0;
    for (LocalCondition c : result.local) result.local_ok += c == LocalCondition::holds;
  }
  result.max_tangency_error = tangency();
  result.face_circles.assign(result.layout.circles.begin() + static_cast<long>(n), result.layout.circles.end());
  lap(phases.final);
  return result;
}

}  // namespace laguerre::core
