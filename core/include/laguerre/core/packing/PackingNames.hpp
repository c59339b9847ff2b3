#pragma once
/// @file
/// The names of the packing enums (EnumNames.hpp): the spellings of the command line, the scenario
/// files and the JSON outputs.

#include "laguerre/core/EnumNames.hpp"
#include "laguerre/core/packing/Packer.hpp"

namespace laguerre::core {

/// Acceleration: plain, superstep, anderson, newton, chebyshev, local-superstep, newton-krylov.
inline constexpr EnumNames<Acceleration, 7> acceleration_names{{{Acceleration::plain, "plain"},
                                                                {Acceleration::superstep, "superstep"},
                                                                {Acceleration::anderson, "anderson"},
                                                                {Acceleration::newton, "newton"},
                                                                {Acceleration::chebyshev, "chebyshev"},
                                                                {Acceleration::local_superstep, "local-superstep"},
                                                                {Acceleration::newton_krylov, "newton-krylov"}}};
/// StopRule: lpd, exact, angle, cap.
inline constexpr EnumNames<StopRule, 4> stop_rule_names{
    {{StopRule::lpd, "lpd"}, {StopRule::exact, "exact"}, {StopRule::angle, "angle"}, {StopRule::cap, "cap"}}};
/// Termination: layout, radius-only.
inline constexpr EnumNames<Termination, 3> termination_names{
    {{Termination::layout, "layout"}, {Termination::radius_only, "radius-only"}, {Termination::radius_flood, "radius-flood"}}};
/// Sweep: jacobi, gauss-seidel.
inline constexpr EnumNames<Sweep, 2> sweep_names{{{Sweep::jacobi, "jacobi"}, {Sweep::gauss_seidel, "gauss-seidel"}}};
/// RootRule: deepest, smallest-id.
inline constexpr EnumNames<RootRule, 2> root_rule_names{
    {{RootRule::deepest, "deepest"}, {RootRule::smallest_id, "smallest-id"}}};
/// NewtonSolver: lu, cholesky, pcg.
inline constexpr EnumNames<NewtonSolver, 3> newton_solver_names{
    {{NewtonSolver::lu, "lu"}, {NewtonSolver::cholesky, "cholesky"}, {NewtonSolver::pcg, "pcg"}}};
/// LayoutMethod: wave, frames.
inline constexpr EnumNames<LayoutMethod, 2> layout_method_names{
    {{LayoutMethod::wave, "wave"}, {LayoutMethod::frames, "frames"}}};
/// LayoutArithmetic: binary64, binary128.
inline constexpr EnumNames<LayoutArithmetic, 3> layout_arithmetic_names{
    {{LayoutArithmetic::binary64, "binary64"}, {LayoutArithmetic::binary128, "binary128"}, {LayoutArithmetic::mixed, "mixed"}}};
/// Precision: ok, degraded, collapsed, unrepresentable.
inline constexpr EnumNames<Precision, 4> precision_names{{{Precision::ok, "ok"},
                                                          {Precision::degraded, "degraded"},
                                                          {Precision::collapsed, "collapsed"},
                                                          {Precision::unrepresentable, "unrepresentable"}}};

}  // namespace laguerre::core
