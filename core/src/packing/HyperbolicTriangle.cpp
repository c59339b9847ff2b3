#include "laguerre/core/packing/HyperbolicTriangle.hpp"

#include "../detail/HyperbolicTriangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace laguerre::core {

namespace {
detail::LiftT<double> as_t(Lift l) { return {l.x, l.xbar}; }
}  // namespace

Lift lift(double h) {
  const auto l = detail::lift_t(h);
  return {l.x, l.xbar};
}

double tangent_angle(Lift x, Lift y, Lift z) { return detail::tangent_angle_t(as_t(x), as_t(y), as_t(z)); }

double overlap_angle(Lift x, Lift y, Lift z, double cxy, double cxz, double cyz) {
  return detail::overlap_angle_t(as_t(x), as_t(y), as_t(z), cxy, cxz, cyz);
}

double uniform_neighbour_update(double h, double theta, int k) {
  const Lift l = lift(h);
  const double t = std::sqrt(l.x);
  // Common neighbour value U with k·tangent_angle(h, U, U) = θ: sin(θ/2k) = β = √X Ū / (1 − XU), so
  //   Ū = 1 − U = β X̄ / (√X (1 − β√X)),  1 − β√X = (1 − β) + β X̄ / (1 + √X),
  // and 1 − β = 2 sin²((kπ − θ) / 4k) has no cancellation when θ is close to kπ (a vanishing circle).
  const double pi = std::numbers::pi;
  const double phi = std::min(theta / (2 * k), pi / 2);
  const double beta = std::sin(phi);
  const double half_gap = std::sin(std::max(0.0, pi / 2 - phi) / 2);
  const double one_minus_beta_t = 2 * half_gap * half_gap + beta * l.xbar / (1 + t);
  double ubar = t > 0 ? beta * l.xbar / (t * one_minus_beta_t) : 1.0;
  ubar = std::clamp(ubar, std::numeric_limits<double>::min(), 1.0);
  const double u = 1 - ubar;
  // t' = √X' solves δU t'² + Ū t' − δ = 0 with δ = sin(π/k): t' = 2δ / (Ū + S), S = √(Ū² + 4δ²U),
  // and 1 − t' = Ū (S + 2δ + Ū − 4δ²) / ((S + 2δ)(Ū + S)), where S + 2δ − 4δ² ≥ 4δ(1 − δ) > 0.
  const double delta = std::sin(pi / k);
  const double s = std::sqrt(ubar * ubar + 4 * delta * delta * u);
  const double tp = 2 * delta / (ubar + s);
  if (tp < 0.5) return -std::log(tp);
  const double w = ubar * (s + 2 * delta + ubar - 4 * delta * delta) / ((s + 2 * delta) * (ubar + s));
  return -std::log1p(-w);
}

double radius_of(double X) {
  return X <= 0 ? std::numeric_limits<double>::infinity() : -0.5 * std::log(X);
}

double x_of_radius(double h) { return std::isinf(h) ? 0.0 : std::exp(-2 * h); }

}  // namespace laguerre::core
