#include "laguerre/core/packing/HyperbolicTriangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace laguerre::core {

double tangent_angle(double X, double Y, double Z) {
  const double s2 = X * (1 - Y) * (1 - Z) / ((1 - X * Y) * (1 - X * Z));
  return 2 * std::asin(std::sqrt(std::min(1.0, s2)));
}

namespace {
// L_ab = (1+A)(1+B) + c(1−A)(1−B) = 4√(AB) cosh l_ab.
double lifted_cosh(double A, double B, double c) { return (1 + c) * (1 + A * B) + (1 - c) * (A + B); }
// L_ab² − 16AB = (L_ab − 4√(AB))(L_ab + 4√(AB)), with the first factor rewritten as
// (1+c)(1−√(AB))² + (1−c)(√A−√B)² so that nothing cancels when A, B → 1 (tiny circles).
double lifted_sinh2(double A, double B, double c, double L) {
  const double a = std::sqrt(A), b = std::sqrt(B);
  const double p = 1 - a * b, m = a - b;
  return ((1 + c) * p * p + (1 - c) * m * m) * (L + 4 * a * b);
}
}  // namespace

double overlap_angle(double X, double Y, double Z, double cxy, double cxz, double cyz) {
  // cosh l_ab = L_ab / (4 √(AB)).
  const double lxy = lifted_cosh(X, Y, cxy), lxz = lifted_cosh(X, Z, cxz), lyz = lifted_cosh(Y, Z, cyz);
  // cos α = N / √P with N = L_xz L_xy − 4X L_yz and P = (L_xz² − 16XZ)(L_xy² − 16XY); the factors
  // 16X√(YZ) common to numerator and denominator cancel, so Y = 0 or Z = 0 (horocycles) are fine.
  const double n = lxz * lxy - 4 * X * lyz;
  const double sp = std::sqrt(lifted_sinh2(X, Z, cxz, lxz) * lifted_sinh2(X, Y, cxy, lxy));
  // 1 − cos α = (P − N²) / (√P (√P + N)) and P − N² = X·Q exactly, with
  //   Q = 8 L_xz L_xy L_yz − 16 (Y L_xz² + Z L_xy² + X L_yz²) + 256 XYZ.
  // For the triangles of G′ (one tangency, two right angles) Q factors, which removes the
  // cancellation of the generic expression:
  //   c_yz = 1, c_xy = c_xz = 0:  Q = 16 (1−X)² (1−YZ)²
  //   c_xy = 1, c_xz = c_yz = 0:  Q = 16 (1−XY)² (1−Z)²   (and symmetrically in y, z).
  double q;
  if (cxy == 0 && cxz == 0 && cyz == 1) {
    q = 16 * (1 - X) * (1 - X) * (1 - Y * Z) * (1 - Y * Z);
  } else if (cxy == 1 && cxz == 0 && cyz == 0) {
    q = 16 * (1 - X * Y) * (1 - X * Y) * (1 - Z) * (1 - Z);
  } else if (cxz == 1 && cxy == 0 && cyz == 0) {
    q = 16 * (1 - X * Z) * (1 - X * Z) * (1 - Y) * (1 - Y);
  } else {
    q = 8 * lxz * lxy * lyz - 16 * (Y * lxz * lxz + Z * lxy * lxy + X * lyz * lyz) + 256 * X * Y * Z;
  }
  double s2;  // sin²(α/2)
  double c2;  // cos²(α/2)
  if (n >= 0) {  // small angles: the factored form keeps their relative precision
    s2 = X * q / (2 * sp * (sp + n));
    c2 = (sp + n) / (2 * sp);
  } else {  // obtuse angles: 1 − cos α has no cancellation
    s2 = (sp - n) / (2 * sp);
    c2 = X * q / (2 * sp * (sp - n));
  }
  return 2 * std::atan2(std::sqrt(std::max(0.0, s2)), std::sqrt(std::max(0.0, c2)));
}

double uniform_neighbour_update(double X, double theta, int k) {
  const double t = std::sqrt(X);
  // Common neighbour value U with k·tangent_angle(X, U, U) = θ:
  //   sin(θ/2k) = β = √X (1−U)/(1−XU)  ⇒  U = (√X − β) / (√X − βX).
  const double beta = std::sin(theta / (2 * k));
  double u = (t - beta) / (t - beta * X);
  u = std::clamp(u, 0.0, 1.0);
  // X' = t'² with √X'(1−U)/(1−X'U) = δ = sin(π/k): δU t'² + (1−U) t' − δ = 0, positive root written
  // without cancellation.
  const double delta = std::sin(std::numbers::pi / k);
  const double a = 1 - u;
  const double tp = 2 * delta / (a + std::sqrt(a * a + 4 * delta * delta * u));
  return tp * tp;
}

double radius_of(double X) {
  return X <= 0 ? std::numeric_limits<double>::infinity() : -0.5 * std::log(X);
}

double x_of_radius(double h) { return std::isinf(h) ? 0.0 : std::exp(-2 * h); }

}  // namespace laguerre::core
