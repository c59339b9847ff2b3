#include "laguerre/sim/Link.hpp"

#include <cmath>
#include <string>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

namespace {
Duration distance_term(double per_unit, double d) {
  return static_cast<Duration>(std::llround(per_unit * d));
}
}  // namespace

LatencyModel LatencyModel::constant(Duration latency) {
  LatencyModel m{LatencyKind::constant, latency, 0, 0};
  m.validate();
  return m;
}

LatencyModel LatencyModel::uniform(Duration lo, Duration hi) {
  LAGUERRE_PRECONDITION(lo <= hi, "A uniform latency needs lo <= hi, got [" + std::to_string(lo) + ", " +
                                       std::to_string(hi) + "] ns.");
  LatencyModel m{LatencyKind::uniform, lo, hi - lo, 0};
  m.validate();
  return m;
}

LatencyModel LatencyModel::distance(Duration base, double ns_per_unit, Duration jitter) {
  LatencyModel m{LatencyKind::distance, base, jitter, ns_per_unit};
  m.validate();
  return m;
}

void LatencyModel::validate() const {
  LAGUERRE_PRECONDITION(base >= 0, "A latency cannot be negative, got " + std::to_string(base) + " ns.");
  LAGUERRE_PRECONDITION(spread >= 0, "A latency spread cannot be negative, got " + std::to_string(spread) + " ns.");
  LAGUERRE_PRECONDITION(kind != LatencyKind::constant || spread == 0, "A constant latency has no spread.");
  LAGUERRE_PRECONDITION(std::isfinite(per_unit) && per_unit >= 0,
                        "A distance-based latency needs a finite, non-negative slope (ns per unit of distance).");
}

Duration LatencyModel::min_latency(double d) const {
  return kind == LatencyKind::distance ? base + distance_term(per_unit, d) : base;
}

Duration LatencyModel::max_latency(double d) const { return min_latency(d) + spread; }

Duration LatencyModel::draw(double d, RandomStream& rng) const {
  switch (kind) {
    case LatencyKind::constant: return base;
    case LatencyKind::uniform: return rng.uniform_int(base, base + spread);
    case LatencyKind::distance:
      return base + distance_term(per_unit, d) + (spread > 0 ? rng.uniform_int(0, spread) : 0);
  }
  return base;
}

void LinkModel::validate() const {
  latency.validate();
  LAGUERRE_PRECONDITION(loss >= 0 && loss <= 1,
                        "A loss probability must lie in [0, 1], got " + std::to_string(loss) + ".");
  LAGUERRE_PRECONDITION(duplication >= 0 && duplication <= 1,
                        "A duplication probability must lie in [0, 1], got " + std::to_string(duplication) + ".");
}

LinkDecision decide(const LinkModel& model, double d, RandomStream& rng) {
  LinkDecision out;
  out.lost = rng.bernoulli(model.loss);
  out.latency = model.latency.draw(d, rng);
  out.duplicated = rng.bernoulli(model.duplication);
  if (out.duplicated) {
    out.duplicate_lost = rng.bernoulli(model.loss);
    out.duplicate_latency = model.latency.draw(d, rng);
  }
  return out;
}

}  // namespace laguerre::sim
