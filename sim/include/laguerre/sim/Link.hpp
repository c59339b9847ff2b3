#pragma once
/// @file
/// Link models: latency (constant, uniform, distance-based), loss and duplication, and the decision
/// they make for one message given that message's own random stream.
///
/// Reordering is not a separate knob: it arises whenever latency is random (two messages on the same
/// link may overtake each other), exactly as on a real radio channel with variable queueing delay.

#include <cstdint>

#include "laguerre/sim/Random.hpp"
#include "laguerre/sim/Time.hpp"

namespace laguerre::sim {

/// Which latency law a LatencyModel follows.
enum class LatencyKind {
  constant,  ///< always `base`
  uniform,   ///< uniform integer in [base, base + spread]
  distance,  ///< base + round(per_unit · |p(u) − p(v)|) + uniform integer in [0, spread]
};

/// A latency law, in nanoseconds. Build it with the named constructors.
struct LatencyModel {
  LatencyKind kind = LatencyKind::constant;  ///< the law
  Duration base = milliseconds(1);           ///< constant value, lower bound, or intercept
  Duration spread = 0;                       ///< width of the uniform part (uniform, distance jitter)
  double per_unit = 0;                       ///< distance law: nanoseconds per unit of distance

  /// Always `latency`.
  static LatencyModel constant(Duration latency);
  /// Uniform integer in [lo, hi].
  static LatencyModel uniform(Duration lo, Duration hi);
  /// Affine in the Euclidean distance between the endpoints' positions, plus a uniform jitter in
  /// [0, jitter]: base + round(ns_per_unit · distance) + jitter.
  static LatencyModel distance(Duration base, double ns_per_unit, Duration jitter = 0);

  /// Throws core::InternalError (a broken precondition) (a full sentence) for negative or non-finite parameters.
  void validate() const;
  /// The smallest latency this law can produce for endpoints at distance `d`.
  Duration min_latency(double d) const;
  /// The largest latency this law can produce for endpoints at distance `d`.
  Duration max_latency(double d) const;
  /// Draws one latency for endpoints at distance `d`.
  Duration draw(double d, RandomStream& rng) const;
};

/// How one directed link treats messages.
struct LinkModel {
  LatencyModel latency;      ///< per-copy latency law
  double loss = 0;           ///< probability that a copy is lost, in [0, 1]
  double duplication = 0;    ///< probability that a message is sent twice, in [0, 1]

  /// Throws core::InternalError (a broken precondition) (a full sentence) for probabilities outside [0, 1] or a bad latency.
  void validate() const;
  /// Whether every message gets the same fate, whatever its random stream: a constant latency, no
  /// loss, no duplication (`decide` then returns {false, latency.base, false, …} for any stream).
  bool is_deterministic() const {
    return latency.kind == LatencyKind::constant && loss == 0 && duplication == 0;
  }
};

/// The fate of one message on a link: up to two copies, each lost or delivered after a latency.
struct LinkDecision {
  bool lost = false;           ///< the original copy is lost
  Duration latency = 0;        ///< its latency (drawn even when lost, to keep the draw count fixed)
  bool duplicated = false;     ///< a second copy exists
  bool duplicate_lost = false; ///< the second copy is lost
  Duration duplicate_latency = 0;  ///< its latency
};

/// Decides the fate of one message at distance `d` from the message's own stream. Draw order (fixed):
/// loss, latency, duplication, then for a duplicate its loss and latency.
LinkDecision decide(const LinkModel& model, double d, RandomStream& rng);

}  // namespace laguerre::sim
