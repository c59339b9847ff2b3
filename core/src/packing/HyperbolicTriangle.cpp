#include "laguerre/core/packing/HyperbolicTriangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace laguerre::core {

Lift lift(double h) {
  if (std::isinf(h)) return {0.0, 1.0};
  return {std::exp(-2 * h), -std::expm1(-2 * h)};
}

double tangent_angle(Lift x, Lift y, Lift z) {
  // sin²(α/2) = X Ȳ Z̄ / D and cos²(α/2) = X̄ (X̄ + X (Ȳ + Y Z̄)) / D with D = (X̄ + X Ȳ)(X̄ + X Z̄):
  // the complement expands to X̄² + X̄X(Ȳ + Z̄ − ȲZ̄) and Ȳ + Z̄ − ȲZ̄ = 1 − YZ = Ȳ + Y Z̄, so both
  // are sums of positive terms; atan2 keeps α accurate near 0 (huge x) and near π (vanishing x).
  const double s = std::sqrt(x.x * y.xbar * z.xbar);
  const double c = std::sqrt(x.xbar * (x.xbar + x.x * (y.xbar + y.x * z.xbar)));
  return 2 * std::atan2(s, c);
}

namespace {
// Angle at x in the right triangle (x, T, o) of a G′ triangle, where o is the circle that is not
// tangent to x in the pair (x tangent to its other neighbour, o orthogonal to x), or, at a face
// circle x, either of its two tangent neighbours: atan(tanh h_o / sinh h_x) = atan2(2√X Ō, X̄(1+O)).
double right_part(Lift x, Lift o) { return std::atan2(2 * std::sqrt(x.x) * o.xbar, x.xbar * (1 + o.x)); }

// L_ab = (1+A)(1+B) + c(1−A)(1−B) = 4√(AB) cosh l_ab.
double lifted_cosh(double A, double B, double c) { return (1 + c) * (1 + A * B) + (1 - c) * (A + B); }
// L_ab² − 16AB = (L_ab − 4√(AB))(L_ab + 4√(AB)), with the first factor rewritten as
// (1+c)(1−√(AB))² + (1−c)(√A−√B)².
double lifted_sinh2(double A, double B, double c, double L) {
  const double a = std::sqrt(A), b = std::sqrt(B);
  const double p = 1 - a * b, m = a - b;
  return ((1 + c) * p * p + (1 - c) * m * m) * (L + 4 * a * b);
}

// The general law of cosines in X (any cosines): cos α = N / √P with N = L_xz L_xy − 4X L_yz and
// P = (L_xz² − 16XZ)(L_xy² − 16XY), P − N² = X·Q with
// Q = 8 L_xz L_xy L_yz − 16 (Y L_xz² + Z L_xy² + X L_yz²) + 256 XYZ.
double general_angle(double X, double Y, double Z, double cxy, double cxz, double cyz) {
  const double lxy = lifted_cosh(X, Y, cxy), lxz = lifted_cosh(X, Z, cxz), lyz = lifted_cosh(Y, Z, cyz);
  const double n = lxz * lxy - 4 * X * lyz;
  const double sp = std::sqrt(lifted_sinh2(X, Z, cxz, lxz) * lifted_sinh2(X, Y, cxy, lxy));
  const double q = 8 * lxz * lxy * lyz - 16 * (Y * lxz * lxz + Z * lxy * lxy + X * lyz * lyz) + 256 * X * Y * Z;
  double s2, c2;  // sin²(α/2), cos²(α/2)
  if (n >= 0) {
    s2 = X * q / (2 * sp * (sp + n));
    c2 = (sp + n) / (2 * sp);
  } else {
    s2 = (sp - n) / (2 * sp);
    c2 = X * q / (2 * sp * (sp - n));
  }
  return 2 * std::atan2(std::sqrt(std::max(0.0, s2)), std::sqrt(std::max(0.0, c2)));
}
}  // namespace

double overlap_angle(Lift x, Lift y, Lift z, double cxy, double cxz, double cyz) {
  if (cxy == 1 && cxz == 1 && cyz == 1) return tangent_angle(x, y, z);
  if (cxy == 1 && cxz == 0 && cyz == 0) return right_part(x, z);  // z is the face circle
  if (cxz == 1 && cxy == 0 && cyz == 0) return right_part(x, y);  // y is the face circle
  if (cyz == 1 && cxy == 0 && cxz == 0) return right_part(x, y) + right_part(x, z);  // x is the face circle
  return general_angle(x.x, y.x, z.x, cxy, cxz, cyz);
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
